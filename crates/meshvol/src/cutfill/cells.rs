//! Cut and fill per cell of a plan grid.
//!
//! Each piece of the overlay is cut along the grid's lines, column by column, then row
//! by row within its column: the part left of a line goes to the column, the rest on to
//! the next, and the last part to the last column the piece reaches. Every part lands
//! in some cell (a part just outside the grid goes to the edge cell), so the cells add
//! up to the totals. d is interpolated along the cut edges, exactly as it is linear.
//!
//! The parallel tasks give each cell's contributions in their order; they are added
//! into the cell arrays task by task, in order, so the cells have the same bits at any
//! thread count.

use super::piece::{amounts, Piece};
use super::{Design, Overlay};
use crate::accumulate::ordered_reduce;
use crate::progress::{Counter, Progress};

/// Most cells a plan grid may have (two f64 arrays of 2 GiB each).
pub const MAX_CELLS: usize = 1 << 28;

/// A grid of cells in plan: `counts[a]` cells of size `cell[a]` along x and y from
/// `origin`. Cell (i, j) spans `origin + (i, j)·cell` to `origin + (i+1, j+1)·cell` and
/// is entry `i·ny + j` of a cell array (C order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanGrid {
    origin: [f64; 2],
    cell: [f64; 2],
    counts: [usize; 2],
}

/// Why a plan grid cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum PlanGridError {
    #[error("a grid needs at least one cell along x and y; got {}×{}", .counts[0], .counts[1])]
    NoCells { counts: [usize; 2] },
    #[error("cell sizes must be positive and finite; got {} and {}", .cell[0], .cell[1])]
    BadCellSize { cell: [f64; 2] },
    #[error("the grid's origin must be finite; got ({}, {})", .origin[0], .origin[1])]
    BadOrigin { origin: [f64; 2] },
    #[error("a {}×{} grid has more than {} cells: use fewer cells or a larger pitch", .counts[0], .counts[1], MAX_CELLS)]
    TooManyCells { counts: [usize; 2] },
}

impl PlanGrid {
    pub fn new(
        origin: [f64; 2],
        cell: [f64; 2],
        counts: [usize; 2],
    ) -> Result<PlanGrid, PlanGridError> {
        if counts.contains(&0) {
            return Err(PlanGridError::NoCells { counts });
        }
        if !cell.iter().all(|h| h.is_finite() && *h > 0.0) {
            return Err(PlanGridError::BadCellSize { cell });
        }
        if !origin.iter().all(|x| x.is_finite()) {
            return Err(PlanGridError::BadOrigin { origin });
        }
        if counts[0].checked_mul(counts[1]).is_none_or(|n| n > MAX_CELLS) {
            return Err(PlanGridError::TooManyCells { counts });
        }
        Ok(PlanGrid { origin, cell, counts })
    }

    pub fn origin(&self) -> [f64; 2] {
        self.origin
    }

    pub fn cell(&self) -> [f64; 2] {
        self.cell
    }

    pub fn counts(&self) -> [usize; 2] {
        self.counts
    }

    pub fn cell_count(&self) -> usize {
        self.counts[0] * self.counts[1]
    }

    /// The cell's index along `axis` holding local coordinate `x` (the grid's origin at
    /// `start`), clamped to the grid.
    fn index(&self, axis: usize, start: f64, x: f64) -> usize {
        let i = ((x - start) / self.cell[axis]).floor();
        if i.is_nan() {
            return 0;
        }
        (i.max(0.0) as usize).min(self.counts[axis] - 1)
    }

    /// Calls `each(i, part)` for the parts of `piece` in the cells along `axis` (0:
    /// columns, 1: rows), the grid's origin at `start` along that axis.
    fn cut(&self, piece: &Piece, axis: usize, start: f64, mut each: impl FnMut(usize, &Piece)) {
        let (lo, hi) =
            piece.corners().iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                (lo.min(c[axis]), hi.max(c[axis]))
            });
        let (first, last) = (self.index(axis, start, lo), self.index(axis, start, hi));
        let mut rest = *piece;
        for i in first..last {
            let line = start + (i + 1) as f64 * self.cell[axis];
            let (before, after) = rest.split(|c| c[axis] - line);
            if !before.is_empty() {
                each(i, &before);
            }
            rest = after;
            if rest.is_empty() {
                return;
            }
        }
        each(last, &rest);
    }
}

/// Cut and fill volumes per cell (C order, see [`PlanGrid`]).
#[derive(Clone, Debug, PartialEq)]
pub struct CellCutFill {
    pub cut: Vec<f64>,
    pub fill: Vec<f64>,
}

/// Cut and fill of `existing` against `design` in each cell of `grid`; parts of the
/// footprint outside the grid go to its edge cells.
pub fn cell_cut_fill(
    existing: &super::Terrain,
    design: Design<'_>,
    grid: &PlanGrid,
) -> CellCutFill {
    cell_cut_fill_with(existing, design, grid, &())
}

/// [`cell_cut_fill`], telling `progress` its stages and the tasks done (as
/// [`super::cut_fill_with`]).
pub fn cell_cut_fill_with(
    existing: &super::Terrain,
    design: Design<'_>,
    grid: &PlanGrid,
    progress: &dyn Progress,
) -> CellCutFill {
    let n = grid.cell_count();
    let mut cells = CellCutFill { cut: vec![0.0; n], fill: vec![0.0; n] };
    progress.stage("pairing the surfaces' triangles");
    let Some(overlay) = Overlay::new(existing, design) else {
        return cells;
    };
    let start = [0, 1].map(|a| grid.origin[a] - overlay.origin[a]);
    let ny = grid.counts[1];
    let (tasks, chunk) = overlay.tasks();
    progress.stage("integrating cut and fill per cell");
    let done = Counter::new(progress, tasks);
    let parts = ordered_reduce(
        tasks,
        chunk,
        |range| {
            let mut found: Vec<(usize, f64, f64)> = Vec::new();
            let units = range.len();
            overlay.pieces(range, |piece| {
                grid.cut(piece, 0, start[0], |i, column| {
                    grid.cut(column, 1, start[1], |j, part| {
                        let a = amounts(part);
                        found.push((i * ny + j, a[0], a[1]));
                    });
                });
            });
            done.add(units);
            vec![found]
        },
        |all, more| all.extend(more),
    );
    for (cell, cut, fill) in parts.into_iter().flatten().flatten() {
        cells.cut[cell] += cut;
        cells.fill[cell] += fill;
    }
    cells
}
