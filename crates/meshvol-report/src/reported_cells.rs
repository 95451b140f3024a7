//! A grid's cells in the report's units: the one conversion behind every grid sink (the
//! command's `.npy`, `.npz`, `.vti`, `.csv` and `.zarr` files, its summary, and
//! Python's `Grid` and `CutCells`), so that a file, an array and the summary give one
//! number after their stated unit.
//!
//! Each array is scaled by its dimension through [`Scale`]: points and lengths (origin,
//! cell size, centroids) by the length factor f, areas and ∫ n dA by f², volumes by f³,
//! second moments by f⁵; fractions and apertures are ratios and stay as they are. The
//! kernels work in the file's coordinates (arguments that are places, `--bounds`,
//! `--pitch`, `--slice`, stay in them); the arrays are converted where they are, in
//! parallel, once, before any sink reads them. Nothing is touched when nothing converts,
//! so a grid without units is the kernel's bits.
//!
//! A density does not change the volumes: sinks that write masses (`mass` beside
//! `volume`, or the masses alone in a one-array `.npy` or `.zarr`) multiply the reported
//! volume by [`Scale::mass_per_volume`].

use crate::quantities::Dimension::{self, *};
use crate::units::Scale;
use meshvol::grid::{CutCells, Grid};
use meshvol::Point;
use rayon::prelude::*;

/// `grid` with its origin and cell size in reported lengths.
pub fn grid(scale: &Scale, grid: &Grid) -> Result<Grid, String> {
    if !scale.converts() {
        return Ok(*grid);
    }
    Grid::new(scale.point(grid.origin), scale.point(grid.cell), grid.counts)
        .map_err(|e| format!("the grid in the units asked for: {e}"))
}

/// Scales `values` of dimension `d` where they are, in parallel.
fn convert(values: &mut [f64], scale: &Scale, d: Dimension) {
    if scale.converts() {
        values.par_iter_mut().for_each(|x| *x = scale.convert(d, *x));
    }
}

/// Scales points (or vectors of one dimension) where they are.
fn convert_points(values: &mut [Point], scale: &Scale, d: Dimension) {
    convert(values.as_flattened_mut(), scale, d);
}

/// Cell volumes in reported volume units, where they are.
pub fn volumes(scale: &Scale, volumes: &mut [f64]) {
    convert(volumes, scale, Volume);
}

/// Every array of `cells` in reported units, where they are, and its grid.
pub fn cut_cells(scale: &Scale, cells: &mut CutCells) -> Result<(), String> {
    cells.grid = grid(scale, &cells.grid)?;
    convert(&mut cells.volume, scale, Volume);
    convert_points(&mut cells.centroid, scale, Length);
    convert(&mut cells.boundary_area, scale, Area);
    convert_points(&mut cells.boundary_vector, scale, Area);
    convert_points(&mut cells.boundary_centroid, scale, Length);
    convert(cells.inertia.as_flattened_mut().as_flattened_mut(), scale, VolumeMoment);
    for centroids in &mut cells.aperture_centroid {
        convert_points(centroids, scale, Length);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::UnitOptions;
    use meshvol::grid::{cut_cells_extras, Extras};
    use meshvol::Mesh;

    /// An axis-aligned box [lo, hi]³ as a closed triangle mesh.
    fn cube(lo: f64, hi: f64) -> Mesh {
        let v = |i: u32| [0, 1, 2].map(|a| if i >> a & 1 == 1 { hi } else { lo });
        let quads: [[u32; 4]; 6] =
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let faces = quads.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect();
        Mesh::from_triangles((0..8).map(v).collect(), faces).unwrap()
    }

    #[test]
    fn each_array_scales_by_its_dimension() {
        // 1 in = 25.4 mm, written out by hand: lengths ×25.4, areas ×645.16, volumes
        // ×16387.064, second moments ×16387.064·645.16.
        let options = UnitOptions { units: Some("in:mm".parse().unwrap()), density: None };
        let (scale, _) = Scale::resolve(&options, None).unwrap();
        let solid = cube(0.25, 1.75);
        let g = Grid::new([0.0; 3], [1.0; 3], [2, 2, 2]).unwrap();
        let extras = Extras { second_moments: true, face_centroids: true };
        let whole = [0..2, 0..2, 0..2];
        let raw = cut_cells_extras(&solid, &g, &whole, extras, &()).unwrap();
        let mut cells = cut_cells_extras(&solid, &g, &whole, extras, &()).unwrap();
        cut_cells(&scale, &mut cells).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
        assert!(close(cells.grid.cell[0], 25.4) && cells.grid.origin == [0.0; 3]);
        for (a, b) in cells.volume.iter().zip(&raw.volume) {
            assert!(close(*a, b * 16387.064), "{a} vs {b}");
        }
        for (a, b) in cells.boundary_area.iter().zip(&raw.boundary_area) {
            assert!(close(*a, b * 645.16));
        }
        for (a, b) in cells.centroid.as_flattened().iter().zip(raw.centroid.as_flattened()) {
            assert!(close(*a, b * 25.4));
        }
        let (i, j) = (cells.inertia.as_flattened(), raw.inertia.as_flattened());
        for (a, b) in i.as_flattened().iter().zip(j.as_flattened()) {
            assert!(close(*a, b * 16387.064 * 645.16), "{a} vs {b}");
        }
        // Apertures are ratios.
        assert_eq!(cells.aperture, raw.aperture);
        // Each cell holds 0.75³ in³ of the cube: 0.421875 in³.
        assert!(cells.volume.iter().all(|&v| close(v, 0.421875 * 16387.064)));
    }

    #[test]
    fn nothing_converts_without_units() {
        let g = Grid::new([0.5; 3], [0.1; 3], [3, 3, 3]).unwrap();
        let scale = Scale::default();
        assert_eq!(grid(&scale, &g).unwrap(), g);
        let mut v = vec![0.1, -0.0, 3.0];
        volumes(&scale, &mut v);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&v), bits(&[0.1, -0.0, 3.0]));
    }
}
