//! An open shell whose holes were capped contains what lies inside it through its caps,
//! as a closed one does: volumes against the UV spheres' exact volumes.

use meshvol::shapes::{uv_sphere, uv_sphere_volume};
use meshvol::topology::{check, Check, CheckOptions};
use meshvol::{mass_properties, Mesh};
use std::f64::consts::PI;

const AGAINST_ITS_ROLE: &str = "wound against its role";

/// The outer sphere: radius 10, 48 segments, 24 rings.
const OUTER: (f64, u32, u32) = (10.0, 48, 24);

/// A triangulated UV sphere about `centre`, turned (x, y, z) → (z, x, y) so that its
/// poles lie on the x axis, wound outward or inward.
fn sphere(centre: [f64; 3], (radius, segments, rings): (f64, u32, u32), outward: bool) -> Mesh {
    let s = uv_sphere(radius, segments, rings).triangulated();
    let s = if outward { s } else { s.flipped() };
    let positions = s
        .positions()
        .iter()
        .map(|p| [p[2] + centre[0], p[0] + centre[1], p[1] + centre[2]])
        .collect();
    Mesh::new(positions, s.faces().clone()).unwrap()
}

/// The outer sphere without the faces between its +x pole and its ring `rings` (all of
/// whose vertices come before that ring's last one): a hole whose rim is that ring, flat.
fn outer_without_polar_cap(rings: u32) -> Mesh {
    let s = sphere([0.0; 3], OUTER, true);
    let last_vertex = rings * OUTER.1; // the pole is vertex 0, ring k holds 1 + (k−1)m ..
    let kept: Vec<&[u32]> = (0..s.face_count())
        .map(|f| s.face(f))
        .filter(|f| f.iter().any(|&v| v > last_vertex))
        .collect();
    let removed = s.face_count() - kept.len();
    assert_eq!(removed, (2 * rings as usize - 1) * OUTER.1 as usize);
    Mesh::from_polygons(s.positions().to_vec(), kept).unwrap()
}

/// The exact volume the outer sphere loses with the faces up to ring `rings`, closed by
/// that ring's plane: as `uv_sphere_volume`, m·sin(2π/m)·∫∫ x dA over the meridian's
/// part from the pole to that ring, closed by the ring's radius (which adds nothing).
fn polar_cap_volume(rings: u32) -> f64 {
    let (r, m, n) = OUTER;
    let meridian = |k: u32| {
        let phi = PI * k as f64 / n as f64;
        (r * phi.sin(), r * phi.cos())
    };
    let moment: f64 = (0..rings)
        .map(|k| {
            let ((x0, z0), (x1, z1)) = (meridian(k), meridian(k + 1));
            (z0 - z1) * (x0 * x0 + x0 * x1 + x1 * x1) / 6.0
        })
        .sum();
    m as f64 * (2.0 * PI / m as f64).sin() * moment
}

/// The check and the volume of its solid, which must be `expected` within the caps'
/// uncertainty and rounding.
fn measured(mesh: &Mesh, expected: f64) -> Check {
    let c = check(mesh, &CheckOptions::default()).unwrap();
    let volume = mass_properties(&c.solid(mesh)).signed_volume;
    let tolerance = c.volume_uncertainty + 1e-12 * expected.abs();
    assert!((volume - expected).abs() <= tolerance, "{volume} against {expected}");
    assert!((c.volume - expected).abs() <= tolerance, "{} against {expected}", c.volume);
    c
}

fn wound_outward(c: &Check) -> Vec<Option<bool>> {
    c.shells.iter().map(|s| s.wound_outward).collect()
}

fn against_its_role(c: &Check) -> usize {
    c.doubts().iter().filter(|d| d.contains(AGAINST_ITS_ROLE)).count()
}

/// The outer sphere without one face at its +x pole, around a cavity. (The rays from
/// the cavity's samples miss so small a hole: the wide hole's tests below show that the
/// rays meet the caps.)
fn one_face_missing_around_a_cavity(cavity_wound_inward: bool) -> Mesh {
    let outer = sphere([0.0; 3], OUTER, true);
    let faces: Vec<&[u32]> = (1..outer.face_count()).map(|f| outer.face(f)).collect();
    assert!(outer.face(0).contains(&0));
    let outer = Mesh::from_polygons(outer.positions().to_vec(), faces).unwrap();
    let cavity = sphere([0.0; 3], (3.0, 24, 12), !cavity_wound_inward);
    Mesh::concatenate(&[outer, cavity])
}

#[test]
fn a_shell_with_a_missing_face_holds_its_cavity() {
    let mesh = one_face_missing_around_a_cavity(true);
    // A triangle's hole is flat: its cap restores the face.
    let expected = uv_sphere_volume(OUTER.0, OUTER.1, OUTER.2) - uv_sphere_volume(3.0, 24, 12);
    let c = measured(&mesh, expected);
    assert_eq!((c.boundary_loops, c.shells.len(), c.cavities), (1, 2, 1));
    assert!(!c.shells[0].closed && !c.shells[0].cavity);
    assert!(c.shells[1].closed && c.shells[1].cavity);
    assert_eq!(c.shells[1].parent, Some(0));
    assert_eq!(wound_outward(&c), [Some(true), Some(true)]);
    assert!(c.overlapping_shells.is_empty());
    assert_eq!(against_its_role(&c), 0, "{:?}", c.doubts());
}

#[test]
fn a_cavity_wound_like_a_solid_in_a_shell_with_a_missing_face_is_turned_inward() {
    let mesh = one_face_missing_around_a_cavity(false);
    let expected = uv_sphere_volume(OUTER.0, OUTER.1, OUTER.2) - uv_sphere_volume(3.0, 24, 12);
    let c = measured(&mesh, expected);
    assert_eq!((c.shells.len(), c.cavities), (2, 1));
    assert!(c.shells[1].cavity && c.shells[1].parent == Some(0));
    assert_eq!(wound_outward(&c), [Some(true), Some(false)]);
    assert_eq!(against_its_role(&c), 1, "{:?}", c.doubts());
}

/// The rings around the +x pole whose faces are removed: the hole's rim lies in the
/// plane x = 5, a circle of radius 8.66, wider than the cavity and the sphere beside.
const HOLE_RINGS: u32 = 8;

#[test]
fn a_shell_with_a_wide_hole_holds_its_cavity_through_its_cap() {
    // Every ray along +x from the cavity leaves the outer shell through the cap.
    let outer = outer_without_polar_cap(HOLE_RINGS);
    let mesh = Mesh::concatenate(&[outer, sphere([0.0; 3], (3.0, 24, 12), false)]);
    let capped = uv_sphere_volume(OUTER.0, OUTER.1, OUTER.2) - polar_cap_volume(HOLE_RINGS);
    let c = measured(&mesh, capped - uv_sphere_volume(3.0, 24, 12));
    assert_eq!((c.boundary_loops, c.shells.len(), c.cavities), (1, 2, 1));
    assert!(c.shells[1].cavity && c.shells[1].parent == Some(0));
    assert_eq!(wound_outward(&c), [Some(true), Some(true)]);
    assert!(c.overlapping_shells.is_empty());
}

#[test]
fn a_sphere_beside_a_shell_with_a_wide_hole_is_a_second_solid() {
    // Within the open shell's box but outside it: rays along +x from the small sphere
    // enter the open shell through a face and leave through the cap, two crossings of
    // opposite sign (of the same sign, it would be inside, or the two would overlap).
    let (centre, small) = ([-8.0, 0.0, 8.5], (1.0, 24, 12));
    let mesh =
        Mesh::concatenate(&[outer_without_polar_cap(HOLE_RINGS), sphere(centre, small, true)]);
    let capped = uv_sphere_volume(OUTER.0, OUTER.1, OUTER.2) - polar_cap_volume(HOLE_RINGS);
    let c = measured(&mesh, capped + uv_sphere_volume(small.0, small.1, small.2));
    assert_eq!((c.shells.len(), c.cavities), (2, 0));
    assert!(c.shells.iter().all(|s| s.parent.is_none()));
    assert!(c.overlapping_shells.is_empty());
    assert_eq!(against_its_role(&c), 0, "{:?}", c.doubts());
}

#[test]
fn a_body_under_an_open_sheet_is_no_cavity_of_it() {
    // The four sides of a square pyramid (base 10 × 10, height 2), its base open: a
    // sheet, not a wall with a hole (its cap, the base, is 100 against 107.7 of faces),
    // so it contains nothing, and the unit cube under its apex stays a solid. The
    // solid's volume is the capped pyramid's, base × height / 3, plus the cube's.
    let sheet = Mesh::from_triangles(
        vec![
            [0.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            [10.0, 10.0, 0.0],
            [0.0, 10.0, 0.0],
            [5.0, 5.0, 2.0],
        ],
        vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
    )
    .unwrap();
    let corner =
        |i: u32| [4.5 + f64::from(i & 1), 4.5 + f64::from(i >> 1 & 1), 0.2 + f64::from(i >> 2)];
    let quads: [&[u32]; 6] =
        [&[0, 2, 3, 1], &[4, 5, 7, 6], &[0, 1, 5, 4], &[2, 6, 7, 3], &[0, 4, 6, 2], &[1, 3, 7, 5]];
    let cube = Mesh::from_polygons((0..8).map(corner).collect(), quads).unwrap();
    let c = measured(&Mesh::concatenate(&[sheet, cube]), 100.0 * 2.0 / 3.0 + 1.0);
    assert_eq!((c.boundary_loops, c.shells.len(), c.cavities), (1, 2, 0));
    assert!(c.shells.iter().all(|s| s.parent.is_none() && !s.cavity));
}
