//! `meshvol grid --out cells.zarr`: the grid computed and written one chunk row at a time
//! (the chunks that share their x cells), so that memory holds `CX × NY × NZ` cells
//! however large the grid. Each row is a block of the grid (`cell_volumes_region`): the
//! same bits as the whole grid's cells, and the rows in order are the whole array in C
//! order, so the summary's total is the in-memory one's.

use crate::input::Progress;
use meshvol::grid::{cell_volumes_region, Grid};
use meshvol::Surface;
use meshvol_io::grid_out::zarr::ZarrCells;
use meshvol_report::grid::{check_memory, tallied_summary, CellTally, GridReport, GridRun};
use std::path::Path;
use std::time::Instant;

/// Chunks along each axis when --chunks is not given: 2 MiB of float64, a common size
/// for Zarr readers.
const DEFAULT_CHUNK: usize = 64;

/// Computes the cells of `grid` row by row into a Zarr array at `out`.
pub fn write<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    out: &Path,
    chunks: Option<[usize; 3]>,
    mut run: GridRun,
    progress: &Progress,
) -> Result<GridReport, String> {
    // A chunk larger than the grid would only pad it with zeros.
    let chunks = [0, 1, 2].map(|a| chunks.map_or(DEFAULT_CHUNK, |c| c[a]).min(grid.counts[a]));
    let [_, ny, nz] = grid.counts;
    // The row of cells, and the copy of one chunk per thread beside it.
    check_memory([chunks[0], ny, nz], 1, "chunk row")?;
    let name = out.display();
    let cells =
        ZarrCells::create(out, grid, chunks, run.fraction).map_err(|e| format!("{name}: {e}"))?;
    let mut tally = CellTally::default();
    let mut seconds = 0.0;
    for row in 0..cells.rows() {
        progress.stage_all(&format!("computing chunk row {} of {}", row + 1, cells.rows()));
        let start = Instant::now();
        let region = [cells.row_cells(row), 0..ny, 0..nz];
        let volumes = cell_volumes_region(surface, grid, &region).map_err(|e| e.to_string())?;
        seconds += start.elapsed().as_secs_f64();
        tally.add(grid, &volumes);
        cells.write_row(row, &volumes).map_err(|e| format!("{name}: {e}"))?;
    }
    run.seconds = seconds;
    run.chunks = Some(chunks);
    Ok(tallied_summary(grid, &tally, run))
}
