//! Mass properties against independent values: closed forms, integer arithmetic, and
//! invariances (translation, rotation, flipping, splitting, thread count).

mod common;

use common::{bumpy_sphere, mapped, moved};

use meshvol::shapes::{cuboid, tetrahedron, torus, torus_volume, uv_sphere, uv_sphere_volume};
use meshvol::{exact_signed_volume, mass_properties, Faces, MassProperties, Mesh, Surface};
use num_bigint::BigInt;
use proptest::prelude::*;
use std::f64::consts::PI;

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

fn assert_close(what: &str, a: f64, b: f64, rel: f64) {
    assert!(close(a, b, rel), "{what}: {a} vs {b} (relative {:e})", ((a - b) / b).abs());
}

/// Area of the surface made by revolving the polyline `(x, z)` in `m` polygonal steps:
/// each band is m planar trapezoids with parallel sides 2·x·sin(π/m) and height the
/// distance between the sides' midpoints (x·cos(π/m), z).
fn revolved_area(polyline: &[(f64, f64)], m: u32) -> f64 {
    let half = PI / m as f64;
    polyline
        .windows(2)
        .map(|w| {
            let ((x0, z0), (x1, z1)) = (w[0], w[1]);
            let h = (((x0 - x1) * half.cos()).powi(2) + (z0 - z1).powi(2)).sqrt();
            m as f64 * (x0 + x1) * half.sin() * h
        })
        .sum()
}

/// The unit cube wound as OpenSCAD's polyhedron() wants (clockwise seen from outside):
/// the face list from its documentation.
fn openscad_cube() -> Mesh {
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let f = vec![
        [0, 1, 2],
        [0, 2, 3],
        [4, 6, 5],
        [4, 7, 6],
        [0, 5, 1],
        [0, 4, 5],
        [1, 6, 2],
        [1, 5, 6],
        [2, 7, 3],
        [2, 6, 7],
        [3, 4, 0],
        [3, 7, 4],
    ];
    Mesh::from_triangles(p, f).unwrap()
}

/// Σ a·(b×c)/6 about the world origin, in plain f64: what most tools compute.
fn naive_volume(mesh: &Mesh) -> f64 {
    let p = mesh.positions();
    let t = mesh.triangulated();
    let Faces::Triangles(tris) = t.faces() else { unreachable!() };
    tris.iter()
        .map(|&[a, b, c]| {
            let (a, b, c) = (p[a as usize], p[b as usize], p[c as usize]);
            a[0] * (b[1] * c[2] - b[2] * c[1])
                + a[1] * (b[2] * c[0] - b[0] * c[2])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum::<f64>()
        / 6.0
}

#[test]
fn unit_cube_with_quads() {
    let mp = mass_properties(&cuboid([0.0; 3], [1.0; 3]));
    assert_eq!((mp.faces, mp.triangles), (6, 12));
    assert_eq!(mp.signed_volume, 1.0);
    assert_eq!(mp.area, 6.0);
    assert_eq!(mp.centroid, Some([0.5, 0.5, 0.5]));
    assert!(mp.volume_error_bound < 1e-14);
}

#[test]
fn box_inertia_is_analytic() {
    // A 2×3×5 box: Ixx = V(b² + c²)/12 etc., no products of inertia.
    let (a, b, c) = (2.0, 3.0, 5.0);
    let mp = mass_properties(&cuboid([-7.0, 1.0, 4.0], [-7.0 + a, 1.0 + b, 4.0 + c]));
    let v = a * b * c;
    assert_close("volume", mp.volume(), v, 1e-15);
    assert_close("area", mp.area, 2.0 * (a * b + b * c + c * a), 1e-15);
    let expected =
        [v * (b * b + c * c) / 12.0, v * (a * a + c * c) / 12.0, v * (a * a + b * b) / 12.0];
    for k in 0..3 {
        assert_close("inertia", mp.inertia[k][k], expected[k], 1e-13);
        assert!(mp.inertia[k][(k + 1) % 3].abs() < 1e-12);
    }
    let p = mp.principal();
    let mut sorted = expected;
    sorted.sort_by(f64::total_cmp);
    for k in 0..3 {
        assert_close("principal", p.moments[k], sorted[k], 1e-13);
    }
    // The smallest moment, V(a² + b²)/12, is about z; its axis is +z by the sign rule.
    assert!((p.axes[0][2] - 1.0).abs() < 1e-12, "{:?}", p.axes);
}

#[test]
fn tetrahedron_matches_hand_integrals() {
    // The corner tetrahedron (0, e1, e2, e3): V = 1/6, centroid 1/4, and about the origin
    // ∫x² dV = 1/60, ∫xy dV = 1/120.
    let mp =
        mass_properties(&tetrahedron([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]));
    let v = 1.0 / 6.0;
    assert_close("volume", mp.signed_volume, v, 1e-15);
    assert_close("area", mp.area, 1.5 + 3f64.sqrt() / 2.0, 1e-15);
    let c = 0.25;
    assert_eq!(mp.centroid, Some([c; 3]));
    let (xx, xy) = (1.0 / 60.0 - v * c * c, 1.0 / 120.0 - v * c * c);
    assert_close("Ixx", mp.inertia[0][0], 2.0 * xx, 1e-14);
    assert_close("Ixy", mp.inertia[0][1], -xy, 1e-14);
}

#[test]
fn uv_sphere_matches_its_polyhedral_closed_form() {
    for (m, n) in [(8, 4), (64, 32), (360, 181)] {
        let r = 2.5;
        let mesh = uv_sphere(r, m, n);
        let mp = mass_properties(&mesh);
        assert_close("sphere volume", mp.signed_volume, uv_sphere_volume(r, m, n), 1e-13);
        let meridian: Vec<_> = (0..=n)
            .map(|k| {
                let phi = PI * k as f64 / n as f64;
                (r * phi.sin(), r * phi.cos())
            })
            .collect();
        assert_close("sphere area", mp.area, revolved_area(&meridian, m), 1e-13);
        let c = mp.centroid.unwrap();
        assert!(c.iter().all(|x| x.abs() < 1e-14), "{c:?}");
        // Symmetry: Ixx = Iyy; and a fine sphere approaches 2/5·V·r².
        assert_close("Ixx=Iyy", mp.inertia[0][0], mp.inertia[1][1], 1e-12);
        if m == 360 {
            assert_close("continuum", mp.inertia[2][2], 0.4 * mp.signed_volume * r * r, 1e-3);
        }
    }
}

#[test]
fn torus_matches_its_polyhedral_closed_form() {
    let (big, small, m, n) = (3.0, 1.0, 96, 48);
    let mp = mass_properties(&torus(big, small, m, n));
    assert_close("torus volume", mp.signed_volume, torus_volume(big, small, m, n), 1e-13);
    let section: Vec<_> = (0..=n)
        .map(|j| {
            let phi = 2.0 * PI * j as f64 / n as f64;
            (big + small * phi.cos(), small * phi.sin())
        })
        .collect();
    assert_close("torus area", mp.area, revolved_area(&section, m), 1e-13);
}

#[test]
fn openscad_winding_gives_negative_signed_volume() {
    let mp = mass_properties(&openscad_cube());
    assert_eq!(mp.signed_volume, -1.0);
    assert_eq!(mp.volume(), 1.0);
    assert_eq!(mp.area, 6.0);
    assert_eq!(mp.centroid, Some([0.5; 3]));
    // The solid's inertia, whatever the winding: a unit cube has 1/6 about each axis.
    assert_close("Ixx", mp.inertia[0][0], 1.0 / 6.0, 1e-15);
    assert_eq!(exact_signed_volume(&openscad_cube()), Ok(-1.0));
}

#[test]
fn far_from_the_origin_keeps_every_digit() {
    // Snap a sphere to a 2⁻²⁰ grid so that adding an integer offset of 10⁷ is exact: the
    // translated polyhedron is the same solid, so its volume must not change.
    let snap = |p: [f64; 3]| p.map(|x| (x * 1048576.0).round() / 1048576.0);
    let sphere = mapped(&uv_sphere(1.0, 64, 32), snap);
    let here = mass_properties(&sphere);
    let offset = [1e7, -2e7, 3e7];
    let far = moved(&sphere, offset);
    let there = mass_properties(&far);
    let rel = |a: f64| ((a - here.signed_volume) / here.signed_volume).abs();
    assert!(rel(there.signed_volume) < 1e-13, "meshvol loses {:e}", rel(there.signed_volume));
    assert!(rel(naive_volume(&far)) > 1e-10, "the naive sum should lose digits here");
    // The exact volumes are equal bit for bit, and the fast one is within its bound.
    let exact = exact_signed_volume(&far).unwrap();
    assert_eq!(exact, exact_signed_volume(&sphere).unwrap());
    assert!((there.signed_volume - exact).abs() <= there.volume_error_bound);
    for k in 0..3 {
        let moved = there.centroid.unwrap()[k] - offset[k];
        assert!((moved - here.centroid.unwrap()[k]).abs() < 1e-8);
        assert_close("inertia", there.inertia[k][k], here.inertia[k][k], 1e-9);
    }
}

#[test]
fn rotation_keeps_volume_and_rotates_inertia() {
    let mesh = torus(2.0, 0.7, 48, 24);
    let here = mass_properties(&mesh);
    // Rotation about (1, 2, 2)/3 by 1 rad (Rodrigues' formula).
    let (k, ang) = ([1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0], 1.0f64);
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let kx = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
            let kk = k[i] * k[j] - if i == j { 1.0 } else { 0.0 };
            r[i][j] =
                if i == j { 1.0 } else { 0.0 } + ang.sin() * kx[i][j] + (1.0 - ang.cos()) * kk;
        }
    }
    let rot = |p: [f64; 3]| [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2]);
    let there = mass_properties(&mapped(&mesh, rot));
    assert_close("volume", there.signed_volume, here.signed_volume, 1e-13);
    assert_close("area", there.area, here.area, 1e-13);
    // I' = R I Rᵀ
    let scale = here.inertia[2][2];
    for i in 0..3 {
        for j in 0..3 {
            let expected: f64 = (0..3)
                .flat_map(|a| (0..3).map(move |b| (a, b)))
                .map(|(a, b)| r[i][a] * here.inertia[a][b] * r[j][b])
                .sum();
            assert!((there.inertia[i][j] - expected).abs() < 1e-12 * scale);
        }
    }
}

#[test]
fn flipping_negates_the_signed_volume() {
    let tri = uv_sphere(1.0, 32, 16).triangulated();
    let (a, b) = (mass_properties(&tri), mass_properties(&tri.flipped()));
    assert_eq!(b.signed_volume, -a.signed_volume);
    assert_eq!((b.area, b.centroid, b.inertia), (a.area, a.centroid, a.inertia));
    // Polygons flip by reversing the loop, which changes the fan: equal within bounds.
    let poly = torus(2.0, 0.5, 24, 12);
    let (a, b) = (mass_properties(&poly), mass_properties(&poly.flipped()));
    assert!(
        (a.signed_volume + b.signed_volume).abs() <= a.volume_error_bound + b.volume_error_bound
    );
}

/// Splits every triangle into four at its edge midpoints.
fn subdivided(mesh: &Mesh) -> Mesh {
    let t = mesh.triangulated();
    let Faces::Triangles(tris) = t.faces() else { unreachable!() };
    let mut p = t.positions().to_vec();
    let mut out = Vec::new();
    for &[a, b, c] in tris {
        let mid = |i: u32, j: u32, p: &mut Vec<[f64; 3]>| {
            let (u, v) = (p[i as usize], p[j as usize]);
            p.push([0, 1, 2].map(|k| 0.5 * (u[k] + v[k])));
            p.len() as u32 - 1
        };
        let (ab, bc, ca) = (mid(a, b, &mut p), mid(b, c, &mut p), mid(c, a, &mut p));
        out.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    Mesh::from_triangles(p, out).unwrap()
}

fn assert_same_properties(a: &MassProperties, b: &MassProperties, rel: f64) {
    assert_close("volume", a.signed_volume, b.signed_volume, rel);
    assert_close("area", a.area, b.area, rel);
    let (ca, cb) = (a.centroid.unwrap(), b.centroid.unwrap());
    let size = a.bounds.unwrap().size().iter().fold(0.0f64, |m, x| m.max(*x));
    for k in 0..3 {
        assert!((ca[k] - cb[k]).abs() < rel * size);
        for j in 0..3 {
            assert!((a.inertia[k][j] - b.inertia[k][j]).abs() < rel * a.inertia[k][k].abs());
        }
    }
}

#[test]
fn splitting_faces_changes_nothing() {
    let mesh = torus(2.0, 0.7, 40, 20);
    let whole = mass_properties(&mesh);
    assert_same_properties(&mass_properties(&mesh.triangulated()), &whole, 1e-13);
    assert_same_properties(&mass_properties(&subdivided(&mesh)), &whole, 1e-13);
}

#[test]
fn same_bits_at_any_thread_count() {
    let mesh = moved(&uv_sphere(3.0, 300, 150), [1e5, 2e5, -3e5]); // 89k triangles
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| (mass_properties(&mesh), exact_signed_volume(&mesh)))
    };
    let one = run(1);
    for threads in [2, 3, 8] {
        let many = run(threads);
        assert_eq!(format!("{:?}", many.0), format!("{:?}", one.0), "{threads} threads");
        assert_eq!(many.1, one.1);
    }
}

#[test]
fn empty_and_flat_surfaces() {
    let empty = Mesh::from_triangles(vec![], vec![]).unwrap();
    let mp = mass_properties(&empty);
    assert_eq!((mp.signed_volume, mp.area, mp.centroid, mp.bounds), (0.0, 0.0, None, None));
    assert_eq!(exact_signed_volume(&empty), Ok(0.0));
    // A single triangle bounds nothing: no centroid. Its signed volume is that of the
    // cone from the origin: area 1/2, facing up at height 3, so 3 · 1/2 / 3.
    let flat = Mesh::from_triangles(
        vec![[1.0, 2.0, 3.0], [2.0, 2.0, 3.0], [1.0, 3.0, 3.0]],
        vec![[0, 1, 2]],
    )
    .unwrap();
    let mp = mass_properties(&flat);
    assert_eq!((mp.signed_volume, mp.area, mp.centroid), (0.5, 0.5, None));
    assert_eq!(exact_signed_volume(&flat), Ok(0.5));
}

/// 6V of a triangle mesh with integer coordinates, in exact integer arithmetic.
fn integer_six_volume(p: &[[i64; 3]], tris: &[[u32; 3]]) -> i128 {
    tris.iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| p[i as usize].map(i128::from));
            a[0] * (b[1] * c[2] - b[2] * c[1])
                + a[1] * (b[2] * c[0] - b[0] * c[2])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The fast volume is within its stated bound of the exact one, and the bound is tight.
    #[test]
    fn error_bound_holds(
        radii in prop::collection::vec(0.5f64..1.5, 74),
        scale in 1e-3f64..1e3,
        offset in prop::array::uniform3(-1e7f64..1e7),
    ) {
        let mesh = bumpy_sphere(&radii, scale, offset);
        let mp = mass_properties(&mesh);
        let exact = exact_signed_volume(&mesh).unwrap();
        prop_assert!((mp.signed_volume - exact).abs() <= mp.volume_error_bound,
            "{} vs {} bound {}", mp.signed_volume, exact, mp.volume_error_bound);
        prop_assert!(mp.volume_error_bound < 1e-11 * exact.abs());
    }

    /// On integer coordinates the exact volume is (6V as an integer) / 6, rounded once.
    #[test]
    fn exact_volume_matches_integer_arithmetic(
        radii in prop::collection::vec(0.5f64..1.5, 74),
        offset in prop::array::uniform3(-100_000i64..100_000),
    ) {
        let mesh = bumpy_sphere(&radii, 1000.0, [0.0; 3]);
        let ints: Vec<[i64; 3]> = mesh.positions().iter().map(|v| [0, 1, 2].map(|k| v[k].round() as i64 + offset[k])).collect();
        let floats: Vec<[f64; 3]> = ints.iter().map(|v| v.map(|x| x as f64)).collect();
        let mesh = Mesh::new(floats, mesh.faces().clone()).unwrap();
        let Faces::Triangles(tris) = mesh.faces() else { unreachable!() };
        let six = integer_six_volume(&ints, tris);
        prop_assert!(six.abs() < 1 << 53); // so `six as f64` is exact and one division rounds
        prop_assert_eq!(exact_signed_volume(&mesh).unwrap(), six as f64 / 6.0);
    }
}

#[test]
fn revolved_profiles_match_greens_theorem() {
    use meshvol::shapes::{revolve, revolve_volume};
    // A regular hexagon revolved is a torus: two closed forms must agree.
    let hexagon: Vec<_> = (0..6)
        .map(|j| {
            let phi = PI * j as f64 / 3.0;
            (3.0 + phi.cos(), phi.sin())
        })
        .collect();
    assert_close("torus", revolve_volume(&hexagon, 40), torus_volume(3.0, 1.0, 40, 6), 1e-14);
    // A non-convex profile (an L) revolved: kernel against the closed form.
    let l_profile = [(1.0, 0.0), (4.0, 0.0), (4.0, 1.0), (2.0, 1.0), (2.0, 5.0), (1.0, 5.0)];
    let mp = mass_properties(&revolve(&l_profile, 90));
    assert_close("L", mp.signed_volume, revolve_volume(&l_profile, 90), 1e-14);
}

/// x·2^shift as an integer: exact, for any finite x and shift ≥ 1074 + 53.
fn big_scaled(x: f64, shift: u32) -> BigInt {
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64;
    let fraction = bits & ((1u64 << 52) - 1);
    let (mantissa, e) =
        if exponent == 0 { (fraction, -1074) } else { (fraction | 1 << 52, exponent - 1075) };
    let m = BigInt::from(mantissa) << (e + shift as i64) as usize;
    if bits >> 63 == 1 {
        -m
    } else {
        m
    }
}

/// Σ a·(b×c) over the fan triangles, about the origin, times 2^(3·1200): exact.
fn big_six_volume(mesh: &Mesh) -> BigInt {
    let mut total = BigInt::from(0);
    for f in 0..mesh.face_count() {
        mesh.fan(f, |a, b, c| {
            let [a, b, c] = [a, b, c].map(|p| p.map(|x| big_scaled(x, 1200)));
            total += &a[0] * (&b[1] * &c[2] - &b[2] * &c[1])
                + &a[1] * (&b[2] * &c[0] - &b[0] * &c[2])
                + &a[2] * (&b[0] * &c[1] - &b[1] * &c[0]);
        });
    }
    total
}

/// |value − six/6| ≤ bound, with six = Σ a·(b×c) · 2^3600, decided exactly.
fn within_of_exact(value: f64, bound: f64, six: &BigInt) -> bool {
    let scale = |x: f64| -> BigInt { (big_scaled(x, 1200) * 6) << 2400 };
    let difference = scale(value) - six;
    let bound = scale(bound);
    difference <= bound && -difference <= bound
}

/// The open-surface checks: the default signed volume (about the origin) is within its
/// bound of the exact mode's and of a big-integer sum, and the bound is tight.
fn assert_origin_convention(what: &str, mesh: &Mesh, expected: Option<f64>) {
    let mp = mass_properties(mesh);
    let exact = exact_signed_volume(mesh).unwrap();
    let six = big_six_volume(mesh);
    assert!(
        (mp.signed_volume - exact).abs() <= mp.volume_error_bound,
        "{what}: {} vs exact {exact}, bound {:e}",
        mp.signed_volume,
        mp.volume_error_bound
    );
    assert!(within_of_exact(mp.signed_volume, mp.volume_error_bound, &six), "{what}");
    assert!(within_of_exact(exact, f64::EPSILON / 2.0 * exact.abs(), &six), "{what}: exact");
    assert!(mp.volume_error_bound <= 1e-11 * exact.abs(), "{what}: {:e}", mp.volume_error_bound);
    if let Some(v) = expected {
        assert_eq!(exact, v, "{what}");
        assert!((mp.signed_volume - v).abs() <= mp.volume_error_bound, "{what}");
    }
}

#[test]
fn open_surfaces_measure_cones_from_the_origin() {
    // The unit cube without its top: each remaining face contributes area · (signed
    // distance of its plane from the origin) / 3, which for the box [t, t + 1] sums to
    // (2 − t_z)/3 (the x and y pairs give 1 each, the bottom −t_z).
    let cube = cuboid([0.0; 3], [1.0; 3]);
    let top =
        (0..6).find(|&f| cube.face(f).iter().all(|&v| cube.positions()[v as usize][2] == 1.0));
    let top = top.unwrap();
    let faces: Vec<&[u32]> = (0..6).filter(|&f| f != top).map(|f| cube.face(f)).collect();
    let open = Mesh::from_polygons(cube.positions().to_vec(), faces).unwrap();
    for t in [[0.0; 3], [1e3, -2e3, 5e2], [-0.5, 0.25, 7.0], [3e6, 1e6, -2e6]] {
        let moved = moved(&open, t);
        assert_origin_convention(&format!("open cube at {t:?}"), &moved, Some((2.0 - t[2]) / 3.0));
        // The triangulated faces give the same: the convention is per surface, not fan.
        let tris = moved.triangulated();
        assert_origin_convention(&format!("open cube triangles at {t:?}"), &tris, None);
    }
    // A hemisphere (faces of a sphere with every vertex at z ≥ 0), snapped to a grid,
    // near and far from the origin.
    let snap = |p: [f64; 3]| p.map(|x| (x * 1048576.0).round() / 1048576.0);
    let sphere = mapped(&uv_sphere(1.0, 32, 16), snap).triangulated();
    let upper: Vec<&[u32]> = (0..sphere.face_count())
        .map(|f| sphere.face(f))
        .filter(|f| f.iter().all(|&v| sphere.positions()[v as usize][2] >= 0.0))
        .collect();
    let hemisphere = Mesh::from_polygons(sphere.positions().to_vec(), upper).unwrap();
    for t in [[0.0; 3], [0.3, -0.7, 0.1], [1e3, -2e3, 5e2], [-4e6, 2e5, 1e7]] {
        assert_origin_convention(&format!("hemisphere at {t:?}"), &moved(&hemisphere, t), None);
    }
    // A fan: a cone's side around an apex, without its base.
    let n = 24;
    let mut p = vec![[0.0, 0.0, 1.5]];
    p.extend((0..n).map(|i| {
        let t = 2.0 * PI * i as f64 / n as f64;
        snap([1.25 * t.cos(), 1.25 * t.sin(), 0.0])
    }));
    let fan: Vec<[u32; 3]> = (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
    let fan = Mesh::from_triangles(p, fan).unwrap();
    for t in [[0.0; 3], [1e3, -2e3, 5e2], [0.125, 3.5, -2.0]] {
        assert_origin_convention(&format!("fan at {t:?}"), &moved(&fan, t), None);
    }
}
