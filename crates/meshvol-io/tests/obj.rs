//! Wavefront OBJ.

mod common;

use common::*;
use meshvol::{Faces, Surface};
use meshvol_io::{read, Format, LoadedSurface, Location};

const ORIGIN: [f64; 3] = [-1.0, 2.0, 3.5];
const SIZE: [f64; 3] = [2.0, 3.0, 4.0];

/// The box as OBJ: its corners as `v` lines, faces as quads (or triangles).
fn box_obj(quads: bool) -> String {
    let mut s = String::from("# a box\nmtllib box.mtl\no box\n");
    for p in box_corners(ORIGIN, SIZE) {
        s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    s += "vt 0 0\nvn 0 0 1\ng sides\nusemtl red\ns off\n";
    for q in BOX_QUADS {
        let q = q.map(|i| i + 1);
        if quads {
            s += &format!("f {} {} {} {}\n", q[0], q[1], q[2], q[3]);
        } else {
            s += &format!("f {} {} {}\nf {} {} {}\n", q[0], q[1], q[2], q[0], q[2], q[3]);
        }
    }
    s
}

fn mesh_faces(l: &meshvol_io::Loaded) -> &Faces {
    match &l.surface {
        LoadedSurface::Mesh(m) => m.faces(),
        LoadedSurface::StlSoup(_) => panic!("not a mesh"),
    }
}

#[test]
fn quads_are_kept_as_polygons() {
    let loaded = read_as("box.obj", box_obj(true)).unwrap();
    assert_eq!(loaded.format, Format::Obj);
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert_eq!((loaded.vertex_count(), loaded.face_count(), loaded.triangle_count()), (8, 6, 12));
    assert!(matches!(mesh_faces(&loaded), Faces::Polygons { .. }));
    assert_close(volume(&loaded.surface), 24.0, 1e-12);
}

#[test]
fn all_triangles_are_stored_as_triangles() {
    let loaded = read_as("box.obj", box_obj(false)).unwrap();
    assert!(matches!(mesh_faces(&loaded), Faces::Triangles(t) if t.len() == 12));
    assert_close(volume(&loaded.surface), 24.0, 1e-12);
}

#[test]
fn polygon_of_many_vertices() {
    // A prism over a regular 12-gon: two 12-gon caps and 12 quads.
    let n = 12;
    let (r, h) = (2.0, 3.0);
    let mut s = String::new();
    for z in [0.0, h] {
        for i in 0..n {
            let a = i as f64 * std::f64::consts::TAU / n as f64;
            s += &format!("v {} {} {}\n", r * a.cos(), r * a.sin(), z);
        }
    }
    let bottom: Vec<String> = (1..=n).rev().map(|i| i.to_string()).collect();
    let top: Vec<String> = (n + 1..=2 * n).map(|i| i.to_string()).collect();
    s += &format!("f {}\nf {}\n", bottom.join(" "), top.join(" "));
    for i in 0..n {
        let j = (i + 1) % n;
        s += &format!("f {} {} {} {}\n", i + 1, j + 1, j + n + 1, i + n + 1);
    }
    let loaded = read_as("prism.obj", s).unwrap();
    assert_eq!(loaded.face_count(), 14);
    assert_eq!(loaded.triangle_count(), 2 * 10 + 12 * 2);
    // Area of the regular 12-gon: n/2 r² sin(2π/n).
    let area = n as f64 / 2.0 * r * r * (std::f64::consts::TAU / n as f64).sin();
    assert_close(volume(&loaded.surface), area * h, 1e-12);
}

#[test]
fn negative_indices_and_slash_tokens() {
    // Each face is written right after its vertices, with negative indices.
    let mut s = String::new();
    for t in tetra_triangles() {
        for p in t {
            s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
        }
        s += "vn 0 0 1\nvt 0.5 0.5\n";
        s += "f -3/-1/-1 -2//-1 -1/1\n";
    }
    let loaded = read_as("neg.obj", s).unwrap();
    assert_eq!(loaded.vertex_count(), 12);
    assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-15);
    assert_eq!(triangles(&loaded.surface), tetra_triangles());
}

#[test]
fn v_with_colour_columns_and_vn_tokens_and_crlf() {
    let mut s = String::new();
    for p in box_corners(ORIGIN, SIZE) {
        s += &format!("v {} {} {} 0.5 0.25 nan\r\n", p[0], p[1], p[2]);
    }
    s += "vn 1 0 0\r\n";
    for q in BOX_QUADS {
        let q = q.map(|i| i + 1);
        s += &format!("f {}//1 {}//1 {}//1 {}//1 # comment\r\n", q[0], q[1], q[2], q[3]);
    }
    let loaded = read_as("c.obj", s).unwrap();
    assert_close(volume(&loaded.surface), 24.0, 1e-12);
}

#[test]
fn faces_may_name_later_vertices() {
    let s = "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
    let loaded = read_as("late.obj", s).unwrap();
    assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-15);
}

#[test]
fn line_and_point_elements_are_counted_in_one_warning() {
    let s = box_obj(true) + "l 1 2\nl 2 3 4\nl 5 6\np 1\np 2 3\nvp 0.5\n";
    let loaded = read_as("w.obj", s).unwrap();
    assert_eq!(loaded.warnings, vec!["ignored 3 line elements (l) and 2 point elements (p)"]);
    assert_close(volume(&loaded.surface), 24.0, 1e-12);
    let loaded = read_as("w.obj", box_obj(true) + "l 1 2\nl 2 3\nl 5 6\n").unwrap();
    assert_eq!(loaded.warnings, vec!["ignored 3 line elements (l)"]);
    let loaded = read_as("w.obj", box_obj(true) + "curv 0 1 1 2\nsurf 0 1 0 1 1\n").unwrap();
    assert_eq!(loaded.warnings, vec!["ignored 2 unsupported statements (curv, surf)"]);
}

#[test]
fn errors_carry_lines() {
    let good = box_obj(true);
    let line_of = |needle: &str| good.lines().position(|l| l == needle).unwrap() as u64 + 1;
    let cases: &[(&str, &str, &str)] = &[
        ("f 1 3 4 2", "f 1 3 0 2", "vertex index 0: OBJ indices start at 1"),
        ("f 1 3 4 2", "f 1 3 9 2", "vertex index 9 is out of range: the file has 8 vertices"),
        (
            "f 1 3 4 2",
            "f 1 3 -9 2",
            "negative vertex index points before the first vertex (1 too far back)",
        ),
        // Faces of fewer than 3 vertices are skipped with a warning: tests/forgiving.rs.
        ("f 1 3 4 2", "f 1 3 x 2", "invalid vertex index 'x'"),
        ("f 1 3 4 2", "f 1 3 4.5 2", "invalid vertex index '4.5'"),
        ("f 1 3 4 2", "f 1 3 99999999999999999 2", "vertex index '99999999999999999' is too large"),
    ];
    for (from, to, message) in cases {
        let line = line_of(from);
        let e = read_err("e.obj", good.replacen(from, to, 1));
        assert_eq!(
            (e.location.clone(), e.message.as_str()),
            (Some(Location::Line(line)), *message),
            "{to}"
        );
        assert_eq!(e.to_string(), format!("e.obj: line {line}: {message}"));
    }
    let v = good.lines().find(|l| l.starts_with("v ")).unwrap().to_string();
    let line = line_of(&v);
    for (to, message) in [
        ("v 1 2", "expected 3 coordinates after 'v', found 2"),
        ("v 1 nan 2", "non-finite coordinate 'nan'"),
        ("v 1 2 -inf", "non-finite coordinate '-inf'"),
        ("v 1 2 1e400", "non-finite coordinate '1e400'"),
        ("v 1 2 3x", "invalid number '3x'"),
        ("v 1 2 x", "invalid number 'x'"),
    ] {
        let e = read_err("e.obj", good.replacen(&v, to, 1));
        assert_eq!(
            (e.location.clone(), e.message.as_str()),
            (Some(Location::Line(line)), message),
            "{to}"
        );
    }
    let e = read_err("e.obj", good.clone() + "3 4 5\n");
    assert_eq!(e.message, "expected an OBJ statement, found '3'");
}

#[test]
fn errors_in_later_chunks_carry_lines() {
    // Big enough for several 1 MiB chunks; an out-of-range index near the end and a
    // negative index reaching across chunks near the start.
    let mut s = String::new();
    let mut expected = 0.0;
    for i in 0..40_000 {
        for p in box_corners([i as f64, 0.0, 0.0], [0.5, 1.0, 1.0]) {
            s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
        }
        for q in BOX_QUADS {
            let q = q.map(|k| k as i64 - 8);
            s += &format!("f {} {} {} {}\n", q[0], q[1], q[2], q[3]);
        }
        expected += 0.5;
    }
    assert!(s.len() > 4 << 20);
    let loaded = read_as("big.obj", s.clone()).unwrap();
    assert_eq!(loaded.face_count(), 240_000);
    assert_close(volume(&loaded.surface), expected, 1e-6);

    let lines: Vec<&str> = s.lines().collect();
    let target = lines.len() - 3;
    assert!(lines[target].starts_with("f "));
    let mut bad = lines.clone();
    bad[target] = "f 1 2 320001";
    let e = read_err("big.obj", bad.join("\n"));
    assert_eq!(e.location, Some(Location::Line(target as u64 + 1)));
    assert!(e.message.contains("320001"), "{e}");
}

#[test]
fn empty_and_vertex_only_files() {
    for text in ["", "# nothing\n", "\n\n"] {
        let loaded = read_as("e.obj", text).unwrap();
        assert_eq!((loaded.vertex_count(), loaded.face_count()), (0, 0));
    }
    let loaded = read_as("p.obj", "v 1 2 3\nv 4 5 6\n").unwrap();
    assert_eq!((loaded.vertex_count(), loaded.face_count()), (2, 0));
}

#[test]
fn through_the_file_system() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_temp(dir.path(), "BOX.OBJ", box_obj(true).as_bytes());
    let loaded = read(&path).unwrap();
    assert_eq!(loaded.format, Format::Obj);
    assert_close(volume(&loaded.surface), 24.0, 1e-12);
    let m = loaded.surface.into_mesh().unwrap();
    assert_eq!(m.face_count(), 6);
    assert_eq!(Surface::face_count(&m), 6);
}

#[test]
fn backslash_continues_a_line() {
    let s = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 \\\r\n1\nf 1 3 \\\n 2\nf 1 2 4\nf 1 4 3\nf 2 3 \\  \r\n\\\n4\n";
    let loaded = read_as("c.obj", s).unwrap();
    assert_eq!(loaded.vertex_count(), 4);
    assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-15);
    // An error in a joined line names the line where it starts.
    let e = read_err("c.obj", s.replace("f 2 3 \\", "f 2 0 \\"));
    assert_eq!(e.location, Some(Location::Line(10)));
}
