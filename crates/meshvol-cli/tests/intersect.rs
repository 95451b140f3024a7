//! `meshvol intersect` end to end: the built binary on files written here, against
//! volumes computed by hand (boxes, a box with a cavity, a box turned 45°), and its bad
//! inputs.

mod common;
use common::{box_obj, f, meshvol, p, write};

use serde_json::Value;
use std::path::Path;

/// The one JSON object a successful run prints.
fn json(args: &[&str]) -> Value {
    let out = meshvol(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

fn boxed(dir: &Path, name: &str, min: [f64; 3], max: [f64; 3]) -> String {
    p(&write(dir, name, box_obj(min, max, 1, true, false))).to_string()
}

/// Asserts that the report's interval holds `exact` within `width` (relative).
fn holds(v: &Value, exact: f64, width: f64) {
    let (lo, hi) = (f(&v["lower"]), f(&v["upper"]));
    assert!(lo <= exact && exact <= hi, "{exact} not in {v}");
    assert!(hi - lo <= width * exact.max(1.0), "{v}");
}

#[test]
fn two_boxes_give_every_key() {
    let dir = tempfile::tempdir().unwrap();
    let a = boxed(dir.path(), "a.obj", [0.0; 3], [2.0, 3.0, 1.0]);
    let b = boxed(dir.path(), "b.obj", [1.5, -1.0, 0.25], [4.0, 1.0, 3.0]);
    let v = json(&["intersect", &a, &b, "--json"]);
    let exact = 0.5 * 1.0 * 0.75;
    let (va, vb) = (6.0, 2.5 * 2.0 * 2.75);
    holds(&v, exact, 1e-9);
    assert_eq!(v["file"], format!("{a}, {b}"));
    assert!(v["warnings"].as_array().unwrap().is_empty(), "{v}");
    for (key, want) in [
        ("volume", exact),
        ("volume_a", va),
        ("volume_b", vb),
        ("a_minus_b", va - exact),
        ("b_minus_a", vb - exact),
        ("union", va + vb - exact),
        ("iou", exact / (va + vb - exact)),
        ("dice", 2.0 * exact / (va + vb)),
    ] {
        assert!((f(&v[key]) - want).abs() <= 1e-9 * want, "{key}: {v}");
    }
    assert!(f(&v["iou_lower"]) <= f(&v["iou"]) && f(&v["iou"]) <= f(&v["iou_upper"]));
    assert_eq!(v["disjoint"], false);
    // The common box [1.5, 2] × [0, 1] × [0.25, 1]: its centre and inertia.
    let c = &v["centroid"];
    let (dx, dy, dz) = (0.5f64, 1.0f64, 0.75f64);
    for (k, want) in [1.75, 0.5, 0.625].into_iter().enumerate() {
        assert!((f(&c[k]) - want).abs() < 1e-9, "{v}");
    }
    let i = &v["inertia"];
    let diagonal =
        [dy * dy + dz * dz, dx * dx + dz * dz, dx * dx + dy * dy].map(|s| exact * s / 12.0);
    for (k, want) in diagonal.into_iter().enumerate() {
        assert!((f(&i[k][k]) - want).abs() < 1e-9 * want, "{v}");
    }
    // The interface: B's faces x = 1.5 (−x), y = 1 (+y), z = 0.25 (−z) inside A, of
    // areas 0.75, 0.375 and 0.5, and A's faces x = 2, y = 0, z = 1 inside B, the same.
    assert!((f(&v["contact_area"]) - 2.0 * (0.75 + 0.375 + 0.5)).abs() < 1e-9, "{v}");
    let n = (0.75f64 * 0.75 + 0.375 * 0.375 + 0.5 * 0.5).sqrt();
    for (k, want) in [-0.75, 0.375, -0.5].into_iter().enumerate() {
        assert!((f(&v["contact_vector"][k]) - want).abs() < 1e-9, "{v}");
        assert!((f(&v["contact_normal"][k]) - want / n).abs() < 1e-9, "{v}");
    }
    // Swapped, the same volume.
    let w = json(&["intersect", &b, &a, "--json"]);
    holds(&w, exact, 1e-9);
    // Text names the files and the IoU.
    let out = meshvol(&["intersect", &a, &b]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("intersection of") && text.contains("IoU"), "{text}");
}

#[test]
fn boxes_apart_are_zero_without_a_grid() {
    let dir = tempfile::tempdir().unwrap();
    let a = boxed(dir.path(), "a.obj", [0.0; 3], [1.0; 3]);
    let b = boxed(dir.path(), "b.obj", [1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    let v = json(&["intersect", &a, &b, "--json"]);
    assert_eq!((f(&v["lower"]), f(&v["upper"]), f(&v["iou"])), (0.0, 0.0, 0.0), "{v}");
    assert_eq!(v["disjoint"], true);
    assert!(v["centroid"].is_null() && v["inertia"].is_null(), "{v}");
    assert_eq!(f(&v["a_minus_b"]), 1.0);
    assert_eq!(f(&v["contact_area"]), 0.0);
    assert_eq!(v["contact_vector"], serde_json::json!([0.0, 0.0, 0.0]));
    assert!(v["contact_normal"].is_null(), "{v}");
}

#[test]
fn a_box_and_a_box_turned_45_degrees() {
    // A box [-1, 1]² × [0, 1] and the square |x| + |y| ≤ 1.5 over [0.25, 2]: the
    // square's area inside is 2r² − 4(r − 1)² = 3.5, over a height of 0.75.
    let dir = tempfile::tempdir().unwrap();
    let a = boxed(dir.path(), "a.obj", [-1.0, -1.0, 0.0], [1.0, 1.0, 1.0]);
    let mut obj = String::new();
    for z in [0.25, 2.0] {
        for (x, y) in [(1.5, 0.0), (0.0, 1.5), (-1.5, 0.0), (0.0, -1.5)] {
            obj += &format!("v {x} {y} {z}\n");
        }
    }
    obj += "f 4 3 2 1\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let b = p(&write(dir.path(), "diamond.obj", obj)).to_string();
    holds(&json(&["intersect", &a, &b, "--json"]), 3.5 * 0.75, 1e-9);
}

#[test]
fn a_body_is_its_checked_solid() {
    let dir = tempfile::tempdir().unwrap();
    // A 2×2×2 box with a centred unit cavity, against a box over [0.25, 1.75]³: 1.5³ − 1.
    let text =
        box_obj([0.0; 3], [2.0; 3], 1, true, false) + &box_obj([0.5; 3], [1.5; 3], 9, false, false);
    let cavity = p(&write(dir.path(), "cavity.obj", text)).to_string();
    let middle = boxed(dir.path(), "middle.obj", [0.25; 3], [1.75; 3]);
    holds(&json(&["intersect", &cavity, &middle, "--json"]), 1.5f64.powi(3) - 1.0, 1e-9);
    // An open box is capped and warned about; its cap is its missing top.
    let open =
        p(&write(dir.path(), "open.obj", box_obj([0.0; 3], [1.0; 3], 1, true, true))).to_string();
    let half = boxed(dir.path(), "half.obj", [0.5, 0.0, 0.0], [3.0, 1.0, 1.0]);
    let v = json(&["intersect", &open, &half, "--json"]);
    holds(&v, 0.5, 1e-6);
    let warnings = v["warnings"].to_string();
    assert!(warnings.contains("open.obj") && warnings.contains("hole"), "{v}");
}

#[test]
fn bad_inputs_are_errors_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let a = boxed(dir.path(), "a.obj", [0.0; 3], [1.0; 3]);
    let missing = dir.path().join("missing.stl");
    let garbage = write(dir.path(), "garbage.stl", b"solid x\nfacet normal nonsense\n");
    for bad in [p(&missing), p(&garbage)] {
        let out = meshvol(&["intersect", &a, bad, "--json"]);
        assert_eq!(out.status.code(), Some(1), "{bad}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(bad), "{stderr}");
    }
    // One file only, or a bad tolerance: a usage error.
    assert_eq!(meshvol(&["intersect", &a]).status.code(), Some(2));
    assert_eq!(meshvol(&["intersect", &a, &a, "--tolerance", "-1"]).status.code(), Some(2));
}

#[test]
fn pairs_measure_each_overlapping_pair_once() {
    let dir = tempfile::tempdir().unwrap();
    let a = boxed(dir.path(), "a.obj", [0.0; 3], [2.0; 3]);
    let b = boxed(dir.path(), "b.obj", [1.0; 3], [3.0; 3]);
    let far = boxed(dir.path(), "far.obj", [10.0; 3], [11.0; 3]);
    // Touches a along x = 2 and b along y = 1: no volume in common with either.
    let touching = boxed(dir.path(), "touching.obj", [2.0, 0.0, 0.0], [3.0, 1.0, 1.0]);
    let c = boxed(dir.path(), "c.obj", [1.5, 0.0, 1.5], [2.5, 2.5, 2.5]);
    let out = meshvol(&["intersect", &a, &b, &far, &touching, &c, "--pairs", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let lines: Vec<Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let files: Vec<&str> = lines.iter().map(|v| v["file"].as_str().unwrap()).collect();
    assert_eq!(files, [format!("{a}, {b}"), format!("{a}, {c}"), format!("{b}, {c}")]);
    // a ∩ b: the unit cube; a ∩ c: [1.5, 2] × [0, 2] × [1.5, 2]; b ∩ c: [1.5, 2.5] ×
    // [1, 2.5] × [1.5, 2.5].
    for (v, exact) in lines.iter().zip([1.0, 0.5 * 2.0 * 0.5, 1.0 * 1.5 * 1.0]) {
        holds(v, exact, 1e-9);
    }
    // Without --pairs, two files only; more pairs than --max-pairs is refused.
    assert_eq!(meshvol(&["intersect", &a, &b, &c]).status.code(), Some(2));
    let out = meshvol(&["intersect", &a, &b, &c, "--pairs", "--max-pairs", "2"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--max-pairs"));
}
