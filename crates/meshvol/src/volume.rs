//! The signed volume alone, with its rounding bound, in one pass: the
//! `signed_volume` and `volume_error_bound` of [`crate::mass_properties`], the same bits,
//! without the moments, the area and the bounding box.
//!
//! # What is summed
//! The volume's sums of [`crate::properties`] (whose module docs give the math), in the
//! same order: about the reference point r (the first corner of the first face), for
//! each fan triangle (a, b, c), its cross product w = (b − a)×(c − a) and
//! D = (a − r)·w (= (a − r)·((b − r)×(c − r))) summed compensated (TwoSum), Σ|D| and
//! Σ P with P = Σ|aᵢ − rᵢ|·Mᵢ, M the magnitudes of w's two products a component; and,
//! for the move from r to the origin, each face's vector area S_f = Σ w over its fan,
//! summed compensated over faces, with Σ M. The faces are cut into the same
//! fixed chunks as [`crate::mass_properties`]; within a chunk, triangle k (and face k)
//! goes to the (k mod 4)-th of four interleaved sums, merged in order at the chunk's
//! end (`volume_sums::LaneSums`), and the chunks are combined left to right: the same bits at any
//! thread count, and the same bits as `mass_properties(surface).signed_volume` and
//! `.volume_error_bound`.
//!
//! # The bound (rigorous)
//! With u = 2⁻⁵³ and γ(n) = n·u/(1 − n·u), `volume_error_bound` bounds |computed − V|,
//! V the exact signed volume (about the world origin) of the polyhedron the f64
//! coordinates describe:
//! - each D̂ is within γ(8)·P of D (a − r, b − a and c − a, the cross product's
//!   products and difference, the dot product's products and two additions: at most 8
//!   roundings along any of the six terms). P is |a − r| times edge lengths squared,
//!   where the former D = (a − r)·((b − r)×(c − r)) had |a − r||b − r||c − r|: on a
//!   1M-triangle sphere the bound is 1.0·10⁻¹⁴ instead of 1.4·10⁻¹⁰;
//! - the compensated sum of n terms adds u·|ΣD̂| + γ(n)²·Σ|D̂| (Ogita, Rump, Oishi
//!   2005); the division by 6 adds u·|V|; the bound's own sums are evaluated with a
//!   factor (1 + γ(n + 8)) of headroom;
//! - the move to the origin, V_O = V_r + r·S/6, adds per component
//!   |r_k|·(2u·Σ(m + 4)·M + u·|S_k| + 2γ(F)²·ΣM + γ(4)·|S_k|), M the magnitudes of a
//!   face's cross products' products and m its fan's length; when r·S/6 is within that bound of 0 (a closed
//!   surface, where S = 0), it is not added and the bound covers it;
//! - a surface whose vector area is known to be exactly zero
//!   ([`Surface::vector_area_is_zero`], a checked closed solid) takes no move: its bound
//!   is the bound about r;
//! - when that move would make the bound looser than both the bound about r and 2⁻⁴²
//!   of the volume (a surface far from the origin compared with its size), the exact
//!   sum ([`crate::exact_signed_volume`]) is taken instead and the bound is u·|V|.
//!
//! # Speed
//! An indexed triangle mesh (a [`crate::Mesh`] of triangles, or borrowed arrays through
//! [`triangles_signed_volume`]) is read four triangles at a time: the differences,
//! cross and dot products and magnitudes in SIMD lanes (one triangle a lane, the same
//! IEEE operations as the scalar code, so the same bits), and the sums too: the
//! interleaved order makes lane j of every running sum the j-th of the four sums, so no
//! value crosses lanes until the chunk's end. The lanes are `wide::f64x4`, which this
//! crate's baseline target (x86-64 without AVX) builds as two 128-bit halves; on a CPU
//! with AVX2 the pass runs a copy compiled for it, its lanes one 256-bit register
//! (`lanes::Avx`), and on one with AVX-512VL a third copy, the same 256-bit operations with
//! 32 registers instead of 16, which holds every running sum in a register (the AVX2
//! copy spills and reloads a quarter of its instructions' operands). None uses fused
//! multiply-adds, so all give the same bits; the tests compare them. The corners'
//! indices are checked in one vectorised pass over a chunk before the positions are
//! read. One triangle costs one cross product, shared by D and the vector area (see
//! [`crate::properties`]). [`crate::mass_properties`] of an indexed triangle mesh takes
//! the same lanes, adding the moments, the area and the bounds.
//!
//! On one thread of an AMD EPYC (Zen 4), a 100k-triangle sphere's arrays: the volume
//! 0.52 ms → 0.31 ms and the mass properties 1.07 → 0.59 ms with the
//! changes above (in-cache, a plain unbounded Σ a·(b×c) loop takes 0.23 ms).
//! Where a chunk's triangles name vertices scattered through memory (`scattered`), the
//! loops ask for the positions `PREFETCH_TRIANGLES` triangles ahead: a 1M-triangle
//! sphere's volume with its vertices in random order, two threads, 6.8 → 2.9 ms (the
//! mass properties 12 → 5 ms).
//! From [`PARALLEL_TRIANGLES`] (two chunks) the chunks run on the caller's rayon pool;
//! below, on the caller's thread.

use crate::accumulate::CHUNK_FACES;
use crate::accumulate::{ordered_reduce_on, CompensatedSum, UNIT_ROUNDOFF};
use crate::lanes::{dispatch, Lanes, OnLanes};
use crate::mesh::MeshError;
use crate::volume_sums::{add_face_fan, LaneSums, VolumeSums};
use crate::{Point, Surface};
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
    /// The index as a `usize`, for one known to be in range (`to_index` below the
    /// positions' count): a plain conversion, no sign check.
    fn in_range_index(self) -> usize;
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
            #[inline(always)]
            fn in_range_index(self) -> usize {
                self as usize
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
        if let Ok(v) = triangles_volume(positions, triangles, surface.vector_area_is_zero()) {
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
                let (vector_area, magnitude, fan) = add_face_fan(surface, face, |a, b, c| {
                    let sums = &mut lanes.0[triangle % 4];
                    triangle += 1;
                    let (cross, magnitude, _) = sums.add_fan_triangle(r, a, b, c);
                    (cross, magnitude)
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
    triangles_volume(positions, triangles, false)
}

/// [`triangles_signed_volume`], knowing whether the triangles' vector area is exactly
/// zero ([`Surface::vector_area_is_zero`]).
fn triangles_volume<I: VertexIndex>(
    positions: &[Point],
    triangles: &[[I; 3]],
    zero_vector_area: bool,
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
    let view = Borrowed { positions, triangles, zero_vector_area };
    Ok(finish(&view, faces, r, &sums))
}

/// The volume from the sums; the exact sum where the bound would be loose.
fn finish<S: Surface + ?Sized>(surface: &S, faces: usize, r: Point, sums: &VolumeSums) -> Volume {
    let done = sums.finish(faces, r, surface.vector_area_is_zero());
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
    zero_vector_area: bool,
}

impl<I: VertexIndex> Surface for Borrowed<'_, I> {
    fn face_count(&self) -> usize {
        self.triangles.len()
    }

    fn vector_area_is_zero(&self) -> bool {
        self.zero_vector_area
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
    /// Plain: Σ|D|, ΣP, ΣM_x, ΣM_y, ΣM_z (a triangle is a face of one fan triangle: no
    /// fan excess).
    plain: [L; 5],
    triangles: usize,
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
            plain: [zero; 5],
            triangles: 0,
        }
    }

    /// Adds four triangles; returns, for callers that sum more of them, their vector
    /// areas (b − a)×(c − a), their determinants D and their first corners about r.
    #[inline(always)]
    pub(crate) fn add(
        &mut self,
        [[ax, ay, az], [bx, by, bz], [cx, cy, cz]]: Corners<L>,
    ) -> ([L; 3], L, [L; 3]) {
        let [rx, ry, rz] = self.r;
        // (b − a)×(c − a) and its magnitudes, as `properties::cross_products`.
        let (ux, uy, uz) = (bx - ax, by - ay, bz - az);
        let (vx, vy, vz) = (cx - ax, cy - ay, cz - az);
        let plus = [uy * vz, uz * vx, ux * vy];
        let minus = [uz * vy, ux * vz, uy * vx];
        let cross = [plus[0] - minus[0], plus[1] - minus[1], plus[2] - minus[2]];
        let magnitude = [
            plus[0].abs() + minus[0].abs(),
            plus[1].abs() + minus[1].abs(),
            plus[2].abs() + minus[2].abs(),
        ];
        // D = (a − r)·cross and P, as `VolumeSums::add_determinant`.
        let a = [ax - rx, ay - ry, az - rz];
        let d = a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2];
        let permanent =
            a[0].abs() * magnitude[0] + a[1].abs() * magnitude[1] + a[2].abs() * magnitude[2];
        // The scalar sum adds a face's fan to 0.0 first (`0.0 + x` turns −0 into +0);
        // not needed here: a compensated sum that starts at +0 gives the same bits for a
        // −0 term as for a +0 one (its sum can never become −0).
        let area = cross;
        for (k, x) in [d, area[0], area[1], area[2]].into_iter().enumerate() {
            add_compensated(&mut self.sum[k], &mut self.compensation[k], x);
        }
        let plain = [d.abs(), permanent, magnitude[0], magnitude[1], magnitude[2]];
        for (sum, x) in self.plain.iter_mut().zip(plain) {
            *sum += x;
        }
        self.triangles += 4;
        (area, d, a)
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
            vector_area_fan_excess: [0.0; 3],
            triangles: self.triangles / 4,
        }))
    }
}

fn chunk_sums<I: VertexIndex>(
    positions: &[Point],
    triangles: &[[I; 3]],
    first: usize,
    r: Point,
) -> Result<VolumeSums, MeshError> {
    dispatch(ChunkSums { positions, triangles, first, r })
}

/// [`chunk_sums_any`]'s arguments, for the lanes [`dispatch`] picks.
#[derive(Clone, Copy)]
struct ChunkSums<'a, I> {
    positions: &'a [Point],
    triangles: &'a [[I; 3]],
    first: usize,
    r: Point,
}

impl<I: VertexIndex> OnLanes for ChunkSums<'_, I> {
    type Output = Result<VolumeSums, MeshError>;
    #[inline(always)]
    fn run<L: Lanes>(self) -> Self::Output {
        chunk_sums_any::<I, L>(self.positions, self.triangles, self.first, self.r)
    }
}

/// How far ahead of the four triangles being summed the corner loops ask for the
/// positions of four more ([`prefetch_corners`]).
///
/// The positions are read in the order the triangles name them: in a mesh whose
/// vertices are not numbered along its surface, each read is a cache miss, and the
/// loop's arithmetic keeps too few of them in flight. Asked for 16 triangles ahead, on
/// one thread of an AMD EPYC (Zen 4): a 1M-triangle sphere's volume with its vertices
/// in random order 14.8 → 6.2 ms, the benchmark's subdivided sphere 5.7 → 4.4 ms, a UV
/// sphere numbered ring by ring unchanged (8, 32, 64 and 128 ahead were no better).
pub(crate) const PREFETCH_TRIANGLES: usize = 16;

/// Whether `triangles` (a chunk) name vertices scattered through memory, so that the
/// corner loops should prefetch ([`PREFETCH_TRIANGLES`]): whether the first
/// [`SCATTER_SAMPLE`] of them span more than 16 vertex ids a triangle. A mesh numbered
/// along its surface (a UV sphere ring by ring, a welded STL by first use) spans about
/// one id a triangle, and there the processor's own prefetcher is ahead: asking as
/// well cost it 5–12%.
#[inline(always)]
pub(crate) fn scattered<I: VertexIndex>(triangles: &[[I; 3]]) -> bool {
    let sample = &triangles[..triangles.len().min(SCATTER_SAMPLE)];
    let (low, high) = sample
        .as_flattened()
        .iter()
        .fold((usize::MAX, 0), |(low, high), &i| (low.min(i.to_index()), high.max(i.to_index())));
    high.saturating_sub(low) > 16 * sample.len()
}

/// How many triangles [`scattered`] looks at.
const SCATTER_SAMPLE: usize = 256;

/// Asks the processor to start loading the corners' positions of the triangles `ahead`
/// (`None` past the end), read through `at` (a hint: no effect on results).
#[inline(always)]
pub(crate) fn prefetch_corners<'p, I: Copy>(ahead: Option<&[[I; 3]]>, at: impl Fn(I) -> &'p Point) {
    if let Some(four) = ahead {
        for t in four {
            for &i in t {
                crate::buckets::prefetch(at(i));
            }
        }
    }
}

#[inline(always)]
fn chunk_sums_any<I: VertexIndex, L: Lanes>(
    positions: &[Point],
    triangles: &[[I; 3]],
    first: usize,
    r: Point,
) -> Result<VolumeSums, MeshError> {
    // Every index in range, checked in one pass over the chunk's indices (which the
    // compiler vectorises) before the loop below reads the positions unchecked: a
    // bounds check per corner took 5 instructions, 15 a triangle.
    let count = positions.len();
    let in_range = triangles.as_flattened().iter().fold(true, |ok, &i| ok & (i.to_index() < count));
    if !in_range {
        if let Some((k, t)) =
            triangles.iter().enumerate().find(|(_, t)| t.iter().any(|i| i.to_index() >= count))
        {
            return Err(index_error(positions, first + k, t));
        }
    }
    let mut lanes = VolumeLanes::<L>::new(r);
    let mut groups = triangles.chunks_exact(4);
    let mut face = first;
    // SAFETY: every index of `triangles` is below `positions.len()` (above).
    let at = |i: I| unsafe { positions.get_unchecked(i.in_range_index()) };
    let prefetch = scattered(triangles);
    for group in &mut groups {
        if prefetch {
            let ahead = face - first + PREFETCH_TRIANGLES;
            prefetch_corners(triangles.get(ahead..ahead + 4), at);
        }
        let [t0, t1, t2, t3] = [&group[0], &group[1], &group[2], &group[3]];
        lanes.add([
            L::gather([at(t0[0]), at(t1[0]), at(t2[0]), at(t3[0])]),
            L::gather([at(t0[1]), at(t1[1]), at(t2[1]), at(t3[1])]),
            L::gather([at(t0[2]), at(t1[2]), at(t2[2]), at(t3[2])]),
        ]);
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
        // The remainder starts at a multiple of 4 from the chunk's start.
        let sums = &mut sums.0[lane];
        let (cross, magnitude, _) = sums.add_fan_triangle(r, a, b, c);
        sums.add_vector_area(cross.map(|x| 0.0 + x), magnitude, 1);
        face += 1;
    }
    Ok(sums.merged())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::every_copy;
    use crate::test_rng::XorShift;

    /// The baseline lanes (`wide`, what a CPU without AVX2 runs) give the bits of the
    /// AVX2 and AVX-512 copies (those this CPU has) and of the dispatched one,
    /// remainders and ±0 coordinates included.
    #[test]
    fn baseline_and_dispatched_lanes_agree() {
        let mut rng = XorShift::new(0x2545_f491_4f6c_dd1d);
        let positions: Vec<Point> = (0..20_000)
            .map(|_| {
                [0; 3].map(|_| match rng.below(6) {
                    0 => 0.0,
                    1 => -0.0,
                    _ => (rng.unit() - 0.5) * 2f64.powi(rng.below(40) as i32 - 20),
                })
            })
            .collect();
        // Ids among the first 200 vertices, and then among all 20,000: scattered, so
        // that the loops prefetch.
        for (n, ids) in [(1, 200), (4, 200), (7, 200), (64, 200), (1001, 200), (1001, 20_000)] {
            let triangles: Vec<[u32; 3]> =
                (0..n).map(|_| [0; 3].map(|_| rng.below(ids) as u32)).collect();
            if n >= 64 {
                assert_eq!(scattered(&triangles), ids > 200, "{n} triangles");
            }
            let r = positions[triangles[0][0] as usize];
            let sums = ChunkSums { positions: &positions, triangles: &triangles, first: 0, r };
            let mut copies = every_copy(sums);
            let baseline = copies.remove(0).unwrap();
            copies.push(chunk_sums(&positions, &triangles, 0, r));
            let copies: Vec<VolumeSums> = copies.into_iter().map(Result::unwrap).collect();
            for copy in copies {
                assert_eq!(format!("{baseline:?}"), format!("{copy:?}"), "{n} triangles");
            }
        }
    }
}
