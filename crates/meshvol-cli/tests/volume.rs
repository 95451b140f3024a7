//! `meshvol volume` end to end: the built binary on files written here, checked against
//! closed forms and hand-computed values.

mod common;
use common::{box_obj, f, meshvol, p, write};

use serde_json::Value;
use std::path::Path;
use std::process::Output;

fn json_lines(out: &Output) -> Vec<Value> {
    assert!(out.status.success(), "stderr: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout.clone())
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect()
}

fn sample() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../samples/flanged-bushing.stl")
        .display()
        .to_string()
}

/// The unit cube as OBJ quads, wound outward.
const CUBE_OBJ: &str =
    "# unit cube\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

/// The unit cube as OpenSCAD's polyhedron() wants it (clockwise seen from outside), as
/// an ASCII STL with a bare `solid` line.
fn openscad_cube_stl() -> String {
    let p =
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]];
    let faces = [
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
    let mut s = String::from("solid\n");
    for t in faces {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for i in t {
            let [x, y, z] = p[i];
            s += &format!("      vertex {x} {y} {z}\n");
        }
        s += "    endloop\n  endfacet\n";
    }
    s + "endsolid\n"
}

#[test]
fn sample_part_matches_its_closed_form() {
    // Closed form of the polyhedron before its coordinates were stored as float32
    // (see crates/meshvol/examples/sample_part.rs): m·sin(2π/m)·∫∫x dA = 26183.2961038995.
    let r = &json_lines(&meshvol(&["volume", &sample(), "--json"]))[0];
    assert!((f(&r["volume"]) / 26183.2961038995 - 1.0).abs() < 1e-6);
    assert_eq!(r["format"], "stl-binary");
    assert_eq!((r["faces"].as_u64(), r["triangles"].as_u64()), (Some(3840), Some(3840)));
    // Symmetric about the z axis, between z = 0 and 30, inside radius 30.
    let c = &r["centroid"];
    assert!(f(&c[0]).abs() < 1e-9 && f(&c[1]).abs() < 1e-9);
    assert_eq!(r["bounds"]["max"][2], 30.0);
    // Exact mode agrees within the default mode's stated bound.
    let e = &json_lines(&meshvol(&[&sample(), "--json", "--exact"]))[0];
    assert_eq!(e["exact"], true);
    let diff = (f(&e["signed_volume"]) - f(&r["signed_volume"])).abs();
    assert!(diff <= f(&r["volume_error_bound"]), "{diff} > bound");
}

#[test]
fn json_has_every_documented_key() {
    let r = &json_lines(&meshvol(&[&sample(), "--json"]))[0];
    for key in [
        "file",
        "format",
        "vertices",
        "faces",
        "triangles",
        "volume",
        "signed_volume",
        "volume_error_bound",
        "area",
        "centroid",
        "inertia",
        "principal_moments",
        "principal_axes",
        "density",
        "mass",
        "bounds",
        "warnings",
    ] {
        assert!(r.get(key).is_some(), "missing key {key}");
    }
}

#[test]
fn quad_cube_and_plain_invocation() {
    let dir = tempfile::tempdir().unwrap();
    let cube = write(dir.path(), "cube.obj", CUBE_OBJ);
    let cube = cube.to_str().unwrap();
    let plain = meshvol(&[cube, "--json"]);
    let explicit = meshvol(&["volume", cube, "--json"]);
    assert_eq!(plain.stdout, explicit.stdout);
    let r = &json_lines(&plain)[0];
    assert_eq!((f(&r["volume"]), f(&r["area"])), (1.0, 6.0));
    assert_eq!((r["faces"].as_u64(), r["triangles"].as_u64()), (Some(6), Some(12)));
    assert_eq!(r["centroid"], serde_json::json!([0.5, 0.5, 0.5]));
    // A unit cube's inertia about its centroid: 1/6 on the diagonal, 0 off it.
    assert!((f(&r["inertia"][1][1]) - 1.0 / 6.0).abs() < 1e-15);
    assert!(f(&r["inertia"][0][1]).abs() < 1e-15);
    assert_eq!(r["warnings"], serde_json::json!([]));
    // Text output by default.
    let text = String::from_utf8(meshvol(&[cube]).stdout).unwrap();
    assert!(text.contains("volume") && text.contains("centroid"), "{text}");
}

#[test]
fn openscad_winding_is_reported() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "openscad.stl", openscad_cube_stl());
    let out = meshvol(&[path.to_str().unwrap(), "--json"]);
    let r = &json_lines(&out)[0];
    assert_eq!(r["format"], "stl-ascii");
    assert_eq!((f(&r["signed_volume"]), f(&r["volume"])), (-1.0, 1.0));
    assert!(r["warnings"][0].as_str().unwrap().contains("OpenSCAD"));
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning"));
}

#[test]
fn units_density_and_mass() {
    let dir = tempfile::tempdir().unwrap();
    let cube = write(dir.path(), "cube.obj", CUBE_OBJ);
    let cube = cube.to_str().unwrap();
    // A 1 in cube is 16.387064 mL (2.54³ cm³), exactly by definition of the inch.
    let r = &json_lines(&meshvol(&[cube, "--json", "--units", "in:mL"]))[0];
    assert!((f(&r["volume"]) - 16.387064).abs() < 1e-12);
    assert_eq!(r["units"]["volume"], "mL");
    assert!((f(&r["area"]) - 6.0 * 2.54 * 2.54).abs() < 1e-12);
    // Read as millimetres, the cube is 1e-3 cm³; steel at 7.85 g/cm³.
    let r = &json_lines(&meshvol(&[cube, "--json", "--units", "mm:cm", "--density", "7.85"]))[0];
    assert!((f(&r["volume"]) - 1e-3).abs() < 1e-18);
    assert!((f(&r["mass"]) - 7.85e-3).abs() < 1e-15);
    // Inertia of a cube of side s, mass m about its centroid: m·s²/6 (s = 0.1 cm).
    assert!((f(&r["inertia"][2][2]) - 7.85e-3 * 0.01 / 6.0).abs() < 1e-17);
    assert_eq!(f(&r["density"]), 7.85);
    let bad = meshvol(&[cube, "--units", "furlong"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("furlong"));
}

#[test]
fn same_output_at_any_thread_count() {
    let one = meshvol(&["--threads", "1", &sample(), "--json"]);
    let three = meshvol(&["--threads", "3", &sample(), "--json"]);
    assert_eq!(json_lines(&one), json_lines(&three));
}

#[test]
fn errors_name_the_file_and_place_and_set_the_exit_status() {
    let dir = tempfile::tempdir().unwrap();
    let cube = write(dir.path(), "cube.obj", CUBE_OBJ);
    let broken = write(dir.path(), "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    let empty = write(dir.path(), "empty.stl", "solid empty\nendsolid empty\n");
    let missing = dir.path().join("missing.stl");
    let out = meshvol(&[
        cube.to_str().unwrap(),
        broken.to_str().unwrap(),
        empty.to_str().unwrap(),
        missing.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    // The good file is still measured; each failed one has a line {"file", "error"}.
    let stdout = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<serde_json::Value> =
        stdout.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 4, "{stdout}");
    assert_eq!(lines[0]["volume"], 1.0);
    for (line, path) in lines[1..].iter().zip([&broken, &empty, &missing]) {
        let mut keys: Vec<&String> = line.as_object().unwrap().keys().collect();
        keys.sort();
        assert_eq!(keys, ["error", "file"]);
        assert_eq!(line["file"], path.to_str().unwrap());
        assert!(line["error"].as_str().unwrap().contains(path.to_str().unwrap()));
    }
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("broken.obj: line 4"), "{stderr}");
    assert!(stderr.contains("empty.stl") && stderr.contains("no faces"), "{stderr}");
    assert!(stderr.contains("missing.stl"), "{stderr}");
    // No file at all is a usage error.
    assert_eq!(meshvol(&["volume"]).status.code(), Some(2));
}

/// Caps close an open surface's holes for its volume, but its area is its own faces':
/// a flat unit square (capped by itself) has area 1, not 2; a unit box without its top
/// has area 5 and, capped, volume 1.
#[test]
fn an_open_surfaces_area_leaves_its_caps_out() {
    let dir = tempfile::tempdir().unwrap();
    let sheet = write(dir.path(), "sheet.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    let open = box_obj([0.0; 3], [1.0; 3], 1, true, true);
    let open = write(dir.path(), "open.obj", open);
    let json = |path: &Path| {
        let out = meshvol(&["volume", p(path), "--json", "-q"]);
        serde_json::from_slice::<Value>(&out.stdout).unwrap()
    };
    let (sheet, open) = (json(&sheet), json(&open));
    assert_eq!((f(&sheet["area"]), f(&sheet["volume"])), (1.0, 0.0));
    assert_eq!(f(&open["area"]), 5.0);
    assert!((f(&open["volume"]) - 1.0).abs() < 1e-15);
    assert_eq!(open["boundary_loops"], 1);
}
