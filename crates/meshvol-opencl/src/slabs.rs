//! How many x layers of a region one slab holds on the device.
//!
//! A region's cells in C order are its x layers one after another, so a run of x layers
//! is a block of the grid whose cells are a contiguous run of the region's: a slab.
//! `cell_volumes_region` of a block is the same code path as the whole grid's, bit for
//! bit (the Dask blocks rely on it), so a region computed a slab at a time is the
//! region's cells, whatever the slabs. What bounds a slab is the device's memory: its
//! cells and its columns' area sums are the two buffers that grow with the grid.

use crate::Error;
use std::ops::Range;

/// What the device gives one slab's cells and column area sums.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Budget {
    /// Bytes for both buffers together.
    pub(crate) bytes: u64,
    /// The device's largest single allocation: each buffer stays within it.
    pub(crate) max_alloc: u64,
}

/// The x layers of each slab of `region` (x range `x`, `width` columns a layer, `depth`
/// cells and `areas` area sums a column): as many as `budget` allows, at least one.
/// A single layer over the budget is refused, naming `device`.
pub(crate) fn rows_per_slab(
    x: &Range<usize>,
    width: usize,
    depth: usize,
    areas: usize,
    budget: Budget,
    device: &str,
) -> Result<usize, Error> {
    let layer = |values: usize| width as u128 * values as u128 * 8;
    let both = layer(depth) + layer(areas);
    // `areas` is at least `depth + 1` (the layers above the region too), so the area
    // sums are the larger buffer and the one the largest allocation bounds.
    let rows = (budget.bytes as u128 / both).min(budget.max_alloc as u128 / layer(areas));
    if rows == 0 {
        return Err(Error::SlabTooLarge {
            device: device.to_string(),
            bytes: both,
            budget: budget.bytes,
            max_alloc: budget.max_alloc,
        });
    }
    Ok(rows.min(x.len() as u128) as usize)
}

/// The slabs of `x`, `rows` layers each (the last may have fewer), in order.
pub(crate) fn slabs(x: &Range<usize>, rows: usize) -> impl Iterator<Item = Range<usize>> + '_ {
    x.clone().step_by(rows).map(move |s| s..(s + rows).min(x.end))
}
