//! A surface read with every vertex moved by an affine map, or as it is: a body placed
//! by a pose without copying or re-checking it.

use crate::assembly::Affine;
use crate::{Point, Surface};

/// `surface` with every fan corner moved by `transform` (`None`: as it is, bit for bit).
///
/// A transform whose linear part has a negative determinant (a mirror) reverses the
/// faces' winding; `Moved` does not correct for it: callers place bodies by rigid
/// motions (rotation and translation), which keep the winding.
///
/// ```
/// use meshvol::assembly::Affine;
/// use meshvol::shapes::cuboid;
/// use meshvol::surface::Moved;
/// use meshvol::mass_properties;
/// let shift = Affine([[1.0, 0.0, 0.0, 5.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
/// let moved = Moved::new(cuboid([0.0; 3], [2.0; 3]), Some(shift));
/// let p = mass_properties(&moved);
/// assert_eq!((p.signed_volume, p.bounds.unwrap().min), (8.0, [5.0, 0.0, 0.0]));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Moved<S> {
    surface: S,
    transform: Option<Affine>,
}

impl<S> Moved<S> {
    pub fn new(surface: S, transform: Option<Affine>) -> Self {
        Moved { surface, transform }
    }
}

impl<S: Surface> Surface for Moved<S> {
    fn face_count(&self) -> usize {
        self.surface.face_count()
    }

    #[inline]
    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        match &self.transform {
            Some(t) => {
                self.surface.fan(face, |a, b, c| triangle(t.apply(a), t.apply(b), t.apply(c)))
            }
            None => self.surface.fan(face, triangle),
        }
    }
}
