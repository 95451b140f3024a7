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
//! A face's area is the length of its vector area (half the sum of its fan triangles'
//! cross products: Newell's formula), never the sum of the fan triangles' areas, which
//! overcounts non-convex and non-planar faces.
//!
//! # Accuracy
//! - r is a vertex of the surface, never the world origin: the terms stay the size of the
//!   mesh, not of its offset, so a part at 10⁷ keeps all the digits of a part at 0.
//! - Every sum is compensated (TwoSum) and the chunks combine in a fixed order: the same
//!   bits for any thread count.
//! - `volume_error_bound` bounds |computed − exact| for the polyhedron the f64
//!   coordinates describe: each D carries at most 8 roundings (3 subtractions of r,
//!   the cross and dot products), so |D̂ − D| ≤ γ(8)·P with P = Σ|aᵢ||bⱼ||cₖ| over the
//!   determinant's six terms; the compensated sum adds u·|ΣD| + γ(n)²·Σ|D|; the final
//!   division by 6 adds u·|V|. (γ(n) = n·u/(1 − n·u), u = 2⁻⁵³.) The bound is evaluated
//!   with a little headroom for its own rounding.

use crate::accumulate::{gamma, ordered_reduce, CompensatedSum, UNIT_ROUNDOFF};
use crate::vector::{add, cross, dot, norm, scale, sub};
use crate::{Point, Surface};

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
    /// Σ of signed tetrahedron volumes as the surface is wound: positive for outward
    /// normals.
    pub signed_volume: f64,
    /// A bound on |`signed_volume` − the exact signed volume of the polyhedron given by
    /// the f64 coordinates|.
    pub volume_error_bound: f64,
    /// Total face area.
    pub area: f64,
    /// The centroid of the solid; `None` when the volume is not distinguishable from 0.
    pub centroid: Option<Point>,
    /// Inertia tensor about the centroid for unit density (scale by the density for a
    /// body); zero when the centroid is `None`.
    pub inertia: [[f64; 3]; 3],
    /// Bounds of the surface's vertices; `None` for an empty surface.
    pub bounds: Option<Bounds>,
}

impl MassProperties {
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

/// Per-chunk running sums. The volume, whose error bound is reported, is compensated
/// term by term; the moments and area (no published bound) are summed plainly within
/// blocks of [`BLOCK_FACES`] faces and compensated across blocks, which keeps them
/// accurate to about γ(64) of their terms at a fraction of the cost.
#[derive(Clone, Copy, Default)]
struct Partial {
    six_volume: CompensatedSum,
    first: [CompensatedSum; 3],
    /// xx, yy, zz, xy, yz, zx.
    second: [CompensatedSum; 6],
    double_area: CompensatedSum,
    /// The current block's plain sums: first moments, second moments, double area.
    block: [f64; 10],
    /// Σ P, for the error bound.
    determinant_magnitude: f64,
    /// Σ |D|, for the error bound.
    abs_six_volume: f64,
    triangles: usize,
    bounds: Option<Bounds>,
}

impl Partial {
    pub(crate) fn merge(&mut self, o: Partial) {
        self.six_volume.merge(&o.six_volume);
        for (a, b) in self.first.iter_mut().zip(&o.first) {
            a.merge(b);
        }
        for (a, b) in self.second.iter_mut().zip(&o.second) {
            a.merge(b);
        }
        self.double_area.merge(&o.double_area);
        self.determinant_magnitude += o.determinant_magnitude;
        self.abs_six_volume += o.abs_six_volume;
        self.triangles += o.triangles;
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

    #[inline(always)]
    fn add_triangle(&mut self, a: Point, b: Point, c: Point) {
        let bc = cross(b, c);
        let d = dot(a, bc);
        let abs = |p: Point| [p[0].abs(), p[1].abs(), p[2].abs()];
        let (aa, ba, ca) = (abs(a), abs(b), abs(c));
        let permanent = aa[0] * (ba[1] * ca[2] + ba[2] * ca[1])
            + aa[1] * (ba[2] * ca[0] + ba[0] * ca[2])
            + aa[2] * (ba[0] * ca[1] + ba[1] * ca[0]);
        self.six_volume.add(d);
        self.abs_six_volume += d.abs();
        self.determinant_magnitude += permanent;
        // Grouped as a + (b + c) so that reversing the winding (swapping b and c)
        // negates every term exactly.
        let s = add(a, add(b, c));
        let pair = |i: usize, j: usize| a[i] * a[j] + (b[i] * b[j] + c[i] * c[j]) + s[i] * s[j];
        let terms = [
            s[0],
            s[1],
            s[2],
            pair(0, 0),
            pair(1, 1),
            pair(2, 2),
            pair(0, 1),
            pair(1, 2),
            pair(2, 0),
        ];
        for (sum, t) in self.block.iter_mut().zip(terms) {
            *sum += d * t;
        }
        self.triangles += 1;
    }
}

/// The first vertex of the first face: the reference point sums are taken about.
fn reference_point<S: Surface + ?Sized>(surface: &S) -> Option<Point> {
    let mut r = None;
    if surface.face_count() > 0 {
        surface.fan(0, |a, _, _| r = r.or(Some(a)));
    }
    r
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
    let Some(r) = reference_point(surface) else {
        return MassProperties {
            faces,
            triangles: 0,
            signed_volume: 0.0,
            volume_error_bound: 0.0,
            area: 0.0,
            centroid: None,
            inertia: [[0.0; 3]; 3],
            bounds: None,
        };
    };
    let sums = ordered_reduce(
        faces,
        CHUNK_FACES,
        |range| {
            let mut part = Partial::default();
            let mut bounds = Bounds::of(r);
            for face in range {
                let mut vector_area = [0.0; 3];
                surface.fan(face, |a, b, c| {
                    vector_area = add(vector_area, cross(sub(b, a), sub(c, a)));
                    bounds.include(a);
                    bounds.include(b);
                    bounds.include(c);
                    part.add_triangle(sub(a, r), sub(b, r), sub(c, r));
                });
                part.block[9] += norm(vector_area);
                if face % BLOCK_FACES == BLOCK_FACES - 1 {
                    part.flush_block();
                }
            }
            part.flush_block();
            part.bounds = Some(bounds);
            part
        },
        Partial::merge,
    )
    .unwrap_or_default();
    finish(faces, r, &sums)
}

fn finish(faces: usize, r: Point, sums: &Partial) -> MassProperties {
    let n = sums.triangles as f64;
    let six_volume = sums.six_volume.value();
    let signed_volume = six_volume / 6.0;
    let six_bound = gamma(8.0) * sums.determinant_magnitude
        + UNIT_ROUNDOFF * six_volume.abs()
        + gamma(n).powi(2) * sums.abs_six_volume;
    // (1 + γ(n + 8)) covers the rounding of the bound's own sums.
    let volume_error_bound =
        six_bound * (1.0 + gamma(n + 8.0)) / 6.0 + UNIT_ROUNDOFF * signed_volume.abs();

    let mut centroid = None;
    let mut inertia = [[0.0; 3]; 3];
    if signed_volume.abs() > volume_error_bound {
        let first = sums.first.map(|s| s.value());
        let c = scale(first, 1.0 / (4.0 * six_volume));
        // Covariance of the solid about its centroid, from the second moments about r.
        let m = sums.second.map(|s| s.value() / 120.0);
        let sign = signed_volume.signum();
        let cov = |k: usize, i: usize, j: usize| sign * (m[k] - signed_volume * c[i] * c[j]);
        let (xx, yy, zz) = (cov(0, 0, 0), cov(1, 1, 1), cov(2, 2, 2));
        let (xy, yz, zx) = (cov(3, 0, 1), cov(4, 1, 2), cov(5, 2, 0));
        inertia = [[yy + zz, -xy, -zx], [-xy, xx + zz, -yz], [-zx, -yz, xx + yy]];
        centroid = Some(add(r, c));
    }
    MassProperties {
        faces,
        triangles: sums.triangles,
        signed_volume,
        volume_error_bound,
        area: sums.double_area.value() / 2.0,
        centroid,
        inertia,
        bounds: sums.bounds,
    }
}
