//! The input of every stage: where each face's corners lie in one corner numbering
//! (a fan (a, b, c), (a, c, d), … is the loop a, b, c, d, …), and their positions,
//! gathered from the surface's fans so that stages index corners instead of calling
//! the surface again.
//!
//! Only welding reads the positions ([`Loops::corners`]); every later stage reads the
//! welded vertex of a corner and that vertex's position, which is the corner's own
//! position bit for bit under exact welding. So the positions (24 bytes a corner, the
//! largest array of a check) are dropped once welded rather than kept through the
//! check. A binary STL's are gathered as the f32 it stores ([`Loops::corners_f32`]):
//! 12 bytes a corner, welded to the same vertices. (On a 1M-triangle STL, 2 cores:
//! welding 0.109–0.115 CPU s in f64, 0.093–0.100 s in f32; 36 MB less at the weld's
//! peak. Welding the corners in place from the file's 50-byte records instead, with no
//! copy, was slower: 0.54 s against 0.40–0.44 s on a 5M-triangle STL, 2 cores.)

use super::error::CheckError;
use super::weld::Welded;
use crate::buckets::{filled, for_each_range_mut, par_starts};
use crate::vector::{add, cross, sub};
use crate::{Point, Surface};
use rayon::prelude::*;

/// Faces as loops of corners.
pub(super) struct Loops {
    /// Face f's corners are `start[f]..start[f + 1]`. (32 bits: [`super::check`]
    /// refuses surfaces of more corners.)
    pub start: Vec<u32>,
}

impl Loops {
    /// Each face's corner count, from its fan (k − 2 triangles: k corners), in parallel.
    /// Corners are numbered with 32 bits, faces with 31 (edge uses and neighbours keep
    /// a flag beside a face).
    pub fn of<S: Surface + ?Sized>(surface: &S) -> Result<Loops, CheckError> {
        let faces = surface.face_count();
        if faces >= (1 << 31) - 1 {
            return Err(CheckError::TooManyFaces { faces });
        }
        if surface.faces_are_triangles() || surface.indexed_triangles().is_some() {
            // One triangle a face, as the surface says: three corners each, without a
            // pass over the faces (which decodes every record of a binary STL, 8–27 ms
            // of a 5M-triangle check at 16 threads, 36–99 ms on one).
            if u32::try_from(3 * faces).is_err() {
                return Err(CheckError::TooLarge { corners: 3 * faces });
            }
            let start = (0..faces + 1).into_par_iter().map(|f| (3 * f) as u32).collect();
            return Ok(Loops { start });
        }
        let sizes: Vec<u32> = (0..faces)
            .into_par_iter()
            .map(|f| {
                let mut triangles: u32 = 0;
                surface.fan(f, |_, _, _| triangles = triangles.saturating_add(1));
                if triangles == 0 {
                    0
                } else {
                    triangles.saturating_add(2)
                }
            })
            .collect();
        let corners = par_starts(faces, |f| sizes[f] as usize);
        if u32::try_from(corners[faces]).is_err() {
            return Err(CheckError::TooLarge { corners: corners[faces] });
        }
        Ok(Loops { start: corners.par_iter().map(|&c| c as u32).collect() })
    }

    /// The corners' positions, each face's fan written into its place in parallel.
    pub fn corners<S: Surface + ?Sized>(&self, surface: &S) -> Vec<Point> {
        let mut corners = filled(self.corner_count(), [0.0; 3]);
        for_each_range_mut(&mut corners, self.face_count(), &|f| self.face(f), &|f, corners| {
            let mut next = 0;
            surface.fan(f, |a, b, c| {
                // A fan longer than the face's loop (a surface breaking its word that
                // each face is one triangle) is cut to the loop, never written past it.
                if next + 2 > corners.len() {
                    return;
                }
                if next == 0 {
                    corners[0] = a;
                    next = 1;
                }
                corners[next] = b;
                corners[next + 1] = c;
                next += 1;
            });
        });
        corners
    }

    /// [`Loops::corners`] as the f32 values the surface stores, when it says it has
    /// them ([`Surface::triangle_f32`]: triangles only): half the bytes. `None` when it
    /// does not, for any face.
    pub fn corners_f32<S: Surface + ?Sized>(&self, surface: &S) -> Option<Vec<[f32; 3]>> {
        let faces = self.face_count();
        if !surface.faces_are_triangles() || self.corner_count() != 3 * faces {
            return None;
        }
        let mut corners = filled(3 * faces, [0.0f32; 3]);
        corners.par_chunks_mut(3).enumerate().try_for_each(|(f, out)| {
            out.copy_from_slice(&surface.triangle_f32(f)?);
            Some(())
        })?;
        Some(corners)
    }

    /// The faces as fans of their corners' welded vertices: under an exact weld, the
    /// surface's own fans, bit for bit (a vertex is at its corners' position; only the
    /// sign of a zero coordinate may be its first corner's), read without the surface.
    pub fn welded_fans<'a>(&'a self, welded: &'a Welded) -> WeldedFans<'a> {
        WeldedFans { loops: self, welded }
    }

    pub fn face_count(&self) -> usize {
        self.start.len() - 1
    }

    pub fn corner_count(&self) -> usize {
        self.start[self.face_count()] as usize
    }

    pub fn face(&self, f: usize) -> std::ops::Range<usize> {
        self.start[f] as usize..self.start[f + 1] as usize
    }

    /// Twice face `f`'s vector area, Σ (cᵢ − c₀) × (cᵢ₊₁ − c₀) over its fan of welded
    /// vertices: zero for a flat face, twice its area in length for a plane one.
    pub fn doubled_vector_area(&self, f: usize, welded: &Welded) -> Point {
        let r = self.face(f);
        let apex = welded.at(r.start);
        (r.start + 1..r.end - 1).fold([0.0; 3], |s, c| {
            add(s, cross(sub(welded.at(c), apex), sub(welded.at(c + 1), apex)))
        })
    }

    /// The corner after `c` in its face.
    pub fn next(&self, f: usize, c: usize) -> usize {
        if c + 1 == self.start[f + 1] as usize {
            self.start[f] as usize
        } else {
            c + 1
        }
    }

    /// The corner before `c` in its face.
    pub fn previous(&self, f: usize, c: usize) -> usize {
        if c == self.start[f] as usize {
            self.start[f + 1] as usize - 1
        } else {
            c - 1
        }
    }
}

/// [`Loops::welded_fans`].
pub(super) struct WeldedFans<'a> {
    loops: &'a Loops,
    welded: &'a Welded,
}

impl Surface for WeldedFans<'_> {
    fn face_count(&self) -> usize {
        self.loops.face_count()
    }

    #[inline]
    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        let corners = self.loops.face(face);
        let first = self.welded.at(corners.start);
        for c in corners.start + 1..corners.end.saturating_sub(1) {
            triangle(first, self.welded.at(c), self.welded.at(c + 1));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Loops;
    use crate::shapes::uv_sphere;
    use crate::{Point, Surface};

    /// A surface read through its fans alone (its loops counted face by face), saying
    /// that each face is one triangle when `.1`, whatever its fans are.
    struct Fans<'a, S>(&'a S, bool);

    impl<S: Surface> Surface for Fans<'_, S> {
        fn face_count(&self) -> usize {
            self.0.face_count()
        }

        fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
            self.0.fan(face, triangle)
        }

        fn faces_are_triangles(&self) -> bool {
            self.1
        }
    }

    #[test]
    fn triangle_surfaces_take_three_corners_a_face_as_their_fans_count() {
        let triangles = uv_sphere(1.0, 24, 12).triangulated();
        assert!(triangles.indexed_triangles().is_some());
        let counted = Loops::of(&Fans(&triangles, false)).unwrap();
        let said = Loops::of(&triangles).unwrap();
        assert_eq!(said.start, counted.start);
        assert_eq!(said.corners(&triangles), counted.corners(&Fans(&triangles, false)));
        // Quads said to be triangles: three corners a face, the fan cut to them.
        let quads = uv_sphere(1.0, 24, 12);
        let loops = Loops::of(&Fans(&quads, true)).unwrap();
        assert_eq!(loops.corner_count(), 3 * quads.face_count());
        let corners = loops.corners(&Fans(&quads, true));
        let whole_loops = Loops::of(&quads).unwrap();
        let all = whole_loops.corners(&quads);
        for f in 0..quads.face_count() {
            let whole = &all[whole_loops.face(f)];
            assert_eq!(&corners[loops.face(f)], &whole[..3], "face {f}");
        }
    }
}
