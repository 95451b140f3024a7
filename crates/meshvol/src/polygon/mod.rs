//! Plane polygons with holes: area, perimeter, centroid and second moments, and the
//! checks that say whether those numbers mean what they seem to.
//!
//! # Math
//! Green's theorem turns each integral over a region into a sum over its boundary edges.
//! For an edge from a = (x₀, y₀) to b = (x₁, y₁), with k = x₀y₁ − x₁y₀ (twice the signed
//! area of the triangle (0, a, b)):
//!
//! - area:           A     = Σ k / 2
//! - first moments:  ∫x dA = Σ (x₀ + x₁) k / 6,  ∫y dA = Σ (y₀ + y₁) k / 6
//! - second moments: ∫x² dA = Σ (x₀² + x₀x₁ + x₁²) k / 12, ∫y² dA likewise,
//!   ∫xy dA = Σ (2x₀y₀ + x₀y₁ + x₁y₀ + 2x₁y₁) k / 24
//!
//! A ring's sums are signed by its winding: positive counter-clockwise. A region counts
//! once whatever its rings' windings: each [`Polygon`]'s exterior adds |its sums| and each
//! hole subtracts |its sums| (the sums of a ring are all multiplied by the sign of its
//! area, then by +1 or −1 for its role). The polygons of a set add up, so polygons that
//! overlap each other count twice: [`polygon_issues`] reports them.
//!
//! [`SecondMoments`] are about the centroid c: `ix` = ∫(y − c_y)² dA (about the axis
//! through c parallel to x), `iy` = ∫(x − c_x)² dA, the product `ixy` = ∫(x − c_x)(y − c_y) dA
//! and the polar moment `ix + iy`.
//!
//! # Accuracy
//! Coordinates in survey systems (UTM, state plane) are 10⁶–10⁷ while parcels are
//! 10–10³ wide: the naive shoelace Σ x₀y₁ − x₁y₀ adds and cancels products of 10¹⁴,
//! whose rounding (≈ 0.02 each) swamps the area's last digits. Here:
//!
//! - Every ring is summed about its own first vertex r: `x − r` is exact whenever x and
//!   r are within a factor of two (Sterbenz), which holds for any parcel far from the
//!   origin, so the terms are the size of the parcel, not of its offset.
//! - k is computed with fused multiply-adds (Kahan's 2×2 determinant: error below
//!   1.5 ulp of k itself, however much x₀y₁ and x₁y₀ cancel), and every sum is a
//!   [`CompensatedSum`](crate::accumulate::CompensatedSum).
//! - The second moments are summed in a second pass about the centroid itself, never
//!   shifted with the parallel-axis theorem (which subtracts two large numbers).
//!
//! The area of a ring with coordinates of at most 2²⁶ units after the translation comes
//! out correctly rounded in practice; the tests compare with exact integer arithmetic.
//!
//! # Stages and files
//!
//! | what | file |
//! | --- | --- |
//! | [`Polygon`] and [`Point2`] | `mod.rs` |
//! | area, perimeter, centroid and second moments ([`area_properties`]) | `area.rs` |
//! | whether rings are simple and holes inside ([`polygon_issues`]): the sweep | `validity.rs` |

mod area;
mod validity;

pub use area::{
    area_properties, signed_area, AreaProperties, RingProperties, RingRole, SecondMoments,
};
pub(crate) use validity::point_in_ring;
pub use validity::{polygon_issues, PolygonIssue, MAX_EDGE_PAIR_TESTS};

/// A point in the plane.
pub type Point2 = [f64; 2];

/// A polygon: one exterior ring and any number of holes.
///
/// Rings are open: the last vertex is not a copy of the first (readers drop a closing
/// copy; a copy left in adds a zero-length edge, which changes nothing). Any winding is
/// accepted; holes subtract whatever their winding.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polygon {
    pub exterior: Vec<Point2>,
    pub holes: Vec<Vec<Point2>>,
}

impl Polygon {
    pub fn new(exterior: Vec<Point2>, holes: Vec<Vec<Point2>>) -> Polygon {
        Polygon { exterior, holes }
    }

    /// The rings in order: the exterior (ring 0), then the holes (rings 1, 2, …).
    pub fn rings(&self) -> impl Iterator<Item = &[Point2]> {
        std::iter::once(self.exterior.as_slice()).chain(self.holes.iter().map(Vec::as_slice))
    }
}
