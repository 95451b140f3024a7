//! `--units` and `--density` on every measuring command: one solid, written in mm, in
//! inches and in metres, gives the same physical answers, checked against the closed form
//! converted by hand (a 1000 mm cube is 1 m³ = 1000 L = 1/0.9144³ yd³).

mod common;
use common::{box_obj, f, meshvol, p, write};

use serde_json::Value;
use std::path::Path;

/// The file units and a 1 m side in each.
const UNITS: [(&str, f64); 3] = [("mm", 1000.0), ("in", 1000.0 / 25.4), ("m", 1.0)];

fn json(args: &[&str]) -> Value {
    let out = meshvol(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

#[track_caller]
fn near(v: &Value, expected: f64) {
    let x = f(v);
    assert!((x - expected).abs() <= 1e-9 * expected.abs().max(1.0), "{x} ≠ {expected}");
}

/// A cube of side `s` from the origin, and its copy moved by s/2 along x.
fn cubes(dir: &Path, unit: &str, s: f64) -> (String, String) {
    let a = write(dir, &format!("a-{unit}.obj"), box_obj([0.0; 3], [s; 3], 1, true, false));
    let b = box_obj([s / 2.0, 0.0, 0.0], [1.5 * s, s, s], 1, true, false);
    let b = write(dir, &format!("b-{unit}.obj"), b);
    (p(&a).to_string(), p(&b).to_string())
}

#[test]
fn one_cube_in_three_units_is_one_cubic_metre_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    for (unit, s) in UNITS {
        let (a, b) = cubes(dir.path(), unit, s);
        let to_l = format!("{unit}:L");
        let to_m3 = format!("{unit}:m3");
        let half = (s / 2.0).to_string();

        let v = json(&["volume", &a, "--units", &to_l, "--density", "1kg/L", "--json"]);
        near(&v["volume"], 1000.0);
        near(&v["mass"], 1000.0);
        assert_eq!(
            (v["mass_unit"].as_str(), v["density_unit"].as_str()),
            (Some("kg"), Some("kg/L"))
        );
        assert_eq!(v["units"]["volume"], "L");
        near(&v["centroid"][2], 5.0); // dm

        let v = json(&["check", &a, "--units", &to_l, "--density", "7.85g/cm3", "--json"]);
        near(&v["solid_volume"], 1000.0);
        near(&v["mass"], 7.85e6); // g
        assert_eq!(v["mass_unit"], "g");

        let v = json(&["grid", &a, "--cells", "2,2,2", "--units", &to_l, "--json"]);
        near(&v["total"], 1000.0);
        near(&v["cell_size"][0], 5.0);
        near(&v["mesh_volume"], 1000.0);

        let v = json(&["profile", &a, "--levels", "4", "--units", &to_l, "--json"]);
        near(&v["levels"][4], 10.0);
        near(&v["volume_below"][2], 500.0);
        near(&v["slab_volume"][0], 250.0);
        near(&v["section_area"][2], 100.0); // dm²

        let plane = format!("0,0,1,{half}");
        let v = json(&[
            "below",
            &a,
            "--plane",
            &plane,
            "--units",
            &to_m3,
            "--density",
            "1000kg/m3",
            "--json",
        ]);
        near(&v["volume"], 0.5);
        near(&v["mass"], 500.0);
        near(&v["level"], 0.5);
        near(&v["wetted_area"], 3.0);

        let v = json(&["union", &a, &b, "--units", &to_l, "--json"]);
        near(&v["volume"], 1500.0);

        let v = json(&["intersect", &a, &b, "--units", &to_l, "--json"]);
        near(&v["volume"], 500.0);
        near(&v["union"], 1500.0);
        near(&v["centroid"][0], 7.5);

        let v = json(&["hull", &a, "--units", &to_l, "--json"]);
        near(&v["volume"], 1000.0);
        near(&v["area"], 600.0);

        let z = format!("z={half}");
        let v = json(&["section", &a, "--plane", &z, "--units", &format!("{unit}:m"), "--json"]);
        near(&v["area"], 1.0);
        near(&v["perimeter"], 4.0);
        near(&v["inertia"]["ix"], 1.0 / 12.0);
        // A mass per area: a sheet of 62.8 kg/m² (8 mm of steel) cut to the 1 m² section.
        let v = json(&[
            "section",
            &a,
            "--plane",
            &z,
            "--units",
            unit,
            "--density",
            "62.8kg/m2",
            "--json",
        ]);
        near(&v["mass"], 62.8);
        assert_eq!(
            (v["mass_unit"].as_str(), v["density_unit"].as_str()),
            (Some("kg"), Some("kg/m^2"))
        );

        let wkt = format!("POLYGON((0 0, {s} 0, {s} {s}, 0 {s}, 0 0))");
        let poly = write(dir.path(), &format!("sq-{unit}.wkt"), wkt);
        let v = json(&["area", p(&poly), "--units", &format!("{unit}:m"), "--json"]);
        near(&v["area"], 1.0);
        near(&v["perimeter"], 4.0);
        let v = json(&[
            "area",
            p(&poly),
            "--units",
            &format!("{unit}:cm"),
            "--density",
            "0.5g/cm2",
            "--json",
        ]);
        near(&v["mass"], 5000.0); // 1 m² = 10⁴ cm², at 0.5 g/cm²
        assert_eq!(v["mass_unit"], "g");

        let sheet = format!("v 0 0 0\nv {s} 0 0\nv {s} {s} 0\nv 0 {s} 0\nf 1 2 3\nf 1 3 4\n");
        let sheet = write(dir.path(), &format!("ground-{unit}.obj"), sheet);
        let level = s.to_string();
        let v = json(&[
            "cutfill",
            p(&sheet),
            "--level",
            &level,
            "--units",
            &format!("{unit}:yd3"),
            "--json",
        ]);
        near(&v["fill"], 1.0 / 0.9144f64.powi(3));
        let v = json(&[
            "cutfill",
            p(&sheet),
            "--level",
            &level,
            "--units",
            &format!("{unit}:acre-ft"),
            "--json",
        ]);
        near(&v["fill"], 1.0 / 1233.48183754752);
        assert_eq!(v["units"]["volume"], "acre-ft");
    }
}

#[test]
fn text_names_units_and_mass() {
    let dir = tempfile::tempdir().unwrap();
    let (a, _) = cubes(dir.path(), "mm", 1000.0);
    let out = meshvol(&["profile", &a, "--levels", "10", "--units", "mm:L", "--density", "1kg/L"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(text.contains("volumes in L (the file in mm)"), "{text}");
    assert!(text.contains("mass               1000 kg  (density 1 kg/L)"), "{text}");
    let out = meshvol(&["volume", &a, "--units", "mm:m", "--density", "7850kg/m3"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("mass               7850 kg  (density 7850 kg/m^3)"), "{text}");
    assert!(text.contains("rounding)"), "{text}");
}

#[test]
fn bad_units_and_densities_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (a, _) = cubes(dir.path(), "mm", 1000.0);
    for command in ["volume", "check", "below", "hull"] {
        let mut args = vec![command, a.as_str(), "--units", "mm:furlong"];
        if command == "below" {
            args.extend(["--plane", "0,0,1,1"]);
        }
        let out = meshvol(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command}: {err}");
        assert!(err.contains("furlong") && err.contains("mL") && err.contains("acre-ft"), "{err}");
    }
    for bad in ["0", "-2", "inf", "NaN", "0g/cm3", "1g/furlong"] {
        let out = meshvol(&["grid", &a, "--cells", "1,1,1", "--density", bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
    }
    // A density of the other kind: per area for volumes, per volume for areas.
    for (args, wanted) in [
        (vec!["volume", a.as_str(), "--units", "mm", "--density", "62.8kg/m2"], "mass per volume"),
        (
            vec![
                "section",
                a.as_str(),
                "--plane",
                "z=1",
                "--units",
                "mm",
                "--density",
                "7.85g/cm3",
            ],
            "mass per area",
        ),
    ] {
        let out = meshvol(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(wanted), "{err}");
    }
    // A density with a unit needs the file's length unit.
    let out = meshvol(&["volume", &a, "--density", "7.85g/cm3"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--units"));
    // Files in different declared units cannot be measured together unconverted.
    let out = meshvol(&["union", &a, &a, "--units", "mm:L"]);
    assert!(out.status.success());
}
