//! The height-field check: the first pair of triangles whose interiors overlap in plan.
//!
//! Triangles are counter-clockwise in plan (see [`super::terrain`]). Their corners are
//! numbered by plan position, so triangles sharing a corner are known, and pairs split
//! in two kinds:
//!
//! - **Pairs sharing a corner v.** Near v each triangle fills the sector between its
//!   two edges out of v (narrower than π), and the triangle lies inside that sector's
//!   cone. So two triangles around v overlap exactly when their sectors do. Sorting the
//!   sectors around v by their first edge (exactly: half-plane, then `orient2d`), any
//!   overlap shows between neighbours in that order (a sector overlapping a later one
//!   also overlaps every one that starts between them), so a vertex of degree k costs
//!   k log k, not k²: a fan of 10⁵ slivers around one apex stays linear.
//! - **Pairs without a common corner.** Candidates come from a [`Bvh`] over the
//!   triangles' boxes, tagged with their corners so that node pairs whose triangles
//!   all share a corner are never walked (the slivers of a fan all overlap near their
//!   apex), and each is decided by separating edge lines, exactly.

use super::plan::{facet_box, Facet};
use crate::bvh::Bvh;
use crate::vector::orient2d;
use crate::Bounds;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::HashMap;

/// A pair of faces whose triangles overlap in plan, if any: the first by face order
/// among those sharing a corner, else the first the search meets (the same every run).
pub(crate) fn first_overlap(facets: &[Facet]) -> Option<(usize, usize)> {
    let corners = corner_ids(facets);
    first_around_corners(facets, &corners).or_else(|| first_apart(facets, &corners))
}

/// Each triangle's corners numbered by plan position (−0 and 0 alike).
fn corner_ids(facets: &[Facet]) -> Vec<[u32; 3]> {
    let mut ids: HashMap<[u64; 2], u32> = HashMap::with_capacity(facets.len());
    let key = |p: [f64; 2]| p.map(|x| (x + 0.0).to_bits());
    facets
        .iter()
        .map(|f| {
            f.xy.map(|p| {
                let next = ids.len() as u32;
                *ids.entry(key(p)).or_insert(next)
            })
        })
        .collect()
}

/// Whether `p` comes in the first half-turn around `v` (from the +x direction,
/// counter-clockwise, that direction included).
pub(super) fn first_half(v: [f64; 2], p: [f64; 2]) -> bool {
    p[1] > v[1] || (p[1] == v[1] && p[0] > v[0])
}

/// The order of directions `v→p` and `v→q` counter-clockwise from +x.
pub(super) fn by_angle(v: [f64; 2], p: [f64; 2], q: [f64; 2]) -> Ordering {
    match (first_half(v, p), first_half(v, q)) {
        (true, false) => Ordering::Less,
        (false, true) => Ordering::Greater,
        _ => orient2d(v, p, q).partial_cmp(&0.0).unwrap_or(Ordering::Equal).reverse(),
    }
}

/// One triangle's sector at a corner: from the edge to `start` counter-clockwise to the
/// edge to `end`.
#[derive(Clone, Copy)]
struct Sector {
    start: [f64; 2],
    end: [f64; 2],
    face: usize,
}

/// Whether sector `b`, which starts at or after `a` around `v` (less than a full turn
/// later), begins inside `a`.
fn starts_inside(v: [f64; 2], a: &Sector, b: &Sector) -> bool {
    let turn = orient2d(v, a.start, b.start);
    let same_ray = turn == 0.0 && first_half(v, a.start) == first_half(v, b.start);
    same_ray || (turn > 0.0 && orient2d(v, b.start, a.end) > 0.0)
}

/// The first overlapping pair among triangles sharing a corner (see the module docs).
fn first_around_corners(facets: &[Facet], corners: &[[u32; 3]]) -> Option<(usize, usize)> {
    let mut uses: Vec<(u32, u32, u8)> = corners
        .iter()
        .enumerate()
        .flat_map(|(f, ids)| (0..3u8).map(move |c| (ids[c as usize], f as u32, c)))
        .collect();
    uses.par_sort_unstable();
    uses.par_chunk_by(|a, b| a.0 == b.0)
        .filter(|around| around.len() > 1)
        .filter_map(|around| {
            let (f, c) = (around[0].1 as usize, around[0].2 as usize);
            let v = facets[f].xy[c];
            let mut sectors: Vec<Sector> = around
                .iter()
                .map(|&(_, f, c)| {
                    let (xy, c) = (&facets[f as usize].xy, c as usize);
                    Sector {
                        start: xy[(c + 1) % 3],
                        end: xy[(c + 2) % 3],
                        face: facets[f as usize].face,
                    }
                })
                .collect();
            sectors.sort_by(|a, b| by_angle(v, a.start, b.start).then(a.face.cmp(&b.face)));
            let n = sectors.len();
            (0..n)
                .filter_map(|i| {
                    let (a, b) = (&sectors[i], &sectors[(i + 1) % n]);
                    let overlap =
                        starts_inside(v, a, b) || (n > 1 && i + 1 == n && starts_inside(v, b, a));
                    overlap.then(|| (a.face.min(b.face), a.face.max(b.face)))
                })
                .min()
        })
        .min()
}

/// Whether the interiors of two counter-clockwise triangles overlap: no edge line of
/// either has the other wholly on its outer side (touching allowed).
pub(crate) fn interiors_overlap(a: &[[f64; 2]; 3], b: &[[f64; 2]; 3]) -> bool {
    let separates = |t: &[[f64; 2]; 3], other: &[[f64; 2]; 3]| {
        (0..3).any(|i| {
            let (p, q) = (t[i], t[(i + 1) % 3]);
            other.iter().all(|&x| orient2d(p, q, x) <= 0.0)
        })
    };
    !separates(a, b) && !separates(b, a)
}

/// An overlapping pair among triangles without a common corner.
fn first_apart(facets: &[Facet], corners: &[[u32; 3]]) -> Option<(usize, usize)> {
    let boxes: Vec<Bounds> = facets
        .iter()
        .map(|f| {
            let [lo, hi] = facet_box(f);
            Bounds { min: [lo[0], lo[1], 0.0], max: [hi[0], hi[1], 0.0] }
        })
        .collect();
    let (order, bvh) = Bvh::over_boxes(&boxes);
    let tags: Vec<[u32; 3]> = order.iter().map(|&i| corners[i as usize]).collect();
    // The first pair the walk meets, not the first by face: a stack of many layers
    // has pairs by the million, and one names the problem.
    // (Pairs with a common corner, tagged by them, never reach the test.)
    let pair = bvh.first_overlapping_pair(Some(&tags), |i, j| {
        let (a, b) = (order[i] as usize, order[j] as usize);
        interiors_overlap(&facets[a].xy, &facets[b].xy)
    })?;
    let (a, b) = (facets[order[pair.0] as usize].face, facets[order[pair.1] as usize].face);
    Some((a.min(b), a.max(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn facet(xy: [[f64; 2]; 3], face: usize) -> Facet {
        Facet { xy, z: [0.0; 3], face }
    }

    #[test]
    fn neighbours_touch_and_overlaps_are_found() {
        let a = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let b = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(!interiors_overlap(&a, &b));
        let corner = [[1.0, 1.0], [2.0, 1.0], [1.0, 2.0]];
        assert!(!interiors_overlap(&a, &corner));
        let inside = [[0.1, 0.1], [0.3, 0.1], [0.1, 0.3]];
        assert!(interiors_overlap(&a, &inside) && interiors_overlap(&inside, &a));
        // A star of David: no corner of either inside the other, yet they overlap.
        let up = [[0.0, 0.0], [2.0, 0.0], [1.0, 1.8]];
        let down = [[0.0, 1.2], [1.0, -0.6], [2.0, 1.2]];
        assert!(interiors_overlap(&up, &down));
    }

    /// A fan of `n` triangles around the origin covering `turns` full turns.
    fn fan(n: usize, turns: f64) -> Vec<Facet> {
        let at = |i: usize| {
            let a = turns * std::f64::consts::TAU * i as f64 / n as f64;
            [a.cos(), a.sin()]
        };
        (0..n).map(|i| facet([[0.0, 0.0], at(i), at(i + 1)], i)).collect()
    }

    #[test]
    fn sectors_around_a_corner_against_all_pairs() {
        // Every pair tested directly (all share the apex) against the sector rule.
        let brute = |facets: &[Facet]| {
            let mut first = None;
            for (i, a) in facets.iter().enumerate() {
                for b in &facets[i + 1..] {
                    if interiors_overlap(&a.xy, &b.xy) {
                        let pair = (a.face.min(b.face), a.face.max(b.face));
                        first = Some(first.map_or(pair, |f: (usize, usize)| f.min(pair)));
                    }
                }
            }
            first
        };
        for (n, turns) in [(12, 1.0), (12, 0.5), (12, 2.0), (7, 1.5), (3, 1.0)] {
            let facets = fan(n, turns);
            assert_eq!(first_overlap(&facets), brute(&facets), "{n} {turns}");
        }
        // One triangle twice, and a thin one inside a wide one at the same corner.
        let t = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        assert_eq!(first_overlap(&[facet(t, 4), facet(t, 9)]), Some((4, 9)));
        let thin = [[0.0, 0.0], [1.0, 0.5], [0.5, 1.0]];
        assert_eq!(first_overlap(&[facet(t, 0), facet(thin, 1)]), Some((0, 1)));
        // The last sector wrapping over the first.
        let wide = [[0.0, 0.0], [0.0, -1.0], [1.0, 0.5]];
        assert_eq!(first_overlap(&[facet(t, 0), facet(wide, 1)]), Some((0, 1)));
    }

    #[test]
    fn random_triangles_on_a_small_grid_against_all_pairs() {
        // Corners on a 4×4 grid: shared corners, collinear edges and touching galore.
        let mut rng = crate::test_rng::XorShift::new(0x9e3779b97f4a7c15);
        for _ in 0..3000 {
            let mut facets = Vec::new();
            while facets.len() < 4 {
                let mut p = || [(rng.next_u64() % 4) as f64, (rng.next_u64() % 4) as f64];
                let (a, b, c) = (p(), p(), p());
                let turn = orient2d(a, b, c);
                if turn != 0.0 {
                    let xy = if turn > 0.0 { [a, b, c] } else { [a, c, b] };
                    facets.push(facet(xy, facets.len()));
                }
            }
            let overlapping =
                (0..4).any(|i| (i + 1..4).any(|j| interiors_overlap(&facets[i].xy, &facets[j].xy)));
            assert_eq!(
                first_overlap(&facets).is_some(),
                overlapping,
                "{:?}",
                facets.iter().map(|f| f.xy).collect::<Vec<_>>()
            );
        }
    }

    #[test]
    fn a_fan_of_many_slivers_is_checked_in_linear_time() {
        // 2·10⁵ slivers around one apex: all pairs would be 2·10¹⁰ tests.
        assert_eq!(first_overlap(&fan(200_000, 1.0)), None);
        let mut folded = fan(200_000, 1.0);
        folded.push(facet([[0.0, 0.0], [0.5, 0.01], [0.5, 0.02]], 200_000));
        assert_eq!(first_overlap(&folded).map(|p| p.1), Some(200_000));
    }
}
