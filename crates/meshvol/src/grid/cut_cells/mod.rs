//! Cut-cell geometry: for every cell of a grid, the moments of the solid inside it, the
//! integrals of the surface inside it, and the fraction of each cell face inside the
//! solid; exact up to rounding, from the same sweeps as the cell volumes.
//!
//! # The math
//! Cell `C = [x₀,x₁]×[y₀,y₁]×[z₀,z₁]` of a solid Ω bounded by a closed surface S, local
//! coordinates `x' = (x − x₀)/dx` (and y', z'), `g(z) = clamp(z', 0, 1)`. As for the
//! volume (the [grid module](super)), a field `F = (0, 0, f)` vanishes on the column's
//! side walls, so `∫_{Ω∩C} ∂f/∂z dV = ∫_{S ∩ column} f n_z dA`:
//!
//! | quantity | f | in the cell's layer | each layer below a part gets |
//! |---|---|---|---|
//! | volume | `g` | `∫ z' n_z dA` | `A` (its projected area) |
//! | `∫ x' dV` | `x' g` | `∫ x' z' n_z dA` | `∫ x' n_z dA` |
//! | `∫ y' dV` | `y' g` | `∫ y' z' n_z dA` | `∫ y' n_z dA` |
//! | `∫ z' dV` | `½ g²` | `∫ ½ z'² n_z dA` | `½ A` |
//!
//! so three sums per column are handed down (area and its x and y moments), by the
//! suffix sums of the volume kernel. The integrands are polynomials of degree ≤ 2 over
//! planar parts ([`integrals`]). The `centroid` is `∫ x dV / V`.
//!
//! The second moments ([`Extras::second_moments`]) are the same with degree-2 fields:
//!
//! | quantity | f | in the cell's layer | each layer below a part gets |
//! |---|---|---|---|
//! | `∫ x'² dV` | `x'² g` | `∫ x'² z' n_z dA` | `∫ x'² n_z dA` |
//! | `∫ y'² dV` | `y'² g` | `∫ y'² z' n_z dA` | `∫ y'² n_z dA` |
//! | `∫ x'y' dV` | `x'y' g` | `∫ x'y' z' n_z dA` | `∫ x'y' n_z dA` |
//! | `∫ x'z' dV` | `½ x' g²` | `∫ ½ x' z'² n_z dA` | `½ ∫ x' n_z dA` |
//! | `∫ y'z' dV` | `½ y' g²` | `∫ ½ y' z'² n_z dA` | `½ ∫ y' n_z dA` |
//! | `∫ z'² dV` | `⅓ g³` | `∫ ⅓ z'³ n_z dA` | `⅓ A` |
//!
//! (three more sums handed down; integrands of degree ≤ 3), in the cell's own
//! coordinates, so that nothing cancels far from the origin; then moved to the cell's
//! centroid `c` (`M₂ − c M₁ᵀ − M₁ cᵀ + V c cᵀ`, exact about any point) and scaled to
//! world units. `inertia` is `tr(C)·𝟙 − C` of that covariance `C` (unit density, products
//! of inertia negative), as [`MassProperties::inertia`](crate::MassProperties) is.
//!
//! The surface inside a cell is the set of parts the sweeps cut (each a convex polygon,
//! the triangle ∩ the cell): `boundary_area` sums their areas, `boundary_vector` their
//! area vectors `∫ n dA`, `boundary_centroid` is their area-weighted centroid. Faces
//! parallel to z (walls) have no projection and add nothing to the volume terms, but
//! are cut and counted here.
//!
//! The aperture of a cell face is the fraction of it inside the solid. On a plane
//! `z = z_k` it is the column's suffix sum of projected areas at that plane (what hands
//! the volume down); on `x = x_i` and `y = y_j` it follows from the same theorem with a
//! constant field ([`apertures`]), and their centroids ([`Extras::face_centroids`]) from
//! the first moments of the same sums.
//!
//! # Identities (tested)
//! For every cell, `Σ_faces ± aperture · face area · axis + boundary_vector = 0` (the
//! divergence theorem on the cut cell); `Σ boundary_area` = the surface's area inside the
//! grid; `Σ volume · centroid` = the first moment of the solid inside the grid;
//! `Σ boundary_vector` = 0 for a closed surface inside the grid.
//!
//! # Conventions
//! A surface lying exactly on a cell face belongs to the cell on its high side (as the
//! volumes' layers do), except on the grid's far faces (`x = x_nx`, `y = y_ny`,
//! `z = z_nz`), where it belongs to the cell inside: the grid is closed, so a solid's
//! surface on its bounding box is all in the grid whose bounds are that box. Where the
//! surface lies on a face's plane, the aperture is the solid's section just below the
//! plane (as [`section`](crate::section::section) takes it: full on a box's top face,
//! empty on its bottom face), and on the grid's far faces the section just beyond them. Empty and full cells (volume within [`OCCUPANCY_TOLERANCE`](super::OCCUPANCY_TOLERANCE) of 0 or of
//! the cell) have their centroid at the cell's middle, as does the boundary centroid
//! of a cell without surface; other centroids are clamped to their cell (the ratio of
//! two sums each rounded). Everything is in world units except the apertures, which are
//! fractions (negative, like the volumes, for an inward-wound surface).
//!
//! # Stages
//! | stage | file |
//! |---|---|
//! | the integrals over one part | [`integrals`] |
//! | sweeps, sums and per-column finish | [`kernel`] |
//! | x and y apertures, surface centroids | [`apertures`] |
//! | the per-column stage run elsewhere (a device), the rest here | [`device`] |
//!
//! ```
//! use meshvol::grid::{cut_cells, Grid};
//! use meshvol::shapes::cuboid;
//! // A 1.5 × 1 × 1 box in two cells of 1 × 2 × 2.
//! let grid = Grid::new([0.0, -0.5, -0.5], [1.0, 2.0, 2.0], [2, 1, 1]).unwrap();
//! let c = cut_cells(&cuboid([0.0; 3], [1.5, 1.0, 1.0]), &grid).unwrap();
//! let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15);
//! assert!(close(&c.volume, &[1.0, 0.5]));
//! assert!(close(&c.centroid[1], &[1.25, 0.5, 0.5]));
//! // Cell 1 holds the wall x = 1.5 and half of each face around x.
//! assert!(close(&c.boundary_vector[1], &[1.0, 0.0, 0.0]));
//! assert!(close(&[c.boundary_area[1]], &[1.0 + 4.0 * 0.5]));
//! // Faces x = 0, 1, 2: the box's face x = 0 lies on the first (counted on its high side).
//! assert!(close(&c.aperture[0], &[0.0, 0.25, 0.0]));
//! ```

mod apertures;
mod arrays;
mod device;
mod integrals;
mod kernel;

pub use arrays::{CutCells, Extras};
pub use device::{cut_cells_swept, cut_tile_work, SweptCells};

use super::cells::Block;
use super::{Grid, GridError, Region};
use crate::accumulate::CompensatedSum;
use crate::progress::Progress;
use crate::Surface;
use rayon::prelude::*;

/// The cut-cell geometry of `surface` on `grid` (module docs). Parallel over tiles of
/// columns; the same bits for any number of threads.
pub fn cut_cells<S: Surface + ?Sized>(surface: &S, grid: &Grid) -> Result<CutCells, GridError> {
    cut_cells_with(surface, grid, &())
}

/// [`cut_cells`], telling `progress` its stages and the tiles done.
pub fn cut_cells_with<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    progress: &dyn Progress,
) -> Result<CutCells, GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    let whole = Block::whole(grid.counts);
    Ok(computed(surface, &grid, &whole, Extras::default(), progress, Carried::default())?.0)
}

/// The cut-cell geometry of the cells of `region` of `grid`: the same bits as those
/// cells of [`cut_cells`] over the whole grid, so that blocks can be computed apart.
///
/// The x and y apertures sum the surface from the grid's far x and y faces down, so a
/// region is computed over the cells from its start to those faces (and cut back): a
/// block near the grid's low corner costs about as much as the whole grid. To compute
/// a whole grid in parts, take its rows from the far x face down: [`cut_cells_rows`].
pub fn cut_cells_region<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    region: &Region,
) -> Result<CutCells, GridError> {
    cut_cells_extras(surface, grid, region, Extras::default(), &())
}

/// The cut-cell geometry of the cells of `region` of `grid` with the arrays `extras`
/// asks for beyond the default ones, telling `progress` its stages: the same bits as
/// [`cut_cells`] (and [`cut_cells_region`]) for those, and for the extra arrays the same
/// bits for any region and any number of threads.
pub fn cut_cells_extras<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    region: &Region,
    extras: Extras,
    progress: &dyn Progress,
) -> Result<CutCells, GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    super::check_region(&grid, region)?;
    let [x, y, z] = region.clone();
    let [nx, ny, _] = grid.counts;
    let reach = Block { counts: grid.counts, region: [x.start..nx, y.start..ny, z] };
    let (cells, _) = computed(surface, &grid, &reach, extras, progress, Carried::default())?;
    Ok(if cells.region == *region { cells } else { cells.cropped(region) })
}

/// What a part of a grid computed from the far x face down hands to the part below it:
/// the x sums (apertures and, with face centroids, their moments) at its first plane.
#[derive(Default)]
struct Carried {
    apertures: Option<Vec<CompensatedSum>>,
    centroids: Option<Vec<[CompensatedSum; 2]>>,
}

/// The cut cells of `block`, which reaches the grid's far y face, and its far x face
/// unless `carried` holds the sums of the cells beyond it; and what it hands down.
fn computed<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    block: &Block,
    extras: Extras,
    progress: &dyn Progress,
    carried: Carried,
) -> Result<(CutCells, Carried), GridError> {
    if extras == Extras::default() {
        let (mut cells, mut none, _) =
            kernel::cut_cells::<S, false>(surface, grid, block, progress)?;
        progress.stage("summing apertures");
        let (_, apertures) = apertures::fill(surface, &mut cells, &mut none, carried.apertures);
        return Ok((cells, Carried { apertures: Some(apertures), centroids: None }));
    }
    let (mut cells, mut sums, planes) =
        kernel::cut_cells::<S, true>(surface, grid, block, progress)?;
    progress.stage("summing apertures");
    let (beyond, apertures) = apertures::fill(surface, &mut cells, &mut sums, carried.apertures);
    let mut centroids = None;
    if extras.face_centroids {
        let (points, state) =
            apertures::face_centroids(&cells, &sums, &planes, &beyond, carried.centroids);
        cells.aperture_centroid = points;
        centroids = Some(state);
    }
    drop(planes);
    if extras.second_moments {
        let tensor = |e: &kernel::Extra| {
            let [xx, yy, zz, xy, yz, zx] = e.second;
            [[yy + zz, -xy, -zx], [-xy, xx + zz, -yz], [-zx, -yz, xx + yy]]
        };
        cells.inertia = sums.par_iter().map(tensor).collect();
    }
    Ok((cells, Carried { apertures: Some(apertures), centroids }))
}

/// The cut cells of a grid as its *rows* (the blocks of every cell along y and z and
/// `row` cells along x, the last one shorter), from the far x face down: each the same
/// bits as those cells of [`cut_cells_extras`] over the whole grid, and each computed
/// alone (the x sums of the rows beyond, a plane of them, are carried down), so that
/// memory holds one row however large the grid. What [`cut_cells_rows`] returns.
pub struct CutCellRows<'a, S: Surface + ?Sized> {
    surface: &'a S,
    grid: Grid,
    row: usize,
    extras: Extras,
    /// Where the next row ends along x (0: done).
    end: usize,
    /// The x sums at plane `end` (none at the far face).
    carried: Carried,
}

/// The rows of `row` cells along x of the cut cells of `surface` on `grid`, with the
/// arrays `extras` asks for, from the far x face down ([`CutCellRows`]): row `r` holds
/// cells `r·row..min((r+1)·row, NX)` and comes after the rows beyond it.
pub fn cut_cells_rows<'a, S: Surface + ?Sized>(
    surface: &'a S,
    grid: &Grid,
    row: usize,
    extras: Extras,
) -> Result<CutCellRows<'a, S>, GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    let row = row.clamp(1, grid.counts[0]);
    let end = grid.counts[0];
    Ok(CutCellRows { surface, grid, row, extras, end, carried: Carried::default() })
}

impl<S: Surface + ?Sized> Iterator for CutCellRows<'_, S> {
    type Item = Result<CutCells, GridError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.end == 0 {
            return None;
        }
        let [_, ny, nz] = self.grid.counts;
        // Rows start at multiples of `row`: the last one holds what is left.
        let start = (self.end - 1) / self.row * self.row;
        let block = Block { counts: self.grid.counts, region: [start..self.end, 0..ny, 0..nz] };
        self.end = start;
        let carried = std::mem::take(&mut self.carried);
        match computed(self.surface, &self.grid, &block, self.extras, &(), carried) {
            Ok((cells, carried)) => {
                self.carried = carried;
                Some(Ok(cells))
            }
            Err(e) => {
                self.end = 0;
                Some(Err(e))
            }
        }
    }
}
