//! `meshvol cutfill`: planes against planes and levels (closed forms), the per-cell
//! .npy and the map, and every way the arguments or the inputs can be wrong.

mod common;
use common::{f, meshvol, p, write};

use serde_json::Value;
use std::path::{Path, PathBuf};

/// The unit square as an OBJ of `n × n` quads at heights `z(x, y)`, cut along one
/// diagonal or the other.
fn square(dir: &Path, name: &str, n: usize, flip: bool, z: impl Fn(f64, f64) -> f64) -> PathBuf {
    let mut obj = String::new();
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            obj += &format!("v {x} {y} {}\n", z(x, y));
        }
    }
    let at = |i: usize, j: usize| i * (n + 1) + j + 1;
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            obj += &if flip {
                format!("f {a} {b} {d}\nf {b} {c} {d}\n")
            } else {
                format!("f {a} {b} {c}\nf {a} {c} {d}\n")
            };
        }
    }
    write(dir, name, obj)
}

fn json(args: &[&str]) -> Value {
    let out = meshvol(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn close(v: &Value, expected: f64) -> bool {
    (f(v) - expected).abs() < 1e-14
}

#[test]
fn a_flat_surface_against_a_ramp() {
    // z = 1 against z = x: cut ∫ (1 − x) = 1/2 over the whole unit square.
    let dir = tempfile::tempdir().unwrap();
    let flat = square(dir.path(), "flat.obj", 1, false, |_, _| 1.0);
    let ramp = square(dir.path(), "ramp.obj", 3, true, |x, _| x);
    let v = json(&["cutfill", p(&flat), "--design", p(&ramp), "--json"]);
    // The keys, in the order the command prints them (docs/json.md).
    let out = meshvol(&["cutfill", p(&flat), "--design", p(&ramp), "--json"]);
    let line = String::from_utf8_lossy(&out.stdout);
    let keys = [
        "file",
        "design",
        "level",
        "cut",
        "fill",
        "net",
        "area_cut",
        "area_fill",
        "footprint_area",
        "footprint_bounds",
        "existing_area",
        "design_area",
        "grid",
        "units",
        "warnings",
    ];
    let at: Vec<usize> = keys.iter().map(|k| line.find(&format!("\"{k}\":")).unwrap()).collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{line}");
    assert_eq!(v.as_object().unwrap().len(), keys.len());
    assert_eq!(v["file"], p(&flat));
    assert_eq!(v["design"], p(&ramp));
    assert!(v["level"].is_null() && v["grid"].is_null());
    assert!(close(&v["cut"], 0.5) && close(&v["net"], 0.5) && close(&v["fill"], 0.0), "{v}");
    assert!(close(&v["area_cut"], 1.0) && close(&v["area_fill"], 0.0), "{v}");
    assert!(close(&v["footprint_area"], 1.0) && close(&v["design_area"], 1.0), "{v}");
    assert_eq!(v["warnings"], serde_json::json!([]));
    // The text names both and the numbers.
    let out = meshvol(&["cutfill", p(&flat), "--design", p(&ramp)]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("against") && text.contains("ramp.obj") && text.contains("0.5"),
        "{text}"
    );
}

#[test]
fn a_ramp_against_a_level_in_cells() {
    // z = x against z = 1/2: a cut of 1/8 over half the square, a fill of 1/8 over the
    // other half. In 4 × 1 cells, cell i holds ∫ over [i/4, (i+1)/4] of (x − 1/2)±.
    let dir = tempfile::tempdir().unwrap();
    let ramp = square(dir.path(), "ramp.obj", 2, false, |x, _| x);
    let npy = dir.path().join("cells.npy");
    let png = dir.path().join("map.png");
    let v = json(&[
        "cutfill",
        p(&ramp),
        "--level",
        "0.5",
        "--cells",
        "4,1",
        "--out",
        p(&npy),
        "--png",
        p(&png),
        "--json",
    ]);
    assert_eq!(v["design"], "z = 0.5");
    assert_eq!(f(&v["level"]), 0.5);
    assert!(close(&v["cut"], 0.125) && close(&v["fill"], 0.125) && close(&v["net"], 0.0), "{v}");
    assert!(close(&v["area_cut"], 0.5) && close(&v["area_fill"], 0.5), "{v}");
    assert!(v["design_area"].is_null());
    assert_eq!(
        v["grid"],
        serde_json::json!({"counts": [4, 1], "origin": [0.0, 0.0], "cell": [0.25, 1.0]})
    );
    // The .npy: shape (2, 4, 1), cut then fill.
    let bytes = std::fs::read(&npy).unwrap();
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = std::str::from_utf8(&bytes[10..10 + header_len]).unwrap();
    assert!(header.contains("'shape': (2, 4, 1)"), "{header}");
    let values: Vec<f64> = bytes[10 + header_len..]
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    let part = |a: f64, b: f64| (b * b - a * a) / 2.0 - 0.5 * (b - a);
    let cut = [0.0, 0.0, part(0.5, 0.75), part(0.75, 1.0)];
    let fill = [-part(0.0, 0.25), -part(0.25, 0.5), 0.0, 0.0];
    for (k, expected) in cut.iter().chain(&fill).enumerate() {
        assert!((values[k] - expected).abs() < 1e-15, "{k}: {values:?}");
    }
    assert_eq!(&std::fs::read(&png).unwrap()[..8], b"\x89PNG\r\n\x1a\n");
    // A pitch: square cells, as many as cover the footprint.
    let v = json(&["cutfill", p(&ramp), "--level", "0.5", "--pitch", "0.3", "--json"]);
    assert_eq!(v["grid"]["counts"], serde_json::json!([4, 4]));
}

#[test]
fn partial_cover_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let flat = square(dir.path(), "flat.obj", 1, false, |_, _| 1.0);
    // The ramp moved right by 1/2: only [1/2, 1] × [0, 1] is common, where
    // x_ramp = x − 1/2: cut ∫ (1 − (x − 1/2)) over it = 3/8.
    let mut obj = String::from("v 0.5 0 0\nv 1.5 0 1\nv 1.5 1 1\nv 0.5 1 0\n");
    obj += "f 1 2 3\nf 1 3 4\n";
    let shifted = write(dir.path(), "shifted.obj", obj);
    let v = json(&["cutfill", p(&flat), "--design", p(&shifted), "--json"]);
    assert!(close(&v["cut"], 0.375) && close(&v["footprint_area"], 0.5), "{v}");
    assert!(v["warnings"][0].as_str().unwrap().contains("common footprint only"), "{v}");
}

#[test]
fn wrong_arguments_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let flat = square(dir.path(), "flat.obj", 1, false, |_, _| 1.0);
    let runs: Vec<Vec<&str>> = vec![
        vec!["cutfill", p(&flat)],
        vec!["cutfill", p(&flat), "--level", "1", "--design", p(&flat)],
        vec!["cutfill", p(&flat), "--level", "1", "--cells", "0,3"],
        vec!["cutfill", p(&flat), "--level", "1", "--cells", "3"],
        vec!["cutfill", p(&flat), "--level", "1", "--cells", "3,x"],
        vec!["cutfill", p(&flat), "--level", "1", "--cells", "3,3", "--pitch", "1"],
        vec!["cutfill", p(&flat), "--level", "1", "--pitch", "-1"],
        vec!["cutfill", p(&flat), "--level", "nan"],
        vec!["cutfill", p(&flat), "--level", "1", "--out", "cells.npy"],
        vec!["cutfill", p(&flat), "--level", "1", "--cells", "2,2", "--out", "cells.csv"],
    ];
    for args in runs {
        let out = meshvol(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("error"), "{args:?}");
    }
}

#[test]
fn bad_inputs_are_errors_that_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let flat = square(dir.path(), "flat.obj", 1, false, |_, _| 1.0);
    // Folded back over itself along x = 1: faces 2 and 3 lie over faces 0 and 1.
    let folded = write(
        dir.path(),
        "folded.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0 1\nv 0.5 1 1\n\
         f 1 2 3\nf 1 3 4\nf 2 5 6\nf 2 6 3\n",
    );
    let empty = write(dir.path(), "empty.stl", "solid empty\nendsolid empty\n");
    let nan = write(dir.path(), "nan.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let degenerate = write(dir.path(), "line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    let huge = write(
        dir.path(),
        "huge.obj",
        "v -1e300 -1e300 0\nv 1e300 -1e300 1e300\nv 1e300 1e300 0\nv -1e300 1e300 -1e300\n\
         f 1 2 3\nf 1 3 4\n",
    );
    let missing = dir.path().join("missing.obj");
    for (args, name) in [
        (vec!["cutfill", p(&huge), "--level", "0"], "huge.obj"),
        (vec!["cutfill", p(&folded), "--level", "0"], "folded.obj"),
        (vec!["cutfill", p(&flat), "--design", p(&folded)], "folded.obj"),
        (vec!["cutfill", p(&empty), "--level", "0"], "empty.stl"),
        (vec!["cutfill", p(&nan), "--level", "0"], "nan.obj"),
        (vec!["cutfill", p(&flat), "--design", p(&missing)], "missing.obj"),
    ] {
        let out = meshvol(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(name), "{args:?}: {stderr}");
        if name == "folded.obj" {
            assert!(
                stderr.contains("faces 0 and 2") && stderr.contains("height field"),
                "{stderr}"
            );
        }
        let mut args = args;
        args.push("--json");
        let line: Value = serde_json::from_slice(&meshvol(&args).stdout).unwrap();
        assert!(line["error"].as_str().unwrap().contains(name), "{line}");
    }
    // A surface of one degenerate triangle: measured, nothing in plan, and said so; a
    // grid over no footprint is an error.
    let v = json(&["cutfill", p(&degenerate), "--level", "0", "--json"]);
    assert_eq!(f(&v["footprint_area"]), 0.0);
    assert!(v["warnings"].to_string().contains("no footprint in common"), "{v}");
    let out = meshvol(&["cutfill", p(&degenerate), "--level", "0", "--cells", "2,2"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("line.obj"));
}
