//! A checked solid whose vector area is exactly zero (closed, consistently oriented,
//! welded exactly: `Check::vector_area_is_zero`) is measured about its first vertex,
//! without the move to the origin, whose bound grows with the distance from it. Each
//! test compares with the exact rational volume (`exact_signed_volume`), and the
//! surfaces that are not so (open, flipped, welded within a tolerance, with a duplicate
//! face as wound) keep the origin's convention.

mod common;
use common::bumpy_sphere;
use meshvol::shapes::{torus, uv_sphere};
use meshvol::topology::{check, Check, CheckOptions, Weld};
use meshvol::{exact_signed_volume, mass_properties, Faces, MassProperties, Mesh, Point};
use proptest::prelude::*;

/// Coordinates on a 2⁻²⁰ grid, so that integer offsets up to 10⁷ move them exactly.
fn snapped(mesh: &Mesh) -> Mesh {
    let snap = |x: f64| (x * 1048576.0).round() / 1048576.0;
    let p = mesh.positions().iter().map(|p| p.map(snap)).collect();
    Mesh::new(p, mesh.faces().clone()).unwrap()
}

fn moved(mesh: &Mesh, t: Point) -> Mesh {
    let p = mesh.positions().iter().map(|p| [p[0] + t[0], p[1] + t[1], p[2] + t[2]]).collect();
    Mesh::new(p, mesh.faces().clone()).unwrap()
}

fn triangles(mesh: &Mesh) -> Vec<[u32; 3]> {
    match mesh.triangulated().faces() {
        Faces::Triangles(t) => t.clone(),
        Faces::Polygons { .. } => unreachable!("triangulated"),
    }
}

fn checked(mesh: &Mesh) -> Check {
    check(mesh, &CheckOptions::default()).unwrap()
}

/// |value − exact| ≤ bound.
fn assert_within(what: &str, mp: &MassProperties, exact: f64) {
    let error = (mp.signed_volume - exact).abs();
    assert!(
        error <= mp.volume_error_bound,
        "{what}: {} is {error:e} from the exact {exact}, bound {:e}",
        mp.signed_volume,
        mp.volume_error_bound
    );
}

#[test]
fn a_closed_solid_far_away_keeps_the_bound_of_its_size() {
    for (name, solid) in
        [("sphere", snapped(&uv_sphere(1.0, 64, 32))), ("torus", snapped(&torus(2.0, 0.5, 48, 24)))]
    {
        for offset in [[0.0; 3], [1e3, -2e3, 5e2], [1e7, -2e7, 3e7]] {
            let far = moved(&solid, offset);
            let c = checked(&far);
            assert!(c.vector_area_is_zero(), "{name} at {offset:?}");
            let exact = exact_signed_volume(&far).unwrap();
            let (solid_mp, as_wound) =
                (mass_properties(&c.solid(&far)), mass_properties(&c.as_wound(&far)));
            assert_within(name, &solid_mp, exact);
            assert_within(name, &as_wound, exact);
            // The bound is that of the sum about a vertex, the size of the solid's
            // edges, wherever the solid is.
            assert!(solid_mp.volume_error_bound < 1e-14 * exact.abs(), "{name} at {offset:?}");
            assert_eq!(solid_mp.signed_volume.to_bits(), as_wound.signed_volume.to_bits());
            assert_eq!(
                solid_mp.volume_error_bound.to_bits(),
                as_wound.volume_error_bound.to_bits()
            );
        }
    }
}

#[test]
fn surfaces_without_a_proven_zero_vector_area_keep_the_origin_convention() {
    let sphere = moved(&snapped(&uv_sphere(1.0, 32, 16)), [3e6, -1e6, 2e6]);
    let t = triangles(&sphere);
    let p = sphere.positions().to_vec();

    // Open: the upper half of the sphere.
    let upper: Vec<[u32; 3]> =
        t.iter().copied().filter(|f| f.iter().all(|&v| p[v as usize][2] >= 2e6)).collect();
    // One face turned: closed, not consistently oriented.
    let mut turned = t.clone();
    turned[5].swap(1, 2);
    // A face given twice the same way: the solid drops the copy, as wound it stays.
    let mut doubled = t.clone();
    doubled.push(t[7]);
    for (name, faces) in [("open", upper), ("turned", turned), ("doubled", doubled)] {
        let mesh = Mesh::from_triangles(p.clone(), faces).unwrap();
        let c = checked(&mesh);
        let as_wound = mass_properties(&c.as_wound(&mesh));
        assert_within(name, &as_wound, exact_signed_volume(&mesh).unwrap());
        let solid = c.solid_mesh(true);
        assert_within(
            name,
            &mass_properties(&c.solid(&mesh)),
            exact_signed_volume(&solid).unwrap(),
        );
        match name {
            "doubled" => assert!(c.vector_area_is_zero(), "the solid drops the copy"),
            _ => assert!(!c.vector_area_is_zero(), "{name}"),
        }
    }
    // Welded within a tolerance: the vertices are not the corners' exact positions.
    let tolerance = CheckOptions { weld: Weld::Tolerance(1e-9), ..CheckOptions::default() };
    assert!(!check(&sphere, &tolerance).unwrap().vector_area_is_zero());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Bumpy closed spheres of any size anywhere: the solid's volume, taken about its
    /// first vertex, is within its bound of the exact one.
    #[test]
    fn closed_solids_anywhere_stay_within_their_bound(
        radii in prop::collection::vec(0.5f64..1.5, 74),
        scale in 1e-3f64..1e3,
        offset in prop::array::uniform3(-1e7f64..1e7),
    ) {
        let mesh = bumpy_sphere(&radii, scale, offset);
        let c = checked(&mesh);
        prop_assert!(c.vector_area_is_zero());
        let exact = exact_signed_volume(&mesh).unwrap();
        let mp = mass_properties(&c.solid(&mesh));
        prop_assert!((mp.signed_volume - exact).abs() <= mp.volume_error_bound,
            "{} vs {} bound {}", mp.signed_volume, exact, mp.volume_error_bound);
        prop_assert!(mp.volume_error_bound < 1e-11 * exact.abs());
    }
}
