//! One solid behind every number: `volume`, `grid`, `profile`, `union` and `section`
//! measure the same checked solid of a file by default, say in a warning why it may not
//! be the one meant, and measure the surface as wound with `--no-check`. Every expected
//! value is a closed form of the construction.

mod common;
use common::{box_obj, f, meshvol};

use serde_json::Value;
use std::path::{Path, PathBuf};

/// The one JSON object a successful run prints.
fn json(args: &[&str]) -> Value {
    let out = meshvol(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

fn warnings(v: &Value) -> Vec<String> {
    v["warnings"].as_array().expect("a warnings list").iter().map(|w| w.to_string()).collect()
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path: PathBuf = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// A 2×2×2 box with a centred 1×1×1 cavity: volume 7, section area 3 at mid-height, 4
/// elsewhere; 9 (or 8 for the union of the two boxes) if the cavity is taken for a solid.
fn cavity_box(dir: &Path, cavity_outward: bool) -> String {
    let text = box_obj([0.0; 3], [2.0; 3], 1, true, false)
        + &box_obj([0.5; 3], [1.5; 3], 9, cavity_outward, false);
    write(dir, &format!("cavity-{cavity_outward}.obj"), &text)
}

#[test]
fn every_command_measures_the_solid_with_its_cavity() {
    let dir = tempfile::tempdir().unwrap();
    for outward in [true, false] {
        let file = cavity_box(dir.path(), outward);
        let volume = json(&["volume", &file, "--json"]);
        assert_eq!(f(&volume["volume"]), 7.0);
        let grid = json(&["grid", &file, "--cells", "4,4,4", "--json"]);
        assert!((f(&grid["total"]) - 7.0).abs() < 1e-12, "{grid}");
        assert_eq!(f(&grid["mesh_volume"]), 7.0);
        let profile = json(&["profile", &file, "--levels", "4", "--json"]);
        let below = profile["volume_below"].as_array().unwrap();
        assert!((f(&below[4]) - 7.0).abs() < 1e-12);
        let areas: Vec<f64> = profile["section_area"].as_array().unwrap().iter().map(f).collect();
        assert!((areas[2] - 3.0).abs() < 1e-12, "{areas:?}"); // z = 1: 4 − 1
        let union = json(&["union", &file, "--json"]);
        assert!(f(&union["lower"]) <= 7.0 && 7.0 <= f(&union["upper"]), "{union}");
        assert_eq!(union["bodies"], 1); // the cavity belongs to its box
        let section = json(&["section", &file, "--plane", "z=1", "--json"]);
        assert!((f(&section["area"]) - 3.0).abs() < 1e-12);
        // A cavity wound like a solid is named in every command's warnings.
        for report in [&volume, &union] {
            assert_eq!(warnings(report).iter().any(|w| w.contains("role")), outward, "{report}");
        }
    }
}

#[test]
fn no_check_measures_the_surface_as_wound_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    let file = cavity_box(dir.path(), true);
    // Both boxes counted as solids: 8 + 1.
    let volume = json(&["volume", &file, "--no-check", "--json"]);
    assert_eq!(f(&volume["volume"]), 9.0);
    let grid = json(&["grid", &file, "--cells", "4,4,4", "--no-check", "--json"]);
    assert!((f(&grid["total"]) - 9.0).abs() < 1e-12);
    let profile = json(&["profile", &file, "--levels", "2", "--no-check", "--json"]);
    assert!((f(&profile["volume_below"][2]) - 9.0).abs() < 1e-12);
    assert!((f(&profile["section_area"][1]) - 5.0).abs() < 1e-12);
    // Unchecked, the two boxes are two bodies and their union is the outer box.
    let union = json(&["union", &file, "--no-check", "--json"]);
    assert!(f(&union["lower"]) <= 8.0 && 8.0 <= f(&union["upper"]));
    let section = json(&["section", &file, "--plane", "z=1", "--no-check", "--json"]);
    assert!((f(&section["area"]) - 3.0).abs() < 1e-12 || !warnings(&section).is_empty());
}

#[test]
fn overlapping_parts_are_found_alike_by_volume_and_check() {
    // Two unit cubes overlapping in a 0.5×1×1 slab, and a third apart: one pair.
    let dir = tempfile::tempdir().unwrap();
    let text = box_obj([0.0; 3], [1.0; 3], 1, true, false)
        + &box_obj([0.5, 0.2, 0.3], [1.5, 1.2, 1.3], 9, true, false)
        + &box_obj([5.0; 3], [6.0; 3], 17, true, false);
    let file = write(dir.path(), "overlap.obj", &text);
    let check = meshvol(&["check", &file, "--json"]);
    assert!(!check.status.success(), "overlapping shells do not bound a volume");
    let check: Value = serde_json::from_slice(&check.stdout).unwrap();
    let volume = json(&["volume", &file, "--json"]);
    assert_eq!(check["overlapping_shells"], serde_json::json!([[0, 1]]));
    assert_eq!(volume["overlapping_shells"], check["overlapping_shells"]);
    assert!(warnings(&volume).iter().any(|w| w.contains("overlap")), "{volume}");
    // The plain sum counts the overlap (0.5 × 0.8 × 0.7) twice; the union once.
    assert!((f(&volume["volume"]) - 3.0).abs() < 1e-12);
    let union = json(&["union", &file, "--json"]);
    let exact = 3.0 - 0.5 * 0.8 * 0.7;
    assert_eq!(union["bodies"], 3);
    assert!(f(&union["lower"]) <= exact && exact <= f(&union["upper"]), "{union}");
    assert!(f(&union["upper"]) - f(&union["lower"]) <= 1e-6 * exact);
}

#[test]
fn an_open_body_is_capped_and_says_so() {
    // A unit cube without its top: capped, the volume is 1 with a flat cap (no
    // uncertainty); every command warns that it is open.
    let dir = tempfile::tempdir().unwrap();
    let cube = box_obj([0.0; 3], [1.0; 3], 1, true, false);
    let open: String =
        cube.lines().filter(|l| *l != "f 5 6 8 7").map(|l| format!("{l}\n")).collect();
    assert_eq!(open.lines().count(), cube.lines().count() - 1);
    let file = write(dir.path(), "open.obj", &open);
    let volume = json(&["volume", &file, "--json"]);
    assert_eq!(f(&volume["volume"]), 1.0);
    let grid = json(&["grid", &file, "--cells", "2,2,2", "--json"]);
    assert!((f(&grid["total"]) - 1.0).abs() < 1e-12);
    let union = json(&["union", &file, "--json"]);
    assert!(f(&union["lower"]) <= 1.0 && 1.0 <= f(&union["upper"]));
    for report in [&volume, &union] {
        assert!(warnings(report).iter().any(|w| w.contains("open")), "{report}");
    }
    let stderr = String::from_utf8(meshvol(&["grid", &file, "--cells", "2,2,2"]).stderr).unwrap();
    assert!(stderr.contains("warning") && stderr.contains("open"), "{stderr}");

    // A single triangle: nothing is certified without a word.
    let file = write(dir.path(), "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n");
    let union = json(&["union", &file, "--json"]);
    assert!(f(&union["lower"]) <= f(&union["upper"]));
    assert!(!warnings(&union).is_empty(), "{union}");
}

#[test]
fn exact_does_not_claim_exactness_for_a_capped_guess() {
    // A box missing its top, tilted so its rim is not flat: the caps carry uncertainty.
    let dir = tempfile::tempdir().unwrap();
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1.2\nv 1 1 1\nv 0 1 1.3\n\
                f 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let file = write(dir.path(), "ragged.obj", text);
    let out = meshvol(&["volume", &file, "--exact"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("uncertainty"), "{text}");
    assert!(!text.contains("correctly rounded"), "{text}");
}
