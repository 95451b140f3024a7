//! `area` (2D polygons): the same area, perimeter, centroid (moved) and second moments
//! (turned) whatever ring each polygon starts at, which way its rings wind, the order
//! of the polygons and holes, and the plane motion (x and y swapped or flipped, a
//! translation by ±2ᵏ up to 2²⁰, survey coordinates; a scaling by 2ᵏ: area s², perimeter
//! s, moments s⁴). Across commands: the section of the polygons' prism (holes as
//! cavities) at mid-height is the polygons, and `below` that level holds area × height.

use crate::common::XorShift;
use crate::solids::{prism, Shape};
use crate::{assert_near, checked};
use meshvol::below::below;
use meshvol::polygon::{area_properties, AreaProperties, Point2, Polygon};
use meshvol::section::{section, Plane};
use meshvol::Mesh;
use proptest::prelude::*;

/// An L (area 12, perimeter 16) with two square holes (1 and 0.25), and a triangle
/// apart (area 0.5): exteriors counter-clockwise, holes clockwise.
fn polygons() -> Vec<Polygon> {
    let l = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [2.0, 2.0], [2.0, 4.0], [0.0, 4.0]];
    let square = |x: f64, y: f64, h: f64| vec![[x, y], [x, y + h], [x + h, y + h], [x + h, y]];
    vec![
        Polygon::new(l, vec![square(0.5, 0.5, 1.0), square(0.5, 2.5, 0.5)]),
        Polygon::new(vec![[6.0, 0.0], [7.0, 0.0], [6.0, 1.0]], vec![]),
    ]
}

/// What changes the rings but not the region, and a plane motion.
#[derive(Clone, Debug)]
struct Motion {
    seed: u64,
    swap: bool,
    signs: [f64; 2],
    scale: f64,
    shift: [f64; 2],
}

fn motions() -> impl Strategy<Value = Motion> {
    let shift = prop::option::of((-4i32..=20, any::<bool>()));
    (
        any::<u64>(),
        any::<bool>(),
        prop::array::uniform2(any::<bool>()),
        0usize..5,
        prop::array::uniform2(shift),
    )
        .prop_map(|(seed, swap, flips, k, shift)| Motion {
            seed,
            swap,
            signs: flips.map(|f| if f { -1.0 } else { 1.0 }),
            scale: 2f64.powi([0, 1, -1, 2, -2][k]),
            shift: shift
                .map(|s| s.map_or(0.0, |(k, neg)| if neg { -1.0 } else { 1.0 } * 2f64.powi(k))),
        })
}

impl Motion {
    fn point(&self, p: Point2) -> Point2 {
        let q = if self.swap { [p[1], p[0]] } else { p };
        [0, 1].map(|a| self.signs[a] * self.scale * q[a] + self.shift[a])
    }

    /// Each ring moved, started at another vertex and perhaps reversed; holes and
    /// polygons shuffled (seed 0: only moved).
    fn apply(&self, polygons: &[Polygon]) -> Vec<Polygon> {
        let mut rng = XorShift::new(self.seed | 1);
        let mut ring = |r: &[Point2]| {
            let mut r: Vec<Point2> = r.iter().map(|&p| self.point(p)).collect();
            if self.seed != 0 {
                let k = rng.below(r.len() as u64) as usize;
                r.rotate_left(k);
                if rng.below(2) == 1 {
                    r.reverse();
                }
            }
            r
        };
        let mut out: Vec<Polygon> = polygons
            .iter()
            .map(|p| Polygon::new(ring(&p.exterior), p.holes.iter().map(|h| ring(h)).collect()))
            .collect();
        if self.seed != 0 {
            let mut rng = XorShift::new(self.seed);
            out.reverse();
            for p in &mut out {
                if rng.below(2) == 1 {
                    p.holes.reverse();
                }
            }
        }
        out
    }

    /// Second moments (ix, iy, ixy) turned and scaled with the polygons.
    fn moments(&self, m: [f64; 3]) -> [f64; 3] {
        let s4 = self.scale.powi(4);
        let (ix, iy) = if self.swap { (m[1], m[0]) } else { (m[0], m[1]) };
        [s4 * ix, s4 * iy, self.signs[0] * self.signs[1] * s4 * m[2]]
    }
}

fn moments(p: &AreaProperties) -> [f64; 3] {
    [p.inertia.ix, p.inertia.iy, p.inertia.ixy]
}

fn areas_follow(m: &Motion) {
    let (s, area, perimeter) = (m.scale, 12.0 - 1.25 + 0.5, 16.0 + 4.0 + 2.0 + 2.0 + 2f64.sqrt());
    let p0 = area_properties(&polygons());
    assert_near("area", p0.area, area, area);
    assert_near("perimeter", p0.perimeter, perimeter, perimeter);
    let p1 = area_properties(&m.apply(&polygons()));
    let what = |w: &str| format!("{w} under {m:?}");
    assert_near(&what("area"), p1.area, s * s * area, s * s * area);
    assert_near(&what("perimeter"), p1.perimeter, s * perimeter, s * perimeter);
    let (c0, c1) = (p0.centroid.unwrap(), p1.centroid.unwrap());
    let want = m.point(c0);
    let reach = 7.0 * s + m.shift.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for a in 0..2 {
        assert_near(&what("centroid"), c1[a], want[a], reach);
    }
    let (want, got) = (m.moments(moments(&p0)), moments(&p1));
    let largest = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for k in 0..3 {
        assert_near(&what(["ix", "iy", "ixy"][k]), got[k], want[k], largest);
    }
}

/// The prism of the polygons from z = 0 to `height`: each exterior's prism, each hole's
/// prism turned inside out (a cavity).
fn prism_of(polygons: &[Polygon], height: f64) -> Mesh {
    let ccw = |r: &[Point2]| {
        let mut r = r.to_vec();
        if meshvol::polygon::signed_area(&r) < 0.0 {
            r.reverse();
        }
        r
    };
    let mut parts = Vec::new();
    for p in polygons {
        parts.push(prism(&ccw(&p.exterior), 0.0, height).mesh());
        for h in &p.holes {
            parts.push(prism(&ccw(h), 0.0, height).mesh().flipped());
        }
    }
    Shape::of(&Mesh::concatenate(&parts)).mesh()
}

fn prism_sections_are_the_polygons(m: &Motion) {
    let polygons = m.apply(&polygons());
    let height = 2.0 * m.scale;
    let mesh = prism_of(&polygons, height);
    let c = checked(&mesh);
    let solid = c.solid(&mesh);
    let p = area_properties(&polygons);
    let cut = section(&solid, &Plane::axis(2, 0.5 * height).unwrap());
    let q = area_properties(&cut.polygons);
    let what = |w: &str| format!("the prism's section: {w} under {m:?}");
    assert_near(&what("area"), q.area, p.area, p.area);
    assert_near(&what("perimeter"), q.perimeter, p.perimeter, p.perimeter);
    let reach = 7.0 * m.scale + m.shift.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for a in 0..2 {
        assert_near(&what("centroid"), q.centroid.unwrap()[a], p.centroid.unwrap()[a], reach);
    }
    let largest = moments(&p).iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for k in 0..3 {
        assert_near(&what(["ix", "iy", "ixy"][k]), moments(&q)[k], moments(&p)[k], largest);
    }
    let part = below(&solid, &Plane::axis(2, 0.5 * height).unwrap()).part.signed_volume;
    let v = 0.5 * height * p.area;
    assert_near(&what("below half the height"), part, v, v);
}

proptest! {
    #![proptest_config(crate::cases(32))]

    #[test]
    fn areas_move_with_the_polygons(m in motions()) {
        areas_follow(&m);
    }

    #[test]
    fn prism_sections_are_their_polygons(m in motions()) {
        prism_sections_are_the_polygons(&m);
    }
}
