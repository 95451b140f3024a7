//! Mass properties of the solid a closed surface bounds: volume, area, centroid, inertia.
//!
//! # Math
//! Divergence theorem: ∫Ω ∇·F dV = ∮∂Ω F·n dA. Cutting the solid into tetrahedra from a
//! reference point r to every (fan) triangle (a, b, c), with a, b, c taken relative to r
//! and D = a·(b×c) (six times the tetrahedron's signed volume):
//!
//! - volume:         V      = Σ D / 6
//! - first moment:   ∫ x dV = Σ D (a + b + c) / 24
//! - second moment:  ∫ xᵢxⱼ dV = Σ D (aᵢaⱼ + bᵢbⱼ + cᵢcⱼ + sᵢsⱼ) / 120, s = a + b + c
//!
//! (the moments of a tetrahedron with one vertex at the origin; Eberly, "Polyhedral Mass
//! Properties (Revisited)"; Tonon 2004). The centroid is the first moment over V; the
//! covariance about the centroid is C = ∫ x xᵀ dV − V c cᵀ, and the inertia tensor is
//! I = tr(C)·𝟙 − C. Signs follow the winding: outward normals (counter-clockwise seen from
//! outside) give V > 0. Reported inertia is that of the solid, whatever the winding.
//!
//! # Open surfaces
//! For a closed surface the sums do not depend on r; for an open one they do. The
//! signed volume reported is the one about the world origin, Σ det(a, b, c)/6 over the
//! absolute coordinates (trimesh's convention, and what [`crate::exact_signed_volume`]
//! rounds): the signed volume of the cones from the origin to the faces. With a, b, c
//! relative to r, det(a + r, b + r, c + r) = det(a, b, c) + r·((b − a)×(c − a)), so
//! V_origin = V_r + r·S/6 with S = Σ (b − a)×(c − a), twice the surface's vector area
//! (zero for a closed surface). S is summed (compensated) in the same pass and the
//! correction applied once at the end, only when it is distinguishable from its own
//! rounding: a closed surface keeps the value about r, bit for bit.
//! A surface whose vector area is known to be exactly zero
//! ([`Surface::vector_area_is_zero`]: the solid of a check that found it closed,
//! consistently oriented and exactly welded, every directed edge matched by its reverse)
//! skips the move: its volume about r is its volume about the origin, and its bound that
//! of the sum about r, whatever its distance from the origin.
//! The centroid and inertia stay those about r: for an open surface they describe the
//! solid of the cones from r (the first vertex of the first face) to the faces, i.e.
//! the surface closed by joining its rim to r; for a closed one, the solid itself.
//!
//! A face's area is the length of its vector area (half the sum of its fan triangles'
//! cross products: Newell's formula), never the sum of the fan triangles' areas, which
//! overcounts non-convex and non-planar faces.
//!
//! # Accuracy
//! - r is a vertex of the surface, never the world origin: the terms stay the size of the
//!   mesh, not of its offset, so a part at 10⁷ keeps all the digits of a part at 0.
//! - Every sum is compensated (TwoSum) and the chunks combine in a fixed order: the same
//!   bits for any thread count. Within a chunk the triangles go to four interleaved sums
//!   (the k-th to sum k mod 4; `volume::LaneSums`), merged in order: one SIMD lane each.
//! - D is evaluated as D = a·((b − a)×(c − a)) (a, b, c relative to r), equal to
//!   a·(b×c) because a·(a×w) = 0: the cross product is the one the vector area S
//!   and the area take anyway, so a triangle costs one cross product, not two, and the
//!   rounding bound is the smaller (P below is |a|·|edge|², not |a||b||c|).
//! - `volume_error_bound` bounds |computed − exact| for the polyhedron the f64
//!   coordinates describe: each D carries at most 8 roundings along any of its six
//!   terms (a − r, b − a and c − a, the cross product's products and difference, the
//!   dot product's product and two additions), so |D̂ − D| ≤ γ(8)·P with
//!   P = Σ|aᵢ|(|uⱼvₖ| + |uₖvⱼ|) = |a|·M, u = b − a, v = c − a and M the magnitudes of the
//!   cross product's products; the compensated sum adds u·|ΣD| + γ(n)²·Σ|D|; the final
//!   division by 6 adds u·|V|. (γ(n) = n·u/(1 − n·u), u = 2⁻⁵³.) The bound is evaluated
//!   with a little headroom for its own rounding.
//! - The move to the origin adds |r|-weighted bounds on S (each cross product component
//!   within γ(4) of its products' magnitudes, each face's fan sum within γ(m − 1), the
//!   compensated sum's own term) and on the dot product. When that would make the bound
//!   looser than both the bound about r and 2⁻⁴² of the volume (a surface far from the
//!   origin compared with its size: r·S is huge against the volume), the exact sum of
//!   [`crate::exact_signed_volume`] is taken instead (3–5× the time) and the bound is
//!   its rounding, u·|V|. Only if that sum is out of range does the wide bound stay.

use crate::accumulate::{gamma, ordered_reduce_on, CompensatedSum, UNIT_ROUNDOFF};
use crate::lanes::{dispatch, Lanes, OnLanes};
use crate::mesh::only_triangle;
use crate::vector::{add, dot, norm, scale, sub};
use crate::volume::Corners;
use crate::{Point, Surface};
use rayon::prelude::*;
use std::ops::{Add, Mul};

/// Faces per chunk of the deterministic parallel reduction.
pub(crate) const CHUNK_FACES: usize = 1 << 14;

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

/// The principal moments of inertia (ascending) and their axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principal {
    pub moments: [f64; 3],
    /// `axes[k]` is the unit axis of `moments[k]`; the three form a right-handed frame.
    pub axes: [Point; 3],
}

/// What [`mass_properties`] measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassProperties {
    /// Faces read.
    pub faces: usize,
    /// Triangles in the faces' fans.
    pub triangles: usize,
    /// Σ of signed tetrahedron volumes from the world origin to the fan triangles, as
    /// the surface is wound: positive for outward normals. For a closed surface, the
    /// solid's signed volume; for an open one, the signed volume of the cones from the
    /// origin to the faces (trimesh's convention, and the value
    /// [`crate::exact_signed_volume`] gives correctly rounded).
    pub signed_volume: f64,
    /// A bound on |`signed_volume` − the exact signed volume of the polyhedron given by
    /// the f64 coordinates|.
    pub volume_error_bound: f64,
    /// Total face area.
    pub area: f64,
    /// The centroid of the solid; `None` when the volume is not distinguishable from 0.
    /// Taken about the first vertex of the first face: for an open surface, that of the
    /// surface closed by cones to that vertex (see the module docs).
    pub centroid: Option<Point>,
    /// Inertia tensor about the centroid for unit density (scale by the density for a
    /// body); zero when the centroid is `None`.
    pub inertia: [[f64; 3]; 3],
    /// Bounds of the surface's vertices; `None` for an empty surface.
    pub bounds: Option<Bounds>,
}

impl MassProperties {
    /// What `faces` faces with no triangles (or a degenerate point set) measure: nothing,
    /// with no centroid.
    pub(crate) fn empty(faces: usize) -> MassProperties {
        MassProperties {
            faces,
            triangles: 0,
            signed_volume: 0.0,
            volume_error_bound: 0.0,
            area: 0.0,
            centroid: None,
            inertia: [[0.0; 3]; 3],
            bounds: None,
        }
    }

    /// The solid's volume: |signed volume|.
    pub fn volume(&self) -> f64 {
        self.signed_volume.abs()
    }

    /// Principal moments (ascending) and axes of [`MassProperties::inertia`].
    pub fn principal(&self) -> Principal {
        crate::eigen::principal(self.inertia)
    }
}

/// Faces summed in plain f64 before their moment sums join the compensated ones.
const BLOCK_FACES: usize = 64;

/// The sums the signed volume and its bound are made of: what [`mass_properties`] and
/// [`crate::volume`] share, summed in the same order by both, so that both give the same
/// bits.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct VolumeSums {
    pub(crate) six_volume: CompensatedSum,
    /// Σ over faces of twice the vector area (each face's fan summed plainly), for the
    /// move from the reference point to the origin.
    pub(crate) vector_area: [CompensatedSum; 3],
    /// Per component, Σ of the magnitudes M of the two products in each fan triangle's
    /// cross product, and Σ (m − 1)·M over faces of m > 1 fan triangles (none in a
    /// triangle mesh): the bound weighs each face's M by m + 4, 5·ΣM plus this.
    pub(crate) vector_area_magnitude: [f64; 3],
    pub(crate) vector_area_fan_excess: [f64; 3],
    /// Σ P, for the error bound.
    pub(crate) determinant_magnitude: f64,
    /// Σ |D|, for the error bound.
    pub(crate) abs_six_volume: f64,
    pub(crate) triangles: usize,
}

impl VolumeSums {
    pub(crate) fn merge(&mut self, o: &VolumeSums) {
        self.six_volume.merge(&o.six_volume);
        for k in 0..3 {
            self.vector_area[k].merge(&o.vector_area[k]);
            self.vector_area_magnitude[k] += o.vector_area_magnitude[k];
            self.vector_area_fan_excess[k] += o.vector_area_fan_excess[k];
        }
        self.determinant_magnitude += o.determinant_magnitude;
        self.abs_six_volume += o.abs_six_volume;
        self.triangles += o.triangles;
    }

    /// Adds triangle (a, b, c) by its first corner relative to the reference point r,
    /// `a_r` = a − r, and its cross product (b − a)×(c − a) as [`cross_products`] gives
    /// it (`cross` = plus − minus, `magnitude` = |plus| + |minus|): D = a_r·cross and
    /// its magnitude P = |a_r|·magnitude (see the module docs).
    #[inline(always)]
    pub(crate) fn add_determinant(&mut self, a_r: Point, cross: Point, magnitude: Point) -> f64 {
        let d = dot(a_r, cross);
        let permanent =
            a_r[0].abs() * magnitude[0] + a_r[1].abs() * magnitude[1] + a_r[2].abs() * magnitude[2];
        self.six_volume.add(d);
        self.abs_six_volume += d.abs();
        self.determinant_magnitude += permanent;
        self.triangles += 1;
        d
    }

    /// Adds fan triangle (a, b, c) of a face: D (see [`Self::add_determinant`]); returns
    /// its cross product and magnitudes for the face's vector area.
    #[inline(always)]
    pub(crate) fn add_fan_triangle(
        &mut self,
        r: Point,
        a: Point,
        b: Point,
        c: Point,
    ) -> (Point, Point) {
        let (cross, magnitude) = cross_products(a, b, c);
        self.add_determinant(sub(a, r), cross, magnitude);
        (cross, magnitude)
    }

    /// Adds a face's vector area (its fan's cross products summed plainly), their
    /// products' magnitudes, and its fan's length.
    #[inline(always)]
    pub(crate) fn add_vector_area(&mut self, vector_area: Point, magnitude: Point, fan: usize) {
        for k in 0..3 {
            self.vector_area[k].add(vector_area[k]);
            self.vector_area_magnitude[k] += magnitude[k];
            if fan > 1 {
                self.vector_area_fan_excess[k] += (fan - 1) as f64 * magnitude[k];
            }
        }
    }
}

/// The cross product (b − a)×(c − a) as plus − minus of its components' two products,
/// and the products' magnitudes |plus| + |minus|: the same operations as the SIMD lanes
/// (`volume::VolumeLanes::add`).
#[inline(always)]
pub(crate) fn cross_products(a: Point, b: Point, c: Point) -> (Point, Point) {
    let (u, v) = (sub(b, a), sub(c, a));
    let plus = [u[1] * v[2], u[2] * v[0], u[0] * v[1]];
    let minus = [u[2] * v[1], u[0] * v[2], u[1] * v[0]];
    (
        [plus[0] - minus[0], plus[1] - minus[1], plus[2] - minus[2]],
        [
            plus[0].abs() + minus[0].abs(),
            plus[1].abs() + minus[1].abs(),
            plus[2].abs() + minus[2].abs(),
        ],
    )
}

/// Per-chunk running sums. The volume, whose error bound is reported, is compensated
/// term by term; the moments and area (no published bound) are summed plainly within
/// blocks of [`BLOCK_FACES`] faces and compensated across blocks, which keeps them
/// accurate to about γ(64) of their terms at a fraction of the cost.
#[derive(Clone, Copy, Debug, Default)]
struct Partial {
    volume: VolumeSums,
    first: [CompensatedSum; 3],
    /// xx, yy, zz, xy, yz, zx.
    second: [CompensatedSum; 6],
    double_area: CompensatedSum,
    /// The current block's plain sums: first moments, second moments, double area.
    block: [f64; 10],
    bounds: Option<Bounds>,
}

impl Partial {
    pub(crate) fn merge(&mut self, o: Partial) {
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
    fn flush_block(&mut self) {
        let block = std::mem::take(&mut self.block);
        for (sum, x) in self.first.iter_mut().chain(&mut self.second).zip(block) {
            sum.add(x);
        }
        self.double_area.add(block[9]);
    }

    /// A chunk's four interleaved sums (see `volume::LaneSums`), their blocks flushed,
    /// merged in order, with the chunk's bounds.
    fn merged(mut lanes: [Partial; 4], bounds: Bounds) -> Partial {
        lanes.iter_mut().for_each(Partial::flush_block);
        let [mut total, rest @ ..] = lanes;
        for lane in rest {
            total.merge(lane);
        }
        total.bounds = Some(bounds);
        total
    }

    /// Adds fan triangle (a, b, c): its D and its moments' terms about r; returns its
    /// cross product and magnitudes for the face's vector area.
    #[inline(always)]
    fn add_triangle(&mut self, r: Point, a: Point, b: Point, c: Point) -> (Point, Point) {
        let (cross, magnitude) = cross_products(a, b, c);
        let (a, b, c) = (sub(a, r), sub(b, r), sub(c, r));
        let d = self.volume.add_determinant(a, cross, magnitude);
        let terms = moment_terms(a, b, c);
        for (sum, t) in self.block.iter_mut().zip(terms) {
            *sum += d * t;
        }
        (cross, magnitude)
    }
}

/// Computes the mass properties of the solid bounded by `surface`, in one parallel,
/// deterministic pass.
///
/// ```
/// use meshvol::{Mesh, mass_properties};
/// // The unit cube with quad faces, wound counter-clockwise seen from outside.
/// let p = vec![
///     [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0],
///     [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0],
/// ];
/// let quads: [&[u32]; 6] = [
///     &[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7],
/// ];
/// let mp = mass_properties(&Mesh::from_polygons(p, quads).unwrap());
/// assert_eq!(mp.signed_volume, 1.0);
/// assert_eq!(mp.area, 6.0);
/// assert_eq!(mp.centroid, Some([0.5, 0.5, 0.5]));
/// assert!((mp.inertia[0][0] - 1.0 / 6.0).abs() < 1e-15);
/// ```
pub fn mass_properties<S: Surface + ?Sized>(surface: &S) -> MassProperties {
    let faces = surface.face_count();
    let Some(r) = crate::mesh::first_corner(surface) else {
        return MassProperties::empty(faces);
    };
    let sums = ordered_reduce_on(
        faces >= crate::volume::PARALLEL_TRIANGLES,
        faces,
        CHUNK_FACES,
        |range| {
            if let Some((positions, triangles)) = surface.indexed_triangles() {
                return triangles_partial(&Indexed { positions, triangles }, range, r);
            }
            if surface.faces_are_triangles() {
                let each = EachTriangle(|f: usize| only_triangle(surface, f));
                return triangles_partial(&each, range, r);
            }
            // The chunk's k-th triangle and k-th face to sum k mod 4 (`volume::LaneSums`).
            let mut lanes = [Partial::default(); 4];
            let mut bounds = Bounds::of(r);
            let mut triangle = 0usize;
            for (k, face) in range.enumerate() {
                let mut vector_area = [0.0; 3];
                let mut magnitude = [0.0; 3];
                let mut fan = 0usize;
                surface.fan(face, |a, b, c| {
                    let (cross, m) = lanes[triangle % 4].add_triangle(r, a, b, c);
                    for k in 0..3 {
                        vector_area[k] += cross[k];
                        magnitude[k] += m[k];
                    }
                    fan += 1;
                    bounds.include(a);
                    bounds.include(b);
                    bounds.include(c);
                    triangle += 1;
                });
                let lane = &mut lanes[k % 4];
                lane.block[9] += norm(vector_area);
                lane.volume.add_vector_area(vector_area, magnitude, fan);
                if face % BLOCK_FACES == BLOCK_FACES - 1 {
                    lanes.iter_mut().for_each(Partial::flush_block);
                }
            }
            Partial::merged(lanes, bounds)
        },
        Partial::merge,
    )
    .unwrap_or_default();
    let (mut properties, loose) = finish(faces, r, &sums, surface.vector_area_is_zero());
    if loose {
        // Far from the origin, the move from r to the origin would widen the bound
        // beyond what the sum about r achieves: take the exact sum instead (correctly
        // rounded). Out of its range, the bound stays as wide as it is.
        if let Ok(exact) = crate::exact::exact_signed_volume(surface) {
            properties.signed_volume = exact;
            properties.volume_error_bound = UNIT_ROUNDOFF * exact.abs();
        }
    }
    properties
}

/// Where [`triangles_partial`] reads a surface whose every face is one triangle.
trait Triangles {
    /// Every coordinate is a number (not NaN): the bounds' minima and maxima can skip
    /// their NaN tests.
    const NUMBERS: bool;

    /// Face `face`'s corners.
    fn corners(&self, face: usize) -> [Point; 3];

    /// Whether faces `range` name their corners scattered through memory, so that the
    /// loop should prefetch them ([`crate::volume::scattered`]).
    #[inline(always)]
    fn scattered(&self, _range: std::ops::Range<usize>) -> bool {
        false
    }

    /// Asks the processor to start loading the corners of faces `ahead..ahead + 4`
    /// (those that exist; a hint).
    #[inline(always)]
    fn prefetch(&self, _ahead: usize) {}

    /// Faces `face..face + 4`'s corners as lanes, lane j face `face + j`'s.
    #[inline(always)]
    fn four<L: Lanes>(&self, face: usize) -> Corners<L> {
        let mut p = [[[0.0; 4]; 3]; 3];
        for lane in 0..4 {
            for (corner, q) in self.corners(face + lane).into_iter().enumerate() {
                for k in 0..3 {
                    p[corner][k][lane] = q[k];
                }
            }
        }
        crate::volume::corners::<L>(&p)
    }
}

/// An indexed triangle mesh (a surface's [`Surface::indexed_triangles`], such as a
/// [`crate::Mesh`] of triangles): four triangles' corners are gathered into lanes from
/// the positions ([`Lanes::gather`]).
struct Indexed<'a> {
    positions: &'a [Point],
    triangles: &'a [[u32; 3]],
}

impl Triangles for Indexed<'_> {
    // Arrays behind a `Surface` hold finite coordinates (its contract; a `Mesh`
    // validates them when built).
    const NUMBERS: bool = true;

    #[inline(always)]
    fn corners(&self, face: usize) -> [Point; 3] {
        self.triangles[face].map(|i| self.positions[i as usize])
    }

    #[inline(always)]
    fn scattered(&self, range: std::ops::Range<usize>) -> bool {
        crate::volume::scattered(&self.triangles[range])
    }

    #[inline(always)]
    fn prefetch(&self, ahead: usize) {
        let at = |i: u32| &self.positions[i as usize];
        crate::volume::prefetch_corners(self.triangles.get(ahead..ahead + 4), at);
    }

    #[inline(always)]
    fn four<L: Lanes>(&self, face: usize) -> Corners<L> {
        let t = &self.triangles[face..face + 4];
        let at = |i: u32| &self.positions[i as usize];
        [
            L::gather([at(t[0][0]), at(t[1][0]), at(t[2][0]), at(t[3][0])]),
            L::gather([at(t[0][1]), at(t[1][1]), at(t[2][1]), at(t[3][1])]),
            L::gather([at(t[0][2]), at(t[1][2]), at(t[2][2]), at(t[3][2])]),
        ]
    }
}

/// Any other surface of triangles (a binary STL read in place), face by face.
struct EachTriangle<F>(F);

impl<F: Fn(usize) -> [Point; 3]> Triangles for EachTriangle<F> {
    const NUMBERS: bool = false;

    #[inline(always)]
    fn corners(&self, face: usize) -> [Point; 3] {
        (self.0)(face)
    }
}

/// One chunk of [`mass_properties`] over a surface whose every face is one triangle
/// (an indexed triangle mesh, a validated [`crate::Mesh`]; a binary STL read in
/// place), four triangles a SIMD step: every per-triangle
/// quantity of the scalar loop (the same IEEE operations, lane by lane), and every sum
/// too, lane j holding the chunk's j-th interleaved sum (`volume::LaneSums`): the same
/// bits as the scalar loop, which the tests compare (`tests/volume.rs`). The bounds are
/// lane-wise minima and maxima, their zeros (whose sign depends on the order) redone
/// in order.
fn triangles_partial<T: Triangles>(
    corners: &T,
    range: std::ops::Range<usize>,
    r: Point,
) -> Partial {
    dispatch(TrianglesPartial { corners, range, r })
}

/// [`triangles_partial_in`]'s arguments, for the lanes [`dispatch`] picks.
struct TrianglesPartial<'a, T> {
    corners: &'a T,
    range: std::ops::Range<usize>,
    r: Point,
}

// Not derived: `T` need not be Clone for its reference to be.
impl<T> Clone for TrianglesPartial<'_, T> {
    fn clone(&self) -> Self {
        TrianglesPartial { corners: self.corners, range: self.range.clone(), r: self.r }
    }
}

impl<T: Triangles> OnLanes for TrianglesPartial<'_, T> {
    type Output = Partial;
    #[inline(always)]
    fn run<L: Lanes>(self) -> Partial {
        triangles_partial_in::<L, T>(self.corners, self.range, self.r)
    }
}

#[inline(always)]
fn triangles_partial_in<L: Lanes, T: Triangles>(
    triangles: &T,
    range: std::ops::Range<usize>,
    r: Point,
) -> Partial {
    use crate::volume::{add_compensated, VolumeLanes};
    let zero = L::ZERO;
    let first = range.start;
    let mut bounds = Bounds::of(r);
    // The volume's sums in `VolumeLanes`; the block's ten plain sums (first and second
    // moments, double area) and their compensated sums, one triangle a lane likewise.
    let mut lanes = VolumeLanes::<L>::new(r);
    let mut block = [zero; 10];
    let (mut sum, mut compensation) = ([zero; 10], [zero; 10]);
    // The bounds lane by lane; see below for their signed zeros.
    let rl = [L::splat(r[0]), L::splat(r[1]), L::splat(r[2])];
    let (mut low, mut high) = (rl, rl);
    let groups_end = first + range.len() / 4 * 4;
    let mut face = first;
    // Block by block: the inner loop holds the running sums in registers, the outer one
    // the compensated sums, which it touches once a block.
    let ends_block = |next: usize| (next - 1) % BLOCK_FACES == BLOCK_FACES - 1;
    let prefetch = triangles.scattered(range.clone());
    while face < groups_end {
        loop {
            if prefetch {
                triangles.prefetch(face + crate::volume::PREFETCH_TRIANGLES);
            }
            let corners = triangles.four::<L>(face);
            let [[ax, ay, az], [bx, by, bz], [cx, cy, cz]] = corners;
            for (k, [x, y, z]) in [[ax, bx, cx], [ay, by, cy], [az, bz, cz]].into_iter().enumerate()
            {
                if T::NUMBERS {
                    low[k] = low[k].min_of_numbers(x).min_of_numbers(y).min_of_numbers(z);
                    high[k] = high[k].max_of_numbers(x).max_of_numbers(y).max_of_numbers(z);
                } else {
                    low[k] = low[k].min(x).min(y).min(z);
                    high[k] = high[k].max(x).max(y).max(z);
                }
            }
            let (area, d, a) = lanes.add(corners);
            let (b, c) =
                ([bx - rl[0], by - rl[1], bz - rl[2]], [cx - rl[0], cy - rl[1], cz - rl[2]]);
            // The moments' terms and the double area, as `Partial::add_triangle`.
            for (sum, t) in block.iter_mut().zip(moment_terms(a, b, c)) {
                *sum += d * t;
            }
            block[9] += (area[0] * area[0] + area[1] * area[1] + area[2] * area[2]).sqrt();
            face += 4;
            if face == groups_end || ends_block(face) {
                break;
            }
        }
        // The group's last face ended a block: `Partial::flush_block`, lane by lane.
        if ends_block(face) {
            for k in 0..10 {
                add_compensated(&mut sum[k], &mut compensation[k], block[k]);
            }
            block = [zero; 10];
        }
    }
    let volume = lanes.lanes();
    let (sum, compensation, block) = (
        sum.map(|x| x.to_array()),
        compensation.map(|x| x.to_array()),
        block.map(|x| x.to_array()),
    );
    let mut parts: [Partial; 4] = std::array::from_fn(|j| {
        let compensated = |k: usize| CompensatedSum::from_parts(sum[k][j], compensation[k][j]);
        Partial {
            volume: volume.0[j],
            first: [0, 1, 2].map(compensated),
            second: [3, 4, 5, 6, 7, 8].map(compensated),
            double_area: compensated(9),
            block: block.map(|b| b[j]),
            bounds: None,
        }
    });
    for k in 0..3 {
        let pick = |lanes: L, better: fn(f64, f64) -> bool| {
            lanes.to_array().into_iter().fold(r[k], |m, x| if better(x, m) { x } else { m })
        };
        bounds.min[k] = pick(low[k], |x, m| x < m);
        bounds.max[k] = pick(high[k], |x, m| x > m);
    }
    // The last few triangles as the scalar loop reads them; the remainder starts at a
    // multiple of 4 from the chunk's start, so at lane 0.
    for lane in 0..range.len() % 4 {
        let [a, b, c] = triangles.corners(face);
        bounds.include(a);
        bounds.include(b);
        bounds.include(c);
        let part = &mut parts[lane];
        let (cross, magnitude) = part.add_triangle(r, a, b, c);
        // A face's fan sum starts at 0.0 (`0.0 + x` turns −0 into +0).
        let vector_area = cross.map(|x| 0.0 + x);
        part.block[9] += norm(vector_area);
        part.volume.add_vector_area(vector_area, magnitude, 1);
        if face % BLOCK_FACES == BLOCK_FACES - 1 {
            parts.iter_mut().for_each(Partial::flush_block);
        }
        face += 1;
    }
    // `Bounds::include` keeps the first of equal extremes, so its result has the same
    // bits in any order except for a zero extreme (−0.0 or +0.0, whichever came
    // first). r comes first: a zero extreme is r's when r is at zero on that axis (a
    // part standing on z = 0 whose first vertex is there); otherwise recompute it in
    // the scalar loop's order (r, then each triangle's corners).
    for k in 0..3 {
        let unsure = |extreme: f64| extreme == 0.0 && r[k] != 0.0;
        if bounds.min[k] == 0.0 && r[k] == 0.0 {
            bounds.min[k] = r[k];
        }
        if bounds.max[k] == 0.0 && r[k] == 0.0 {
            bounds.max[k] = r[k];
        }
        if unsure(bounds.min[k]) || unsure(bounds.max[k]) {
            let (mut low, mut high) = (r[k], r[k]);
            for x in range.clone().flat_map(|f| triangles.corners(f).map(|p| p[k])) {
                low = if x < low { x } else { low };
                high = if x > high { x } else { high };
            }
            if bounds.min[k] == 0.0 {
                bounds.min[k] = low;
            }
            if bounds.max[k] == 0.0 {
                bounds.max[k] = high;
            }
        }
    }
    Partial::merged(parts, bounds)
}

/// How much wider than the bound of the sum about r the correction to the origin may
/// make the volume's bound, relative to the volume, before the exact sum is taken.
const LOOSE_BOUND: f64 = 1.0 / (1u64 << 42) as f64;

/// The signed volume and its bound from [`VolumeSums`] (see the module docs).
pub(crate) struct VolumeFinish {
    pub(crate) signed_volume: f64,
    pub(crate) volume_error_bound: f64,
    /// The signed volume about r, and its bound.
    pub(crate) about_r: f64,
    pub(crate) bound_about_r: f64,
    /// The bound is loose (see [`LOOSE_BOUND`]): the exact sum should replace it.
    pub(crate) loose: bool,
}

impl VolumeSums {
    /// `zero_vector_area`: the surface's vector area is known to be exactly zero
    /// ([`Surface::vector_area_is_zero`]), so the volume about r is the volume about the
    /// origin and its bound the whole bound.
    pub(crate) fn finish(&self, faces: usize, r: Point, zero_vector_area: bool) -> VolumeFinish {
        let sums = self;
        let n = sums.triangles as f64;
        let six_volume = sums.six_volume.value();
        // About r: what the centroid and inertia are taken about.
        let about_r = six_volume / 6.0;
        let six_bound = gamma(8.0) * sums.determinant_magnitude
            + UNIT_ROUNDOFF * six_volume.abs()
            + gamma(n).powi(2) * sums.abs_six_volume;
        // (1 + γ(n + 8)) covers the rounding of the bound's own sums.
        let headroom = 1.0 + gamma(n + 8.0);
        let bound_about_r = six_bound * headroom / 6.0 + UNIT_ROUNDOFF * about_r.abs();
        if zero_vector_area {
            let (signed_volume, volume_error_bound) = (about_r, bound_about_r);
            return VolumeFinish {
                signed_volume,
                volume_error_bound,
                about_r,
                bound_about_r,
                loose: false,
            };
        }

        // To the origin: V_O = V_r + r·S/6, S = Σ (b − a) × (c − a) over the fan triangles.
        // Each cross product component is off by at most γ(4) of its two products'
        // magnitudes (two subtractions, a product, a difference); a face's fan of m
        // triangles, summed plainly, by γ(m − 1) more; the compensated sum over faces adds
        // u·|S| + γ(F)²·Σ|terms|. 2u·(m + 4) covers γ(m + 4) with room.
        let s = sums.vector_area.map(|x| x.value());
        let faces_f = faces as f64;
        let mut correction_bound = 0.0;
        for k in 0..3 {
            let weighted = 5.0 * sums.vector_area_magnitude[k] + sums.vector_area_fan_excess[k];
            let s_bound = 2.0 * UNIT_ROUNDOFF * weighted
                + UNIT_ROUNDOFF * s[k].abs()
                + 2.0 * gamma(faces_f).powi(2) * sums.vector_area_magnitude[k];
            // The dot product and division by 6 round by γ(4) of Σ|r_k S_k|.
            correction_bound += r[k].abs() * (s_bound + gamma(4.0) * s[k].abs());
        }
        let correction_bound = correction_bound * headroom / 6.0;
        let correction = dot(r, s) / 6.0;
        let (signed_volume, volume_error_bound) = if correction.abs() <= correction_bound {
            // Not distinguishable from 0 (a closed surface's S is 0): adding it would only
            // add its rounding. The value stays V_r; the bound covers the true correction.
            (about_r, bound_about_r + correction.abs() + correction_bound)
        } else {
            let v = about_r + correction;
            (v, bound_about_r + correction_bound + UNIT_ROUNDOFF * v.abs())
        };
        let loose = volume_error_bound - bound_about_r
            > bound_about_r.max(LOOSE_BOUND * signed_volume.abs());
        VolumeFinish { signed_volume, volume_error_bound, about_r, bound_about_r, loose }
    }
}

/// The properties from the sums, and whether the volume's bound is loose (see
/// [`LOOSE_BOUND`]).
fn finish(
    faces: usize,
    r: Point,
    sums: &Partial,
    zero_vector_area: bool,
) -> (MassProperties, bool) {
    let VolumeFinish { signed_volume, volume_error_bound, about_r, bound_about_r, loose } =
        sums.volume.finish(faces, r, zero_vector_area);
    let six_volume = sums.volume.six_volume.value();

    let mut centroid = None;
    let mut inertia = [[0.0; 3]; 3];
    // Centroid and inertia from the moments about r (for a closed surface the same
    // solid as about the origin; see the module docs for an open one).
    if about_r.abs() > bound_about_r {
        let first = sums.first.map(|s| s.value());
        let c = scale(first, 1.0 / (4.0 * six_volume));
        // Covariance of the solid about its centroid, from the second moments about r.
        let m = sums.second.map(|s| s.value() / 120.0);
        let sign = about_r.signum();
        let cov = |k: usize, i: usize, j: usize| sign * (m[k] - about_r * c[i] * c[j]);
        let (xx, yy, zz) = (cov(0, 0, 0), cov(1, 1, 1), cov(2, 2, 2));
        let (xy, yz, zx) = (cov(3, 0, 1), cov(4, 1, 2), cov(5, 2, 0));
        inertia = [[yy + zz, -xy, -zx], [-xy, xx + zz, -yz], [-zx, -yz, xx + yy]];
        centroid = Some(add(r, c));
    }
    let properties = MassProperties {
        faces,
        triangles: sums.volume.triangles,
        signed_volume,
        volume_error_bound,
        area: sums.double_area.value() / 2.0,
        centroid,
        inertia,
        bounds: sums.bounds,
    };
    (properties, loose)
}

/// The nine terms a triangle `(a, b, c)` adds, times its determinant, to the first and
/// second moments: `s = a + (b + c)` and `a_i a_j + (b_i b_j + c_i c_j) + s_i s_j`, grouped
/// so that reversing the winding (swapping b and c) negates every term exactly. One body
/// for one triangle (f64) and for four at once (SIMD lanes): the same bits.
#[inline(always)]
fn moment_terms<T: Copy + Add<Output = T> + Mul<Output = T>>(
    a: [T; 3],
    b: [T; 3],
    c: [T; 3],
) -> [T; 9] {
    // Written out, not through `array::map` (see `volume::corners`).
    let s = [a[0] + (b[0] + c[0]), a[1] + (b[1] + c[1]), a[2] + (b[2] + c[2])];
    let pair = |i: usize, j: usize| a[i] * a[j] + (b[i] * b[j] + c[i] * c[j]) + s[i] * s[j];
    [s[0], s[1], s[2], pair(0, 0), pair(1, 1), pair(2, 2), pair(0, 1), pair(1, 2), pair(2, 0)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::every_copy;
    use crate::test_rng::XorShift;

    /// The baseline lanes (`wide`, what a CPU without AVX2 runs) give the bits of the
    /// AVX2 and AVX-512 copies (those this CPU has) and of the dispatched one, blocks,
    /// bounds' signed zeros and remainders included.
    #[test]
    fn baseline_and_dispatched_lanes_agree() {
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        // Some coordinates exactly ±0, for the bounds' zeros.
        let positions: Vec<Point> = (0..20_000)
            .map(|_| {
                [0; 3].map(|_| match rng.below(5) {
                    0 => 0.0,
                    1 => -0.0,
                    _ => (rng.unit() - 0.5) * 2f64.powi(rng.below(30) as i32 - 15),
                })
            })
            .collect();
        // Ids among the first 300 vertices, and last among all 20,000: scattered, so
        // that the indexed loop prefetches.
        let sizes = [1, 5, 8, 67, BLOCK_FACES + 3, 3 * BLOCK_FACES + 9, 3 * BLOCK_FACES + 9];
        for (n, ids) in sizes.into_iter().zip([300, 300, 300, 300, 300, 300, 20_000]) {
            let triangles: Vec<[u32; 3]> =
                (0..n).map(|_| [0; 3].map(|_| rng.below(ids) as u32)).collect();
            let r = positions[triangles[0][0] as usize];
            let corners = EachTriangle(|f: usize| triangles[f].map(|i: u32| positions[i as usize]));
            let indexed = Indexed { positions: &positions, triangles: &triangles };
            if n >= 64 {
                assert_eq!(indexed.scattered(0..n), ids > 300, "{n} triangles");
            }
            let mut copies = every_copy(TrianglesPartial { corners: &corners, range: 0..n, r });
            let baseline = copies.remove(0);
            copies.extend(every_copy(TrianglesPartial { corners: &indexed, range: 0..n, r }));
            copies.push(triangles_partial(&corners, 0..n, r));
            copies.push(triangles_partial(&indexed, 0..n, r));
            for copy in copies {
                assert_eq!(format!("{baseline:?}"), format!("{copy:?}"), "{n} triangles");
            }
        }
    }
}
