//! The union's interval against values found without it: one sphere at two resolutions
//! (the coarse one's vertices are the fine one's, so it lies inside: the union is the
//! fine polyhedron, whose volume has a closed form), two overlapping spheres (the union
//! of two balls by spherical caps, between the inscribed and the circumscribed radius),
//! and two boxes (rationals), at tolerances loose enough that refinement alone ends the
//! work as well as tight ones that need the exact resolution.

mod common;

use common::{mapped, moved};
use meshvol::grid::{
    union, union_cell_volumes, union_cell_volumes_with, union_with, Grid, UnionVolume,
};
use meshvol::progress::Progress;
use meshvol::shapes::{cuboid, uv_sphere, uv_sphere_volume};
use meshvol::{Mesh, Surface};
use std::f64::consts::PI;
use std::sync::Mutex;

/// `[lower, upper]` holds `[low, high]`'s values: the exact value lies in `[low, high]`,
/// so the union's interval must meet it, and hold it when it is one point.
fn holds(what: &str, u: &UnionVolume, low: f64, high: f64) {
    assert!(u.lower <= u.upper, "{what}: inverted {u:?}");
    assert!(u.lower <= high && low <= u.upper, "{what}: [{low}, {high}] outside {u:?}");
    assert!(u.bodies_not_solid.is_empty() && u.columns_unresolved == 0, "{what}: {u:?}");
}

fn narrow(what: &str, u: &UnionVolume, tolerance: f64) {
    let width = u.upper - u.lower;
    assert!(width <= tolerance * u.lower, "{what}: width {width:e} at {tolerance:e}: {u:?}");
}

/// The volume of the union of two balls of radii `r1`, `r2` whose centres are `d` apart
/// (the lens by two spherical caps).
fn balls_union(r1: f64, r2: f64, d: f64) -> f64 {
    let ball = |r: f64| 4.0 / 3.0 * PI * r.powi(3);
    let lens = if d >= r1 + r2 {
        0.0
    } else if d <= (r1 - r2).abs() {
        ball(r1.min(r2))
    } else {
        PI * (r1 + r2 - d).powi(2) * (d * d + 2.0 * d * (r1 + r2) - 3.0 * (r1 - r2).powi(2))
            / (12.0 * d)
    };
    ball(r1) + ball(r2) - lens
}

/// The least distance from `centre` to the planes of `mesh`'s faces: a convex
/// polyhedron with its vertices on a sphere holds the ball of that radius.
fn inscribed(mesh: &Mesh, centre: [f64; 3]) -> f64 {
    let mut r = f64::INFINITY;
    for f in 0..mesh.face_count() {
        mesh.fan(f, |a, b, c| {
            let (u, v) = ([0, 1, 2].map(|k| b[k] - a[k]), [0, 1, 2].map(|k| c[k] - a[k]));
            let n =
                [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
            let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let d = (0..3).map(|k| n[k] * (a[k] - centre[k])).sum::<f64>().abs() / length;
            r = r.min(d);
        });
    }
    r
}

#[test]
fn one_sphere_at_two_resolutions_is_the_finer() {
    // Rings at π·k/n and meridians at 2π·j/m: doubling both gives the same doubles for
    // the coarse sphere's vertices, so the coarse hull lies in the fine one.
    let d = [0.31, -0.17, 0.23];
    for (m, n) in [(24, 12), (40, 17)] {
        let coarse = moved(&uv_sphere(1.5, m, n), d);
        let fine = moved(&uv_sphere(1.5, 2 * m, 2 * n), d);
        let exact = uv_sphere_volume(1.5, 2 * m, 2 * n);
        for tolerance in [1e-2, 1e-6, 1e-9] {
            for bodies in [[&coarse, &fine], [&fine, &coarse]] {
                let u = union(&bodies, tolerance).unwrap();
                let what = format!("{m}×{n} in {}×{} at {tolerance:e}", 2 * m, 2 * n);
                holds(&what, &u, exact, exact);
                narrow(&what, &u, tolerance);
            }
        }
    }
}

#[test]
fn two_overlapping_spheres_against_the_lens() {
    for (r1, r2, d) in [(1.0, 1.0, 1.2), (1.0, 0.7, 0.9), (1.2, 0.5, 1.0)] {
        let (a_centre, b_centre) = ([0.05, 0.11, -0.07], [0.05 + d, 0.11, -0.07]);
        let a = moved(&uv_sphere(r1, 96, 48), a_centre);
        let b = moved(&uv_sphere(r2, 80, 40), b_centre);
        let (i1, i2) = (inscribed(&a, a_centre), inscribed(&b, b_centre));
        // The polyhedra lie between their inscribed and circumscribed balls (up to the
        // rounding of their vertices, far below the gap between the two).
        let (low, high) = (balls_union(i1, i2, d), balls_union(r1, r2, d));
        let mut by_refinement = false;
        for tolerance in [3e-2, 1e-4, 3e-5, 1e-5, 1e-6] {
            let u = union(&[&a, &b], tolerance).unwrap();
            let what = format!("r {r1}, {r2} at {d}, {tolerance:e}");
            holds(&what, &u, low, high);
            narrow(&what, &u, tolerance);
            by_refinement |= u.cells_refined > 0 && u.cells_resolved_exactly == 0;
        }
        // Some tolerance is met by refinement alone: its bounds are what is checked.
        assert!(by_refinement, "r {r1}, {r2} at {d}: every tolerance resolved exactly");
    }
}

/// A general rotation: unit quaternion (w, x, y, z) normalised.
fn rotate(q: [f64; 4]) -> impl Fn([f64; 3]) -> [f64; 3] {
    let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|c| c / n);
    let r = [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
        [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
    ];
    move |p| [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2])
}

#[test]
fn two_boxes_at_loose_and_tight_tolerances() {
    // Dyadic corners: the overlap 1.375 × 1.625 × 0.875 and the union are exact.
    let a = cuboid([0.0; 3], [2.0; 3]);
    let b = cuboid([0.625, 0.375, 1.125], [2.625, 2.375, 3.125]);
    let exact = 16.0 - 1.375 * 1.625 * 0.875;
    let turn = rotate([0.9, 0.3, -0.2, 0.25]);
    let turned = [mapped(&a, &turn), mapped(&b, &turn)];
    for tolerance in [5e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-9] {
        let u = union(&[a.clone(), b.clone()], tolerance).unwrap();
        holds(&format!("boxes at {tolerance:e}"), &u, exact, exact);
        narrow(&format!("boxes at {tolerance:e}"), &u, tolerance);
        // Turned, the corners are rounded: the union moves by some 1e-15.
        let u = union(&turned, tolerance).unwrap();
        let what = format!("turned boxes at {tolerance:e}");
        holds(&what, &u, exact * (1.0 - 1e-13), exact * (1.0 + 1e-13));
        narrow(&what, &u, tolerance);
    }
}

/// Records a kernel's progress: `(stage, 0, 0)` as a stage starts, `("", done, total)`
/// for an advance.
#[derive(Default)]
struct Record(Mutex<Vec<(&'static str, u64, u64)>>);

impl Progress for Record {
    fn stage(&self, name: &'static str) {
        self.0.lock().unwrap().push((name, 0, 0));
    }
    fn advance(&self, done: u64, total: u64) {
        self.0.lock().unwrap().push(("", done, total));
    }
}

#[test]
fn refinement_is_the_same_bits_on_one_thread_and_reports_its_stages() {
    let a = uv_sphere(1.0, 64, 32);
    let b = moved(&uv_sphere(0.8, 48, 24), [0.9, 0.2, 0.1]);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    for tolerance in [3e-2, 1e-4, 1e-6] {
        let record = Record::default();
        let u = union_with(&[&a, &b], tolerance, &record).unwrap();
        let one = pool.install(|| union(&[&a, &b], tolerance).unwrap());
        let bits = |u: &UnionVolume| (u.lower.to_bits(), u.upper.to_bits());
        assert_eq!(bits(&one), bits(&u));
        let calls = record.0.into_inner().unwrap();
        // Stages in order, each counting up to its total.
        let names = ["bounds", "refining", "resolving columns"];
        let stages: Vec<usize> = calls
            .iter()
            .filter(|c| !c.0.is_empty())
            .map(|c| names.iter().position(|n| *n == c.0).expect("a known stage"))
            .collect();
        assert_eq!(stages.first(), Some(&0), "{calls:?}");
        assert!(stages.windows(2).all(|w| w[0] <= w[1]), "{calls:?}");
        for run in calls.split(|c| !c.0.is_empty()).skip(1) {
            assert!(run.windows(2).all(|w| w[0].1 <= w[1].1 && w[0].2 == w[1].2), "{run:?}");
            assert!(run.last().is_some_and(|l| l.1 == l.2), "{run:?}");
        }
        let refined = stages.iter().filter(|&&s| s == 1).count();
        assert_eq!(refined > 0, u.cells_refined > 0, "{calls:?}");
        assert_eq!(stages.contains(&2), u.cells_resolved_exactly > 0, "{calls:?}");
    }
}

#[test]
fn union_cell_volumes_reports_bounds_then_every_column_and_keeps_its_bits() {
    // Two overlapping boxes: the union's cells sum to the exact union, 2 + 2 − 1/2.
    let (a, b) = (cuboid([0.0; 3], [1.0, 1.0, 2.0]), cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 2.0]));
    let grid = Grid::new([-0.25, -0.25, -0.25], [0.4, 0.3, 0.5], [5, 6, 6]).unwrap();
    let record = Record::default();
    let (cells, unresolved) = union_cell_volumes_with(&[&a, &b], &grid, &record).unwrap();
    assert_eq!((cells.clone(), unresolved), union_cell_volumes(&[&a, &b], &grid).unwrap());
    assert_eq!(unresolved, 0);
    let total: f64 = cells.iter().sum();
    assert!((total - 3.0).abs() < 1e-12, "{total}");
    let calls = record.0.into_inner().unwrap();
    let stages: Vec<&str> = calls.iter().map(|c| c.0).filter(|n| !n.is_empty()).collect();
    assert_eq!(stages, ["bounds", "resolving columns"], "{calls:?}");
    let columns = calls.split(|c| !c.0.is_empty()).next_back().unwrap();
    assert!(columns.windows(2).all(|w| w[0].1 <= w[1].1), "{columns:?}");
    assert_eq!(columns.last().map(|l| (l.1, l.2)), Some((30, 30)), "{columns:?}");
}
