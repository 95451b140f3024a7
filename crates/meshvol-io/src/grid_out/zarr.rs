//! Grids as Zarr v3 arrays, written chunk by chunk: a grid that does not fit in memory
//! goes to disk one slab of chunks (a *chunk row*: the chunks that share their x cells)
//! at a time.
//!
//! The array (through the `zarrs` crate, filesystem store): float64 of shape `(nx, ny,
//! nz)`, regular chunks, the `bytes` codec (little-endian, no compression), fill value
//! 0, chunk keys `c/I/J/K`, dimension names `x`, `y`, `z`, and attributes `origin`,
//! `cell_size` (f64 numbers that read back to the same bits) and `values` (`volume` or
//! `fraction`). Chunks whose every cell is +0.0 are not stored (readers return the fill
//! value; a chunk left by an earlier array at the same path is erased), which leaves
//! the empty space around a solid off the disk; a chunk holding -0.0 is stored, so that
//! every value reads back as the same bits. Edge chunks are stored whole, padded with
//! zeros, as Zarr's regular grid has them.

use meshvol::grid::Grid;
use rayon::prelude::*;
use std::io;
use std::path::Path;
use std::sync::Arc;
use zarrs::array::codec::CodecOptions;
use zarrs::array::{Array, ArrayBuilder, DataType};
use zarrs::filesystem::FilesystemStore;

/// A Zarr array of a grid's cells, its metadata written, its chunks written by rows.
pub struct ZarrCells {
    array: Array<FilesystemStore>,
    counts: [usize; 3],
    chunks: [usize; 3],
    /// What each volume is divided by before it is stored (the cell volume for
    /// fractions).
    divisor: f64,
}

fn failed(e: impl std::fmt::Display) -> io::Error {
    io::Error::other(e.to_string())
}

impl ZarrCells {
    /// Creates the array at `path` (a directory; made if missing) for the cells of
    /// `grid` in chunks of `chunks` cells (each at least 1, at most the grid's count on
    /// its axis), and writes its metadata.
    pub fn create(
        path: &Path,
        grid: &Grid,
        chunks: [usize; 3],
        fraction: bool,
    ) -> io::Result<ZarrCells> {
        if (0..3).any(|a| chunks[a] == 0 || chunks[a] > grid.counts[a]) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("chunks {chunks:?} must be between 1 and the grid's {:?}", grid.counts),
            ));
        }
        if path.is_file() {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                "is a file: a Zarr array is a directory",
            ));
        }
        std::fs::create_dir_all(path)?;
        let store = Arc::new(FilesystemStore::new(path).map_err(failed)?);
        let attributes = serde_json::json!({
            "origin": grid.origin,
            "cell_size": grid.cell,
            "values": if fraction { "fraction" } else { "volume" },
        });
        let array = ArrayBuilder::new(
            grid.counts.map(|n| n as u64),
            chunks.map(|n| n as u64),
            DataType::Float64,
            0.0f64,
        )
        .dimension_names(Some(["x", "y", "z"]))
        .attributes(attributes.as_object().cloned().unwrap_or_default())
        .build(store, "/")
        .map_err(failed)?;
        array.store_metadata().map_err(failed)?;
        let divisor = if fraction { grid.cell_volume() } else { 1.0 };
        Ok(ZarrCells { array, counts: grid.counts, chunks, divisor })
    }

    /// Cells along x of chunk row `row`: the rows of cells [`ZarrCells::write_row`] takes.
    pub fn row_cells(&self, row: usize) -> std::ops::Range<usize> {
        let start = row * self.chunks[0];
        start..(start + self.chunks[0]).min(self.counts[0])
    }

    /// The number of chunk rows.
    pub fn rows(&self) -> usize {
        self.counts[0].div_ceil(self.chunks[0])
    }

    /// Writes chunk row `row` from `volumes`: the cells of [`ZarrCells::row_cells`]
    /// along x and every cell along y and z, in C order. The row's chunks are encoded
    /// and written in parallel.
    pub fn write_row(&self, row: usize, volumes: &[f64]) -> io::Result<()> {
        let [_, ny, nz] = self.counts;
        let [cx, cy, cz] = self.chunks;
        let xs = self.row_cells(row);
        if volumes.len() != xs.len() * ny * nz {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{} values for a row of {} cells", volumes.len(), xs.len() * ny * nz),
            ));
        }
        let (columns, layers) = (ny.div_ceil(cy), nz.div_ceil(cz));
        // One thread per chunk already: the codec need not split a chunk further.
        let mut options = CodecOptions::default();
        options.set_concurrent_target(1);
        (0..columns * layers).into_par_iter().try_for_each(|c| {
            let (bj, bk) = (c / layers, c % layers);
            let (j0, k0) = (bj * cy, bk * cz);
            let mut chunk = vec![0.0f64; cx * cy * cz];
            for i in 0..xs.len() {
                for j in j0..(j0 + cy).min(ny) {
                    let from = (i * ny + j) * nz;
                    let to = (i * cy + j - j0) * cz;
                    let k1 = (k0 + cz).min(nz);
                    for (out, v) in
                        chunk[to..to + k1 - k0].iter_mut().zip(&volumes[from + k0..from + k1])
                    {
                        *out = v / self.divisor;
                    }
                }
            }
            let at = [row as u64, bj as u64, bk as u64];
            self.array.store_chunk_elements_opt(&at, &chunk, &options).map_err(failed)
        })
    }
}
