//! The connected parts of a surface as it is read, before any check.
//!
//! Two faces are connected when they share a vertex *position* (exactly equal
//! coordinates, with −0 = +0): corners are sorted by their coordinates' bits, faces
//! with equal corners are joined in a [`UnionFind`], and the parts are numbered by
//! their first face. Sorting rather than hashing keeps the numbering independent of the
//! thread count.
//!
//! A part is not a *shell*: the `topology` module's shells are connected components of
//! the welded surface through shared edges, after degenerate and duplicate faces are
//! dropped, and come with closedness, orientation and nesting. A part is only what
//! touches what, and is cheap: the bodies of a file measured without a check.

use crate::union_find::UnionFind;
use crate::{Point, Surface};
use rayon::prelude::*;

/// The connected parts of `surface`, faces joined at shared vertex positions: lists of
/// face indices, ordered by their first face.
///
/// ```
/// use meshvol::shapes::tetrahedron;
/// use meshvol::surface::{connected_parts, Joined};
/// // Two tetrahedra touching at one corner form one part; apart, two.
/// let at = |x: f64| tetrahedron([x, 0.0, 0.0], [x + 1.0, 0.0, 0.0], [x, 1.0, 0.0], [x, 0.0, 1.0]);
/// let touching = Joined::new(vec![at(0.0), at(1.0)]);
/// assert_eq!(connected_parts(&touching), vec![(0..8).collect::<Vec<_>>()]);
/// let apart = Joined::new(vec![at(0.0), at(2.0)]);
/// assert_eq!(connected_parts(&apart), vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]]);
/// ```
pub fn connected_parts<S: Surface + ?Sized>(surface: &S) -> Vec<Vec<usize>> {
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
    let mut components = UnionFind::new(faces);
    for w in corners.windows(2) {
        if w[0].0 == w[1].0 {
            components.join(w[0].1, w[1].1);
        }
    }
    let mut part_of_root = vec![u32::MAX; faces];
    let mut parts: Vec<Vec<usize>> = Vec::new();
    for f in 0..faces {
        let root = components.find(f as u32) as usize;
        if part_of_root[root] == u32::MAX {
            part_of_root[root] = parts.len() as u32;
            parts.push(Vec::new());
        }
        parts[part_of_root[root] as usize].push(f);
    }
    parts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{cuboid, uv_sphere};
    use crate::surface::FaceSubset;
    use crate::{mass_properties, Mesh};

    #[test]
    fn separate_solids_are_separate_parts() {
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
        let found = connected_parts(&soup);
        // The sphere (inside the first box, sharing no position) is its own part; the
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
