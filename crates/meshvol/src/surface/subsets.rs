//! Parts of a surface as surfaces of their own: a contiguous run of its faces
//! ([`FaceRange`], one object of a multi-object file) or any list of them
//! ([`FaceSubset`], one connected part or body).

use crate::{Point, Surface};

/// A contiguous run of another surface's faces, measured on its own: one object of a
/// multi-object file, without copying.
///
/// ```
/// use meshvol::surface::FaceRange;
/// use meshvol::{mass_properties, Mesh};
/// // Two corner tetrahedra in one mesh, the second twice the size.
/// let p = vec![
///     [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0],
///     [5.0, 0.0, 0.0], [7.0, 0.0, 0.0], [5.0, 2.0, 0.0], [5.0, 0.0, 2.0],
/// ];
/// let t = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
/// let faces = t.iter().chain(&t).enumerate().map(|(f, t)| t.map(|i| i + 4 * (f as u32 / 4)));
/// let mesh = Mesh::from_triangles(p, faces.collect()).unwrap();
/// assert_eq!(mass_properties(&FaceRange::new(&mesh, 4..8)).signed_volume, 8.0 / 6.0);
/// assert_eq!(mass_properties(&mesh).signed_volume, 9.0 / 6.0);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct FaceRange<'a, S: ?Sized> {
    surface: &'a S,
    start: usize,
    len: usize,
}

impl<'a, S: Surface + ?Sized> FaceRange<'a, S> {
    /// Faces `range` of `surface`, clamped to the faces it has.
    pub fn new(surface: &'a S, range: std::ops::Range<usize>) -> Self {
        let end = range.end.min(surface.face_count());
        let start = range.start.min(end);
        FaceRange { surface, start, len: end - start }
    }
}

impl<S: Surface + ?Sized> Surface for FaceRange<'_, S> {
    fn face_count(&self) -> usize {
        self.len
    }

    #[inline]
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        self.surface.fan(self.start + face, triangle)
    }
}

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
