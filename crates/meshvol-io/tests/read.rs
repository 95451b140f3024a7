//! Choosing the format: extensions, content, errors that name the file.

mod common;

use std::path::Path;

use common::*;
use meshvol_io::{read, Format, Location, ReadError};

fn obj_tetra() -> String {
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n".into()
}

#[test]
fn format_names() {
    let names: Vec<String> = [Format::StlBinary, Format::StlAscii, Format::Obj, Format::Off]
        .iter()
        .map(|f| f.to_string())
        .collect();
    assert_eq!(names, ["stl-binary", "stl-ascii", "obj", "off"]);
    assert_eq!(Format::Obj.name(), "obj");
}

#[test]
fn unknown_extensions_are_sniffed() {
    let cases: Vec<(Vec<u8>, Format)> = vec![
        (binary_stl("solid x", &tetra_triangles()), Format::StlBinary),
        (binary_stl("", &tetra_triangles()), Format::StlBinary),
        (ascii_solid("x", &tetra_triangles(), "\n").into_bytes(), Format::StlAscii),
        (obj_tetra().into_bytes(), Format::Obj),
        (format!("# c\n{}", obj_tetra()).into_bytes(), Format::Obj),
        (
            b"OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
                .to_vec(),
            Format::Off,
        ),
    ];
    for name in ["mesh.dat", "mesh", "mesh.txt"] {
        for (bytes, format) in &cases {
            let loaded = read_as(name, bytes.clone()).unwrap();
            assert_eq!(loaded.format, *format);
            assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-7);
        }
    }
}

#[test]
fn unrecognised_content_is_a_clear_error() {
    let e = read_err("model.ply", "ply\nformat ascii 1.0\nend_header\n");
    assert_eq!(e.location, None);
    assert_eq!(
        e.to_string(),
        "model.ply: the extension '.ply' is not one of .stl, .obj, .off, and the content looks like none of STL, OBJ, OFF"
    );
    let e = read_err("noext", "");
    assert!(e.message.contains("no extension") && e.message.contains("empty"), "{e}");
    let e = read_err("x.3mf", vec![0x50, 0x4b, 3, 4, 0, 0, 0, 0]);
    assert!(e.message.contains(".3mf"), "{e}");
}

#[test]
fn file_system_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.stl");
    let e = read(&missing).unwrap_err();
    assert_eq!(e.path, missing);
    assert!(e.to_string().starts_with(&format!("{}: ", missing.display())), "{e}");
    let e = read(dir.path()).unwrap_err();
    assert!(e.message.contains("directory"), "{e}");
}

#[test]
fn empty_files() {
    let dir = tempfile::tempdir().unwrap();
    for (name, ok) in [("e.stl", false), ("e.obj", true), ("e.off", false), ("e.xyz", false)] {
        let path = write_temp(dir.path(), name, b"");
        match read(&path) {
            Ok(l) => {
                assert!(ok, "{name}");
                assert_eq!(l.face_count(), 0);
            }
            Err(e) => {
                assert!(!ok, "{name}: {e}");
                assert!(e.message.contains("empty"), "{e}");
            }
        }
    }
}

#[test]
fn read_error_display() {
    let e = ReadError {
        path: "a/b.stl".into(),
        location: Some(Location::Line(12)),
        message: "expected 3 coordinates after 'vertex', found 2".into(),
    };
    assert_eq!(e.to_string(), "a/b.stl: line 12: expected 3 coordinates after 'vertex', found 2");
    let e = ReadError { location: Some(Location::Byte(84)), message: "m".into(), ..e };
    assert_eq!(e.to_string(), "a/b.stl: byte 84: m");
    let e = ReadError { location: Some(Location::Face(7)), ..e };
    assert_eq!(e.to_string(), "a/b.stl: face 7: m");
    let e = ReadError { location: None, ..e };
    assert_eq!(e.to_string(), "a/b.stl: m");
    let _: &dyn std::error::Error = &e;
    assert_eq!(e.path, Path::new("a/b.stl"));
}
