//! Refinement: an open cell is cut into 2×2×2 children, and the kernel run on a 2×2×2
//! grid over it with only the faces of the touching bodies that lie in its column at or
//! above its bottom (those below add nothing to any layer of it; those above add their
//! projected area). A cell whose children's gaps add up to more than [`super::STALL`]
//! of its own is not refined further.

use super::bounds::{face_box, Cell, Tally};
use super::STALL;
use crate::grid::cells::{add_faces, finish_column, Block, Units};
use crate::grid::{Grid, GridError};
use crate::surface::Oriented;
use crate::{Point, Surface};

/// An open cell during refinement: its box (world), the base column it lies in, and
/// for each touching body the faces of its column at or above its bottom.
pub(super) struct OpenCell {
    pub column: usize,
    pub lo: Point,
    pub size: Point,
    pub faces: Vec<(usize, Vec<u32>)>,
    pub lower: f64,
    pub upper: f64,
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

/// The faces of `faces` whose box meets the closed column over `lo..lo + size` (xy) at
/// or above `lo.z`.
pub(super) fn faces_in_column<S: Surface + ?Sized>(
    body: &S,
    faces: &[u32],
    lo: Point,
    size: Point,
) -> Vec<u32> {
    faces
        .iter()
        .copied()
        .filter(|&f| {
            let (a, b) = face_box(body, f as usize, |p| p);
            a[0] <= lo[0] + size[0]
                && b[0] >= lo[0]
                && a[1] <= lo[1] + size[1]
                && b[1] >= lo[1]
                && b[2] >= lo[2]
        })
        .collect()
}

pub(super) fn refine<S: Surface + ?Sized>(
    bodies: &[Oriented<'_, S>],
    cell: &OpenCell,
) -> Result<Refined, GridError> {
    let half = cell.size.map(|s| 0.5 * s);
    let sub = Grid::new(cell.lo, half, [2, 2, 2])?;
    let units = Units::new(&sub);
    let child_volume = sub.cell_volume();
    // Per touching body: its volume and touch in each child.
    let per_body: Vec<([f64; 8], [u8; 8])> = cell
        .faces
        .iter()
        .map(|(b, faces)| {
            let (mut cells, mut area, mut touched) = ([0.0; 8], [0.0; 12], [0u8; 8]);
            let faces = faces.iter().map(|&f| f as usize);
            add_faces::<_, true>(
                &bodies[*b],
                faces,
                &units,
                &Block::whole([2, 2, 2]),
                &(0..4),
                &mut cells,
                &mut area,
                &mut touched,
            );
            for (direct, area) in cells.chunks_mut(2).zip(area.chunks(3)) {
                finish_column(direct, area, child_volume);
            }
            (cells, touched)
        })
        .collect();
    let mut exact = 0.0;
    let mut open = Vec::new();
    for child in 0..8 {
        let mut tally = Tally::default();
        for (v, t) in &per_body {
            tally.add(v[child], t[child] != 0, child_volume);
        }
        match tally.cell(child_volume) {
            Cell::Exact(v) => exact += v,
            Cell::Open { lower, upper } => {
                let (i, j, k) = (child >> 2, (child >> 1) & 1, child & 1);
                let lo = [0, 1, 2].map(|a| cell.lo[a] + [i, j, k][a] as f64 * half[a]);
                let faces = cell
                    .faces
                    .iter()
                    .zip(&per_body)
                    .filter(|(_, (_, t))| t[child] != 0)
                    .map(|((b, faces), _)| (*b, faces_in_column(&bodies[*b], faces, lo, half)))
                    .collect();
                open.push(OpenCell { column: cell.column, lo, size: half, faces, lower, upper });
            }
        }
    }
    let gap: f64 = open.iter().map(|c| c.upper - c.lower).sum();
    let stalled = gap > STALL * (cell.upper - cell.lower);
    Ok(Refined { column: cell.column, exact, open, stalled })
}
