//! `union`: the union of one input's bodies (each outermost shell with what it holds,
//! as `meshvol union FILE` takes them) contains the solid's volume in its certified
//! interval, before and after every transform (times s³); the bodies and the sum of
//! their volumes do not change.

use crate::solids::catalogue;
use crate::transform::{transforms, Transform};
use crate::{checked, REL};
use meshvol::grid::union;
use meshvol::surface::FaceSubset;
use meshvol::{mass_properties, Mesh};
use proptest::prelude::*;

/// The union of a mesh's checked bodies: (lower, upper, bodies, sum of volumes).
fn union_of(mesh: &Mesh) -> (f64, f64, usize, f64) {
    let c = checked(mesh);
    let bodies: Vec<_> =
        c.bodies().into_iter().map(|b| FaceSubset::new(c.solid(mesh), b.faces)).collect();
    let u = union(&bodies, 1e-6).unwrap();
    (u.lower, u.upper, u.bodies, u.sum_of_volumes)
}

fn union_follows(t: &Transform, which: usize) {
    let solid = &catalogue()[which % catalogue().len()];
    let name = solid.name;
    let s3 = t.scale.powi(3);
    let before = solid.shape.mesh();
    let volume = solid.volume.unwrap_or_else(|| {
        let c = checked(&before);
        mass_properties(&c.solid(&before)).signed_volume
    });
    let (lower0, upper0, bodies0, sum0) = union_of(&before);
    let (lower1, upper1, bodies1, sum1) = union_of(&t.apply(&solid.shape).mesh());
    let slack = REL * volume;
    for (label, lower, upper, v) in
        [("before", lower0, upper0, volume), ("after", lower1, upper1, s3 * volume)]
    {
        let slack = if label == "after" { s3 * slack } else { slack };
        assert!(
            lower - slack <= v && v <= upper + slack,
            "{name}: the union [{lower}, {upper}] {label} {t:?} does not hold the volume {v}"
        );
    }
    assert_eq!(bodies1, bodies0, "{name}: bodies under {t:?}");
    assert!(
        (sum1 - s3 * sum0).abs() <= s3 * slack,
        "{name}: sum of volumes {sum1} against {} under {t:?}",
        s3 * sum0
    );
}

proptest! {
    #![proptest_config(crate::cases(16))]

    #[test]
    fn the_union_of_one_solid_holds_its_volume(t in transforms(), which in 0usize..64) {
        union_follows(&t, which);
    }
}

/// Every solid of the catalogue once, untransformed and mirrored: no body is left to
/// chance.
#[test]
fn every_solid_is_its_own_union() {
    let mut mirror = Transform::identity();
    mirror.signs = [-1.0, 1.0, 1.0];
    for which in 0..catalogue().len() {
        union_follows(&mirror, which);
    }
}
