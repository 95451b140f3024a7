//! Bodies from one surface: its shells, each measured as a surface of its own.
//!
//! A shell is a connected component of faces, two faces being connected when they share
//! a vertex *position* (exactly equal coordinates, with −0 = +0): corners are sorted by
//! their coordinates' bits, faces with equal corners are merged in a union–find, and the
//! shells are numbered by their first face. Sorting rather than hashing keeps the
//! numbering independent of the thread count. (The `topology` module's checks weld the
//! same way and go further: edges, orientation, nesting.)

use crate::{Point, Surface};
use rayon::prelude::*;

/// Some faces of a surface, by index, as a surface of their own: one shell of a file,
/// or all of a file's faces. `S` is the surface itself or a reference to it.
#[derive(Clone, Debug)]
pub struct FaceSubset<S> {
    surface: S,
    faces: Vec<usize>,
}

impl<S: Surface> FaceSubset<S> {
    /// Faces `faces` of `surface`; indices beyond its faces are left out.
    pub fn new(surface: S, mut faces: Vec<usize>) -> Self {
        let n = surface.face_count();
        faces.retain(|&f| f < n);
        FaceSubset { surface, faces }
    }

    /// All faces of `surface`.
    pub fn all(surface: S) -> Self {
        let faces = (0..surface.face_count()).collect();
        FaceSubset { surface, faces }
    }

    /// The faces, as indices into the whole surface.
    pub fn faces(&self) -> &[usize] {
        &self.faces
    }
}

impl<S: Surface> Surface for FaceSubset<S> {
    fn face_count(&self) -> usize {
        self.faces.len()
    }

    #[inline]
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        self.surface.fan(self.faces[face], triangle)
    }
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let up = parent[parent[x as usize] as usize];
        parent[x as usize] = up;
        x = up;
    }
    x
}

/// The shells of `surface`: lists of face indices, ordered by their first face.
///
/// ```
/// use meshvol::grid::shells;
/// use meshvol::shapes::tetrahedron;
/// use meshvol::{FaceRange, Surface};
/// // Two tetrahedra touching at one corner form one shell; apart, two.
/// let a = tetrahedron([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
/// assert_eq!(shells(&a), vec![vec![0, 1, 2, 3]]);
/// ```
pub fn shells<S: Surface + ?Sized>(surface: &S) -> Vec<Vec<usize>> {
    let faces = surface.face_count();
    if faces == 0 {
        return Vec::new();
    }
    let key = |p: Point| p.map(|x| (x + 0.0).to_bits());
    let mut corners: Vec<([u64; 3], u32)> = (0..faces)
        .into_par_iter()
        .flat_map_iter(|f| {
            let mut keys = Vec::new();
            surface.fan(f, |a, b, c| keys.extend([key(a), key(b), key(c)]));
            keys.into_iter().map(move |k| (k, f as u32))
        })
        .collect();
    corners.par_sort_unstable();
    let mut parent: Vec<u32> = (0..faces as u32).collect();
    for w in corners.windows(2) {
        if w[0].0 == w[1].0 {
            let (a, b) = (find(&mut parent, w[0].1), find(&mut parent, w[1].1));
            // The smaller face index becomes the root: the result does not depend on
            // the order of the merges.
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            parent[hi as usize] = lo;
        }
    }
    let mut shell_of_root = vec![u32::MAX; faces];
    let mut shells: Vec<Vec<usize>> = Vec::new();
    for f in 0..faces {
        let root = find(&mut parent, f as u32) as usize;
        if shell_of_root[root] == u32::MAX {
            shell_of_root[root] = shells.len() as u32;
            shells.push(Vec::new());
        }
        shells[shell_of_root[root] as usize].push(f);
    }
    shells
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{cuboid, uv_sphere};
    use crate::{mass_properties, Mesh};

    #[test]
    fn separate_solids_are_separate_shells() {
        // Two boxes and a sphere in one mesh, as a triangle soup (no shared indices).
        let parts = [
            cuboid([0.0; 3], [1.0; 3]).triangulated(),
            uv_sphere(0.5, 8, 4).triangulated(),
            cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]).triangulated(), // touches the first box
            cuboid([5.0; 3], [6.0; 3]).triangulated(),
        ];
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for part in &parts {
            for f in 0..part.face_count() {
                part.fan(f, |a, b, c| {
                    let n = positions.len() as u32;
                    positions.extend([a, b, c]);
                    triangles.push([n, n + 1, n + 2]);
                });
            }
        }
        let soup = Mesh::from_triangles(positions, triangles).unwrap();
        let found = shells(&soup);
        // The sphere (inside the first box, sharing no position) is its own shell; the
        // touching boxes merge.
        assert_eq!(found.len(), 3);
        assert_eq!(found[0].len(), 24);
        assert_eq!(found[1].len(), parts[1].face_count());
        let volumes: Vec<f64> = found
            .iter()
            .map(|s| mass_properties(&FaceSubset::new(&soup, s.clone())).signed_volume)
            .collect();
        assert!((volumes[0] - 2.0).abs() < 1e-15 && (volumes[2] - 1.0).abs() < 1e-15);
    }
}
