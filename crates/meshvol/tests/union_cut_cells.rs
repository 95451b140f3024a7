//! The cut cells of a union of bodies (`union_boundary` measured by `cut_cells`) against
//! independent computations: the sum of the single bodies' cut cells where they are
//! apart; closed forms for two overlapping boxes (inclusion–exclusion of boxes, and
//! the faces each leaves outside the other); a mesh of the union written by hand; the
//! union's cell volumes resolved on the measuring grid itself; the identities of
//! docs/cells.md; the same bits at any thread count.

mod common;

use common::{cells, divergence, mapped, moved, polygons, rotation, XorShift};
use meshvol::grid::{
    cut_cells, cut_cells_extras, union, union_boundary, union_cell_volumes, CutCells, Extras, Grid,
};
use meshvol::shapes::{cuboid, uv_sphere};
use meshvol::{mass_properties, Mesh, Surface};

type P = [f64; 3];

/// The union's cut cells on `grid`, with both extras.
fn union_cells<S: Surface>(bodies: &[S], grid: &Grid) -> CutCells {
    let boundary = union_boundary(bodies).unwrap();
    let all = Extras { second_moments: true, face_centroids: true };
    cut_cells_extras(&boundary, grid, &grid.counts.map(|n| 0..n), all, &()).unwrap()
}

/// The per-cell sums that add up over bodies apart: volume, first moment, surface area,
/// ∫ n dA, area-weighted surface centroid, apertures.
fn additive(c: &CutCells) -> Vec<Vec<f64>> {
    let mut out = vec![c.volume.clone(), c.boundary_area.clone()];
    for d in 0..3 {
        out.push(c.volume.iter().zip(&c.centroid).map(|(v, x)| v * x[d]).collect());
        out.push(c.boundary_vector.iter().map(|v| v[d]).collect());
        let weighted = c.boundary_area.iter().zip(&c.boundary_centroid).map(|(a, x)| a * x[d]);
        out.push(weighted.collect());
        out.push(c.aperture[d].clone());
    }
    out
}

#[test]
fn bodies_apart_give_the_sum_of_their_own_cut_cells() {
    // Two spheres and a box, apart but sharing cells.
    let bodies = [
        uv_sphere(1.0, 32, 16),
        moved(&uv_sphere(0.7, 24, 12), [2.3, 0.2, -0.1]),
        cuboid([-1.0, 1.2, -0.6], [2.5, 1.9, 0.4]),
    ];
    let grid = Grid::from_bounds([-1.13, -1.07, -1.11], [3.1, 2.03, 1.09], [17, 13, 9]).unwrap();
    let u = union_cells(&bodies, &grid);
    let parts: Vec<Vec<Vec<f64>>> =
        bodies.iter().map(|b| additive(&cut_cells(b, &grid).unwrap())).collect();
    let got = additive(&u);
    for (q, array) in got.iter().enumerate() {
        for (n, &x) in array.iter().enumerate() {
            let want: f64 = parts.iter().map(|p| p[q][n]).sum();
            assert!((x - want).abs() < 1e-12, "quantity {q} entry {n}: {x} vs {want}");
        }
    }
}

/// An axis-aligned box.
#[derive(Clone, Copy)]
struct Box3 {
    lo: P,
    hi: P,
}

impl Box3 {
    fn meet(self, o: Box3) -> Box3 {
        Box3 {
            lo: [0, 1, 2].map(|d| self.lo[d].max(o.lo[d])),
            hi: [0, 1, 2].map(|d| self.hi[d].min(o.hi[d])),
        }
    }
    fn side(self, d: usize) -> f64 {
        (self.hi[d] - self.lo[d]).max(0.0)
    }
    fn volume(self) -> f64 {
        self.side(0) * self.side(1) * self.side(2)
    }
    /// ∫ x dV over the box.
    fn moment(self) -> P {
        [0, 1, 2].map(|d| self.volume() * 0.5 * (self.lo[d] + self.hi[d]))
    }
    /// The area of its rectangle across axis `a` and that rectangle's ∫ x dA (the
    /// coordinate along `a` left out).
    fn across(self, a: usize) -> (f64, P) {
        let (p, q) = ((a + 1) % 3, (a + 2) % 3);
        let area = self.side(p) * self.side(q);
        let mut m = [0.0; 3];
        for d in [p, q] {
            m[d] = area * 0.5 * (self.lo[d] + self.hi[d]);
        }
        (area, m)
    }
}

/// The union of boxes `a` and `b` in cell `c` by inclusion–exclusion, and their faces
/// outside each other in it: (volume, ∫ x dV, surface area, ∫ n dA, ∫ x dA).
fn two_boxes_in(a: Box3, b: Box3, c: Box3) -> (f64, P, f64, P, P) {
    let (ca, cb, cab) = (c.meet(a), c.meet(b), c.meet(a.meet(b)));
    let volume = ca.volume() + cb.volume() - cab.volume();
    let moment = [0, 1, 2].map(|d| ca.moment()[d] + cb.moment()[d] - cab.moment()[d]);
    let (mut area, mut vector, mut weighted) = (0.0, [0.0; 3], [0.0; 3]);
    for (x, y) in [(a, b), (b, a)] {
        for d in 0..3 {
            for (plane, sign) in [(x.lo[d], -1.0), (x.hi[d], 1.0)] {
                // No box face lies on a grid plane: the face is in the cell's open slab.
                if !(c.lo[d] < plane && plane < c.hi[d]) {
                    continue;
                }
                let (full, full_m) = c.meet(x).across(d);
                // Hidden where the plane is strictly inside the other box.
                let (hidden, hidden_m) = if y.lo[d] < plane && plane < y.hi[d] {
                    c.meet(x).meet(y).across(d)
                } else {
                    (0.0, [0.0; 3])
                };
                let seen = full - hidden;
                area += seen;
                vector[d] += sign * seen;
                for e in 0..3 {
                    let m = if e == d { seen * plane } else { full_m[e] - hidden_m[e] };
                    weighted[e] += m;
                }
            }
        }
    }
    (volume, moment, area, vector, weighted)
}

/// The fraction of face `at` across axis `a` (corner `lo`, sides `cell`) in A ∪ B.
fn two_boxes_aperture(a: Box3, b: Box3, at: P, axis: usize, cell: P) -> f64 {
    let plane = at[axis];
    let mut face = Box3 { lo: at, hi: [0, 1, 2].map(|d| at[d] + cell[d]) };
    face.hi[axis] = plane;
    let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
    let inside = |x: Box3| x.lo[axis] < plane && plane < x.hi[axis];
    let area = |x: Box3| {
        let m = face.meet(x);
        m.side(p) * m.side(q)
    };
    let mut wet = 0.0;
    if inside(a) {
        wet += area(a);
    }
    if inside(b) {
        wet += area(b);
    }
    if inside(a) && inside(b) {
        wet -= area(a.meet(b));
    }
    wet / (cell[p] * cell[q])
}

#[test]
fn two_overlapping_boxes_by_closed_forms() {
    let a = Box3 { lo: [0.0, 0.0, 0.0], hi: [2.0, 2.0, 2.0] };
    let b = Box3 { lo: [1.0, 0.5, 1.25], hi: [3.0, 2.5, 3.0] };
    let bodies = [cuboid(a.lo, a.hi), cuboid(b.lo, b.hi)];
    // No grid plane on a box face.
    let grid = Grid::new([-0.3, -0.2, -0.35], [0.45, 0.4, 0.5], [8, 8, 8]).unwrap();
    let c = union_cells(&bodies, &grid);
    let face = grid.cell[0] * grid.cell[1];
    let tol = 1e-12;
    for at in cells(&grid) {
        let lo = [0, 1, 2].map(|d| grid.origin[d] + at[d] as f64 * grid.cell[d]);
        let cell = Box3 { lo, hi: [0, 1, 2].map(|d| lo[d] + grid.cell[d]) };
        let n = grid.index(at);
        let (v, m, area, vector, weighted) = two_boxes_in(a, b, cell);
        assert!((c.volume[n] - v).abs() < tol, "{at:?}: volume {} vs {v}", c.volume[n]);
        assert!(
            (c.boundary_area[n] - area).abs() < tol,
            "{at:?}: {} vs {area}",
            c.boundary_area[n]
        );
        for d in 0..3 {
            assert!((c.volume[n] * c.centroid[n][d] - m[d]).abs() < tol, "{at:?}: centroid");
            assert!((c.boundary_vector[n][d] - vector[d]).abs() < tol, "{at:?}: vector");
            let w = c.boundary_area[n] * c.boundary_centroid[n][d];
            assert!(
                (w - weighted[d]).abs() < tol,
                "{at:?}: boundary centroid {w} vs {}",
                weighted[d]
            );
        }
        let div = divergence(&c, at);
        assert!(div.iter().all(|x| x.abs() < tol * face), "{at:?}: {div:?}");
    }
    // Every face's aperture.
    let [nx, ny, nz] = grid.counts;
    for axis in 0..3 {
        let mut shape = [nx, ny, nz];
        shape[axis] += 1;
        for i in 0..shape[0] {
            for j in 0..shape[1] {
                for k in 0..shape[2] {
                    let at = [i, j, k].map(|x| x as f64);
                    let corner = [0, 1, 2].map(|d| grid.origin[d] + at[d] * grid.cell[d]);
                    let want = two_boxes_aperture(a, b, corner, axis, grid.cell);
                    let got = c.aperture[axis][(i * shape[1] + j) * shape[2] + k];
                    assert!(
                        (got - want).abs() < tol,
                        "aperture {axis} {i} {j} {k}: {got} vs {want}"
                    );
                }
            }
        }
    }
    // In sum: 8 + 7 − 1·1.5·0.75 of volume; 24 + 22 of surface minus the faces hidden in
    // the other box (A's x = 2, y = 2, z = 2 and B's x = 1, y = 0.5, z = 1.25).
    let hidden = 2.0 * (1.5 * 0.75 + 1.0 * 0.75 + 1.0 * 1.5);
    let area: f64 = c.boundary_area.iter().sum();
    assert!((area - (46.0 - hidden)).abs() < 1e-11, "{area}");
    let volume: f64 = c.volume.iter().sum();
    assert!((volume - (15.0 - 1.125)).abs() < 1e-11, "{volume}");
}

/// Two unit cubes' union, one moved by (½, ½, 0) from the other: a prism over an
/// octagon, written by hand (top and bottom as three convex quadrilaterals each).
fn octagon_prism() -> Mesh {
    let plan: [[f64; 2]; 8] = [
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 0.5],
        [1.5, 0.5],
        [1.5, 1.5],
        [0.5, 1.5],
        [0.5, 1.0],
        [0.0, 1.0],
    ];
    let mut p: Vec<P> = plan.iter().map(|q| [q[0], q[1], 0.0]).collect();
    p.extend(plan.iter().map(|q| [q[0], q[1], 1.0]));
    // Extra corners for the rectangles of the caps: (1, 1) below and above.
    p.push([1.0, 1.0, 0.0]);
    p.push([1.0, 1.0, 1.0]);
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for k in 0..8u32 {
        let n = (k + 1) % 8;
        faces.push(vec![k, n, n + 8, k + 8]);
    }
    // The square [0,1]² = 0 1 X 7, and the rest of the octagon cut along X–4 into
    // 2 3 4 X and 6 X 4 5 (X = (1, 1), index 16).
    let rects = [[0, 1, 16, 7], [2, 3, 4, 16], [6, 16, 4, 5]];
    for r in rects {
        // Counter-clockwise in plan: the top faces up, the bottom down.
        let top: Vec<u32> = r.iter().map(|&v| if v == 16 { 17 } else { v + 8 }).collect();
        faces.push(top);
        faces.push(r.iter().rev().copied().collect());
    }
    polygons(&p, &faces)
}

#[test]
fn a_cube_and_its_moved_copy_against_their_union_written_by_hand() {
    let cube = cuboid([0.0; 3], [1.0; 3]);
    let mut rng = XorShift::new(7);
    // Along x alone (the union a box), and across (a prism over an octagon); as they
    // are and turned (steep faces: the turned passes).
    let cases =
        [([0.5, 0.0, 0.0], cuboid([0.0; 3], [1.5, 1.0, 1.0])), ([0.5, 0.5, 0.0], octagon_prism())];
    for (shift, by_hand) in cases {
        for turn in [false, true] {
            let r = if turn {
                rotation(&mut rng)
            } else {
                [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
            };
            let place = |m: &Mesh| {
                mapped(m, |p| [0, 1, 2].map(|i| (0..3).map(|j| r[i][j] * p[j]).sum::<f64>()))
            };
            let bodies = [place(&cube), place(&moved(&cube, shift))];
            let reference = place(&by_hand);
            let b = mass_properties(&reference).bounds.unwrap();
            let grid =
                Grid::from_bounds(b.min.map(|x| x - 0.07), b.max.map(|x| x + 0.11), [9, 8, 7])
                    .unwrap();
            let got = union_cells(&bodies, &grid);
            let all = Extras { second_moments: true, face_centroids: true };
            let want =
                cut_cells_extras(&reference, &grid, &grid.counts.map(|n| 0..n), all, &()).unwrap();
            let close = |x: f64, y: f64, what: &str| {
                let ok = (x - y).abs() < 1e-11 || (x.is_nan() && y.is_nan());
                assert!(ok, "{shift:?} turned {turn}: {what}: {x} vs {y}");
            };
            for n in 0..grid.cell_count() {
                close(got.volume[n], want.volume[n], "volume");
                close(got.boundary_area[n], want.boundary_area[n], "boundary area");
                for d in 0..3 {
                    close(
                        got.volume[n] * got.centroid[n][d],
                        want.volume[n] * want.centroid[n][d],
                        "moment",
                    );
                    close(got.boundary_vector[n][d], want.boundary_vector[n][d], "vector");
                    let w = |c: &CutCells| c.boundary_area[n] * c.boundary_centroid[n][d];
                    close(w(&got), w(&want), "boundary centroid");
                    for e in 0..3 {
                        close(got.inertia[n][d][e], want.inertia[n][d][e], "inertia");
                    }
                }
            }
            for axis in 0..3 {
                for (n, (&x, &y)) in got.aperture[axis].iter().zip(&want.aperture[axis]).enumerate()
                {
                    close(x, y, "aperture");
                    if x.abs() > 1e-6 {
                        for d in 0..3 {
                            let (p, q) = (
                                got.aperture_centroid[axis][n][d],
                                want.aperture_centroid[axis][n][d],
                            );
                            close(x * p, y * q, "face centroid");
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn overlapping_spheres_meet_the_identities_and_the_unions_own_cell_volumes() {
    let bodies = [
        uv_sphere(1.0, 40, 20),
        moved(&uv_sphere(0.8, 36, 18), [0.9, 0.3, -0.2]),
        moved(&cuboid([-0.4, -0.5, -0.3], [0.6, 0.4, 0.5]), [0.2, -0.6, 0.7]),
    ];
    let grid = Grid::from_bounds([-1.1, -1.2, -1.15], [1.8, 1.15, 1.25], [13, 11, 12]).unwrap();
    let c = union_cells(&bodies, &grid);
    let face = grid.cell[0] * grid.cell[1];
    for at in cells(&grid) {
        let d = divergence(&c, at);
        assert!(d.iter().all(|x| x.abs() < 1e-12 * face.max(1.0)), "{at:?}: {d:?}");
    }
    // The union's cell volumes, resolved on this grid itself (not on the boundary's).
    let (volumes, unresolved) = union_cell_volumes(&bodies, &grid).unwrap();
    assert_eq!(unresolved, 0);
    for (n, (x, y)) in c.volume.iter().zip(&volumes).enumerate() {
        assert!((x - y).abs() < 1e-12, "cell {n}: {x} vs {y}");
    }
    // Σ volume in the certified interval; a closed surface's Σ n dA = 0; the first
    // moment is the boundary's own (the divergence theorem over the whole union).
    let u = union(&bodies, 1e-12).unwrap();
    let total: f64 = c.volume.iter().sum();
    assert!(u.lower - 1e-12 <= total && total <= u.upper + 1e-12, "{total} vs {u:?}");
    let sum_n: Vec<f64> = (0..3).map(|d| c.boundary_vector.iter().map(|v| v[d]).sum()).collect();
    assert!(sum_n.iter().all(|x| x.abs() < 1e-12), "{sum_n:?}");
    let boundary = union_boundary(&bodies).unwrap();
    let mp = mass_properties(&boundary);
    assert!((mp.area - c.boundary_area.iter().sum::<f64>()).abs() < 1e-12 * mp.area);
    for d in 0..3 {
        let m: f64 = c.volume.iter().zip(&c.centroid).map(|(v, x)| v * x[d]).sum();
        let want = mp.centroid.unwrap()[d] * mp.signed_volume;
        assert!((m - want).abs() < 1e-12, "{m} vs {want}");
    }
}

#[test]
fn the_same_bits_at_any_thread_count() {
    let bodies =
        [uv_sphere(1.0, 32, 16), moved(&cuboid([0.0; 3], [1.2, 0.9, 0.8]), [0.1, -0.2, 0.05])];
    let grid = Grid::from_bounds([-1.05; 3], [1.35, 1.05, 1.05], [11, 9, 10]).unwrap();
    let at = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| union_cells(&bodies, &grid))
    };
    let bits = |c: &CutCells| {
        let mut v: Vec<u64> =
            c.volume.iter().chain(&c.boundary_area).map(|x| x.to_bits()).collect();
        for a in [&c.centroid, &c.boundary_vector, &c.boundary_centroid] {
            v.extend(a.as_flattened().iter().map(|x| x.to_bits()));
        }
        for a in &c.aperture {
            v.extend(a.iter().map(|x| x.to_bits()));
        }
        v.extend(c.inertia.as_flattened().as_flattened().iter().map(|x| x.to_bits()));
        v
    };
    let one = bits(&at(1));
    assert_eq!(one, bits(&at(2)));
    assert_eq!(one, bits(&at(5)));
}

/// A right prism over a regular `n`-gon of circumradius `r` centred at `(x, y)`, from
/// `z0` to `z1`.
fn prism(n: usize, r: f64, [x, y]: [f64; 2], (z0, z1): (f64, f64)) -> Mesh {
    let angle = |k: usize| 2.0 * std::f64::consts::PI * k as f64 / n as f64;
    let mut p: Vec<P> =
        (0..n).map(|k| [x + r * angle(k).cos(), y + r * angle(k).sin(), z0]).collect();
    p.extend((0..n).map(|k| [x + r * angle(k).cos(), y + r * angle(k).sin(), z1]));
    let n32 = n as u32;
    let mut faces: Vec<Vec<u32>> =
        (0..n32).map(|k| vec![k, (k + 1) % n32, (k + 1) % n32 + n32, k + n32]).collect();
    faces.push((0..n32).rev().collect());
    faces.push((n32..2 * n32).collect());
    polygons(&p, &faces)
}

#[test]
fn a_prism_of_many_sides_through_a_face_is_resolved_on_finer_columns() {
    // The prism's 96 walls cut the box's top face along a 96-gon inside one column of
    // the boundary's grid: a sub-piece of more sides than resolution holds, so the
    // column is resolved again on finer ones.
    let (n, r) = (96, 0.04);
    let bodies = [cuboid([0.0; 3], [4.0, 4.0, 2.0]), prism(n, r, [2.03, 1.97], (1.0, 3.0))];
    let boundary = union_boundary(&bodies).unwrap();
    let turn = 2.0 * std::f64::consts::PI / n as f64;
    let (plan, perimeter) =
        (0.5 * n as f64 * r * r * turn.sin(), 2.0 * n as f64 * r * (0.5 * turn).sin());
    // The box and the prism's part above it; the box's surface less the prism's plan on
    // its top, the prism's walls above the box and its top.
    let mp = mass_properties(&boundary);
    assert!((mp.signed_volume - (32.0 + plan)).abs() < 1e-12, "{}", mp.signed_volume);
    assert!((mp.area - (64.0 + perimeter)).abs() < 1e-12, "{}", mp.area);
    let grid = Grid::from_bounds([-0.1, -0.2, -0.15], [4.2, 4.1, 3.3], [7, 9, 8]).unwrap();
    let c = cut_cells(&boundary, &grid).unwrap();
    assert!((c.volume.iter().sum::<f64>() - (32.0 + plan)).abs() < 1e-12);
    assert!((c.boundary_area.iter().sum::<f64>() - (64.0 + perimeter)).abs() < 1e-12);
    let face = grid.cell[0] * grid.cell[1];
    for at in cells(&grid) {
        let d = divergence(&c, at);
        assert!(d.iter().all(|x| x.abs() < 1e-12 * face), "{at:?}: {d:?}");
    }
}
