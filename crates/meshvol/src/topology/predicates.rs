//! Exact geometric predicates on triangles, from Shewchuk's adaptive orientation tests
//! (the `robust` crate): signs are exact, so the answers do not depend on rounding.

use crate::Point;
use robust::{orient2d, orient3d, Coord, Coord3D};

fn c3(p: Point) -> Coord3D<f64> {
    Coord3D { x: p[0], y: p[1], z: p[2] }
}

/// Sign of det[a − d; b − d; c − d]: positive when d lies behind the triangle (a, b, c),
/// i.e. on the side its normal (b − a) × (c − a) points away from.
pub(crate) fn orient(a: Point, b: Point, c: Point, d: Point) -> f64 {
    orient3d(c3(a), c3(b), c3(c), c3(d)).signum()
}

/// Whether segment pq crosses triangle abc properly: p and q strictly on opposite sides
/// of its plane, and the segment's line strictly inside the triangle.
fn segment_crosses(p: Point, q: Point, a: Point, b: Point, c: Point) -> bool {
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if sp * sq >= 0.0 {
        return false;
    }
    let (s1, s2, s3) = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
    s1 != 0.0 && s1 == s2 && s2 == s3
}

/// Whether two triangles cross properly: an edge of one passes strictly through the
/// interior of the other. Touching (shared or coplanar parts, an edge lying on a face)
/// does not count: it neither double-counts volume nor breaks a surface.
pub(crate) fn triangles_cross(t: [Point; 3], u: [Point; 3]) -> bool {
    let edges = |t: [Point; 3]| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
    edges(t).iter().any(|&(p, q)| segment_crosses(p, q, u[0], u[1], u[2]))
        || edges(u).iter().any(|&(p, q)| segment_crosses(p, q, t[0], t[1], t[2]))
}

/// How the ray from `p` in +x meets triangle (a, b, c): `Some(±1)` when it passes
/// strictly through the interior, the sign being that of the triangle's normal's x
/// component (+1 where the ray leaves an outward-wound solid); `Some(0)` when it misses;
/// `None` when it grazes an edge or vertex, or p lies on the triangle's plane inside it
/// (the caller then tries another ray).
pub(crate) fn ray_crossing(p: Point, a: Point, b: Point, c: Point) -> Option<i32> {
    let yz = |v: Point| Coord { x: v[1], y: v[2] };
    let normal_x = orient2d(yz(a), yz(b), yz(c)).signum();
    if normal_x == 0.0 {
        return Some(0); // edge-on to the ray: parallel, no crossing
    }
    let e = [
        orient2d(yz(a), yz(b), yz(p)),
        orient2d(yz(b), yz(c), yz(p)),
        orient2d(yz(c), yz(a), yz(p)),
    ]
    .map(f64::signum);
    if e.iter().any(|&s| s == -normal_x) {
        return Some(0); // p's projection is outside the triangle's
    }
    if e.contains(&0.0) {
        return None;
    }
    // The plane is ahead of p along +x iff (p − a)·n and n_x have opposite signs, i.e.
    // orient (which is −sign((p − a)·n)) has the sign of n_x.
    match orient(a, b, c, p) {
        s if s == normal_x => Some(normal_x as i32),
        0.0 => None,
        _ => Some(0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_and_touching_triangles() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        // Pierces t through its interior.
        assert!(triangles_cross(t, [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 3.0, 0.5]]));
        // Stands on t (touches along a segment, does not cross).
        assert!(!triangles_cross(t, [[0.2, 0.2, 0.0], [1.0, 0.2, 0.0], [0.5, 0.5, 1.0]]));
        // Shares an edge.
        assert!(!triangles_cross(t, [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, -1.0, 1.0]]));
        // Far away.
        assert!(!triangles_cross(t, [[5.0, 5.0, -1.0], [5.0, 5.0, 1.0], [6.0, 6.0, 0.0]]));
    }

    #[test]
    fn ray_crossings_follow_the_normal() {
        // Triangle in the plane x = 1, normal +x (counter-clockwise seen from +x).
        let (a, b, c) = ([1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 1.0]);
        assert_eq!(ray_crossing([0.0, 0.2, 0.2], a, b, c), Some(1));
        assert_eq!(ray_crossing([0.0, 0.2, 0.2], a, c, b), Some(-1));
        assert_eq!(ray_crossing([2.0, 0.2, 0.2], a, b, c), Some(0)); // behind the ray
        assert_eq!(ray_crossing([0.0, 0.9, 0.9], a, b, c), Some(0)); // outside
        assert_eq!(ray_crossing([0.0, 0.5, 0.5], a, b, c), None); // through an edge
        assert_eq!(ray_crossing([1.0, 0.2, 0.2], a, b, c), None); // on the triangle
    }
}
