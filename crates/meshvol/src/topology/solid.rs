//! The solid a checked surface bounds, as a [`Surface`] over the original one: faces
//! kept or dropped, each possibly reversed, plus cap triangles over holes. No geometry
//! is copied except the caps.

use crate::{Point, Surface};

/// Which faces of the checked surface make the solid, which way round, and the caps.
#[derive(Clone, Debug, Default)]
pub struct Solid {
    /// Kept faces, and whether each is reversed.
    faces: Vec<(usize, bool)>,
    caps: Vec<[Point; 3]>,
    flipped: usize,
    dropped: usize,
}

impl Solid {
    pub(crate) fn new(
        kept: &[bool],
        flip: &[bool],
        caps: Vec<[Point; 3]>,
        cap_flip: &[bool],
    ) -> Solid {
        let faces: Vec<(usize, bool)> =
            (0..kept.len()).filter(|&f| kept[f]).map(|f| (f, flip[f])).collect();
        let flipped = flip.iter().filter(|&&x| x).count();
        let caps = caps
            .into_iter()
            .zip(cap_flip)
            .map(|(c, &f)| if f { [c[0], c[2], c[1]] } else { c })
            .collect();
        Solid { dropped: kept.len() - faces.len(), faces, caps, flipped }
    }

    pub(crate) fn view<'a, S: Surface + ?Sized>(&'a self, surface: &'a S) -> SolidView<'a, S> {
        SolidView { solid: self, surface }
    }

    /// (faces reversed, faces dropped, cap triangles added).
    pub(crate) fn changes(&self) -> (usize, usize, usize) {
        (self.flipped, self.dropped, self.caps.len())
    }
}

/// A [`Solid`] read over the surface it was checked from.
#[derive(Clone, Copy, Debug)]
pub struct SolidView<'a, S: ?Sized> {
    solid: &'a Solid,
    surface: &'a S,
}

impl<S: Surface + ?Sized> Surface for SolidView<'_, S> {
    fn face_count(&self) -> usize {
        self.solid.faces.len() + self.solid.caps.len()
    }

    #[inline]
    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        match self.solid.faces.get(face) {
            Some(&(f, true)) => self.surface.fan(f, |a, b, c| triangle(a, c, b)),
            Some(&(f, false)) => self.surface.fan(f, triangle),
            None => {
                let [a, b, c] = self.solid.caps[face - self.solid.faces.len()];
                triangle(a, b, c)
            }
        }
    }
}
