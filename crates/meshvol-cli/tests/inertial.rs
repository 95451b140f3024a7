//! `volume --format urdf|sdf|mjcf`: the `<inertial>` element of a steel box in SI units,
//! against the closed form of a cuboid's inertia, turned about z so that every entry of
//! the tensor is tested in its place.

mod common;
use common::{meshvol, write};

const DENSITY: f64 = 7850.0; // steel, kg/m³

/// A 10 × 20 × 30 mm box centred at (c, c, c) mm, turned by `angle` about z, as OBJ.
fn turned_box(angle: f64, c: f64) -> String {
    let (sin, cos) = angle.sin_cos();
    let mut s = String::new();
    for k in 0..8 {
        let h = [5.0, 10.0, 15.0];
        let p: Vec<f64> = (0..3).map(|a| if k >> a & 1 == 1 { h[a] } else { -h[a] }).collect();
        let (x, y) = (cos * p[0] - sin * p[1], sin * p[0] + cos * p[1]);
        s += &format!("v {} {} {}\n", x + c, y + c, p[2] + c);
    }
    for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        s += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    s
}

/// The numbers of attribute or element `key` in `text` (`key="a b c"` or `<key>a</key>`).
fn values(text: &str, key: &str) -> Vec<f64> {
    let raw = if let Some(at) = text.find(&format!("{key}=\"")) {
        let rest = &text[at + key.len() + 2..];
        &rest[..rest.find('"').unwrap()]
    } else {
        let at = text.find(&format!("<{key}>")).unwrap_or_else(|| panic!("{key} in {text}"));
        let rest = &text[at + key.len() + 2..];
        &rest[..rest.find('<').unwrap()]
    };
    raw.split_whitespace().map(|v| v.parse().unwrap()).collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1e-12)
}

#[test]
fn a_steel_box_in_urdf_sdf_and_mjcf() {
    let dir = tempfile::tempdir().unwrap();
    let angle = std::f64::consts::FRAC_PI_6;
    let obj = write(dir.path(), "box.obj", turned_box(angle, 40.0));
    // Closed form in SI: m = ρ a b c; about the centre I = m/12 (b² + c², ...).
    let (a, b, c) = (0.010, 0.020, 0.030);
    let m = DENSITY * a * b * c;
    let (i0, i1, i2) =
        (m * (b * b + c * c) / 12.0, m * (a * a + c * c) / 12.0, m * (a * a + b * b) / 12.0);
    // Turned by θ about z: I' = R I Rᵀ.
    let (s, co) = angle.sin_cos();
    let ixx = co * co * i0 + s * s * i1;
    let iyy = s * s * i0 + co * co * i1;
    let ixy = co * s * (i0 - i1);
    let density = DENSITY.to_string();
    let run = |format: &str| {
        let out = meshvol(&[
            "volume",
            obj.to_str().unwrap(),
            "--units",
            "mm:m",
            "--density",
            &density,
            "--format",
            format,
        ]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8(out.stdout).unwrap()
    };
    let check = |text: &str, mass: f64, centre: &[f64], tensor: [f64; 6]| {
        assert!(close(mass, m), "{mass} vs {m}: {text}");
        assert!(centre.iter().all(|&x| close(x, 0.040)), "{text}");
        let expected = [ixx, ixy, 0.0, iyy, 0.0, i2];
        for (got, want) in tensor.iter().zip(expected) {
            assert!((got - want).abs() <= 1e-12 * i2, "{got} vs {want}: {text}");
        }
    };
    let urdf = run("urdf");
    let i = |k: &str| values(&urdf, k)[0];
    check(
        &urdf,
        values(&urdf, "value")[0],
        &values(&urdf, "xyz"),
        [i("ixx"), i("ixy"), i("ixz"), i("iyy"), i("iyz"), i("izz")],
    );
    let sdf = run("sdf");
    let i = |k: &str| values(&sdf, k)[0];
    check(
        &sdf,
        values(&sdf, "mass")[0],
        &values(&sdf, "pose")[..3],
        [i("ixx"), i("ixy"), i("ixz"), i("iyy"), i("iyz"), i("izz")],
    );
    let mjcf = run("mjcf");
    let f = values(&mjcf, "fullinertia"); // ixx iyy izz ixy ixz iyz
    check(
        &mjcf,
        values(&mjcf, "mass")[0],
        &values(&mjcf, "pos"),
        [f[0], f[3], f[4], f[1], f[5], f[2]],
    );
    // Without metres it is refused, saying why.
    let out = meshvol(&["volume", obj.to_str().unwrap(), "--format", "urdf"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--units"));
}
