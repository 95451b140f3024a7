//! `profile`: along an axis moved by the transform, the profile of the moved solid is
//! the solid's along the axis it came from: levels moved, volumes below times s³ (read
//! from the top, V − volume below, where the axis is flipped), slabs times s³, section
//! areas times s². And across commands: its top is the volume, and at each level
//! `below` holds its `volume_below` while `below`'s and `section`'s section areas are
//! its `section_area`.

use crate::solids::catalogue;
use crate::transform::{transforms, Transform};
use crate::{assert_near, checked, sections_comparable};
use meshvol::below::below;
use meshvol::grid::{profile, Axis, Levels};
use meshvol::mass_properties;
use meshvol::polygon::area_properties;
use meshvol::section::{section, Plane};
use proptest::prelude::*;

const AXES: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

/// Whether some vertex lies at `level` along `axis`: a face may lie flat there, where
/// a profile's section area is the area just above the level (its right derivative)
/// and a section's the area just below, so the two are not compared there.
fn on_a_vertex(points: &[[f64; 3]], axis: usize, level: f64) -> bool {
    points.iter().any(|p| p[axis] == level)
}

fn profiles_follow(t: &Transform, slabs: usize) {
    let (s, s3) = (t.scale, t.scale.powi(3));
    for solid in catalogue() {
        let name = solid.name;
        let shape1 = t.apply(&solid.shape);
        let (before, after) = (solid.shape.mesh(), shape1.mesh());
        let (c0, c1) = (checked(&before), checked(&after));
        let volume = mass_properties(&c0.solid(&before)).signed_volume;
        for a in 0..3 {
            let b = t.axes[a];
            let p0 = profile(&c0.solid(&before), AXES[b], Levels::Count(slabs)).unwrap();
            let p1 = profile(&c1.solid(&after), AXES[a], Levels::Count(slabs)).unwrap();
            let flipped = t.signs[a] < 0.0;
            let from = |k: usize| if flipped { slabs - k } else { k };
            let size = p0.levels[slabs] - p0.levels[0];
            for k in 0..=slabs {
                let what =
                    |w: &str| format!("{name}: {w} at level {k} of {slabs} along {a} under {t:?}");
                let level = t.signs[a] * s * p0.levels[from(k)] + t.shift[a];
                assert_near(&what("level"), p1.levels[k], level, s * size + t.shift[a].abs());
                let vb =
                    if flipped { volume - p0.volume_below[from(k)] } else { p0.volume_below[k] };
                assert_near(&what("volume below"), p1.volume_below[k], s3 * vb, s3 * volume);
                let interior = k > 0 && k < slabs;
                if !(flipped
                    && interior
                    && on_a_vertex(&solid.shape.positions, b, p0.levels[from(k)]))
                {
                    let area = s * s * p0.section_area[from(k)];
                    assert_near(
                        &what("section area"),
                        p1.section_area[k],
                        area,
                        s * s * volume / size,
                    );
                }
            }
            for k in 0..slabs {
                let j = if flipped { slabs - 1 - k } else { k };
                let what = format!("{name}: slab {k} of {slabs} along {a} under {t:?}");
                assert_near(&what, p1.slab_volume[k], s3 * p0.slab_volume[j], s3 * volume);
            }
        }
    }
}

/// At each level of each axis' profile: `below` the level holds the profile's volume
/// below it, and `below`'s and `section`'s section areas are the profile's.
fn profile_below_section_agree(t: &Transform, slabs: usize) {
    for solid in catalogue().iter().filter(|s| s.solid) {
        let name = solid.name;
        let shape = t.apply(&solid.shape);
        let mesh = shape.mesh();
        let c = checked(&mesh);
        let surface = c.solid(&mesh);
        let volume = mass_properties(&surface).signed_volume;
        for (a, &axis) in AXES.iter().enumerate() {
            let p = profile(&surface, axis, Levels::Count(slabs)).unwrap();
            assert_near(
                &format!("{name}: profile top along {a} under {t:?}"),
                p.volume_below[slabs],
                volume,
                volume,
            );
            let size = p.levels[slabs] - p.levels[0];
            for k in 0..=slabs {
                let level = p.levels[k];
                let what =
                    |w: &str| format!("{name}: {w} at level {k} of {slabs} along {a} under {t:?}");
                let mut e = [0.0; 3];
                e[a] = 1.0;
                let mut o = [0.0; 3];
                o[a] = level;
                let b = below(&surface, &Plane::new(o, e).unwrap());
                assert_near(
                    &what("below's volume against the profile's"),
                    b.part.signed_volume,
                    p.volume_below[k],
                    volume,
                );
                let generic = k > 0 && k < slabs && !on_a_vertex(&shape.positions, a, level);
                if generic && sections_comparable(solid, t) {
                    let area = p.section_area[k];
                    let scale = volume / size;
                    assert_near(
                        &what("below's section area against the profile's"),
                        b.section_area,
                        area,
                        scale,
                    );
                    let cut = section(&surface, &Plane::axis(a, level).unwrap());
                    let got = area_properties(&cut.polygons).area;
                    assert_near(&what("section's area against the profile's"), got, area, scale);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(crate::cases(16))]

    #[test]
    fn profiles_move_with_the_solid(t in transforms(), k in 0u32..4) {
        profiles_follow(&t, 1 << k);
    }

    #[test]
    fn profile_below_and_section_agree_at_every_level(t in transforms(), k in 1u32..4) {
        profile_below_section_agree(&t, (1 << k) + 1);
    }
}
