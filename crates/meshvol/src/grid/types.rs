//! What a grid is ([`Grid`], a [`Region`] of it) and why one cannot be used ([`GridError`]): a leaf below mod.rs.

use crate::Point;
use std::ops::Range;

/// A regular grid: `counts[a]` cells of size `cell[a]` along axis `a`, starting at
/// `origin`. Cell `(i, j, k)` spans `origin + (i, j, k)·cell` to `origin + (i+1, j+1,
/// k+1)·cell` and is entry `(i·ny + j)·nz + k` of a cell array (C order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    pub origin: Point,
    pub cell: [f64; 3],
    pub counts: [usize; 3],
}

/// Why a grid cannot be used.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum GridError {
    #[error("a grid needs at least one cell along each axis; got {}×{}×{}", .counts[0], .counts[1], .counts[2])]
    NoCells { counts: [usize; 3] },
    #[error("cell sizes must be positive and finite; got {}, {}, {}", .cell[0], .cell[1], .cell[2])]
    BadCellSize { cell: [f64; 3] },
    #[error("cells of {:e} × {:e} × {:e} have a volume beyond f64 (it overflows): use smaller cells", .cell[0], .cell[1], .cell[2])]
    CellVolumeOverflow { cell: [f64; 3] },
    #[error("the grid's origin must be finite; got ({}, {}, {})", .origin[0], .origin[1], .origin[2])]
    BadOrigin { origin: Point },
    #[error("the bounds are empty along {axis} (from {min} to {max}): give bounds with min < max")]
    EmptyBounds { axis: char, min: f64, max: f64 },
    #[error("a {}×{}×{} grid has {cells} cells, which would need {} of memory for its f64 cell volumes", .counts[0], .counts[1], .counts[2], bytes_text(*.bytes))]
    TooManyCells { counts: [usize; 3], cells: u128, bytes: u128 },
    #[error("could not allocate {} for the cell volumes", bytes_text(*.bytes))]
    OutOfMemory { bytes: u128 },
    #[error("a pitch of {pitch:e} along {axis} across {extent:e} gives about {:.1e} cells on that axis alone: use a larger pitch", extent / pitch)]
    PitchTooFine { axis: char, pitch: f64, extent: f64 },
    #[error("{triangles} triangles are more than a device's 32-bit triangle index can number: use the CPU (--backend cpu)")]
    TooManyTriangles { triangles: usize },
    #[error("the region is empty along {axis} (cells {start}..{end}): give start < end")]
    EmptyRegion { axis: char, start: usize, end: usize },
    #[error("the region's cells {start}..{end} along {axis} reach beyond the grid's {cells} cells on that axis")]
    RegionOutsideGrid { axis: char, start: usize, end: usize, cells: usize },
}

/// `bytes` in binary units: `512 B`, `1.5 GiB`, `8.0 EiB`.
pub fn bytes_text(bytes: u128) -> String {
    const UNITS: [&str; 7] = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

impl Grid {
    /// A grid from its origin, cell size and counts, checked: finite origin, positive
    /// finite cell sizes, at least one cell per axis, and a cell count whose f64 array
    /// fits in memory addresses.
    pub fn new(origin: Point, cell: [f64; 3], counts: [usize; 3]) -> Result<Grid, GridError> {
        if origin.iter().any(|x| !x.is_finite()) {
            return Err(GridError::BadOrigin { origin });
        }
        if cell.iter().any(|&d| !(d.is_finite() && d > 0.0)) {
            return Err(GridError::BadCellSize { cell });
        }
        if counts.contains(&0) {
            return Err(GridError::NoCells { counts });
        }
        // Every cell volume is a multiple of this: if it overflows, so do they.
        if !(cell[0] * cell[1] * cell[2]).is_finite() {
            return Err(GridError::CellVolumeOverflow { cell });
        }
        let cells = counts.iter().map(|&n| n as u128).product::<u128>();
        let bytes = cells * 8;
        if bytes > isize::MAX as u128 {
            return Err(GridError::TooManyCells { counts, cells, bytes });
        }
        Ok(Grid { origin, cell, counts })
    }

    /// `counts` cells between `min` and `max`.
    ///
    /// ```
    /// use meshvol::grid::Grid;
    /// let g = Grid::from_bounds([0.0; 3], [1.0, 2.0, 4.0], [4, 4, 4]).unwrap();
    /// assert_eq!(g.cell, [0.25, 0.5, 1.0]);
    /// assert!(Grid::from_bounds([0.0; 3], [1.0, 0.0, 1.0], [4, 4, 4]).is_err());
    /// ```
    pub fn from_bounds(min: Point, max: Point, counts: [usize; 3]) -> Result<Grid, GridError> {
        check_bounds(min, max)?;
        let cell = [0, 1, 2].map(|a| (max[a] - min[a]) / counts[a] as f64);
        Grid::new(min, cell, counts)
    }

    /// Cells of size `pitch` from `min`, enough of them to reach `max` (the last cell
    /// may end beyond it). An axis where `min = max` gets one cell.
    ///
    /// ```
    /// use meshvol::grid::Grid;
    /// let g = Grid::with_pitch([0.0; 3], [1.0, 0.3, 0.0], [0.25; 3]).unwrap();
    /// assert_eq!(g.counts, [4, 2, 1]);
    /// ```
    pub fn with_pitch(min: Point, max: Point, pitch: [f64; 3]) -> Result<Grid, GridError> {
        if pitch.iter().any(|&d| !(d.is_finite() && d > 0.0)) {
            return Err(GridError::BadCellSize { cell: pitch });
        }
        if let Some(a) = (0..3).find(|&a| {
            let ordered = max[a] >= min[a] && (max[a] - min[a]).is_finite();
            !ordered
        }) {
            return Err(GridError::EmptyBounds { axis: AXES[a], min: min[a], max: max[a] });
        }
        let counts = [0, 1, 2].map(|a| ((max[a] - min[a]) / pitch[a]).ceil().max(1.0));
        // Counts that do not fit an index are named by axis, not printed saturated.
        if let Some(a) = (0..3).find(|&a| counts[a] >= u32::MAX as f64) {
            let (pitch, extent) = (pitch[a], max[a] - min[a]);
            return Err(GridError::PitchTooFine { axis: AXES[a], pitch, extent });
        }
        Grid::new(min, pitch, counts.map(|n| n as usize))
    }

    /// The number of cells.
    pub fn cell_count(&self) -> usize {
        self.counts.iter().product()
    }

    /// dx·dy·dz.
    pub fn cell_volume(&self) -> f64 {
        self.cell[0] * self.cell[1] * self.cell[2]
    }

    /// The far corner, `origin + counts·cell`.
    pub fn max(&self) -> Point {
        [0, 1, 2].map(|a| self.origin[a] + self.counts[a] as f64 * self.cell[a])
    }

    /// The position of cell `(i, j, k)` in a cell array.
    pub fn index(&self, [i, j, k]: [usize; 3]) -> usize {
        (i * self.counts[1] + j) * self.counts[2] + k
    }

    /// Bytes of the f64 cell array.
    pub fn array_bytes(&self) -> u128 {
        self.counts.iter().map(|&n| n as u128).product::<u128>() * 8
    }
}

const AXES: [char; 3] = ['x', 'y', 'z'];

fn check_bounds(min: Point, max: Point) -> Result<(), GridError> {
    match (0..3).find(|&a| {
        let ordered = max[a] > min[a] && (max[a] - min[a]).is_finite();
        !ordered
    }) {
        Some(a) => Err(GridError::EmptyBounds { axis: AXES[a], min: min[a], max: max[a] }),
        None => Ok(()),
    }
}

/// The cells `x × y × z` of a grid (ranges of cell indices along each axis): a block of
/// it, as [`cell_volumes_region`](super::cell_volumes_region) computes it.
pub type Region = [Range<usize>; 3];

/// Refuses a region that is not inside the grid with at least one cell along each
/// axis, as [`cell_volumes_region`](super::cell_volumes_region) does (a device that splits a region checks it first:
/// an empty one would otherwise split into nothing and give no error).
pub fn check_region(grid: &Grid, region: &Region) -> Result<(), GridError> {
    for (a, range) in region.iter().enumerate() {
        let (axis, start, end, cells) = (AXES[a], range.start, range.end, grid.counts[a]);
        if start >= end {
            return Err(GridError::EmptyRegion { axis, start, end });
        }
        if end > cells {
            return Err(GridError::RegionOutsideGrid { axis, start, end, cells });
        }
    }
    Ok(())
}
