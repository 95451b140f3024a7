//! The union of bodies (`grid::union`, `union_cell_volumes`) against closed forms:
//! overlapping boxes (whole and per cell, by inclusion–exclusion), boxes sharing faces,
//! identical bodies, a sphere with boxes, and overlapping spheres between the bounds.

mod common;

use common::{assert_close, grid_around, mapped, sum};

use meshvol::grid::{union, union_cell_volumes, Grid, UnionVolume};
use meshvol::shapes::{cuboid, torus, torus_volume, uv_sphere, uv_sphere_volume};

type P3 = [f64; 3];

fn box_volume(lo: P3, hi: P3) -> f64 {
    (0..3).map(|a| (hi[a] - lo[a]).max(0.0)).product()
}

fn intersection(a: (P3, P3), b: (P3, P3)) -> (P3, P3) {
    ([0, 1, 2].map(|k| a.0[k].max(b.0[k])), [0, 1, 2].map(|k| a.1[k].min(b.1[k])))
}

fn assert_contains(what: &str, u: &UnionVolume, exact: f64, width: f64) {
    assert!(
        u.lower <= exact && exact <= u.upper,
        "{what}: {exact} not in [{}, {}]",
        u.lower,
        u.upper
    );
    assert!(u.upper - u.lower <= width, "{what}: [{}, {}] is wider than {width}", u.lower, u.upper);
}

#[test]
fn union_of_overlapping_boxes() {
    let a = ([0.0, 0.0, 0.0], [2.0, 2.0, 2.0]);
    let b = ([1.3, 0.7, -0.4], [3.1, 2.9, 1.5]);
    let overlap = intersection(a, b);
    let exact = box_volume(a.0, a.1) + box_volume(b.0, b.1) - box_volume(overlap.0, overlap.1);
    let u = union(&[cuboid(a.0, a.1), cuboid(b.0, b.1)], 1e-6).unwrap();
    assert_contains("boxes", &u, exact, 1e-6 * exact);
    assert_eq!((u.bodies, u.sum_of_volumes), (2, 8.0 + 1.8 * 2.2 * 1.9));
    // A tight tolerance: still contained, and narrower.
    let tight = union(&[cuboid(a.0, a.1), cuboid(b.0, b.1)], 1e-12).unwrap();
    assert_contains("boxes, 1e-12", &tight, exact, 1e-9 * exact);
    // Per cell, on a grid that cuts both boxes: (A ∪ B) ∩ C = A∩C + B∩C − A∩B∩C.
    let grid = Grid::new([-0.5, -0.25, -0.5], [0.45, 0.4, 0.35], [8, 9, 8]).unwrap();
    let (cells, unresolved) =
        union_cell_volumes(&[cuboid(a.0, a.1), cuboid(b.0, b.1)], &grid).unwrap();
    assert_eq!(unresolved, 0);
    for i in 0..8 {
        for j in 0..9 {
            for k in 0..8 {
                let lo = [0, 1, 2].map(|d| grid.origin[d] + [i, j, k][d] as f64 * grid.cell[d]);
                let hi = [0, 1, 2].map(|d| lo[d] + grid.cell[d]);
                let c = (lo, hi);
                let (ac, bc) = (intersection(a, c), intersection(b, c));
                let abc = intersection(overlap, c);
                let expected =
                    box_volume(ac.0, ac.1) + box_volume(bc.0, bc.1) - box_volume(abc.0, abc.1);
                assert_close(
                    &format!("cell {i},{j},{k}"),
                    cells[grid.index([i, j, k])],
                    expected,
                    1e-14,
                );
            }
        }
    }
}

#[test]
fn union_of_boxes_sharing_faces() {
    // Side by side (a vertical shared face), stacked (a horizontal one), and a smaller
    // box against a larger one's face.
    let cases = [
        (([0.0; 3], [1.0; 3]), ([1.0, 0.0, 0.0], [2.5, 1.0, 1.0])),
        (([0.0; 3], [1.0; 3]), ([0.0, 0.0, 1.0], [1.0, 1.0, 1.75])),
        (([0.0; 3], [1.0; 3]), ([0.25, 0.3, 1.0], [0.5, 0.9, 1.3])),
        (([0.0; 3], [1.0; 3]), ([1.0, 0.2, 0.1], [1.4, 0.7, 0.6])),
    ];
    for (a, b) in cases {
        let exact = box_volume(a.0, a.1) + box_volume(b.0, b.1);
        let u = union(&[cuboid(a.0, a.1), cuboid(b.0, b.1)], 1e-6).unwrap();
        assert_contains(&format!("{a:?} {b:?}"), &u, exact, 1e-6 * exact);
    }
}

#[test]
fn union_of_identical_bodies_is_one_body() {
    let t = torus(2.0, 0.7, 32, 12);
    let volume = torus_volume(2.0, 0.7, 32, 12);
    let u = union(&[t.clone(), t.clone(), t.triangulated()], 1e-6).unwrap();
    assert_contains("three tori", &u, volume, 1e-6 * volume);
    assert!(u.cells_resolved_exactly > 0);
    // A copy wound inward counts the same.
    let u = union(&[t.clone(), t.flipped()], 1e-6).unwrap();
    assert_contains("torus and its flip", &u, volume, 1e-6 * volume);
    assert_eq!(u.flipped, vec![1]);
}

#[test]
fn union_of_a_sphere_and_a_box() {
    // The box holds the upper half of the polyhedral sphere (whose equator lies in z = 0).
    let sphere = uv_sphere(1.0, 32, 16);
    let volume = uv_sphere_volume(1.0, 32, 16);
    let b = cuboid([-2.0, -2.0, 0.0], [2.0, 2.0, 2.0]);
    let exact = 32.0 + volume / 2.0;
    let u = union(&[sphere.clone(), b], 1e-6).unwrap();
    assert_contains("sphere and box", &u, exact, 1e-6 * exact);
    // A box inside the sphere: the sphere. Disjoint: the sum.
    let inner = cuboid([-0.3; 3], [0.4; 3]);
    let u = union(&[sphere.clone(), inner], 1e-6).unwrap();
    assert_contains("box inside", &u, volume, 1e-6 * volume);
    let away = cuboid([3.0; 3], [4.0; 3]);
    let u = union(&[sphere.clone(), away], 1e-6).unwrap();
    assert_contains("apart", &u, volume + 1.0, 1e-6 * volume);
    // One body: its volume.
    let u = union(&[sphere], 1e-6).unwrap();
    assert_contains("alone", &u, volume, 1e-9);
}

#[test]
fn union_of_overlapping_spheres_is_between_the_bounds_of_inclusion_exclusion() {
    // Two polyhedral spheres overlapping: the union lies between max and sum, and the
    // interval is narrow; a translated copy of the pair gives the same interval.
    let s = uv_sphere(1.0, 48, 24);
    let v = uv_sphere_volume(1.0, 48, 24);
    let t = mapped(&s, |p| [p[0] + 0.9, p[1] + 0.2, p[2] - 0.1]);
    let u = union(&[s.clone(), t.clone()], 1e-6).unwrap();
    assert!(u.lower > v && u.upper < 2.0 * v);
    assert!(u.upper - u.lower <= 1e-6 * u.lower, "[{}, {}]", u.lower, u.upper);
    // Cross-check: the union's per-cell volumes on a grid sum into the interval.
    let grid = grid_around(&s, [20, 20, 20], 0.8);
    let (cells, unresolved) = union_cell_volumes(&[s, t], &grid).unwrap();
    assert_eq!(unresolved, 0);
    let total = sum(&cells);
    assert!(
        u.lower - 1e-9 <= total && total <= u.upper + 1e-9,
        "{total} vs [{}, {}]",
        u.lower,
        u.upper
    );
}
