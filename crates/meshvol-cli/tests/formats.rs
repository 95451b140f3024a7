//! The formats end to end: PLY, 3MF and GLB files, objects, units declared by files,
//! standard input, format detection and `--quiet`, through the built binary.

mod common;
use common::{f, meshvol, three_mf, write};

use serde_json::Value;
use std::io::Write;
use std::process::{Command, Output, Stdio};

/// Runs meshvol with `input` on standard input.
fn meshvol_stdin(args: &[&str], input: &[u8]) -> Output {
    let mut child = Command::new(common::bin())
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("meshvol runs");
    child.stdin.take().unwrap().write_all(input).unwrap();
    child.wait_with_output().unwrap()
}

fn json(out: &Output) -> Value {
    assert!(out.status.success(), "stderr: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

/// The box [x, x + a] × [0, b] × [0, c] as a 3MF mesh: eight vertices, twelve outward
/// triangles.
fn box_mesh_xml(x: f64, a: f64, b: f64, c: f64) -> String {
    let corner =
        |i: usize| [x + a * (i & 1) as f64, b * (i >> 1 & 1) as f64, c * (i >> 2 & 1) as f64];
    let quads =
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
    let mut s = String::from("<mesh><vertices>");
    for i in 0..8 {
        let p = corner(i);
        s += &format!(r#"<vertex x="{}" y="{}" z="{}"/>"#, p[0], p[1], p[2]);
    }
    s += "</vertices><triangles>";
    for q in quads {
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            s += &format!(r#"<triangle v1="{}" v2="{}" v3="{}"/>"#, t[0], t[1], t[2]);
        }
    }
    s + "</triangles></mesh>"
}

/// Two boxes (volumes 6 and 1) in inches.
fn two_boxes_in_inches() -> Vec<u8> {
    three_mf(&format!(
        r#"<model unit="inch" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources><object id="1" name="block">{}</object><object id="2" name="cube">{}</object></resources><build><item objectid="1"/><item objectid="2" transform="1 0 0 0 1 0 0 0 1 0 0 10"/></build></model>"#,
        box_mesh_xml(0.0, 1.0, 2.0, 3.0),
        box_mesh_xml(5.0, 1.0, 1.0, 1.0)
    ))
}

#[test]
fn three_mf_objects_and_declared_unit() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "boxes.3mf", two_boxes_in_inches());
    let path = path.to_str().unwrap();

    // No --units: reported in the declared unit.
    let r = json(&meshvol(&["--json", path]));
    assert_eq!(r["format"], "3mf");
    assert_eq!(r["format_source"], "extension");
    assert!(close(f(&r["volume"]), 7.0));
    assert_eq!(r["units"]["length"], "in");
    assert_eq!(r["units"]["file"], "in");
    assert_eq!(r["units"]["file_declared"], "in");
    let objects = r["objects"].as_array().unwrap();
    assert_eq!(objects.len(), 2);
    assert_eq!(objects[0]["name"], "block");
    assert_eq!(objects[0]["faces"], serde_json::json!([0, 12]));
    assert_eq!(objects[0]["triangles"], 12);
    assert!(close(f(&objects[0]["volume"]), 6.0));
    assert!(close(f(&objects[0]["area"]), 2.0 * (2.0 + 3.0 + 6.0)));
    assert_eq!(objects[1]["name"], "cube");
    assert!(close(f(&objects[1]["signed_volume"]), 1.0));
    let c = objects[1]["centroid"].as_array().unwrap();
    assert!(close(f(&c[0]), 5.5) && close(f(&c[1]), 0.5) && close(f(&c[2]), 10.5));

    // --units :cm converts from the declared inches: 2.54³ per cubic inch.
    let r = json(&meshvol(&["--json", "--units", ":cm", path]));
    assert!(close(f(&r["volume"]), 7.0 * 2.54f64.powi(3)));
    assert!(close(f(&r["objects"][1]["volume"]), 2.54f64.powi(3)));
    assert!(close(f(&r["objects"][1]["centroid"][2]), 10.5 * 2.54));
    assert_eq!(r["units"]["volume"], "cm^3");

    // An explicit file unit overrides the declaration, with a warning.
    let out = meshvol(&["--json", "--units", "mm:cm", path]);
    let r = json(&out);
    assert!(close(f(&r["volume"]), 7.0e-3));
    assert_eq!(r["units"]["file"], "mm");
    assert_eq!(r["units"]["file_declared"], "in");
    assert!(stderr(&out).contains("the file declares its lengths in in; --units says mm"));
    // --quiet silences it.
    let out = meshvol(&["--json", "--quiet", "--units", "mm:cm", path]);
    assert!(out.status.success());
    assert_eq!(stderr(&out), "");

    // The text report has the objects table.
    let out = meshvol(&[path]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("objects (2, measured as wound):"), "{text}");
    assert!(
        text.lines().any(|l| l.trim_start().starts_with("block") && l.contains(" 12 ")),
        "{text}"
    );
}

#[test]
fn standard_input_is_read_by_content() {
    let quads = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n\
                 property float z\nelement face 6\nproperty list uchar int vertex_indices\n\
                 end_header\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n0 0 2\n2 0 2\n2 2 2\n0 2 2\n\
                 4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
    let r = json(&meshvol_stdin(&["--json", "-"], quads.as_bytes()));
    assert_eq!(r["file"], "-");
    assert_eq!(r["format"], "ply-ascii");
    assert_eq!(r["format_source"], "content");
    assert_eq!((r["faces"].as_u64(), r["triangles"].as_u64()), (Some(6), Some(12)));
    assert!(close(f(&r["volume"]), 8.0));
    assert!(r.get("objects").is_none(), "one object: no list");
    assert!(r["units"].is_null());

    let out = meshvol_stdin(&["--json", "-"], b"");
    assert!(!out.status.success());
    assert!(stderr(&out).contains("-: the file has no extension, and the file is empty"));
}

#[test]
fn glb_is_in_metres_and_content_beats_a_wrong_extension() {
    let dir = tempfile::tempdir().unwrap();
    // A GLB written by meshvol-io, named .stl.
    let cube = meshvol::Mesh::from_polygons(
        (0..8).map(|i| [(i & 1) as f64, (i >> 1 & 1) as f64 * 3.0, (i >> 2 & 1) as f64]).collect(),
        [[0u32, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
            .iter()
            .map(|q| &q[..]),
    )
    .unwrap();
    let mut glb = vec![];
    meshvol_io::write::glb(&mut glb, &cube).unwrap();
    let path = write(dir.path(), "cube.stl", &glb);
    let out = meshvol(&["--json", "--units", ":L", path.to_str().unwrap()]);
    let r = json(&out);
    assert_eq!(r["format"], "glb");
    assert_eq!(r["format_source"], "content");
    assert!(stderr(&out).contains("the content is glTF, not STL as the extension '.stl' says"));
    // 3 m³ = 3000 L.
    assert!(close(f(&r["volume"]), 3000.0));
    assert_eq!(r["units"]["file_declared"], "m");
}

#[test]
fn point_clouds_and_undeclared_units_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let points = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
                  property float z\nend_header\n0 0 0\n1 1 1\n";
    let path = write(dir.path(), "points.ply", points.as_bytes());
    let out = meshvol(&[path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("points.ply: no faces: there is no surface to measure"));

    let obj = write(
        dir.path(),
        "t.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    );
    let out = meshvol(&["--units", ":cm", obj.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("t.obj: the file declares no length unit"), "{}", stderr(&out));
}

#[test]
fn obj_groups_are_objects() {
    let dir = tempfile::tempdir().unwrap();
    let mut text =
        String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 7 0 0\nv 5 2 0\nv 5 0 2\n");
    text += "o small\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\no large\nf 5 7 6\nf 5 6 8\nf 5 8 7\nf 6 7 8\n";
    let path = write(dir.path(), "two.obj", text.as_bytes());
    let r = json(&meshvol(&["--json", path.to_str().unwrap()]));
    let objects = r["objects"].as_array().unwrap();
    let names: Vec<&str> = objects.iter().map(|o| o["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["small", "large"]);
    assert!(close(f(&objects[0]["volume"]), 1.0 / 6.0));
    assert!(close(f(&objects[1]["volume"]), 8.0 / 6.0));
    assert!(close(f(&r["volume"]), 9.0 / 6.0));
}

#[test]
fn hull_and_area_read_standard_input() {
    // The corner tetrahedron of the unit cube: volume 1/6.
    let v = json(&meshvol_stdin(&["hull", "-", "--json"], b"0 0 0\n1 0 0\n0 1 0\n0 0 1\n"));
    assert_eq!((v["file"].as_str(), v["points"].as_u64()), (Some("-"), Some(4)));
    assert!((f(&v["volume"]) - 1.0 / 6.0).abs() < 1e-15);
    // A 3 × 2 rectangle with a 1 × 0.5 hole: area 5.5.
    let wkt = b"POLYGON ((0 0, 3 0, 3 2, 0 2, 0 0), (1 1, 1 1.5, 2 1.5, 2 1, 1 1))";
    let v = json(&meshvol_stdin(&["area", "-", "--json"], wkt));
    assert_eq!((v["file"].as_str(), v["format"].as_str()), (Some("-"), Some("wkt")));
    assert_eq!(f(&v["area"]), 5.5);
}

/// A gzip on standard input is read as the mesh it holds (standard input has no name:
/// its first bytes say it is compressed), and a glTF zipped with its `.bin` reads the
/// buffer from the archive.
#[test]
fn compressed_standard_input_and_a_zipped_gltf_are_read() {
    let obj = common::box_obj([0.0; 3], [1.0, 2.0, 3.0], 1, true, false);
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(obj.as_bytes()).unwrap();
    let v = json(&meshvol_stdin(&["--json", "-"], &gz.finish().unwrap()));
    assert_eq!((v["file"].as_str(), v["format"].as_str()), (Some("-"), Some("obj")));
    assert!((f(&v["volume"]) - 6.0).abs() < 1e-12, "{v}");
    // The unit cube's eight corners (f32) and twelve triangles (u16), in a .bin beside
    // the .gltf inside the zip.
    let mut bin = Vec::new();
    for k in 0..8u8 {
        for axis in 0..3 {
            bin.extend_from_slice(&f32::from((k >> axis) & 1).to_le_bytes());
        }
    }
    let faces: [[u16; 3]; 12] = [
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    faces.iter().flatten().for_each(|i| bin.extend_from_slice(&i.to_le_bytes()));
    let gltf = r#"{"asset":{"version":"2.0"},"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3"},
                     {"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}],
        "bufferViews":[{"buffer":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":72}],
        "buffers":[{"byteLength":168,"uri":"cube.bin"}]}"#;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for (name, bytes) in [("cube/cube.gltf", gltf.as_bytes()), ("cube/cube.bin", &bin)] {
        zip.start_file(name, zip::write::SimpleFileOptions::default()).unwrap();
        zip.write_all(bytes).unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "cube.zip", zip.finish().unwrap().into_inner());
    let out = meshvol(&["volume", "--json", path.to_str().unwrap()]);
    let v = json(&out);
    // glTF lengths are metres; the cube is 1 m³ and closed.
    assert!((f(&v["volume"]) - 1.0).abs() < 1e-15, "{v}");
    assert!(!stderr(&out).contains("os error"), "{}", stderr(&out));
}
