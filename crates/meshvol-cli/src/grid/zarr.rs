//! `meshvol grid --out cells.zarr`: the grid computed and written one chunk row at a time
//! (the chunks that share their x cells), so that memory holds `CX × NY × NZ` cells
//! however large the grid. Each row is a block of the grid (`cell_volumes_region`): the
//! same bits as the whole grid's cells, and the rows in order are the whole array in C
//! order, so the summary's total is the in-memory one's.
//!
//! With `--moments`, a Zarr group of the cut-cell arrays: the x apertures are sums from
//! the grid's far x face down, so the rows are computed from the far face down
//! (`cut_cells_rows`: each alone, the same bits as the whole grid's), and the summary's
//! total from the rows' volumes again from the near face (the volume kernel alone: the
//! same bits as the cut cells' volumes, summed in the in-memory order).

use crate::input::Progress;
use meshvol::grid::{cell_volumes_region, cut_cells_rows, CutCells, Extras, Grid};
use meshvol::Surface;
use meshvol_io::grid_out::zarr::{ZarrCells, ZarrGroup};
use meshvol_io::grid_out::{cut_cell_arrays, CellValues};
use meshvol_report::grid::{check_memory, tallied_summary, CellTally, GridReport, GridRun};
use meshvol_report::reported_cells;
use meshvol_report::units::Scale;
use std::path::Path;
use std::time::Instant;

/// Chunks along each axis when --chunks is not given: 2 MiB of float64, a common size
/// for Zarr readers.
const DEFAULT_CHUNK: usize = 64;

/// The chunk shape: --chunks, or [`DEFAULT_CHUNK`], at most the grid's counts (a larger
/// chunk would only pad it with zeros).
fn chunk_shape(grid: &Grid, chunks: Option<[usize; 3]>) -> [usize; 3] {
    [0, 1, 2].map(|a| chunks.map_or(DEFAULT_CHUNK, |c| c[a]).min(grid.counts[a]))
}

/// A grid written to a `.zarr` at `out`: computed on `grid` (the file's coordinates),
/// each row converted to the units of `scale` before it is written and tallied.
pub struct Write<'a> {
    pub grid: &'a Grid,
    pub scale: &'a Scale,
    pub out: &'a Path,
    pub chunks: Option<[usize; 3]>,
}

impl Write<'_> {
    /// Computes the cut cells row by row, from the far x face down, into a Zarr group
    /// (module docs); with a density, `mass` beside `volume`.
    pub fn cut_cells<S: Surface + ?Sized>(
        &self,
        surface: &S,
        extras: Extras,
        mut run: GridRun,
        progress: &Progress,
    ) -> Result<GridReport, String> {
        let (grid, scale) = (self.grid, self.scale);
        let reported = reported_cells::grid(scale, grid)?;
        let chunks = chunk_shape(grid, self.chunks);
        let [_, ny, nz] = grid.counts;
        // A row of the cut cells (and its faces), a row of volumes for the tally, and the
        // copy of one chunk per thread beside them.
        let arrays = CutCells::bytes_with(grid, extras) / grid.array_bytes().max(1) + 2;
        check_memory([chunks[0], ny, nz], arrays, "chunk row")?;
        let name = self.out.display();
        let mut group =
            ZarrGroup::create(self.out, &reported, chunks).map_err(|e| format!("{name}: {e}"))?;
        let mut rows =
            cut_cells_rows(surface, grid, chunks[0], extras).map_err(|e| e.to_string())?;
        // The seconds computing, not writing (as for the volumes).
        let mut seconds = 0.0;
        for row in (0..group.rows()).rev() {
            progress.stage_all(&format!(
                "computing chunk row {} of {} (from the far x face)",
                row + 1,
                group.rows()
            ));
            let start = Instant::now();
            let mut cells = match rows.next() {
                Some(cells) => cells.map_err(|e| e.to_string())?,
                None => break,
            };
            seconds += start.elapsed().as_secs_f64();
            debug_assert_eq!(cells.region[0], group.row_cells(row));
            reported_cells::cut_cells(scale, &mut cells)?;
            let arrays = cut_cell_arrays(&cells, scale.mass_per_volume());
            group.write_row(row, &arrays).map_err(|e| format!("{name}: {e}"))?;
        }
        let start = Instant::now();
        let rows = (0..group.rows()).map(|r| group.row_cells(r));
        let tally = self.tally_rows(surface, &reported, rows, progress)?;
        run.seconds = seconds + start.elapsed().as_secs_f64();
        run.chunks = Some(chunks);
        Ok(tallied_summary(&reported, &tally, run))
    }

    /// The summary's tally of the cells' volumes, row by row from the near x face (C
    /// order), in the reported units.
    fn tally_rows<S: Surface + ?Sized>(
        &self,
        surface: &S,
        reported: &Grid,
        rows: impl Iterator<Item = std::ops::Range<usize>>,
        progress: &Progress,
    ) -> Result<CellTally, String> {
        let [_, ny, nz] = self.grid.counts;
        let mut tally = CellTally::default();
        for cells in rows {
            progress.stage_all(&format!("summing the volumes of cells {cells:?} along x"));
            let mut volumes = cell_volumes_region(surface, self.grid, &[cells, 0..ny, 0..nz])
                .map_err(|e| e.to_string())?;
            reported_cells::volumes(self.scale, &mut volumes);
            tally.add(reported, &volumes);
        }
        Ok(tally)
    }

    /// Computes the cells row by row into a Zarr array of `values`.
    pub fn cells<S: Surface + ?Sized>(
        &self,
        surface: &S,
        values: CellValues,
        mut run: GridRun,
        progress: &Progress,
    ) -> Result<GridReport, String> {
        let grid = self.grid;
        let reported = reported_cells::grid(self.scale, grid)?;
        let chunks = chunk_shape(grid, self.chunks);
        let [_, ny, nz] = grid.counts;
        // The row of cells, and the copy of one chunk per thread beside it.
        check_memory([chunks[0], ny, nz], 1, "chunk row")?;
        let name = self.out.display();
        let cells = ZarrCells::create(self.out, &reported, chunks, values)
            .map_err(|e| format!("{name}: {e}"))?;
        let mut tally = CellTally::default();
        let mut seconds = 0.0;
        for row in 0..cells.rows() {
            progress.stage_all(&format!("computing chunk row {} of {}", row + 1, cells.rows()));
            let start = Instant::now();
            let region = [cells.row_cells(row), 0..ny, 0..nz];
            let mut volumes =
                cell_volumes_region(surface, grid, &region).map_err(|e| e.to_string())?;
            seconds += start.elapsed().as_secs_f64();
            reported_cells::volumes(self.scale, &mut volumes);
            tally.add(&reported, &volumes);
            cells.write_row(row, &volumes).map_err(|e| format!("{name}: {e}"))?;
        }
        run.seconds = seconds;
        run.chunks = Some(chunks);
        Ok(tallied_summary(&reported, &tally, run))
    }
}
