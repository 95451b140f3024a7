//! A chunk's running sums of the mass properties (see the module docs of
//! [`crate::properties`]): the volume's [`VolumeSums`], the first and second moments and
//! the double area, and the box; one triangle's terms.

use super::bounds::Bounds;
use crate::accumulate::CompensatedSum;
use crate::vector::sub;
use crate::volume_sums::VolumeSums;
use crate::Point;
use std::ops::{Add, Mul};

/// Faces summed in plain f64 before their moment sums join the compensated ones.
pub(super) const BLOCK_FACES: usize = 64;

/// Per-chunk running sums. The volume, whose error bound is reported, is compensated
/// term by term; the moments and area (no published bound) are summed plainly within
/// blocks of [`BLOCK_FACES`] faces and compensated across blocks, which keeps them
/// accurate to about γ(64) of their terms at a fraction of the cost.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Partial {
    pub(super) volume: VolumeSums,
    pub(super) first: [CompensatedSum; 3],
    /// xx, yy, zz, xy, yz, zx.
    pub(super) second: [CompensatedSum; 6],
    pub(super) double_area: CompensatedSum,
    /// The current block's plain sums: first moments, second moments, double area.
    pub(super) block: [f64; 10],
    pub(super) bounds: Option<Bounds>,
}

impl Partial {
    pub(super) fn merge(&mut self, o: Partial) {
        self.volume.merge(&o.volume);
        for (a, b) in self.first.iter_mut().zip(&o.first) {
            a.merge(b);
        }
        for (a, b) in self.second.iter_mut().zip(&o.second) {
            a.merge(b);
        }
        self.double_area.merge(&o.double_area);
        match (&mut self.bounds, o.bounds) {
            (Some(a), Some(b)) => a.merge(&b),
            (a @ None, b) => *a = b,
            _ => {}
        }
    }

    /// Moves the block's plain sums into the compensated ones.
    pub(super) fn flush_block(&mut self) {
        let block = std::mem::take(&mut self.block);
        for (sum, x) in self.first.iter_mut().chain(&mut self.second).zip(block) {
            sum.add(x);
        }
        self.double_area.add(block[9]);
    }

    /// A chunk's four interleaved sums (see `volume_sums::LaneSums`), their blocks flushed,
    /// merged in order, with the chunk's bounds.
    pub(super) fn merged(mut lanes: [Partial; 4], bounds: Bounds) -> Partial {
        lanes.iter_mut().for_each(Partial::flush_block);
        let [mut total, rest @ ..] = lanes;
        for lane in rest {
            total.merge(lane);
        }
        total.bounds = Some(bounds);
        total
    }

    /// Adds fan triangle (a, b, c): its D ([`VolumeSums::add_fan_triangle`]) and its
    /// moments' terms about r; returns its cross product and magnitudes for the face's
    /// vector area.
    #[inline(always)]
    pub(super) fn add_triangle(
        &mut self,
        r: Point,
        a: Point,
        b: Point,
        c: Point,
    ) -> (Point, Point) {
        let (cross, magnitude, d) = self.volume.add_fan_triangle(r, a, b, c);
        let terms = moment_terms(sub(a, r), sub(b, r), sub(c, r));
        for (sum, t) in self.block.iter_mut().zip(terms) {
            *sum += d * t;
        }
        (cross, magnitude)
    }
}

/// The nine terms a triangle `(a, b, c)` adds, times its determinant, to the first and
/// second moments: `s = a + (b + c)` and `a_i a_j + (b_i b_j + c_i c_j) + s_i s_j`, grouped
/// so that reversing the winding (swapping b and c) negates every term exactly. One body
/// for one triangle (f64) and for four at once (SIMD lanes): the same bits.
#[inline(always)]
pub(super) fn moment_terms<T: Copy + Add<Output = T> + Mul<Output = T>>(
    a: [T; 3],
    b: [T; 3],
    c: [T; 3],
) -> [T; 9] {
    // Written out, not through `array::map` (see `volume::corners`).
    let s = [a[0] + (b[0] + c[0]), a[1] + (b[1] + c[1]), a[2] + (b[2] + c[2])];
    let pair = |i: usize, j: usize| a[i] * a[j] + (b[i] * b[j] + c[i] * c[j]) + s[i] * s[j];
    [s[0], s[1], s[2], pair(0, 0), pair(1, 1), pair(2, 2), pair(0, 1), pair(1, 2), pair(2, 0)]
}
