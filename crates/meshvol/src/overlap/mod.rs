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
//! | prepare (once per body) | [`body`] | weld by exact coordinates, edges, vertex graph, box hierarchy in the body's own frame |
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
//! [`Degenerate`], and the caller measures by the grid method
//! ([`crate::grid::intersection`]), which resolves those. Bodies must be closed with
//! exactly equal shared vertices ([`Body::unfit`]), wound outward, and free of
//! self-crossings (insideness is the parity of crossings): the caller vouches for the
//! last from the check.

mod body;
mod pairs;
mod regions;

pub use body::Body;
pub use pairs::Degenerate;

use crate::accumulate::gamma;
use crate::assembly::Affine;
use crate::grid::intersect::moments::finish;
use crate::Point;
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
}

/// A∩B for `a` and `b` placed by their poses (`None`: where they are), or
/// [`Degenerate`] where the surfaces meet in a way this method does not settle, or a
/// body is [`Body::unfit`].
///
/// ```
/// use meshvol::overlap::{overlap, Body};
/// use meshvol::shapes::cuboid;
/// // Two 2×2×2 boxes, one turned a little about z and moved by (1, 1, 1).
/// let (a, b) = (Body::new(&cuboid([0.0; 3], [2.0; 3])), Body::new(&cuboid([0.0; 3], [2.0; 3])));
/// let (s, c) = (0.1f64.sin(), 0.1f64.cos());
/// let pose = meshvol::assembly::Affine([[c, -s, 0.0, 1.0], [s, c, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]]);
/// let o = overlap(&a, None, &b, Some(pose)).unwrap();
/// assert!(o.volume > 0.5 && o.volume < 1.0 && o.error < 1e-12);
/// ```
pub fn overlap(
    a: &Body,
    pose_a: Option<Affine>,
    b: &Body,
    pose_b: Option<Affine>,
) -> Result<Overlap, Degenerate> {
    if a.unfit().is_some() || b.unfit().is_some() {
        return Err(Degenerate);
    }
    let placed = [Placed::new(a, pose_a), Placed::new(b, pose_b)];
    let found = crossings(&placed[0], &placed[1])?;
    let origin = match (placed[0].bounds, placed[1].bounds) {
        (Some(p), Some(q)) => {
            [0, 1, 2].map(|k| 0.5 * (p.min[k].max(q.min[k]) + p.max[k].min(q.max[k])))
        }
        _ => [0.0; 3],
    };
    let mut parts = [Part::default(); 2];
    for s in 0..2 {
        let (this, other) = (&placed[s], &placed[1 - s]);
        let inside = inside_points(this, other, &found.cuts[s])?;
        parts[s] = inside_part(this, &inside, &found.cuts[s], &found.seams[s], origin);
    }
    let mut sums = [0.0; 10];
    for k in 0..10 {
        sums[k] = parts[0].sums[k] + parts[1].sums[k];
    }
    // Recursive sums of n terms are within γ(n − 1) of the sum of their magnitudes.
    let magnitude = parts[0].magnitude + parts[1].magnitude;
    let summing = gamma((parts[0].terms + parts[1].terms) as f64) * magnitude;
    let volume = sums[0];
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
    })
}

#[cfg(test)]
mod tests;
