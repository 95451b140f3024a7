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
//!   (the k-th to sum k mod 4; `volume_sums::LaneSums`), merged in order: one SIMD lane each.
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

mod bounds;
mod partial;
mod triangles;

pub use crate::eigen::Principal;
pub use bounds::Bounds;

use crate::accumulate::{ordered_reduce_on, CHUNK_FACES, UNIT_ROUNDOFF};
use crate::mesh::only_triangle;
use crate::vector::{add, norm, scale};
use crate::volume_sums::{add_face_fan, VolumeFinish};
use crate::{Point, Surface};
use partial::{Partial, BLOCK_FACES};
use triangles::{triangles_partial, EachTriangle, Indexed};

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
            // The chunk's k-th triangle and k-th face to sum k mod 4 (`volume_sums::LaneSums`).
            let mut lanes = [Partial::default(); 4];
            let mut bounds = Bounds::of(r);
            let mut triangle = 0usize;
            for (k, face) in range.enumerate() {
                let (vector_area, magnitude, fan) = add_face_fan(surface, face, |a, b, c| {
                    let sums = &mut lanes[triangle % 4];
                    triangle += 1;
                    bounds.include(a);
                    bounds.include(b);
                    bounds.include(c);
                    sums.add_triangle(r, a, b, c)
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

/// The properties from the sums, and whether the volume's bound is loose (see
/// `volume_sums::LOOSE_BOUND`).
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
