//! The JSON contract every command keeps (docs/json.md): each line has `file` and
//! `warnings`; a file that fails gives `{"file", "error"}` and exit status 1; global
//! flags work before or after the subcommand; `-q` silences every warning.

mod common;
use common::{meshvol, p, write};

use serde_json::Value;
use std::path::Path;
use std::process::Output;

/// The unit cube as OBJ triangles; `open` leaves out the top face; an `l` line makes the
/// reader warn (a line element, `l`, is read and not used).
fn cube(open: bool) -> String {
    let mut s = String::from("l 1 2\n");
    for k in 0..8 {
        s += &format!("v {} {} {}\n", k & 1, (k >> 1) & 1, (k >> 2) & 1);
    }
    let quads =
        [[0, 2, 3, 1], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5], [4, 5, 7, 6]];
    for q in &quads[..if open { 5 } else { 6 }] {
        s += &format!(
            "f {} {} {}\nf {} {} {}\n",
            q[0] + 1,
            q[1] + 1,
            q[2] + 1,
            q[0] + 1,
            q[2] + 1,
            q[3] + 1
        );
    }
    s
}

fn lines(out: &Output) -> Vec<Value> {
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

#[test]
fn every_json_line_has_file_and_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "cube.obj", cube(false));
    let wkt = write(dir.path(), "square.wkt", "POLYGON ((0 0, 2 0, 2 2, 0 2, 0 0))");
    let xyz = write(dir.path(), "corners.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
    let repaired = dir.path().join("out.stl");
    let runs: Vec<Vec<&str>> = vec![
        vec!["volume", p(&obj)],
        vec!["check", p(&obj)],
        vec!["grid", p(&obj), "--cells", "2,2,2"],
        vec!["profile", p(&obj), "--levels", "2"],
        vec!["union", p(&obj)],
        vec!["intersect", p(&obj), p(&obj)],
        vec!["section", p(&obj), "--plane", "z=0.5"],
        vec!["below", p(&obj), "--plane", "0,0,1,0.5"],
        vec!["area", p(&wkt)],
        vec!["hull", p(&xyz)],
        vec!["repair", p(&obj), "-o", p(&repaired)],
    ];
    for mut args in runs {
        args.push("--json");
        let out = meshvol(&args);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        let lines = lines(&out);
        assert_eq!(lines.len(), 1, "{args:?}");
        let v = &lines[0];
        let file = v["file"].as_str().unwrap_or_else(|| panic!("{args:?}: no file in {v}"));
        assert!(file.ends_with(Path::new(args[1]).file_name().unwrap().to_str().unwrap()));
        assert!(v["warnings"].is_array(), "{args:?}: no warnings in {v}");
    }
    // The reader's warning reaches the report of every mesh command, repair included.
    let v = &lines(&meshvol(&["repair", p(&obj), "-o", p(&repaired), "--json"]))[0];
    assert!(v["warnings"].to_string().contains("ignored"), "{v}");
}

#[test]
fn a_failed_file_is_a_json_line_with_its_error() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.obj");
    let bad_wkt = write(dir.path(), "bad.wkt", "POLYGON ((0 0, 1 0");
    let runs: Vec<Vec<&str>> = vec![
        vec!["volume", p(&missing)],
        vec!["check", p(&missing)],
        vec!["grid", p(&missing), "--cells", "2,2,2"],
        vec!["profile", p(&missing), "--levels", "2"],
        vec!["union", p(&missing)],
        vec!["intersect", p(&missing), p(&missing)],
        vec!["section", p(&missing), "--plane", "z=0"],
        vec!["below", p(&missing), "--volume", "1"],
        vec!["cutfill", p(&missing), "--level", "1"],
        vec!["area", p(&bad_wkt)],
        vec!["hull", p(&missing)],
    ];
    for mut args in runs {
        args.push("--json");
        let out = meshvol(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let lines = lines(&out);
        assert_eq!(lines.len(), 1, "{args:?}");
        let mut keys: Vec<&String> = lines[0].as_object().unwrap().keys().collect();
        keys.sort();
        assert_eq!(keys, ["error", "file"], "{args:?}");
        // Several inputs (intersect) are named together, joined by ", ".
        assert!(lines[0]["file"].as_str().unwrap().starts_with(args[1]), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("meshvol: error:"));
    }
}

#[test]
fn global_flags_work_before_or_after_the_subcommand() {
    let dir = tempfile::tempdir().unwrap();
    let open = write(dir.path(), "open.obj", cube(true));
    // Checked, the open cube is capped and warned about (and the reader warns too).
    let loud = meshvol(&["volume", p(&open)]);
    assert!(loud.status.success());
    let stderr = String::from_utf8_lossy(&loud.stderr);
    assert!(stderr.contains("hole") && stderr.contains("ignored"), "{stderr}");
    for args in [
        vec!["-q", "volume", p(&open)],
        vec!["volume", p(&open), "-q"],
        vec!["-q", p(&open)],
        vec!["--threads", "1", "-q", p(&open)],
        vec!["--quiet", "--threads=2", "volume", p(&open)],
    ] {
        let out = meshvol(&args);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert_eq!(String::from_utf8_lossy(&out.stderr), "", "{args:?}");
        assert_eq!(out.stdout, loud.stdout, "{args:?}");
    }
    // `-q check FILE` checks FILE (it once measured a file named "check"): the open cube
    // does not bound a volume, so the exit status is 1, silently.
    for args in [vec!["-q", "check", p(&open)], vec!["check", "-q", p(&open)]] {
        let out = meshvol(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stdout).contains("open"), "{args:?}");
        assert_eq!(String::from_utf8_lossy(&out.stderr), "", "{args:?}");
    }
}

#[test]
fn absurd_thread_counts_are_capped_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write(dir.path(), "cube.obj", cube(false));
    let out = meshvol(&["--threads", "100000", "volume", p(&obj), "--json"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("per core"));
    assert_eq!(lines(&out)[0]["volume"], 1.0);
}

#[test]
fn repair_refuses_a_file_without_faces_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let empty = write(dir.path(), "empty.stl", "solid empty\nendsolid empty\n");
    let out_path = dir.path().join("out.stl");
    let out = meshvol(&["repair", p(&empty), "-o", p(&out_path)]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no faces"));
    assert!(!out_path.exists());
}

#[test]
fn text_reports_print_small_numbers_in_scientific_notation() {
    // A box centred on the origin whose centroid carries rounding: any coordinate printed
    // must be short (no run of zeros after the point).
    let dir = tempfile::tempdir().unwrap();
    let mut s = String::new();
    for k in 0..8 {
        let c = |bit: usize, lo: f64, hi: f64| if k >> bit & 1 == 1 { hi } else { lo };
        s += &format!("v {} {} {}\n", c(0, -0.1, 0.3), c(1, -0.7, 0.7), c(2, -0.3, 0.1));
    }
    for q in [[0, 2, 3, 1], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5], [4, 5, 7, 6]] {
        s += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    let obj = write(dir.path(), "box.obj", &s);
    let out = meshvol(&["volume", p(&obj)]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.contains("0.0000000"), "{text}");
    assert!(text.contains("1 triangle") || text.contains("12 triangles"), "{text}");
}
