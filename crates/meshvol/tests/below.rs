//! The part of a solid below a plane, against closed forms.

mod common;

use meshvol::below::{below, level_for_volume};
use meshvol::section::Plane;
use meshvol::shapes::cuboid;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-14 * b.abs().max(1.0)
}

#[test]
fn the_unit_cube_below_x_plus_z_is_a_prism() {
    // x + z ≤ 1: the triangular prism over (0,0), (1,0), (0,1) in (x, z), length 1 in y.
    let plane = Plane::new([0.5, 0.0, 0.5], [1.0, 0.0, 1.0]).unwrap();
    let b = below(&cuboid([0.0; 3], [1.0; 3]), &plane);
    assert!(close(b.part.signed_volume, 0.5));
    let c = b.part.centroid.unwrap();
    assert!(close(c[0], 1.0 / 3.0) && close(c[1], 0.5) && close(c[2], 1.0 / 3.0), "{c:?}");
    // The section: a √2 × 1 rectangle through (1,·,0) and (0,·,1), centred at (½, ½, ½).
    assert!(close(b.section_area, 2f64.sqrt()));
    let s = b.section_centroid.unwrap();
    assert!(s.iter().all(|&x| close(x, 0.5)), "{s:?}");
    // Wetted: the bottom (1), the side x = 0 (1), two triangles of ½ (y = 0, 1).
    assert!(close(b.part.area, 3.0), "{}", b.part.area);
}

#[test]
fn the_level_that_holds_a_volume() {
    let cube = cuboid([0.0; 3], [1.0; 3]);
    let d = level_for_volume(&cube, [0.0, 0.0, 1.0], 0.3).unwrap();
    assert!(close(d, 0.3), "{d}");
    // A box 4 × 2 × 1 at a tilt: below n·x ≤ d is linear in d where the plane cuts only
    // the side faces; at the centre's level it holds half.
    let b = cuboid([0.0; 3], [4.0, 2.0, 1.0]);
    let n = [0.0, 0.2f64.sin(), 0.2f64.cos()];
    let d = level_for_volume(&b, n, 4.0).unwrap();
    let centre = 1.0 * n[1] + 0.5 * n[2];
    assert!((d - centre).abs() <= 1e-14, "{d} vs {centre}");
    assert!(level_for_volume(&cube, [0.0, 0.0, 1.0], 2.0).is_err());
}

#[test]
fn a_heeled_box_barge_has_its_centre_of_buoyancy_in_closed_form() {
    // A barge of beam B = 2 (y), depth 1, length L = 4, floating at draft T = 0.5 upright,
    // heeled by θ about the x axis through the waterline's centre with the same
    // displacement (the waterline stays in the sides while tan θ ≤ T / (B/2)). The
    // immersed section is a trapezoid; its centroid, relative to the upright centre of
    // buoyancy (0, 1, T/2) in (y, z): y = B² tan θ / (12 T), z = B² tan² θ / (24 T).
    let (beam, depth, length, draft) = (2.0, 1.0, 4.0, 0.5);
    let barge = cuboid([0.0; 3], [length, beam, depth]);
    for degrees in [5.0f64, 10.0, 20.0] {
        let t = degrees.to_radians();
        // The waterplane through (·, 1, T) tilted by θ: normal (0, −sin θ, cos θ).
        let n = [0.0, -t.sin(), t.cos()];
        let o = [0.0, beam / 2.0, draft];
        let b = below(&barge, &Plane::new(o, n).unwrap());
        assert!(close(b.part.signed_volume, length * beam * draft));
        let c = b.part.centroid.unwrap();
        let y = beam / 2.0 + beam * beam * t.tan() / (12.0 * draft);
        let z = draft / 2.0 + beam * beam * t.tan().powi(2) / (24.0 * draft);
        assert!(close(c[1], y) && close(c[2], z), "{degrees}°: {c:?} vs ({y}, {z})");
        // The waterplane: B / cos θ wide.
        assert!(close(b.section_area, length * beam / t.cos()));
    }
}

/// The regression the invariance issue found: face 0 wholly above the plane left the
/// cut surface's sums without a reference point, and every such plane gave 0. Every
/// rotation of the face order must give the same part.
#[test]
fn the_part_does_not_depend_on_which_face_comes_first() {
    let cube = cuboid([0.0; 3], [1.0; 3]);
    let lists = common::face_lists(&cube);
    let plane = Plane::new([0.0, 0.0, 0.5], [0.0, 0.0, 1.0]).unwrap();
    for first in 0..lists.len() {
        let mut faces = lists.clone();
        faces.rotate_left(first);
        let mesh = common::polygons(cube.positions(), &faces);
        let b = below(&mesh, &plane);
        assert!(close(b.part.signed_volume, 0.5), "first face {first}: {}", b.part.signed_volume);
        assert!(close(b.part.area, 3.0), "first face {first}: {}", b.part.area);
        let d = level_for_volume(&mesh, [0.0, 0.0, 1.0], 0.25).unwrap();
        assert!(close(d, 0.25), "first face {first}: level {d}");
    }
}

/// An open surface's volume below is not monotone in the level: a volume it never
/// crosses is an error, never another volume.
#[test]
fn a_volume_an_open_surface_never_holds_is_an_error() {
    let open = common::open_box([0.0; 3], [1.0; 3]);
    let total = meshvol::mass_properties(&open).signed_volume;
    let asked = 0.5 * total;
    match level_for_volume(&open, [1.0, 0.0, 0.0], asked) {
        Err(e) => assert!(e.to_string().contains("no level holds"), "{e}"),
        Ok(d) => {
            let plane = Plane::new([d, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
            let got = below(&open, &plane).part.signed_volume;
            assert!((got - asked).abs() <= 1e-12, "level {d} holds {got}, not {asked}");
        }
    }
}
