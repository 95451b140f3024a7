//! The cut cells' second moments (`inertia`) and face centroids against independent
//! computations: a naive clip of every triangle against every cell box (Sutherland–
//! Hodgman, written here) closed by the solid's sections on the cell faces (clipped to
//! the face rectangles), integrated by the divergence theorem with a quadrature rule;
//! closed forms for a box; the whole solid's mass properties by the parallel axis
//! theorem; the same bits at any thread count and for any block.

mod common;

use common::{clip, overlap, XorShift};
use meshvol::grid::{cut_cells, cut_cells_extras, CutCells, Extras, Grid};
use meshvol::section::{section, Plane};
use meshvol::shapes::{cuboid, torus, uv_sphere};
use meshvol::{mass_properties, Mesh};

type P = [f64; 3];

const ALL: Extras = Extras { second_moments: true, face_centroids: true };

fn extras(mesh: &Mesh, grid: &Grid) -> CutCells {
    cut_cells_extras(mesh, grid, &grid.counts.map(|n| 0..n), ALL, &()).unwrap()
}

/// A grid around `mesh` with a margin, of `counts` cells.
fn around(mesh: &Mesh, counts: [usize; 3], margin: f64) -> Grid {
    let b = mass_properties(mesh).bounds.unwrap();
    Grid::from_bounds(b.min.map(|x| x - margin), b.max.map(|x| x + margin), counts).unwrap()
}

fn cells(shape: [usize; 3]) -> impl Iterator<Item = [usize; 3]> {
    let [nx, ny, nz] = shape;
    (0..nx).flat_map(move |i| (0..ny).flat_map(move |j| (0..nz).map(move |k| [i, j, k])))
}

fn tilted_box() -> Mesh {
    // A box turned about (1, 2, 3) by 0.7 rad (Rodrigues), off the grid's planes.
    let (lo, hi) = ([-0.6, -0.4, -0.5], [0.6, 0.4, 0.5]);
    let n = 14f64.sqrt();
    let k = [1.0 / n, 2.0 / n, 3.0 / n];
    let (s, c) = 0.7f64.sin_cos();
    common::mapped(&cuboid(lo, hi), |p| {
        let kxp = [k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2], k[0] * p[1] - k[1] * p[0]];
        let kp = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
        [0, 1, 2].map(|d| p[d] * c + kxp[d] * s + k[d] * kp * (1.0 - c) + 0.05)
    })
}

/// Strang and Fix's 4-point rule, exact for cubics on a triangle: barycentric points and
/// weights (summing to 1).
const RULE: [([f64; 3], f64); 4] = [
    ([1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0], -27.0 / 48.0),
    ([0.6, 0.2, 0.2], 25.0 / 48.0),
    ([0.2, 0.6, 0.2], 25.0 / 48.0),
    ([0.2, 0.2, 0.6], 25.0 / 48.0),
];

/// `Σ_fan (signed measure) · mean of f over the triangle` by [`RULE`]: `measure(o, a, b)`
/// gives the triangle's signed measure (`∫ n_x dA` in 3D, its area in 2D).
fn over_fan<const D: usize>(
    poly: &[[f64; D]],
    measure: impl Fn([f64; D], [f64; D], [f64; D]) -> f64,
    f: impl Fn([f64; D]) -> f64,
) -> f64 {
    let mut total = 0.0;
    for t in 1..poly.len().saturating_sub(1) {
        let (o, a, b) = (poly[0], poly[t], poly[t + 1]);
        let mean: f64 = RULE
            .iter()
            .map(|(l, w)| w * f(std::array::from_fn(|e| l[0] * o[e] + l[1] * a[e] + l[2] * b[e])))
            .sum();
        total += measure(o, a, b) * mean;
    }
    total
}

/// The triangles of `mesh`.
fn triangles(mesh: &Mesh) -> Vec<[P; 3]> {
    let mut t = Vec::new();
    for f in 0..mesh.face_count() {
        let v = mesh.face(f);
        for k in 1..v.len() - 1 {
            t.push([v[0], v[k], v[k + 1]].map(|i| mesh.positions()[i as usize]));
        }
    }
    t
}

/// The solid's section at `x_axis = value` as rings in the plane's frame `(u, v)` (axes
/// `frame`), exteriors counter-clockwise and holes clockwise.
fn section_rings(mesh: &Mesh, axis: usize, value: f64) -> (Vec<Vec<[f64; 2]>>, [usize; 2]) {
    let plane = Plane::axis(axis, value).unwrap();
    let f = plane.frame();
    let which = |u: P| (0..3).find(|&d| u[d] != 0.0).unwrap();
    let s = section(mesh, &plane);
    let rings = s.polygons.iter().flat_map(|p| p.rings().map(<[_]>::to_vec)).collect();
    (rings, [which(f.u), which(f.v)])
}

/// `∫ g dA` over the part of the section `rings` (frame axes `frame`) inside the
/// rectangle `lo ≤ p ≤ hi` (world), for `g` of the world point (the plane's coordinate
/// left 0).
fn over_wetted(
    (rings, frame): &(Vec<Vec<[f64; 2]>>, [usize; 2]),
    lo: P,
    hi: P,
    g: impl Fn(P) -> f64 + Copy,
) -> f64 {
    let area = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        0.5 * ((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]))
    };
    rings
        .iter()
        .map(|ring| {
            let mut poly = ring.clone();
            for (e, &d) in frame.iter().enumerate() {
                poly = clip(poly, e, lo[d], hi[d]);
            }
            over_fan(&poly, area, |q| {
                let mut p = [0.0; 3];
                p[frame[0]] = q[0];
                p[frame[1]] = q[1];
                g(p)
            })
        })
        .sum()
}

/// The cut cell `cell`'s volume, first and second moments `(xx, yy, zz, xy, yz, zx)`
/// about its low corner, by `∫ ∂F/∂x dV = ∮ F n_x dA` with `F` vanishing on the face
/// `x = x_lo` (every `F` below has a factor `u = x − x_lo`): the surface clipped to the
/// cell, and the section at `x = x_hi` clipped to the face.
fn reference(
    triangles: &[[P; 3]],
    far: &(Vec<Vec<[f64; 2]>>, [usize; 2]),
    lo: P,
    hi: P,
) -> (f64, P, [f64; 6]) {
    // F_x per quantity, of the local point r = p − lo.
    let fields: [fn(P) -> f64; 10] = [
        |r| r[0],
        |r| r[0] * r[0] / 2.0,
        |r| r[0] * r[1],
        |r| r[0] * r[2],
        |r| r[0].powi(3) / 3.0,
        |r| r[0] * r[1] * r[1],
        |r| r[0] * r[2] * r[2],
        |r| r[0] * r[0] * r[1] / 2.0,
        |r| r[0] * r[1] * r[2],
        |r| r[0] * r[0] * r[2] / 2.0,
    ];
    let local = |p: P| [0, 1, 2].map(|d| p[d] - lo[d]);
    let n_x =
        |o: P, a: P, b: P| 0.5 * ((a[1] - o[1]) * (b[2] - o[2]) - (a[2] - o[2]) * (b[1] - o[1]));
    let mut sums = [0.0; 10];
    for t in triangles {
        let mut poly = t.to_vec();
        for d in 0..3 {
            poly = clip(poly, d, lo[d], hi[d]);
        }
        for (s, f) in sums.iter_mut().zip(fields) {
            *s += over_fan(&poly, n_x, |p| f(local(p)));
        }
    }
    for (s, f) in sums.iter_mut().zip(fields) {
        // The face x = x_hi, outward normal +x.
        *s += over_wetted(far, lo, hi, |p| f(local([hi[0], p[1], p[2]])));
    }
    let s = sums;
    (s[0], [s[1], s[2], s[3]], [s[4], s[5], s[6], s[7], s[8], s[9]])
}

/// The inertia tensor about `c` (relative to the corner) of second moments `m2` about
/// the corner, first moment `m1`, volume `v`.
fn inertia_of(v: f64, m1: P, m2: [f64; 6], c: P) -> [[f64; 3]; 3] {
    let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0)];
    let cov: Vec<f64> = pairs
        .iter()
        .enumerate()
        .map(|(n, &(a, b))| m2[n] - c[a] * m1[b] - m1[a] * c[b] + v * c[a] * c[b])
        .collect();
    let (xx, yy, zz, xy, yz, zx) = (cov[0], cov[1], cov[2], cov[3], cov[4], cov[5]);
    [[yy + zz, -xy, -zx], [-xy, xx + zz, -yz], [-zx, -yz, xx + yy]]
}

#[test]
fn every_cell_against_a_naive_clip_closed_by_sections() {
    for mesh in [uv_sphere(1.0, 16, 9), tilted_box()] {
        let grid = around(&mesh, [5, 4, 6], 0.1);
        let c = extras(&mesh, &grid);
        let triangles = triangles(&mesh);
        let size = grid.cell.iter().fold(0.0f64, |a, &b| a.max(b));
        let scale = grid.cell_volume() * size * size;
        let mut cut = 0;
        for cell in cells(grid.counts) {
            let n = grid.index(cell);
            let lo = [0, 1, 2].map(|d| grid.origin[d] + cell[d] as f64 * grid.cell[d]);
            let hi = [0, 1, 2].map(|d| lo[d] + grid.cell[d]);
            let far = section_rings(&mesh, 0, hi[0]);
            let (v, m1, m2) = reference(&triangles, &far, lo, hi);
            assert!((v - c.volume[n]).abs() < 1e-12, "{cell:?}: {v} vs {}", c.volume[n]);
            let want = if v.abs() < 1e-9 * grid.cell_volume() {
                [[0.0; 3]; 3]
            } else {
                inertia_of(v, m1, m2, m1.map(|m| m / v))
            };
            for a in 0..3 {
                for b in 0..3 {
                    let got = c.inertia[n][a][b];
                    assert!(
                        (got - want[a][b]).abs() < 1e-11 * scale,
                        "{cell:?} [{a}][{b}]: {got} vs {}",
                        want[a][b]
                    );
                }
            }
            if v > 1e-3 * grid.cell_volume() && v < 0.999 * grid.cell_volume() {
                cut += 1;
            }
        }
        assert!(cut > 10, "only {cut} cut cells");
    }
}

#[test]
fn face_centroids_are_those_of_the_sections_in_the_faces() {
    for mesh in [uv_sphere(1.0, 16, 9), tilted_box(), torus(1.0, 0.35, 24, 12)] {
        let grid = around(&mesh, [6, 5, 4], 0.07);
        let c = extras(&mesh, &grid);
        let (mut wet, mut dry) = (0, 0);
        for axis in 0..3 {
            let mut shape = grid.counts;
            shape[axis] += 1;
            let face = grid.cell[(axis + 1) % 3] * grid.cell[(axis + 2) % 3];
            for m in 0..shape[axis] {
                let plane = grid.origin[axis] + m as f64 * grid.cell[axis];
                let rings = section_rings(&mesh, axis, plane);
                for at in cells(shape).filter(|at| at[axis] == m) {
                    let lo = [0, 1, 2].map(|d| grid.origin[d] + at[d] as f64 * grid.cell[d]);
                    let hi = [0, 1, 2].map(|d| lo[d] + grid.cell[d]);
                    let area = over_wetted(&rings, lo, hi, |_| 1.0);
                    let n = (at[0] * shape[1] + at[1]) * shape[2] + at[2];
                    let got = c.aperture_centroid[axis][n];
                    assert!((c.aperture[axis][n] * face - area).abs() < 1e-12);
                    if area.abs() < 1e-12 {
                        assert!(got.iter().all(|x| x.is_nan()), "{axis} {at:?}: {got:?}");
                        dry += 1;
                        continue;
                    }
                    let mut want = [plane; 3];
                    for d in (0..3).filter(|&d| d != axis) {
                        want[d] = over_wetted(&rings, lo, hi, |p| p[d] - lo[d]) / area + lo[d];
                    }
                    let tol = if area > 1e-6 * face { 1e-10 } else { 1e-3 };
                    for d in 0..3 {
                        assert!(
                            (got[d] - want[d]).abs() < tol * grid.cell[d],
                            "axis {axis} face {at:?}: {got:?} vs {want:?}"
                        );
                    }
                    wet += 1;
                }
            }
        }
        assert!(wet > 20 && dry > 20, "{wet} wetted faces, {dry} dry");
    }
}

#[test]
fn a_box_by_closed_forms() {
    let (lo, hi) = ([0.13, -0.27, 0.31], [1.71, 0.94, 1.05]);
    let mesh = cuboid(lo, hi);
    let grid = Grid::new([-0.2, -0.5, 0.0], [0.25, 0.3, 0.2], [9, 6, 7]).unwrap();
    let c = extras(&mesh, &grid);
    let range = |d: usize, n: usize| {
        let a = grid.origin[d] + n as f64 * grid.cell[d];
        (a, a + grid.cell[d])
    };
    let (mut full, mut partial) = (0, 0);
    for at in cells(grid.counts) {
        let n = grid.index(at);
        let o = [0, 1, 2].map(|d| overlap(range(d, at[d]), (lo[d], hi[d])));
        let l = o.map(|(a, b)| (b - a).max(0.0));
        let v = l[0] * l[1] * l[2];
        // A box's inertia about its centre: V (l_b² + l_c²) / 12, no products.
        let want = [0, 1, 2].map(|a| {
            [0, 1, 2].map(|b| {
                if a == b {
                    v * (l[(a + 1) % 3].powi(2) + l[(a + 2) % 3].powi(2)) / 12.0
                } else {
                    0.0
                }
            })
        });
        if v == grid.cell_volume() {
            full += 1;
        } else if v > 0.0 {
            partial += 1;
        }
        for a in 0..3 {
            for b in 0..3 {
                let got = c.inertia[n][a][b];
                assert!((got - want[a][b]).abs() < 1e-15, "{at:?} [{a}][{b}]: {got}");
            }
        }
    }
    assert!(full > 10 && partial > 10);
    // The wetted part of a face: the rectangle of the box's section in it.
    for axis in 0..3 {
        let mut shape = grid.counts;
        shape[axis] += 1;
        for at in cells(shape) {
            let plane = grid.origin[axis] + at[axis] as f64 * grid.cell[axis];
            let got = c.aperture_centroid[axis][(at[0] * shape[1] + at[1]) * shape[2] + at[2]];
            let o = [0, 1, 2].map(|d| overlap(range(d, at[d]), (lo[d], hi[d])));
            let wetted = plane >= lo[axis]
                && plane < hi[axis]
                && (0..3).filter(|&d| d != axis).all(|d| o[d].1 > o[d].0);
            if !wetted {
                assert!(got.iter().all(|x| x.is_nan()), "{axis} {at:?}: {got:?}");
                continue;
            }
            for d in 0..3 {
                let want = if d == axis { plane } else { 0.5 * (o[d].0 + o[d].1) };
                assert!((got[d] - want).abs() < 1e-14, "{axis} {at:?} {d}: {got:?}");
            }
        }
    }
}

/// `Σ` over the cells of their inertia moved back to the solid's centroid, the solid's
/// inertia (parallel axis theorem: `C_about_g = Σ C_cell + V_cell (c − g)(c − g)ᵀ`).
fn summed_inertia(c: &CutCells, g: P) -> [[f64; 3]; 3] {
    let mut cov = [[0.0; 3]; 3];
    for n in 0..c.volume.len() {
        let i = c.inertia[n];
        let tr = (i[0][0] + i[1][1] + i[2][2]) / 2.0;
        let r = [0, 1, 2].map(|d| c.centroid[n][d] - g[d]);
        for a in 0..3 {
            for b in 0..3 {
                let own = if a == b { tr - i[a][a] } else { -i[a][b] };
                cov[a][b] += own + c.volume[n] * r[a] * r[b];
            }
        }
    }
    let tr = cov[0][0] + cov[1][1] + cov[2][2];
    [0, 1, 2].map(|a| [0, 1, 2].map(|b| if a == b { tr - cov[a][a] } else { -cov[a][b] }))
}

#[test]
fn the_cells_sum_to_the_solids_inertia() {
    let moved = common::moved(&tilted_box(), [0.3, -0.2, 0.1]);
    for (name, mesh) in [("sphere", uv_sphere(1.0, 40, 20)), ("box", moved)] {
        for counts in [[7, 5, 6], [16, 13, 11]] {
            let grid = around(&mesh, counts, 0.05);
            let c = extras(&mesh, &grid);
            let mp = mass_properties(&mesh);
            let got = summed_inertia(&c, mp.centroid.unwrap());
            let scale = mp.inertia[0][0].abs();
            for a in 0..3 {
                for b in 0..3 {
                    assert!(
                        (got[a][b] - mp.inertia[a][b]).abs() < 1e-12 * scale,
                        "{name} {counts:?} [{a}][{b}]: {} vs {}",
                        got[a][b],
                        mp.inertia[a][b]
                    );
                }
            }
        }
    }
}

/// The bits of the extra arrays (NaN ≠ NaN for `==`).
fn bits(c: &CutCells) -> Vec<u64> {
    let inertia = c.inertia.iter().flatten().flatten();
    let faces = c.aperture_centroid.iter().flatten().flatten();
    inertia.chain(faces).map(|x| x.to_bits()).collect()
}

#[test]
fn the_same_bits_at_any_thread_count_and_without_the_extras() {
    let mesh = uv_sphere(1.0, 64, 32);
    let grid = around(&mesh, [40, 33, 29], 0.05);
    let at = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| extras(&mesh, &grid))
    };
    let one = at(1);
    assert!(!one.inertia.is_empty() && one.aperture_centroid.iter().all(|a| !a.is_empty()));
    for threads in [2, 5] {
        assert_eq!(bits(&one), bits(&at(threads)), "{threads} threads");
    }
    // The default arrays are the same bits with or without the extras.
    let mut plain = one.clone();
    plain.inertia.clear();
    plain.aperture_centroid = Default::default();
    assert_eq!(plain, cut_cells(&mesh, &grid).unwrap());
    // Either extra alone is the same bits as with both.
    for (second_moments, face_centroids) in [(true, false), (false, true)] {
        let e = Extras { second_moments, face_centroids };
        let alone = cut_cells_extras(&mesh, &grid, &grid.counts.map(|n| 0..n), e, &()).unwrap();
        assert_eq!(alone.inertia.is_empty(), !second_moments);
        assert_eq!(alone.aperture_centroid[0].is_empty(), !face_centroids);
        let mut expected = one.clone();
        if !second_moments {
            expected.inertia.clear();
        }
        if !face_centroids {
            expected.aperture_centroid = Default::default();
        }
        assert_eq!(bits(&alone), bits(&expected));
    }
}

#[test]
fn any_block_is_the_same_bits_as_the_whole_grid() {
    let (lo, hi) = ([0.13, -0.27, 0.31], [1.71, 0.94, 1.05]);
    let cases = [
        (uv_sphere(1.0, 40, 20), Grid::new([-1.1; 3], [0.2, 0.26, 0.24], [7, 5, 5]).unwrap()),
        (cuboid(lo, hi), Grid::from_bounds(lo, hi, [5, 4, 3]).unwrap()),
        (tilted_box(), Grid::new([-0.7, -0.8, -0.6], [0.3, 0.25, 0.35], [4, 6, 5]).unwrap()),
    ];
    let mut rng = XorShift::new(13);
    for (mesh, grid) in cases {
        let whole = extras(&mesh, &grid);
        for _ in 0..10 {
            let region = grid.counts.map(|n| {
                let a = rng.below(n as u64) as usize;
                let b = rng.below(n as u64) as usize;
                a.min(b)..a.max(b) + 1
            });
            let block = cut_cells_extras(&mesh, &grid, &region, ALL, &()).unwrap();
            for (n, at) in cells(block.shape()).enumerate() {
                let g = whole.local([0, 1, 2].map(|a| at[a] + region[a].start)).unwrap();
                let (x, y) = (block.inertia[n].as_flattened(), whole.inertia[g].as_flattened());
                assert!(x.iter().zip(y).all(|(a, b)| a.to_bits() == b.to_bits()), "{at:?}");
            }
            for a in 0..3 {
                let mut shape = block.shape();
                shape[a] += 1;
                let mut full = grid.counts;
                full[a] += 1;
                for (n, at) in cells(shape).enumerate() {
                    let g = [0, 1, 2].map(|d| at[d] + region[d].start);
                    let w = whole.aperture_centroid[a][(g[0] * full[1] + g[1]) * full[2] + g[2]];
                    let b = block.aperture_centroid[a][n];
                    assert_eq!(b.map(f64::to_bits), w.map(f64::to_bits), "axis {a} {g:?}");
                }
            }
        }
    }
}

#[test]
fn a_box_on_its_own_bounding_box() {
    // Every cell full; the box's faces lie on the grid's outer faces, whose apertures are
    // the section beyond them (0: NaN centroids), and the inner faces are whole (their
    // middles).
    let (lo, hi) = ([0.5, -1.0, 2.0], [1.7, 0.5, 2.9]);
    let grid = Grid::from_bounds(lo, hi, [3, 4, 5]).unwrap();
    let c = extras(&cuboid(lo, hi), &grid);
    let h = grid.cell;
    let own = [0, 1, 2].map(|a| {
        let v = grid.cell_volume();
        v * (h[(a + 1) % 3].powi(2) + h[(a + 2) % 3].powi(2)) / 12.0
    });
    for n in 0..grid.cell_count() {
        for a in 0..3 {
            for b in 0..3 {
                let want = if a == b { own[a] } else { 0.0 };
                assert!((c.inertia[n][a][b] - want).abs() < 1e-15 * own[a], "{n} [{a}][{b}]");
            }
        }
    }
    for axis in 0..3 {
        let mut shape = grid.counts;
        shape[axis] += 1;
        for (n, at) in cells(shape).enumerate() {
            let got = c.aperture_centroid[axis][n];
            if at[axis] == 0 || at[axis] == grid.counts[axis] {
                assert!(got.iter().all(|x| x.is_nan()), "{axis} {at:?}: {got:?}");
                continue;
            }
            for d in 0..3 {
                let middle = if d == axis { 0.0 } else { 0.5 };
                let want = grid.origin[d] + (at[d] as f64 + middle) * h[d];
                assert!((got[d] - want).abs() < 1e-14, "{axis} {at:?}: {got:?}");
            }
        }
    }
}
