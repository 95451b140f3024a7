//! Numbers beyond f64 are an error (or a warning with the value left out), never a
//! silent `null` with exit status 0.

mod common;
use common::meshvol;

use std::path::{Path, PathBuf};
use std::process::Output;

fn sample() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/flanged-bushing.stl")
}

/// Fails naming `file`, with `message` on stderr and no `null` on stdout.
fn assert_refused(out: &Output, file: &str, message: &str) {
    let (stdout, stderr) =
        (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!out.status.success(), "exit 0: {stdout} {stderr}");
    assert!(stderr.contains(message) && stderr.contains(file), "{stderr}");
    assert!(!stdout.contains("null"), "{stdout}");
}

#[test]
fn an_area_beyond_f64_is_an_error() {
    // Side 1e200: the area 1e400 is beyond f64's 1.8e308.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("huge.wkt");
    std::fs::write(&path, "POLYGON((0 0,1e200 0,1e200 1e200,0 1e200,0 0))").unwrap();
    let file = path.to_str().unwrap();
    for json in [true, false] {
        let args = if json { vec!["area", file, "--json"] } else { vec!["area", file] };
        let out = meshvol(&args);
        assert_refused(&out, "huge.wkt", "the area overflows f64: coordinates up to 1e200");
        assert!(!String::from_utf8_lossy(&out.stderr).contains("the area is zero"));
    }
}

#[test]
fn an_area_within_f64_whose_moments_are_not_is_reported_without_them() {
    // Side 1e100: the area 1e200 is exact; the second moments (1e400 / 12) are not.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("large.wkt");
    std::fs::write(&path, "POLYGON((0 0,1e100 0,1e100 1e100,0 1e100,0 0))").unwrap();
    let out = meshvol(&["area", path.to_str().unwrap(), "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("the second moments overflow f64"), "{stderr}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["area"].as_f64(), Some(1e100 * 1e100));
    assert_eq!(v["perimeter"].as_f64(), Some(4e100));
    // The centroid (5e99, 5e99) is within range and kept.
    let c = &v["centroid"];
    let close = |x: &serde_json::Value| (x.as_f64().unwrap() / 5e99 - 1.0).abs() < 1e-15;
    assert!(close(&c[0]) && close(&c[1]), "{c}");
}

#[test]
fn a_mass_beyond_f64_is_an_error() {
    let sample = sample();
    for json in [true, false] {
        let mut args = vec!["volume", "--density", "1e308", sample.to_str().unwrap()];
        if json {
            args.push("--json");
        }
        let out = meshvol(&args);
        assert_refused(&out, "flanged-bushing.stl", "mass or inertia overflows f64");
    }
    // A density whose mass fits still works: 1e300 × the sample's volume (26183.3 mm³).
    let out = meshvol(&["volume", "--density", "1e290", "--json", sample.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let (mass, volume) = (v["mass"].as_f64().unwrap(), v["volume"].as_f64().unwrap());
    assert_eq!(mass, 1e290 * volume);
}

#[test]
fn cells_whose_volume_is_beyond_f64_are_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let out_path = dir.path().join("cells.csv");
    let sample = sample();
    let out = meshvol(&[
        "grid",
        sample.to_str().unwrap(),
        "--pitch",
        "1e300",
        "--out",
        out_path.to_str().unwrap(),
        "--json",
    ]);
    assert_refused(&out, "", "cells of 1e300 × 1e300 × 1e300 have a volume beyond f64");
    // One cell of 1e100 per axis is a finite grid: the sample's volume in one cell.
    let out = meshvol(&[
        "grid",
        sample.to_str().unwrap(),
        "--pitch",
        "1e100",
        "--out",
        out_path.to_str().unwrap(),
        "--json",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let (total, mesh) = (v["total"].as_f64().unwrap(), v["mesh_volume"].as_f64().unwrap());
    assert!((total - mesh).abs() <= 1e-9 * mesh, "{total} vs {mesh}");
}
