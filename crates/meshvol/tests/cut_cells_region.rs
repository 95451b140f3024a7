//! Blocks and rows of cut cells against the whole grid: any region (`cut_cells_region`)
//! and the rows from the far face (`cut_cells_rows`, at any thread count, with and
//! without the extras) are the same bits as the same cells of `cut_cells`.

mod common;

use common::{overlapping_boxes, XorShift};
use meshvol::grid::{cut_cells, cut_cells_extras, CutCells, Extras, Grid};
use meshvol::shapes::{cuboid, uv_sphere};

type P = [f64; 3];

#[test]
fn any_block_is_the_same_bits_as_the_whole_grid() {
    use meshvol::grid::cut_cells_region;
    let (lo, hi) = ([0.13, -0.27, 0.31], [1.71, 0.94, 1.05]);
    let cases = [
        (uv_sphere(1.0, 40, 20), Grid::new([-1.1; 3], [0.2, 0.26, 0.24], [7, 5, 5]).unwrap()),
        (cuboid(lo, hi), Grid::from_bounds(lo, hi, [5, 4, 3]).unwrap()),
        (overlapping_boxes(), Grid::from_bounds([-0.1; 3], [1.4, 1.2, 1.3], [6, 7, 5]).unwrap()),
    ];
    let mut rng = XorShift::new(11);
    for (mesh, grid) in cases {
        let whole = cut_cells(&mesh, &grid).unwrap();
        for _ in 0..12 {
            let region = grid.counts.map(|n| {
                let a = rng.below(n as u64) as usize;
                let b = rng.below(n as u64) as usize;
                a.min(b)..a.max(b) + 1
            });
            let block = cut_cells_region(&mesh, &grid, &region).unwrap();
            assert_eq!(block.region, region);
            let [bx, by, bz] = block.shape();
            for (n, at) in (0..bx)
                .flat_map(|i| (0..by).flat_map(move |j| (0..bz).map(move |k| [i, j, k])))
                .enumerate()
            {
                let g = whole.local([0, 1, 2].map(|a| at[a] + region[a].start)).unwrap();
                assert_eq!(block.volume[n].to_bits(), whole.volume[g].to_bits());
                assert_eq!(block.centroid[n], whole.centroid[g]);
                assert_eq!(block.boundary_area[n].to_bits(), whole.boundary_area[g].to_bits());
                assert_eq!(block.boundary_vector[n], whole.boundary_vector[g]);
                assert_eq!(block.boundary_centroid[n], whole.boundary_centroid[g]);
            }
            for a in 0..3 {
                let mut shape = block.shape();
                shape[a] += 1;
                let mut full = grid.counts;
                full[a] += 1;
                for (n, at) in (0..shape[0])
                    .flat_map(|i| {
                        (0..shape[1]).flat_map(move |j| (0..shape[2]).map(move |k| [i, j, k]))
                    })
                    .enumerate()
                {
                    let g = [0, 1, 2].map(|d| at[d] + region[d].start);
                    let w = whole.aperture[a][(g[0] * full[1] + g[1]) * full[2] + g[2]];
                    assert_eq!(block.aperture[a][n].to_bits(), w.to_bits(), "axis {a} {g:?}");
                }
            }
        }
    }
}

/// Every value of `c` as bits, array by array (cells, then each axis's faces).
fn bits(c: &CutCells) -> Vec<Vec<u64>> {
    let flat = |v: &[P]| v.as_flattened().iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let scalars = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let mut out = vec![
        scalars(&c.volume),
        flat(&c.centroid),
        scalars(&c.boundary_area),
        flat(&c.boundary_vector),
        flat(&c.boundary_centroid),
    ];
    out.extend(c.aperture.iter().map(|a| scalars(a)));
    out.push(flat(c.inertia.as_flattened()));
    out.extend(c.aperture_centroid.iter().map(|a| flat(a)));
    out
}

#[test]
fn rows_from_the_far_face_are_the_whole_grids_bits() {
    use meshvol::grid::cut_cells_rows;
    let (lo, hi) = ([0.13, -0.27, 0.31], [1.71, 0.94, 1.05]);
    let cases = [
        (uv_sphere(1.0, 40, 20), Grid::new([-1.1; 3], [0.2, 0.26, 0.24], [11, 9, 9]).unwrap()),
        // The box's faces on the grid's far faces (closed: counted in the cells inside).
        (cuboid(lo, hi), Grid::from_bounds(lo, hi, [7, 4, 3]).unwrap()),
        (overlapping_boxes(), Grid::from_bounds([-0.1; 3], [1.4, 1.2, 1.3], [6, 7, 5]).unwrap()),
    ];
    let all = Extras { second_moments: true, face_centroids: true };
    for ((mesh, grid), extras) in
        cases.into_iter().flat_map(|c| [(c.clone(), Extras::default()), (c, all)])
    {
        let everything = [0..grid.counts[0], 0..grid.counts[1], 0..grid.counts[2]];
        let whole = cut_cells_extras(&mesh, &grid, &everything, extras, &()).unwrap();
        let nx = grid.counts[0];
        for row in [1, 2, 3, 4, nx - 1, nx, nx + 3] {
            for threads in [1, 2, 5] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let rows: Vec<CutCells> = pool.install(|| {
                    let rows = cut_cells_rows(&mesh, &grid, row, extras).unwrap();
                    rows.map(|r| r.unwrap()).collect()
                });
                // From the far face down, starting at multiples of the row.
                let starts: Vec<usize> = rows.iter().map(|r| r.region[0].start).collect();
                let expected: Vec<usize> = (0..nx).step_by(row.min(nx)).rev().collect();
                assert_eq!(starts, expected, "row {row}");
                for r in &rows {
                    let [x, y, z] = r.region.clone();
                    assert_eq!((y, z), (0..grid.counts[1], 0..grid.counts[2]));
                    let [_, ny, nz] = grid.counts;
                    let plane = ny * nz;
                    let (cells, faces) = (x.start * plane..x.end * plane, x.clone());
                    let w = bits(&whole);
                    let got = bits(r);
                    for (a, name) in
                        ["volume", "centroid", "area", "vector", "bcentroid"].iter().enumerate()
                    {
                        let per = if [1, 3, 4].contains(&a) { 3 } else { 1 };
                        let range = cells.start * per..cells.end * per;
                        assert_eq!(got[a], w[a][range], "{name}, row {row} at {x:?}");
                    }
                    // x faces: the row's planes and the one beyond it; y and z: its cells'.
                    assert_eq!(got[5], w[5][faces.start * plane..(faces.end + 1) * plane]);
                    let (py, pz) = ((ny + 1) * nz, ny * (nz + 1));
                    assert_eq!(got[6], w[6][x.start * py..x.end * py]);
                    assert_eq!(got[7], w[7][x.start * pz..x.end * pz]);
                    // The extras (empty without them): inertia per cell, face centroids
                    // as the apertures, 3 components each.
                    let inertia = if w[8].is_empty() {
                        &[][..]
                    } else {
                        &w[8][cells.start * 9..cells.end * 9]
                    };
                    assert_eq!(got[8], inertia, "inertia");
                    let (x3, y3, z3) = (3 * plane, 3 * py, 3 * pz);
                    let [cx, cy, cz] = [&got[9], &got[10], &got[11]];
                    if !w[9].is_empty() {
                        assert_eq!(*cx, w[9][faces.start * x3..(faces.end + 1) * x3]);
                        assert_eq!(*cy, w[10][x.start * y3..x.end * y3]);
                        assert_eq!(*cz, w[11][x.start * z3..x.end * z3]);
                    } else {
                        assert!(cx.is_empty() && cy.is_empty() && cz.is_empty());
                    }
                }
            }
        }
    }
}
