//! OFF.

mod common;

use common::*;
use meshvol::Faces;
use meshvol_io::{read, Format, LoadedSurface, Location};

const ORIGIN: [f64; 3] = [0.5, 1.0, -3.0];
const SIZE: [f64; 3] = [2.0, 3.0, 4.0];

/// The box as OFF, with `header` as the first line(s) and colours on the faces.
fn box_off(header: &str) -> String {
    common::box_off(header, ORIGIN, SIZE)
}

#[test]
fn headers() {
    for header in [
        "OFF\n8 6 12",
        "OFF 8 6 12",
        "OFF8 6 12",
        "COFF\n8 6 0",
        "NOFF 8 6",
        "CNOFF\n# counts next\n\n8 6 12",
        "8 6 12",
        "\u{feff}OFF\r\n8 6 12\r",
        "\t  OFF    8 6 12 # trailing comment",
    ] {
        let loaded = read_as("box.off", box_off(header)).unwrap();
        assert_eq!(loaded.format, Format::Off);
        assert_eq!((loaded.vertex_count(), loaded.face_count()), (8, 6), "{header}");
        assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
        assert_close(volume(&loaded.surface), 24.0, 1e-12);
    }
}

#[test]
fn comments_everywhere_and_vertex_colours() {
    let mut s = String::from("# leading comment\nOFF # the keyword\n# counts:\n8 6 12\n");
    for (i, p) in box_corners(ORIGIN, SIZE).iter().enumerate() {
        s += &format!("{} {} {} 255 0 0 255 # vertex {i}\n\n", p[0], p[1], p[2]);
    }
    s += "# faces\n";
    for q in BOX_QUADS {
        s += &format!("4 {} {} {} {} # quad\n", q[0], q[1], q[2], q[3]);
    }
    s += "# end\n";
    let loaded = read_as("c.off", s).unwrap();
    assert_close(volume(&loaded.surface), 24.0, 1e-12);
    let LoadedSurface::Mesh(m) = &loaded.surface else { panic!() };
    assert!(matches!(m.faces(), Faces::Polygons { .. }));
}

#[test]
fn triangles_are_stored_as_triangles() {
    let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut s = String::from("OFF\n4 4 6\n");
    for v in p {
        s += &format!("{} {} {}\n", v[0], v[1], v[2]);
    }
    s += "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    let loaded = read_as("t.off", s).unwrap();
    let LoadedSurface::Mesh(m) = &loaded.surface else { panic!() };
    assert!(matches!(m.faces(), Faces::Triangles(t) if t.len() == 4));
    assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-15);
    assert_eq!(triangles(&loaded.surface), tetra_triangles());
}

#[test]
fn errors_carry_lines() {
    let good = box_off("OFF\n8 6 12");
    // Line 3 is the first vertex, line 11 the first face.
    let first_vertex = good.lines().nth(2).unwrap().to_string();
    let first_face = good.lines().nth(10).unwrap().to_string();
    let last_face = good.lines().nth(15).unwrap().to_string();
    let cases: Vec<(String, &str, u64, &str)> = vec![
        (first_vertex.clone(), "1 2", 3, "expected 3 coordinates for a vertex, found 2"),
        (first_vertex.clone(), "1 nan 2", 3, "non-finite coordinate 'nan'"),
        (first_vertex.clone(), "1 inf 2", 3, "non-finite coordinate 'inf'"),
        (first_vertex.clone(), "1 2 y", 3, "invalid number 'y'"),
        // A face's indices may continue on the next lines: only the end of the file
        // leaves one short. (Faces of fewer than 3 vertices: tests/forgiving.rs.)
        (last_face, "4 0 1 2", 16, "face declares 4 vertices but the file ends after 3 indices"),
        (
            first_face.clone(),
            "4 0 1 2 8",
            11,
            "vertex index 8 is out of range: the file has 8 vertices",
        ),
        (
            first_face.clone(),
            "4 0 1 2 -1",
            11,
            "vertex index -1 is out of range: the file has 8 vertices",
        ),
        (first_face.clone(), "4 0 1 x 2", 11, "invalid vertex index 'x'"),
        (first_face.clone(), "x 0 1 2", 11, "expected the face's vertex count, found 'x'"),
        ("8 6 12".into(), "8", 2, "expected the face count"),
        ("8 6 12".into(), "-8 6 12", 2, "expected the vertex count, found '-8'"),
        ("8 6 12".into(), "99999999999 6 12", 2, "99999999999 vertices do not fit 32-bit indices"),
    ];
    for (from, to, line, message) in &cases {
        let e = read_err("e.off", good.replacen(from.as_str(), to, 1));
        assert_eq!(
            (e.location.clone(), e.message.as_str()),
            (Some(Location::Line(*line)), *message),
            "{to}"
        );
        assert_eq!(e.to_string(), format!("e.off: line {line}: {message}"));
    }
}

#[test]
fn too_few_vertices_or_faces() {
    let good = box_off("OFF\n8 6 12");
    let lines: Vec<&str> = good.lines().collect();
    // Only 5 of the 8 vertices.
    let short = lines[..7].join("\n") + "\n";
    let e = read_err("s.off", short);
    assert_eq!(e.message, "declared 8 vertices, file ends after 5");
    assert_eq!(e.location, Some(Location::Line(7)));
    // 4 of the 6 faces, with a trailing comment line.
    let short = lines[..14].join("\n") + "\n# the end\n";
    let e = read_err("s.off", short);
    assert_eq!(e.message, "declared 6 faces, file ends after 4");
    assert_eq!(e.location, Some(Location::Line(15)));
}

#[test]
fn counts_are_not_trusted_for_allocation() {
    let e = read_err("huge.off", "OFF\n4000000000 4000000000 0\n0 0 0\n");
    assert_eq!(e.message, "declared 4000000000 vertices, file ends after 1");
    let e = read_err("huge.off", "OFF\n3 999999999999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    assert_eq!(e.message, "declared 999999999999999 faces, file ends after 1");
    let e = read_err("huge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n");
    assert!(e.message.contains("4000000000 vertices but the file ends after 3"), "{e}");
}

#[test]
fn trailing_content_warns_and_empty_files() {
    let loaded = read_as("t.off", box_off("OFF 8 6 12") + "1 2\n3 4\n").unwrap();
    assert_eq!(loaded.warnings, vec!["ignored 2 lines after the 6 declared faces (from line 16)"]);
    let loaded = read_as("e.off", "OFF\n0 0 0\n").unwrap();
    assert_eq!(loaded.face_count(), 0);
    let e = read_err("e.off", "");
    assert_eq!(e.message, "empty file: no OFF header");
    let e = read_err("e.off", "# only a comment\n");
    assert_eq!(e.message, "empty file: no OFF header");
    let e = read_err("e.off", "OFF\n");
    assert!(e.message.contains("counts"), "{e}");
    let e = read_err("e.off", "OFF BINARY\n8 6 12\n");
    assert!(e.message.contains("binary OFF is not read"), "{e}");
    let e = read_err("e.off", "4OFF\n1 0 0\n1 2 3 4\n");
    assert!(e.message.contains("4D"), "{e}");
}

#[test]
fn through_the_file_system() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_temp(dir.path(), "BOX.OFF", box_off("OFF 8 6 12").as_bytes());
    let loaded = read(&path).unwrap();
    assert_close(volume(&loaded.surface), 24.0, 1e-12);
}
