//! `--timings`: every command can say how long each stage took, in wall and CPU
//! seconds; the stages of an input are contiguous, so they add up to at most the run.

mod common;
use common::{f, meshvol};

use serde_json::Value;
use std::time::Instant;

const SAMPLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../samples/flanged-bushing.stl");

/// The `timings` list of one run's JSON, and the run's wall seconds as the test saw them.
fn timings(args: &[&str]) -> (Vec<Value>, f64) {
    let start = Instant::now();
    let out = meshvol(args);
    let seen = start.elapsed().as_secs_f64();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    let v: Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    (v["timings"].as_array().expect("a timings list").clone(), seen)
}

#[test]
fn every_measuring_command_lists_its_stages_in_order() {
    let runs: [&[&str]; 6] = [
        &["volume", SAMPLE],
        &["check", SAMPLE],
        &["grid", SAMPLE, "--cells", "4,4,4"],
        &["profile", SAMPLE, "--levels", "4"],
        &["below", SAMPLE, "--plane", "0,0,1,10"],
        &["union", SAMPLE, SAMPLE],
    ];
    for args in runs {
        let mut all = args.to_vec();
        all.extend(["--json", "--timings", "-q"]);
        let (stages, seen) = timings(&all);
        let names: Vec<&str> = stages.iter().map(|s| s["stage"].as_str().unwrap()).collect();
        assert_eq!(names.first(), Some(&"reading"), "{args:?}: {names:?}");
        assert!(names.contains(&"welding"), "{args:?}: the check's stages are listed: {names:?}");
        let (mut wall, mut peak) = (0.0, 0.0);
        for s in &stages {
            let keys: Vec<&String> = s.as_object().unwrap().keys().collect();
            assert_eq!(keys.len(), 4, "{args:?}: {s}");
            let (w, c, p) = (f(&s["wall_s"]), f(&s["cpu_s"]), f(&s["peak_mb"]));
            assert!(w >= 0.0 && c >= 0.0, "{args:?}: {s}");
            // The process's high-water mark: it never falls from one stage to the next.
            assert!(p > 0.0 && p >= peak, "{args:?}: {s} after a peak of {peak} MB");
            (wall, peak) = (wall + w, p);
        }
        assert!(wall > 0.0 && wall <= seen, "{args:?}: stages {wall} s in a run of {seen} s");
    }
}

#[test]
fn without_the_flag_there_is_no_list_and_in_text_it_goes_to_stderr() {
    let out = meshvol(&["volume", SAMPLE, "--json", "-q"]);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v.get("timings").is_none());
    let out = meshvol(&["--timings", SAMPLE, "-q"]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("timings (wall s, cpu s, peak MB)") && err.contains("welding"), "{err}");
    assert!(!String::from_utf8_lossy(&out.stdout).contains("timings"));
}

#[test]
fn no_check_runs_have_no_check_stages() {
    let (stages, _) = timings(&["volume", SAMPLE, "--no-check", "--json", "--timings"]);
    let names: Vec<&str> = stages.iter().map(|s| s["stage"].as_str().unwrap()).collect();
    assert_eq!(names, ["reading", "measuring"]);
}

#[test]
fn writing_the_cells_is_a_stage_of_its_own() {
    // The arrays' allocation and the file's writing are not counted in the kernel's
    // last stage (at 256³ with --moments, each took longer than the sweeps).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cells.npz");
    let out = out.to_str().unwrap();
    let args = ["grid", SAMPLE, "--cells", "4,4,4", "--moments", "--out", out];
    let (stages, _) = timings(&[&args[..], &["--json", "--timings", "-q"]].concat());
    let names: Vec<&str> = stages.iter().map(|s| s["stage"].as_str().unwrap()).collect();
    let at = |name: &str| names.iter().position(|n| *n == name);
    let (allocating, cutting, writing) =
        (at("allocating the cells' arrays"), at("cutting faces into cells"), at("writing"));
    assert!(allocating.is_some() && allocating < cutting && cutting < writing, "{names:?}");
    assert_eq!(writing, Some(names.len() - 1), "{names:?}");
    assert!(std::fs::metadata(out).unwrap().len() > 0);
}
