//! Cut-cell geometry against independent computations: closed forms for boxes, a naive
//! clip of every triangle against every cell box (Sutherland–Hodgman, written here)
//! with the divergence theorem on the cut cell, plane sections for the apertures,
//! whole-mesh mass properties for the sums, and cyclic turns of the axes.

mod common;

use common::{cells, clip, divergence, mapped, overlap, rotation, XorShift};
use meshvol::grid::{cell_volumes, cut_cells, CutCells, Grid};
use meshvol::section::{section, Plane};
use meshvol::shapes::{cuboid, torus, uv_sphere};
use meshvol::{mass_properties, Mesh};

type P = [f64; 3];

fn turned(mesh: &Mesh, r: [[f64; 3]; 3], shift: P) -> Mesh {
    mapped(mesh, |p| [0, 1, 2].map(|i| (0..3).map(|j| r[i][j] * p[j]).sum::<f64>() + shift[i]))
}

/// A grid around `mesh` with a margin, of `counts` cells.
fn around(mesh: &Mesh, counts: [usize; 3], margin: f64) -> Grid {
    let b = mass_properties(mesh).bounds.unwrap();
    Grid::from_bounds(b.min.map(|x| x - margin), b.max.map(|x| x + margin), counts).unwrap()
}

/// The solids the identities run on: smooth, walled, tilted, holed, and a dirty pair of
/// overlapping boxes (its cells count the overlap twice, as the raw surface says).
fn solids() -> Vec<(&'static str, Mesh)> {
    let mut rng = XorShift::new(29);
    vec![
        ("sphere", uv_sphere(1.0, 40, 20)),
        ("box", cuboid([0.13, -0.27, 0.31], [1.71, 0.94, 1.05])),
        (
            "turned box",
            turned(&cuboid([-0.6, -0.4, -0.5], [0.6, 0.4, 0.5]), rotation(&mut rng), [0.1; 3]),
        ),
        ("torus", turned(&torus(1.0, 0.35, 24, 12), rotation(&mut rng), [0.0; 3])),
        ("two boxes", common::overlapping_boxes()),
    ]
}

#[test]
fn identities_hold_on_every_cell_and_in_sum() {
    for (name, mesh) in solids() {
        for counts in [[7, 5, 6], [16, 13, 11]] {
            let grid = around(&mesh, counts, 0.05);
            let c = cut_cells(&mesh, &grid).unwrap();
            let mp = mass_properties(&mesh);
            let face = grid.cell[0] * grid.cell[1];
            for cell in cells(&grid) {
                let d = divergence(&c, cell);
                assert!(d.iter().all(|x| x.abs() < 1e-12 * face), "{name} {cell:?}: {d:?}");
            }
            // The surface's area; the solid's first moment; a closed surface's Σ n dA.
            let area: f64 = c.boundary_area.iter().sum();
            assert!((area - mp.area).abs() < 1e-12 * mp.area, "{name}: {area} vs {}", mp.area);
            let moment: Vec<f64> = (0..3)
                .map(|d| c.volume.iter().zip(&c.centroid).map(|(v, x)| v * x[d]).sum())
                .collect();
            let expected = mp.centroid.unwrap().map(|x| x * mp.signed_volume);
            for d in 0..3 {
                assert!(
                    (moment[d] - expected[d]).abs() < 1e-12,
                    "{name}: {moment:?} vs {expected:?}"
                );
            }
            let total: Vec<f64> =
                (0..3).map(|d| c.boundary_vector.iter().map(|v| v[d]).sum()).collect();
            assert!(total.iter().all(|x| x.abs() < 1e-12), "{name}: Σ n dA = {total:?}");
            // The volumes are the grid command's, bit for bit.
            assert_eq!(c.volume, cell_volumes(&mesh, &grid).unwrap(), "{name}");
        }
    }
}

#[test]
fn a_box_by_closed_forms() {
    let (lo, hi) = ([0.13, -0.27, 0.31], [1.71, 0.94, 1.05]);
    let mesh = cuboid(lo, hi);
    let grid = Grid::new([-0.2, -0.5, 0.0], [0.25, 0.3, 0.2], [9, 6, 7]).unwrap();
    let c = cut_cells(&mesh, &grid).unwrap();
    let range = |d: usize, n: usize| {
        let a = grid.origin[d] + n as f64 * grid.cell[d];
        (a, a + grid.cell[d])
    };
    for [i, j, k] in cells(&grid) {
        let n = grid.index([i, j, k]);
        let o = [0, 1, 2].map(|d| overlap(range(d, [i, j, k][d]), (lo[d], hi[d])));
        let len = o.map(|(a, b)| (b - a).max(0.0));
        let volume = len[0] * len[1] * len[2];
        assert!((c.volume[n] - volume).abs() < 1e-15, "{:?}", [i, j, k]);
        if volume > 1e-9 * grid.cell_volume() && volume < grid.cell_volume() * (1.0 - 1e-9) {
            for d in 0..3 {
                let mid = 0.5 * (o[d].0 + o[d].1);
                assert!((c.centroid[n][d] - mid).abs() < 1e-12, "{:?} {d}", [i, j, k]);
            }
        }
        // The box's faces in this cell: each face is its rectangle ∩ the cell.
        let (mut area, mut vector) = (0.0, [0.0; 3]);
        for d in 0..3 {
            let (p, q) = ((d + 1) % 3, (d + 2) % 3);
            let across = len[p] * len[q];
            for (plane, sign) in [(lo[d], -1.0), (hi[d], 1.0)] {
                let (a, b) = range(d, [i, j, k][d]);
                if plane >= a && plane < b && len[p] > 0.0 && len[q] > 0.0 {
                    area += across;
                    vector[d] += sign * across;
                }
            }
        }
        assert!((c.boundary_area[n] - area).abs() < 1e-15, "{:?}", [i, j, k]);
        for d in 0..3 {
            assert!((c.boundary_vector[n][d] - vector[d]).abs() < 1e-15);
        }
    }
    // Apertures: the box's cross-section in each cell face.
    let [nx, ny, nz] = grid.counts;
    for d in 0..3 {
        let mut shape = grid.counts;
        shape[d] += 1;
        for i in 0..shape[0] {
            for j in 0..shape[1] {
                for k in 0..shape[2] {
                    let at = [i, j, k];
                    let plane = grid.origin[d] + at[d] as f64 * grid.cell[d];
                    let inside = plane >= lo[d] && plane < hi[d];
                    let (p, q) = ((d + 1) % 3, (d + 2) % 3);
                    let side = |e: usize| {
                        let o = overlap(range(e, at[e]), (lo[e], hi[e]));
                        (o.1 - o.0).max(0.0) / grid.cell[e]
                    };
                    let expected = if inside { side(p) * side(q) } else { 0.0 };
                    let got = c.aperture[d][(i * shape[1] + j) * shape[2] + k];
                    assert!(
                        (got - expected).abs() < 1e-14,
                        "axis {d} face {at:?}: {got} vs {expected}"
                    );
                }
            }
        }
    }
    let _ = (nx, ny, nz);
}

/// Over a planar polygon (as a fan): its area vector, `∫ x_d n dA`... here, for axis
/// `d`: `(∫ n_d dA, ∫ x_d n_d dA, ∫ ½ x_d² n_d dA)`, and `(area, Σ area · centroid)`.
fn polygon_integrals(poly: &[P], d: usize) -> ([f64; 3], f64, P) {
    let (mut sums, mut area, mut weighted) = ([0.0; 3], 0.0, [0.0; 3]);
    for t in 1..poly.len() - 1 {
        let (o, a, b) = (poly[0], poly[t], poly[t + 1]);
        let e = [0, 1, 2].map(|i| a[i] - o[i]);
        let f = [0, 1, 2].map(|i| b[i] - o[i]);
        let c = [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]];
        let n_d = 0.5 * c[d];
        let x = [o[d], a[d], b[d]];
        let s: f64 = x.iter().sum();
        sums[0] += n_d;
        sums[1] += n_d * s / 3.0;
        sums[2] += 0.5 * n_d * (x.iter().map(|v| v * v).sum::<f64>() + s * s) / 12.0;
        let size = 0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        area += size;
        for i in 0..3 {
            weighted[i] += size * (o[i] + a[i] + b[i]) / 3.0;
        }
    }
    (sums, area, weighted)
}

#[test]
fn every_cell_against_a_naive_clip_and_the_divergence_theorem() {
    let mut rng = XorShift::new(7);
    let meshes = [
        uv_sphere(1.0, 16, 9),
        turned(&cuboid([-0.6, -0.4, -0.5], [0.6, 0.4, 0.5]), rotation(&mut rng), [0.05; 3]),
    ];
    for mesh in meshes {
        let grid = around(&mesh, [5, 4, 6], 0.1);
        let c = cut_cells(&mesh, &grid).unwrap();
        let triangles: Vec<[P; 3]> = {
            let mut t = Vec::new();
            for f in 0..mesh.face_count() {
                let v = mesh.face(f);
                for k in 1..v.len() - 1 {
                    t.push([v[0], v[k], v[k + 1]].map(|i| mesh.positions()[i as usize]));
                }
            }
            t
        };
        let [_, ny, nz] = grid.counts;
        for cell in cells(&grid) {
            let n = grid.index(cell);
            let lo = [0, 1, 2].map(|d| grid.origin[d] + cell[d] as f64 * grid.cell[d]);
            let hi = [0, 1, 2].map(|d| lo[d] + grid.cell[d]);
            // The surface in the cell, and its integrals along each axis.
            let (mut per_axis, mut area, mut weighted, mut vector) =
                ([[0.0; 3]; 3], 0.0, [0.0; 3], [0.0; 3]);
            for t in &triangles {
                let mut poly = t.to_vec();
                for d in 0..3 {
                    poly = clip(poly, d, lo[d], hi[d]);
                }
                if poly.len() < 3 {
                    continue;
                }
                for d in 0..3 {
                    let (s, a, w) = polygon_integrals(&poly, d);
                    for m in 0..3 {
                        per_axis[d][m] += s[m];
                    }
                    vector[d] += s[0];
                    if d == 0 {
                        area += a;
                        for i in 0..3 {
                            weighted[i] += w[i];
                        }
                    }
                }
            }
            let tol = 1e-12;
            assert!(
                (c.boundary_area[n] - area).abs() < tol,
                "{cell:?}: {} vs {area}",
                c.boundary_area[n]
            );
            for d in 0..3 {
                assert!((c.boundary_vector[n][d] - vector[d]).abs() < tol);
                if area > 1e-9 {
                    assert!((c.boundary_centroid[n][d] - weighted[d] / area).abs() < 1e-9);
                }
            }
            // The cut cell's closed boundary is this surface and the cell faces' inside
            // parts, on which x_d is constant: V = ∮ x_d n_d dA, ∫ x_d dV = ∮ ½ x_d² n_d dA.
            for d in 0..3 {
                let face = grid.cell[(d + 1) % 3] * grid.cell[(d + 2) % 3];
                let at = |m: usize| {
                    let mut idx = cell;
                    idx[d] += m;
                    let mut shape = grid.counts;
                    shape[d] += 1;
                    c.aperture[d][(idx[0] * shape[1] + idx[1]) * shape[2] + idx[2]] * face
                };
                let _ = (ny, nz);
                let (a0, a1) = (at(0), at(1));
                let volume = hi[d] * a1 - lo[d] * a0 + per_axis[d][1];
                let moment = 0.5 * (hi[d] * hi[d] * a1 - lo[d] * lo[d] * a0) + per_axis[d][2];
                assert!(
                    (c.volume[n] - volume).abs() < tol,
                    "{cell:?} axis {d}: {} vs {volume}",
                    c.volume[n]
                );
                if c.volume[n] > 1e-6 * grid.cell_volume() {
                    let x = moment / volume;
                    assert!(
                        (c.centroid[n][d] - x).abs() < 1e-9,
                        "{cell:?} axis {d}: {} vs {x}",
                        c.centroid[n][d]
                    );
                }
            }
        }
    }
}

#[test]
fn apertures_are_the_sections_of_the_solid() {
    for (name, mesh) in solids() {
        let grid = around(&mesh, [9, 8, 7], 0.05);
        let c = cut_cells(&mesh, &grid).unwrap();
        for d in 0..3 {
            let mut shape = grid.counts;
            shape[d] += 1;
            let face = grid.cell[(d + 1) % 3] * grid.cell[(d + 2) % 3];
            let plane_cells = shape[(d + 1) % 3] * shape[(d + 2) % 3];
            for m in 0..shape[d] {
                let at = grid.origin[d] + m as f64 * grid.cell[d];
                let s = section(&mesh, &Plane::axis(d, at).unwrap()).signed_area;
                let total: f64 = (0..plane_cells)
                    .map(|r| {
                        let (p, q) = (r / shape[(d + 2) % 3], r % shape[(d + 2) % 3]);
                        let mut idx = [0; 3];
                        idx[d] = m;
                        idx[(d + 1) % 3] = p;
                        idx[(d + 2) % 3] = q;
                        c.aperture[d][(idx[0] * shape[1] + idx[1]) * shape[2] + idx[2]]
                    })
                    .sum::<f64>()
                    * face;
                if name != "two boxes" {
                    assert!((total - s).abs() < 1e-12, "{name} axis {d} plane {m}: {total} vs {s}");
                }
            }
        }
    }
}

#[test]
fn x_apertures_hold_over_planes_of_many_tubes() {
    // 70 × 61 = 4270 tubes (j, k) a plane: the x sums run in more than one task, the last
    // one short. Every cell's divergence theorem and every x plane's section still hold.
    for (name, mesh) in solids().into_iter().filter(|(n, _)| ["sphere", "torus"].contains(n)) {
        let grid = around(&mesh, [5, 70, 61], 0.05);
        let c = cut_cells(&mesh, &grid).unwrap();
        let face = grid.cell[1] * grid.cell[2];
        for cell in cells(&grid) {
            let d = divergence(&c, cell);
            assert!(d.iter().all(|x| x.abs() < 1e-12 * face), "{name} {cell:?}: {d:?}");
        }
        let plane = 70 * 61;
        for m in 0..=5 {
            let at = grid.origin[0] + m as f64 * grid.cell[0];
            let s = section(&mesh, &Plane::axis(0, at).unwrap()).signed_area;
            let total: f64 = c.aperture[0][m * plane..(m + 1) * plane].iter().sum::<f64>() * face;
            assert!((total - s).abs() < 1e-12, "{name} plane {m}: {total} vs {s}");
        }
    }
}

#[test]
fn turning_the_axes_turns_every_array() {
    // (x, y, z) → (y, z, x): the x moments come from the turned z path and back.
    for (name, mesh) in solids() {
        let grid = around(&mesh, [6, 7, 5], 0.05);
        let turn = |p: P| [p[1], p[2], p[0]];
        let turned_mesh = mapped(&mesh, turn);
        let turned_grid = Grid::new(turn(grid.origin), turn(grid.cell), {
            let [a, b, c] = grid.counts;
            [b, c, a]
        })
        .unwrap();
        let (c, t) =
            (cut_cells(&mesh, &grid).unwrap(), cut_cells(&turned_mesh, &turned_grid).unwrap());
        for [i, j, k] in cells(&grid) {
            let (n, m) = (grid.index([i, j, k]), turned_grid.index([j, k, i]));
            assert!((c.volume[n] - t.volume[m]).abs() < 1e-13, "{name}");
            assert!((c.boundary_area[n] - t.boundary_area[m]).abs() < 1e-13, "{name}");
            for (a, b) in
                [(c.centroid[n], t.centroid[m]), (c.boundary_centroid[n], t.boundary_centroid[m])]
            {
                if c.volume[n].abs() > 1e-6 * grid.cell_volume() {
                    assert!(
                        turn(a).iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-9),
                        "{name} {:?}",
                        [i, j, k]
                    );
                }
            }
            let (a, b) = (turn(c.boundary_vector[n]), t.boundary_vector[m]);
            assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-13), "{name}");
        }
    }
}

#[test]
fn the_same_bits_at_any_thread_count() {
    let mesh = uv_sphere(1.0, 64, 32);
    let grid = around(&mesh, [40, 33, 29], 0.05);
    let at = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| cut_cells(&mesh, &grid).unwrap())
    };
    let one = at(1);
    assert_eq!(one, at(2));
    assert_eq!(one, at(5));
}

#[test]
fn a_grid_that_cuts_the_solid_keeps_the_solid_inside_it() {
    // The grid ends inside the sphere on x, y and z: its far faces' apertures come from
    // the surface beyond the grid. A larger grid with the same planes has those faces
    // inside, summed from its cells instead: the two must agree.
    let mesh = uv_sphere(1.0, 40, 20);
    let (origin, cell) = ([-1.1; 3], [0.2, 0.26, 0.24]);
    let small = cut_cells(&mesh, &Grid::new(origin, cell, [7, 5, 5]).unwrap()).unwrap();
    let large = cut_cells(&mesh, &Grid::new(origin, cell, [11, 9, 10]).unwrap()).unwrap();
    for cell in cells(&small.grid) {
        let d = divergence(&small, cell);
        assert!(d.iter().all(|x| x.abs() < 1e-12), "{cell:?}: {d:?}");
    }
    let face = |c: &CutCells, d: usize, idx: [usize; 3]| {
        let mut shape = c.grid.counts;
        shape[d] += 1;
        c.aperture[d][(idx[0] * shape[1] + idx[1]) * shape[2] + idx[2]]
    };
    let mut open = 0;
    for d in 0..3 {
        let mut shape = small.grid.counts;
        shape[d] += 1;
        for i in 0..shape[0] {
            for j in 0..shape[1] {
                for k in 0..shape[2] {
                    let (a, b) = (face(&small, d, [i, j, k]), face(&large, d, [i, j, k]));
                    assert!((a - b).abs() < 1e-12, "axis {d} face {:?}: {a} vs {b}", [i, j, k]);
                    open += usize::from([i, j, k][d] == small.grid.counts[d] && a > 0.0);
                }
            }
        }
    }
    assert!(open > 20, "the far faces cut the sphere: {open} open faces");
    let v: f64 = small.volume.iter().sum();
    assert_eq!(v, cell_volumes(&mesh, &small.grid).unwrap().iter().sum::<f64>());
}

#[test]
fn a_grid_on_the_solids_bounding_box_holds_all_its_surface() {
    // The grid's far faces are closed: a solid's top, back and right faces lying on them
    // are in the grid, as the bottom, front and left ones are.
    let (lo, hi) = ([0.13, -0.27, 0.31], [1.71, 0.94, 1.05]);
    let mesh = cuboid(lo, hi);
    let grid = Grid::from_bounds(lo, hi, [5, 4, 3]).unwrap();
    let c = cut_cells(&mesh, &grid).unwrap();
    let area: f64 = c.boundary_area.iter().sum();
    let mp = mass_properties(&mesh);
    assert!((area - mp.area).abs() < 1e-12, "{area} vs {}", mp.area);
    for cell in cells(&grid) {
        let d = divergence(&c, cell);
        assert!(d.iter().all(|x| x.abs() < 1e-12), "{cell:?}: {d:?}");
        // Every cell is full; the faces of the box lie on the outer cells' faces.
        let n = grid.index(cell);
        assert!((c.volume[n] - grid.cell_volume()).abs() < 1e-15);
        for a in 0..3 {
            let outer = usize::from(cell[a] == 0) + usize::from(cell[a] + 1 == grid.counts[a]);
            let face = grid.cell[(a + 1) % 3] * grid.cell[(a + 2) % 3];
            let expected = if cell[a] == 0 { -face } else { 0.0 }
                + if cell[a] + 1 == grid.counts[a] { face } else { 0.0 };
            assert!((c.boundary_vector[n][a] - expected).abs() < 1e-14, "{cell:?} {a}: {outer}");
        }
    }
    // The apertures: 1 inside, 0 on the box's own faces (the surface covers them).
    for a in 0..3 {
        let mut shape = grid.counts;
        shape[a] += 1;
        for (f, &x) in c.aperture[a].iter().enumerate() {
            let at = [f / (shape[1] * shape[2]), f / shape[2] % shape[1], f % shape[2]][a];
            let expected = if at == 0 || at == grid.counts[a] { 0.0 } else { 1.0 };
            assert!((x - expected).abs() < 1e-14, "axis {a} face {f}: {x}");
        }
    }
}

#[test]
fn non_convex_polygon_faces_count_their_own_area() {
    // An L-shaped prism whose L faces are single polygons fanned from a vertex beside the
    // reflex corner (the fan folds over itself), against the same prism in triangles.
    let l = [[2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0], [0.0, 0.0], [2.0, 0.0]];
    let mut p: Vec<P> = l.iter().map(|q| [q[0], q[1], 0.0]).collect();
    p.extend(l.iter().map(|q| [q[0], q[1], 1.0]));
    let mut faces: Vec<Vec<u32>> = vec![(0..6).rev().collect(), (6..12).collect()];
    for k in 0..6u32 {
        let n = (k + 1) % 6;
        faces.push(vec![k, n, n + 6, k + 6]);
    }
    let polygons = common::polygons(&p, &faces);
    // The same surface in triangles that do not fold: the L as two rectangles.
    let mut triangles: Vec<Vec<u32>> =
        faces[2..].iter().flat_map(|q| [vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]]).collect();
    for (base, up) in [(0u32, false), (6, true)] {
        // Rectangles (4, 5, 0, 1') and (4, 1, 2, 3) of the L's corners, with (2,1)=0,
        // (1,1)=1, (1,2)=2, (0,2)=3, (0,0)=4, (2,0)=5; as triangles wound like the face.
        for t in [[4, 5, 0], [4, 0, 1], [4, 1, 2], [4, 2, 3]] {
            let t: Vec<u32> = t.iter().map(|v| v + base).collect();
            triangles.push(if up { t } else { vec![t[0], t[2], t[1]] });
        }
    }
    let triangles = common::polygons(&p, &triangles);
    let mp = mass_properties(&triangles);
    assert!((mass_properties(&polygons).area - mp.area).abs() < 1e-12);
    let grid = Grid::from_bounds([-0.1, -0.1, -0.1], [2.1, 2.1, 1.1], [5, 6, 3]).unwrap();
    let (a, b) = (cut_cells(&polygons, &grid).unwrap(), cut_cells(&triangles, &grid).unwrap());
    let area: f64 = a.boundary_area.iter().sum();
    assert!((area - mp.area).abs() < 1e-12, "{area} vs {}", mp.area);
    for n in 0..grid.cell_count() {
        assert!((a.volume[n] - b.volume[n]).abs() < 1e-14);
        assert!((a.boundary_area[n] - b.boundary_area[n]).abs() < 1e-13, "cell {n}");
        for d in 0..3 {
            assert!((a.boundary_vector[n][d] - b.boundary_vector[n][d]).abs() < 1e-13);
            if a.boundary_area[n] > 1e-9 {
                assert!((a.boundary_centroid[n][d] - b.boundary_centroid[n][d]).abs() < 1e-12);
            }
        }
    }
}
