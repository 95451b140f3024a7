//! Faces of many corners and vertices of high degree: a cone over a regular k-gon base
//! (one face of k corners; k side triangles meeting at the apex). The check must find
//! what it finds on small faces — closed, one shell, the exact pyramid volume, and a
//! crossing where a triangle pierces the base — at any k.

mod common;
use common::polygons;
use meshvol::topology::{check, CheckOptions};

/// The cone: base corners on the unit circle in z = 0 (wound clockwise seen from above,
/// so the base faces down and out), apex at (0, 0, 1).
fn cone(k: usize) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let mut p: Vec<[f64; 3]> = (0..k)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / k as f64;
            [a.cos(), a.sin(), 0.0]
        })
        .collect();
    p.push([0.0, 0.0, 1.0]);
    let mut faces: Vec<Vec<u32>> = vec![(0..k as u32).rev().collect()];
    faces.extend((0..k as u32).map(|i| vec![i, (i + 1) % k as u32, k as u32]));
    (p, faces)
}

/// The base polygon's area by the shoelace formula, summed in f64 (independent of the
/// kernel's fans), and the pyramid's volume area · h / 3.
fn pyramid_volume(p: &[[f64; 3]], k: usize) -> f64 {
    let area: f64 =
        (0..k).map(|i| 0.5 * (p[i][0] * p[(i + 1) % k][1] - p[(i + 1) % k][0] * p[i][1])).sum();
    area / 3.0
}

#[test]
fn a_cone_over_a_huge_polygon_checks_like_a_small_one() {
    for k in [5, 33, 1000, 30_000] {
        let (p, faces) = cone(k);
        let c = check(&polygons(&p, &faces), &CheckOptions::default()).unwrap();
        assert!(c.bounds_a_volume(), "k = {k}: {}", c.verdict());
        assert_eq!((c.shells.len(), c.self_intersections), (1, Some(0)), "k = {k}");
        let exact = pyramid_volume(&p, k);
        // Both sums round k times: within 2k units of roundoff of each other.
        let tolerance = 2.0 * k as f64 * f64::EPSILON * exact;
        assert!((c.volume - exact).abs() <= tolerance, "k = {k}: {} vs {exact}", c.volume);
    }
}

#[test]
fn a_triangle_piercing_a_huge_base_is_found() {
    for k in [5, 33, 1000, 30_000] {
        let (mut p, mut faces) = cone(k);
        // A separate triangle through the base (inside the pentagon's inradius 0.81),
        // standing across z = 0 and ending inside the cone (whose side is at z = 0.4
        // over r = 0.6).
        let base = p.len() as u32;
        p.extend([[0.6, -0.05, -0.5], [0.6, 0.05, -0.5], [0.6, 0.0, 0.2]]);
        faces.push(vec![base, base + 1, base + 2]);
        let c = check(&polygons(&p, &faces), &CheckOptions::default()).unwrap();
        assert!(!c.bounds_a_volume(), "k = {k}");
        let crossing_base = c.intersection_examples.iter().chain(&c.overlapping_shells);
        assert!(
            c.intersection_examples.contains(&[0, k + 1]) || !c.overlapping_shells.is_empty(),
            "k = {k}: {:?}",
            crossing_base.collect::<Vec<_>>()
        );
        assert!(
            c.intersection_examples.contains(&[0, k + 1]),
            "k = {k}: {:?}",
            c.intersection_examples
        );
    }
}
