//! Refinement: an open cell is cut into 2×2×2 children, and the kernel run on a 2×2×2
//! grid over it with only the faces of the touching bodies whose boxes meet the cell
//! (the cell's *list*), plus, per child column, the area above: the signed projected
//! area of the body's faces in the column that lie wholly above the cell (its *field*,
//! kept on a lattice of fine squares, [`FINE`] to a base column's side). Faces wholly
//! below add nothing to any layer of the cell. A child's list is the part of its
//! parent's list that meets it; its field is its parent's over its footprint, plus, for
//! a lower child, the parent's listed faces wholly above the child. So each level costs
//! what its cells' own faces cost, not their columns'. A cell whose children's gaps add
//! up to more than [`STALL`] of its own is not refined further.

use super::bounds::{face_box, Cell, Rule, Tally};
use crate::grid::cells::{add_faces, finish_column, for_each_piece, Block, Piece, Units};
use crate::grid::{Grid, GridError};
use crate::surface::Oriented;
use crate::{Point, Surface};

/// A cell whose children's gaps add up to more than this fraction of its own gap is not
/// refined further: a curve where two surfaces cross leaves about a quarter of the gap
/// in the children, two surfaces lying on each other about half.
pub const STALL: f64 = 0.4;

/// Refinement levels at most: each halves the cell size.
pub const MAX_DEPTH: usize = 4;

/// Fine squares to a base column's side: the fields' resolution, which is what the
/// quadrants of the deepest cells refined need.
pub(super) const FINE: usize = 1 << MAX_DEPTH;

/// A face's box meets a cell when it meets the cell's closed box widened by this (base
/// grid units): far more than the rounding between the base grid's units and a cell's
/// own, so every face the kernel finds touching a child is on the child's list, and
/// every other face is either wholly above (in the field) or adds nothing.
pub(super) const MARGIN: f64 = 1e-9;

/// One touching body's faces of an open cell.
pub(super) struct Part {
    pub body: usize,
    /// Faces whose box meets the cell (widened by [`MARGIN`]).
    pub faces: Vec<u32>,
    /// Signed projected area (fine squares) of the body's faces in the column wholly
    /// above the cell (lowest z above its top + [`MARGIN`]) over each fine square of its
    /// footprint, `x · side + y`; empty for cells too deep to be refined.
    pub above: Vec<f64>,
}

/// An open cell during refinement: its lower corner (base grid units) and level (its
/// side is 2^−level base cells), the base column it lies in, and its bounds; its parts
/// are filled where it may be refined.
pub(super) struct OpenCell {
    pub column: usize,
    pub at: Point,
    pub level: u32,
    pub parts: Vec<Part>,
    pub lower: f64,
    pub upper: f64,
}

impl OpenCell {
    /// Side in base grid units.
    pub fn size(&self) -> f64 {
        0.5f64.powi(self.level as i32)
    }

    /// Fine squares to the side of its footprint (0 below the finest).
    pub fn lattice(&self) -> usize {
        FINE.checked_shr(self.level).unwrap_or(0)
    }
}

/// What refining one open cell gives.
pub(super) struct Refined {
    pub column: usize,
    /// Σ of the children that are exactly known.
    pub exact: f64,
    /// Children still open.
    pub open: Vec<OpenCell>,
    pub stalled: bool,
}

/// Whether the box `lo..hi` meets the cell at `at` of side `size`, widened by [`MARGIN`].
pub(super) fn meets(lo: Point, hi: Point, at: Point, size: f64) -> bool {
    (0..3).all(|a| lo[a] <= at[a] + size + MARGIN && hi[a] >= at[a] - MARGIN)
}

/// Adds the signed projected area of triangle `t` (base grid units) over each fine
/// square of the footprint at `at`, `side` squares a side, to `field`.
pub(super) fn add_area(t: [Point; 3], at: Point, side: usize, field: &mut [f64]) {
    let f = FINE as f64;
    let fine = |v: Point| [(v[0] - at[0]) * f, (v[1] - at[1]) * f, 0.0];
    let piece = Piece::triangle(fine(t[0]), fine(t[1]), fine(t[2]));
    if piece.area() == 0.0 {
        return;
    }
    let block = Block::whole([side, side, 1]);
    for_each_piece(&piece, &block, &(0..side * side), false, |square, part| {
        field[square] += part.area();
    });
}

/// Refines `cell` (whose level is below [`MAX_DEPTH`]): the children's bounds, and the
/// lists and fields of the open ones.
pub(super) fn refine<S: Surface + ?Sized>(
    bodies: &[Oriented<'_, S>],
    rule: Rule,
    grid: &Grid,
    cell: &OpenCell,
) -> Result<Refined, GridError> {
    let (side, level) = (cell.lattice(), cell.level + 1);
    let q = side / 2;
    if q == 0 || cell.parts.iter().any(|p| p.above.len() != side * side) {
        // Not refinable: keep the cell's bounds.
        let same = OpenCell { parts: Vec::new(), level, ..*cell };
        return Ok(Refined { column: cell.column, exact: 0.0, open: vec![same], stalled: true });
    }
    let half = 0.5 * cell.size();
    let lo = [0, 1, 2].map(|a| grid.origin[a] + cell.at[a] * grid.cell[a]);
    let sub = Grid::new(lo, grid.cell.map(|s| s * half), [2, 2, 2])?;
    let base = Units::new(grid);
    let units = Units::new(&sub);
    let child_volume = sub.cell_volume();
    // Per touching body: its volume and touch in each child.
    let per_body: Vec<([f64; 8], [u8; 8])> = cell
        .parts
        .iter()
        .map(|part| {
            let (mut cells, mut area, mut touched) = ([0.0; 8], [0.0; 12], [0u8; 8]);
            let faces = part.faces.iter().map(|&f| f as usize);
            add_faces::<_, true>(
                &bodies[part.body],
                faces,
                &units,
                &Block::whole([2, 2, 2]),
                &(0..4),
                &mut cells,
                &mut area,
                &mut touched,
            );
            // The faces wholly above the cell, over each child column (fine squares to
            // child units: a child's footprint is q² squares).
            for (quadrant, top) in area.chunks_mut(3).enumerate() {
                let (qi, qj) = (quadrant >> 1, quadrant & 1);
                let mut sum = 0.0;
                for x in qi * q..(qi + 1) * q {
                    for y in qj * q..(qj + 1) * q {
                        sum += part.above[x * side + y];
                    }
                }
                top[2] += sum / (q * q) as f64;
            }
            for (direct, area) in cells.chunks_mut(2).zip(area.chunks(3)) {
                finish_column(direct, area, child_volume);
            }
            (cells, touched)
        })
        .collect();
    let mut exact = 0.0;
    let mut open = Vec::new();
    // The parts' face boxes (base units), found once for all children.
    let mut boxes: Vec<Vec<(Point, Point)>> = Vec::new();
    for child in 0..8 {
        let mut tally = Tally::default();
        for (v, t) in &per_body {
            tally.add(v[child], t[child] != 0, child_volume, rule);
        }
        match tally.cell(child_volume, rule) {
            Cell::Exact(v) => exact += v,
            Cell::Open { lower, upper } => {
                let (i, j, k) = (child >> 2, (child >> 1) & 1, child & 1);
                let at = [0, 1, 2].map(|a| cell.at[a] + [i, j, k][a] as f64 * half);
                let mut parts = Vec::new();
                if level < MAX_DEPTH as u32 {
                    if boxes.is_empty() {
                        boxes = cell
                            .parts
                            .iter()
                            .map(|part| {
                                let body = &bodies[part.body];
                                let face = |&f: &u32| face_box(body, f as usize, |p| base.map(p));
                                part.faces.iter().map(face).collect()
                            })
                            .collect();
                    }
                    for ((part, (_, t)), boxes) in cell.parts.iter().zip(&per_body).zip(&boxes) {
                        if t[child] != 0 {
                            let body = &bodies[part.body];
                            let octant = [i, j, k];
                            parts.push(child_part(body, &base, part, boxes, side, at, octant));
                        }
                    }
                }
                open.push(OpenCell { column: cell.column, at, level, parts, lower, upper });
            }
        }
    }
    let gap: f64 = open.iter().map(|c| c.upper - c.lower).sum();
    let stalled = gap > STALL * (cell.upper - cell.lower);
    Ok(Refined { column: cell.column, exact, open, stalled })
}

/// A child's part from its parent's (its faces' boxes `boxes`; `side` fine squares a
/// side; the child at `at` is octant `[i, j, k]`): the listed faces that meet it, and the parent's field over its
/// footprint plus, for a lower child, the listed faces wholly above it.
fn child_part<S: Surface + ?Sized>(
    body: &Oriented<'_, S>,
    units: &Units,
    part: &Part,
    boxes: &[(Point, Point)],
    side: usize,
    at: Point,
    [i, j, k]: [usize; 3],
) -> Part {
    let q = side / 2;
    let size = side as f64 / FINE as f64 * 0.5;
    let mut above = Vec::with_capacity(q * q);
    for x in 0..q {
        let row = (i * q + x) * side + j * q;
        above.extend_from_slice(&part.above[row..row + q]);
    }
    let mut faces = Vec::new();
    for (&f, &(lo, hi)) in part.faces.iter().zip(boxes) {
        if meets(lo, hi, at, size) {
            faces.push(f);
        } else if k == 0 && lo[2] > at[2] + size + MARGIN {
            body.fan(f as usize, |a, b, c| {
                add_area([a, b, c].map(|p| units.map(p)), at, q, &mut above);
            });
        }
    }
    Part { body: part.body, faces, above }
}
