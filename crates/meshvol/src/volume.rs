//! The signed volume alone, with its rounding bound, in one pass: the
//! `signed_volume` and `volume_error_bound` of [`crate::mass_properties`], the same bits,
//! without the moments, the area and the bounding box.
//!
//! # What is summed
//! The volume's sums of [`crate::properties`] (whose module docs give the math), in the
//! same order: about the reference point r (the first corner of the first face), for
//! each fan triangle (a, b, c), D = (a − r)·((b − r)×(c − r)) summed compensated
//! (TwoSum), Σ|D| and Σ P with P = Σ|aᵢ − rᵢ||bⱼ − rⱼ||cₖ − rₖ| over the determinant's
//! six terms; and, for the move from r to the origin, each face's vector area
//! S_f = Σ (b − a)×(c − a) over its fan, summed compensated over faces, with the
//! magnitudes of its cross products' two products. The faces are cut into the same
//! fixed chunks as [`crate::mass_properties`]; within a chunk, triangle k (and face k)
//! goes to the (k mod 4)-th of four interleaved sums, merged in order at the chunk's
//! end ([`LaneSums`]), and the chunks are combined left to right: the same bits at any
//! thread count, and the same bits as `mass_properties(surface).signed_volume` and
//! `.volume_error_bound`.
//!
//! # The bound (rigorous)
//! With u = 2⁻⁵³ and γ(n) = n·u/(1 − n·u), `volume_error_bound` bounds |computed − V|,
//! V the exact signed volume (about the world origin) of the polyhedron the f64
//! coordinates describe:
//! - each D̂ is within γ(8)·P of D (3 subtractions of r, then the cross and dot
//!   products: at most 8 roundings along any of the six terms);
//! - the compensated sum of n terms adds u·|ΣD̂| + γ(n)²·Σ|D̂| (Ogita, Rump, Oishi
//!   2005); the division by 6 adds u·|V|; the bound's own sums are evaluated with a
//!   factor (1 + γ(n + 8)) of headroom;
//! - the move to the origin, V_O = V_r + r·S/6, adds per component
//!   |r_k|·(2u·Σ(m + 4)·M + u·|S_k| + 2γ(F)²·ΣM + γ(4)·|S_k|), M the magnitudes of a
//!   face's cross products' products and m its fan's length; when r·S/6 is within that bound of 0 (a closed
//!   surface, where S = 0), it is not added and the bound covers it;
//! - when that move would make the bound looser than both the bound about r and 2⁻⁴²
//!   of the volume (a surface far from the origin compared with its size), the exact
//!   sum ([`crate::exact_signed_volume`]) is taken instead and the bound is u·|V|.
//!
//! # Speed
//! An indexed triangle mesh (a [`crate::Mesh`] of triangles, or borrowed arrays through
//! [`triangles_signed_volume`]) is read four triangles at a time: the differences,
//! cross and dot products and magnitudes in SIMD lanes (`wide::f64x4`, one triangle a
//! lane, the same IEEE operations as the scalar code, so the same bits), and the sums
//! too: the interleaved order makes lane j of every running sum the j-th of the four
//! sums, so no value crosses lanes until the chunk's end. (Summing the four lanes one
//! after another, in face order, as before, made a chain of dependent additions per
//! triangle: cachegrind counted 169 instructions a triangle for the volume then, 158
//! now; 430 against 309 for the mass properties, a needless rescan of the bounds' zeros
//! gone too.) The lanes are `wide::f64x4`, which this crate's baseline target (x86-64
//! without AVX) builds as two 128-bit halves; on a CPU with AVX2 the arrays' pass runs a
//! copy compiled for it, its lanes one 256-bit register ([`Avx`]), the same operations
//! (no fused multiply-add), so the same bits: 84 instructions a triangle instead of
//! 158, 0.49 ms for 100k triangles on one thread instead of 1.08 ms (AMD EPYC, Zen 4).
//! [`crate::mass_properties`] of an indexed triangle mesh does the same ([`Lanes`] has
//! the minima, maxima and square roots it takes too): 135 instructions a triangle
//! instead of 309, 0.96 ms instead of 1.76 for those 100k triangles, 1.6–2× the volume.
//! From [`PARALLEL_TRIANGLES`] (two chunks) the chunks run on the caller's rayon pool;
//! below, on the caller's thread.

use crate::accumulate::{ordered_reduce_on, CompensatedSum, UNIT_ROUNDOFF};
use crate::mesh::MeshError;
use crate::properties::{VolumeSums, CHUNK_FACES};
use crate::vector::sub;
use crate::{Point, Surface};
use std::ops::{Add, AddAssign, Mul, Sub};
use wide::f64x4;

/// Below this many faces (two chunks) the volume (and [`crate::mass_properties`]) is
/// summed on the caller's thread alone; the chunks, and so the bits, are the same
/// either way. Once the lanes made a triangle cheap, the pool paid from the second
/// chunk on: the volume of a 100k-triangle sphere's arrays (i32 faces) on 2 cores took
/// 0.49 ms on one thread and 0.26 ms on the pool called back to back, 0.29–0.35 ms with
/// the pool asleep (2 ms between calls); this was 200,000 then.
pub const PARALLEL_TRIANGLES: usize = 2 * CHUNK_FACES;

/// The signed volume of the solid a surface bounds, and a bound on its rounding error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Volume {
    /// Σ of signed tetrahedron volumes from the world origin to the fan triangles, as
    /// the surface is wound (positive for outward normals): exactly
    /// [`crate::MassProperties::signed_volume`].
    pub signed_volume: f64,
    /// A bound on |`signed_volume` − the exact signed volume of the polyhedron the f64
    /// coordinates describe|: exactly [`crate::MassProperties::volume_error_bound`].
    pub volume_error_bound: f64,
    /// Faces read.
    pub faces: usize,
    /// Triangles in the faces' fans.
    pub triangles: usize,
}

impl Volume {
    /// |signed volume|.
    pub fn volume(&self) -> f64 {
        self.signed_volume.abs()
    }
}

/// An integer type a face array may index vertices with.
pub trait VertexIndex: Copy + Sync {
    /// The index as a `usize`; `usize::MAX` (never in range) when negative.
    fn to_index(self) -> usize;
    /// The value, for an error message.
    fn value(self) -> i128;
}

macro_rules! vertex_index {
    ($($t:ty),*) => {$(
        impl VertexIndex for $t {
            #[inline(always)]
            fn to_index(self) -> usize {
                usize::try_from(self).unwrap_or(usize::MAX)
            }
            fn value(self) -> i128 {
                self as i128
            }
        }
    )*};
}
vertex_index!(u32, i32, i64, u64, usize);

/// The signed volume of `surface` and its rounding bound: the same bits as
/// [`crate::mass_properties`]'s, at a fraction of its cost.
///
/// ```
/// use meshvol::{mass_properties, shapes::cuboid, volume::signed_volume};
/// let cube = cuboid([0.0; 3], [1.0, 2.0, 3.0]);
/// let v = signed_volume(&cube);
/// assert_eq!((v.signed_volume, v.volume_error_bound), (6.0, mass_properties(&cube).volume_error_bound));
/// ```
pub fn signed_volume<S: Surface + ?Sized>(surface: &S) -> Volume {
    if let Some((positions, triangles)) = surface.indexed_triangles() {
        // A validated mesh: every index is in range and every coordinate finite.
        if let Ok(v) = triangles_signed_volume(positions, triangles) {
            return v;
        }
    }
    let faces = surface.face_count();
    let Some(r) = crate::mesh::first_corner(surface) else {
        return Volume { signed_volume: 0.0, volume_error_bound: 0.0, faces, triangles: 0 };
    };
    let sums = ordered_reduce_on(
        faces >= PARALLEL_TRIANGLES,
        faces,
        CHUNK_FACES,
        |range| {
            // The chunk's k-th triangle and k-th face to sum k mod 4 (see `LaneSums`).
            let mut lanes = LaneSums::default();
            let mut triangle = 0usize;
            for (k, face) in range.enumerate() {
                let mut vector_area = [0.0; 3];
                let mut magnitude = [0.0; 3];
                let mut fan = 0usize;
                surface.fan(face, |a, b, c| {
                    let (plus, minus) = cross_products(a, b, c);
                    for k in 0..3 {
                        vector_area[k] += plus[k] - minus[k];
                        magnitude[k] += plus[k].abs() + minus[k].abs();
                    }
                    fan += 1;
                    lanes.0[triangle % 4].add_determinant(sub(a, r), sub(b, r), sub(c, r));
                    triangle += 1;
                });
                lanes.0[k % 4].add_vector_area(vector_area, magnitude, fan);
            }
            lanes.merged()
        },
        |total, part| total.merge(&part),
    )
    .unwrap_or_default();
    finish(surface, faces, r, &sums)
}

/// The signed volume of the solid bounded by `triangles`, which index `positions`, and
/// its rounding bound, read in place (no copy of either array): the same bits as
/// [`crate::mass_properties`] of the [`crate::Mesh`] of these arrays.
///
/// Errors name the first face (in order) with an index out of range or negative, or,
/// when the sum is not finite, the first vertex a face uses with a non-finite
/// coordinate. Vertices no face uses are not read.
///
/// ```
/// use meshvol::volume::triangles_signed_volume;
/// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let t: [[i64; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
/// let v = triangles_signed_volume(&p, &t).unwrap();
/// assert_eq!(v.signed_volume, 1.0 / 6.0);
/// assert!(v.volume_error_bound < 1e-15);
/// assert!(triangles_signed_volume(&p, &[[0i64, 1, 4]]).is_err());
/// ```
pub fn triangles_signed_volume<I: VertexIndex>(
    positions: &[Point],
    triangles: &[[I; 3]],
) -> Result<Volume, MeshError> {
    let faces = triangles.len();
    let Some(first) = triangles.first() else {
        return Ok(Volume { signed_volume: 0.0, volume_error_bound: 0.0, faces, triangles: 0 });
    };
    let r = *positions.get(first[0].to_index()).ok_or_else(|| index_error(positions, 0, first))?;
    let sums = ordered_reduce_on(
        faces >= PARALLEL_TRIANGLES,
        faces,
        CHUNK_FACES,
        |range| {
            let start = range.start;
            chunk_sums(positions, &triangles[range], start, r)
        },
        |total, part| match (&mut *total, part) {
            (Ok(t), Ok(p)) => t.merge(&p),
            (Ok(_), Err(e)) => *total = Err(e),
            (Err(_), _) => {}
        },
    )
    .unwrap_or_else(|| Ok(VolumeSums::default()))?;
    let finite = [
        sums.six_volume.value(),
        sums.abs_six_volume,
        sums.determinant_magnitude,
        sums.vector_area_magnitude.iter().sum(),
    ];
    if !finite.iter().all(|x| x.is_finite()) {
        if let Some(e) = non_finite_vertex(positions, triangles) {
            return Err(e);
        }
    }
    let view = Borrowed { positions, triangles };
    Ok(finish(&view, faces, r, &sums))
}

/// The volume from the sums; the exact sum where the bound would be loose.
fn finish<S: Surface + ?Sized>(surface: &S, faces: usize, r: Point, sums: &VolumeSums) -> Volume {
    let done = sums.finish(faces, r);
    let (mut signed_volume, mut volume_error_bound) = (done.signed_volume, done.volume_error_bound);
    if done.loose {
        // As in mass_properties: far from the origin, the exact sum, correctly rounded.
        if let Ok(exact) = crate::exact::exact_signed_volume(surface) {
            signed_volume = exact;
            volume_error_bound = UNIT_ROUNDOFF * exact.abs();
        }
    }
    Volume { signed_volume, volume_error_bound, faces, triangles: sums.triangles }
}

/// The two products of each component of (b − a)×(c − a): the cross product is
/// `plus − minus`.
#[inline(always)]
fn cross_products(a: Point, b: Point, c: Point) -> (Point, Point) {
    let (u, v) = (sub(b, a), sub(c, a));
    ([u[1] * v[2], u[2] * v[0], u[0] * v[1]], [u[2] * v[1], u[0] * v[2], u[1] * v[0]])
}

fn index_error<I: VertexIndex>(positions: &[Point], face: usize, triangle: &[I; 3]) -> MeshError {
    let bad = triangle.iter().find(|i| i.to_index() >= positions.len()).unwrap_or(&triangle[0]);
    match u64::try_from(bad.value()) {
        Ok(index) => MeshError::IndexOutOfRange { face, index, vertices: positions.len() },
        Err(_) => MeshError::NegativeIndex { face, index: bad.value() as i64 },
    }
}

/// The first vertex, in face order, with a non-finite coordinate.
fn non_finite_vertex<I: VertexIndex>(
    positions: &[Point],
    triangles: &[[I; 3]],
) -> Option<MeshError> {
    triangles.iter().flatten().find_map(|i| {
        let vertex = i.to_index();
        let p = positions[vertex];
        p.iter().find(|x| !x.is_finite()).map(|&value| MeshError::NonFiniteVertex { vertex, value })
    })
}

/// Validated arrays as a surface (for the exact sum).
struct Borrowed<'a, I> {
    positions: &'a [Point],
    triangles: &'a [[I; 3]],
}

impl<I: VertexIndex> Surface for Borrowed<'_, I> {
    fn face_count(&self) -> usize {
        self.triangles.len()
    }

    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        let [a, b, c] = self.triangles[face].map(|i| self.positions[i.to_index()]);
        triangle(a, b, c);
    }
}

/// The volume's sums of triangles taken four at a time in SIMD lanes, lane `j` holding
/// the sums of a chunk's triangles `j`, `j + 4`, `j + 8`, ...: the same IEEE operations
/// as [`VolumeSums::add_determinant`] and [`VolumeSums::add_vector_area`] applied to
/// [`LaneSums`]' sum `j`, so the bits of the scalar loop over the same triangles.
pub(crate) struct VolumeLanes<L: Lanes = f64x4> {
    r: [L; 3],
    /// Compensated, one triangle a lane: D, S_x, S_y, S_z.
    sum: [L; 4],
    compensation: [L; 4],
    /// Plain: Σ|D|, ΣP, ΣM_x, ΣM_y, ΣM_z, Σ5M_x, Σ5M_y, Σ5M_z (a triangle is a face of
    /// one triangle: its weight is 1 + 4).
    plain: [L; 8],
    triangles: usize,
}

/// Four f64 lanes and the IEEE operations the sums take of them, lane by lane (never a
/// fused multiply-add): `wide::f64x4`, and [`F4`], plain arrays that the compiler
/// vectorises to the width the calling function's target features allow.
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
    fn sqrt(self) -> Self;
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
    fn sqrt(self) -> Self {
        f64x4::sqrt(self)
    }
}

/// Four lanes in one 256-bit AVX register, for functions compiled with AVX enabled
/// (`wide::f64x4` is chosen when this crate is compiled, for the baseline target: two
/// 128-bit halves). Its operations are the AVX instructions of `wide`'s own AVX build.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
pub(crate) struct Avx(std::arch::x86_64::__m256d);

#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{Avx, Lanes};
    use std::arch::x86_64::*;
    use std::ops::{Add, AddAssign, Mul, Sub};

    // SAFETY (every `unsafe` here): `Avx` values are only made in functions compiled
    // with AVX enabled, on a CPU that has it (`chunk_sums`).
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
        fn abs(self) -> Self {
            // Clears the sign bits, as f64::abs.
            Avx(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
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

/// Four triangles' corners: `[corner][axis]`, one triangle a lane.
pub(crate) type Corners<L = f64x4> = [[L; 3]; 3];

/// Corners gathered as `[corner][axis][lane]`, as lanes.
///
/// Written out, like every step of the lanes' arithmetic: a closure handed to
/// `array::map` can be compiled out of line, and then an AVX operation in it is a call
/// (the function compiled for AVX2 took 185 instructions a triangle instead of 84 in the
/// Python package, whose build did not inline those closures).
#[inline(always)]
pub(crate) fn corners<L: Lanes>(p: &[[[f64; 4]; 3]; 3]) -> Corners<L> {
    let corner =
        |[x, y, z]: &[[f64; 4]; 3]| [L::from_array(*x), L::from_array(*y), L::from_array(*z)];
    [corner(&p[0]), corner(&p[1]), corner(&p[2])]
}

/// TwoSum lane by lane (`accumulate::two_sum`), into a running sum and compensation.
#[inline(always)]
pub(crate) fn add_compensated<L: Lanes>(sum: &mut L, compensation: &mut L, x: L) {
    let s = *sum + x;
    let z = s - *sum;
    *compensation += (*sum - (s - z)) + (x - z);
    *sum = s;
}

impl<L: Lanes> VolumeLanes<L> {
    #[inline(always)]
    pub(crate) fn new(r: Point) -> Self {
        let zero = L::ZERO;
        VolumeLanes {
            r: [L::splat(r[0]), L::splat(r[1]), L::splat(r[2])],
            sum: [zero; 4],
            compensation: [zero; 4],
            plain: [zero; 8],
            triangles: 0,
        }
    }

    /// Adds four triangles; returns, for callers that sum more of them, their vector
    /// areas (b − a)×(c − a), their determinants D and their corners about r.
    #[inline(always)]
    pub(crate) fn add(
        &mut self,
        [[ax, ay, az], [bx, by, bz], [cx, cy, cz]]: Corners<L>,
    ) -> ([L; 3], L, Corners<L>) {
        let zero = L::ZERO;
        let [rx, ry, rz] = self.r;
        // (b − a)×(c − a) as plus − minus, as `cross_products`.
        let (ux, uy, uz) = (bx - ax, by - ay, bz - az);
        let (vx, vy, vz) = (cx - ax, cy - ay, cz - az);
        let plus = [uy * vz, uz * vx, ux * vy];
        let minus = [uz * vy, ux * vz, uy * vx];
        // A face's fan sum starts at 0.0 (`0.0 + x` turns −0 into +0, as the scalar sum).
        let area =
            [zero + (plus[0] - minus[0]), zero + (plus[1] - minus[1]), zero + (plus[2] - minus[2])];
        let magnitude = [
            plus[0].abs() + minus[0].abs(),
            plus[1].abs() + minus[1].abs(),
            plus[2].abs() + minus[2].abs(),
        ];
        // D about r, as `VolumeSums::add_determinant`.
        let a = [ax - rx, ay - ry, az - rz];
        let b = [bx - rx, by - ry, bz - rz];
        let c = [cx - rx, cy - ry, cz - rz];
        let bc = [b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]];
        let d = a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2];
        let abs = |[x, y, z]: [L; 3]| [x.abs(), y.abs(), z.abs()];
        let (aa, ba, ca) = (abs(a), abs(b), abs(c));
        let permanent = aa[0] * (ba[1] * ca[2] + ba[2] * ca[1])
            + aa[1] * (ba[2] * ca[0] + ba[0] * ca[2])
            + aa[2] * (ba[0] * ca[1] + ba[1] * ca[0]);
        for (k, x) in [d, area[0], area[1], area[2]].into_iter().enumerate() {
            add_compensated(&mut self.sum[k], &mut self.compensation[k], x);
        }
        let five = L::splat(5.0);
        let plain = [
            d.abs(),
            permanent,
            magnitude[0],
            magnitude[1],
            magnitude[2],
            five * magnitude[0],
            five * magnitude[1],
            five * magnitude[2],
        ];
        for (sum, x) in self.plain.iter_mut().zip(plain) {
            *sum += x;
        }
        self.triangles += 4;
        (area, d, [a, b, c])
    }

    /// The sums so far, lane by lane.
    #[inline(always)]
    pub(crate) fn lanes(&self) -> LaneSums {
        let (s, c) = (self.sum.map(|x| x.to_array()), self.compensation.map(|x| x.to_array()));
        let p = self.plain.map(|x| x.to_array());
        LaneSums(std::array::from_fn(|j| VolumeSums {
            six_volume: CompensatedSum::from_parts(s[0][j], c[0][j]),
            vector_area: [1, 2, 3].map(|k| CompensatedSum::from_parts(s[k][j], c[k][j])),
            abs_six_volume: p[0][j],
            determinant_magnitude: p[1][j],
            vector_area_magnitude: [p[2][j], p[3][j], p[4][j]],
            vector_area_weighted: [p[5][j], p[6][j], p[7][j]],
            triangles: self.triangles / 4,
        }))
    }
}

/// A chunk's volume sums as four interleaved sums: the chunk's `k`-th triangle (and for
/// the per-face sums its `k`-th face) goes to sum `k mod 4`, and the four are merged in
/// order at the chunk's end. This is the summation order of every path, scalar or SIMD
/// ([`VolumeLanes`]), so all give the same bits; the error bound is that of a
/// compensated sum cut into parts merged in order, as the chunks already are.
#[derive(Clone, Copy, Default)]
pub(crate) struct LaneSums(pub(crate) [VolumeSums; 4]);

impl LaneSums {
    /// The four sums merged in order.
    pub(crate) fn merged(&self) -> VolumeSums {
        let mut total = self.0[0];
        for lane in &self.0[1..] {
            total.merge(lane);
        }
        total
    }
}

fn chunk_sums<I: VertexIndex>(
    positions: &[Point],
    triangles: &[[I; 3]],
    first: usize,
    r: Point,
) -> Result<VolumeSums, MeshError> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2.
        return unsafe { chunk_sums_avx2(positions, triangles, first, r) };
    }
    chunk_sums_any::<I, f64x4>(positions, triangles, first, r)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn chunk_sums_avx2<I: VertexIndex>(
    positions: &[Point],
    triangles: &[[I; 3]],
    first: usize,
    r: Point,
) -> Result<VolumeSums, MeshError> {
    chunk_sums_any::<I, Avx>(positions, triangles, first, r)
}

#[inline(always)]
fn chunk_sums_any<I: VertexIndex, L: Lanes>(
    positions: &[Point],
    triangles: &[[I; 3]],
    first: usize,
    r: Point,
) -> Result<VolumeSums, MeshError> {
    let mut lanes = VolumeLanes::<L>::new(r);
    let mut groups = triangles.chunks_exact(4);
    let mut face = first;
    for group in &mut groups {
        // corner, axis, lane
        let mut p = [[[0.0; 4]; 3]; 3];
        for (lane, t) in group.iter().enumerate() {
            for (corner, &i) in t.iter().enumerate() {
                let Some(q) = positions.get(i.to_index()) else {
                    return Err(index_error(positions, face + lane, t));
                };
                for k in 0..3 {
                    p[corner][k][lane] = q[k];
                }
            }
        }
        lanes.add(corners(&p));
        face += 4;
    }
    let mut sums = lanes.lanes();
    for (lane, t) in groups.remainder().iter().enumerate() {
        let mut corner = [r; 3];
        for (k, &i) in t.iter().enumerate() {
            corner[k] =
                *positions.get(i.to_index()).ok_or_else(|| index_error(positions, face, t))?;
        }
        let [a, b, c] = corner;
        let (plus, minus) = cross_products(a, b, c);
        let area = [0, 1, 2].map(|k| 0.0 + (plus[k] - minus[k]));
        let magnitude = [0, 1, 2].map(|k| plus[k].abs() + minus[k].abs());
        // The remainder starts at a multiple of 4 from the chunk's start.
        let sums = &mut sums.0[lane];
        sums.add_determinant(sub(a, r), sub(b, r), sub(c, r));
        sums.add_vector_area(area, magnitude, 1);
        face += 1;
    }
    Ok(sums.merged())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::XorShift;

    /// The baseline lanes (`wide`, what a CPU without AVX2 runs) give the bits of the
    /// lanes this CPU runs (AVX2 where it has it), remainders included.
    #[test]
    fn baseline_and_dispatched_lanes_agree() {
        let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
        let positions: Vec<Point> = (0..200)
            .map(|_| [0; 3].map(|_| (rng.unit() - 0.5) * 2f64.powi(rng.below(40) as i32 - 20)))
            .collect();
        for n in [1, 4, 7, 64, 1001] {
            let triangles: Vec<[u32; 3]> =
                (0..n).map(|_| [0; 3].map(|_| rng.below(200) as u32)).collect();
            let r = positions[triangles[0][0] as usize];
            let baseline = chunk_sums_any::<u32, f64x4>(&positions, &triangles, 0, r).unwrap();
            let dispatched = chunk_sums(&positions, &triangles, 0, r).unwrap();
            assert_eq!(format!("{baseline:?}"), format!("{dispatched:?}"), "{n} triangles");
        }
    }
}
