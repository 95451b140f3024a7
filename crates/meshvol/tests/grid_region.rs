//! Blocks of a grid against the whole grid: every region's cells are the same bits as
//! the same cells of `cell_volumes`, for random regions of several solids, and bad
//! regions are refused by name.

mod common;

use common::{face_lists, polygons};
use meshvol::grid::{cell_volumes, cell_volumes_region, Grid, GridError, Region};
use meshvol::shapes::{cuboid, torus, uv_sphere, uv_sphere_volume};
use meshvol::Mesh;
use proptest::prelude::*;

/// A cube of side 4 with a cubic cavity of side 2 (its faces wound inward) off centre.
fn cube_with_cavity() -> Mesh {
    let outer = cuboid([0.0; 3], [4.0; 3]);
    let inner = cuboid([0.7, 1.1, 0.9], [2.7, 3.1, 2.9]);
    let mut positions = outer.positions().to_vec();
    positions.extend_from_slice(inner.positions());
    let mut faces = face_lists(&outer);
    let base = outer.vertex_count() as u32;
    for mut face in face_lists(&inner) {
        face.reverse();
        faces.push(face.iter().map(|v| v + base).collect());
    }
    polygons(&positions, &faces)
}

/// The solids and a grid on each: cells not aligned with the solid, and a grid that
/// cuts it (parts above, below and beside the grid must still count as in the whole).
fn cases() -> Vec<(&'static str, Mesh, Grid)> {
    vec![
        (
            "sphere",
            uv_sphere(1.0, 48, 24),
            Grid::from_bounds([-1.1, -1.05, -1.2], [1.2, 1.1, 1.05], [13, 11, 17]).unwrap(),
        ),
        (
            "torus cut by the grid",
            torus(2.0, 0.7, 64, 32).triangulated(),
            Grid::from_bounds([-2.0, -3.0, -0.5], [2.9, 1.5, 0.4], [9, 14, 12]).unwrap(),
        ),
        (
            "cube with a cavity",
            cube_with_cavity(),
            Grid::from_bounds([-0.3, -0.2, -0.1], [4.2, 4.1, 4.3], [10, 9, 11]).unwrap(),
        ),
    ]
}

/// The cells of `region` picked out of the whole grid's array, in C order.
fn slice_of(whole: &[f64], grid: &Grid, region: &Region) -> Vec<f64> {
    let mut out = Vec::new();
    for i in region[0].clone() {
        for j in region[1].clone() {
            for k in region[2].clone() {
                out.push(whole[grid.index([i, j, k])]);
            }
        }
    }
    out
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Picks `start..end` with `start < end <= n` from two random numbers.
fn range_of(n: usize, a: usize, b: usize) -> std::ops::Range<usize> {
    let start = a % n;
    start..start + 1 + b % (n - start)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn a_region_is_the_same_bits_as_the_whole_grids_cells(
        ends in proptest::array::uniform6(0usize..1000)
    ) {
        for (name, mesh, grid) in cases() {
            let whole = cell_volumes(&mesh, &grid).unwrap();
            let region = [0, 1, 2].map(|a| range_of(grid.counts[a], ends[2 * a], ends[2 * a + 1]));
            let block = cell_volumes_region(&mesh, &grid, &region).unwrap();
            prop_assert_eq!(
                bits(&block),
                bits(&slice_of(&whole, &grid, &region)),
                "{} region {:?}",
                name,
                region
            );
        }
    }
}

#[test]
fn blocks_tile_the_grid_exactly_at_any_thread_count() {
    // Every block of a 3×2×4 split, computed on one thread, against the whole grid on
    // the default pool: the blocks cover the grid and agree cell by cell.
    for (name, mesh, grid) in cases() {
        let whole = cell_volumes(&mesh, &grid).unwrap();
        let cuts = |n: usize, parts: usize| -> Vec<std::ops::Range<usize>> {
            (0..parts).map(|p| p * n / parts..(p + 1) * n / parts).collect()
        };
        let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let mut covered = 0;
        for x in cuts(grid.counts[0], 3) {
            for y in cuts(grid.counts[1], 2) {
                for z in cuts(grid.counts[2], 4) {
                    let region = [x.clone(), y.clone(), z];
                    let block =
                        one_thread.install(|| cell_volumes_region(&mesh, &grid, &region).unwrap());
                    assert_eq!(bits(&block), bits(&slice_of(&whole, &grid, &region)), "{name}");
                    covered += block.len();
                }
            }
        }
        assert_eq!(covered, grid.cell_count(), "{name}");
    }
}

#[test]
fn blocks_sum_to_the_volume() {
    // Independent of the whole grid: the sphere's closed-form polyhedron volume.
    let sphere = uv_sphere(1.0, 48, 24);
    let grid = Grid::from_bounds([-1.0; 3], [1.0; 3], [8, 8, 8]).unwrap();
    let mut total = 0.0;
    for x in [0..3, 3..8] {
        for z in [0..5, 5..8] {
            let block = cell_volumes_region(&sphere, &grid, &[x.clone(), 0..8, z]).unwrap();
            total += block.iter().sum::<f64>();
        }
    }
    let volume = uv_sphere_volume(1.0, 48, 24);
    assert!((total - volume).abs() < 1e-12, "{total} vs {volume}");
}

#[test]
fn bad_regions_are_refused_by_name() {
    let cube = cuboid([0.0; 3], [1.0; 3]);
    let grid = Grid::new([0.0; 3], [0.25; 3], [4, 4, 4]).unwrap();
    let empty = cell_volumes_region(&cube, &grid, &[0..4, 2..2, 0..4]).unwrap_err();
    assert_eq!(empty, GridError::EmptyRegion { axis: 'y', start: 2, end: 2 });
    assert!(empty.to_string().contains("empty along y"), "{empty}");
    #[allow(clippy::reversed_empty_ranges)] // the mistake under test
    let reversed = cell_volumes_region(&cube, &grid, &[0..4, 0..4, 3..1]).unwrap_err();
    assert_eq!(reversed, GridError::EmptyRegion { axis: 'z', start: 3, end: 1 });
    let beyond = cell_volumes_region(&cube, &grid, &[2..5, 0..4, 0..4]).unwrap_err();
    assert_eq!(beyond, GridError::RegionOutsideGrid { axis: 'x', start: 2, end: 5, cells: 4 });
    assert!(beyond.to_string().contains("beyond the grid's 4 cells"), "{beyond}");
    // The grid itself is checked first, as for the whole grid.
    let flat = Grid { origin: [0.0; 3], cell: [0.0, 1.0, 1.0], counts: [1, 1, 1] };
    let bad = cell_volumes_region(&cube, &flat, &[0..1, 0..1, 0..1]).unwrap_err();
    assert!(matches!(bad, GridError::BadCellSize { .. }));
}
