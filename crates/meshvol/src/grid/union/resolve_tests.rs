//! The cut's two filters against brute force: `crossing` (exact sides) and
//! `Cutter::apart` (the separating-axis test in plan).

use super::*;
use crate::test_rng::XorShift;

/// A number in `[-1, 1)`.
fn signed(rng: &mut XorShift) -> f64 {
    2.0 * rng.unit() - 1.0
}

fn point(rng: &mut XorShift) -> Point {
    [signed(rng), signed(rng), signed(rng)]
}

fn cutter(t: [Point; 3]) -> Cutter {
    let sides = counter_clockwise(&t).map(|(corners, _)| sides(corners));
    Cutter { body: 1, world: t, unit: t, plan: plan_box(&t), sides }
}

/// Float side of `v` against the plane of `t`, scaled to a distance.
fn distance(t: &[Point; 3], v: Point) -> f64 {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    dot(n, sub(v, t[0])) / dot(n, n).sqrt()
}

#[test]
fn a_touch_at_a_shared_corner_does_not_cut() {
    // A fan's centre shared by two meshes: the other triangle meets the plane only there.
    let own = [[0.0, 0.0, 1.0], [1.0, 0.1, 0.99], [0.1, 1.0, 0.98]];
    let below = [[0.0, 0.0, 1.0], [-1.0, 0.2, 0.5], [0.3, -1.0, 0.4]];
    let above = [[0.0, 0.0, 1.0], [1.0, 0.3, 1.5], [0.2, 1.0, 1.6]];
    assert_eq!(crossing(&below, &own), None);
    assert_eq!(crossing(&above, &own), None);
    // Through the shared corner and across: a segment from it.
    let across = [[0.0, 0.0, 1.0], [1.0, 0.3, 1.5], [0.2, 1.0, 0.5]];
    let (p, q) = crossing(&across, &own).expect("crosses");
    assert!(p == own[0] || q == own[0]);
}

#[test]
fn crossings_lie_on_both_planes_and_are_found_when_corners_straddle() {
    let mut n = XorShift::new(7);
    for _ in 0..20_000 {
        let own = [point(&mut n), point(&mut n), point(&mut n)];
        let t = [point(&mut n), point(&mut n), point(&mut n)];
        let d = t.map(|v| distance(&own, v));
        let straddles = d.iter().any(|&x| x > 1e-6) && d.iter().any(|&x| x < -1e-6);
        match crossing(&t, &own) {
            Some((p, q)) => {
                for e in [p, q] {
                    assert!(distance(&own, e).abs() < 1e-9, "{e:?} off {own:?}");
                    assert!(distance(&t, e).abs() < 1e-9, "{e:?} off {t:?}");
                }
            }
            None => assert!(!straddles, "{t:?} straddles {own:?} ({d:?}) but no crossing"),
        }
    }
}

/// Whether `p` lies in triangle `t`'s closed plan projection, by a margin `m`.
fn in_triangle(t: &[Point; 3], p: Point, m: f64) -> bool {
    let s = [(0, 1), (1, 2), (2, 0)].map(|(a, b)| {
        let (u, v) = (t[a], t[b]);
        let (dx, dy) = (v[0] - u[0], v[1] - u[1]);
        (dx * (p[1] - u[1]) - dy * (p[0] - u[0])) / (dx * dx + dy * dy).sqrt()
    });
    s.iter().all(|&x| x >= -m) || s.iter().all(|&x| x <= m)
}

#[test]
fn apart_only_when_plan_shapes_do_not_meet() {
    let mut n = XorShift::new(11);
    let (mut separated, mut cases) = (0, 0);
    for _ in 0..20_000 {
        let scale = 0.05 + signed(&mut n).abs();
        let t = [point(&mut n), point(&mut n), point(&mut n)].map(|v| v.map(|x| x * scale));
        let c = cutter(t);
        let centre = point(&mut n);
        // A quadrilateral: a convex polygon of four corners around `centre`.
        let r = 0.3 * signed(&mut n).abs() + 1e-3;
        let mut part = Polygon::<9>::EMPTY;
        let turn = signed(&mut n) * 3.0;
        for k in 0..4 {
            let a = turn + k as f64 * std::f64::consts::FRAC_PI_2 + 0.3 * signed(&mut n);
            part.push([centre[0] + r * a.cos(), centre[1] + r * a.sin(), centre[2]]);
        }
        // Brute force: points of the part (a lattice of convex combinations of its
        // corners) in the triangle, or the triangle's corners in the part.
        let v = part.vertices();
        let mut meet = false;
        for i in 0..=8 {
            for j in 0..=8 - i {
                let (a, b) = (i as f64 / 8.0, j as f64 / 8.0);
                for (p, q, s) in [(v[0], v[1], v[2]), (v[0], v[2], v[3])] {
                    let w = 1.0 - a - b;
                    let x = [0, 1, 2].map(|k| w * p[k] + a * q[k] + b * s[k]);
                    meet |= in_triangle(&t, x, 1e-12);
                }
            }
        }
        for corner in t {
            meet |= in_triangle(&[v[0], v[1], v[2]], corner, 1e-12);
            meet |= in_triangle(&[v[0], v[2], v[3]], corner, 1e-12);
        }
        cases += 1;
        if c.apart(&part) {
            separated += 1;
            assert!(!meet, "apart, but {t:?} meets {v:?}");
        }
    }
    // The filter does filter: most random pairs of small shapes are apart.
    assert!(separated > cases / 4, "{separated} of {cases}");
}
