//! `hull`: the hull of a point cloud moved (and its points shuffled) is the hull moved:
//! volume s³, area s², centroid moved, the same hull vertices; and the hull of a convex
//! solid's vertices, with points inside and repeated, is the solid.

use crate::solids::catalogue;
use crate::transform::{transforms, Transform};
use crate::{assert_near, assert_near_point, bounds};
use meshvol::hull::convex_hull;
use meshvol::Point;
use proptest::prelude::*;

/// A solid's vertices, its box's centre (inside every convex solid of the catalogue,
/// and inside the box of the others) and a repeat of its first vertex.
fn cloud(positions: &[Point]) -> Vec<Point> {
    let (min, max) = bounds(positions);
    let mut points = positions.to_vec();
    points.push([0, 1, 2].map(|a| 0.5 * (min[a] + max[a])));
    points.push(positions[0]);
    points
}

fn hulls_follow(t: &Transform) {
    let (s, s3) = (t.scale, t.scale.powi(3));
    for solid in catalogue() {
        let name = solid.name;
        let points = cloud(&solid.shape.positions);
        let h0 = convex_hull(&points).unwrap();
        let h1 = convex_hull(&t.points(&points)).unwrap();
        let v0 = h0.volume();
        if solid.convex {
            let v = solid.volume.unwrap();
            assert_near(&format!("{name}: the hull of its vertices"), v0, v, v);
        }
        let what = |w: &str| format!("{name}: hull {w} under {t:?}");
        assert_near(&what("volume"), h1.volume(), s3 * v0, s3 * v0);
        let a0 = h0.properties.area;
        assert_near(&what("area"), h1.properties.area, s * s * a0, s * s * a0);
        let (min, max) = bounds(&points);
        let size = (0..3).map(|a| max[a] - min[a]).fold(0.0, f64::max);
        let reach = s * size + t.shift.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let c0 = h0.properties.centroid.unwrap();
        assert_near_point(&what("centroid"), h1.properties.centroid.unwrap(), t.point(c0), reach);
        let vertices = |h: &meshvol::hull::Hull| h.mesh.as_ref().map(|m| m.vertex_count());
        assert_eq!(vertices(&h1), vertices(&h0), "{}", what("vertices"));
    }
}

proptest! {
    #![proptest_config(crate::cases(24))]

    #[test]
    fn hulls_move_with_their_points(t in transforms()) {
        hulls_follow(&t);
    }
}
