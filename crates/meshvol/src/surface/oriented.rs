//! A surface read with every face reversed, or as it is: one wound inward measured as
//! if wound outward, without copying it.

use crate::{Point, Surface};

/// `surface` with each fan triangle reversed when `reversed` (so its signed volume
/// changes sign), as it is otherwise.
///
/// ```
/// use meshvol::shapes::cuboid;
/// use meshvol::surface::Oriented;
/// use meshvol::mass_properties;
/// let inward = cuboid([0.0; 3], [2.0; 3]).flipped();
/// assert_eq!(mass_properties(&inward).signed_volume, -8.0);
/// assert_eq!(mass_properties(&Oriented::new(&inward, true)).signed_volume, 8.0);
/// ```
#[derive(Debug)]
pub struct Oriented<'a, S: ?Sized> {
    surface: &'a S,
    reversed: bool,
}

impl<'a, S: ?Sized> Oriented<'a, S> {
    pub fn new(surface: &'a S, reversed: bool) -> Self {
        Oriented { surface, reversed }
    }
}

impl<S: Surface + ?Sized> Surface for Oriented<'_, S> {
    fn face_count(&self) -> usize {
        self.surface.face_count()
    }

    #[inline]
    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        if self.reversed {
            self.surface.fan(face, |a, b, c| triangle(a, c, b))
        } else {
            self.surface.fan(face, triangle)
        }
    }
}
