//! `meshvol check`, `meshvol repair`, and the solid-aware `meshvol volume`, end to end on
//! boxes whose volumes are known by construction.

mod common;
use common::{f, meshvol};

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Output;

fn json(out: &Output) -> Value {
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    serde_json::from_str(text.lines().next().expect("a JSON line")).unwrap()
}

/// OBJ text for axis-aligned boxes, each wound outward or inward, dropping face
/// `missing` of box `k` when given.
fn boxes(list: &[([f64; 3], [f64; 3], bool)], missing: Option<(usize, usize)>) -> String {
    let quads =
        [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
    let mut s = String::new();
    for (k, (lo, hi, outward)) in list.iter().enumerate() {
        for c in 0..8 {
            let x = if c % 4 == 1 || c % 4 == 2 { hi[0] } else { lo[0] };
            let y = if c % 4 >= 2 { hi[1] } else { lo[1] };
            let z = if c >= 4 { hi[2] } else { lo[2] };
            s += &format!("v {x} {y} {z}\n");
        }
        for (f, q) in quads.iter().enumerate() {
            if missing == Some((k, f)) {
                continue;
            }
            let mut q = q.map(|i| i + 1 + 8 * k);
            if !outward {
                q.reverse();
            }
            s += &format!("f {} {} {} {}\n", q[0], q[1], q[2], q[3]);
        }
    }
    s
}

fn file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn cavity_wound_like_a_solid_is_still_subtracted() {
    let dir = tempfile::tempdir().unwrap();
    // 2×2×2 box with a 1×1×1 cavity whose faces point outward like a solid's.
    let p = file(
        dir.path(),
        "cavity.obj",
        &boxes(&[([0.0; 3], [2.0; 3], true), ([0.5; 3], [1.5; 3], true)], None),
    );
    let p = p.to_str().unwrap();
    let out = meshvol(&["check", p, "--json"]);
    assert_eq!(out.status.code(), Some(0));
    let r = json(&out);
    assert_eq!((r["shells"].as_u64(), r["cavities"].as_u64()), (Some(2), Some(1)));
    assert_eq!((r["closed"].as_bool(), r["bounds_a_volume"].as_bool()), (Some(true), Some(true)));
    assert_eq!(r["orientation"], "mixed");
    assert_eq!(f(&r["solid_volume"]), 7.0);
    assert_eq!(r["shell_details"][1]["parent"], 0);
    let v = json(&meshvol(&["volume", p, "--json"]));
    assert_eq!(f(&v["volume"]), 7.0);
    assert_eq!(f(&v["signed_volume"]), 9.0); // the plain sum, as the file is wound
    assert_eq!(v["cavities"], 1); // check facts are in volume's JSON too
                                  // Skipping the check gives the plain magnitude and no topology keys.
    let raw = json(&meshvol(&["volume", p, "--json", "--no-check"]));
    assert_eq!(f(&raw["volume"]), 9.0);
    assert!(raw.get("cavities").is_none());
    // The text report leads with the verdict.
    let text = String::from_utf8(meshvol(&["check", p]).stdout).unwrap();
    assert!(
        text.lines().next().unwrap().contains("closed, 2 shells, 1 cavity: volume is exact"),
        "{text}"
    );
}

#[test]
fn open_box_is_capped_and_check_fails() {
    let dir = tempfile::tempdir().unwrap();
    let p = file(dir.path(), "open.obj", &boxes(&[([0.0; 3], [1.0; 3], true)], Some((0, 1))));
    let p = p.to_str().unwrap();
    let out = meshvol(&["check", p, "--json"]);
    assert_eq!(out.status.code(), Some(1)); // gates a pipeline
    let r = json(&out);
    assert_eq!((r["boundary_edges"].as_u64(), r["boundary_loops"].as_u64()), (Some(4), Some(1)));
    assert!(r["verdict"].as_str().unwrap().contains("open"));
    let v = json(&meshvol(&["volume", p, "--json"]));
    assert_eq!((f(&v["volume"]), f(&v["volume_uncertainty"])), (1.0, 0.0)); // a flat hole
                                                                            // Repair with caps writes a closed box.
    let fixed = dir.path().join("fixed.stl");
    let out = meshvol(&["repair", p, "-o", fixed.to_str().unwrap(), "--cap", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary = json(&out);
    assert_eq!(
        (summary["holes_capped"].as_u64(), summary["cap_triangles"].as_u64()),
        (Some(1), Some(4))
    );
    let again = meshvol(&["check", fixed.to_str().unwrap(), "--json"]);
    assert_eq!(again.status.code(), Some(0));
    assert_eq!(f(&json(&again)["solid_volume"]), 1.0);
}

#[test]
fn overlapping_boxes_point_to_union() {
    let dir = tempfile::tempdir().unwrap();
    let text = boxes(&[([0.0; 3], [1.0; 3], true), ([0.5, 0.6, 0.7], [1.5, 1.6, 1.7], true)], None);
    let p = file(dir.path(), "overlap.obj", &text);
    let out = meshvol(&["check", p.to_str().unwrap(), "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let r = json(&out);
    assert_eq!(r["overlapping_shells"], serde_json::json!([[0, 1]]));
    assert!(r["verdict"].as_str().unwrap().contains("meshvol union"));
    // Skipping the crossing search leaves only what the rays can see: still found, as
    // each box has a corner inside the other.
    let quick = json(&meshvol(&["check", p.to_str().unwrap(), "--json", "--no-intersections"]));
    assert_eq!(quick["self_intersections"], Value::Null);
    assert_eq!(quick["overlapping_shells"], serde_json::json!([[0, 1]]));
}

#[test]
fn inward_file_is_named_and_repaired() {
    let dir = tempfile::tempdir().unwrap();
    let p = file(dir.path(), "inward.obj", &boxes(&[([0.0; 3], [3.0; 3], false)], None));
    let r = json(&meshvol(&["check", p.to_str().unwrap(), "--json"]));
    assert_eq!((r["orientation"].as_str(), r["winding"].as_str()), (Some("inward"), Some("cw")));
    let out = dir.path().join("outward.obj");
    let summary =
        json(&meshvol(&["repair", p.to_str().unwrap(), "-o", out.to_str().unwrap(), "--json"]));
    assert_eq!(summary["faces_flipped"], 6);
    assert_eq!(
        (f(&summary["signed_volume_before"]), f(&summary["signed_volume_after"])),
        (-27.0, 27.0)
    );
    let r = json(&meshvol(&["check", out.to_str().unwrap(), "--json"]));
    assert_eq!(r["winding"], "ccw");
}

/// Corpus facts checked against independent tools (skips when ../shared is absent).
#[test]
fn corpus_verdicts_agree_with_independent_tools() {
    let corpus =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/trimesh-models");
    if !corpus.exists() {
        eprintln!("corpus not found at {}, skipping", corpus.display());
        return;
    }
    let check =
        |name: &str| json(&meshvol(&["check", corpus.join(name).to_str().unwrap(), "--json"]));
    // manifold3d's boolean union of box.STL's 10 bodies is 16.0821 against a sum of
    // 16.0845 (counter.unitsmm.STL: 888806.38 against 888809.01): their bodies overlap,
    // which trimesh (watertight, volume = the sum) does not report.
    for name in ["box.STL", "counter.unitsmm.STL"] {
        let r = check(name);
        assert!(!r["overlapping_shells"].as_array().unwrap().is_empty(), "{name}");
    }
    // CAD exports whose repeated vertices differ in the last bits: closed once welded
    // within 1e-9 of the size (trimesh merges them too and calls them watertight).
    for name in ["angle_block.STL", "featuretype.STL", "idler_riser.STL"] {
        let r = check(name);
        assert_eq!(r["bounds_a_volume"], true, "{name}: {}", r["verdict"]);
        assert!(r["weld_tolerance"].as_f64().is_some(), "{name}");
    }
}
