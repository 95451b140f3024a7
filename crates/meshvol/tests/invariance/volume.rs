//! `volume` and `check`: the check's verdict and facts do not change, and the checked
//! solid's volume (s³), uncertainty (s³), area (s²), centroid (moved with the solid)
//! and inertia (s⁵, turned with the solid) follow the transform.

use crate::solids::catalogue;
use crate::transform::{transforms, Transform};
use crate::{assert_near, assert_near_point, checked};
use meshvol::mass_properties;
use meshvol::topology::Check;
use proptest::prelude::*;

/// The check's facts that no transform may change, as one comparable value. Shells
/// are compared as a sorted list (their numbering follows the face order), each with
/// its parent named by the parent's face count.
fn facts(c: &Check) -> impl PartialEq + std::fmt::Debug {
    let mut shells: Vec<_> = c
        .shells
        .iter()
        .map(|s| {
            let kind = (s.closed, s.orientable, s.consistently_oriented, s.cavity, s.wound_outward);
            let parent = s.parent.map(|p| c.shells[p].faces);
            (s.faces, kind, parent, s.boundary_loops, s.euler_characteristic, s.genus)
        })
        .collect();
    shells.sort();
    (
        (c.bounds_a_volume(), c.closed, c.vertices, c.edges, c.faces),
        (c.boundary_edges, c.boundary_loops, c.non_manifold_edges, c.non_manifold_vertices),
        (c.degenerate_faces, c.flat_faces, c.duplicate_faces, c.double_wall_faces),
        (c.consistently_oriented, c.orientation, c.cavities, c.overlapping_shells.len()),
        (c.self_intersections, c.euler_characteristic, c.weld_tolerance.is_some()),
        shells,
    )
}

/// The checked solid of every catalogue entry, before and after `t`.
fn same_solid(t: &Transform) {
    let s = t.scale;
    for solid in catalogue() {
        let name = solid.name;
        let (before, after) = (solid.shape.mesh(), t.apply(&solid.shape).mesh());
        let (c0, c1) = (checked(&before), checked(&after));
        assert_eq!(facts(&c0), facts(&c1), "{name}: the check's facts changed under {t:?}");
        let (m0, m1) = (mass_properties(&c0.solid(&before)), mass_properties(&c1.solid(&after)));
        let v = solid.volume.unwrap_or(m0.signed_volume);
        let v1 = s.powi(3) * v;
        let what = |w: &str| format!("{name}: {w} under {t:?}");
        assert_near(&what("volume"), m1.signed_volume, v1, v1);
        assert!(
            (m1.signed_volume - v1).abs() <= m1.volume_error_bound + s.powi(3) * v * 1e-15,
            "{}: {} against {v1}, beyond its stated bound {:e}",
            what("volume"),
            m1.signed_volume,
            m1.volume_error_bound
        );
        assert_near(&what("check volume"), c1.volume, v1, v1);
        let u = s.powi(3) * c0.volume_uncertainty;
        assert_near(&what("volume uncertainty"), c1.volume_uncertainty, u, v1);
        assert_near(&what("area"), m1.area, s * s * m0.area, s * s * m0.area);
        let size =
            m0.bounds.map_or(0.0, |b| (0..3).map(|a| b.max[a] - b.min[a]).fold(0.0, f64::max));
        let reach = s * size + t.shift.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert_near_point(
            &what("centroid"),
            m1.centroid.unwrap(),
            t.point(m0.centroid.unwrap()),
            reach,
        );
        let (want, got) = (t.tensor(m0.inertia), m1.inertia);
        let largest = want.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        for a in 0..3 {
            for b in 0..3 {
                assert_near(&what(&format!("inertia[{a}][{b}]")), got[a][b], want[a][b], largest);
            }
        }
    }
}

/// The catalogue's solids are what their constructions say (the reference every other
/// test leans on): the check's facts and the checked volume against closed forms.
#[test]
fn the_catalogue_is_what_it_claims() {
    for solid in catalogue() {
        let mesh = solid.shape.mesh();
        let c = checked(&mesh);
        if let Some(f) = solid.facts {
            let got = (c.closed, c.shells.len(), c.cavities, c.bounds_a_volume());
            assert_eq!(got, (f.closed, f.shells, f.cavities, f.bounds_a_volume), "{}", solid.name);
        }
        if let Some(v) = solid.volume {
            assert_near(solid.name, mass_properties(&c.solid(&mesh)).signed_volume, v, v);
            assert_near(solid.name, c.volume, v, v);
        }
    }
}

#[test]
fn the_identity_changes_nothing() {
    same_solid(&Transform::identity());
}

proptest! {
    #![proptest_config(crate::cases(24))]

    #[test]
    fn volume_and_check_follow_the_transform(t in transforms()) {
        same_solid(&t);
    }
}
