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
mod occupancy;
pub(crate) mod piece_moments;
mod profile;
mod tile_work;
mod types;
mod union;

pub use cut_cells::{
    cut_cells, cut_cells_extras, cut_cells_region, cut_cells_rows, cut_cells_swept, cut_cells_with,
    cut_tile_work, CutCellRows, CutCells, Extras, SweptCells,
};
pub use intersect::{
    intersection, intersection_placed, intersection_with, overlapping_boxes, Bounded, Contact,
    Intersection, Method, Moments,
};
pub use occupancy::{occupancy, Occupancy, OCCUPANCY_TOLERANCE};
pub use profile::{profile, Axis, Levels, Profile, ProfileError, MAX_LEVELS};
pub use tile_work::{tile_work, TileWork};
pub use types::{bytes_text, check_region, Grid, GridError, Region};
pub use union::{
    union, union_boundary, union_boundary_with, union_cell_volumes, union_cell_volumes_with,
    union_with, UnionBoundary, UnionError, UnionVolume, COPLANAR_TOLERANCE, MAX_DEPTH, STALL,
};

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
