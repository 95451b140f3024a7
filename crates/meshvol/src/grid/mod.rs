//! Exact per-cell volumes on a regular grid (the column–clamp method), volume-below-level
//! profiles, and the volume of a union of bodies with a certified interval.
//!
//! # The column–clamp method
//! Cell C = [x₀,x₁]×[y₀,y₁]×[z₀,z₁] of a solid Ω bounded by a closed surface S. Take the
//! field F = (0, 0, g(z)) with g(z) = clamp(z, z₀, z₁) − z₀. Its divergence is 1 inside
//! the slab z₀ < z < z₁ and 0 outside it, and on the four side walls of the column over
//! [x₀,x₁]×[y₀,y₁] F·n = 0. The divergence theorem on Ω ∩ column gives
//!
//! ```text
//! vol(Ω ∩ C) = ∫ over S ∩ column of g(z) n_z dA
//! ```
//!
//! with no closing of the clipped surface, no flood fill and no inside test. `n_z dA` is
//! the signed area of the surface's projection on the xy plane (positive where the
//! outward normal points up), so orientation takes care of itself: an inward-wound
//! surface gives negative cells. Per triangle:
//!
//! 1. clip its xy projection to each column it overlaps (a convex *piece*, on the stack);
//! 2. cut the piece at the layer planes z = k; for the part in layer k (z linear on it)
//!    `∫ g dA = ∫ (z − z_k) dA`, exact from the part's area and the mean of z over it;
//! 3. every layer below a part gets `A·dz` (A the part's signed projected area): add A to
//!    an accumulator at the part's layer, and let one suffix sum per column hand it down.
//!
//! Work is O(pieces + cells), not O(pieces × layers). Cells deep inside get their full
//! volume from the surfaces above and below them, cells outside get zero, each up to
//! rounding. Parts of the surface outside the grid's columns are dropped and parts above
//! or below it are clamped, so only the solid inside the grid counts.
//!
//! See [`cell_volumes`] (the grid), [`cell_volumes_region`] (a block of it, the same
//! bits), [`profile()`] (one column along any axis: volume below
//! each level, slab volumes, section areas) and [`union()`] (several bodies).

mod cells;
mod clip;
mod cut_cells;
pub(crate) mod intersect;
mod layout;
pub(crate) mod piece_moments;
mod profile;
mod tile_work;
mod union;

pub use cut_cells::{
    cut_cells, cut_cells_extras, cut_cells_region, cut_cells_rows, cut_cells_swept, cut_cells_with,
    cut_tile_work, CutCellRows, CutCells, Extras, SweptCells,
};
pub use intersect::{
    intersection, intersection_placed, intersection_with, overlapping_boxes, Bounded, Contact,
    Intersection, Method, Moments,
};
pub use profile::{profile, Axis, Levels, Profile, ProfileError, MAX_LEVELS};
pub use tile_work::{tile_work, TileWork};
pub use union::{
    union, union_boundary, union_boundary_with, union_cell_volumes, union_cell_volumes_with,
    union_with, UnionBoundary, UnionError, UnionVolume, COPLANAR_TOLERANCE, MAX_DEPTH, STALL,
};

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

/// The volume of the solid in each cell of `grid`, in C order (see [`Grid`]).
///
/// Exact up to rounding for any closed surface: negative where the surface is wound
/// inward, and only the part of the solid inside the grid counts. Parallel over tiles
/// of columns, with the same bits for any number of threads.
///
/// ```
/// use meshvol::grid::{cell_volumes, Grid};
/// use meshvol::shapes::cuboid;
/// // A 1.5 × 1 × 1 box on a grid of unit cells: one full cell and one half cell.
/// let grid = Grid::new([0.0; 3], [1.0; 3], [2, 1, 1]).unwrap();
/// let v = cell_volumes(&cuboid([0.0; 3], [1.5, 1.0, 1.0]), &grid).unwrap();
/// assert_eq!(v, vec![1.0, 0.5]);
/// ```
pub fn cell_volumes<S: crate::Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
) -> Result<Vec<f64>, GridError> {
    cell_volumes_with(surface, grid, &())
}

/// [`cell_volumes`], telling `progress` its stages and the tiles of columns (strips of
/// the grid's rows) done.
pub fn cell_volumes_with<S: crate::Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    progress: &dyn crate::progress::Progress,
) -> Result<Vec<f64>, GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    cells::cell_volumes_with(surface, &grid, &cells::Block::whole(grid.counts), None, progress)
}

/// The cells `x × y × z` of a grid (ranges of cell indices along each axis): a block of
/// it, as [`cell_volumes_region`] computes it.
pub type Region = [Range<usize>; 3];

/// The volume of the solid in each cell of `region` of `grid`, in C order within the
/// region (shape `region[a].len()` along axis `a`): the same bits as those cells of
/// [`cell_volumes`] over the whole grid.
///
/// A cell's volume takes the areas of the surface above it, so a region's columns are
/// cut through the grid's full height (the layers above the region hand their areas
/// down, in the same order as for the whole grid); only faces whose xy bounding box
/// meets the region's columns are cut. Blocks of one grid are therefore independent:
/// threads, processes or machines can each compute some and the cells agree exactly.
///
/// ```
/// use meshvol::grid::{cell_volumes, cell_volumes_region, Grid};
/// use meshvol::shapes::cuboid;
/// let grid = Grid::new([0.0; 3], [0.5; 3], [4, 4, 4]).unwrap();
/// let cube = cuboid([0.1; 3], [1.7, 1.3, 1.9]);
/// let all = cell_volumes(&cube, &grid).unwrap();
/// let block = cell_volumes_region(&cube, &grid, &[1..3, 2..4, 3..4]).unwrap();
/// assert_eq!(block, [all[grid.index([1, 2, 3])], all[grid.index([1, 3, 3])],
///                    all[grid.index([2, 2, 3])], all[grid.index([2, 3, 3])]]);
/// assert!(cell_volumes_region(&cube, &grid, &[0..5, 0..4, 0..4]).is_err());
/// ```
pub fn cell_volumes_region<S: crate::Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    region: &Region,
) -> Result<Vec<f64>, GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    check_region(&grid, region)?;
    let block = cells::Block { counts: grid.counts, region: region.clone() };
    cells::cell_volumes(surface, &grid, &block, None)
}

/// Refuses a region that is not inside the grid with at least one cell along each
/// axis, as [`cell_volumes_region`] does (a device that splits a region checks it first:
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

/// How many cells are empty, partial or full.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Occupancy {
    pub empty: usize,
    pub partial: usize,
    pub full: usize,
}

/// Cells whose volume is within this fraction of 0 or of the cell's volume count as
/// empty or full: far above the rounding of the column sums (about 10⁻¹³ of a cell on
/// a 512³ grid), far below any solid a user would model.
pub const OCCUPANCY_TOLERANCE: f64 = 1e-9;

/// Counts empty, partial and full cells of a cell array (by |volume|, so that inward
/// surfaces count the same), with [`OCCUPANCY_TOLERANCE`].
pub fn occupancy(volumes: &[f64], cell_volume: f64) -> Occupancy {
    let tolerance = OCCUPANCY_TOLERANCE * cell_volume;
    let mut o = Occupancy::default();
    for v in volumes {
        let v = v.abs();
        if v <= tolerance {
            o.empty += 1;
        } else if v >= cell_volume - tolerance {
            o.full += 1;
        } else {
            o.partial += 1;
        }
    }
    o
}

#[cfg(test)]
mod progress_tests {
    use super::{cell_volumes, cell_volumes_with, Grid};
    use crate::progress::testing::Record;
    use crate::shapes::uv_sphere;

    #[test]
    fn progress_counts_the_tiles_and_changes_nothing() {
        let sphere = uv_sphere(1.0, 48, 24);
        let grid = Grid::from_bounds([-1.1; 3], [1.1; 3], [40, 30, 20]).unwrap();
        let record = Record::default();
        let with = cell_volumes_with(&sphere, &grid, &record).unwrap();
        assert_eq!(with, cell_volumes(&sphere, &grid).unwrap());
        assert_eq!(record.counted_stages(), ["cutting faces into cells"]);
    }
}
