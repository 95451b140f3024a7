//! What the body readers (`ascii.rs`, `binary.rs`) share with the file that calls them:
//! the [`Layout`] they read by, the [`Body`] they give, and how faces and strips become
//! a mesh.

use meshvol::{Faces, Mesh, Point};
use rayon::prelude::*;

use crate::error::ParseError;

/// Which elements and properties hold the geometry.
pub(super) struct Layout {
    /// The vertex element and the indices of its `x`, `y`, `z` properties.
    pub(super) vertex: Option<(usize, [usize; 3])>,
    /// The face element and the index of its vertex index list.
    pub(super) face: Option<(usize, usize)>,
    /// The `tristrips` element and the index of its vertex index list.
    pub(super) strips: Option<(usize, usize)>,
    /// The declared vertex count (what face indices are checked against).
    pub(super) vertices: usize,
}

/// Ends a strip in [`Body::strips`]. No vertex has this index: the vertex count fits
/// `u32` (checked in `layout` in `mod.rs`), so indices are below `u32::MAX`.
pub(super) const STRIP_END: u32 = u32::MAX;

/// What a body reader gives.
pub(super) struct Body {
    pub(super) positions: Vec<Point>,
    pub(super) faces: Faces,
    /// The `tristrips` element's vertex indices, [`STRIP_END`] after each strip.
    pub(super) strips: Vec<u32>,
}

impl Body {
    /// The mesh: the faces, then the strips' triangles.
    pub(super) fn into_mesh(self) -> Result<Mesh, ParseError> {
        let Body { positions, mut faces, strips } = self;
        if !strips.is_empty() {
            let triangles = strip_triangles(&strips);
            match &mut faces {
                Faces::Triangles(t) => t.extend(triangles),
                Faces::Polygons { offsets, indices } => {
                    for t in triangles {
                        indices.extend(t);
                        offsets.push(indices.len());
                    }
                }
            }
        }
        Mesh::new(positions, faces).map_err(|e| ParseError::new(None, e.to_string()))
    }
}

/// The triangles of strips separated by [`STRIP_END`], every second one reversed;
/// those that repeat a vertex (strip joins) left out.
fn strip_triangles(strips: &[u32]) -> Vec<[u32; 3]> {
    let mut triangles = Vec::with_capacity(strips.len());
    for strip in strips.split(|&i| i == STRIP_END) {
        for (i, w) in strip.windows(3).enumerate() {
            let t = if i % 2 == 0 { [w[0], w[1], w[2]] } else { [w[1], w[0], w[2]] };
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                triangles.push(t);
            }
        }
    }
    triangles
}

/// The faces from concatenated vertex indices and each face's end.
pub(super) fn faces(
    indices: Vec<u32>,
    face_ends: impl Iterator<Item = usize>,
    all_triangles: bool,
) -> Faces {
    if all_triangles {
        Faces::Triangles(indices.par_chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
    } else {
        Faces::Polygons { offsets: std::iter::once(0).chain(face_ends).collect(), indices }
    }
}

/// The warning for faces of fewer than three vertices.
pub(super) fn warn_skipped(skipped: usize, first: Option<String>, warnings: &mut Vec<String>) {
    if skipped > 0 {
        warnings.push(format!(
            "skipped {skipped} faces with fewer than 3 vertices (the first at {})",
            first.unwrap_or_default()
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_alternate_winding_and_drop_joins() {
        // 0 1 2 3 4: triangles 012, 213, 234; 5 6 7; then a join (8 8 9) and 9 8 10, its
        // odd place reversing it.
        let strips = [0, 1, 2, 3, 4, STRIP_END, 5, 6, 7, STRIP_END, 8, 8, 9, 10, STRIP_END];
        assert_eq!(
            strip_triangles(&strips),
            vec![[0, 1, 2], [2, 1, 3], [2, 3, 4], [5, 6, 7], [9, 8, 10]]
        );
    }
}
