//! Meshes: f64 positions and faces that index them, and the [`Surface`] view that the
//! kernels read.
//!
//! A face is a closed loop of vertex indices. Triangles are stored as `[u32; 3]`; faces of
//! any size as offsets into one index array (no per-face allocation). Kernels never look
//! at the storage: they read a [`Surface`], which yields each face as a fan of triangles
//! from the face's first vertex. For a planar polygon the signed fan is exact even when
//! the polygon is not convex, which is why the fan is the one triangulation kernels use.

use crate::Point;

/// The faces of a [`Mesh`].
#[derive(Clone, Debug, PartialEq)]
pub enum Faces {
    /// Every face is a triangle.
    Triangles(Vec<[u32; 3]>),
    /// Faces of any size: face `f` is `indices[offsets[f]..offsets[f + 1]]`.
    /// `offsets` has one more entry than there are faces and starts at 0.
    Polygons { offsets: Vec<usize>, indices: Vec<u32> },
}

/// Why a [`Mesh`] could not be built from the given arrays.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    #[error("vertex {vertex} has a non-finite coordinate ({value})")]
    NonFiniteVertex { vertex: usize, value: f64 },
    #[error("face {face} uses vertex index {index}, but there are only {vertices} vertices")]
    IndexOutOfRange { face: usize, index: u64, vertices: usize },
    #[error("face {face} uses vertex index {index}, which is negative (indices count from 0)")]
    NegativeIndex { face: usize, index: i64 },
    #[error("face {face} has {count} vertices; a face needs at least 3")]
    TooFewVertices { face: usize, count: usize },
    #[error("polygon offsets must start at 0, never decrease and end at the index count ({indices}); offset {position} is {offset}")]
    BadOffsets { position: usize, offset: usize, indices: usize },
    #[error("{vertices} vertices do not fit 32-bit indices")]
    TooManyVertices { vertices: usize },
}

/// A polygon mesh: positions and the faces that index them.
///
/// Built only through validated constructors, so every index is in range and every
/// coordinate is finite: kernels need no checks of their own.
///
/// ```
/// use meshvol::{Mesh, Faces};
/// // A unit square pyramid: one quad base, four triangles.
/// let positions = vec![
///     [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, 1.0],
/// ];
/// let mesh = Mesh::from_polygons(
///     positions,
///     [&[0u32, 3, 2, 1][..], &[0, 1, 4], &[1, 2, 4], &[2, 3, 4], &[3, 0, 4]],
/// ).unwrap();
/// assert_eq!(mesh.face_count(), 5);
/// assert_eq!(mesh.triangle_count(), 6);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    positions: Vec<Point>,
    faces: Faces,
}

impl Mesh {
    /// Builds a mesh, checking that coordinates are finite, indices in range, and
    /// polygon faces have at least three vertices.
    pub fn new(positions: Vec<Point>, faces: Faces) -> Result<Mesh, MeshError> {
        if u32::try_from(positions.len()).is_err() {
            return Err(MeshError::TooManyVertices { vertices: positions.len() });
        }
        if let Some((vertex, value)) = positions
            .iter()
            .enumerate()
            .find_map(|(v, p)| p.iter().find(|c| !c.is_finite()).map(|&c| (v, c)))
        {
            return Err(MeshError::NonFiniteVertex { vertex, value });
        }
        let n = positions.len();
        let out_of_range = |face: usize, index: u32| MeshError::IndexOutOfRange {
            face,
            index: u64::from(index),
            vertices: n,
        };
        match &faces {
            Faces::Triangles(tris) => {
                for (face, tri) in tris.iter().enumerate() {
                    if let Some(&index) = tri.iter().find(|&&i| i as usize >= n) {
                        return Err(out_of_range(face, index));
                    }
                }
            }
            Faces::Polygons { offsets, indices } => {
                if offsets.first() != Some(&0) {
                    let offset = offsets.first().copied().unwrap_or(usize::MAX);
                    return Err(MeshError::BadOffsets {
                        position: 0,
                        offset,
                        indices: indices.len(),
                    });
                }
                for (face, w) in offsets.windows(2).enumerate() {
                    if w[1] < w[0] || w[1] > indices.len() {
                        return Err(MeshError::BadOffsets {
                            position: face + 1,
                            offset: w[1],
                            indices: indices.len(),
                        });
                    }
                    if w[1] - w[0] < 3 {
                        return Err(MeshError::TooFewVertices { face, count: w[1] - w[0] });
                    }
                    if let Some(&index) = indices[w[0]..w[1]].iter().find(|&&i| i as usize >= n) {
                        return Err(out_of_range(face, index));
                    }
                }
                let last = offsets.len() - 1;
                if offsets[last] != indices.len() {
                    return Err(MeshError::BadOffsets {
                        position: last,
                        offset: offsets[last],
                        indices: indices.len(),
                    });
                }
            }
        }
        Ok(Mesh { positions, faces })
    }

    /// A triangle mesh.
    pub fn from_triangles(
        positions: Vec<Point>,
        triangles: Vec<[u32; 3]>,
    ) -> Result<Mesh, MeshError> {
        Mesh::new(positions, Faces::Triangles(triangles))
    }

    /// A mesh of polygon faces given as index lists. Stored as triangles when every face
    /// is one.
    pub fn from_polygons<'a>(
        positions: Vec<Point>,
        polygons: impl IntoIterator<Item = &'a [u32]>,
    ) -> Result<Mesh, MeshError> {
        let mut offsets = vec![0];
        let mut indices = Vec::new();
        for polygon in polygons {
            indices.extend_from_slice(polygon);
            offsets.push(indices.len());
        }
        Mesh::new(positions, Faces::Polygons { offsets, indices }).map(Mesh::compact)
    }

    /// Stores all-triangle polygon faces as [`Faces::Triangles`].
    fn compact(self) -> Mesh {
        match &self.faces {
            Faces::Polygons { offsets, indices }
                if offsets.windows(2).all(|w| w[1] - w[0] == 3) =>
            {
                let tris = indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
                Mesh { positions: self.positions, faces: Faces::Triangles(tris) }
            }
            _ => self,
        }
    }

    pub fn positions(&self) -> &[Point] {
        &self.positions
    }

    pub fn faces(&self) -> &Faces {
        &self.faces
    }

    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    pub fn face_count(&self) -> usize {
        match &self.faces {
            Faces::Triangles(t) => t.len(),
            Faces::Polygons { offsets, .. } => offsets.len() - 1,
        }
    }

    /// The number of triangles in the faces' fans: a face of k vertices counts k − 2.
    pub fn triangle_count(&self) -> usize {
        match &self.faces {
            Faces::Triangles(t) => t.len(),
            Faces::Polygons { offsets, indices } => indices.len() - 2 * (offsets.len() - 1),
        }
    }

    /// The vertex indices of face `face`.
    pub fn face(&self, face: usize) -> &[u32] {
        match &self.faces {
            Faces::Triangles(t) => &t[face],
            Faces::Polygons { offsets, indices } => &indices[offsets[face]..offsets[face + 1]],
        }
    }

    /// The same surface with every face replaced by its fan of triangles.
    pub fn triangulated(&self) -> Mesh {
        let mut triangles = Vec::with_capacity(self.triangle_count());
        for f in 0..self.face_count() {
            let face = self.face(f);
            for w in face[1..].windows(2) {
                triangles.push([face[0], w[0], w[1]]);
            }
        }
        Mesh { positions: self.positions.clone(), faces: Faces::Triangles(triangles) }
    }

    /// The meshes one after another, as one mesh (vertices not shared between them).
    ///
    /// ```
    /// use meshvol::shapes::cuboid;
    /// use meshvol::Mesh;
    /// let two = Mesh::concatenate(&[cuboid([0.0; 3], [1.0; 3]), cuboid([2.0; 3], [3.0; 3])]);
    /// assert_eq!((two.vertex_count(), two.face_count()), (16, 12));
    /// ```
    pub fn concatenate(meshes: &[Mesh]) -> Mesh {
        let mut positions = Vec::new();
        let mut offsets = vec![0];
        let mut indices = Vec::new();
        for mesh in meshes {
            let base = positions.len() as u32;
            positions.extend_from_slice(&mesh.positions);
            for f in 0..mesh.face_count() {
                indices.extend(mesh.face(f).iter().map(|&v| v + base));
                offsets.push(indices.len());
            }
        }
        Mesh { positions, faces: Faces::Polygons { offsets, indices } }.compact()
    }

    /// The same mesh with every face's winding reversed.
    pub fn flipped(&self) -> Mesh {
        let faces = match &self.faces {
            Faces::Triangles(t) => Faces::Triangles(t.iter().map(|&[a, b, c]| [a, c, b]).collect()),
            Faces::Polygons { offsets, indices } => {
                let mut indices = indices.clone();
                for w in offsets.windows(2) {
                    indices[w[0]..w[1]].reverse();
                }
                Faces::Polygons { offsets: offsets.clone(), indices }
            }
        };
        Mesh { positions: self.positions.clone(), faces }
    }
}

/// A surface the kernels can measure: a list of faces, each read as a fan of triangles.
///
/// [`Mesh`] implements it; so can a reader's zero-copy view of a file (a memory-mapped
/// binary STL), which is why kernels take this trait and not a `Mesh`.
pub trait Surface: Sync {
    /// The number of faces.
    fn face_count(&self) -> usize;

    /// Calls `triangle(a, b, c)` for each triangle of face `face`'s fan from its first
    /// vertex, in order: (v0, v1, v2), (v0, v2, v3), …
    ///
    /// Implementations must yield finite coordinates (validate when building).
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point));

    /// The positions and triangles behind the faces, when the surface is exactly an
    /// indexed triangle mesh (face `f` is triangle `f`): kernels with a faster path for
    /// arrays take it. `None` (the default) for anything else.
    fn indexed_triangles(&self) -> Option<(&[Point], &[[u32; 3]])> {
        None
    }

    /// Whether every face is exactly one triangle, so that `fan(face, ..)` calls back
    /// once (a binary STL read in place): kernels with a faster path for triangles then
    /// read four faces at a time. `false` (the default) when not known to be so.
    fn faces_are_triangles(&self) -> bool {
        false
    }

    /// When every face is one triangle whose coordinates are f32 values (a binary STL
    /// read in place): face `face`'s corners as those f32 values, which `fan` gives
    /// widened to f64. Kernels that copy the corners then keep them at half the size.
    /// `None` (the default) otherwise.
    fn triangle_f32(&self, _face: usize) -> Option<[[f32; 3]; 3]> {
        None
    }

    /// Whether the surface's vector area, Σ (b − a)×(c − a) over its fan triangles, is
    /// known to be exactly zero: every directed edge between two corners is matched by
    /// its reverse, the corners exactly equal (a closed, consistently oriented surface,
    /// welded exactly: what [`crate::topology::Check::vector_area_is_zero`] proves of the
    /// solid it finds). Its volume about any point is then its volume about the origin,
    /// and [`crate::mass_properties`] takes the sum about its first vertex as it is,
    /// with that sum's bound alone: no move to the origin, whose bound grows with the
    /// distance from it. `false` (the default) when not known.
    fn vector_area_is_zero(&self) -> bool {
        false
    }

    /// A hint that the faces will not be read for a while: a surface that reads a
    /// memory-mapped file in place lets the system drop the pages it has read (they are
    /// read again from the file if asked, the same bytes), so that a check of a large
    /// file does not keep both the file and its own arrays in memory. Reads after it
    /// give the same faces. Nothing (the default) for a surface in ordinary memory.
    fn release_pages(&self) {}
}

/// Face `face`'s one triangle, of a surface whose [`Surface::faces_are_triangles`].
#[inline(always)]
pub(crate) fn only_triangle<S: Surface + ?Sized>(surface: &S, face: usize) -> [Point; 3] {
    let mut corners = [[0.0; 3]; 3];
    surface.fan(face, |a, b, c| corners = [a, b, c]);
    corners
}

/// The first corner of the first face that has a triangle: the point a kernel takes its
/// sums about. Not simply face 0's: an adapter (a surface cut by a plane, a subset) may
/// give face 0 no triangle, and a closed surface's sums need a point near the surface,
/// not the origin, to keep their rounding small. `None` when no face has a triangle.
pub(crate) fn first_corner<S: Surface + ?Sized>(surface: &S) -> Option<Point> {
    let mut r = None;
    for face in 0..surface.face_count() {
        surface.fan(face, |a, _, _| r = r.or(Some(a)));
        if r.is_some() {
            break;
        }
    }
    r
}

/// A reference to a surface is the surface.
impl<S: Surface + ?Sized> Surface for &S {
    fn face_count(&self) -> usize {
        (**self).face_count()
    }

    #[inline]
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        (**self).fan(face, triangle)
    }

    fn indexed_triangles(&self) -> Option<(&[Point], &[[u32; 3]])> {
        (**self).indexed_triangles()
    }

    fn faces_are_triangles(&self) -> bool {
        (**self).faces_are_triangles()
    }

    fn triangle_f32(&self, face: usize) -> Option<[[f32; 3]; 3]> {
        (**self).triangle_f32(face)
    }

    fn vector_area_is_zero(&self) -> bool {
        (**self).vector_area_is_zero()
    }

    fn release_pages(&self) {
        (**self).release_pages()
    }
}

impl Surface for Mesh {
    fn face_count(&self) -> usize {
        Mesh::face_count(self)
    }

    #[inline]
    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        let p = &self.positions;
        match &self.faces {
            Faces::Triangles(t) => {
                let [a, b, c] = t[face];
                triangle(p[a as usize], p[b as usize], p[c as usize]);
            }
            Faces::Polygons { offsets, indices } => {
                let loop_ = &indices[offsets[face]..offsets[face + 1]];
                let apex = p[loop_[0] as usize];
                for w in loop_[1..].windows(2) {
                    triangle(apex, p[w[0] as usize], p[w[1] as usize]);
                }
            }
        }
    }

    fn indexed_triangles(&self) -> Option<(&[Point], &[[u32; 3]])> {
        match &self.faces {
            Faces::Triangles(t) => Some((&self.positions, t)),
            Faces::Polygons { .. } => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_input_with_the_place() {
        let p = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert_eq!(
            Mesh::from_triangles(p.clone(), vec![[0, 1, 2], [0, 1, 3]]),
            Err(MeshError::IndexOutOfRange { face: 1, index: 3, vertices: 3 })
        );
        let mut bad = p.clone();
        bad[2][1] = f64::NAN;
        assert!(matches!(
            Mesh::from_triangles(bad, vec![[0, 1, 2]]),
            Err(MeshError::NonFiniteVertex { vertex: 2, .. })
        ));
        assert_eq!(
            Mesh::from_polygons(p.clone(), [&[0u32, 1, 2][..], &[0, 1]]),
            Err(MeshError::TooFewVertices { face: 1, count: 2 })
        );
        let faces = Faces::Polygons { offsets: vec![0, 3, 2], indices: vec![0, 1, 2] };
        assert!(matches!(Mesh::new(p, faces), Err(MeshError::BadOffsets { position: 2, .. })));
    }

    #[test]
    fn all_triangle_polygons_are_stored_as_triangles() {
        let p = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let m = Mesh::from_polygons(p, [&[0u32, 1, 2][..]]).unwrap();
        assert_eq!(m.faces(), &Faces::Triangles(vec![[0, 1, 2]]));
    }

    #[test]
    fn fan_and_flip() {
        let p = vec![[0.0; 3], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let m = Mesh::from_polygons(p, [&[0u32, 1, 2, 3][..]]).unwrap();
        let mut tris = vec![];
        m.fan(0, |a, b, c| tris.push([a, b, c]));
        assert_eq!(tris.len(), 2);
        assert_eq!(tris[1], [[0.0; 3], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(m.flipped().face(0), &[3, 2, 1, 0]);
    }
}
