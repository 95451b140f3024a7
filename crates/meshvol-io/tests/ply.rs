//! PLY: ASCII and binary, property types and order, polygon faces, lying headers.

mod common;

use common::*;
use meshvol::{Faces, Surface};
use meshvol_io::write::{ply, PlyEncoding};
use meshvol_io::{Format, LoadedSurface, Location};

const ORIGIN: [f64; 3] = [1.5, -2.0, 0.25];
const SIZE: [f64; 3] = [2.0, 3.0, 4.0];
const BOX_VOLUME: f64 = 24.0;

fn encodings() -> [(PlyEncoding, Format); 3] {
    [
        (PlyEncoding::Ascii, Format::PlyAscii),
        (PlyEncoding::BinaryLittleEndian, Format::PlyBinaryLittleEndian),
        (PlyEncoding::BinaryBigEndian, Format::PlyBinaryBigEndian),
    ]
}

#[test]
fn box_of_quads_in_every_encoding() {
    let mesh = box_mesh(ORIGIN, SIZE);
    for (encoding, format) in encodings() {
        let mut bytes = vec![];
        ply(&mut bytes, &mesh, encoding).unwrap();
        for name in ["box.ply", "box.PLY", "-"] {
            let loaded = read_as(name, bytes.clone()).unwrap();
            assert_eq!(loaded.format, format, "{name}");
            assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
            assert!(loaded.objects.is_empty());
            assert_eq!(loaded.unit, None);
            assert_eq!(
                (loaded.vertex_count(), loaded.face_count(), loaded.triangle_count()),
                (8, 6, 12)
            );
            assert_eq!(volume(&loaded.surface), BOX_VOLUME);
            let LoadedSurface::Mesh(m) = &loaded.surface else { panic!("a mesh") };
            assert_eq!(m.positions(), box_corners(ORIGIN, SIZE).as_slice());
            assert!(matches!(m.faces(), Faces::Polygons { .. }));
        }
    }
}

/// A binary file with every scalar type, properties out of the usual order, a list in the
/// vertex element, an element before the faces, and faces with other properties.
fn odd_binary(big: bool) -> Vec<u8> {
    let format = if big { "binary_big_endian" } else { "binary_little_endian" };
    let mut out = format!(
        "ply\r\nformat {format} 1.0\r\ncomment odd\r\nobj_info x\r\n\r\nelement vertex 4\r\n\
         property uchar red\r\nproperty double z\r\nproperty list uint8 float32 uv\r\n\
         property float y\r\nproperty int16 flags\r\nproperty float64 x\r\nelement edge 1\r\n\
         property list uchar int vertex_indices\r\nelement face 4\r\nproperty ushort tag\r\n\
         property list ushort uint vertex_index\r\nproperty char last\r\nend_header\r\n"
    )
    .into_bytes();
    macro_rules! put {
        ($v:expr) => {
            if big {
                out.extend_from_slice(&$v.to_be_bytes())
            } else {
                out.extend_from_slice(&$v.to_le_bytes())
            }
        };
    }
    let p: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for (i, v) in p.iter().enumerate() {
        out.push(200); // red
        put!(v[2]);
        out.push(i as u8 % 3); // uv list
        for _ in 0..i % 3 {
            put!(0.5f32);
        }
        put!(v[1] as f32);
        put!(-7i16);
        put!(v[0]);
    }
    out.push(2); // the edge
    put!(0i32);
    put!(1i32);
    for t in [[0u32, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
        put!(9u16);
        put!(3u16);
        for i in t {
            put!(i);
        }
        out.push(0xff);
    }
    out
}

#[test]
fn any_property_order_and_type() {
    for big in [false, true] {
        let loaded = read_as("odd.ply", odd_binary(big)).unwrap();
        assert_eq!(loaded.face_count(), 4);
        assert_eq!(volume(&loaded.surface), 1.0 / 6.0);
    }
    let ascii = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float nx\nproperty double \
                 z\nproperty list uchar float uv\nproperty float y\nproperty int x\nelement \
                 face 2\nproperty list int uchar vertex_indices\nproperty uchar flag\nend_header\n\
                 nan 0 0 0 0\n-1 0 2 1 1 0 1\n1e30 0 1 3 1 0\n\n0 1 0 0 0\n\
                 4 0 3 2 1 7\n   3 1 2 3    9\n";
    let loaded = read_as("a.ply", ascii).unwrap();
    let (o, x, y, z) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    assert_eq!(loaded.face_count(), 2);
    assert_eq!(triangles(&loaded.surface), vec![[o, z, y], [o, y, x], [x, y, z]]);
}

#[test]
fn faces_of_fewer_than_three_vertices_are_skipped() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                property float z\nelement face 6\nproperty list uchar int vertex_indices\n\
                end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n0\n3 0 1 3\n2 1 2\n3 0 3 2\n\
                3 1 2 3\n";
    let loaded = read_as("t.ply", text).unwrap();
    assert_eq!(loaded.face_count(), 4);
    assert_eq!(volume(&loaded.surface), 1.0 / 6.0);
    assert_eq!(loaded.warnings.len(), 1);
    assert!(
        loaded.warnings[0].contains("skipped 2 faces") && loaded.warnings[0].contains("line 15"),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn faces_of_different_sizes_in_binary() {
    // A square pyramid: a quad base, then triangles (the fixed-size guess fails).
    let p = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.0, 2.0, 0.0], [1.0, 1.0, 3.0]];
    let faces: [&[u32]; 5] = [&[0, 3, 2, 1], &[0, 1, 4], &[1, 2, 4], &[2, 3, 4], &[3, 0, 4]];
    let mesh = meshvol::Mesh::from_polygons(p.to_vec(), faces).unwrap();
    for (encoding, _) in encodings() {
        let mut bytes = vec![];
        ply(&mut bytes, &mesh, encoding).unwrap();
        let loaded = read_as("pyramid.ply", bytes).unwrap();
        assert_eq!(loaded.triangle_count(), 6);
        assert_close(volume(&loaded.surface), 4.0 * 3.0 / 3.0, 1e-15);
    }
}

#[test]
fn point_clouds_have_no_faces() {
    let text = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
                property float z\nend_header\n0 0 0\n1 2 3\n";
    let loaded = read_as("points.ply", text).unwrap();
    assert_eq!((loaded.vertex_count(), loaded.face_count()), (2, 0));
    let empty = read_as("e.ply", "ply\nformat binary_little_endian 1.0\nend_header\n").unwrap();
    assert_eq!(empty.face_count(), 0);
}

#[test]
fn large_files_read_in_parallel_chunks() {
    // More records than one parallel chunk (64K), more bytes than one ASCII chunk (1 MiB).
    let sphere = meshvol::shapes::uv_sphere(2.0, 400, 201).triangulated();
    assert!(sphere.face_count() > 150_000);
    let expected = volume(&sphere);
    for (encoding, _) in encodings() {
        let mut bytes = vec![];
        ply(&mut bytes, &sphere, encoding).unwrap();
        let loaded = read_as("sphere.ply", bytes).unwrap();
        let LoadedSurface::Mesh(m) = &loaded.surface else { panic!() };
        assert_eq!(m, &sphere);
        assert_eq!(volume(&loaded.surface), expected);
    }
}

#[test]
fn lying_headers_fail_fast() {
    for format in ["binary_little_endian", "binary_big_endian", "ascii"] {
        let text = format!(
            "ply\nformat {format} 1.0\nelement vertex 4000000000\nproperty float x\nproperty \
             float y\nproperty float z\nelement face 1000000000000\nproperty list uchar int \
             vertex_indices\nend_header\n0 0 0\n"
        );
        // Refused from the header: reading 4·10⁹ vertices (or allocating for them) would
        // not come back with this error.
        let e = read_err("lie.ply", text);
        assert!(e.message.contains("4000000000"), "{e}");
        // Counts beyond 32-bit indices are refused from the header.
        let text = format!(
            "ply\nformat {format} 1.0\nelement vertex 1000000000000\nproperty float x\n\
             property float y\nproperty float z\nend_header\n"
        );
        let e = read_err("lie.ply", text);
        assert_eq!(e.location, Some(Location::Line(3)));
        assert!(e.message.contains("32-bit"), "{e}");
    }
    // Faces that claim more than the file holds, read record by record (empty faces).
    let text = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n\
                property float y\nproperty float z\nelement face 1000000000000\nproperty list \
                uint int vertex_indices\nend_header\n\0\0\0\0";
    let e = read_err("lie.ply", text);
    assert!(e.message.contains("ends inside face 1"), "{e}");
}

#[test]
fn errors_say_where() {
    let mesh = box_mesh(ORIGIN, SIZE);
    let mut bytes = vec![];
    ply(&mut bytes, &mesh, PlyEncoding::BinaryLittleEndian).unwrap();
    let header = bytes.len() - 8 * 24 - 6 * 17;

    let mut truncated = bytes.clone();
    truncated.truncate(header + 8 * 24 + 17 * 2 + 5);
    let e = read_err("t.ply", truncated);
    assert!(matches!(e.location, Some(Location::Byte(_))), "{e}");
    assert!(e.message.contains("face 2"), "{e}");

    let mut bad_index = bytes.clone();
    let third_face = header + 8 * 24 + 17 * 3 + 1 + 4;
    bad_index[third_face..third_face + 4].copy_from_slice(&8u32.to_le_bytes());
    let e = read_err("t.ply", bad_index);
    assert_eq!(e.location, Some(Location::Face(3)));
    assert!(e.message.contains("vertex index 8 is out of range"), "{e}");

    let mut nan = bytes.clone();
    nan[header + 24 * 5 + 8..header + 24 * 5 + 16].copy_from_slice(&f64::NAN.to_le_bytes());
    let e = read_err("t.ply", nan);
    assert_eq!(e.location, Some(Location::Byte((header + 24 * 5 + 8) as u64)));
    assert!(e.message.contains("vertex 5") && e.message.contains("(y)"), "{e}");

    let ascii = |body: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
             end_header\n{body}"
        )
    };
    let cases = [
        ("0 0 0\n1 0 0\n0 1\n3 0 1 2\n", 12, "the line ends before 'z'"),
        ("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 13, "vertex index 3 is out of range"),
        ("0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 13, "vertex index -1 is out of range"),
        ("0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n", 12, "non-finite coordinate 'inf'"),
        ("0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n", 11, "invalid number 'x'"),
        ("0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 13, "the face declares 4 vertices"),
        ("0 0 0\n1 0 0\n", 12, "declares 3 vertex elements, but the file ends after 2"),
    ];
    for (body, line, message) in cases {
        let e = read_err("a.ply", ascii(body));
        assert_eq!(e.location, Some(Location::Line(line)), "{body:?}: {e}");
        assert!(e.message.contains(message), "{body:?}: {e}");
    }

    let headers = [
        ("ply\nformat ascii 2.0\nend_header\n", 2, "version '2.0'"),
        ("ply\nformat binary 1.0\nend_header\n", 2, "unknown format 'binary'"),
        ("ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n", 4, "unknown property type 'real'"),
        ("ply\nformat ascii 1.0\nproperty float x\nend_header\n", 3, "before any 'element'"),
        ("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n", 3, "no property 'y'"),
        ("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n", 3, "integer type"),
        ("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", 3, "invalid element count"),
        ("ply\nformat ascii 1.0\nelement vertex 1\n", 3, "without 'end_header'"),
    ];
    for (text, line, message) in headers {
        let e = read_err("h.ply", text);
        assert_eq!(e.location, Some(Location::Line(line)), "{text:?}: {e}");
        assert!(e.message.contains(message), "{text:?}: {e}");
    }
}

#[test]
fn extra_values_on_a_line_are_ignored_with_a_warning() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                property float z\nelement face 4\nproperty list uchar int vertex_indices\n\
                end_header\n0 0 0\n1 0 0 7 7\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3 9\n3 0 3 2\n3 1 2 3\n";
    let loaded = read_as("t.ply", text).unwrap();
    assert_eq!(volume(&loaded.surface), 1.0 / 6.0);
    assert_eq!(
        loaded.warnings,
        ["2 lines have more values than their element's properties (the first is line 11): the \
          extra values were ignored"]
    );
}

#[test]
fn trailing_data_is_reported() {
    let mut bytes = vec![];
    ply(&mut bytes, &box_mesh(ORIGIN, SIZE), PlyEncoding::BinaryBigEndian).unwrap();
    bytes.extend_from_slice(b"xyz");
    let loaded = read_as("t.ply", bytes).unwrap();
    assert!(loaded.warnings[0].contains("3 bytes after"), "{:?}", loaded.warnings);
    let mut text = vec![];
    ply(&mut text, &box_mesh(ORIGIN, SIZE), PlyEncoding::Ascii).unwrap();
    text.extend_from_slice(b"1 2 3\n");
    let loaded = read_as("t.ply", text).unwrap();
    assert_eq!(loaded.warnings, vec!["ignored 1 lines after the declared elements"]);
    assert_eq!(loaded.surface.face_count(), 6);
}
