//! Sums that keep their digits: compensated (TwoSum) sums with an error bound, an exact
//! fixed-point accumulator, and the fixed-chunk parallel reduction that makes every
//! result the same bits at any thread count.
//!
//! # Compensated sums
//! [`CompensatedSum`] keeps a running sum `s` and the exact rounding error of each
//! addition (Knuth's TwoSum: `t = s + x` and `(s − (t − z)) + (x − z)` with `z = t − s`
//! is exactly `s + x − t`), accumulated in `c`. The result `s + c` is as accurate as a
//! sum in twice the working precision (Ogita, Rump, Oishi 2005, "Sum2"):
//! `|result − Σx| ≤ u·|Σx| + γ(n−1)²·Σ|x|`, with `u = 2⁻⁵³` and `γ(n) = n·u / (1 − n·u)`.
//!
//! # Exact sums
//! [`ExactSum`] is a fixed-point accumulator wide enough for every finite f64
//! (Kulisch's long accumulator): each double `m·2ᵉ` is added as integers into 32-bit
//! limbs, so the sum is exact, independent of order, and rounded once at the end.
//! Written here rather than taken from a crate because the exact mode needs the exact
//! sum *divided by 6* rounded once, which requires the accumulator's integer value;
//! summation crates return only the rounded sum, and rounding twice can miss by an ulp.
//!
//! # Deterministic reduction
//! [`ordered_reduce`] cuts the index range into fixed chunks, maps them in parallel and
//! combines the chunk results strictly left to right: the chunking, and so every
//! rounding, does not depend on the number of threads.

use num_bigint::{BigInt, Sign};
use rayon::prelude::*;
use std::ops::Range;

/// Unit roundoff of f64: 2⁻⁵³.
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// γ(n) = n·u / (1 − n·u), the classic bound on the relative error of n roundings.
pub fn gamma(n: f64) -> f64 {
    let nu = n * UNIT_ROUNDOFF;
    nu / (1.0 - nu)
}

/// `a + b` as the rounded sum and its exact rounding error.
#[inline(always)]
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let z = s - a;
    (s, (a - (s - z)) + (b - z))
}

/// A compensated (TwoSum) running sum; see the module docs for its error bound.
///
/// ```
/// use meshvol::accumulate::CompensatedSum;
/// let mut s = CompensatedSum::default();
/// for x in [1e16, 1.0, -1e16, 1.0] { s.add(x); }
/// assert_eq!(s.value(), 2.0); // a plain f64 sum gives 0 or 1
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CompensatedSum {
    sum: f64,
    compensation: f64,
}

impl CompensatedSum {
    #[inline(always)]
    pub fn add(&mut self, x: f64) {
        let (s, e) = two_sum(self.sum, x);
        self.sum = s;
        self.compensation += e;
    }

    /// Adds another compensated sum (used to combine chunk results in order).
    pub fn merge(&mut self, other: &CompensatedSum) {
        self.add(other.sum);
        self.compensation += other.compensation;
    }

    #[inline]
    pub fn value(&self) -> f64 {
        self.sum + self.compensation
    }

    /// The sum with running sum `sum` and accumulated errors `compensation` (as a SIMD
    /// lane that ran the same additions left them).
    pub(crate) fn from_parts(sum: f64, compensation: f64) -> CompensatedSum {
        CompensatedSum { sum, compensation }
    }
}

/// Faces per chunk of the deterministic parallel reductions over a surface's faces (the
/// volume, the mass properties, the exact sum, sections, grids).
pub(crate) const CHUNK_FACES: usize = 1 << 14;

/// Maps fixed chunks of `0..len` in parallel and combines the results in index order.
///
/// `map` receives a chunk's index range; `combine` folds results left to right. The
/// chunk size is fixed, so the result is bit-identical for any number of threads.
pub fn ordered_reduce<T: Send>(
    len: usize,
    chunk: usize,
    map: impl Fn(Range<usize>) -> T + Sync,
    combine: impl FnMut(&mut T, T),
) -> Option<T> {
    ordered_reduce_on(true, len, chunk, map, combine)
}

/// [`ordered_reduce`] on the caller's thread alone when `parallel` is false: the same
/// chunks combined in the same order, so the same bits, without the pool's hand-offs
/// (which cost more than a small input's whole sum).
pub fn ordered_reduce_on<T: Send>(
    parallel: bool,
    len: usize,
    chunk: usize,
    map: impl Fn(Range<usize>) -> T + Sync,
    mut combine: impl FnMut(&mut T, T),
) -> Option<T> {
    let chunks = len.div_ceil(chunk);
    let range = |i: usize| i * chunk..((i + 1) * chunk).min(len);
    if !parallel {
        let mut parts = (0..chunks).map(|i| map(range(i)));
        let mut total = parts.next()?;
        for part in parts {
            combine(&mut total, part);
        }
        return Some(total);
    }
    let parts: Vec<T> = (0..chunks).into_par_iter().map(|i| map(range(i))).collect();
    let mut parts = parts.into_iter();
    let mut total = parts.next()?;
    for part in parts {
        combine(&mut total, part);
    }
    Some(total)
}

/// Bits of a limb's weight: limb `i` weighs 2^(32·i − 1074).
const LIMB_BITS: u32 = 32;
/// Lowest bit of the largest finite double is at 2^971, i.e. position 2045 from 2^−1074;
/// a 53-bit mantissa shifted by up to 31 more bits spans three limbs, plus headroom limbs
/// for the sums of many terms.
const LIMBS: usize = 2045 / LIMB_BITS as usize + 3 + 2;
/// Additions allowed before carries must be propagated: each adds less than 2³² to a
/// limb, and an i64 limb holds 2⁶³.
const ADDS_BEFORE_CARRY: u32 = 1 << 30;

/// Exact sum of finite doubles (a long fixed-point accumulator).
///
/// ```
/// use meshvol::accumulate::ExactSum;
/// let mut s = ExactSum::default();
/// for x in [1e300, 1e-300, -1e300, 3.0] { s.add(x); }
/// assert_eq!(s.round(), 3.0 + 1e-300);
/// assert_eq!(s.round_divided_by(3), (3.0 + 1e-300) / 3.0);
/// ```
#[derive(Clone, Debug)]
pub struct ExactSum {
    limbs: [i64; LIMBS],
    pending: u32,
}

impl Default for ExactSum {
    fn default() -> Self {
        ExactSum { limbs: [0; LIMBS], pending: 0 }
    }
}

impl ExactSum {
    /// Adds `x` exactly. `x` must be finite (non-finite values are ignored by contract;
    /// callers check first).
    #[inline]
    pub fn add(&mut self, x: f64) {
        if x == 0.0 || !x.is_finite() {
            return;
        }
        let bits = x.to_bits();
        let biased_exp = ((bits >> 52) & 0x7ff) as u32;
        let fraction = bits & ((1u64 << 52) - 1);
        // x = mantissa · 2^(position − 1074)
        let (mantissa, position) =
            if biased_exp == 0 { (fraction, 0) } else { (fraction | (1u64 << 52), biased_exp - 1) };
        let limb = (position / LIMB_BITS) as usize;
        let shifted = u128::from(mantissa) << (position % LIMB_BITS);
        let negative = bits >> 63 == 1;
        for k in 0..3 {
            let piece = ((shifted >> (LIMB_BITS * k)) & 0xffff_ffff) as i64;
            if negative {
                self.limbs[limb + k as usize] -= piece;
            } else {
                self.limbs[limb + k as usize] += piece;
            }
        }
        self.pending += 1;
        if self.pending == ADDS_BEFORE_CARRY {
            self.carry();
        }
    }

    /// Adds another exact sum.
    pub fn merge(&mut self, other: &ExactSum) {
        let mut other = other.clone();
        other.carry();
        self.carry();
        for (a, b) in self.limbs.iter_mut().zip(other.limbs) {
            *a += b;
        }
        self.carry();
    }

    /// Propagates carries so every limb but the last lies in [0, 2³²).
    fn carry(&mut self) {
        for i in 0..LIMBS - 1 {
            let carry = self.limbs[i] >> LIMB_BITS;
            self.limbs[i] -= carry << LIMB_BITS;
            self.limbs[i + 1] += carry;
        }
        self.pending = 0;
    }

    /// The exact value as `integer · 2⁻¹⁰⁷⁴`.
    fn integer(&self) -> BigInt {
        let mut s = self.clone();
        s.carry();
        s.limbs.iter().rev().fold(BigInt::from(0), |acc, &limb| (acc << LIMB_BITS) + limb)
    }

    /// The sum, correctly rounded (to nearest, ties to even).
    pub fn round(&self) -> f64 {
        self.round_divided_by(1)
    }

    /// The sum divided by `divisor`, correctly rounded once (to nearest, ties to even).
    pub fn round_divided_by(&self, divisor: u32) -> f64 {
        let n = self.integer();
        let (sign, magnitude) = n.into_parts();
        if magnitude.bits() == 0 {
            return 0.0;
        }
        // q = ⌊magnitude·2^extra / divisor⌋ has at least 60 significant bits; what the
        // division leaves over only decides ties (as a sticky bit).
        let extra = 64u64;
        let scaled = magnitude << extra;
        let q = &scaled / divisor;
        let sticky = (&scaled % divisor).bits() != 0;
        let bits = q.bits();
        // Keep 53 bits, or fewer where the result is subnormal (its last bit is 2^−1074,
        // i.e. `extra` bits up from the bottom of q).
        let drop = bits.saturating_sub(53).max(extra);
        let kept = &q >> drop;
        let rest = &q - (&kept << drop);
        let half = num_bigint::BigUint::from(1u8) << (drop - 1);
        let mut m = u64::try_from(kept).unwrap_or(u64::MAX);
        if rest > half || (rest == half && (sticky || m % 2 == 1)) {
            m += 1;
        }
        let exponent = drop as i64 - extra as i64 - 1074;
        let value = scale_by_power_of_two(m as f64, exponent);
        if sign == Sign::Minus {
            -value
        } else {
            value
        }
    }
}

/// `x · 2^e` for `x` below 2⁵⁴ and `e ≥ −1074`: exact whenever the result is
/// representable, because the first factor keeps the intermediate normal.
fn scale_by_power_of_two(x: f64, e: i64) -> f64 {
    let pow2 = |k: i64| f64::from_bits(((k.clamp(-1022, 1023) + 1023) as u64) << 52);
    if e < -1000 {
        x * pow2(-1000) * pow2(e + 1000)
    } else if e > 1000 {
        x * pow2(1000) * pow2(e - 1000)
    } else {
        x * pow2(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact reference: the sum of doubles as a rational with a power-of-two denominator.
    fn reference(xs: &[f64], divisor: u32) -> f64 {
        let mut s = ExactSum::default();
        xs.iter().for_each(|&x| s.add(x));
        s.round_divided_by(divisor)
    }

    #[test]
    fn exact_sum_matches_integer_arithmetic() {
        // Integers small enough that f64 holds every partial sum exactly: the plain sum
        // is the reference.
        let xs: Vec<f64> = (0..1000).map(|i| ((i * 7919) % 2003) as f64 - 1000.0).collect();
        assert_eq!(reference(&xs, 1), xs.iter().sum::<f64>());
        // Division rounds once: 1/3 and 2/6 are the f64 nearest to a third.
        assert_eq!(reference(&[1.0], 3), 1.0 / 3.0);
        assert_eq!(reference(&[1.0, 1.0], 6), 1.0 / 3.0);
        assert_eq!(reference(&[-5.0], 6), -5.0 / 6.0);
    }

    #[test]
    fn exact_sum_catches_what_float_sums_lose() {
        // What survives the cancellation is a two-term sum, which IEEE addition rounds
        // correctly: the reference.
        let tiny = f64::MIN_POSITIVE / 4.0;
        let xs = [1e308, 1e308, -1e308, -1e308, 1e-300, tiny];
        assert_eq!(reference(&xs, 1), 1e-300 + tiny);
        assert_eq!(reference(&[1e-300, f64::from_bits(1)], 1), 1e-300);
        let xs = [2f64.powi(60), 1.0, -(2f64.powi(60))];
        assert_eq!(reference(&xs, 1), 1.0);
        // Smallest subnormal survives.
        assert_eq!(reference(&[f64::from_bits(1)], 1), f64::from_bits(1));
        // Ties round to even: (2^53 + 1) is halfway between 2^53 and 2^53 + 2.
        assert_eq!(reference(&[2f64.powi(53), 1.0], 1), 2f64.powi(53));
        assert_eq!(reference(&[2f64.powi(53), 1.0, 2f64.powi(-60)], 1), 2f64.powi(53) + 2.0);
    }

    #[test]
    fn merge_is_exact_and_order_free() {
        let xs: Vec<f64> = (1..500).map(|i| (i as f64).sqrt() * 1e10 - 1e11 / i as f64).collect();
        let mut whole = ExactSum::default();
        xs.iter().for_each(|&x| whole.add(x));
        let mut left = ExactSum::default();
        let mut right = ExactSum::default();
        xs[..200].iter().for_each(|&x| left.add(x));
        xs[200..].iter().rev().for_each(|&x| right.add(x));
        right.merge(&left);
        assert_eq!(right.round(), whole.round());
    }

    #[test]
    fn compensated_sum_is_close_to_exact() {
        let xs: Vec<f64> =
            (1..10_000).map(|i| 1.0 / i as f64 * if i % 2 == 0 { -1e8 } else { 1e8 }).collect();
        let mut s = CompensatedSum::default();
        xs.iter().for_each(|&x| s.add(x));
        let exact = reference(&xs, 1);
        let abs: f64 = xs.iter().map(|x| x.abs()).sum();
        let bound = UNIT_ROUNDOFF * exact.abs() + gamma(xs.len() as f64).powi(2) * abs;
        assert!((s.value() - exact).abs() <= bound);
    }

    #[test]
    fn ordered_reduce_is_thread_count_independent() {
        let xs: Vec<f64> = (0..100_000).map(|i| ((i as f64) * 0.618).sin() * 1e6).collect();
        let run = |threads| {
            rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(|| {
                ordered_reduce(xs.len(), 1000, |r| xs[r].iter().sum::<f64>(), |a, b| *a += b)
            })
        };
        assert_eq!(run(1).unwrap().to_bits(), run(3).unwrap().to_bits());
        assert_eq!(ordered_reduce(0, 10, |_| 1.0, |a: &mut f64, b| *a += b), None);
    }
}
