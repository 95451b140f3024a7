//! Axis-aligned bounding boxes: the one type every stage's box is.

use crate::vector::sub;
use crate::Point;
use rayon::prelude::*;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: Point,
    pub max: Point,
}

impl Bounds {
    /// Contains nothing: the identity of [`Bounds::merge`].
    pub(crate) const EMPTY: Bounds =
        Bounds { min: [f64::INFINITY; 3], max: [f64::NEG_INFINITY; 3] };

    pub(crate) fn of(p: Point) -> Bounds {
        Bounds { min: p, max: p }
    }

    #[inline(always)]
    pub(crate) fn include(&mut self, p: Point) {
        // Plain comparisons, not f64::min/max: coordinates are finite, and the NaN
        // handling of min/max costs several instructions each in the hot loop.
        for ((lo, hi), x) in self.min.iter_mut().zip(&mut self.max).zip(p) {
            *lo = if x < *lo { x } else { *lo };
            *hi = if x > *hi { x } else { *hi };
        }
    }

    pub(crate) fn merge(&mut self, other: &Bounds) {
        self.include(other.min);
        self.include(other.max);
    }

    /// The box of `points` (`None` for none), reduced in parallel for many points (minima
    /// and maxima do not depend on the order); on the caller's thread below 2¹⁴ points,
    /// as for a placed body in a pose loop.
    pub(crate) fn of_points(points: &[Point]) -> Option<Bounds> {
        let merged = |mut a: Bounds, b: Bounds| {
            a.merge(&b);
            a
        };
        let include = |mut b: Bounds, p: &Point| {
            b.include(*p);
            b
        };
        let b = points
            .par_iter()
            .with_min_len(1 << 14)
            .fold(|| Bounds::EMPTY, include)
            .reduce(|| Bounds::EMPTY, merged);
        (!points.is_empty()).then_some(b)
    }

    pub fn size(&self) -> Point {
        sub(self.max, self.min)
    }
}
