//! The volume of the intersection of two closed bodies, without a boolean mesh, as a
//! certified interval; with it the union, the differences, IoU and Dice.
//!
//! # Method
//! The intersection is the union's machinery ([`super::union`]) with the other rule,
//! stage for stage:
//!
//! - **Grid.** A∩B lies in the common box of A's and B's boxes; the base grid covers
//!   that box with room (10⁻⁶ of its longest side) on every side, so no piece of ∂(A∩B)
//!   lies on the grid's faces. Boxes apart (or only touching: the common box is flat)
//!   give exactly 0 with no grid at all.
//! - **Bounds per cell.** A body that does not touch cell C holds all of it or none. If
//!   one of them holds none, A∩B misses C: exactly 0. Otherwise the bodies not touching
//!   C fill it and the intersection in C is that of the touching ones: `|C|` for none,
//!   `v` for one, and for t ≥ 2 touching bodies
//!   `max(0, Σ v_i − (t − 1)|C|) ≤ vol(∩ ∩ C) ≤ min_i v_i` (Bonferroni).
//! - **Refinement** of open cells, exactly as for the union, with these bounds; but
//!   where the moments are wanted (always, from [`intersection`]), every column is
//!   resolved exactly for them anyway, so that pass settles the open columns and
//!   nothing is refined (refinement only narrows what resolution then closes). Where a
//!   column fails to resolve, the interval is found by refinement and resolution as
//!   for the union.
//! - **Exact resolution.** ∂(A∩B) is the part of ∂A inside B and the part of ∂B inside
//!   A. Each piece of a triangle in an open cell is split along the other body's
//!   triangles as for the union, and a sub-piece is kept when, for the other body:
//!   it lies on a triangle of it facing the same way and belongs to the first body
//!   (one copy of a shared boundary), or, off its faces, a vertical ray from its
//!   centroid crosses its triangles with signed crossings summing to more than 0
//!   (inside). Sub-pieces on a face of the other body facing the opposite way (bodies
//!   glued face to face: the intersection has no volume there) are dropped. A piece in a
//!   cell the other body misses is dropped; in a cell it fills without touching, kept.
//!   Pieces above the grid's top (outside the common box) are dropped. The column–clamp
//!   integral of the kept pieces is the intersection's volume in each cell.
//!
//! # Moments
//! The kept pieces of every column of the grid are ∂(A∩B) (its vertical faces aside,
//! which add nothing below): so the same resolution run over every column, with the
//! vertical fields of [`super::piece_moments`] integrated over the kept pieces, gives the volume,
//! the centroid and the inertia of A∩B by the divergence theorem. Their volume must lie
//! in the interval (within 10⁻⁹ of it); otherwise, or if a column fails to resolve, no
//! moments are given.
//!
//! # Contact
//! The same kept pieces, those of one body inside the other, are the interface: their
//! area and vector area (∫ n dA over ∂B inside A, the derivative of the overlap under a
//! translation of B) are added up in the same pass; the faces the plan pass sees badly
//! are counted in two more passes with the bodies' axes turned ([`contact`]), each on
//! the columns of the full grid that hold such faces only.
//!
//! # Interval
//! `[lower, upper]` adds exact columns, exact cells and open leaves' bounds, is clamped
//! to `[0, min(|A|, |B|)]`, and is widened for rounding by `2⁻³⁶ · Σ ∫|n_z| dA · H` over
//! the faces that meet the grid (H its height), as for the union. The union, the
//! differences, IoU and Dice follow from it and the bodies' volumes:
//! `|A∪B| = |A| + |B| − |A∩B|`, `|A∖B| = |A| − |A∩B|`,
//! `IoU = |A∩B| / |A∪B|`, `Dice = 2|A∩B| / (|A| + |B|)`; their intervals widen by the
//! volumes' rounding bounds.

pub(crate) mod contact;

pub use contact::Contact;

use super::union::{boundary_in_frame, combine, Rule, UnionError};
use super::union::{counted_in, Frame, Interface};
use super::Grid;
use crate::assembly::Affine;
use crate::overlap::{overlap, Body, Overlap};
use crate::progress::Progress;
use crate::surface::Moved;
use crate::vector::{cross, sub};
use crate::{mass_properties, Bounds, MassProperties, Point, Surface};

/// The intersection of two bodies: the certified interval of its volume, the bodies'
/// volumes, and how the interval was found.
#[derive(Clone, Debug, PartialEq)]
pub struct Intersection {
    /// `lower ≤ |A∩B| ≤ upper`.
    pub lower: f64,
    pub upper: f64,
    /// |A| and |B| (each |signed volume|), and bounds on their rounding.
    pub volume_a: f64,
    pub volume_b: f64,
    pub error_a: f64,
    pub error_b: f64,
    /// Cells cut into 2×2×2 children.
    pub cells_refined: usize,
    /// Open cells of the base grid resolved exactly.
    pub cells_resolved_exactly: usize,
    /// Columns that could not be resolved: their bounds stay in the interval.
    pub columns_unresolved: usize,
    /// The bodies' boxes are apart or only touch: the volume is 0, found with no grid.
    pub disjoint: bool,
    /// The base grid (1×1×1 when disjoint).
    pub grid: Grid,
    /// Bodies (0: A, 1: B) wound inward, measured turned outward.
    pub flipped: Vec<usize>,
    /// Bodies found not to be closed solids ([`super::UnionVolume::bodies_not_solid`]):
    /// the interval is then ordered, not certified.
    pub bodies_not_solid: Vec<usize>,
    /// The moments of A∩B from its boundary (module docs, `grid::piece_moments`); `None` for no
    /// volume, or where a column could not be resolved.
    pub moments: Option<Moments>,
    /// The interface of A and B ([`contact`]): zero when the boxes are apart or touch;
    /// `None` where the moments are not given, or a column of one of the three frames
    /// could not be resolved.
    pub contact: Option<Contact>,
    /// How it was measured.
    pub method: Method,
}

/// The volume, centroid and inertia (about the centroid, unit density) of A∩B.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moments {
    /// The volume the moments were integrated with (inside the interval).
    pub volume: f64,
    pub centroid: Point,
    pub inertia: [[f64; 3]; 3],
}

/// A value and the interval that holds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounded {
    pub value: f64,
    pub lower: f64,
    pub upper: f64,
}

impl Intersection {
    /// The midpoint of the interval.
    pub fn volume(&self) -> f64 {
        0.5 * (self.lower + self.upper)
    }

    /// |A∪B| = |A| + |B| − |A∩B|.
    pub fn union(&self) -> Bounded {
        let (s, e) = (self.volume_a + self.volume_b, self.error_a + self.error_b);
        Bounded { value: s - self.volume(), lower: s - e - self.upper, upper: s + e - self.lower }
    }

    /// |A∖B| = |A| − |A∩B|.
    pub fn a_minus_b(&self) -> Bounded {
        difference(self.volume_a, self.error_a, self)
    }

    /// |B∖A| = |B| − |A∩B|.
    pub fn b_minus_a(&self) -> Bounded {
        difference(self.volume_b, self.error_b, self)
    }

    /// Intersection over union, in [0, 1]; 0 when the union has no volume.
    pub fn iou(&self) -> Bounded {
        let u = self.union();
        let ratio = |i: f64, u: f64| if u > 0.0 { (i / u).clamp(0.0, 1.0) } else { 0.0 };
        Bounded {
            value: ratio(self.volume(), u.value),
            lower: ratio(self.lower, u.upper),
            upper: if u.lower > 0.0 { ratio(self.upper, u.lower) } else { 1.0 },
        }
    }

    /// Dice (Sørensen) coefficient 2|A∩B| / (|A| + |B|), in [0, 1].
    pub fn dice(&self) -> Bounded {
        let (s, e) = (self.volume_a + self.volume_b, self.error_a + self.error_b);
        let ratio = |i: f64, s: f64| if s > 0.0 { (2.0 * i / s).clamp(0.0, 1.0) } else { 0.0 };
        Bounded {
            value: ratio(self.volume(), s),
            lower: ratio(self.lower, s + e),
            upper: if s - e > 0.0 { ratio(self.upper, s - e) } else { 1.0 },
        }
    }
}

fn difference(volume: f64, error: f64, i: &Intersection) -> Bounded {
    Bounded {
        value: (volume - i.volume()).max(0.0),
        lower: (volume - error - i.upper).max(0.0),
        upper: (volume + error - i.lower).max(0.0),
    }
}

/// The volume of A∩B (each a closed surface; one wound inward is turned outward and
/// listed in `flipped`), refined to within `tolerance` of the lower bound where
/// refinement and exact resolution allow. See the module docs.
///
/// ```
/// use meshvol::grid::intersection;
/// use meshvol::shapes::cuboid;
/// // Two 2×2×2 boxes overlapping in a unit cube.
/// let a = cuboid([0.0; 3], [2.0; 3]);
/// let b = cuboid([1.0; 3], [3.0; 3]);
/// let i = intersection(&a, &b, 1e-9).unwrap();
/// assert!(i.lower <= 1.0 && 1.0 <= i.upper && i.upper - i.lower < 1e-8);
/// assert!((i.iou().value - 1.0 / 15.0).abs() < 1e-9);
/// ```
pub fn intersection<S: Surface>(a: &S, b: &S, tolerance: f64) -> Result<Intersection, UnionError> {
    intersection_with(a, b, tolerance, &())
}

/// [`intersection`], telling `progress` its stages (as [`super::union_with`]).
pub fn intersection_with<S: Surface>(
    a: &S,
    b: &S,
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<Intersection, UnionError> {
    let start = Start::of(a, b);
    match start.disjoint_result() {
        Some(i) => Ok(i),
        None => by_grid(a, b, start, tolerance, progress),
    }
}

/// How an intersection was measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// The bodies' boxes are apart or only touch: nothing to measure.
    Boxes,
    /// From the faces' regions inside the other body ([`crate::overlap`]).
    Boundary,
    /// On a grid over the common box (this module's method).
    Grid,
}

impl Method {
    /// `boxes`, `boundary` or `grid`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Boxes => "boxes",
            Method::Boundary => "boundary",
            Method::Grid => "grid",
        }
    }
}

/// [`intersection_with`] for bodies placed by poses (`None`: where they are), where
/// `bodies` are `a` and `b` prepared for the boundary method ([`Body::new`]) when the
/// caller vouches that they are solids without self-crossings (the check found none).
/// The boundary method measures them where it settles the pose (faces in general
/// position, both wound outward); the grid method otherwise, and for unprepared bodies.
/// Either way the interval holds the exact volume of the placed bodies' intersection.
pub fn intersection_placed<S: Surface>(
    a: &S,
    b: &S,
    bodies: [Option<&Body>; 2],
    poses: [Option<Affine>; 2],
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<Intersection, UnionError> {
    if let [Some(body_a), Some(body_b)] = bodies {
        if let Ok(o) = overlap(body_a, poses[0], body_b, poses[1]) {
            let [pa, pb] = o.properties;
            let start = Start::from(pa, pb);
            if let Some(i) = start.disjoint_result() {
                return Ok(i);
            }
            if start.flipped.is_empty() {
                return Ok(start.measured_by_boundary(&o));
            }
        }
    }
    let (a, b) = (Moved::new(a, poses[0]), Moved::new(b, poses[1]));
    let start = Start::of(&a, &b);
    match start.disjoint_result() {
        Some(i) => Ok(i),
        None => by_grid(&a, &b, start, tolerance, progress),
    }
}

/// What both methods need first: the bodies' mass properties, and whether their boxes
/// are apart.
struct Start {
    pa: MassProperties,
    pb: MassProperties,
    disjoint: bool,
    flipped: Vec<usize>,
}

impl Start {
    fn of<S: Surface>(a: &S, b: &S) -> Start {
        Start::from(mass_properties(a), mass_properties(b))
    }

    fn from(pa: MassProperties, pb: MassProperties) -> Start {
        let disjoint = match (pa.bounds, pb.bounds) {
            (Some(p), Some(q)) => (0..3).any(|k| p.max[k] <= q.min[k] || q.max[k] <= p.min[k]),
            _ => true,
        };
        let flipped: Vec<usize> = [&pa, &pb]
            .iter()
            .enumerate()
            .filter(|(_, p)| p.signed_volume < 0.0)
            .map(|(n, _)| n)
            .collect();
        Start { pa, pb, disjoint, flipped }
    }

    /// An intersection with nothing measured yet: the bodies' volumes, no grid.
    fn unmeasured(&self, method: Method) -> Intersection {
        Intersection {
            lower: 0.0,
            upper: 0.0,
            volume_a: self.pa.signed_volume.abs(),
            volume_b: self.pb.signed_volume.abs(),
            error_a: self.pa.volume_error_bound,
            error_b: self.pb.volume_error_bound,
            cells_refined: 0,
            cells_resolved_exactly: 0,
            columns_unresolved: 0,
            disjoint: self.disjoint,
            grid: Grid { origin: [0.0; 3], cell: [1.0; 3], counts: [1, 1, 1] },
            flipped: self.flipped.clone(),
            bodies_not_solid: Vec::new(),
            moments: None,
            contact: None,
            method,
        }
    }

    /// Exactly 0 when the boxes are apart or only touch.
    fn disjoint_result(&self) -> Option<Intersection> {
        self.disjoint.then(|| Intersection {
            contact: Some(Contact { area: 0.0, vector: [0.0; 3], vector_a: [0.0; 3] }),
            ..self.unmeasured(Method::Boxes)
        })
    }

    /// The boundary method's measure as an intersection.
    fn measured_by_boundary(&self, o: &Overlap) -> Intersection {
        let moments = o.centroid.zip(o.inertia).map(|(centroid, inertia)| Moments {
            volume: o.volume,
            centroid,
            inertia,
        });
        Intersection {
            lower: (o.volume - o.error).max(0.0),
            upper: o.volume + o.error,
            moments,
            contact: Some(Contact {
                area: o.contact_area,
                vector: o.contact_vector,
                vector_a: o.contact_vector_a,
            }),
            ..self.unmeasured(Method::Boundary)
        }
    }
}

/// The grid method (module docs) on bodies whose boxes overlap.
fn by_grid<S: Surface>(
    a: &S,
    b: &S,
    start: Start,
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<Intersection, UnionError> {
    let Start { pa, pb, disjoint, flipped } = start;
    let (u, sums) = combine(&[a, b], &[pa, pb], Rule::Intersection, tolerance, true, progress)?;
    let interface_z = sums.as_ref().map(|(_, total)| total.interface());
    let moments = sums
        .and_then(|(origin, sums)| super::piece_moments::finish(&sums.moments(), origin))
        .and_then(|(volume, centroid, inertia)| {
            // The same pieces' volume: it must agree with the interval, else the
            // classification went wrong somewhere and the moments are not given.
            let slack = 1e-9 * u.upper.max(f64::MIN_POSITIVE);
            (u.lower - slack <= volume && volume <= u.upper + slack).then_some(Moments {
                volume,
                centroid,
                inertia,
            })
        });
    // Steep faces (module docs of [`contact`]) are counted with the bodies turned, in
    // the frames some face of theirs in the common box is counted in.
    let contact = match (&moments, interface_z) {
        (Some(_), Some(z)) => {
            let common = (pa.bounds, pb.bounds);
            let mut parts = vec![z];
            let mut resolved = true;
            for frame in [Frame::XUp, Frame::YUp] {
                if !counts_in(a, frame, common) && !counts_in(b, frame, common) {
                    continue;
                }
                let turned = [Moved::new(a, frame.turn()), Moved::new(b, frame.turn())];
                let properties = [&pa, &pb].map(|p| turned_properties(p, frame));
                match boundary_in_frame(&turned, &properties, Rule::Intersection, frame, progress)?
                {
                    Some(total) => parts.push(total.interface()),
                    None => resolved = false,
                }
            }
            resolved.then(|| Contact::from_interface(&Interface::total(&parts)))
        }
        _ => None,
    };
    Ok(Intersection {
        lower: u.lower,
        upper: u.upper,
        volume_a: pa.signed_volume.abs(),
        volume_b: pb.signed_volume.abs(),
        error_a: pa.volume_error_bound,
        error_b: pb.volume_error_bound,
        cells_refined: u.cells_refined,
        cells_resolved_exactly: u.cells_resolved_exactly,
        columns_unresolved: u.columns_unresolved,
        disjoint,
        grid: u.grid,
        flipped,
        bodies_not_solid: u.bodies_not_solid,
        moments,
        contact,
        method: Method::Grid,
    })
}

/// The mass properties of a body turned into `frame` (a permutation of the axes, so
/// its box, centroid and inertia are `p`'s with their axes permuted, exactly), without
/// measuring the turned body again.
pub(crate) fn turned_properties(p: &MassProperties, frame: Frame) -> MassProperties {
    let turn = frame.turn().unwrap_or(Affine::IDENTITY);
    MassProperties {
        bounds: p.bounds.map(|b| Bounds { min: turn.apply(b.min), max: turn.apply(b.max) }),
        centroid: p.centroid.map(|c| turn.apply(c)),
        inertia: turn.turn_tensor(&p.inertia),
        ..*p
    }
}

/// Whether some triangle of `body` whose box meets the common box of `boxes` is counted
/// in `frame` ([`counted_in`]).
fn counts_in<S: Surface>(body: &S, frame: Frame, boxes: (Option<Bounds>, Option<Bounds>)) -> bool {
    let (Some(p), Some(q)) = boxes else { return false };
    let lo = [0, 1, 2].map(|k| p.min[k].max(q.min[k]));
    let hi = [0, 1, 2].map(|k| p.max[k].min(q.max[k]));
    let mut found = false;
    for f in 0..body.face_count() {
        body.fan(f, |a, b, c| {
            let meets = (0..3)
                .all(|k| a[k].min(b[k]).min(c[k]) <= hi[k] && a[k].max(b[k]).max(c[k]) >= lo[k]);
            if meets && !found {
                found = counted_in(cross(sub(b, a), sub(c, a))) == frame;
            }
        });
        if found {
            return true;
        }
    }
    false
}

/// The pairs `(i, j)`, `i < j`, of `boxes` whose interiors overlap (boxes that only
/// touch hold no common volume), in increasing order: a sweep along x over the boxes
/// sorted by their lower x, so the work is n log n plus the pairs whose x ranges
/// overlap, not n². `None` (an empty body) overlaps nothing.
pub fn overlapping_boxes(boxes: &[Option<Bounds>]) -> Vec<(usize, usize)> {
    let mut order: Vec<(usize, Bounds)> =
        boxes.iter().enumerate().filter_map(|(n, b)| b.map(|b| (n, b))).collect();
    order.sort_by(|p, q| p.1.min[0].total_cmp(&q.1.min[0]).then(p.0.cmp(&q.0)));
    let mut pairs = Vec::new();
    for (k, &(n, b)) in order.iter().enumerate() {
        for &(m, c) in &order[k + 1..] {
            if c.min[0] >= b.max[0] {
                break;
            }
            if (1..3).all(|a| c.min[a] < b.max[a] && b.min[a] < c.max[a]) {
                pairs.push((n.min(m), n.max(m)));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}
