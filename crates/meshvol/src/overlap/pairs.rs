//! Stage 1: where the two surfaces cross. Both bodies' hierarchies (built once) are
//! refitted to the placed triangles and walked together, so candidate pairs of
//! triangles come from the pairs of leaves near the crossing curve only; each pair is
//! then decided exactly on the placed coordinates.
//!
//! For a pair of triangles (a, b) in general position, a ∩ b is empty or a segment
//! whose two ends are each where an edge of one crosses the other's interior. Those
//! edge crossings are decided by exact orientation tests; only their positions are
//! rounded, each with a bound on its error. Any exact zero (a corner on the other's
//! plane, an edge through the other's edge, faces in one plane) is a position the
//! method does not settle: the whole query reports [`Degenerate`].

use super::body::{box_of, Body};
use crate::accumulate::UNIT_ROUNDOFF;
use crate::assembly::Affine;
use crate::properties::Bounds;
use crate::topology::predicates::Plane;
use crate::vector::{add, cross, dot, norm, sub};
use crate::Point;
use rayon::prelude::*;
use std::borrow::Cow;

/// Why the boundary method does not settle a query.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Degenerate {
    /// The surfaces touch at points or along lines (a corner on a face, an edge through
    /// an edge): the volume, moments and interface change by no more than the move
    /// itself when B is moved off by a hair ([`super::overlap`] does). Listed first:
    /// the mildest.
    Touching,
    /// A body is not closed with exactly equal vertices ([`super::Body::unfit`]).
    Unfit,
    /// Faces of the two bodies lie in one plane: where they overlap, the interface
    /// (glued or shared faces) depends on which way they would be moved apart.
    Coplanar,
}

/// A body placed by a pose.
pub(super) struct Placed<'a> {
    pub body: &'a Body,
    /// The body's points, moved (the coordinates the grid method would see): the
    /// body's own when nothing moves them (no copy of a million points).
    pub world: Cow<'a, [Point]>,
    /// The world box.
    pub bounds: Option<Bounds>,
    /// The largest |coordinate| of the placed points (what the placed coordinates'
    /// rounding scales with).
    pub reach: f64,
    /// The largest |coordinate| of the own-frame points and of the pose's translation,
    /// plus the shift's length: what the rounding of the moved coordinates scales with.
    pub own_reach: f64,
}

impl<'a> Placed<'a> {
    /// `body` moved by `pose`, then by `shift` (rounded to the nearest coordinates).
    pub fn new(body: &'a Body, pose: Option<Affine>, shift: Point) -> Placed<'a> {
        let moved = |p: Point| match &pose {
            Some(m) => m.apply(p),
            None => p,
        };
        let (world, bounds) = if pose.is_none() && shift == [0.0; 3] {
            (Cow::Borrowed(body.points.as_slice()), body.bounds)
        } else {
            // On the caller's thread below 2¹⁴ points, as a pose loop's small bodies.
            let points = body.points.par_iter().with_min_len(1 << 14);
            let world: Vec<Point> = if shift == [0.0; 3] {
                points.map(|&p| moved(p)).collect()
            } else {
                points.map(|&p| add(moved(p), shift)).collect()
            };
            let bounds = Bounds::of_points(&world);
            (Cow::Owned(world), bounds)
        };
        let largest = |b: Option<Bounds>| {
            b.map_or(0.0, |b| b.min.iter().chain(&b.max).fold(0.0f64, |m, x| m.max(x.abs())))
        };
        let translation = pose.map_or(0.0, |m| (0..3).fold(0.0f64, |s, r| s.max(m.0[r][3].abs())));
        Placed {
            reach: largest(bounds),
            own_reach: largest(body.bounds).max(translation) + norm(shift),
            world,
            bounds,
            body,
        }
    }

    /// The corners of triangle `t`, placed.
    #[inline]
    pub fn corners(&self, t: usize) -> [Point; 3] {
        self.body.triangles[t].map(|i| self.world[i as usize])
    }
}

/// Where an edge crosses the other surface: its parameter from the edge's lower end,
/// the point, and a bound on the point's distance from the exact crossing.
#[derive(Clone, Copy, Debug)]
pub(super) struct Cut {
    pub edge: u32,
    pub t: f64,
    pub point: Point,
    pub error: f64,
}

/// A piece of the crossing curve on a face, oriented so that the other body's inside
/// lies to its left seen from the face's front (along n_face × n_other).
#[derive(Clone, Copy, Debug)]
pub(super) struct Seam {
    pub face: u32,
    pub from: Point,
    pub to: Point,
    pub error: [f64; 2],
}

/// What the crossing search found, per body (0: A, 1: B).
#[derive(Default)]
pub(super) struct Crossings {
    /// Each edge's crossings with the other surface, sorted by edge and parameter.
    pub cuts: [Vec<Cut>; 2],
    /// The seams, sorted by face.
    pub seams: [Vec<Seam>; 2],
}

/// Pairs of leaves per parallel task: fixed, so the output's order is the same at any
/// thread count.
const CHUNK: usize = 16;

/// Every crossing of A's and B's surfaces, or [`Degenerate`] (the worst found: coplanar
/// faces before touching ones).
pub(super) fn crossings(a: &Placed, b: &Placed) -> Result<Crossings, Degenerate> {
    let (Some(ba), Some(bb)) = (a.bounds, b.bounds) else { return Ok(Crossings::default()) };
    if !meets(&ba, &bb) {
        return Ok(Crossings::default());
    }
    // The trees' boxes refitted to the placed triangles: tight, in the placed frame.
    // A triangle's box is found again where it is needed (near the crossing curve
    // only) rather than kept for every triangle: the arrays of them, fresh each query,
    // cost more in page faults than the boxes do to compute.
    let (tree_a, tree_b) = (&a.body.bvh, &b.body.bvh);
    let (nodes_a, nodes_b) = rayon::join(
        || tree_a.refit(|t| box_of(a.corners(t))),
        || tree_b.refit(|t| box_of(b.corners(t))),
    );
    let leaves = tree_a.leaf_pairs_between(tree_b, &nodes_a, &nodes_b);
    let chunks: Vec<Result<Crossings, Degenerate>> = leaves
        .par_chunks(CHUNK)
        .map(|chunk| {
            let mut found = Crossings::default();
            let mut touching = false;
            let mut near_b: Vec<(usize, [Point; 3], Bounds)> = Vec::new();
            for &(m, n) in chunk {
                // Only the items of each leaf that meet the other leaf's box.
                near_b.clear();
                near_b.extend(tree_b.items(n).filter_map(|ib| {
                    let tb = b.corners(ib);
                    let box_b = box_of(tb);
                    meets(&box_b, &nodes_a[m as usize]).then_some((ib, tb, box_b))
                }));
                for ia in tree_a.items(m) {
                    if near_b.is_empty() {
                        break;
                    }
                    let ta = a.corners(ia);
                    let box_a = box_of(ta);
                    if !meets(&box_a, &nodes_b[n as usize]) {
                        continue;
                    }
                    for &(ib, tb, box_b) in &near_b {
                        if !meets(&box_a, &box_b) {
                            continue;
                        }
                        match pair(a, ia, ta, b, ib, tb, &mut found) {
                            Ok(()) => {}
                            // Coplanar faces decide the answer (the caller moves B off a
                            // touch, not off a plane); after a touch the search goes on
                            // for them.
                            Err(Degenerate::Coplanar) => return Err(Degenerate::Coplanar),
                            Err(_) => touching = true,
                        }
                    }
                }
            }
            if touching {
                return Err(Degenerate::Touching);
            }
            Ok(found)
        })
        .collect();
    if let Some(worst) = chunks.iter().filter_map(|c| c.as_ref().err()).max() {
        return Err(*worst);
    }
    let mut all = Crossings::default();
    for chunk in chunks.into_iter().flatten() {
        for s in 0..2 {
            all.cuts[s].extend_from_slice(&chunk.cuts[s]);
            all.seams[s].extend_from_slice(&chunk.seams[s]);
        }
    }
    for s in 0..2 {
        all.cuts[s].par_sort_unstable_by(|p, q| p.edge.cmp(&q.edge).then(p.t.total_cmp(&q.t)));
        all.seams[s].par_sort_by_key(|seam| seam.face);
    }
    Ok(all)
}

/// Whether closed boxes meet.
fn meets(p: &Bounds, q: &Bounds) -> bool {
    (0..3).all(|k| p.min[k] <= q.max[k] && q.min[k] <= p.max[k])
}

/// Decides the pair (A's triangle `ia`, B's `ib`): records the crossings of each one's
/// edges (those it owns) through the other's interior, and the seam of the two.
fn pair(
    a: &Placed,
    ia: usize,
    ta: [Point; 3],
    b: &Placed,
    ib: usize,
    tb: [Point; 3],
    found: &mut Crossings,
) -> Result<(), Degenerate> {
    let (flat_a, flat_b) = (a.body.flat[ia], b.body.flat[ib]);
    if flat_a && flat_b {
        return Ok(());
    }
    let plane_a = (!flat_a).then(|| Plane::of(ta));
    let plane_b = (!flat_b).then(|| Plane::of(tb));
    let sides_a = plane_b.as_ref().map(|p| ta.map(|q| p.orient(q)));
    let sides_b = plane_a.as_ref().map(|p| tb.map(|q| p.orient(q)));
    if sides_a.is_some_and(one_side) || sides_b.is_some_and(one_side) {
        return Ok(());
    }
    if sides_a.into_iter().chain(sides_b).any(|s| s == [0.0; 3]) {
        return Err(Degenerate::Coplanar);
    }
    if sides_a.into_iter().chain(sides_b).any(|s| s.contains(&0.0)) {
        return Err(Degenerate::Touching);
    }
    let mut ends: [(Point, f64); 2] = [([0.0; 3], 0.0); 2];
    let mut count = 0;
    for (side, this, t, other_plane, sides) in
        [(0, a, ia, &plane_b, sides_a), (1, b, ib, &plane_a, sides_b)]
    {
        let (Some(plane), Some(sides)) = (other_plane, sides) else { continue };
        for i in 0..3 {
            if sides[i] == sides[(i + 1) % 3] {
                continue;
            }
            let edge = this.body.face_edges[t][i];
            let [lo, hi] = this.body.edges[edge as usize].map(|v| this.world[v as usize]);
            match plane.crossing(lo, hi) {
                None => return Err(Degenerate::Touching),
                Some(false) => continue,
                Some(true) => {}
            }
            let cut = crossing_point(plane, edge, lo, hi);
            if this.body.owner[edge as usize] as usize == t {
                found.cuts[side].push(cut);
            }
            if count == 2 {
                return Err(Degenerate::Touching);
            }
            ends[count] = (cut.point, cut.error);
            count += 1;
        }
    }
    let (Some(pa), Some(pb)) = (&plane_a, &plane_b) else { return Ok(()) };
    match count {
        0 => Ok(()),
        2 => {
            // Along n_a × n_b, B's inside lies to the left on a, and A's inside to the
            // left on b going the other way.
            let along = cross(pa.normal(), pb.normal());
            let [p, q] = if dot(sub(ends[1].0, ends[0].0), along) >= 0.0 {
                ends
            } else {
                [ends[1], ends[0]]
            };
            found.seams[0].push(Seam { face: ia as u32, from: p.0, to: q.0, error: [p.1, q.1] });
            found.seams[1].push(Seam { face: ib as u32, from: q.0, to: p.0, error: [q.1, p.1] });
            Ok(())
        }
        _ => Err(Degenerate::Touching),
    }
}

/// Whether orientations `s` are all strictly on one side.
fn one_side(s: [f64; 3]) -> bool {
    s[0] != 0.0 && s[0] == s[1] && s[1] == s[2]
}

/// Where edge `lo`–`hi` (ends strictly on opposite sides of `plane`) crosses it, with a
/// bound on the error. From the ends' heights h above the plane (rounded, each within
/// e of the exact one), t = h_lo / (h_lo − h_hi); since the exact heights have
/// opposite signs, |h_lo − h_hi| is their sizes' sum, and t is off by at most about
/// (e_lo + e_hi) / |h_lo − h_hi|, or anything in [0, 1] when that is not small.
fn crossing_point(plane: &Plane, edge: u32, lo: Point, hi: Point) -> Cut {
    let ((h0, e0), (h1, e1)) = (plane.height(lo), plane.height(hi));
    let gap = (h0 - h1).abs();
    let t = if gap > 0.0 { (h0 / (h0 - h1)).clamp(0.0, 1.0) } else { 0.5 };
    let t_error =
        if e0 + e1 < 0.25 * gap { 2.0 * (e0 + e1) / gap + 4.0 * UNIT_ROUNDOFF } else { 1.0 };
    let d = sub(hi, lo);
    let point = [0, 1, 2].map(|k| lo[k] + t * d[k]);
    let error = t_error * norm(d) + 4.0 * UNIT_ROUNDOFF * (norm(lo) + norm(hi));
    Cut { edge, t, point, error }
}
