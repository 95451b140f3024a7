//! The cut cells with their sweep run elsewhere (an OpenCL device, `meshvol-opencl`),
//! the same bits as [`cut_cells_extras`](super::cut_cells_extras) without extras.
//!
//! The kernel's work splits in two by what each result depends on:
//!
//! | stage | depends on | where |
//! |---|---|---|
//! | the sweeps and the sink's sums per cell; each column's suffix sums from the top down: volumes, centroids, z apertures | one column's pieces, in face order | the caller's `sweep`, from [`cut_tile_work`] |
//! | the parts beyond and on the grid's far x and y faces; the x and y apertures (sums along x and y, compensated, from the far faces down); the surface centroids | whole tubes of cells, after every column | here, the CPU kernel's own code ([`super::apertures`]) |
//!
//! So a device repeats the per-column arithmetic of [`super::kernel`] only; the sums
//! across columns, which are cheap (a pass over the cells) and whose order is the CPU's
//! by construction, run here on what it wrote.

use super::kernel::{allocated, face_areas, polygon_normal};
use super::{apertures, CutCells};
use crate::grid::cells::{Block, Units};
use crate::grid::tile_work::{laid_out, TileWork};
use crate::grid::{check_region, Grid, GridError, Region};
use crate::progress::Progress;
use crate::{Point, Surface};

/// The cut cells' work of `region` of `grid` for a device, in tiles of `per_tile`
/// columns: [`tile_work`](crate::grid::tile_work)'s layout with every triangle (walls
/// too) and its face's normal where the face is a polygon ([`TileWork::normals`]), as
/// the cut-cell kernel sweeps them.
pub fn cut_tile_work<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    region: &Region,
    per_tile: usize,
) -> Result<TileWork, GridError> {
    let units = Units::new(grid);
    let scale = face_areas(grid.cell);
    // An indexed triangle mesh has no polygon faces to look at (as the kernel).
    let polygons = surface.indexed_triangles().is_none();
    let normal = |face: usize| match polygons {
        true => polygon_normal(surface, face, &units, scale),
        false => None,
    };
    laid_out(surface, grid, region, per_tile, Some(normal))
}

/// The arrays of a block's cells (C order) that a sweep fills, zeroed before it: what
/// the CPU kernel leaves after its per-column finish.
pub struct SweptCells<'a> {
    /// The cells' volumes, world units.
    pub volume: &'a mut [f64],
    /// The solid's centroids, world units.
    pub centroid: &'a mut [Point],
    /// The surface's area in each cell, its `∫ n dA`, and its area-weighted centroid in
    /// the cell's own coordinates (finished here).
    pub boundary_area: &'a mut [f64],
    pub boundary_vector: &'a mut [Point],
    pub boundary_centroid: &'a mut [Point],
    /// The z apertures, `depth + 1` a column.
    pub aperture_z: &'a mut [f64],
}

/// The cut cells of `region` of `grid` (no extras), with the per-column stage run by
/// `sweep`: it gets the block whose cells it fills (the region reaching the grid's far
/// x and y faces, which the apertures sum from) and those arrays, and must leave in them
/// what [`super::kernel`] leaves (a device running [`cut_tile_work`]'s work, a slab of
/// the block at a time or all at once). Then the x and y apertures and the surface
/// centroids are summed here, telling `progress`; the result is cut back to `region`.
pub fn cut_cells_swept<S, E>(
    surface: &S,
    grid: &Grid,
    region: &Region,
    progress: &dyn Progress,
    sweep: impl FnOnce(&Region, SweptCells<'_>) -> Result<(), E>,
) -> Result<CutCells, E>
where
    S: Surface + ?Sized,
    E: From<GridError>,
{
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    check_region(&grid, region)?;
    let [x, y, z] = region.clone();
    let [nx, ny, _] = grid.counts;
    let reach = Block { counts: grid.counts, region: [x.start..nx, y.start..ny, z] };
    let mut cells = allocated(&grid, &reach, progress)?;
    let [_, _, aperture_z] = &mut cells.aperture;
    sweep(
        &reach.region,
        SweptCells {
            volume: &mut cells.volume,
            centroid: &mut cells.centroid,
            boundary_area: &mut cells.boundary_area,
            boundary_vector: &mut cells.boundary_vector,
            boundary_centroid: &mut cells.boundary_centroid,
            aperture_z,
        },
    )?;
    progress.stage("summing apertures (CPU)");
    apertures::fill(surface, &mut cells, &mut [], None);
    Ok(if cells.region == *region { cells } else { cells.cropped(region) })
}
