//! A floating-point test that two triangles lie apart, for the crossing search's pairs
//! that the orientation filter leaves undecided.
//!
//! Two triangles that share no point cannot cross. Each triangle lies in the closed
//! half-space inside each of its *edge planes*: the plane through an edge, perpendicular
//! to the triangle (normal m = n × e for edge e and normal n = (t₁ − t₀) × (t₂ − t₀);
//! the opposite corner q has (q − p₀)·m = |n|² ≥ 0). When all three corners of the
//! other triangle are strictly outside one of these six planes, the two are disjoint.
//! Coplanar and nearly coplanar neighbours (which make the exact path of every
//! orientation test) are separated this way, in their common plane.
//!
//! Each sign is decided in floating point with a bound on its rounding: the value
//! g = (x − p₀)·(n × e) is a sum of monomials, each a product of four coordinate
//! differences, and its computed value carries at most 11 roundings per monomial (the
//! four differences, two in n, two in m, the product with x − p₀ and two additions), so
//! |ĝ − g| ≤ γ₁₁ · P with P the same sum with every term's magnitude (Higham, *Accuracy
//! and Stability of Numerical Algorithms*, §3.1). P computed in floating point from
//! the rounded differences is at least P(1 − ε)¹¹, so 12ε · P̂ bounds the error. The
//! model needs no underflow or overflow: every coordinate is zero or between 2⁻⁶⁴ and
//! 2⁶⁴ in magnitude (then every nonzero difference is a multiple of 2⁻¹¹⁶ below 2⁶⁵, and
//! every nonzero value met is far inside the normal range); otherwise the test declines.
//! The test only ever says "apart" for pairs that are: it may decline for pairs that
//! are, never the reverse, so the crossings found are those of the exact test alone.

use super::predicates::Plane;
use crate::vector::{cross, dot, sub};
use crate::Point;

/// 12ε with ε = 2⁻⁵³: the bound on the relative rounding of an edge-plane test.
const EDGE_PLANE_BOUND: f64 = 12.0 * (f64::EPSILON / 2.0);

/// Whether the coordinates of a triangle keep the rounding model valid: each zero or
/// between 2⁻⁶⁴ and 2⁶⁴ in magnitude.
fn modelled(t: &[Point; 3]) -> bool {
    const LOW: f64 = 1.0 / (1u128 << 64) as f64;
    const HIGH: f64 = (1u128 << 64) as f64;
    t.iter().flatten().all(|&x| x == 0.0 || (LOW..=HIGH).contains(&x.abs()))
}

/// Whether all of `points` are certainly strictly outside an edge plane of `plane`'s
/// triangle.
fn outside_an_edge(plane: &Plane, points: &[Point; 3]) -> bool {
    let t = &plane.t;
    (0..3).any(|k| {
        let p0 = t[k];
        let e = sub(t[(k + 1) % 3], p0);
        let m = cross(plane.normal, e);
        // The same products with magnitudes: the permanent of m's components.
        let (n_abs, e_abs) = (plane.magnitude, e.map(f64::abs));
        let m_abs = [
            n_abs[1] * e_abs[2] + n_abs[2] * e_abs[1],
            n_abs[2] * e_abs[0] + n_abs[0] * e_abs[2],
            n_abs[0] * e_abs[1] + n_abs[1] * e_abs[0],
        ];
        points.iter().all(|&x| {
            let d = sub(x, p0);
            dot(d, m) < -EDGE_PLANE_BOUND * dot(d.map(f64::abs), m_abs)
        })
    })
}

/// Whether the triangles of `t` and `u` certainly share no point: one strictly outside
/// an edge plane of the other. `false` when unsure.
pub(super) fn apart(t: &Plane, u: &Plane) -> bool {
    modelled(&t.t) && modelled(&u.t) && (outside_an_edge(t, &u.t) || outside_an_edge(u, &t.t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::XorShift;

    /// (x − p₀)·(n × e) for edge k of t, exactly, for coordinates that are integers
    /// below 2²⁴ (products of four differences fit an i128).
    fn edge_plane_exact(t: &[Point; 3], k: usize, x: Point) -> i128 {
        let i = |p: Point| p.map(|c| c as i128);
        let (a, b, c) = (i(t[0]), i(t[1]), i(t[2]));
        let s = |p: [i128; 3], q: [i128; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
        let x3 = |p: [i128; 3], q: [i128; 3]| {
            [p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]]
        };
        let n = x3(s(b, a), s(c, a));
        let p = [a, b, c];
        let m = x3(n, s(p[(k + 1) % 3], p[k]));
        let d = s(i(x), p[k]);
        d[0] * m[0] + d[1] * m[1] + d[2] * m[2]
    }

    /// Whether an edge plane of t has all of `points` strictly outside, exactly.
    fn outside_exactly(t: &[Point; 3], points: &[Point; 3]) -> bool {
        (0..3).any(|k| points.iter().all(|&x| edge_plane_exact(t, k, x) < 0))
    }

    /// Pairs on an integer grid: random, coplanar (both in one random plane through
    /// grid points), slivers and neighbours a step or two apart. `apart` must only say
    /// "apart" where exact arithmetic does, and say it often for coplanar neighbours.
    #[test]
    fn apart_only_where_exact_arithmetic_agrees() {
        let mut rng = XorShift::new(0x6a09e667f3bcc909);
        let (mut said, mut coplanar_said) = (0, 0);
        for case in 0..200_000 {
            let mut r = |n: u64| rng.below(2 * n + 1) as f64 - n as f64;
            let span = [3, 40, 1000, 300_000][case % 4];
            let base = [r(span), r(span), r(span)];
            let (s1, s2) = ([r(span), r(span), r(span)], [r(span), r(span), r(span)]);
            let mut point = |coplanar: bool| -> Point {
                if coplanar {
                    // base + i·s1 + j·s2 with small i, j: exactly in one plane.
                    let (i, j) = (r(3), r(3));
                    [0, 1, 2].map(|k| base[k] + i * s1[k] + j * s2[k])
                } else {
                    [0, 1, 2].map(|k| base[k] + r(span))
                }
            };
            let coplanar = case % 3 != 0;
            let t = [point(coplanar), point(coplanar), point(coplanar)];
            let mut u = [point(coplanar), point(coplanar), point(coplanar)];
            if case % 5 == 0 {
                u[0] = t[0]; // touching at a corner: never apart
            }
            if case % 7 == 0 {
                u[1] = [0, 1, 2].map(|k| (t[1][k] + t[2][k]) / 2.0); // on an edge
                u[1] = u[1].map(f64::floor);
            }
            if t.iter().chain(&u).flatten().any(|c| c.abs() >= (1 << 24) as f64) {
                continue;
            }
            let (pt, pu) = (Plane::of(t), Plane::of(u));
            let exact = outside_exactly(&t, &u) || outside_exactly(&u, &t);
            let fast = apart(&pt, &pu);
            assert!(!fast || exact, "apart but not exactly: {t:?} {u:?}");
            said += fast as usize;
            coplanar_said += (fast && coplanar) as usize;
        }
        assert!(said > 20_000 && coplanar_said > 10_000, "{said} {coplanar_said}");
    }

    /// Nearly coplanar pairs off any grid (an ulp or so out of a common plane), and
    /// slivers: `apart` must never say so for a pair that touches or crosses.
    #[test]
    fn never_apart_when_touching_or_crossing() {
        let mut rng = XorShift::new(0xbb67ae8584caa73b);
        for case in 0..100_000 {
            let mut unit = || rng.unit() - 0.5;
            let scale = [1.0, 1e-6, 1e6, 100.0][case % 4];
            let t = [0; 3].map(|_| [0; 3].map(|_| unit() * scale));
            // A point of t (on it, at barycentric (w, z)), nudged by a few ulps.
            let mut on = || {
                let (w, z) = (unit() + 0.5, unit() + 0.5);
                let (w, z) = if w + z > 1.0 { (1.0 - w, 1.0 - z) } else { (w, z) };
                let p =
                    [0, 1, 2].map(|k| t[0][k] + w * (t[1][k] - t[0][k]) + z * (t[2][k] - t[0][k]));
                p.map(|c| c * (1.0 + unit() * 8.0 * f64::EPSILON))
            };
            // u through a point near t, the rest anywhere in t's plane or off it.
            let far = |p: Point, q: Point, s: f64| [0, 1, 2].map(|k| p[k] + s * (q[k] - p[k]));
            let hit = on();
            let u = match case % 3 {
                0 => [hit, far(hit, t[0], -3.0), far(hit, t[1], -2.5)], // coplanar, overlapping
                1 => [hit, far(hit, t[2], 1e-9), far(hit, t[1], -1e-9)], // a sliver at a point of t
                _ => [hit, [unit(), unit(), unit()], [unit(), unit(), unit()]],
            };
            assert!(!apart(&Plane::of(t), &Plane::of(u)), "{t:?} {u:?}");
            assert!(!apart(&Plane::of(u), &Plane::of(t)), "{t:?} {u:?}");
        }
    }
}
