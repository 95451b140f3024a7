//! Convex pieces of the plan: a counter-clockwise polygon whose corners carry the depth
//! d = existing − design, which is linear on the piece. Cut by a line (Sutherland–Hodgman,
//! one plane at a time), and integrated exactly: a linear function over a triangle
//! integrates to the triangle's area times the mean of its corner values, and a convex
//! polygon is a fan of triangles from its first corner.

use crate::accumulate::CompensatedSum;

/// Most corners a piece can have: a triangle clipped by a triangle has 6, then by the
/// four sides of a cell 10, then by the line d = 0 one more.
const CAPACITY: usize = 12;

/// A convex polygon in the plan, counter-clockwise; each corner is (x, y, d).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Piece {
    corners: [[f64; 3]; CAPACITY],
    len: usize,
}

impl Piece {
    pub fn triangle(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Piece {
        let mut corners = [[0.0; 3]; CAPACITY];
        corners[..3].copy_from_slice(&[a, b, c]);
        Piece { corners, len: 3 }
    }

    pub fn corners(&self) -> &[[f64; 3]] {
        &self.corners[..self.len]
    }

    pub fn corners_mut(&mut self) -> &mut [[f64; 3]] {
        &mut self.corners[..self.len]
    }

    /// Fewer than three corners: nothing left.
    pub fn is_empty(&self) -> bool {
        self.len < 3
    }

    /// The parts of the piece where `side` (an affine function of the corner, so that
    /// it can be interpolated along an edge) is ≤ 0 and ≥ 0. Corners where it is 0 are
    /// in both; a new corner is made where an edge crosses from one sign to the other.
    pub fn split(&self, side: impl Fn([f64; 3]) -> f64) -> (Piece, Piece) {
        let mut below = Piece { corners: [[0.0; 3]; CAPACITY], len: 0 };
        let mut above = below;
        let n = self.len;
        let mut s_here = side(self.corners[0]);
        for i in 0..n {
            let here = self.corners[i];
            let next = self.corners[(i + 1) % n];
            let s_next = side(next);
            if s_here <= 0.0 {
                below.push(here);
            }
            if s_here >= 0.0 {
                above.push(here);
            }
            if (s_here < 0.0 && s_next > 0.0) || (s_here > 0.0 && s_next < 0.0) {
                let t = s_here / (s_here - s_next);
                let crossing = [0, 1, 2].map(|k| here[k] + (next[k] - here[k]) * t);
                below.push(crossing);
                above.push(crossing);
            }
            s_here = s_next;
        }
        (below, above)
    }

    /// The part where `side` ≥ 0.
    pub fn keep(&self, side: impl Fn([f64; 3]) -> f64) -> Piece {
        self.split(side).1
    }

    fn push(&mut self, corner: [f64; 3]) {
        // A convex piece gains at most one corner per cut, and no piece is cut more
        // often than CAPACITY allows; a corner past it (impossible) would be dropped.
        if self.len < CAPACITY {
            self.corners[self.len] = corner;
            self.len += 1;
        }
    }

    /// The piece's area and the integral of d over it, from its fan.
    pub fn area_and_integral(&self) -> (f64, f64) {
        let c = self.corners();
        let (mut area, mut integral) = (0.0, 0.0);
        for k in 1..c.len().saturating_sub(1) {
            let (a, b, e) = (c[0], c[k], c[k + 1]);
            let twice = (b[0] - a[0]) * (e[1] - a[1]) - (b[1] - a[1]) * (e[0] - a[0]);
            area += 0.5 * twice;
            integral += twice * (a[2] + b[2] + e[2]) / 6.0;
        }
        (area, integral)
    }
}

/// Running sums of cut and fill (compensated, merged in a fixed order).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Sums {
    pub cut: CompensatedSum,
    pub fill: CompensatedSum,
    pub area_cut: CompensatedSum,
    pub area_fill: CompensatedSum,
    pub footprint: CompensatedSum,
}

/// What one piece adds: [cut, fill, area_cut, area_fill, footprint].
pub(crate) type Amounts = [f64; 5];

impl Sums {
    pub fn add(&mut self, a: &Amounts) {
        self.cut.add(a[0]);
        self.fill.add(a[1]);
        self.area_cut.add(a[2]);
        self.area_fill.add(a[3]);
        self.footprint.add(a[4]);
    }

    pub fn merge(&mut self, other: &Sums) {
        self.cut.merge(&other.cut);
        self.fill.merge(&other.fill);
        self.area_cut.merge(&other.area_cut);
        self.area_fill.merge(&other.area_fill);
        self.footprint.merge(&other.footprint);
    }
}

/// Cut and fill of one piece: split at d = 0, ∫ d over the part where d > 0 (cut) and
/// ∫ −d where d < 0 (fill), with the parts' areas. A part counts only where d is not 0
/// at every corner, so ground where the surfaces meet is neither cut nor fill.
pub(crate) fn amounts(piece: &Piece) -> Amounts {
    let (footprint, _) = piece.area_and_integral();
    let d = piece.corners().iter().map(|c| c[2]);
    let (any_above, any_below) = d.fold((false, false), |(a, b), d| (a || d > 0.0, b || d < 0.0));
    let [mut cut, mut fill, mut area_cut, mut area_fill] = [0.0; 4];
    let mut take = |part: &Piece, above: bool| {
        let (area, integral) = part.area_and_integral();
        if above {
            (cut, area_cut) = (integral, area);
        } else {
            (fill, area_fill) = (-integral, area);
        }
    };
    match (any_above, any_below) {
        (true, true) => {
            let (below, above) = piece.split(|c| c[2]);
            take(&above, true);
            take(&below, false);
        }
        (true, false) => take(piece, true),
        (false, true) => take(piece, false),
        (false, false) => {}
    }
    [cut, fill, area_cut, area_fill, footprint]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_crossing_zero() {
        // The unit right triangle with d = x − 1/2: cut is ∫ over x > 1/2 of (x − 1/2),
        // the triangle x ∈ [1/2, 1], y ≤ 1 − x: ∫ (x − 1/2)(1 − x) dx = 1/48; fill is
        // ∫ over x < 1/2 of (1/2 − x)(1 − x) dx = 5/48 (both by hand).
        let p = Piece::triangle([0.0, 0.0, -0.5], [1.0, 0.0, 0.5], [0.0, 1.0, -0.5]);
        let [cut, fill, area_cut, area_fill, footprint] = amounts(&p);
        assert!((cut - 1.0 / 48.0).abs() < 1e-16, "{cut}");
        assert!((fill - 5.0 / 48.0).abs() < 1e-16, "{fill}");
        assert!((area_cut - 0.125).abs() < 1e-16 && (area_fill - 0.375).abs() < 1e-16);
        assert_eq!(footprint, 0.5);
    }

    #[test]
    fn ground_where_the_surfaces_meet_is_neither() {
        let p = Piece::triangle([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(amounts(&p), [0.0, 0.0, 0.0, 0.0, 0.5]);
        // Touching zero at one corner only: all cut.
        let p = Piece::triangle([0.0, 0.0, 0.0], [1.0, 0.0, 3.0], [0.0, 1.0, 3.0]);
        assert_eq!(amounts(&p), [1.0, 0.0, 0.5, 0.0, 0.5]);
    }

    #[test]
    fn splitting_keeps_the_area() {
        let p = Piece::triangle([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        let (left, right) = p.split(|c| c[0] - 0.5);
        let (a, b) = (left.area_and_integral().0, right.area_and_integral().0);
        assert_eq!(a + b, 2.0);
        assert_eq!(right.area_and_integral().0, 1.125);
        // A cut that misses leaves the whole piece on one side and nothing on the other.
        let (none, all) = p.split(|c| c[0] + 1.0);
        assert!(none.is_empty() && all.corners().len() == 3);
    }
}
