//! Convex hulls compared with volumes known in closed form.

mod common;

use common::XorShift;
use meshvol::hull::{convex_hull, Degeneracy, HullError};
use meshvol::shapes::{uv_sphere, uv_sphere_volume};
use meshvol::Point;

#[test]
fn hull_of_a_convex_polyhedrons_vertices_is_the_polyhedron() {
    // The UV sphere is convex; with points inside it added, its hull is itself.
    let (radius, m, n) = (2.0, 32, 16);
    let sphere = uv_sphere(radius, m, n);
    let mut rng = XorShift::new(0x9e3779b97f4a7c15);
    let mut points = sphere.positions().to_vec();
    points.extend((0..1000).map(|_| [0.0; 3].map(|_: f64| (rng.unit() - 0.5) * radius)));
    let hull = convex_hull(&points).unwrap();
    let expected = uv_sphere_volume(radius, m, n);
    assert!(
        (hull.volume() - expected).abs() <= 1e-14 * expected,
        "{} vs {expected}",
        hull.volume()
    );
    assert_eq!(hull.mesh.unwrap().vertex_count(), sphere.vertex_count());
    let c = hull.properties.centroid.unwrap();
    assert!(c.iter().all(|x| x.abs() < 1e-14));
}

#[test]
fn lattice_hulls_keep_full_precision_far_from_the_origin() {
    // A 10 × 10 × 10 lattice of unit spacing: many points on each face and edge of the
    // hull, which is the 9 × 9 × 9 cube. Offsets are exact, so the answer is exact.
    for offset in [0.0, 1.0e5, 1.0e7] {
        let points: Vec<Point> = (0..1000)
            .map(|i| {
                [
                    offset + (i % 10) as f64,
                    offset + (i / 10 % 10) as f64,
                    offset + (i / 100) as f64 * 0.5,
                ]
            })
            .collect();
        let hull = convex_hull(&points).unwrap();
        assert_eq!(hull.volume(), 9.0 * 9.0 * 4.5, "offset {offset}");
        assert_eq!(hull.properties.area, 2.0 * (81.0 + 2.0 * 9.0 * 4.5), "offset {offset}");
        assert_eq!(hull.properties.centroid, Some([offset + 4.5, offset + 4.5, offset + 2.25]));
        assert!(hull.properties.signed_volume > 0.0);
    }
    // 40³ lattice points: many inserted early end inside a face or on an edge, so the
    // corners are hulled again.
    let points: Vec<Point> = (0..64_000)
        .map(|i| [1e7 + (i % 40) as f64, (i / 40 % 40) as f64, (i / 1600) as f64])
        .collect();
    assert_eq!(convex_hull(&points).unwrap().volume(), 39.0 * 39.0 * 39.0);
}

#[test]
fn random_clouds_far_away_match_the_same_cloud_at_the_origin() {
    // Coordinates on a 2⁻²⁰ grid: the cloud at 1e7 is the exact translate of the cloud
    // at 0, so the volumes must agree to rounding.
    let mut rng = XorShift::new(0x853c49e6748fea9b);
    let grid = |x: f64| (x * 1048576.0).round() / 1048576.0;
    let cloud: Vec<Point> =
        (0..50_000).map(|_| [0.0; 3].map(|_: f64| grid(rng.unit() * 10.0))).collect();
    let near = convex_hull(&cloud).unwrap();
    for offset in [1.0e5, 1.0e7] {
        let far: Vec<Point> = cloud.iter().map(|p| p.map(|x| x + offset)).collect();
        let hull = convex_hull(&far).unwrap();
        let relative = (hull.volume() - near.volume()).abs() / near.volume();
        assert!(relative < 1e-14, "offset {offset}: relative difference {relative:e}");
        assert!(near.volume() < 1000.0 && near.volume() > 900.0);
    }
}

#[test]
fn degenerate_sets_have_volume_zero_and_say_why() {
    let cases: [(Vec<Point>, Degeneracy); 5] = [
        (vec![], Degeneracy::NoPoints),
        (vec![[1.0, 2.0, 3.0]; 5], Degeneracy::AllCoincide),
        (
            (0..100).map(|i| [i as f64, 2.0 * i as f64, 1e6 - 3.0 * i as f64]).collect(),
            Degeneracy::Collinear,
        ),
        (vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], Degeneracy::Coplanar),
        // Many points on the tilted plane x + y + z = 30, exactly.
        (
            (0..400)
                .map(|i| [(i % 20) as f64, (i / 20) as f64, 30.0 - (i % 20 + i / 20) as f64])
                .collect(),
            Degeneracy::Coplanar,
        ),
    ];
    for (points, why) in cases {
        let hull = convex_hull(&points).unwrap();
        assert_eq!((hull.volume(), hull.degeneracy, hull.mesh.is_none()), (0.0, Some(why), true));
        assert_eq!(hull.properties.area, 0.0);
    }
    assert!(matches!(
        convex_hull(&[[0.0; 3], [f64::NAN, 0.0, 0.0]]),
        Err(HullError::NonFinite { index: 1, .. })
    ));
    // Four points, one of them a hair off the plane: the predicates are exact, so this
    // is a valid, tiny tetrahedron.
    let sliver = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.3, 0.3, 1e-13]];
    let h = convex_hull(&sliver).unwrap();
    assert!((h.volume() - 1e-13 / 6.0).abs() < 1e-20, "{}", h.volume());
}
