//! `section`: the section of the moved solid by the moved plane is the section moved:
//! area and signed area times s², perimeter times s, the centroid (in space) moved, the
//! same loops; closed solids leave no open chain. (Its area against the profile's and
//! `below`'s: `profile::profile_below_and_section_agree_at_every_level`.)

use crate::solids::{catalogue, prism, L_RING};
use crate::transform::{transforms, Transform};
use crate::{assert_near, assert_near_point, bounds, checked, sections_comparable};
use meshvol::polygon::area_properties;
use meshvol::section::{section, Plane};
use meshvol::{mass_properties, Point};
use proptest::prelude::*;

/// The area, perimeter, 3D centroid, loops and open chains of a section.
fn measure(
    surface: &impl meshvol::Surface,
    plane: &Plane,
) -> (f64, f64, f64, Option<Point>, usize, usize) {
    let cut = section(surface, plane);
    let p = area_properties(&cut.polygons);
    let frame = plane.frame();
    let centroid = p
        .centroid
        .map(|[s, t]| [0, 1, 2].map(|a| frame.origin[a] + s * frame.u[a] + t * frame.v[a]));
    (p.area, cut.signed_area, p.perimeter, centroid, cut.loops, cut.open_chains)
}

/// Planes through `at` (fractions of the solid's box): one per axis, and one with
/// normal `normal`.
fn sections_follow(t: &Transform, at: [f64; 3], normal: Point) {
    let s = t.scale;
    for solid in catalogue().iter().filter(|solid| sections_comparable(solid, t)) {
        let name = solid.name;
        let (before, after) = (solid.shape.mesh(), t.apply(&solid.shape).mesh());
        let (c0, c1) = (checked(&before), checked(&after));
        let (solid0, solid1) = (c0.solid(&before), c1.solid(&after));
        let (min, max) = bounds(&solid.shape.positions);
        let o = [0, 1, 2].map(|a| min[a] + at[a] * (max[a] - min[a]));
        let size = (0..3).map(|a| max[a] - min[a]).fold(0.0, f64::max);
        let area = mass_properties(&solid0).area;
        let reach = s * size + t.shift.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut planes = Vec::new();
        for a in 0..3 {
            // New axis a is old axis axes[a].
            let b = t.axes[a];
            let moved = t.signs[a] * s * o[b] + t.shift[a];
            planes.push((
                format!("axis {b} at {}", o[b]),
                Plane::axis(b, o[b]),
                Plane::axis(a, moved),
            ));
        }
        planes.push((
            format!("normal {normal:?} through {o:?}"),
            Plane::new(o, normal),
            Plane::new(t.point(o), t.direction(normal)),
        ));
        for (label, p0, p1) in planes {
            let (p0, p1) = (p0.unwrap(), p1.unwrap());
            let (a0, signed0, perimeter0, centroid0, loops0, open0) = measure(&solid0, &p0);
            let (a1, signed1, perimeter1, centroid1, loops1, open1) = measure(&solid1, &p1);
            let what =
                |w: &str| format!("{name}: {w} of the section by the plane {label} under {t:?}");
            assert_near(&what("area"), a1, s * s * a0, s * s * area);
            // A mirror reverses the plane's frame for axis planes: the signed area keeps
            // its sign only where the frame turns with the solid.
            assert_near(&what("|signed area|"), signed1.abs(), s * s * signed0.abs(), s * s * area);
            assert_near(&what("perimeter"), perimeter1, s * perimeter0, s * size);
            assert_eq!((loops1, open1), (loops0, open0), "{}", what("loops and open chains"));
            if solid.solid {
                assert_eq!(open0, 0, "{}", what("open chains of a closed solid"));
            }
            if a0 > 1e-6 * area {
                assert_near_point(
                    &what("centroid"),
                    centroid1.unwrap(),
                    t.point(centroid0.unwrap()),
                    reach,
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(crate::cases(24))]

    #[test]
    fn sections_move_with_the_solid(
        t in transforms(),
        at in prop::array::uniform3(0.05f64..0.95),
        normal in prop::array::uniform3(-1.0f64..1.0).prop_filter("a direction", |n| n.iter().any(|x| x.abs() > 0.1)),
    ) {
        sections_follow(&t, at, normal);
    }
}

/// A non-convex planar face is a fan of triangles from its first corner; from a corner
/// that does not see all of the face the fan's triangles leave it and cancel outside
/// it, which sums (volume, area, grid, profile) handle exactly, and the section pairs
/// the face's own crossings along the line (`section::face_segments`), so that its loops
/// do not split into loops of both windings. An L-shaped prism (area 3, height 1.5) cut by one plane, with its top and bottom faces
/// started at each corner, must give one section area: the one from the corner (0, 0),
/// whose fan triangulates the L, and the section's own signed area.
#[test]
fn the_section_of_a_non_convex_face_does_not_depend_on_its_first_corner() {
    let shape = prism(&L_RING, -0.5, 1.0);
    let plane = Plane::new(
        [0.11214983767563313, 1.5278691655570893, 0.036545393584243024],
        [0.547515086497173, 0.2292869022245303, 0.8474042651804978],
    )
    .unwrap();
    let reference = area_properties(&section(&shape.mesh(), &plane).polygons).area;
    for first in 0..L_RING.len() {
        let mut turned = shape.clone();
        turned.faces[0].rotate_left(first);
        turned.faces[1].rotate_left(first);
        let cut = section(&turned.mesh(), &plane);
        let area = area_properties(&cut.polygons).area;
        assert_near(
            &format!("signed area, faces from corner {first}"),
            cut.signed_area,
            reference,
            reference,
        );
        assert_near(&format!("area, faces from corner {first}"), area, reference, reference);
    }
}
