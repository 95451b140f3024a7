//! Stages 2 and 3: which points of a body lie inside the other, then the integrals over
//! the part of each face inside the other.
//!
//! **Inside points.** Along an edge, insideness changes at each crossing of the other's
//! closed surface, so a point's state is its neighbour's flipped once per crossing on
//! the edge between them. A walk over each connected part of the vertex graph settles
//! every point from one whose state is known: a point outside the other's box is
//! outside; failing one, a ray from the first point is cast through all of the other's
//! triangles (exact crossing tests, six axis directions tried in turn). An edge whose
//! two ends disagree with its crossings (which a closed surface without self-crossings
//! cannot give) makes the query [`Degenerate`].
//!
//! **Faces.** The part of face F inside the other body is bounded by the seams on F
//! and by the pieces of F's edges inside (an edge's pieces alternate at its
//! crossings), all running counter-clockwise seen from F's front. For such a closed
//! boundary, an integral over the region is the sum, over the boundary's segments
//! (s, e), of the integral over the triangle (p, s, e), p any point of F's plane (a
//! fan whose triangles may be negative): so each segment adds the terms of the
//! tetrahedron (o, p, s, e) to the moments, and (s − p) × (e − p) / 2 to F's vector
//! area. A face with no crossing is inside or outside whole.

use super::pairs::{Cut, Degenerate, Placed, Seam};
use crate::accumulate::{CompensatedSum, UNIT_ROUNDOFF};
use crate::topology::predicates::{ray_crossing, RAY_FRAMES};
use crate::vector::{add, cross, dot, norm, scale, sub};
use crate::Point;
use rayon::prelude::*;

/// The integrals over the part of one body's surface inside the other, about `origin`.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Part {
    /// ∫ 1, x, y, z, x², y², z², xy, yz, zx over the solid these faces bound with the
    /// other's part (each face's share, by the divergence theorem); the first is summed
    /// apart, six times over, compensated: `volume6`.
    pub sums: [f64; 10],
    pub volume6: CompensatedSum,
    /// Σ |terms of `volume6`| (for the summation's rounding) and the bound on the
    /// volume terms' errors from rounded points and products.
    pub magnitude: f64,
    pub error: f64,
    /// The number of terms summed.
    pub terms: usize,
    /// The part's area and ∫ n dA over it.
    pub area: f64,
    pub vector: Point,
}

impl Part {
    fn merge(&mut self, o: &Part) {
        self.volume6.merge(&o.volume6);
        for k in 1..10 {
            self.sums[k] += o.sums[k];
        }
        self.magnitude += o.magnitude;
        self.error += o.error;
        self.terms += o.terms;
        self.area += o.area;
        self.vector = add(self.vector, o.vector);
    }
}

/// Whether each point of `this` lies inside `other`, given `this`'s edge crossings.
pub(super) fn inside_points(
    this: &Placed,
    other: &Placed,
    cuts: &[Cut],
) -> Result<Vec<bool>, Degenerate> {
    let body = this.body;
    let mut odd = vec![false; body.edges.len()];
    for c in cuts {
        odd[c.edge as usize] ^= true;
    }
    const UNSEEN: u8 = 2;
    let mut state = vec![UNSEEN; body.points.len()];
    let mut part: Vec<u32> = Vec::new();
    for first in 0..body.points.len() {
        if state[first] != UNSEEN {
            continue;
        }
        // Walk the part with states relative to `first`'s.
        part.clear();
        part.push(first as u32);
        state[first] = 0;
        let mut next = 0;
        let mut known: Option<u8> = None;
        while next < part.len() {
            let v = part[next] as usize;
            next += 1;
            if known.is_none() && outside_box(this.world[v], other) {
                known = Some(state[v]); // v is outside: `first` is inside iff v's relative state is 1
            }
            let range = body.start[v] as usize..body.start[v + 1] as usize;
            for &(w, e) in &body.adjacent[range] {
                let s = state[v] ^ u8::from(odd[e as usize]);
                match state[w as usize] {
                    UNSEEN => {
                        state[w as usize] = s;
                        part.push(w);
                    }
                    t if t != s => return Err(Degenerate::Touching),
                    _ => {}
                }
            }
        }
        let first_inside = match known {
            Some(relative) => relative,
            None => u8::from(ray_parity(this.world[first], other)?),
        };
        for &v in &part {
            state[v as usize] ^= first_inside;
        }
    }
    Ok(state.into_iter().map(|s| s == 1).collect())
}

/// Whether `p` lies strictly outside `other`'s box.
fn outside_box(p: Point, other: &Placed) -> bool {
    other.bounds.is_none_or(|b| (0..3).any(|k| p[k] < b.min[k] || p[k] > b.max[k]))
}

/// Whether a ray from `p` crosses `other`'s surface an odd number of times (the first
/// of the six axis directions that meets no edge or corner).
fn ray_parity(p: Point, other: &Placed) -> Result<bool, Degenerate> {
    'frames: for turn in RAY_FRAMES {
        let q = turn(p);
        let mut odd = false;
        for t in 0..other.body.triangles.len() {
            let [a, b, c] = other.corners(t).map(turn);
            match ray_crossing(q, a, b, c) {
                Some(0) => {}
                Some(_) => odd = !odd,
                None => continue 'frames,
            }
        }
        return Ok(odd);
    }
    Err(Degenerate::Touching)
}

/// Faces per parallel task (fixed: the sums' order is the same at any thread count).
const CHUNK: usize = 1024;

/// The integrals over the part of `this`'s surface inside the other body, about
/// `origin`, from the points' states, `this`'s crossings (sorted by edge) and seams
/// (sorted by face).
pub(super) fn inside_part(
    this: &Placed,
    inside: &[bool],
    cuts: &[Cut],
    seams: &[Seam],
    origin: Point,
) -> Part {
    let body = this.body;
    // The few faces near the crossing curve are marked (a face with a seam; the ends of
    // each cut edge) and look their seams and cuts up by binary search: no table of
    // offsets over every edge and face, which cost more to fill than the marks.
    let mut seam_face = vec![false; body.triangles.len()];
    seams.iter().for_each(|s| seam_face[s.face as usize] = true);
    let mut cut_end = vec![false; body.points.len()];
    for c in cuts {
        body.edges[c.edge as usize].iter().for_each(|&v| cut_end[v as usize] = true);
    }
    let parts: Vec<Part> = (0..body.triangles.len())
        .into_par_iter()
        .step_by(CHUNK)
        .map(|begin| {
            let mut part = Part::default();
            let mut segments: Vec<([Point; 2], [f64; 2])> = Vec::new();
            for f in begin..(begin + CHUNK).min(body.triangles.len()) {
                if body.flat[f] {
                    continue;
                }
                let ids = body.triangles[f];
                let corners = ids.map(|v| this.world[v as usize]);
                let own_seams = if seam_face[f] { run(seams, |s| s.face, f as u32) } else { &[] };
                // Edge i runs from corner i to corner i + 1.
                let edge_cuts: [&[Cut]; 3] = [0, 1, 2].map(|i| {
                    if cut_end[ids[i] as usize] && cut_end[ids[(i + 1) % 3] as usize] {
                        run(cuts, |c| c.edge, body.face_edges[f][i])
                    } else {
                        &[]
                    }
                });
                segments.clear();
                if own_seams.is_empty() && edge_cuts.iter().all(|c| c.is_empty()) {
                    if !inside[ids[0] as usize] {
                        continue;
                    }
                    segments.push(([corners[1], corners[2]], [0.0; 2]));
                } else {
                    segments.extend(own_seams.iter().map(|s| ([s.from, s.to], s.error)));
                    for i in 0..3 {
                        let j = (i + 1) % 3;
                        edge_pieces(
                            (corners[i], corners[j]),
                            inside[ids[i] as usize],
                            ids[i] < ids[j],
                            edge_cuts[i],
                            &mut segments,
                        );
                    }
                }
                add_face(corners[0], &segments, origin, &mut part);
            }
            part
        })
        .collect();
    let mut total = Part::default();
    for p in &parts {
        total.merge(p);
    }
    total
}

/// The pieces of edge `from`–`to` inside the other body, in that direction: states
/// alternate at the crossings (`cuts`, in increasing parameter from the edge's lower
/// end, which is `from` when `forward`).
fn edge_pieces(
    (from, to): (Point, Point),
    inside_from: bool,
    forward: bool,
    cuts: &[Cut],
    segments: &mut Vec<([Point; 2], [f64; 2])>,
) {
    let mut inside = inside_from;
    let mut at = (from, 0.0);
    let mut step = |point: Point, error: f64, inside: &mut bool| {
        if *inside {
            segments.push(([at.0, point], [at.1, error]));
        }
        *inside = !*inside;
        at = (point, error);
    };
    if forward {
        cuts.iter().for_each(|c| step(c.point, c.error, &mut inside));
    } else {
        cuts.iter().rev().for_each(|c| step(c.point, c.error, &mut inside));
    }
    if inside {
        segments.push(([at.0, to], [at.1, 0.0]));
    }
}

/// Adds the region of a face bounded by `segments` (fanned from its corner `p`) to
/// `part`: the tetrahedra (origin, p, s, e), the vector area, and the error bound.
///
/// A segment's term is det(p, s, e)/6 about the origin, computed as
/// p · ((s − p) × (e − p)) / 6: its rounding is then within 8u|p||s − p||e − p| (the
/// triangle's size, not the origin's distance, squared), and moving p, s or e by δ
/// changes it by at most δ times the matching product of two of |p|, |s − p|, |e − p|.
/// The points' errors are the crossings' plus the rounding of the shift to the origin.
fn add_face(p: Point, segments: &[([Point; 2], [f64; 2])], origin: Point, part: &mut Part) {
    let shift = |x: Point| sub(x, origin);
    let rp = shift(p);
    let np = norm(rp);
    let dp = 2.0 * UNIT_ROUNDOFF * np;
    let mut face_vector = [0.0; 3];
    for &([s, e], [es, ee]) in segments {
        let (rs, re) = (shift(s), shift(e));
        let (v, w) = (sub(rs, rp), sub(re, rp));
        let area2 = cross(v, w);
        let d = dot(rp, area2);
        let terms = moment_terms(rp, rs, re);
        part.volume6.add(d);
        for k in 0..3 {
            part.sums[1 + k] += d / 24.0 * terms[k];
        }
        for k in 3..9 {
            part.sums[1 + k] += d / 120.0 * terms[k];
        }
        face_vector = add(face_vector, scale(area2, 0.5));
        let (nv, nw) = (norm(v), norm(w));
        let ds = es + 2.0 * UNIT_ROUNDOFF * norm(rs);
        let de = ee + 2.0 * UNIT_ROUNDOFF * norm(re);
        part.magnitude += d.abs();
        part.terms += 1;
        part.error += (dp * (nv * nw + np * nw + np * nv)
            + ds * np * nw
            + de * np * nv
            + 8.0 * UNIT_ROUNDOFF * np * nv * nw)
            / 6.0;
    }
    part.area += norm(face_vector);
    part.vector = add(part.vector, face_vector);
}

/// For the tetrahedron (0, a, b, c): s = a + b + c and a_i a_j + b_i b_j + c_i c_j +
/// s_i s_j for (i, j) = (0,0), (1,1), (2,2), (0,1), (1,2), (2,0); times det/24 and
/// det/120 they are its first and second moments.
fn moment_terms(a: Point, b: Point, c: Point) -> [f64; 9] {
    let s = [0, 1, 2].map(|k| a[k] + b[k] + c[k]);
    let pair = |i: usize, j: usize| a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j];
    [s[0], s[1], s[2], pair(0, 0), pair(1, 1), pair(2, 2), pair(0, 1), pair(1, 2), pair(2, 0)]
}

/// The run of `items` (sorted by `key`) whose key is `k`.
fn run<T>(items: &[T], key: impl Fn(&T) -> u32, k: u32) -> &[T] {
    let first = items.partition_point(|x| key(x) < k);
    let count = items[first..].partition_point(|x| key(x) == k);
    &items[first..first + count]
}
