//! The interface of two overlapping bodies: the part of each one's surface inside the
//! other, its area and its vector area, from the same kept pieces as the moments.
//!
//! # Quantities
//! ∂(A∩B) is the part of ∂A inside B and the part of ∂B inside A, plus faces the two
//! share the same way round (which are outside both, and are not an interface). Over
//! the interface:
//!
//! - `contact_area` = area(∂A ∩ B) + area(∂B ∩ A);
//! - `contact_vector` = ∫ n dA over ∂B ∩ A (n: B's outward normal). Translating B by
//!   `t·e` changes the overlap at the rate `d|A∩B|/dt = e · contact_vector` (the surface
//!   of B inside A sweeps volume into or out of A at the rate of its normal speed), so
//!   `−contact_vector` is the direction that separates B from A fastest. Since ∂(A∩B) is
//!   closed, ∫ n dA over ∂A ∩ B is `−contact_vector` (shared faces aside): the tests
//!   check that identity.
//!
//! # Method
//! A kept piece lies on one triangle of its body, with normal N: its area is its plan
//! area · |N| / |N_z| and its vector area its plan area · N / |N_z|. The column pass sees
//! a triangle only through its plan projection: a vertical face not at all, a steep one
//! with its plan area's rounding magnified by |N| / |N_z|. So a triangle is counted in
//! the plan pass when |N_z| ≥ [`STEEP`]·|N| (a magnification of at most 10³, far below
//! the interval's allowance), and otherwise in the same pass run on the bodies with
//! their coordinates turned cyclically ([`Frame`]: a rotation, so windings and
//! insideness stay) so that the larger of |N_x|, |N_y| is vertical (ties to x). Each
//! triangle is counted in exactly one frame; a turned pass is run only when some
//! triangle in the bodies' common box is counted in it (a CAD part's walls, or the few
//! faces of a turned smooth body whose normals fall within 10⁻³ of level), and only
//! over the block of columns that holds those triangles: a column's kept pieces depend
//! on its own faces alone.

use crate::accumulate::CompensatedSum;
use crate::assembly::Affine;
use crate::vector::{cross, dot, sub};
use crate::Point;

use super::moments::{add_piece, Sums};
use crate::grid::union::KeptPieces;

/// A frame of the boundary pass: the bodies' coordinates turned cyclically so that
/// one axis of the bodies' own frame is the pass's z.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Frame {
    /// (x, y, z) as they are.
    Identity,
    /// (y, z, x): the bodies' x is vertical.
    XUp,
    /// (z, x, y): the bodies' y is vertical.
    YUp,
}

impl Frame {
    /// The rotation taking the bodies' coordinates to this frame's (`None`: identity).
    pub(crate) fn turn(self) -> Option<Affine> {
        match self {
            Frame::Identity => None,
            Frame::XUp => {
                Some(Affine([[0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [1.0, 0.0, 0.0, 0.0]]))
            }
            Frame::YUp => {
                Some(Affine([[0.0, 0.0, 1.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]]))
            }
        }
    }

    /// Whether the triangle `p, q, r` (this frame's coordinates) is counted in this
    /// frame.
    pub(crate) fn counts(self, p: Point, q: Point, r: Point) -> bool {
        counted_in(self.back(cross(sub(q, p), sub(r, p)))) == self
    }

    /// A vector (or point) of this frame in the bodies' own frame.
    pub(crate) fn back(self, [a, b, c]: [f64; 3]) -> [f64; 3] {
        match self {
            Frame::Identity => [a, b, c],
            Frame::XUp => [c, a, b],
            Frame::YUp => [b, c, a],
        }
    }
}

/// A triangle whose normal N has |N_z| below this fraction of |N| is steep: counted in a
/// turned frame (module docs).
pub(crate) const STEEP: f64 = 1e-3;

/// The frame a triangle with normal `n` (the bodies' own frame) is counted in.
pub(crate) fn counted_in([x, y, z]: [f64; 3]) -> Frame {
    if z * z >= STEEP * STEEP * (x * x + y * y + z * z) {
        Frame::Identity
    } else if x.abs() >= y.abs() {
        Frame::XUp
    } else {
        Frame::YUp
    }
}

/// What the boundary pass adds up over one column's kept pieces in one frame: the
/// moments (identity frame only) and, per body, the area and vector area of its pieces
/// inside the other body whose triangles this frame counts.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BoundarySums {
    frame: Frame,
    pub moments: Sums,
    area: [f64; 2],
    vector: [[f64; 3]; 2],
}

impl BoundarySums {
    pub(crate) fn new(frame: Frame) -> Self {
        BoundarySums { frame, moments: [0.0; 10], area: [0.0; 2], vector: [[0.0; 3]; 2] }
    }
}

impl KeptPieces for BoundarySums {
    /// Adds a kept piece (`vertices` in grid units; `cell` the grid's cell size) of
    /// `body`'s `triangle` (this frame's coordinates, as oriented); `interface`: it was
    /// kept for lying inside the other body, not on a face the two share.
    fn add(
        &mut self,
        body: usize,
        triangle: &[Point; 3],
        vertices: &[Point],
        cell: [f64; 3],
        interface: bool,
    ) {
        if self.frame == Frame::Identity {
            add_piece(vertices, cell, &mut self.moments);
        }
        if !interface || body > 1 || vertices.len() < 3 {
            return;
        }
        let [p, q, r] = *triangle;
        let n = cross(sub(q, p), sub(r, p));
        if !self.frame.counts(p, q, r) || n[2] == 0.0 {
            return;
        }
        let o = vertices[0];
        let mut double = 0.0;
        for k in 1..vertices.len() - 1 {
            let (a, b) = (vertices[k], vertices[k + 1]);
            double += (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        }
        let plan = 0.5 * double.abs() * cell[0] * cell[1];
        let scale = plan / n[2].abs();
        self.area[body] += scale * dot(n, n).sqrt();
        for (v, x) in self.vector[body].iter_mut().zip(n) {
            *v += scale * x;
        }
    }
}

/// Sums of many columns' [`BoundarySums`], added in the order given (compensated: the
/// same bits at any thread count when the order is the columns').
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct BoundaryTotal {
    moments: [CompensatedSum; 10],
    area: [CompensatedSum; 2],
    vector: [[CompensatedSum; 3]; 2],
    frame: Option<Frame>,
}

impl BoundaryTotal {
    pub(crate) fn add(&mut self, sums: &BoundarySums) {
        self.frame = Some(sums.frame);
        for (t, &x) in self.moments.iter_mut().zip(&sums.moments) {
            t.add(x);
        }
        for b in 0..2 {
            self.area[b].add(sums.area[b]);
            for k in 0..3 {
                self.vector[b][k].add(sums.vector[b][k]);
            }
        }
    }

    pub(crate) fn moments(&self) -> Sums {
        self.moments.map(|t| t.value())
    }

    /// The interface parts found in this frame, in the bodies' own frame.
    pub(crate) fn interface(&self) -> Interface {
        let frame = self.frame.unwrap_or(Frame::Identity);
        let vector = |b: usize| frame.back(self.vector[b].map(|t| t.value()));
        Interface {
            area: [self.area[0].value(), self.area[1].value()],
            vector: [vector(0), vector(1)],
        }
    }
}

/// Per body, the area and the vector area (∫ n dA) of its surface inside the other.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Interface {
    pub area: [f64; 2],
    pub vector: [[f64; 3]; 2],
}

impl Interface {
    /// The three frames' parts, added in frame order.
    pub(crate) fn total(parts: &[Interface]) -> Interface {
        let mut sum = Interface::default();
        for part in parts {
            for b in 0..2 {
                sum.area[b] += part.area[b];
                for k in 0..3 {
                    sum.vector[b][k] += part.vector[b][k];
                }
            }
        }
        sum
    }
}

/// The interface of A and B (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// area(∂A ∩ B) + area(∂B ∩ A).
    pub area: f64,
    /// ∫ n dA over ∂B ∩ A: the rate of change of |A∩B| as B moves (module docs).
    pub vector: [f64; 3],
    /// ∫ n dA over ∂A ∩ B: `−vector` up to rounding when no faces are shared.
    pub vector_a: [f64; 3],
}

/// The length below which [`Contact::vector`], as a fraction of the contact area, is
/// taken for the rounding of a sum of normals that cancel. The vector sums the vector
/// areas of the faces' pieces in plain floating point, whose rounding grows with the
/// number n of pieces up to about n·2⁻⁵³ of their total area: 10⁻⁹ stands above that for
/// up to 9·10⁶ pieces. (The corpus's `ico4uv.obj`, wholly inside `7_8ths_cube.stl`,
/// left a vector of length 4·10⁻¹⁵ against a contact area of 12.5, and its direction
/// moved with the order of the triangles.)
pub const NORMAL_FLOOR: f64 = 1e-9;

impl Contact {
    pub(crate) fn from_interface(i: &Interface) -> Contact {
        Contact { area: i.area[0] + i.area[1], vector: i.vector[1], vector_a: i.vector[0] }
    }

    /// `vector` scaled to length 1; `None` when it is no direction: 0 (no interface),
    /// or not longer than [`NORMAL_FLOOR`] times the contact area, where the normals
    /// cancel (a body wholly inside the other) and what is left of them is the
    /// rounding of their sum.
    pub fn normal(&self) -> Option<[f64; 3]> {
        let length = dot(self.vector, self.vector).sqrt();
        // The floor is never negative, so a length above it is above 0 too.
        let direction = length > NORMAL_FLOOR * self.area && length.is_finite();
        direction.then(|| self.vector.map(|x| x / length))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The axis of the bodies' own frame that is vertical in `frame`.
    fn vertical(frame: Frame) -> usize {
        match frame {
            Frame::Identity => 2,
            Frame::XUp => 0,
            Frame::YUp => 1,
        }
    }

    #[test]
    fn the_frames_turn_coordinates_and_turn_them_back() {
        let p = [1.0, 2.0, 3.0];
        for frame in [Frame::Identity, Frame::XUp, Frame::YUp] {
            let turned = frame.turn().map_or(p, |t| t.apply(p));
            assert_eq!(frame.back(turned), p, "{frame:?}");
            assert_eq!(turned[2], p[vertical(frame)], "{frame:?}");
        }
    }

    #[test]
    fn a_normal_is_counted_where_its_plan_area_is_large() {
        for (n, frame) in [
            ([1.0, 1.0, 1.0], Frame::Identity),
            ([0.0, 0.0, 0.0], Frame::Identity),
            ([-2.0, 2.0, 0.0], Frame::XUp),
            ([0.5, -1.0, 1e-4], Frame::YUp),
            ([3.0, 0.0, -3.0], Frame::Identity),
        ] {
            assert_eq!(counted_in(n), frame, "{n:?}");
            // In its frame, the vertical component is the one it was counted by.
            let turned = frame.turn().map_or(n, |t| t.apply(n));
            assert_eq!(turned[2], n[vertical(frame)]);
        }
    }
}
