//! `below`: the part of the moved solid below the moved plane is the part moved: volume
//! s³, wetted and section areas s², centroids moved; the level that holds a volume
//! moves with the solid; and the part below a plane and the part above it (below the
//! plane turned over) add up to the whole, for every face order. (A reference point
//! taken from face 0, cut away by the plane, gave 0 here: issue 26.)

use crate::solids::{catalogue, Solid};
use crate::transform::{transforms, Transform};
use crate::{assert_near, assert_near_point, bounds, checked, sections_comparable};
use meshvol::below::{below, level_for_volume};
use meshvol::mass_properties;
use meshvol::section::Plane;
use meshvol::Point;
use proptest::prelude::*;

/// A plane of the solid: through a vertex (`vertex` of them, modulo their count) or a
/// point between the solid's bounds at `at` (fractions of its box), with normal
/// `normal` (not normalized).
#[derive(Clone, Debug)]
pub struct Cut {
    vertex: Option<usize>,
    at: [f64; 3],
    normal: Point,
}

fn cuts() -> impl Strategy<Value = Cut> {
    let normal = prop_oneof![
        prop::sample::select(vec![
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 0.0]
        ]),
        prop::array::uniform3(-1.0f64..1.0)
            .prop_filter("a direction", |n| n.iter().any(|x| x.abs() > 0.1)),
    ];
    (prop::option::of(0usize..1000), prop::array::uniform3(0.1f64..0.9), normal)
        .prop_map(|(vertex, at, normal)| Cut { vertex, at, normal })
}

impl Cut {
    fn point(&self, solid: &Solid) -> Point {
        let p = &solid.shape.positions;
        match self.vertex {
            Some(v) => p[v % p.len()],
            None => {
                let (min, max) = bounds(p);
                [0, 1, 2].map(|a| min[a] + self.at[a] * (max[a] - min[a]))
            }
        }
    }
}

fn size(solid: &Solid) -> f64 {
    let (min, max) = bounds(&solid.shape.positions);
    (0..3).map(|a| max[a] - min[a]).fold(0.0, f64::max)
}

fn parts_follow(t: &Transform, cut: &Cut) {
    let (s, s3) = (t.scale, t.scale.powi(3));
    for solid in catalogue() {
        let name = solid.name;
        let (before, after) = (solid.shape.mesh(), t.apply(&solid.shape).mesh());
        let (c0, c1) = (checked(&before), checked(&after));
        let (solid0, solid1) = (c0.solid(&before), c1.solid(&after));
        let volume = mass_properties(&solid0).signed_volume;
        let o = cut.point(solid);
        let b0 = below(&solid0, &Plane::new(o, cut.normal).unwrap());
        let b1 = below(&solid1, &Plane::new(t.point(o), t.direction(cut.normal)).unwrap());
        let what = |w: &str| format!("{name}: {w} below {cut:?} under {t:?}");
        assert_near(
            &what("volume"),
            b1.part.signed_volume,
            s3 * b0.part.signed_volume,
            s3 * volume,
        );
        let area = mass_properties(&solid0).area;
        assert_near(&what("wetted area"), b1.part.area, s * s * b0.part.area, s * s * area);
        let sections = sections_comparable(solid, t);
        if sections {
            let want = s * s * b0.section_area;
            assert_near(&what("section area"), b1.section_area, want, s * s * area);
        }
        let reach = s * size(solid) + t.shift.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // A part with next to no volume has a centroid only its rounding decides.
        if b0.part.signed_volume > 1e-6 * volume {
            let c = t.point(b0.part.centroid.unwrap());
            assert_near_point(&what("centroid"), b1.part.centroid.unwrap(), c, reach);
        }
        if sections && b0.section_area > 1e-6 * area {
            let c = t.point(b0.section_centroid.unwrap());
            assert_near_point(&what("section centroid"), b1.section_centroid.unwrap(), c, reach);
        }

        // The part below and the part above make the whole.
        let up = below(&solid1, &Plane::new(t.point(o), t.direction(cut.normal)).unwrap());
        let down =
            below(&solid1, &Plane::new(t.point(o), t.direction(cut.normal.map(|x| -x))).unwrap());
        let whole = up.part.signed_volume + down.part.signed_volume;
        assert_near(&what("below(n, D) + below(−n, −D)"), whole, s3 * volume, s3 * volume);
        // Vertices on the plane count as above it (the section is the limit from below),
        // so through a vertex, where a face may lie in the plane, the two sides' sections
        // may differ by that face.
        if sections && cut.vertex.is_none() {
            let (a, b) = (down.section_area, up.section_area);
            assert_near(&what("the two sides' section areas"), a, b, s * s * area);
        }
    }
}

fn levels_follow(t: &Transform, direction: Point, fraction: f64) {
    let s = t.scale;
    for solid in catalogue() {
        let name = solid.name;
        let (before, after) = (solid.shape.mesh(), t.apply(&solid.shape).mesh());
        let (c0, c1) = (checked(&before), checked(&after));
        let (solid0, solid1) = (c0.solid(&before), c1.solid(&after));
        let volume = mass_properties(&solid0).signed_volume;
        let length = direction.iter().map(|x| x * x).sum::<f64>().sqrt();
        let n = direction.map(|x| x / length);
        let want = fraction * volume;
        let what = |w: &str| {
            format!("{name}: {w} holding {fraction} of the volume along {n:?} under {t:?}")
        };
        let d0 =
            level_for_volume(&solid0, n, want).unwrap_or_else(|e| panic!("{}: {e}", what("level")));
        let n1 = t.direction(n);
        let d1 = level_for_volume(&solid1, n1, s.powi(3) * want)
            .unwrap_or_else(|e| panic!("{}: {e}", what("level")));
        let shift: f64 = (0..3).map(|a| n1[a] * t.shift[a]).sum();
        assert_near(&what("level"), d1, s * d0 + shift, s * size(solid));
        // The level found holds the volume asked for.
        let plane = Plane::new(n.map(|x| x * d0), n).unwrap();
        assert_near(
            &what("the volume at the level"),
            below(&solid0, &plane).part.signed_volume,
            want,
            volume,
        );
    }
}

proptest! {
    #![proptest_config(crate::cases(24))]

    #[test]
    fn parts_below_move_with_the_solid(t in transforms(), cut in cuts()) {
        parts_follow(&t, &cut);
    }

    #[test]
    fn levels_move_with_the_solid(
        t in transforms(),
        direction in prop::array::uniform3(-1.0f64..1.0).prop_filter("a direction", |n| n.iter().any(|x| x.abs() > 0.1)),
        fraction in 0.05f64..0.95,
    ) {
        levels_follow(&t, direction, fraction);
    }
}
