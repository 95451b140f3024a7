//! Polygon areas and centroids compared with the geo crate's.

mod common;

use common::XorShift;
use geo::{Area, Centroid, LineString, MultiPolygon};
use meshvol::polygon::{area_properties, polygon_issues, Point2, Polygon};

/// A star-shaped ring around `centre` with radii in [r/2, r), wound as asked.
fn star(
    rng: &mut XorShift,
    n: usize,
    centre: Point2,
    r: f64,
    counter_clockwise: bool,
) -> Vec<Point2> {
    let mut ring: Vec<Point2> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let radius = r * (0.5 + 0.5 * rng.unit());
            [centre[0] + radius * a.cos(), centre[1] + radius * a.sin()]
        })
        .collect();
    if !counter_clockwise {
        ring.reverse();
    }
    ring
}

fn to_geo(p: &Polygon) -> geo::Polygon<f64> {
    let line =
        |ring: &[Point2]| LineString::from(ring.iter().map(|&[x, y]| (x, y)).collect::<Vec<_>>());
    geo::Polygon::new(line(&p.exterior), p.holes.iter().map(|h| line(h)).collect())
}

#[test]
fn polygons_with_holes_match_geo() {
    let mut rng = XorShift::new(0x2545f4914f6cdd1d);
    for trial in 0..100 {
        let centre = [rng.unit() * 1000.0 - 500.0, rng.unit() * 1000.0 - 500.0];
        let n = 3 + (rng.unit() * 200.0) as usize;
        let counter_clockwise = rng.unit() < 0.5;
        let exterior = star(&mut rng, n, centre, 100.0, counter_clockwise);
        // Holes inside the exterior's inner radius (50), wound either way.
        let holes: Vec<Vec<Point2>> = (0..trial % 4)
            .map(|k| {
                let angle = k as f64 * 2.0;
                let c = [centre[0] + 30.0 * angle.cos(), centre[1] + 30.0 * angle.sin()];
                let counter_clockwise = rng.unit() < 0.5;
                star(&mut rng, 3 + k * 5, c, 10.0, counter_clockwise)
            })
            .collect();
        let polygon = Polygon::new(exterior, holes);
        assert!(polygon_issues(&[&polygon]).is_empty(), "trial {trial}");
        let ours = area_properties(&[&polygon]);
        let theirs = to_geo(&polygon);
        let area = theirs.unsigned_area();
        assert!((ours.area - area).abs() <= 1e-12 * area, "trial {trial}: {} vs {area}", ours.area);
        let c = theirs.centroid().unwrap();
        let ours_c = ours.centroid.unwrap();
        assert!(
            (ours_c[0] - c.x()).abs() <= 1e-9 && (ours_c[1] - c.y()).abs() <= 1e-9,
            "trial {trial}"
        );
    }
}

#[test]
fn multipolygons_match_geo() {
    let mut rng = XorShift::new(0x9e3779b97f4a7c15);
    let polygons: Vec<Polygon> = (0..10)
        .map(|k| {
            let centre = [k as f64 * 300.0, (k % 3) as f64 * 250.0];
            Polygon::new(star(&mut rng, 40, centre, 100.0, k % 2 == 0), vec![])
        })
        .collect();
    assert!(polygon_issues(&polygons).is_empty());
    let ours = area_properties(&polygons);
    let theirs = MultiPolygon::new(polygons.iter().map(to_geo).collect());
    let area = theirs.unsigned_area();
    assert!((ours.area - area).abs() <= 1e-12 * area);
    let c = theirs.centroid().unwrap();
    let ours_c = ours.centroid.unwrap();
    assert!((ours_c[0] - c.x()).abs() <= 1e-9 && (ours_c[1] - c.y()).abs() <= 1e-9);
}
