//! The memory guard (issue 53): a file whose reading and checking would not fit in the
//! memory available is refused before it is read, naming the file, the estimate and the
//! figure available, with exit status 1; a file that fits is measured. The estimate is
//! computed here from docs/security.md's figures: a binary STL's triangles (its header)
//! times the bytes a triangle, plus the file's own bytes. `MESHVOL_MEMORY_LIMIT` stands
//! in for the machine's memory.

mod common;
use common::server::Server;
use common::{f, p, write};
use std::path::Path;
use std::process::{Command, Output};

/// docs/security.md: a binary STL's bytes a triangle, read and checked, and read alone
/// (`--no-check`).
const CHECKED: u128 = 120;
const UNCHECKED: u128 = 8;
/// docs/security.md: an OBJ's fewest file bytes a triangle, and its bytes a triangle read
/// and checked.
const OBJ_FILE: u128 = 30;
const OBJ_CHECKED: u128 = 200;

fn with_limit(limit: u128, args: &[&str]) -> Output {
    let out = Command::new(common::bin())
        .args(args)
        .env("MESHVOL_MEMORY_LIMIT", limit.to_string())
        .output()
        .unwrap();
    out
}

/// The triangles a binary STL's header declares.
fn declared(path: &Path) -> u128 {
    let bytes = std::fs::read(path).unwrap();
    u128::from(u32::from_le_bytes(bytes[80..84].try_into().unwrap()))
}

/// What the guard estimates for `path` at `per_triangle` bytes a triangle.
fn estimate(path: &Path, per_triangle: u128) -> u128 {
    declared(path) * per_triangle + u128::from(std::fs::metadata(path).unwrap().len())
}

/// The bytes a figure such as `1.2 MiB` or `900 B` stands for, and the most its
/// rounding to one decimal can hide.
fn figure(text: &str) -> (f64, f64) {
    let (value, unit) = text.split_once(' ').unwrap();
    let scale = match unit {
        "B" => 1.0,
        "KiB" => 1024.0,
        "MiB" => 1024.0 * 1024.0,
        "GiB" => 1024.0 * 1024.0 * 1024.0,
        _ => panic!("unit {unit}"),
    };
    let rounding = if unit == "B" { 0.0 } else { 0.05 * scale };
    (value.parse::<f64>().unwrap() * scale, rounding)
}

/// The text between `before` and `after` in `text`.
fn between<'a>(text: &'a str, before: &str, after: &str) -> &'a str {
    let start =
        text.find(before).unwrap_or_else(|| panic!("no '{before}' in {text}")) + before.len();
    let end = text[start..].find(after).unwrap_or_else(|| panic!("no '{after}' in {text}"));
    &text[start..start + end]
}

/// A binary STL of the box [0,2]×[0,3]×[0,4] (volume 24): 12 triangles, wound outward.
fn box_stl() -> Vec<u8> {
    let c = |i: usize| [(i & 1) as f32 * 2.0, (i >> 1 & 1) as f32 * 3.0, (i >> 2 & 1) as f32 * 4.0];
    let quads =
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let mut out = vec![0u8; 80];
    out.extend_from_slice(&12u32.to_le_bytes());
    for q in quads {
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            out.extend_from_slice(&[0u8; 12]);
            for i in t {
                for x in c(i) {
                    out.extend_from_slice(&x.to_le_bytes());
                }
            }
            out.extend_from_slice(&[0u8; 2]);
        }
    }
    out
}

#[test]
fn a_file_too_large_is_refused_with_the_estimate_and_the_figure_available() {
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/flanged-bushing.stl");
    let triangles = declared(&sample);
    for (args, doing, per_triangle) in [
        (vec!["check"], "reading and checking", CHECKED),
        (vec!["volume"], "reading and checking", CHECKED),
        (vec!["volume", "--no-check"], "reading", UNCHECKED),
    ] {
        let args: Vec<&str> = args.into_iter().chain([p(&sample)]).collect();
        let out = with_limit(100_000, &args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(out.stdout.is_empty(), "{args:?}: nothing measured");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("flanged-bushing.stl: "), "{stderr}");
        assert!(stderr.contains(&format!("{doing} {triangles} triangles needs about")), "{stderr}");
        let (need, rounding) = figure(between(&stderr, "needs about ", ";"));
        let expected = estimate(&sample, per_triangle) as f64;
        assert!((need - expected).abs() <= rounding, "{args:?}: {need} for {expected}: {stderr}");
        assert!(stderr.contains("; 97.7 KiB is available"), "{stderr}");
    }
}

#[test]
fn a_text_file_is_estimated_from_its_size() {
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/barge.obj");
    let size = u128::from(std::fs::metadata(&sample).unwrap().len());
    let triangles = size.div_ceil(OBJ_FILE);
    let out = with_limit(1000, &["check", p(&sample)]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("barge.obj: reading and checking a "), "{stderr}");
    assert!(
        stderr.contains(&format!(" OBJ (up to {triangles} triangles) needs about")),
        "{stderr}"
    );
    let (need, rounding) = figure(between(&stderr, "needs about ", ";"));
    let expected = (triangles * OBJ_CHECKED + size) as f64;
    assert!((need - expected).abs() <= rounding, "{need} for {expected}: {stderr}");
}

#[test]
fn a_file_that_fits_is_measured_and_one_byte_less_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let stl = write(dir.path(), "box.stl", box_stl());
    for (extra, per_triangle) in [(None, CHECKED), (Some("--no-check"), UNCHECKED)] {
        let need = estimate(&stl, per_triangle);
        let args: Vec<&str> = ["volume", "--json", p(&stl)].into_iter().chain(extra).collect();
        let out = with_limit(need, &args);
        assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(f(&report["volume"]), 24.0);
        let out = with_limit(need - 1, &args);
        assert_eq!(out.status.code(), Some(1), "{extra:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("box.stl: ") && stderr.contains("12 triangles"), "{stderr}");
    }
}

#[test]
fn the_server_answers_503_for_an_upload_too_large_for_its_memory() {
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/flanged-bushing.stl");
    let dir = tempfile::tempdir().unwrap();
    let stl = write(dir.path(), "box.stl", box_stl());
    // The box's estimate exactly: the box fits, the sample does not.
    let limit = estimate(&stl, CHECKED).to_string();
    let server = Server::start_in_env(&[], &[("MESHVOL_MEMORY_LIMIT", &limit)]);
    let (status, body) = server.post("/api/check?name=box.stl", &box_stl());
    assert_eq!(status, 200, "{body}");
    let report: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(f(&report["solid_volume"]), 24.0);
    let (status, body) = server.post("/api/check?name=part.stl", &std::fs::read(&sample).unwrap());
    assert_eq!(status, 503, "{body}");
    let report: serde_json::Value = serde_json::from_str(&body).unwrap();
    let error = report["error"].as_str().unwrap();
    let triangles = declared(&sample);
    assert!(error.starts_with(&format!("part.stl: reading and checking {triangles} triangles")));
    let (need, rounding) = figure(between(error, "needs about ", ";"));
    assert!((need - estimate(&sample, CHECKED) as f64).abs() <= rounding, "{error}");
}

#[test]
fn a_grid_is_held_to_the_same_figure() {
    // 10⁶ cells of one float64 each: 8,000,000 bytes, above a limit of 10⁶ bytes (976.6
    // KiB) that the file itself (24 triangles) fits in.
    let sample = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/part.obj");
    let dir = tempfile::tempdir().unwrap();
    let out_file = dir.path().join("cells.npy");
    let args = ["grid", p(&sample), "--cells", "100,100,100", "--out", p(&out_file)];
    let out = with_limit(1_000_000, &args);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("has 1000000 cells") && stderr.contains("; 976.6 KiB is available"));
    assert!(!out_file.exists());
}
