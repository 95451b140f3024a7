//! How many x layers of a region one slab holds on the device.
//!
//! A region's cells in C order are its x layers one after another, so a run of x layers
//! is a block of the grid whose cells are a contiguous run of the region's: a slab.
//! `cell_volumes_region` of a block is the same code path as the whole grid's, bit for
//! bit (the Dask blocks rely on it), so a region computed a slab at a time is the
//! region's cells, whatever the slabs (the cut cells' per-column stage too: a column's
//! values depend on its own pieces only). What bounds a slab is the device's memory:
//! its cells and its columns' sums are the buffers that grow with the grid.

use crate::Error;
use std::ops::Range;

/// What the device gives one slab's cells and column sums.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Budget {
    /// Bytes for all those buffers together.
    pub(crate) bytes: u64,
    /// The device's largest single allocation: each buffer stays within it.
    pub(crate) max_alloc: u64,
}

/// The x layers of each slab of `region` (x range `x`, `width` columns a layer), a
/// column needing `values` f64 on the device in all and `largest` in its largest buffer
/// (the volumes: `depth` cells and `areas` area sums, `[depth + areas, areas]`): as many
/// as `budget` allows, at least one. A single layer over the budget is refused, naming
/// `device`.
pub(crate) fn rows_per_slab(
    x: &Range<usize>,
    width: usize,
    [values, largest]: [usize; 2],
    budget: Budget,
    device: &str,
) -> Result<usize, Error> {
    let layer = |values: usize| width as u128 * values as u128 * 8;
    let both = layer(values);
    let rows = (budget.bytes as u128 / both).min(budget.max_alloc as u128 / layer(largest));
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
