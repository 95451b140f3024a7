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
//! the plan pass when |N_z| ≥ `union::frames::STEEP`·|N| (a magnification of at most 10³, far below
//! the interval's allowance), and otherwise in the same pass run on the bodies with
//! their coordinates turned cyclically (`union::frames::Frame`: a rotation, so windings and
//! insideness stay) so that the larger of |N_x|, |N_y| is vertical (ties to x). Each
//! triangle is counted in exactly one frame; a turned pass is run only when some
//! triangle in the bodies' common box is counted in it (a CAD part's walls, or the few
//! faces of a turned smooth body whose normals fall within 10⁻³ of level), and only
//! over the block of columns that holds those triangles: a column's kept pieces depend
//! on its own faces alone.

use crate::vector::dot;

use crate::grid::union::Interface;

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
