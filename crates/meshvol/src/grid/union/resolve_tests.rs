//! The cut's two filters against brute force: `crossing` (exact sides) and
//! `Cutter::apart` (the separating-axis test in plan).

use super::*;

/// A fixed sequence of numbers in `[-1, 1)`.
struct Numbers(u64);

impl Numbers {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn point(&mut self) -> Point {
        [self.next(), self.next(), self.next()]
    }
}

fn cutter(t: [Point; 3]) -> Cutter {
    Cutter { body: 1, world: t, unit: t, plan: plan_box(&t), sides: sides(&t) }
}

/// Float side of `v` against the plane of `t`, scaled to a distance.
fn distance(t: &[Point; 3], v: Point) -> f64 {
    let (e1, e2) = ([0, 1, 2].map(|k| t[1][k] - t[0][k]), [0, 1, 2].map(|k| t[2][k] - t[0][k]));
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (0..3).map(|k| n[k] * (v[k] - t[0][k])).sum::<f64>() / length
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
    let mut n = Numbers(7);
    for _ in 0..20_000 {
        let own = [n.point(), n.point(), n.point()];
        let t = [n.point(), n.point(), n.point()];
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
    let mut n = Numbers(11);
    let (mut separated, mut cases) = (0, 0);
    for _ in 0..20_000 {
        let scale = 0.05 + n.next().abs();
        let t = [n.point(), n.point(), n.point()].map(|v| v.map(|x| x * scale));
        let c = cutter(t);
        let centre = n.point();
        // A quadrilateral: a convex polygon of four corners around `centre`.
        let r = 0.3 * n.next().abs() + 1e-3;
        let mut part = Polygon::<9>::EMPTY;
        let turn = n.next() * 3.0;
        for k in 0..4 {
            let a = turn + k as f64 * std::f64::consts::FRAC_PI_2 + 0.3 * n.next();
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
