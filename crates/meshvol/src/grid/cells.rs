//! The column–clamp kernel: per-cell volumes of the solid a surface bounds.
//!
//! See the [module docs](super) for the math. This file holds the three sweeps that cut
//! a triangle into the parts the integral needs, the sinks that add those parts up,
//! and the parallel driver over column tiles.
//!
//! # Coordinates
//! Every vertex is mapped once to grid units, `u = (p − origin) / cell` per axis, so
//! that column `(i, j)` is `[i, i+1] × [j, j+1]` and layer `k` is `[k, k+1]`; a cell's
//! volume is 1 there and results are scaled by `dx·dy·dz` at the end. Sums are taken in
//! these local coordinates (differences within a piece, heights within a layer), never
//! about the world origin.
//!
//! # Sweeps
//! A triangle is cut into x-strips, each strip into columns, each column piece into
//! layers, by successive splits of what is left ([`Polygon::split_axis`]). The first
//! strip of a triangle, and the first column of a strip, depend only on the triangle,
//! so a piece is the same bits whichever tile asks for it.
//!
//! # Tiles
//! Columns are numbered `c = i·ny + j`; cell `(i, j, k)` is entry `c·nz + k` of the
//! output (C order), so a run of columns is a contiguous slice. A tile is such a run.
//! Faces are binned by the tiles their bounding box meets (in fixed chunks of faces, in
//! face order), and each tile adds up its pieces in face order into its own slice and a
//! scratch array of `(columns)·(nz + 1)` areas. Every cell therefore receives the same
//! terms in the same order for any tile size and any number of threads: the result is
//! the same bits.
//!
//! # Blocks
//! The kernel computes a [`Block`] of the grid: its columns are numbered within the
//! block, its layers' integrals are kept, and the areas of every layer from the block's
//! first to the grid's top are accumulated, so that [`finish_column`] runs the same
//! suffix sum from the top of the grid down. The pieces come from the same sweeps (from
//! the triangle's first strip, column and layer), so a cell gets the same terms in the
//! same order in any block; the whole grid is the block of all cells.

use super::clip::Polygon;
use super::layout::floor;
pub(crate) use super::layout::{cover, Bins, Block, Tiling, Units};
use super::{Grid, GridError};
use crate::accumulate::two_sum;
use crate::progress::{Counter, Progress};
use crate::Surface;
use rayon::prelude::*;
use std::mem::MaybeUninit;
use std::ops::Range;

/// Triangles cut by at most six planes have at most nine vertices.
pub(crate) type Piece = Polygon<9>;

/// Receives the parts of column pieces, layer by layer.
pub(crate) trait LayerSink {
    /// The part of a piece in layer `layer` (`layer ≤ z ≤ layer + 1`).
    fn slab<const N: usize>(&mut self, layer: usize, part: &Polygon<N>);
    /// The part above the top plane (`z ≥ nz`).
    fn above<const N: usize>(&mut self, part: &Polygon<N>);
}

/// Cuts a column piece at the layer planes and hands each part to `sink`.
///
/// `(z0, z1)` is the piece's z range. Parts below z = 0 contribute to no layer and are
/// dropped; a horizontal piece exactly on plane `m` counts as layer `m`'s (it adds its
/// area to the layers below and nothing to layer `m` itself; on plane 0, to nothing).
#[inline(always)]
pub(crate) fn sweep_layers<const N: usize>(
    piece: &Polygon<N>,
    (z0, z1): (f64, f64),
    nz: usize,
    sink: &mut impl LayerSink,
) {
    if z1 < 0.0 || (z1 == 0.0 && z0 < 0.0) {
        return;
    }
    let top = nz as f64;
    if z0 >= top {
        sink.above(piece);
        return;
    }
    let lo = floor(z0).max(0.0);
    if z0 >= lo && z1 <= lo + 1.0 {
        // Within one layer: the common case for meshes finer than the grid.
        sink.slab(lo as usize, piece);
        return;
    }
    let mut bufs = [Polygon::EMPTY; 3];
    let [part, rest, spare] = &mut bufs;
    if z0 < lo {
        piece.split_axis_into(2, lo, part, rest);
    } else {
        *rest = *piece;
    }
    let mut k = lo as usize;
    loop {
        let next = (k + 1) as f64;
        if z1 <= next {
            sink.slab(k, rest);
            return;
        }
        rest.split_axis_into(2, next, part, spare);
        std::mem::swap(rest, spare);
        sink.slab(k, part);
        if k + 1 == nz {
            sink.above(rest);
            return;
        }
        k += 1;
    }
}

/// Cuts `poly` at the planes `axis = i + 1` into the slices `i` in `cells` (from
/// [`cover`] of its range `(lo, hi)` with the same `closed`), calling `slice(i, part)`
/// in order until it returns false. Parts beyond the grid are dropped.
#[inline(always)]
pub(crate) fn sweep_axis<const N: usize>(
    poly: &Polygon<N>,
    axis: usize,
    (lo, hi): (f64, f64),
    (start, end): (usize, usize),
    closed: bool,
    mut slice: impl FnMut(usize, &Polygon<N>) -> bool,
) {
    if start >= end {
        return;
    }
    let last = |i: usize| {
        let next = (i + 1) as f64;
        (closed && hi < next) || (!closed && hi <= next)
    };
    if lo >= start as f64 && last(start) {
        slice(start, poly);
        return;
    }
    let mut bufs = [Polygon::EMPTY; 3];
    let [part, rest, spare] = &mut bufs;
    if lo < start as f64 {
        poly.split_axis_into(axis, start as f64, part, rest);
    } else {
        *rest = *poly;
    }
    for i in start..end {
        if last(i) {
            slice(i, rest);
            return;
        }
        rest.split_axis_into(axis, (i + 1) as f64, part, spare);
        std::mem::swap(rest, spare);
        if !slice(i, part) {
            return;
        }
    }
}

/// Adds a column's parts: `direct[k − first] += ∫ (z − k) dA` of parts in layer k, and
/// `area[k − first] += A` of those parts (and `area[nz − first]` of parts above the
/// grid), for the suffix sum that credits every layer below a part with its area.
///
/// `direct` holds the layers `first..first + direct.len()` of a region; `area` every
/// layer from `first` up, since the layers above the region hand their areas down into
/// it. Parts below `first` only add to layers below the region and are dropped. Parts
/// above the region add their area alone, the same bits as `area_and_moment`'s.
pub(crate) struct ColumnSink<'a> {
    pub(crate) direct: &'a mut [f64],
    pub(crate) area: &'a mut [f64],
    pub(crate) first: usize,
}

impl LayerSink for ColumnSink<'_> {
    #[inline(always)]
    fn slab<const N: usize>(&mut self, layer: usize, part: &Polygon<N>) {
        let Some(local) = layer.checked_sub(self.first) else {
            return;
        };
        if local < self.direct.len() {
            let (area, moment) = part.area_and_moment(layer as f64);
            self.direct[local] += moment;
            self.area[local] += area;
        } else {
            self.area[local] += part.area();
        }
    }

    #[inline(always)]
    fn above<const N: usize>(&mut self, part: &Polygon<N>) {
        let top = self.area.len() - 1;
        self.area[top] += part.area();
    }
}

/// Finishes a column: `cell[k] = (direct[k] + Σ_{m > k} area[m]) · scale`, the running
/// sum compensated (TwoSum) and taken from the top of the grid down.
///
/// `area` runs from the region's first layer to the grid's top (`nz − first + 1`
/// entries) and `direct` over the region's layers: the running sum passes through the
/// layers above the region without writing them, so a region's cells are the same
/// operations on the same terms as the whole column's.
pub(crate) fn finish_column(direct: &mut [f64], area: &[f64], scale: f64) {
    let (mut sum, mut compensation) = (0.0, 0.0);
    for k in (0..area.len() - 1).rev() {
        let (s, e) = two_sum(sum, area[k + 1]);
        sum = s;
        compensation += e;
        if let Some(cell) = direct.get_mut(k) {
            *cell = (*cell + (sum + compensation)) * scale;
        }
    }
}

/// Column pieces of one triangle (grid units) within a run of `block`'s columns: calls
/// `piece(column − first column, piece)` for each column of `columns` the triangle
/// overlaps. The strips and pieces are cut from the triangle's first row and column
/// whichever run asks, so they are the same bits for any block.
#[inline(always)]
pub(crate) fn for_each_piece(
    triangle: &Piece,
    block: &Block,
    columns: &Range<usize>,
    closed: bool,
    mut piece: impl FnMut(usize, &Piece),
) {
    let [nx, ny, _] = block.counts;
    let (x0, y0, width) = (block.region[0].start, block.region[1].start, block.region[1].len());
    let (first_row, last_row) = (x0 + columns.start / width, x0 + (columns.end - 1) / width);
    let x = triangle.range(0);
    sweep_axis(triangle, 0, x, cover(x.0, x.1, nx, closed), closed, |i, strip| {
        if i < first_row {
            return true;
        }
        if i > last_row {
            return false;
        }
        let j_lo = y0 + if i == first_row { columns.start % width } else { 0 };
        let j_hi = y0 + if i == last_row { (columns.end - 1) % width + 1 } else { width };
        let row = (i - x0) * width;
        let y = strip.range(1);
        sweep_axis(strip, 1, y, cover(y.0, y.1, ny, closed), closed, |j, part| {
            if j < j_lo {
                return true;
            }
            if j >= j_hi {
                return false;
            }
            piece(row + j - y0 - columns.start, part);
            true
        });
        true
    });
}

/// An array of `len` zero entries, or the error naming the memory it needed.
///
/// Zeroed by the allocator (`calloc`: fresh memory from the system is zero already) and
/// then written, by all the workers, once a page: the first touch of fresh memory (the
/// system's fault and zeroing of each page) is most of the cost of a large array, and
/// it happens here in parallel, on a write. A write, because the sweeps add into the
/// cells: a page first read would map the system's shared zero page and fault again,
/// copying it, on the first write (with 4 KiB pages, as under the system allocator in
/// Python, the cut cells at 256³ took 4.1 s against 0.90 s so, two cores, 9 µs a fault
/// on a VM). Not `vec!`: it writes the zeros on one thread (in a profile of
/// `grid --moments` at 256³, 1.9 GB of arrays, the page zeroing under that thread was
/// 44% of the run, the workers idle). Nor all the zeros written by the workers, as
/// before: that is a pass over the arrays that the allocator's zeros make needless.
pub(crate) fn zeroed<T: bytemuck::Zeroable + Send>(len: usize) -> Result<Vec<T>, GridError> {
    let bytes = len as u128 * std::mem::size_of::<T>() as u128;
    let mut out = bytemuck::allocation::try_zeroed_vec::<T>(len)
        .map_err(|_| GridError::OutOfMemory { bytes })?;
    // Runs of at most a page: every page of the array holds a run's first entry.
    let per_page = (TOUCH_BYTES / std::mem::size_of::<T>().max(1)).max(1);
    out.par_chunks_mut(per_page).for_each(|run| {
        // SAFETY: `run` is a non-empty slice of the array, so its first entry is valid
        // for writes. Volatile: the compiler may drop a plain store of zeros into memory
        // it knows the allocator zeroed, and the store is here for the fault it takes.
        unsafe { std::ptr::write_volatile(run.as_mut_ptr(), T::zeroed()) }
    });
    Ok(out)
}

/// The smallest page size of the systems meshvol runs on: [`zeroed`] writes an entry
/// at least this often.
const TOUCH_BYTES: usize = 4096;

/// Adds the column pieces of `faces` that fall in `columns` (a run of `block`'s
/// columns) to `cells` (the run's cells) and `area` ([`Block::areas`] per column), in
/// face order; call [`finish_column`] after the last face. With `CLOSED`, also marks in
/// `touched` every cell of the run whose closed box a triangle meets (degenerate pieces
/// on cell faces included); `touched` is not used otherwise.
#[allow(clippy::too_many_arguments)]
pub(crate) fn add_faces<S: Surface + ?Sized, const CLOSED: bool>(
    surface: &S,
    faces: impl Iterator<Item = usize>,
    units: &Units,
    block: &Block,
    columns: &Range<usize>,
    cells: &mut [f64],
    area: &mut [f64],
    touched: &mut [u8],
) {
    let nz = block.counts[2];
    let layers = &block.region[2];
    let (depth, areas) = (layers.len(), block.areas());
    for face in faces {
        surface.fan(face, |a, b, c| {
            let t = Piece::triangle(units.map(a), units.map(b), units.map(c));
            let flat = t.area() == 0.0;
            if flat && !CLOSED {
                return; // edge-on: no projected area, nothing to add
            }
            for_each_piece(&t, block, columns, CLOSED, |column, piece| {
                let z = piece.range(2);
                if CLOSED {
                    let (k0, k1) = cover(z.0, z.1, nz, true);
                    let (k0, k1) = (k0.max(layers.start), k1.min(layers.end));
                    if k0 < k1 {
                        let first = column * depth;
                        touched[first + k0 - layers.start..first + k1 - layers.start].fill(1);
                    }
                }
                if !flat {
                    let mut sink = ColumnSink {
                        direct: &mut cells[column * depth..(column + 1) * depth],
                        area: &mut area[column * areas..(column + 1) * areas],
                        first: layers.start,
                    };
                    sweep_layers(piece, z, nz, &mut sink);
                }
            });
        });
    }
}

/// Per-cell volumes (the [module docs](super)) of `block` of a validated `grid`, in C
/// order within the block; with `touched` (one entry per cell of the block), also marks
/// the cells the surface meets (closed boxes).
///
/// The whole grid is the block of all its cells: every block runs this one path, and a
/// cell receives the same terms in the same order whichever block holds it.
pub(crate) fn cell_volumes<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    block: &Block,
    touched: Option<&mut [u8]>,
) -> Result<Vec<f64>, GridError> {
    cell_volumes_with(surface, grid, block, touched, &())
}

/// [`cell_volumes`], telling `progress` its stages and the tiles of columns done.
pub(crate) fn cell_volumes_with<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    block: &Block,
    touched: Option<&mut [u8]>,
    progress: &dyn Progress,
) -> Result<Vec<f64>, GridError> {
    let [_, _, depth] = block.shape();
    // The cells are zeroed by the worker that fills each tile, as it starts the tile
    // (first touch): zeroing the whole array first was serial, and at 512³ (1 GiB) took
    // longer on one thread than the kernel.
    let len = block.columns() * depth;
    let mut out: Vec<f64> = Vec::new();
    out.try_reserve_exact(len).map_err(|_| GridError::OutOfMemory { bytes: len as u128 * 8 })?;
    let tiling = Tiling::new(block);
    progress.stage("sorting faces into tiles of columns");
    let bins = Bins::new(surface, grid, block, &tiling, touched.is_some());
    progress.stage("cutting faces into cells");
    let done = Counter::new(progress, tiling.tiles());
    let units = Units::new(grid);
    let scale = grid.cell_volume();
    let (tile_cells, areas) = (tiling.per_tile * depth, block.areas());
    let run = |tile: usize, cells: &mut [f64], touched: &mut [u8], closed: bool| {
        let columns = tiling.range(tile);
        let mut area = vec![0.0; columns.len() * areas];
        let faces = bins.faces(tile);
        // One call for both kinds of tile: the kernel is compiled for each.
        type Add<'s, S, I> =
            fn(&'s S, I, &Units, &Block, &Range<usize>, &mut [f64], &mut [f64], &mut [u8]);
        let add: Add<S, _> = if closed { add_faces::<S, true> } else { add_faces::<S, false> };
        add(surface, faces, &units, block, &columns, cells, &mut area, touched);
        for (direct, area) in cells.chunks_mut(depth).zip(area.chunks(areas)) {
            finish_column(direct, area, scale);
        }
        done.add(1);
    };
    let zero = |cells: &mut [MaybeUninit<f64>]| -> &mut [f64] {
        cells.fill(MaybeUninit::new(0.0));
        // SAFETY: every element was just written.
        unsafe { &mut *(cells as *mut [MaybeUninit<f64>] as *mut [f64]) }
    };
    let spare = &mut out.spare_capacity_mut()[..len];
    match touched {
        Some(touched) => spare
            .par_chunks_mut(tile_cells)
            .zip(touched.par_chunks_mut(tile_cells))
            .enumerate()
            .for_each(|(tile, (cells, touched))| run(tile, zero(cells), touched, true)),
        None => spare
            .par_chunks_mut(tile_cells)
            .enumerate()
            .for_each(|(tile, cells)| run(tile, zero(cells), &mut [], false)),
    }
    // SAFETY: the chunks cover the first `len` elements, each zeroed and then filled.
    unsafe { out.set_len(len) };
    Ok(out)
}
