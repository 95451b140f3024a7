//! The boundary pass in three frames: which frame counts a triangle (by its normal),
//! the sums of a column's kept pieces in a frame (moments, and per body the area and
//! vector area of its surface inside the other), every column resolved in a frame, and
//! the block of columns a turned frame needs. The intersection's contact
//! (`grid::intersect::contact`) and the union's boundary read these sums.

use super::bounds::Bodies;
use super::resolve::{KeptPiece, KeptPieces};
use crate::accumulate::CompensatedSum;
use crate::assembly::Affine;
use crate::grid::piece_moments::{add_piece, Sums};
use crate::grid::{Grid, GridError};
use crate::progress::{Counter, Progress};
use crate::vector::{cross, dot, sub};
use crate::{Point, Surface};
use rayon::prelude::*;

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
    /// Adds the piece's moments (in the identity frame) and, for a piece of one of the
    /// two bodies kept for lying inside the other (`interface`), its share of the
    /// interface.
    fn add(&mut self, piece: KeptPiece<'_>, cell: Point) {
        let KeptPiece { body, triangle, vertices, interface } = piece;
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

/// The sums of the kept pieces of every column ([`BoundarySums`] in `frame`; moments
/// about the grid's origin), added in column order; `None` when some column cannot be
/// resolved.
pub(super) fn boundary_pass<S: Surface>(
    model: &Bodies<'_, S>,
    frame: Frame,
    progress: &dyn Progress,
) -> Option<BoundaryTotal> {
    resolve_every_column(model, frame, progress).map(|(_, total)| total)
}

/// One column resolved exactly: its cells' volumes and how many open cells that resolved
/// ([`Bodies::exact_column`]).
type ResolvedColumn = (Vec<f64>, usize);

/// Every column resolved exactly ([`Bodies::exact_column_with`]): per column its cells'
/// volumes and how many open cells that resolved (empty for a column a turned frame
/// skips), and the sums of the kept pieces ([`BoundarySums`] in `frame`; moments about
/// the grid's origin) added in column order; `None` when some column cannot be resolved.
pub(super) fn resolve_every_column<S: Surface>(
    model: &Bodies<'_, S>,
    frame: Frame,
    progress: &dyn Progress,
) -> Option<(Vec<ResolvedColumn>, BoundaryTotal)> {
    let columns = model.grid.counts[0] * model.grid.counts[1];
    progress.stage(if frame == Frame::Identity { "moments" } else { "contact" });
    let done = Counter::new(progress, columns);
    // A turned frame counts only the steep faces: columns without one add nothing.
    let counts_here = |c: usize| {
        frame == Frame::Identity
            || model.bodies.iter().zip(&model.bins).any(|(body, bins)| {
                bins.column(c).iter().any(|&f| {
                    let mut counted = false;
                    body.fan(f as usize, |p, q, r| counted |= frame.counts(p, q, r));
                    counted
                })
            })
    };
    let per_column: Vec<Option<(ResolvedColumn, BoundarySums)>> = (0..columns)
        .into_par_iter()
        .map(|c| {
            let mut sums = BoundarySums::new(frame);
            let resolved = if counts_here(c) {
                model.exact_column_with(c, Some(&mut sums)).map(|cells| (cells, sums))
            } else {
                Some(((Vec::new(), 0), sums))
            };
            done.add(1);
            resolved
        })
        .collect();
    let mut total = BoundaryTotal::default();
    let mut cells = Vec::with_capacity(columns);
    for column in per_column {
        let (volumes, sums) = column?;
        total.add(&sums);
        cells.push(volumes);
    }
    Some((cells, total))
}

/// The columns of `full` that a turned `frame` needs: a turned pass adds up only the
/// faces counted in it (a few steep ones), and a column's kept pieces depend on its own
/// faces alone (the column–clamp method), so its grid is the block of `full`'s columns
/// (all its layers) that covers the plan boxes of those faces, clipped to `full`;
/// `None` when no such face meets `full`.
pub(super) fn counted_columns<S: Surface>(
    bodies: &[S],
    frame: Frame,
    full: &Grid,
) -> Result<Option<Grid>, GridError> {
    let (min, max) = (full.origin, full.max());
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for body in bodies {
        for f in 0..body.face_count() {
            body.fan(f, |p, q, r| {
                let (a, b) = (
                    [0, 1, 2].map(|k| p[k].min(q[k]).min(r[k])),
                    [0, 1, 2].map(|k| p[k].max(q[k]).max(r[k])),
                );
                if (0..3).all(|k| a[k] <= max[k] && b[k] >= min[k]) && frame.counts(p, q, r) {
                    for k in 0..2 {
                        lo[k] = lo[k].min(a[k]);
                        hi[k] = hi[k].max(b[k]);
                    }
                }
            });
        }
    }
    if lo[0] > hi[0] {
        return Ok(None);
    }
    // The full grid's column lines, one column of room for rounding either side.
    let span = |k: usize| {
        let cell = |v: f64| ((v - min[k]) / full.cell[k]).floor();
        let first = (cell(lo[k]) - 1.0).max(0.0) as usize;
        let end = ((cell(hi[k]) + 2.0).max(0.0) as usize).min(full.counts[k]);
        (first, end.max(first + 1))
    };
    let ((i0, i1), (j0, j1)) = (span(0), span(1));
    let origin = [min[0] + i0 as f64 * full.cell[0], min[1] + j0 as f64 * full.cell[1], min[2]];
    Grid::new(origin, full.cell, [i1 - i0, j1 - j0, full.counts[2]]).map(Some)
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
