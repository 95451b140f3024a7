//! Grid kernels against independent values: closed forms, exact boxes, a separate
//! polyhedron clipper written here, and invariances (threads, winding, bounds).

mod common;

use common::{assert_close, grid_around, mapped, sum};

use meshvol::grid::{cell_volumes, occupancy, profile, Axis, Grid, GridError, Levels};
use meshvol::shapes::{cuboid, torus, torus_volume, uv_sphere, uv_sphere_volume};
use meshvol::{mass_properties, Faces, Mesh, Surface};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------
// An independent reference: the volume of mesh ∩ box by clipping the tetrahedra
// (reference point, fan triangle) against the box with a plain convex-polyhedron clipper.

type P3 = [f64; 3];

fn sub(a: P3, b: P3) -> P3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: P3, b: P3) -> P3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A convex polyhedron as outward-wound face loops.
struct Polyhedron {
    faces: Vec<Vec<P3>>,
}

impl Polyhedron {
    /// The tetrahedron (a, b, c, d), wound outward whatever the order of its corners.
    fn tetrahedron(a: P3, b: P3, c: P3, d: P3) -> Polyhedron {
        let (b, c) =
            if dot(sub(d, a), cross(sub(b, a), sub(c, a))) > 0.0 { (c, b) } else { (b, c) };
        // Now (a, b, c) is wound with d behind it.
        Polyhedron { faces: vec![vec![a, b, c], vec![a, d, b], vec![b, d, c], vec![c, d, a]] }
    }

    /// Keeps the part where `x[axis] ≤ value` (`keep_below`) or `≥ value`.
    fn clip(&self, axis: usize, value: f64, keep_below: bool) -> Polyhedron {
        let s = if keep_below { 1.0 } else { -1.0 };
        let dist = |p: &P3| s * (p[axis] - value);
        let mut faces = Vec::new();
        let mut cap: Vec<P3> = Vec::new();
        for face in &self.faces {
            let mut out = Vec::new();
            for k in 0..face.len() {
                let (p, q) = (face[k], face[(k + 1) % face.len()]);
                let (dp, dq) = (dist(&p), dist(&q));
                if dp <= 0.0 {
                    out.push(p);
                }
                if dp == 0.0 {
                    cap.push(p);
                }
                if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
                    let t = dp / (dp - dq);
                    let mut x = [0, 1, 2].map(|i| p[i] + t * (q[i] - p[i]));
                    x[axis] = value;
                    out.push(x);
                    cap.push(x);
                }
            }
            if out.len() >= 3 {
                faces.push(out);
            }
        }
        if cap.len() >= 3 {
            // Order the cap's points by angle about their mean, counter-clockwise seen
            // from the outside (+s along the axis).
            let n = cap.len() as f64;
            let c = [0, 1, 2].map(|i| cap.iter().map(|p| p[i]).sum::<f64>() / n);
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            cap.sort_by(|p, q| {
                let a = (s * (p[v] - c[v])).atan2(p[u] - c[u]);
                let b = (s * (q[v] - c[v])).atan2(q[u] - c[u]);
                a.partial_cmp(&b).unwrap()
            });
            cap.dedup_by(|p, q| p == q);
            if cap.len() >= 3 {
                faces.push(cap);
            }
        }
        Polyhedron { faces }
    }

    fn volume(&self) -> f64 {
        let Some(r) = self.faces.first().map(|f| f[0]) else { return 0.0 };
        self.faces
            .iter()
            .map(|f| {
                (1..f.len() - 1)
                    .map(|k| dot(sub(f[0], r), cross(sub(f[k], r), sub(f[k + 1], r))))
                    .sum::<f64>()
            })
            .sum::<f64>()
            / 6.0
    }
}

/// vol(mesh ∩ box) as Σ ± vol(tetrahedron ∩ box).
fn clipped_volume(mesh: &Mesh, lo: P3, hi: P3) -> f64 {
    let r = [lo[0] - 0.37, lo[1] - 0.21, lo[2] - 0.13];
    let mut total = 0.0;
    for f in 0..mesh.face_count() {
        mesh.fan(f, |a, b, c| {
            let six = dot(sub(a, r), cross(sub(b, r), sub(c, r)));
            if six == 0.0 {
                return;
            }
            let mut t = Polyhedron::tetrahedron(r, a, b, c);
            for axis in 0..3 {
                t = t.clip(axis, lo[axis], false).clip(axis, hi[axis], true);
            }
            total += six.signum() * t.volume();
        });
    }
    total
}

#[test]
fn reference_clipper_is_right_on_boxes() {
    let unit = cuboid([0.0; 3], [1.0; 3]);
    assert_close("inside", clipped_volume(&unit, [0.25; 3], [0.5; 3]), 0.015625, 1e-15);
    assert_close("half", clipped_volume(&unit, [0.5, -1.0, -1.0], [3.0; 3]), 0.5, 1e-15);
    assert_close("outside", clipped_volume(&unit, [2.0; 3], [3.0; 3]), 0.0, 1e-15);
}

#[test]
fn cells_agree_with_clipped_tetrahedra() {
    // A convex and a non-convex solid, on grids that cut them at odd places.
    let sphere = mapped(&uv_sphere(1.0, 16, 8), |p| [p[0] + 0.1, p[1] - 0.05, 1.3 * p[2]]);
    let ring = torus(1.0, 0.4, 16, 8);
    let mut checked = 0;
    for (mesh, counts) in [(sphere, [6, 7, 5]), (ring, [7, 7, 3])] {
        let grid = grid_around(&mesh, counts, 0.05);
        let cells = cell_volumes(&mesh, &grid).unwrap();
        for i in 0..counts[0] {
            for j in 0..counts[1] {
                for k in 0..counts[2] {
                    let lo = [0, 1, 2].map(|a| grid.origin[a] + [i, j, k][a] as f64 * grid.cell[a]);
                    let hi = [0, 1, 2].map(|a| lo[a] + grid.cell[a]);
                    let reference = clipped_volume(&mesh, lo, hi);
                    let v = cells[grid.index([i, j, k])];
                    assert_close(&format!("cell {i},{j},{k}"), v, reference, 1e-12);
                    checked += 1;
                }
            }
        }
    }
    assert!(checked >= 300);
}

// ---------------------------------------------------------------------------------------

#[test]
fn cells_sum_to_the_volume_and_stay_within_the_cell() {
    let solids = [
        (uv_sphere(1.0, 64, 32), uv_sphere_volume(1.0, 64, 32)),
        (torus(3.0, 1.0, 48, 24), torus_volume(3.0, 1.0, 48, 24)),
    ];
    for (mesh, volume) in solids {
        for counts in [[17, 23, 9], [32, 32, 32], [1, 1, 40], [40, 1, 1]] {
            let grid = grid_around(&mesh, counts, 0.07);
            let cells = cell_volumes(&mesh, &grid).unwrap();
            let cv = grid.cell_volume();
            assert_close("sum", sum(&cells), volume, 1e-13 * volume);
            for &v in &cells {
                assert!(v >= -1e-13 * cv && v <= cv * (1.0 + 1e-13), "{v} outside [0, {cv}]");
            }
        }
    }
}

/// For a convex outward mesh: whether p is inside (or on) every face plane.
fn inside_convex(mesh: &Mesh, p: P3, margin: f64) -> bool {
    (0..mesh.face_count()).all(|f| {
        let mut inside = true;
        mesh.fan(f, |a, b, c| {
            let n = cross(sub(b, a), sub(c, a));
            inside &= dot(n, sub(p, a)) <= -margin * dot(n, n).sqrt();
        });
        inside
    })
}

#[test]
fn cells_inside_are_full_and_cells_outside_are_empty() {
    let mesh = uv_sphere(1.0, 32, 16);
    let grid = grid_around(&mesh, [16, 16, 16], 0.0625);
    let cells = cell_volumes(&mesh, &grid).unwrap();
    let cv = grid.cell_volume();
    let (mut full, mut empty) = (0, 0);
    for i in 0..16 {
        for j in 0..16 {
            for k in 0..16 {
                let corner = |c: usize| {
                    [0, 1, 2].map(|a| {
                        let n = [i, j, k][a] + (c >> a & 1);
                        grid.origin[a] + n as f64 * grid.cell[a]
                    })
                };
                let v = cells[grid.index([i, j, k])];
                if (0..8).all(|c| inside_convex(&mesh, corner(c), 1e-9)) {
                    assert_close("full cell", v, cv, 1e-14 * cv);
                    full += 1;
                }
                // All eight corners beyond one face's plane: the cell misses the solid.
                let beyond_one_face = (0..mesh.face_count()).any(|f| {
                    let mut out = true;
                    mesh.fan(f, |a, b, c| {
                        let n = cross(sub(b, a), sub(c, a));
                        out &= (0..8).all(|k| dot(n, sub(corner(k), a)) > 0.0);
                    });
                    out
                });
                if beyond_one_face {
                    assert_close("empty cell", v, 0.0, 1e-14 * cv);
                    empty += 1;
                }
            }
        }
    }
    assert!(full > 100 && empty > 1000, "{full} full, {empty} empty");
}

#[test]
fn a_box_on_grid_planes_is_exact() {
    // Faces on the planes x = 0.25, 1.5, y = 0.5, 1.75, z = 0, 1 of a grid of quarter
    // cells: every cell is exactly full or empty.
    let grid = Grid::new([0.0; 3], [0.25; 3], [8, 8, 8]).unwrap();
    let cells = cell_volumes(&cuboid([0.25, 0.5, 0.0], [1.5, 1.75, 1.0]), &grid).unwrap();
    for i in 0..8 {
        for j in 0..8 {
            for k in 0..8 {
                let inside = (1..6).contains(&i) && (2..7).contains(&j) && k < 4;
                let expected = if inside { 0.015625 } else { 0.0 };
                assert_eq!(cells[grid.index([i, j, k])], expected, "cell {i},{j},{k}");
            }
        }
    }
    // A box that cuts cells in halves and quarters, all exact in binary.
    let cells = cell_volumes(&cuboid([0.125, 0.0, 0.0], [0.5, 0.125, 0.25]), &grid).unwrap();
    assert_eq!(cells[grid.index([0, 0, 0])], 0.125 * 0.125 * 0.25);
    assert_eq!(cells[grid.index([1, 0, 0])], 0.25 * 0.125 * 0.25);
    assert_eq!(sum(&cells), 0.375 * 0.125 * 0.25);
}

/// Length of [a0, a1] ∩ [b0, b1].
fn overlap(a0: f64, a1: f64, b0: f64, b1: f64) -> f64 {
    (a1.min(b1) - a0.max(b0)).max(0.0)
}

#[test]
fn only_the_part_inside_the_bounds_counts() {
    // A box sticking out of the grid on every side: each cell holds box ∩ cell.
    let (lo, hi) = ([-0.3, 0.2, -1.0], [0.7, 2.5, 0.45]);
    let mesh = cuboid(lo, hi);
    let grid = Grid::new([0.0, 0.0, 0.0], [0.1, 0.3, 0.2], [5, 4, 3]).unwrap();
    let cells = cell_volumes(&mesh, &grid).unwrap();
    let mut total = 0.0;
    for i in 0..5 {
        for j in 0..4 {
            for k in 0..3 {
                let c0 = [0, 1, 2].map(|a| grid.origin[a] + [i, j, k][a] as f64 * grid.cell[a]);
                let expected: f64 =
                    (0..3).map(|a| overlap(c0[a], c0[a] + grid.cell[a], lo[a], hi[a])).product();
                assert_close("cell", cells[grid.index([i, j, k])], expected, 1e-15);
                total += expected;
            }
        }
    }
    assert_close("total", sum(&cells), total, 1e-15);
    // Half of the polyhedral sphere lies above z = 0 and half beyond x = 0 (it is
    // symmetric when the rings and segments are even and segments divisible by 4).
    let sphere = uv_sphere(1.0, 32, 16);
    let volume = uv_sphere_volume(1.0, 32, 16);
    let upper = Grid::from_bounds([-2.0, -2.0, 0.0], [2.0, 2.0, 2.0], [8, 8, 5]).unwrap();
    assert_close("upper half", sum(&cell_volumes(&sphere, &upper).unwrap()), volume / 2.0, 1e-14);
    let right = Grid::from_bounds([0.0, -2.0, -2.0], [2.0, 2.0, 2.0], [3, 8, 8]).unwrap();
    assert_close("right half", sum(&cell_volumes(&sphere, &right).unwrap()), volume / 2.0, 1e-14);
    // Entirely outside: nothing.
    let away = Grid::from_bounds([5.0; 3], [6.0; 3], [3, 3, 3]).unwrap();
    assert!(cell_volumes(&sphere, &away).unwrap().iter().all(|&v| v == 0.0));
}

#[test]
fn same_bits_for_any_thread_count() {
    let mesh = torus(2.0, 0.7, 200, 100).triangulated();
    let grid = grid_around(&mesh, [37, 41, 13], 0.02);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| cell_volumes(&mesh, &grid).unwrap())
    };
    let one = run(1);
    for threads in [2, 3, 7] {
        let other = run(threads);
        assert!(one.iter().zip(&other).all(|(a, b)| a.to_bits() == b.to_bits()));
    }
}

#[test]
fn inward_wound_meshes_give_negative_cells() {
    let mesh = torus(2.0, 0.7, 40, 20);
    let grid = grid_around(&mesh, [9, 10, 4], 0.05);
    let outward = cell_volumes(&mesh, &grid).unwrap();
    let inward = cell_volumes(&mesh.flipped(), &grid).unwrap();
    let cv = grid.cell_volume();
    for (a, b) in outward.iter().zip(&inward) {
        assert_close("negated", *b, -a, 1e-14 * cv);
    }
    assert!(sum(&inward) < 0.0);
}

#[test]
fn polygon_and_triangle_faces_agree_and_occupancy_counts() {
    let mesh = uv_sphere(1.0, 24, 12);
    let grid = grid_around(&mesh, [10, 10, 10], 0.05);
    let polygons = cell_volumes(&mesh, &grid).unwrap();
    let triangles = cell_volumes(&mesh.triangulated(), &grid).unwrap();
    for (a, b) in polygons.iter().zip(&triangles) {
        assert_close("fan", *a, *b, 1e-15);
    }
    let o = occupancy(&polygons, grid.cell_volume());
    assert_eq!(o.empty + o.partial + o.full, 1000);
    assert!(o.full > 0 && o.partial > 0 && o.empty > 0);
    // A box on grid planes: 4 full cells of 8.
    let g = Grid::new([0.0; 3], [1.0; 3], [2, 2, 2]).unwrap();
    let box_cells = cell_volumes(&cuboid([0.0; 3], [1.0, 2.0, 2.0]), &g).unwrap();
    assert_eq!(
        occupancy(&box_cells, 1.0),
        meshvol::grid::Occupancy { empty: 4, partial: 0, full: 4 }
    );
}

#[test]
fn bad_grids_are_refused_before_allocating() {
    assert!(matches!(Grid::new([0.0; 3], [1.0; 3], [0, 4, 4]), Err(GridError::NoCells { .. })));
    assert!(matches!(
        Grid::new([0.0; 3], [1.0, -1.0, 1.0], [4, 4, 4]),
        Err(GridError::BadCellSize { .. })
    ));
    // Cells of 1e300 per side: each volume (1e900) is beyond f64; 1e100 per side is not.
    assert!(matches!(
        Grid::new([0.0; 3], [1e300; 3], [1, 1, 1]),
        Err(GridError::CellVolumeOverflow { .. })
    ));
    assert_eq!(Grid::new([0.0; 3], [1e100; 3], [1, 1, 1]).unwrap().cell_volume(), 1e300);
    // 10²¹ cells do not fit in memory addresses; 10¹⁸ do, but no machine has 6.9 EiB.
    match Grid::new([0.0; 3], [1.0; 3], [10_000_000; 3]) {
        Err(e @ GridError::TooManyCells { .. }) => assert!(e.to_string().contains("EiB"), "{e}"),
        other => panic!("{other:?}"),
    }
    // A pitch so fine that one axis alone has 5·10³⁰⁰ cells: named, not a saturated count.
    match Grid::with_pitch([0.0; 3], [5.0, 1.0, 1.0], [1e-300; 3]) {
        Err(e @ GridError::PitchTooFine { axis: 'x', .. }) => {
            assert!(e.to_string().contains("larger pitch"), "{e}")
        }
        other => panic!("{other:?}"),
    }
    let huge = Grid::new([0.0; 3], [1.0; 3], [1_000_000; 3]).unwrap();
    match cell_volumes(&cuboid([0.0; 3], [1.0; 3]), &huge) {
        Err(e @ GridError::OutOfMemory { .. }) => assert!(e.to_string().contains("6.9 EiB"), "{e}"),
        other => panic!("{:?}", other.map(|v| v.len())),
    }
    assert!(Grid::with_pitch([0.0; 3], [1.0; 3], [1e-300; 3]).is_err());
    assert!(Grid::from_bounds([0.0; 3], [1.0, f64::NAN, 1.0], [2, 2, 2]).is_err());
    // An empty surface: all zero.
    let empty = Mesh::new(vec![], Faces::Triangles(vec![])).unwrap();
    let g = Grid::new([0.0; 3], [1.0; 3], [2, 2, 2]).unwrap();
    assert_eq!(cell_volumes(&empty, &g).unwrap(), vec![0.0; 8]);
}

// ---------------------------------------------------------------------------------------
// Profiles.

/// Volume below level t and section area at t of the polyhedral UV sphere: its section
/// at height z is a regular m-gon of circumradius r(z), r linear along each meridian
/// segment, so the area is (m/2)·sin(2π/m)·r² and the volume ∫ of that.
fn sphere_profile(radius: f64, m: u32, n: u32, t: f64) -> (f64, f64) {
    let k = (m as f64 / 2.0) * (2.0 * PI / m as f64).sin();
    let meridian: Vec<(f64, f64)> = (0..=n)
        .rev()
        .map(|i| {
            let phi = PI * i as f64 / n as f64;
            (radius * phi.sin(), radius * phi.cos())
        })
        .collect(); // from the south pole up
    let (mut volume, mut area) = (0.0, 0.0);
    for w in meridian.windows(2) {
        let ((r0, z0), (r1, z1)) = (w[0], w[1]);
        if t <= z0 {
            break;
        }
        let s = t.min(z1);
        let rs = r0 + (r1 - r0) * (s - z0) / (z1 - z0);
        volume += k * (s - z0) * (r0 * r0 + r0 * rs + rs * rs) / 3.0;
        if t < z1 {
            area = k * rs * rs;
        }
    }
    (volume, area)
}

#[test]
fn sphere_profile_matches_the_closed_form() {
    let (m, n) = (48, 24);
    let mesh = uv_sphere(1.0, m, n);
    let total = uv_sphere_volume(1.0, m, n);
    for axis in [Axis::Z, Axis::X, Axis::Y] {
        // Rotate the sphere so that its pole axis is `axis` (cyclic permutations).
        let rotated = match axis {
            Axis::Z => mesh.clone(),
            Axis::X => mapped(&mesh, |p| [p[2], p[0], p[1]]),
            Axis::Y => mapped(&mesh, |p| [p[1], p[2], p[0]]),
        };
        let p = profile(&rotated, axis, Levels::Count(37)).unwrap();
        assert_eq!(p.levels.len(), 38);
        assert_eq!((p.levels[0], p.levels[37]), (-1.0, 1.0));
        for (k, &t) in p.levels.iter().enumerate() {
            let (volume, area) = sphere_profile(1.0, m, n, t);
            assert_close("volume below", p.volume_below[k], volume, 1e-14);
            if k < 37 {
                assert_close("section", p.section_area[k], area, 1e-13);
            }
        }
        assert_close("total", p.volume_below[37], total, 1e-14);
        assert_close("slabs", sum(&p.slab_volume), total, 1e-14);
        for k in 0..37 {
            let d = p.volume_below[k + 1] - p.volume_below[k];
            assert_close("slab", p.slab_volume[k], d, 1e-15);
        }
    }
}

/// A prism: the triangle (0,0), (2,0), (0,1) in the xz plane, extruded along y by 3.
fn prism() -> Mesh {
    let p = vec![
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 3.0, 0.0],
        [2.0, 3.0, 0.0],
        [0.0, 3.0, 1.0],
    ];
    let faces: [&[u32]; 5] = [&[0, 1, 2], &[3, 5, 4], &[0, 3, 4, 1], &[1, 4, 5, 2], &[0, 2, 5, 3]];
    Mesh::from_polygons(p, faces).unwrap()
}

#[test]
fn prism_profiles_along_three_axes() {
    let mesh = prism();
    assert_close("volume", mass_properties(&mesh).signed_volume, 3.0, 1e-15);
    // Along z: section 3·2(1 − z), volume below 3·(2z − z²).
    let p = profile(&mesh, Axis::Z, Levels::Step(0.125)).unwrap();
    assert_eq!(p.levels.len(), 9);
    for (k, &z) in p.levels.iter().enumerate() {
        assert_close("below z", p.volume_below[k], 3.0 * (2.0 * z - z * z), 1e-14);
        assert_close("section z", p.section_area[k], 6.0 * (1.0 - z), 1e-14);
    }
    // Along y: a constant section of area 1.
    let p = profile(&mesh, Axis::Y, Levels::Count(6)).unwrap();
    for (k, &y) in p.levels.iter().enumerate() {
        assert_close("below y", p.volume_below[k], y, 1e-14);
        assert_close("section y", p.section_area[k], 1.0, 1e-14);
    }
    // Along x with a step that overshoots the maximum (2): levels 0, 0.75, 1.5, 2.25.
    let p = profile(&mesh, Axis::X, Levels::Step(0.75)).unwrap();
    assert_eq!(p.levels, vec![0.0, 0.75, 1.5, 2.25]);
    for (k, &x) in p.levels.iter().enumerate() {
        let x = x.min(2.0);
        let h = 1.0 - x / 2.0;
        assert_close("below x", p.volume_below[k], 3.0 * (1.0 - h * h), 1e-14);
        assert_close("section x", p.section_area[k], 3.0 * h, 1e-14);
    }
}

#[test]
fn a_step_reports_the_area_above_it() {
    // Two stacked boxes: 2×2 from z = 0 to 1, 1×1 from 1 to 2, as one closed surface
    // (the bottom box's top is a ring around the upper box's footprint).
    let lower = cuboid([0.0; 3], [2.0, 2.0, 1.0]);
    let upper = cuboid([0.5, 0.5, 1.0], [1.5, 1.5, 2.0]);
    // Union as two touching shells: the shared square at z = 1 appears twice with
    // opposite windings, which cancel in every integral.
    let mut positions = lower.positions().to_vec();
    positions.extend_from_slice(upper.positions());
    let mut faces: Vec<Vec<u32>> = (0..6).map(|f| lower.face(f).to_vec()).collect();
    faces.extend((0..6).map(|f| upper.face(f).iter().map(|i| i + 8).collect::<Vec<u32>>()));
    let mesh = Mesh::from_polygons(positions, faces.iter().map(|f| &f[..])).unwrap();
    let p = profile(&mesh, Axis::Z, Levels::Count(4)).unwrap();
    assert_eq!(p.levels, vec![0.0, 0.5, 1.0, 1.5, 2.0]);
    assert_eq!(p.volume_below, vec![0.0, 2.0, 4.0, 4.5, 5.0]);
    assert_eq!(p.section_area, vec![4.0, 4.0, 1.0, 1.0, 1.0]);
}

#[test]
fn profile_errors() {
    let flat =
        Mesh::from_triangles(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![[0, 1, 2]])
            .unwrap();
    assert!(profile(&flat, Axis::Z, Levels::Count(3)).unwrap_err().to_string().contains("flat"));
    let cube = cuboid([0.0; 3], [1.0; 3]);
    assert!(profile(&cube, Axis::Z, Levels::Count(0)).is_err());
    assert!(profile(&cube, Axis::Z, Levels::Step(-1.0)).is_err());
    assert!(profile(&cube, Axis::Z, Levels::Step(1e-300)).is_err());
    let empty = Mesh::new(vec![], Faces::Triangles(vec![])).unwrap();
    assert!(profile(&empty, Axis::Z, Levels::Count(3)).is_err());
}
