//! Four f64 lanes (`Lanes`) and the one dispatch that picks them for the CPU
//! ([`dispatch`]): the volume's and the mass properties' SIMD loops are written once,
//! generic over the lanes ([`OnLanes::run`]), and compiled in three copies: the
//! baseline target's (`wide::f64x4`, two 128-bit halves), and one AVX register ([`Avx`])
//! in a copy compiled for AVX2 and one for AVX-512 (F and VL: the same 256-bit
//! operations with its 32 registers). Every copy does the same IEEE operations lane by
//! lane (never a fused multiply-add), so all give the same bits; `every_copy` runs each
//! copy this CPU has, for the tests that compare them.
//!
//! The AVX copies are behind tokens: [`on_avx2`] and [`on_avx512`], the only functions
//! here compiled with `#[target_feature(enable = ...)]`, each take a zero-sized token
//! ([`token::Avx2`], [`token::Avx512`]) whose one field is private to the `token`
//! module, so that the only way to get one is that module's `detect`, which returns it
//! only after `is_x86_feature_detected!` said yes to every feature the function
//! enables. Holding a token is therefore the proof that the CPU has those features:
//! calling an AVX copy without detecting them first does not compile, and the one
//! `unsafe` call of each copy (in the token's `run`) rests on the token alone. Tokens
//! are `Copy` and zero-sized: passing one costs nothing.
//!
//! `Avx` is private to this module and named only by the copies compiled with AVX,
//! which only a token can call: its values are made (by the [`Lanes`] methods, whose
//! signatures the generic loops share with `wide::f64x4` and so take no token) and used
//! only inside those copies, where AVX is enabled, so its safe methods can only run
//! there.

use std::ops::{Add, AddAssign, Mul, Sub};
use wide::f64x4;

use crate::Point;

/// A computation over four lanes, written once for any lanes and compiled into each
/// copy [`dispatch`] picks from: `run` must be `#[inline(always)]` (and what it calls),
/// so that each copy's code is compiled with that copy's instructions.
pub(crate) trait OnLanes {
    type Output;
    fn run<L: Lanes>(self) -> Self::Output;
}

/// Runs `k` on the widest lanes this CPU has (module docs).
pub(crate) fn dispatch<K: OnLanes>(k: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    {
        if let Some(t) = token::Avx512::detect() {
            return t.run(k);
        }
        if let Some(t) = token::Avx2::detect() {
            return t.run(k);
        }
    }
    k.run::<f64x4>()
}

/// The proofs that the CPU has an AVX copy's features (module docs): zero-sized, `Copy`,
/// and made only by `detect`, after the CPU said it has every feature the copy enables.
#[cfg(target_arch = "x86_64")]
mod token {
    use super::OnLanes;

    /// Proof that the CPU has AVX2, all that [`super::on_avx2`] enables.
    #[derive(Clone, Copy)]
    pub(super) struct Avx2(());

    impl Avx2 {
        /// A token if the CPU has AVX2, the one feature [`super::on_avx2`] enables.
        #[inline]
        pub(super) fn detect() -> Option<Self> {
            std::arch::is_x86_feature_detected!("avx2").then_some(Avx2(()))
        }

        /// `k` run by the copy compiled for AVX2.
        #[inline]
        pub(super) fn run<K: OnLanes>(self, k: K) -> K::Output {
            // SAFETY: `self` exists, so `detect` found AVX2 on this CPU, every feature
            // `on_avx2` enables.
            unsafe { super::on_avx2(self, k) }
        }
    }

    /// Proof that the CPU has AVX2, AVX-512F and AVX-512VL, all that
    /// [`super::on_avx512`] enables.
    #[derive(Clone, Copy)]
    pub(super) struct Avx512(());

    impl Avx512 {
        /// A token if the CPU has AVX2, AVX-512F and AVX-512VL, every feature
        /// [`super::on_avx512`] enables.
        #[inline]
        pub(super) fn detect() -> Option<Self> {
            (std::arch::is_x86_feature_detected!("avx2")
                && std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx512vl"))
            .then_some(Avx512(()))
        }

        /// `k` run by the copy compiled for AVX-512F and VL.
        #[inline]
        pub(super) fn run<K: OnLanes>(self, k: K) -> K::Output {
            // SAFETY: `self` exists, so `detect` found AVX2, AVX-512F and AVX-512VL on
            // this CPU, every feature `on_avx512` enables.
            unsafe { super::on_avx512(self, k) }
        }
    }
}

/// The copy compiled for AVX-512F and VL; its token proves the CPU has them.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f,avx512vl")]
fn on_avx512<K: OnLanes>(_: token::Avx512, k: K) -> K::Output {
    k.run::<Avx>()
}

/// The copy compiled for AVX2; its token proves the CPU has it.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn on_avx2<K: OnLanes>(_: token::Avx2, k: K) -> K::Output {
    k.run::<Avx>()
}

/// `k` run by every copy this CPU has, the baseline first: for the tests that compare
/// their bits.
#[cfg(test)]
pub(crate) fn every_copy<K: OnLanes + Clone>(k: K) -> Vec<K::Output> {
    let mut outputs = vec![k.clone().run::<f64x4>()];
    #[cfg(target_arch = "x86_64")]
    {
        if let Some(t) = token::Avx2::detect() {
            outputs.push(t.run(k.clone()));
        }
        if let Some(t) = token::Avx512::detect() {
            outputs.push(t.run(k));
        }
    }
    outputs
}

/// Four f64 lanes and the IEEE operations the sums take of them, lane by lane (never a
/// fused multiply-add): `wide::f64x4` (the baseline target's), and [`Avx`], one 256-bit
/// register, for the copies compiled for AVX2 and AVX-512VL.
pub(crate) trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + AddAssign
{
    const ZERO: Self;
    fn splat(x: f64) -> Self;
    fn from_array(x: [f64; 4]) -> Self;
    fn to_array(self) -> [f64; 4];
    fn abs(self) -> Self;
    /// `wide::f64x4::min`: `rhs` where it is less than `self` and not NaN.
    fn min(self, rhs: Self) -> Self;
    /// `wide::f64x4::max`: `rhs` where it is greater than `self` and not NaN.
    fn max(self, rhs: Self) -> Self;
    /// [`Lanes::min`] for lanes that hold no NaN: without its NaN test.
    fn min_of_numbers(self, rhs: Self) -> Self;
    /// [`Lanes::max`] for lanes that hold no NaN: without its NaN test.
    fn max_of_numbers(self, rhs: Self) -> Self;
    fn sqrt(self) -> Self;
    /// Four points' coordinates as lanes, lane j holding point j's: [x, y, z].
    #[inline(always)]
    fn gather([p0, p1, p2, p3]: [&Point; 4]) -> [Self; 3] {
        [
            Self::from_array([p0[0], p1[0], p2[0], p3[0]]),
            Self::from_array([p0[1], p1[1], p2[1], p3[1]]),
            Self::from_array([p0[2], p1[2], p2[2], p3[2]]),
        ]
    }
}

impl Lanes for f64x4 {
    const ZERO: Self = f64x4::ZERO;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        f64x4::splat(x)
    }
    #[inline(always)]
    fn from_array(x: [f64; 4]) -> Self {
        f64x4::new(x)
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        f64x4::to_array(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64x4::abs(self)
    }
    #[inline(always)]
    fn min(self, rhs: Self) -> Self {
        f64x4::min(self, rhs)
    }
    #[inline(always)]
    fn max(self, rhs: Self) -> Self {
        f64x4::max(self, rhs)
    }
    #[inline(always)]
    fn min_of_numbers(self, rhs: Self) -> Self {
        f64x4::fast_min(self, rhs)
    }
    #[inline(always)]
    fn max_of_numbers(self, rhs: Self) -> Self {
        f64x4::fast_max(self, rhs)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64x4::sqrt(self)
    }
}

/// Four lanes in one 256-bit AVX register, for functions compiled with AVX enabled
/// (`wide::f64x4` is chosen when this crate is compiled, for the baseline target: two
/// 128-bit halves). Its operations are the AVX instructions of `wide`'s own AVX build.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
struct Avx(std::arch::x86_64::__m256d);

#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{Avx, Lanes};
    use std::arch::x86_64::*;
    use std::ops::{Add, AddAssign, Mul, Sub};

    // SAFETY (every `unsafe` here): `Avx` is named only by `on_avx2` and `on_avx512`,
    // compiled with AVX enabled and callable only with a token that proves the CPU has
    // it (module docs), so its values are made and used only there.
    macro_rules! op {
        ($trait:ident, $f:ident, $intrinsic:ident) => {
            impl $trait for Avx {
                type Output = Avx;
                #[inline(always)]
                fn $f(self, o: Avx) -> Avx {
                    Avx(unsafe { $intrinsic(self.0, o.0) })
                }
            }
        };
    }
    op!(Add, add, _mm256_add_pd);
    op!(Sub, sub, _mm256_sub_pd);
    op!(Mul, mul, _mm256_mul_pd);

    impl AddAssign for Avx {
        #[inline(always)]
        fn add_assign(&mut self, o: Avx) {
            *self = *self + o;
        }
    }

    impl Lanes for Avx {
        const ZERO: Self = Avx(unsafe { std::mem::transmute::<[f64; 4], __m256d>([0.0; 4]) });
        #[inline(always)]
        fn splat(x: f64) -> Self {
            Avx(unsafe { _mm256_set1_pd(x) })
        }
        #[inline(always)]
        fn from_array(x: [f64; 4]) -> Self {
            Avx(unsafe { _mm256_setr_pd(x[0], x[1], x[2], x[3]) })
        }
        #[inline(always)]
        fn to_array(self) -> [f64; 4] {
            unsafe { std::mem::transmute::<__m256d, [f64; 4]>(self.0) }
        }
        #[inline(always)]
        fn gather([p0, p1, p2, p3]: [&[f64; 3]; 4]) -> [Self; 3] {
            // (x, y) pairs in two 128-bit loads a pair of points, unpacked across them;
            // z two at a time: 11 instructions a corner instead of 15 through `from_array`.
            // (No closures: see `corners`.)
            unsafe {
                let xy02 = _mm256_insertf128_pd::<1>(
                    _mm256_castpd128_pd256(_mm_loadu_pd(p0.as_ptr())),
                    _mm_loadu_pd(p2.as_ptr()),
                );
                let xy13 = _mm256_insertf128_pd::<1>(
                    _mm256_castpd128_pd256(_mm_loadu_pd(p1.as_ptr())),
                    _mm_loadu_pd(p3.as_ptr()),
                );
                let z01 = _mm_loadh_pd(_mm_load_sd(&p0[2]), &p1[2]);
                let z23 = _mm_loadh_pd(_mm_load_sd(&p2[2]), &p3[2]);
                [
                    Avx(_mm256_unpacklo_pd(xy02, xy13)),
                    Avx(_mm256_unpackhi_pd(xy02, xy13)),
                    Avx(_mm256_insertf128_pd::<1>(_mm256_castpd128_pd256(z01), z23)),
                ]
            }
        }
        #[inline(always)]
        fn abs(self) -> Self {
            // Clears the sign bits, as f64::abs.
            Avx(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
        }
        #[inline(always)]
        fn min_of_numbers(self, rhs: Self) -> Self {
            Avx(unsafe { _mm256_min_pd(self.0, rhs.0) })
        }
        #[inline(always)]
        fn max_of_numbers(self, rhs: Self) -> Self {
            Avx(unsafe { _mm256_max_pd(self.0, rhs.0) })
        }
        #[inline(always)]
        fn min(self, rhs: Self) -> Self {
            // As `wide`: vminpd gives its second operand unless the first is less
            // (so on NaN and on equal zeros); a NaN `rhs` keeps `self`.
            unsafe {
                let nan = _mm256_cmp_pd::<_CMP_UNORD_Q>(rhs.0, rhs.0);
                Avx(_mm256_blendv_pd(_mm256_min_pd(self.0, rhs.0), self.0, nan))
            }
        }
        #[inline(always)]
        fn max(self, rhs: Self) -> Self {
            unsafe {
                let nan = _mm256_cmp_pd::<_CMP_UNORD_Q>(rhs.0, rhs.0);
                Avx(_mm256_blendv_pd(_mm256_max_pd(self.0, rhs.0), self.0, nan))
            }
        }
        #[inline(always)]
        fn sqrt(self) -> Self {
            Avx(unsafe { _mm256_sqrt_pd(self.0) })
        }
    }
}
