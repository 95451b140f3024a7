//! Every writer writes what it reports: `repair -o` and `hull --out` read the file back,
//! and refuse (exit 1, nothing left behind) a file that is not the solid reported, unless
//! `--allow-lossy`. Checked against the closed-form volume of a UV sphere's polyhedron
//! (`meshvol::shapes::uv_sphere_volume`) and of boxes.

mod common;
use common::{f, meshvol, p, write};

use meshvol::shapes::{uv_sphere, uv_sphere_volume};
use meshvol::{Faces, Mesh};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Output;

/// The UV sphere's shape: radius 1, 32 meridians, 16 bands (planar quads between the
/// polar fans).
const SPHERE: (f64, u32, u32) = (1.0, 32, 16);

/// Far from the origin for a solid 2 across: float32 keeps steps of 0.5 to 1 there.
const FAR: [f64; 3] = [5e6, 1e7, 0.0];

/// The sphere moved to `centre`, without face `missing` when given (a planar quad: a cap
/// in its own plane restores the closed sphere's volume exactly).
fn sphere(centre: [f64; 3], missing: Option<usize>) -> Mesh {
    let (r, m, n) = SPHERE;
    let s = uv_sphere(r, m, n);
    let positions = s.positions().iter().map(|q| [0, 1, 2].map(|k| q[k] + centre[k])).collect();
    let (mut offsets, mut indices) = (vec![0], Vec::new());
    for face in 0..s.face_count() {
        if Some(face) != missing {
            indices.extend_from_slice(s.face(face));
            offsets.push(indices.len());
        }
    }
    Mesh::new(positions, Faces::Polygons { offsets, indices }).unwrap()
}

fn sphere_volume() -> f64 {
    let (r, m, n) = SPHERE;
    uv_sphere_volume(r, m, n)
}

/// A face of the sphere that is a quad (faces go meridian by meridian: the polar
/// triangle, then the quads down to the other pole).
const A_QUAD: usize = 1;

fn obj(dir: &Path, name: &str, mesh: &Mesh) -> PathBuf {
    let mut bytes = Vec::new();
    meshvol_io::write::obj(&mut bytes, mesh).unwrap();
    write(dir, name, bytes)
}

fn json(out: &Output) -> Value {
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * b.abs()
}

#[test]
fn far_open_sphere_to_stl_is_refused_and_nothing_is_left() {
    let dir = tempfile::tempdir().unwrap();
    let input = obj(dir.path(), "far.obj", &sphere(FAR, Some(A_QUAD)));
    let stl = dir.path().join("far.stl");
    let out = meshvol(&["repair", p(&input), "--cap", "-o", p(&stl)]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let e = stderr(&out);
    for word in ["far.stl", "not written", "float32", ".ply", ".obj", "--allow-lossy", "volume"] {
        assert!(e.contains(word), "{word}: {e}");
    }
    assert!(out.stdout.is_empty());
    assert_eq!(listing(dir.path()), ["far.obj"]); // no file, no temporary
                                                  // Under --json the refusal is the failed file's line.
    let out = meshvol(&["repair", p(&input), "--cap", "-o", p(&stl), "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let line: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(line["error"].as_str().unwrap().contains("float32"), "{line}");
    // A file already there is left as it was.
    std::fs::write(&stl, b"earlier").unwrap();
    let out = meshvol(&["repair", p(&input), "--cap", "-o", p(&stl)]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(std::fs::read(&stl).unwrap(), b"earlier");
    assert_eq!(listing(dir.path()), ["far.obj", "far.stl"]);
}

#[test]
fn far_open_sphere_with_allow_lossy_is_written_warned_and_both_volumes_reported() {
    let dir = tempfile::tempdir().unwrap();
    let input = obj(dir.path(), "far.obj", &sphere(FAR, Some(A_QUAD)));
    let stl = dir.path().join("far.stl");
    let out = meshvol(&["repair", p(&input), "--cap", "-o", p(&stl), "--allow-lossy", "--json"]);
    let e = stderr(&out);
    let r = json(&out);
    assert!(e.contains("warning") && e.contains("not the solid reported"), "{e}");
    assert!(r["warnings"].to_string().contains("float32"), "{r}");
    let exact = sphere_volume();
    // The solid meant: the closed sphere (the cap is in the missing quad's plane), up to
    // the rounding of the moved coordinates.
    assert!(close(f(&r["signed_volume_after"]), exact, 1e-9), "{r}");
    let w = &r["written"];
    assert!(close(f(&w["intended_volume"]), exact, 1e-9), "{w}");
    assert_eq!(
        (w["same_solid"].as_bool(), w["coordinates"].as_str()),
        (Some(false), Some("float32"))
    );
    assert_eq!(w["file"], p(&stl));
    // The written volume is what meshvol measures of the file, and float32 moved it.
    let measured = json(&meshvol(&["volume", p(&stl), "--json", "-q"]));
    assert_eq!(f(&w["volume"]), f(&measured["volume"]));
    assert!(!close(f(&w["volume"]), exact, 1e-3), "{w}");
    assert!(f(&w["duplicate_faces"]) + f(&w["collapsed_faces"]) > 0.0, "{w}");
    assert_eq!(listing(dir.path()), ["far.obj", "far.stl"]);
    // The text report says it too.
    let out = meshvol(&["repair", p(&input), "--cap", "-o", p(&stl), "--allow-lossy"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && text.contains("NOT the same solid"), "{text}");
}

#[test]
fn far_open_sphere_round_trips_through_ply_and_obj() {
    let dir = tempfile::tempdir().unwrap();
    let input = obj(dir.path(), "far.obj", &sphere(FAR, Some(A_QUAD)));
    let exact = sphere_volume();
    for name in ["out.ply", "out.obj"] {
        let path = dir.path().join(name);
        let out = meshvol(&["repair", p(&input), "--cap", "-o", p(&path), "--json"]);
        assert_eq!(stderr(&out), "", "{name}");
        let r = json(&out);
        let w = &r["written"];
        assert_eq!(w["same_solid"], true, "{name}: {w}");
        assert_eq!(w["coordinates"], "float64");
        assert_eq!(
            (w["collapsed_faces"].as_u64(), w["duplicate_faces"].as_u64()),
            (Some(0), Some(0))
        );
        assert_eq!(w["triangles"], w["intended_triangles"]);
        assert_eq!(w["closed"], true);
        // Within the stated bound of the solid meant, and of the closed form.
        let (volume, meant) = (f(&w["volume"]), f(&w["intended_volume"]));
        assert!((volume - meant).abs() <= f(&w["tolerance"]), "{name}: {w}");
        assert!(close(volume, exact, 1e-9), "{name}: {w}");
        let measured = json(&meshvol(&["volume", p(&path), "--json"]));
        assert_eq!(f(&measured["volume"]), volume);
        assert!(measured["warnings"].as_array().unwrap().is_empty(), "{measured}");
    }
}

#[test]
fn near_origin_solids_go_to_stl_silently() {
    let dir = tempfile::tempdir().unwrap();
    // An open unit cube (coordinates float32 holds exactly), capped: the same cube.
    let mut cube = String::new();
    for k in 0..8 {
        cube += &format!("v {} {} {}\n", k & 1, (k >> 1) & 1, (k >> 2) & 1);
    }
    for q in [[0, 2, 3, 1], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        cube += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    let input = write(dir.path(), "cube.obj", cube);
    let stl = dir.path().join("cube.stl");
    let out = meshvol(&["repair", p(&input), "--cap", "-o", p(&stl), "--json"]);
    let r = json(&out);
    assert_eq!(stderr(&out), "");
    assert_eq!(r["warnings"], serde_json::json!([]));
    let w = &r["written"];
    assert_eq!((w["same_solid"].as_bool(), w["format"].as_str()), (Some(true), Some("stl-binary")));
    assert_eq!((f(&w["volume"]), f(&w["intended_volume"])), (1.0, 1.0));
    assert_eq!(f(&json(&meshvol(&["volume", p(&stl), "--json"]))["volume"]), 1.0);
    // A sphere at the origin, whose coordinates float32 rounds: float32's own
    // precision is within the tolerance, so STL is fine here.
    let input = obj(dir.path(), "ball.obj", &sphere([0.0; 3], None));
    let stl = dir.path().join("ball.stl");
    let out = meshvol(&["repair", p(&input), "-o", p(&stl), "--json"]);
    let r = json(&out);
    assert_eq!(stderr(&out), "");
    assert_eq!(r["written"]["same_solid"], true, "{r}");
    assert!(close(f(&r["written"]["volume"]), sphere_volume(), 1e-6), "{r}");
    assert_eq!(listing(dir.path()), ["ball.obj", "ball.stl", "cube.obj", "cube.stl"]);
}

#[test]
fn hull_out_of_far_points_is_refused_as_stl_and_kept_as_ply() {
    let dir = tempfile::tempdir().unwrap();
    // The sphere's vertices: their hull is the sphere (a convex polyhedron).
    let mut xyz = String::new();
    for q in sphere(FAR, None).positions() {
        xyz += &format!("{} {} {}\n", q[0], q[1], q[2]);
    }
    let cloud = write(dir.path(), "far.xyz", xyz);
    let exact = sphere_volume();
    let stl = dir.path().join("hull.stl");
    let out = meshvol(&["hull", p(&cloud), "--out", p(&stl)]);
    assert_eq!(out.status.code(), Some(1));
    let e = stderr(&out);
    for word in ["hull.stl", "float32", ".ply", "--allow-lossy"] {
        assert!(e.contains(word), "{word}: {e}");
    }
    assert_eq!(listing(dir.path()), ["far.xyz"]);

    let out = meshvol(&["hull", p(&cloud), "--out", p(&stl), "--allow-lossy", "--json"]);
    assert!(stderr(&out).contains("not the solid reported"), "{}", stderr(&out));
    let r = json(&out);
    assert!(close(f(&r["volume"]), exact, 1e-9), "{r}");
    assert_eq!(f(&r["written"]["intended_volume"]), f(&r["volume"]));
    assert_eq!(r["written"]["same_solid"], false);
    assert!(!close(f(&r["written"]["volume"]), exact, 1e-3), "{r}");

    let ply = dir.path().join("hull.ply");
    let out = meshvol(&["hull", p(&cloud), "--out", p(&ply), "--json"]);
    assert_eq!(stderr(&out), "");
    let r = json(&out);
    assert_eq!(r["written"]["same_solid"], true);
    assert!(close(f(&r["written"]["volume"]), exact, 1e-9), "{r}");
    // Without --out there is no `written` key (the keys stay those of before).
    let r = json(&meshvol(&["hull", p(&cloud), "--json"]));
    assert!(r.get("written").is_none(), "{r}");
    // --allow-lossy means nothing without --out: a usage error.
    assert_eq!(meshvol(&["hull", p(&cloud), "--allow-lossy"]).status.code(), Some(2));
}
