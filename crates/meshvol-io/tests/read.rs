//! Choosing the format: extensions, content, errors that name the file.

mod common;

use std::path::Path;

use common::*;
use meshvol_io::{read, Format, FormatSource, Location, ReadError};

fn obj_tetra() -> String {
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n".into()
}

#[test]
fn format_names() {
    let names: Vec<String> = [
        Format::StlBinary,
        Format::StlAscii,
        Format::Obj,
        Format::Off,
        Format::PlyAscii,
        Format::PlyBinaryLittleEndian,
        Format::PlyBinaryBigEndian,
        Format::ThreeMf,
        Format::Gltf,
        Format::Glb,
    ]
    .iter()
    .map(|f| f.to_string())
    .collect();
    assert_eq!(
        names,
        [
            "stl-binary",
            "stl-ascii",
            "obj",
            "off",
            "ply-ascii",
            "ply-binary-le",
            "ply-binary-be",
            "3mf",
            "gltf",
            "glb"
        ]
    );
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
    for name in ["mesh.dat", "mesh", "mesh.txt", "-"] {
        for (bytes, format) in &cases {
            let loaded = read_as(name, bytes.clone()).unwrap();
            assert_eq!(loaded.format, *format);
            assert_eq!(loaded.format_source, FormatSource::Content);
            assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-7);
        }
    }
}

#[test]
fn unrecognised_content_is_a_clear_error() {
    let e = read_err("model.xyz", "1 2 3\n4 5 6\n");
    assert_eq!(e.location, None);
    assert_eq!(
        e.to_string(),
        "model.xyz: the extension '.xyz' is not one of .stl, .obj, .off, .ply, .3mf, .gltf, .glb, and the content looks like none of STL, OBJ, OFF, PLY, 3MF, glTF"
    );
    let e = read_err("noext", "");
    assert!(e.message.contains("no extension") && e.message.contains("empty"), "{e}");
    let e = read_err("x.3mf", vec![0x50, 0x4b, 3, 4, 0, 0, 0, 0]);
    assert!(e.message.contains("zip"), "{e}");
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
        budget: None,
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

#[test]
fn content_that_contradicts_the_extension_wins_with_a_warning() {
    // A .stl that is OBJ text, a .obj that is OFF, a .ply that is a binary STL.
    let off = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    let cases: Vec<(&str, Vec<u8>, Format, &str)> = vec![
        (
            "part.stl",
            obj_tetra().into_bytes(),
            Format::Obj,
            "the content is OBJ, not STL as the extension '.stl' says: read as OBJ",
        ),
        ("part.obj", off.into(), Format::Off, "the content is OFF, not OBJ"),
        (
            "part.ply",
            binary_stl("", &tetra_triangles()),
            Format::StlBinary,
            "the content is STL, not PLY",
        ),
    ];
    for (name, bytes, format, warning) in cases {
        let loaded = read_as(name, bytes).unwrap();
        assert_eq!((loaded.format, loaded.format_source), (format, FormatSource::Content));
        assert!(loaded.warnings[0].starts_with(warning), "{:?}", loaded.warnings);
        assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-7);
    }
    // Content the extension's reader accepts: the extension decides, no warning.
    let loaded = read_as("part.obj", obj_tetra()).unwrap();
    assert_eq!((loaded.format_source, loaded.warnings.len()), (FormatSource::Extension, 0));
    // A broken file of the extension's format is that format's error, not a guess.
    let e = read_err("part.obj", "v 0 0 0\nf 1 2 x\n");
    assert_eq!(e.location, Some(Location::Line(2)));
}

#[test]
fn obj_objects_from_o_or_g() {
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
    let tetra = "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    text += "g ignored when there are o statements\n";
    text += tetra;
    text += "o first one\ng group\n";
    text += tetra;
    text += "o empty\no  last \n";
    text += tetra;
    let loaded = read_as("m.obj", text).unwrap();
    let objects: Vec<_> =
        loaded.objects.iter().map(|o| (o.name.as_str(), o.faces.clone())).collect();
    assert_eq!(objects, [("", 0..4), ("first one", 4..8), ("last", 8..12)]);
    // Without o, g names the objects; a single group gives no list.
    let groups =
        read_as("g.obj", format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng a\n{tetra}g b\n{tetra}"))
            .unwrap();
    let names: Vec<&str> = groups.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["a", "b"]);
    let one =
        read_as("g.obj", format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng a\n{tetra}")).unwrap();
    assert!(one.objects.is_empty());
}

fn gz(data: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

fn bz2(data: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut e = bzip2::write::BzEncoder::new(Vec::new(), bzip2::Compression::fast());
    e.write_all(data).unwrap();
    e.finish().unwrap()
}

/// Standard input has no name to say it is compressed: its first bytes do, and it is
/// read as the file it holds, as a compressed file is.
#[test]
fn standard_input_is_decompressed_by_its_signature() {
    let obj = obj_tetra();
    let zstd = ruzstd::encoding::compress_to_vec(
        obj.as_bytes(),
        ruzstd::encoding::CompressionLevel::Fastest,
    );
    for packed in
        [gz(obj.as_bytes()), bz2(obj.as_bytes()), zstd, zip_of(&[("part.obj", obj.as_bytes())])]
    {
        let loaded = read_as("-", packed).unwrap();
        assert_eq!(loaded.format, Format::Obj);
        assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-15);
    }
    // A 3MF package is a zip too: read as the 3MF it is.
    let box_3mf = three_mf(&format!(
        r#"<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources><object id="1" type="model">{}</object></resources><build><item objectid="1"/></build></model>"#,
        three_mf_box_mesh([0.0; 3], [1.0, 2.0, 3.0])
    ));
    let loaded = read_as("-", box_3mf).unwrap();
    assert_eq!(loaded.format, Format::ThreeMf);
    assert_close(volume(&loaded.surface), 6.0, 1e-12);
    // A damaged stream says so and names standard input, not "looks like none of STL".
    let mut cut = gz(obj.as_bytes());
    cut.truncate(cut.len() / 2);
    let e = read_as("-", cut).unwrap_err();
    assert_eq!(e.path, Path::new("-"));
    assert!(e.message.contains("gzip") && !e.message.contains("looks like"), "{e}");
    // Polygons and points on standard input too: a 3 × 2 rectangle, four points.
    let wkt = b"POLYGON ((0 0, 3 0, 3 2, 0 2, 0 0))";
    let file = meshvol_io::read_polygons_bytes(Path::new("-"), &gz(wkt)).unwrap();
    assert_eq!(meshvol::polygon::area_properties(&file.features[0].polygons).area, 6.0);
    let cloud = meshvol_io::read_points_bytes(Path::new("-"), bz2(b"0 0 0\n1 0 0\n0 1 0\n0 0 1\n"));
    assert_eq!(
        cloud.unwrap().points,
        [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    );
}
