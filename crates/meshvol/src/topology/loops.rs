//! The input of every stage: each face's corners, in order, gathered once from the
//! surface's fans (a fan (a, b, c), (a, c, d), … is the loop a, b, c, d, …), so that
//! stages index corners instead of calling the surface again.

use crate::buckets::for_each_range_mut;
use crate::{Point, Surface};
use rayon::prelude::*;

/// Faces as loops of corners.
pub(super) struct Loops {
    pub corners: Vec<Point>,
    /// Face f's corners are `corners[start[f]..start[f + 1]]`.
    pub start: Vec<usize>,
}

impl Loops {
    /// The faces' corners, gathered in parallel: sizes first, then each face's fan
    /// written into its place.
    pub fn of<S: Surface + ?Sized>(surface: &S) -> Loops {
        let faces = surface.face_count();
        let sizes: Vec<usize> = (0..faces)
            .into_par_iter()
            .map(|f| {
                let mut triangles = 0;
                surface.fan(f, |_, _, _| triangles += 1);
                if triangles == 0 {
                    0
                } else {
                    triangles + 2
                }
            })
            .collect();
        let mut start = Vec::with_capacity(faces + 1);
        start.push(0);
        for size in sizes {
            start.push(start.last().unwrap_or(&0) + size);
        }
        let range = |f: usize| start[f]..start[f + 1];
        let mut corners = vec![[0.0; 3]; start[faces]];
        for_each_range_mut(&mut corners, faces, &range, &|f, corners| {
            let mut next = 0;
            surface.fan(f, |a, b, c| {
                if next == 0 {
                    corners[0] = a;
                    next = 1;
                }
                corners[next] = b;
                corners[next + 1] = c;
                next += 1;
            });
        });
        Loops { corners, start }
    }

    pub fn face_count(&self) -> usize {
        self.start.len() - 1
    }

    pub fn face(&self, f: usize) -> std::ops::Range<usize> {
        self.start[f]..self.start[f + 1]
    }

    /// The corner after `c` in its face.
    pub fn next(&self, f: usize, c: usize) -> usize {
        if c + 1 == self.start[f + 1] {
            self.start[f]
        } else {
            c + 1
        }
    }

    /// The corner before `c` in its face.
    pub fn previous(&self, f: usize, c: usize) -> usize {
        if c == self.start[f] {
            self.start[f + 1] - 1
        } else {
            c - 1
        }
    }
}
