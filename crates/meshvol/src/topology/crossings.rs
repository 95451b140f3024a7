//! Stage 7, crossings: pairs of kept faces whose fan triangles cross, an edge of one
//! passing strictly through the interior of the other.
//!
//! The triangles of faces with an interior (flat ones have none) are put in spatial
//! order and a [`Bvh`] is built over their boxes; every pair of overlapping boxes whose
//! triangles share no welded vertex (neighbours meet there by design) and come from two
//! faces is tested with exact orientation predicates ([`Plane::crossed_by`]).
//! Touching is not crossing. Pairs within one shell are self-intersections; pairs from
//! two shells make those shells overlap. The same triangles and hierarchy serve the
//! nesting rays.
//!
//! A face of more than [`LARGE_FACE`] corners is cut into triangles by halving its
//! corner range ([`balanced_triangle`]) instead of a fan: a fan's k − 2 triangles all
//! meet at one corner, so their boxes all overlap and the search would test about k²/2
//! pairs (41 s for a cone with a 3·10⁴-gon base); halving gives triangles that span
//! k/2, k/4, ... consecutive corners, whose boxes overlap O(k log k) times for a convex
//! face. For a plane face both cover the same region, so the crossings found are the
//! same; smaller faces keep the fan the measurements use, corner for corner.

use super::loops::Loops;
use super::predicates::Plane;
use super::weld::Welded;
use crate::buckets::{filled, for_each_range_mut, par_starts};
use crate::bvh::{triangle_centre, Box32, Bvh};
use crate::properties::Bounds;
use crate::Point;
use rayon::prelude::*;
use std::collections::BTreeSet;
use std::sync::Arc;

/// The triangles of the kept faces' fans, as parallel arrays: the crossing search
/// tags nearby pairs by `ids` and reads their points only for pairs sharing no vertex.
#[derive(Default)]
pub(super) struct Triangles<'a> {
    /// Welded vertices.
    pub ids: Vec<[u32; 3]>,
    pub face: Vec<u32>,
    /// The welded vertices' positions. (Read through `ids` rather than copied per
    /// triangle: the copy, 72 bytes a triangle, cost more than the scattered reads.)
    positions: &'a [Point],
}

impl Triangles<'_> {
    /// The triangles' order, as their faces, with the hierarchy built over them.
    pub fn into_index(self, bvh: Bvh) -> SpatialIndex {
        SpatialIndex { faces: Arc::new(self.face), bvh: Arc::new(bvh) }
    }

    pub fn points(&self, i: usize) -> [Point; 3] {
        // Not `ids.map(..)`: that built the array through the stack in pieces whose
        // reads straddled two writes (a store-forwarding stall per point, measured).
        let ([a, b, c], p) = (self.ids[i], self.positions);
        [p[a as usize], p[b as usize], p[c as usize]]
    }
}

/// The crossing search's spatial order and hierarchy, kept by a check that is asked to
/// ([`super::CheckOptions::keep_spatial_index`]) for a body of its solid to take
/// instead of ordering and building them again ([`crate::overlap::Body::of_solid`]).
#[derive(Clone)]
pub(crate) struct SpatialIndex {
    /// The face of each triangle in spatial order.
    pub faces: Arc<Vec<u32>>,
    /// The hierarchy over those triangles' boxes, in that order.
    pub bvh: Arc<Bvh>,
}

impl std::fmt::Debug for SpatialIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SpatialIndex({} triangles)", self.faces.len())
    }
}

/// Faces with more corners than this are triangulated by halving, not as a fan.
const LARGE_FACE: usize = 32;

/// Triangle `t` (0 ≤ t < k − 2) of a k-gon cut by halving: the triangle (i, m, j) with
/// m = ⌊(i + j)/2⌋ on the corner range [i, j] = [0, k − 1], then the same on [i, m] and
/// on [m, j], numbered in that (pre-)order. Each triangle keeps the face's winding
/// (i < m < j), and together they tile the polygon as a fan does. O(log k).
fn balanced_triangle(k: usize, mut t: usize) -> [usize; 3] {
    let (mut i, mut j) = (0, k - 1);
    loop {
        let m = (i + j) / 2;
        if t == 0 {
            return [i, m, j];
        }
        t -= 1;
        // The range [i, m] holds m − i − 1 triangles.
        let left = m - i - 1;
        if t < left {
            j = m;
        } else {
            t -= left;
            i = m;
        }
    }
}

/// The kept faces' triangles in spatial order (neighbours in space are neighbours in
/// memory, which the hierarchy's searches then read), and the hierarchy over them.
/// Every array is made at its final size (no growth, no list of boxes), since these
/// are among the largest arrays of a check.
pub(super) fn triangles_in_space<'a>(
    loops: &Loops,
    kept: &[bool],
    welded: &'a Welded,
) -> (Triangles<'a>, Bvh) {
    // Each triangle as (face, corner): for a fan, the corner of its second vertex;
    // for a large face, its number in the face's halving (plus the face's start + 1).
    let faces = kept.len();
    let triangles_of = |f: usize| if kept[f] { loops.face(f).len() - 2 } else { 0 };
    let first = par_starts(faces, triangles_of);
    let mut fans = filled(first[faces], (0u32, 0u32));
    for_each_range_mut(&mut fans, faces, &|f| first[f]..first[f + 1], &|f, out| {
        let r = loops.face(f);
        for (t, c) in out.iter_mut().zip(r.start + 1..r.end - 1) {
            *t = (f as u32, c as u32);
        }
    });
    drop(first);
    let corners = |(f, c): (u32, u32)| {
        let r = loops.face(f as usize);
        let c = c as usize;
        if r.len() > LARGE_FACE {
            balanced_triangle(r.len(), c - r.start - 1).map(|k| r.start + k)
        } else {
            [r.start, c, c + 1]
        }
    };
    // Ordered by the face's own corners (read in sequence), not the welded vertices,
    // by the centres of their boxes, as a body orders its triangles (so that a body
    // can take this order: [`SpatialIndex`]). (The centres are kept, 24 bytes a
    // triangle: finding them afresh on each of the order's two reads, as
    // `Bvh::spatial_order_of` allows, took 6 ms longer at 1M.)
    let mut centres = Vec::new();
    fans.par_iter()
        .map(|&fan| triangle_centre(corners(fan).map(|c| welded.at(c))))
        .collect_into_vec(&mut centres);
    let order = Bvh::spatial_order(&centres);
    drop(centres);
    let (mut ids, mut face) = (Vec::new(), Vec::new());
    order
        .par_iter()
        .map(|&i| corners(fans[i as usize]).map(|c| welded.corner_vertex[c]))
        .collect_into_vec(&mut ids);
    order.par_iter().map(|&i| fans[i as usize].0).collect_into_vec(&mut face);
    drop((order, fans));
    let triangles = Triangles { ids, face, positions: &welded.positions };
    let bvh = Bvh::new(triangles.ids.len(), |i| {
        let points = triangles.points(i);
        let mut bounds = Bounds::of(points[0]);
        bounds.include(points[1]);
        bounds.include(points[2]);
        Box32::around(&bounds)
    });
    (triangles, bvh)
}

/// The pairs of kept faces whose fan triangles cross, sorted.
pub(super) fn crossing_pairs(triangles: &Triangles, bvh: &Bvh) -> Vec<[usize; 2]> {
    // Tagged by their vertices, neighbours (which meet at shared vertices by design)
    // never reach the test: the walk masks them off with the box tests, and skips the
    // triangles around one vertex wholesale (a cone's apex, a polygon's corner).
    // The first triangle's plane is made once for all its partners in a leaf.
    let prepare = |i: usize| (triangles.face[i] as usize, Plane::of(triangles.points(i)));
    let test = |(f, plane): &(usize, Plane), j: usize| {
        let (f, g) = (*f, triangles.face[j] as usize);
        if f == g {
            return None; // a face's own triangles tile it (its validity is not a crossing)
        }
        plane.crossed_by(triangles.points(j)).then_some([f.min(g), f.max(g)])
    };
    bvh.overlapping_pairs(Some(&triangles.ids), prepare, test)
}

/// What the crossing pairs say: crossing face pairs within shells and a few examples.
pub(super) struct Crossings {
    /// Crossing face pairs within a shell.
    pub self_intersections: usize,
    /// A few crossing face pairs, each once: within shells first, then between shells.
    pub examples: Vec<[usize; 2]>,
}

/// Counts the crossing triangle `pairs` as face pairs, keeps up to `keep` of them,
/// and adds the pairs of shells they make overlap to `overlapping_shells`.
pub(super) fn face_pairs(
    mut pairs: Vec<[usize; 2]>,
    shell_of_face: &[u32],
    keep: usize,
    overlapping_shells: &mut BTreeSet<[usize; 2]>,
) -> Crossings {
    // Polygon faces fan into several triangles: count each crossing face pair once.
    pairs.par_sort_unstable();
    pairs.dedup();
    let same_shell = |&[f, g]: &[usize; 2]| shell_of_face[f] == shell_of_face[g];
    let mut within = 0;
    for pair in &pairs {
        if same_shell(pair) {
            within += 1;
        } else {
            let (sf, sg) = (shell_of_face[pair[0]] as usize, shell_of_face[pair[1]] as usize);
            overlapping_shells.insert([sf.min(sg), sf.max(sg)]);
        }
    }
    // Self-intersections first, so that a count above zero always has an example.
    let (mut examples, between): (Vec<[usize; 2]>, Vec<[usize; 2]>) =
        pairs.iter().partition(|p| same_shell(p));
    examples.extend(between);
    examples.truncate(keep);
    Crossings { self_intersections: within, examples }
}

#[cfg(test)]
mod tests {
    use super::balanced_triangle;

    /// The halving's triangles tile a convex polygon: each keeps the winding, the
    /// triangles are distinct, and their areas add up to the polygon's (shoelace).
    #[test]
    fn halving_tiles_the_polygon() {
        for k in 3..200 {
            let p: Vec<[f64; 2]> = (0..k)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / k as f64;
                    [a.cos(), a.sin()]
                })
                .collect();
            let area = |[a, b, c]: [usize; 3]| {
                0.5 * ((p[b][0] - p[a][0]) * (p[c][1] - p[a][1])
                    - (p[c][0] - p[a][0]) * (p[b][1] - p[a][1]))
            };
            let triangles: Vec<[usize; 3]> = (0..k - 2).map(|t| balanced_triangle(k, t)).collect();
            let mut seen = triangles.clone();
            seen.sort();
            seen.dedup();
            assert_eq!(seen.len(), k - 2);
            assert!(triangles.iter().all(|&[i, m, j]| i < m && m < j && j < k));
            let total: f64 = triangles.iter().map(|&t| area(t)).sum();
            let shoelace: f64 = (0..k)
                .map(|i| {
                    let (a, b) = (p[i], p[(i + 1) % k]);
                    0.5 * (a[0] * b[1] - b[0] * a[1])
                })
                .sum();
            assert!((total - shoelace).abs() < 1e-12, "k = {k}");
            assert!(triangles.iter().all(|&t| area(t) > 0.0));
        }
    }
}
