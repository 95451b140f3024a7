//! The union's volume in every cell of a given grid ([`union_cell_volumes`]): exact
//! per cell, resolving the columns of cells that two or more bodies touch.

use super::bounds::{Bodies, Cell, Rule};
use crate::grid::{Grid, GridError};
use crate::progress::{Counter, Progress};
use crate::surface::Oriented;
use crate::{mass_properties, Surface};
use rayon::prelude::*;

/// The union's volume in every cell of `grid`: exact where at most one body touches a
/// cell, resolved exactly (module docs) in the columns of cells that two or more touch.
/// Returns the cell volumes and the number of columns that could not be resolved (their
/// open cells hold the lower bound, `max_i v_i`).
pub fn union_cell_volumes<S: Surface>(
    bodies: &[S],
    grid: &Grid,
) -> Result<(Vec<f64>, usize), GridError> {
    union_cell_volumes_with(bodies, grid, &())
}

/// [`union_cell_volumes`], telling `progress` its stages (`bounds`, `resolving
/// columns`) and, in each, the bodies or columns done.
pub fn union_cell_volumes_with<S: Surface>(
    bodies: &[S],
    grid: &Grid,
    progress: &dyn Progress,
) -> Result<(Vec<f64>, usize), GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    let oriented =
        bodies.iter().map(|b| Oriented::new(b, mass_properties(b).signed_volume < 0.0)).collect();
    let model = Bodies::new(oriented, Rule::Union, grid, progress)?;
    let [nx, ny, nz] = grid.counts;
    let mut out = crate::grid::cells::zeroed(grid.cell_count())?;
    progress.stage("resolving columns");
    let done = Counter::new(progress, nx * ny);
    let unresolved: usize = out
        .par_chunks_mut(nz)
        .enumerate()
        .map(|(c, cells)| {
            let unresolved = cell_column(&model, c, cells);
            done.add(1);
            unresolved
        })
        .sum();
    Ok((out, unresolved))
}

/// Fills one column's cells (column `c` of the grid) with the union's volume: 1 when
/// the column holds open cells that could not be resolved (they keep their lower
/// bound), else 0.
fn cell_column<S: Surface>(model: &Bodies<'_, S>, c: usize, cells: &mut [f64]) -> usize {
    let nz = cells.len();
    let mut open = false;
    for (k, v) in cells.iter_mut().enumerate() {
        *v = match model.cell(c * nz + k) {
            Cell::Exact(x) => x,
            Cell::Open { lower, .. } => {
                open = true;
                lower
            }
        };
    }
    if !open {
        return 0;
    }
    match model.exact_column(c) {
        Some((exact, _)) => {
            cells.copy_from_slice(&exact);
            0
        }
        None => 1,
    }
}
