//! Stage 3b, sheets: the faces around a non-manifold edge paired into locally manifold
//! sheets, so that two bodies touching along an edge are two closed bodies.
//!
//! Where more than two faces meet at an edge, they are sorted by their angle around it,
//! exactly: each face is represented by its first corner off the edge's line, p, and
//! face j follows face i counter-clockwise about d = w − v (v the smaller vertex) when
//! det[d, pᵢ − v, pⱼ − v] > 0, an orientation predicate. Each face is then paired with a
//! neighbour in that order, as if the faces around the edge were pulled a hair apart
//! (the standard treatment of non-manifold edges; CGAL's polygon-soup orientation and
//! Manifold's import do the same).
//!
//! Which neighbour follows the file's winding where it allows. A face that traverses
//! the edge backward (w → v) has its outward normal pointing clockwise about d, so the
//! material it bounds lies counter-clockwise of it: it opens a wedge of material that
//! the next face traversing the edge forward closes. Matching the faces as brackets
//! around the circle (a backward face opens, a forward face closes), started just after
//! the lowest prefix count, pairs the faces that bound one piece of material; the pairs
//! never cross. Faces left over (the file winds them against each other) lie between
//! complete pairs, and are paired with the next leftover around the circle (such a pair
//! is wound the same way, and orientation propagation turns one of them), starting where
//! the pairs' angles add up least; when their number is odd, one face stays alone: a
//! boundary of its sheet, capped like a hole (see `holes.rs`). A face without a corner
//! off the edge's line (a sliver) has no angle, and is a leftover.
//!
//! After this stage an edge's uses are its sheets: `uses.chunks(2)` gives each sheet's
//! two faces there, or one face alone at a boundary (an edge with one use, or the odd
//! face out at a non-manifold edge). Edges of one or two uses are left as they are.

use super::edges::{EdgeUse, Edges};
use super::loops::Loops;
use super::weld::Welded;
use crate::vector::{cross, dot, orient3d, sub};
use crate::Point;
use std::cmp::Ordering;
use std::f64::consts::TAU;

/// Leftover faces beyond this many are paired from the first, without comparing where
/// to start (a bound on the work a hostile edge can ask for; real edges have a few).
const MAX_LEFTOVERS_COMPARED: usize = 64;

/// Reorders the uses of every non-manifold edge of `edges` into sheets (see the module
/// docs). Returns how many faces were left alone at non-manifold edges.
pub(super) fn pair(edges: &mut Edges, loops: &Loops, welded: &Welded) -> usize {
    let vertex = |c: usize| welded.corner_vertex[c];
    let position = |c: usize| welded.positions[vertex(c) as usize];
    // The edge of a use, in its face's direction, and the face's first corner off it.
    let anchor = |u: &EdgeUse| {
        let (f, c) = (u.face() as usize, u.corner as usize);
        let (a, b) = (position(c), position(loops.next(f, c)));
        let mut k = loops.next(f, loops.next(f, c));
        while k != c {
            let p = position(k);
            if cross(sub(b, a), sub(p, a)) != [0.0; 3] {
                return Some(p);
            }
            k = loops.next(f, k);
        }
        None
    };
    edges.groups_mut(|uses| {
        if uses.len() < 3 {
            return 0;
        }
        let first = uses[0];
        let (f, c) = (first.face() as usize, first.corner as usize);
        let (a, b) = (position(c), position(loops.next(f, c)));
        // The edge from its smaller vertex to its larger.
        let (v, w) = if first.forward() { (a, b) } else { (b, a) };
        let anchored: Vec<(EdgeUse, Option<Point>)> =
            uses.iter().map(|u| (*u, anchor(u))).collect();
        let sheets = sheets_around(v, w, &anchored);
        let alone = sheets.len() % 2;
        uses.copy_from_slice(&sheets);
        alone
    })
}

/// The uses around the edge v → w, each with its anchor point, reordered into sheets.
fn sheets_around(v: Point, w: Point, uses: &[(EdgeUse, Option<Point>)]) -> Vec<EdgeUse> {
    let ccw = |p: Point, q: Point| -orient3d(v, w, p, q); // det[w − v, p − v, q − v]
    let anchored: Vec<(EdgeUse, Point)> = uses.iter().filter_map(|&(u, p)| Some((u, p?))).collect();
    let unanchored = uses.iter().filter(|u| u.1.is_none()).map(|u| u.0);
    let reference = anchored.first().map_or(w, |u| u.1);
    let (d, r) = (sub(w, v), sub(reference, v));
    // Where p lies about the edge seen from the reference, in floating point: the dot
    // product of the two's parts across the edge, and |r⊥| |q⊥| sin of the angle between.
    let across = |p: Point| {
        let q = sub(p, v);
        (dot(r, q) - dot(r, d) * dot(q, d) / dot(d, d), dot(d, cross(r, q)) / dot(d, d).sqrt())
    };
    // Half-turns from the reference: 0 on its ray, 1 the half it turns into
    // counter-clockwise, 2 the opposite ray, 3 the other half (exactly, but for telling
    // the two rays in the reference's plane apart).
    let half = |p: Point| match ccw(reference, p) {
        s if s > 0.0 => 1u8,
        s if s < 0.0 => 3,
        _ if across(p).0 >= 0.0 => 0,
        _ => 2,
    };
    let mut around: Vec<(EdgeUse, Point, u8)> =
        anchored.into_iter().map(|(u, p)| (u, p, half(p))).collect();
    around.sort_by(|x, y| {
        x.2.cmp(&y.2).then_with(|| match ccw(x.1, y.1) {
            s if s > 0.0 => Ordering::Less,
            s if s < 0.0 => Ordering::Greater,
            _ => (x.0.forward(), x.0.face()).cmp(&(y.0.forward(), y.0.face())),
        })
    });

    // Brackets: backward faces open, forward faces close, from just after the lowest
    // prefix count, so that every pair found is one wedge of material.
    let n = around.len();
    let mut count = 0i64;
    let mut start = 0;
    let mut lowest = 0i64;
    for (i, u) in around.iter().enumerate() {
        count += if u.0.forward() { -1 } else { 1 };
        if count < lowest {
            lowest = count;
            start = i + 1;
        }
    }
    let mut sheets = Vec::with_capacity(uses.len());
    let mut open: Vec<usize> = Vec::new();
    let mut leftover: Vec<usize> = Vec::new();
    for i in (0..n).map(|k| (start + k) % n) {
        if !around[i].0.forward() {
            open.push(i);
        } else if let Some(o) = open.pop() {
            sheets.extend([around[o].0, around[i].0]);
        } else {
            leftover.push(i);
        }
    }
    // Unmatched closing faces came first in the walk, unmatched opening ones last: in
    // walk order, they are in order around the edge.
    leftover.extend(open);
    let angle = |i: usize| {
        let (x, y) = across(around[i].1);
        y.atan2(x)
    };
    let mut rest: Vec<EdgeUse> = leftover.iter().map(|&i| around[i].0).collect();
    let angles: Vec<f64> = leftover.iter().map(|&i| angle(i)).collect();
    let shift = cheapest_start(&angles);
    rest.rotate_left(shift);
    rest.extend(unanchored);
    sheets.extend(rest);
    sheets
}

/// Where to start pairing the leftovers at `angles` (in order around the edge) two by
/// two, so that the pairs' angular spans add up least (the one left alone when their
/// number is odd is the one before the start).
fn cheapest_start(angles: &[f64]) -> usize {
    let m = angles.len();
    if !(2..=MAX_LEFTOVERS_COMPARED).contains(&m) {
        return 0;
    }
    let span = |i: usize| (angles[(i + 1) % m] - angles[i]).rem_euclid(TAU);
    let cost = |s: usize| (0..m / 2).map(|k| span((s + 2 * k) % m)).sum::<f64>();
    let starts = if m.is_multiple_of(2) { 2 } else { m };
    (0..starts).min_by(|&x, &y| cost(x).total_cmp(&cost(y))).unwrap_or(0)
}
