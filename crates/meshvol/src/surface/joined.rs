//! Several surfaces read as one: the faces of the first, then those of the second, and
//! so on. Face f belongs to the surface whose run of face numbers holds it, found by a
//! binary search over the runs' starts.

use crate::{Point, Surface};

/// `surfaces` as one surface, their faces one after another: several files measured
/// together, without copying them. `S` is a surface or a reference to one.
///
/// ```
/// use meshvol::shapes::cuboid;
/// use meshvol::surface::Joined;
/// use meshvol::{mass_properties, Surface};
/// // A 2×2×2 box and a unit box apart: 6 + 6 faces, 8 + 1 of volume.
/// let joined = Joined::new(vec![cuboid([0.0; 3], [2.0; 3]), cuboid([5.0; 3], [6.0; 3])]);
/// assert_eq!(joined.face_count(), 12);
/// assert_eq!(mass_properties(&joined).signed_volume, 9.0);
/// ```
#[derive(Clone, Debug)]
pub struct Joined<S> {
    surfaces: Vec<S>,
    /// The first face of each surface in the joined numbering, and the face count last.
    starts: Vec<usize>,
}

impl<S: Surface> Joined<S> {
    pub fn new(surfaces: Vec<S>) -> Self {
        let starts = crate::buckets::starts(surfaces.iter().map(|s| s.face_count()));
        Joined { surfaces, starts }
    }

    /// The surfaces, in order.
    pub fn surfaces(&self) -> &[S] {
        &self.surfaces
    }
}

impl<S: Surface> Surface for Joined<S> {
    fn face_count(&self) -> usize {
        self.starts[self.starts.len() - 1]
    }

    #[inline]
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        // The last surface starting at or before `face` (empty surfaces share a start
        // with the next one, and hold no face).
        let s = self.starts.partition_point(|&start| start <= face) - 1;
        self.surfaces[s].fan(face - self.starts[s], triangle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{cuboid, tetrahedron};
    use crate::Mesh;

    fn triangles<S: Surface>(surface: &S) -> Vec<[Point; 3]> {
        let mut all = Vec::new();
        for f in 0..surface.face_count() {
            surface.fan(f, |a, b, c| all.push([a, b, c]));
        }
        all
    }

    #[test]
    fn faces_come_one_surface_after_another_and_empty_surfaces_hold_none() {
        let corner = tetrahedron([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        let cube = cuboid([2.0; 3], [3.0; 3]);
        let empty = Mesh::from_triangles(Vec::new(), Vec::new()).unwrap();
        let joined = Joined::new(vec![empty.clone(), corner.clone(), empty.clone(), cube.clone()]);
        assert_eq!(joined.face_count(), corner.face_count() + cube.face_count());
        let mut expected = triangles(&corner);
        expected.extend(triangles(&cube));
        assert_eq!(triangles(&joined), expected);
        assert_eq!(Joined::new(vec![empty]).face_count(), 0);
        assert_eq!(Joined::<Mesh>::new(Vec::new()).face_count(), 0);
    }
}
