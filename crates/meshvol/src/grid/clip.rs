//! Convex polygons on the stack, split by planes and lines, and the two integrals the
//! grid kernels need over their xy projections.
//!
//! A [`Polygon`] holds at most `N` vertices in a fixed array: clipping a triangle never
//! allocates. Splitting a convex polygon with `n` vertices by a plane gives two convex
//! polygons with at most `n + 1` vertices each, so a triangle cut by `p` planes never
//! has more than `3 + p` vertices.
//!
//! # Splitting
//! Each vertex goes to the side(s) its signed distance `d` puts it on (both when
//! `d = 0`). An edge whose ends lie strictly on opposite sides gets a new vertex
//! `p + t·(q − p)`, `t = d_p / (d_p − d_q)`, always computed from the end `p` on the
//! negative side. Two triangles that share an edge therefore compute the same bits for
//! the points where it crosses a plane, whichever way each of them runs along the
//! edge, and the pieces of a closed surface stay closed after clipping. For an
//! axis-aligned plane the new vertex's coordinate on that axis is set to the plane's
//! exactly.
//!
//! # Integrals
//! Over the xy projection of a polygon whose z varies linearly, taken as a fan from
//! vertex 0 (exact for convex and for planar non-convex polygons):
//! - signed area `A = ½ Σ (v_k − v_0) × (v_{k+1} − v_0)` (positive counter-clockwise
//!   seen from +z);
//! - `∫ (z − t) dA = Σ A_k · ((z_0 − t) + (z_k − t) + (z_{k+1} − t)) / 3`, since the
//!   mean of a linear function over a triangle is its mean at the corners.

use crate::Point;

/// A convex polygon with at most `N` vertices, in order.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Polygon<const N: usize> {
    len: usize,
    vertices: [Point; N],
}

impl<const N: usize> Polygon<N> {
    pub(crate) const EMPTY: Self = Polygon { len: 0, vertices: [[0.0; 3]; N] };

    pub(crate) fn triangle(a: Point, b: Point, c: Point) -> Self {
        let mut p = Self::EMPTY;
        p.push(a);
        p.push(b);
        p.push(c);
        p
    }

    #[inline(always)]
    pub(crate) fn vertices(&self) -> &[Point] {
        &self.vertices[..self.len]
    }

    /// Appends a vertex; a full polygon ignores it (callers keep within `N` by the vertex
    /// count argument in the module docs).
    #[inline(always)]
    pub(crate) fn push(&mut self, v: Point) {
        if self.len < N {
            self.vertices[self.len] = v;
            self.len += 1;
        }
    }

    /// The least and greatest coordinate on `axis`; `(∞, −∞)` for an empty polygon.
    #[inline(always)]
    pub(crate) fn range(&self, axis: usize) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for v in self.vertices() {
            lo = if v[axis] < lo { v[axis] } else { lo };
            hi = if v[axis] > hi { v[axis] } else { hi };
        }
        (lo, hi)
    }

    /// Splits by the plane `v[axis] = c` into the parts with `v[axis] ≤ c` and `≥ c`.
    #[cfg(test)]
    pub(crate) fn split_axis(&self, axis: usize, c: f64) -> (Self, Self) {
        let (mut below, mut above) = (Self::EMPTY, Self::EMPTY);
        self.split_axis_into(axis, c, &mut below, &mut above);
        (below, above)
    }

    /// [`Polygon::split_axis`] into given polygons (no copies of whole polygons).
    #[inline(always)]
    pub(crate) fn split_axis_into(&self, axis: usize, c: f64, below: &mut Self, above: &mut Self) {
        self.split_into(|v| v[axis] - c, Some((axis, c)), below, above)
    }

    /// Splits by the sign of the affine function `distance` into the parts where it is
    /// ≤ 0 (`below`) and ≥ 0 (`above`). `exact` names an axis and value that new
    /// vertices take exactly.
    #[inline(always)]
    pub(crate) fn split_into(
        &self,
        distance: impl Fn(&Point) -> f64,
        exact: Option<(usize, f64)>,
        below: &mut Self,
        above: &mut Self,
    ) {
        below.len = 0;
        above.len = 0;
        let n = self.len;
        if n == 0 {
            return;
        }
        let mut u = self.vertices[n - 1];
        let mut du = distance(&u);
        for k in 0..n {
            let v = self.vertices[k];
            let dv = distance(&v);
            if (du < 0.0 && dv > 0.0) || (du > 0.0 && dv < 0.0) {
                let (p, q, dp, dq) = if du < 0.0 { (u, v, du, dv) } else { (v, u, dv, du) };
                let t = dp / (dp - dq);
                let mut x =
                    [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])];
                if let Some((axis, c)) = exact {
                    x[axis] = c;
                }
                below.push(x);
                above.push(x);
            }
            if dv <= 0.0 {
                below.push(v);
            }
            if dv >= 0.0 {
                above.push(v);
            }
            u = v;
            du = dv;
        }
    }

    /// Signed area of the xy projection and ∫ (z − t) dA over it (module docs).
    #[inline(always)]
    pub(crate) fn area_and_moment(&self, t: f64) -> (f64, f64) {
        if self.len < 3 {
            return (0.0, 0.0);
        }
        let o = self.vertices[0];
        let zo = o[2] - t;
        let mut double_area = 0.0;
        let mut six_moment = 0.0;
        for k in 1..self.len - 1 {
            let (a, b) = (self.vertices[k], self.vertices[k + 1]);
            let cross = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
            double_area += cross;
            six_moment += cross * (zo + (a[2] - t) + (b[2] - t));
        }
        (0.5 * double_area, six_moment / 6.0)
    }

    /// Signed area of the xy projection.
    #[inline(always)]
    pub(crate) fn area(&self) -> f64 {
        self.area_and_moment(0.0).0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    type P = Polygon<12>;

    #[test]
    fn split_keeps_area_and_is_direction_independent() {
        let t = P::triangle([0.0, 0.0, 0.0], [3.0, 0.0, 3.0], [0.0, 3.0, 6.0]);
        let (below, above) = t.split_axis(0, 1.0);
        assert_eq!(t.area(), 4.5);
        assert_eq!(below.area() + above.area(), 4.5);
        assert_eq!(below.range(0), (0.0, 1.0));
        // The point where edge (3,0)–(0,3) crosses x = 1 is the same either way round.
        let u = P::triangle([3.0, 0.0, 3.0], [0.0, 3.0, 6.0], [3.0, 3.0, 0.0]);
        let (ub, _) = u.split_axis(0, 1.0);
        let on_line = |p: &P| {
            let mut v: Vec<[u64; 3]> =
                p.vertices().iter().filter(|v| v[0] == 1.0).map(|v| v.map(f64::to_bits)).collect();
            v.sort();
            v
        };
        assert!(on_line(&below).iter().any(|v| on_line(&ub).contains(v)));
    }

    #[test]
    fn moment_of_a_linear_height() {
        // z = x over the unit square: ∫ z dA = 1/2; ∫ (z − 1) dA = −1/2.
        let mut sq = P::EMPTY;
        for v in [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 0.0]] {
            sq.push(v);
        }
        assert_eq!(sq.area_and_moment(0.0), (1.0, 0.5));
        assert_eq!(sq.area_and_moment(1.0), (1.0, -0.5));
        // Clockwise: negative.
        let cw = P::triangle([0.0, 0.0, 1.0], [0.0, 1.0, 1.0], [1.0, 0.0, 1.0]);
        assert_eq!(cw.area_and_moment(0.0), (-0.5, -0.5));
    }
}
