//! The intersection A∩B of two closed bodies from their surfaces alone: its volume with
//! a bound on the rounding, its centroid and inertia, and the interface, in time linear
//! in the faces near the crossing curve plus one pass over each body.
//!
//! # Method
//! ∂(A∩B) is the part of ∂A inside B and the part of ∂B inside A (in general position:
//! no face of one touches the other's surface except by crossing it). By the divergence
//! theorem, the volume and moments of A∩B are integrals over those two parts, and each
//! face's share is an integral over the region of the face inside the other body. So no
//! boolean mesh is built:
//!
//! | stage | file | what |
//! |---|---|---|
//! | prepare (once per body) | [`body`], [`edges`] | weld by exact coordinates (or take the check's weld), edges, vertex graph, box hierarchy in the body's own frame |
//! | 1. crossings | [`pairs`] | pairs of faces whose boxes meet; exact tests of which edges cross which faces; the seams (pieces of the crossing curve), oriented |
//! | 2. inside points | [`regions`] | insideness carried along edges, flipping at crossings |
//! | 3. faces | [`regions`] | each face's region inside the other, from its seams and the inside pieces of its edges, integrated as a signed fan |
//!
//! Every decision (which faces cross, which edges pass through which faces, which
//! points are inside) is an exact predicate on the placed coordinates, so the result
//! is the integral over the exact ∂(A∩B) of the bodies as placed, up to the rounding
//! of the crossing points and the sums, which [`Overlap::error`] bounds.
//!
//! # What it does not settle
//! A corner of one body on the other's plane where their faces meet, an edge through
//! another's edge, coplanar overlapping faces: any exact zero among the tests gives
//! [`Degenerate`]. Touching at points or along lines is settled by moving B off by a
//! hair and bounding what the move changes ([`overlap`]); faces in one plane are left
//! to the grid method ([`crate::grid::intersection`]), which resolves them. Bodies must be closed with
//! exactly equal shared vertices ([`Body::unfit`]), wound outward, and free of
//! self-crossings (insideness is the parity of crossings): the caller vouches for the
//! last from the check.

mod body;
mod edges;
mod pairs;
mod regions;

pub use body::Body;
pub use pairs::Degenerate;

use crate::accumulate::{gamma, UNIT_ROUNDOFF};
use crate::assembly::Affine;
use crate::grid::piece_moments::finish;
use crate::topology::predicates::OBLIQUE;
use crate::vector::{norm, scale};
use crate::{Bounds, MassProperties, Point};
use pairs::{crossings, Placed};
use regions::{inside_part, inside_points, Part};

/// A∩B measured from the bodies' surfaces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overlap {
    /// |A∩B|, within `error` of the exact volume of the placed bodies' intersection.
    pub volume: f64,
    pub error: f64,
    /// The centroid and the inertia about it (unit density) of A∩B; `None` without
    /// volume.
    pub centroid: Option<Point>,
    pub inertia: Option<[[f64; 3]; 3]>,
    /// Area of ∂A inside B plus ∂B inside A.
    pub contact_area: f64,
    /// ∫ n dA over ∂B inside A, and over ∂A inside B.
    pub contact_vector: Point,
    pub contact_vector_a: Point,
    /// The mass properties of A and B as placed ([`Body`]'s own, moved, with the box
    /// of the moved points).
    pub properties: [MassProperties; 2],
}

/// A∩B for `a` and `b` placed by their poses (`None`: where they are), or why the
/// boundary method does not settle it ([`Degenerate`]).
///
/// Where the surfaces only touch at points or along lines ([`Degenerate::Touching`]:
/// say two copies of a sphere whose latitude rings lie in the same planes), B is moved
/// off by a hair (2⁻⁴⁶ of the largest coordinate, in a direction no axis or diagonal
/// lines up with) and measured again: A∩B changes by at most the volume B sweeps, which
/// lies within the Minkowski sum of B's surface with a ball of the move's radius d, so
/// the error grows by Σ over B's triangles of 2d·area + (π/2)d²·perimeter + (4π/3)d³.
///
/// ```
/// use meshvol::overlap::{overlap, Body};
/// use meshvol::shapes::cuboid;
/// // Two 2×2×2 boxes, one turned a little about z and moved by (1, 1, 1).
/// let (a, b) = (Body::new(&cuboid([0.0; 3], [2.0; 3])), Body::new(&cuboid([0.0; 3], [2.0; 3])));
/// let (s, c) = 0.1f64.sin_cos();
/// let pose = meshvol::assembly::Affine([[c, -s, 0.0, 1.0], [s, c, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]]);
/// let o = overlap(&a, None, &b, Some(pose)).unwrap();
/// // About the unit cube [1, 2]³, a little more where the turned side reaches past x = 1.
/// assert!(o.volume > 0.9 && o.volume < 1.1 && o.error < 1e-10, "{o:?}");
/// ```
pub fn overlap(
    a: &Body,
    pose_a: Option<Affine>,
    b: &Body,
    pose_b: Option<Affine>,
) -> Result<Overlap, Degenerate> {
    if a.unfit().is_some() || b.unfit().is_some() {
        return Err(Degenerate::Unfit);
    }
    let placed_a = Placed::new(a, pose_a, [0.0; 3]);
    let placed_b = Placed::new(b, pose_b, [0.0; 3]);
    let properties = [
        a.placed_properties(pose_a, placed_a.bounds, placed_a.own_reach),
        b.placed_properties(pose_b, placed_b.bounds, placed_b.own_reach),
    ];
    if apart(placed_a.bounds, placed_b.bounds) {
        return Ok(Overlap {
            volume: 0.0,
            error: 0.0,
            centroid: None,
            inertia: None,
            contact_area: 0.0,
            contact_vector: [0.0; 3],
            contact_vector_a: [0.0; 3],
            properties,
        });
    }
    match measure(&placed_a, &placed_b, properties) {
        Err(Degenerate::Touching) => {}
        settled => return settled,
    }
    let reach = placed_a.reach.max(placed_b.reach);
    for direction in NUDGES {
        let shift = scale(direction, HAIR * reach);
        match measure(&placed_a, &Placed::new(b, pose_b, shift), properties) {
            Ok(mut o) => {
                // The move, and the rounding of the moved coordinates.
                o.error += b.swept(norm(shift) + 8.0 * UNIT_ROUNDOFF * reach);
                return Ok(o);
            }
            Err(Degenerate::Touching) => continue,
            Err(other) => return Err(other),
        }
    }
    Err(Degenerate::Touching)
}

/// Whether closed boxes are apart or only touch (no common volume).
fn apart(p: Option<Bounds>, q: Option<Bounds>) -> bool {
    match (p, q) {
        (Some(p), Some(q)) => (0..3).any(|k| p.max[k] <= q.min[k] || q.max[k] <= p.min[k]),
        _ => true,
    }
}

/// The size of the move off a touching position, relative to the largest coordinate.
const HAIR: f64 = 1.0 / (1u64 << 46) as f64;

/// The directions of the moves tried (unit vectors no axis, diagonal or simple ratio
/// lines up with).
const NUDGES: [Point; 2] =
    [OBLIQUE, [-0.3265986323710904, 0.7348469228349535, -0.5943889992637929]];

/// The boundary method on placed bodies.
fn measure(a: &Placed, b: &Placed, properties: [MassProperties; 2]) -> Result<Overlap, Degenerate> {
    let found = crossings(a, b)?;
    let origin = match (a.bounds, b.bounds) {
        (Some(p), Some(q)) => {
            [0, 1, 2].map(|k| 0.5 * (p.min[k].max(q.min[k]) + p.max[k].min(q.max[k])))
        }
        _ => [0.0; 3],
    };
    // Each body's part on its own thread: neither reads the other's.
    let part = |s: usize, this: &Placed, other: &Placed| -> Result<Part, Degenerate> {
        let inside = inside_points(this, other, &found.cuts[s])?;
        Ok(inside_part(this, &inside, &found.cuts[s], &found.seams[s], origin))
    };
    let (part_a, part_b) = rayon::join(|| part(0, a, b), || part(1, b, a));
    let parts = [part_a?, part_b?];
    let mut sums = [0.0; 10];
    for k in 1..10 {
        sums[k] = parts[0].sums[k] + parts[1].sums[k];
    }
    let mut volume6 = parts[0].volume6;
    volume6.merge(&parts[1].volume6);
    let volume = volume6.value() / 6.0;
    sums[0] = volume;
    // A compensated sum of n terms is within u|Σ| + γ(n − 1)²·Σ|terms| (accumulate's
    // docs); the division by 6 rounds once more.
    let magnitude = parts[0].magnitude + parts[1].magnitude;
    let n = (parts[0].terms + parts[1].terms) as f64;
    let summing = (UNIT_ROUNDOFF * volume6.value().abs() + gamma(n).powi(2) * magnitude) / 6.0
        + UNIT_ROUNDOFF * volume.abs();
    let error = 2.0 * (parts[0].error + parts[1].error + summing);
    let moments = finish(&sums, origin);
    Ok(Overlap {
        volume,
        error,
        centroid: moments.map(|m| m.1),
        inertia: moments.map(|m| m.2),
        contact_area: parts[0].area + parts[1].area,
        contact_vector: parts[1].vector,
        contact_vector_a: parts[0].vector,
        properties,
    })
}

#[cfg(test)]
mod body_tests;
#[cfg(test)]
mod tests;
