//! What peer tools forgive is read here too, with a warning naming the place: unknown
//! PLY header lines, PLY triangle strips, OFF faces continued on the next line, faces of
//! fewer than three vertices, CR line ends (old Mac files). Each is checked against the
//! same geometry written as a clean file, or against the box's analytic volume. Also:
//! a zip that is not a 3MF package, and points and polygons read from bytes (standard
//! input).

mod common;

use std::path::Path;

use common::*;
use meshvol_io::write::{ply, PlyEncoding};
use meshvol_io::{read_points_bytes, read_polygons_bytes, Format, Location, PointSource};

const ORIGIN: [f64; 3] = [1.5, -2.0, 0.25];
const SIZE: [f64; 3] = [2.0, 3.0, 4.0];
const BOX_VOLUME: f64 = 24.0;

fn ascii_box_ply() -> String {
    let mut bytes = vec![];
    ply(&mut bytes, &box_mesh(ORIGIN, SIZE), PlyEncoding::Ascii).unwrap();
    String::from_utf8(bytes).unwrap()
}

#[test]
fn ply_header_lines_with_unknown_keywords_are_skipped_with_a_warning() {
    let clean = ascii_box_ply();
    // Blender 2.47 writes its credit line without `comment`.
    let blender = clean.replacen(
        "format ascii 1.0\n",
        "format ascii 1.0\nCreated by Blender 2.47 (sub 0) - www.blender.org\n",
        1,
    );
    let expected = read_as("clean.ply", clean).unwrap();
    let loaded = read_as("blender.ply", blender).unwrap();
    assert_eq!(triangles(&loaded.surface), triangles(&expected.surface));
    assert_eq!(
        loaded.warnings,
        vec!["skipped 1 header lines with an unknown keyword: line 3 ('Created')"]
    );
    // Faces still refer to the right lines after the skipped one.
    let bad = read_as(
        "b.ply",
        ascii_box_ply().replacen("property", "Created by\nproperty", 1).replacen(
            "4 0 2 3 1",
            "4 0 2 3 9",
            1,
        ),
    )
    .unwrap_err();
    let line = 1 + ascii_box_ply().lines().position(|l| l == "4 0 2 3 1").unwrap() as u64 + 1;
    assert_eq!(bad.location, Some(Location::Line(line)), "{bad}");
}

/// Each quad `a b c d` of the box as the strip `a b d c`: triangles `a b d` and `d b c`.
/// The first four are strips of one instance, split by -1; the last two are joined in
/// the second instance by repeating a vertex on each side of the join, as strip
/// writers do.
fn strip_instances() -> [Vec<i32>; 2] {
    let strip = |q: [usize; 4]| [q[0], q[1], q[3], q[2]].map(|i| i as i32);
    let mut first = vec![];
    for (k, &q) in BOX_QUADS[..4].iter().enumerate() {
        if k > 0 {
            first.push(-1);
        }
        first.extend(strip(q));
    }
    let (a, b) = (strip(BOX_QUADS[4]), strip(BOX_QUADS[5]));
    let mut second = a.to_vec();
    second.extend([a[3], b[0]]);
    second.extend(b);
    [first, second]
}

fn strip_header(format: &str) -> String {
    format!(
        "ply\nformat {format} 1.0\nelement vertex 8\nproperty double x\nproperty double y\n\
         property double z\nelement tristrips 2\nproperty list int int vertex_indices\n\
         end_header\n"
    )
}

#[test]
fn ply_tristrips_are_the_same_triangles_listed_as_faces() {
    let corners = box_corners(ORIGIN, SIZE);
    // The same triangles, listed as faces.
    let mut faces = String::from(
        "ply\nformat ascii 1.0\nelement vertex 8\nproperty double x\nproperty double y\n\
         property double z\nelement face 12\nproperty list uchar int vertex_indices\n\
         end_header\n",
    );
    for p in &corners {
        faces += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for q in BOX_QUADS {
        faces += &format!("3 {} {} {}\n3 {} {} {}\n", q[0], q[1], q[3], q[3], q[1], q[2]);
    }
    let expected = read_as("faces.ply", faces).unwrap();
    assert_eq!(volume(&expected.surface), BOX_VOLUME);

    let mut ascii = strip_header("ascii");
    for p in &corners {
        ascii += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for strip in strip_instances() {
        let items: Vec<String> = strip.iter().map(i32::to_string).collect();
        ascii += &format!("{} {}\n", strip.len(), items.join(" "));
    }
    let mut files = vec![(ascii.into_bytes(), Format::PlyAscii)];
    for (big, format) in
        [(false, Format::PlyBinaryLittleEndian), (true, Format::PlyBinaryBigEndian)]
    {
        let name = if big { "binary_big_endian" } else { "binary_little_endian" };
        let mut bytes = strip_header(name).into_bytes();
        let mut put = |raw: [u8; 8], n: usize| {
            if big {
                bytes.extend(raw[..n].iter().rev())
            } else {
                bytes.extend(&raw[..n])
            }
        };
        for p in &corners {
            for c in p {
                put(c.to_le_bytes(), 8);
            }
        }
        for strip in strip_instances() {
            put((strip.len() as i64).to_le_bytes(), 4);
            for i in strip {
                put(i64::from(i).to_le_bytes(), 4);
            }
        }
        files.push((bytes, format));
    }
    for (bytes, format) in files {
        let loaded = read_as("strips.ply", bytes).unwrap();
        assert_eq!(loaded.format, format);
        assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
        assert_eq!(triangles(&loaded.surface), triangles(&expected.surface), "{format}");
        assert_eq!(volume(&loaded.surface), BOX_VOLUME);
    }

    // Only -1 separates strips; other indices must name a vertex.
    let mut bad = strip_header("ascii");
    for p in &corners {
        bad += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    bad += "4 0 1 2 3\n4 0 -2 2 3\n";
    let e = read_err("bad.ply", bad);
    assert_eq!(e.location, Some(Location::Line(19)));
    assert!(e.message.contains("vertex index -2 is out of range"), "{e}");
}

fn box_off() -> String {
    common::box_off("OFF\n8 6 0", ORIGIN, SIZE)
}

#[test]
fn off_faces_may_continue_on_the_next_lines() {
    let clean = box_off();
    // Lines 11 to 16 are the faces: the second one split over three lines.
    let split = clean.replacen("4 4 5 7 6 ", "4 4\n  5 # a comment between\n\n7 6 ", 1);
    let expected = read_as("clean.off", clean).unwrap();
    let loaded = read_as("split.off", split).unwrap();
    assert_eq!(triangles(&loaded.surface), triangles(&expected.surface));
    assert_eq!(volume(&loaded.surface), BOX_VOLUME);
    assert_eq!(loaded.warnings, vec!["1 faces continue on the next lines (the first at line 12)"]);
}

#[test]
fn faces_of_fewer_than_three_vertices_are_skipped_with_a_warning() {
    // OBJ: a two-vertex face and an empty one among the box's quads.
    let mut obj = String::new();
    for p in box_corners(ORIGIN, SIZE) {
        obj += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    let clean_obj = obj.clone()
        + &BOX_QUADS
            .iter()
            .map(|q| format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1))
            .collect::<String>();
    let mut dirty = obj.clone();
    for (k, q) in BOX_QUADS.iter().enumerate() {
        if k == 2 {
            dirty += "f 1// 2//\n"; // line 11
        }
        if k == 4 {
            dirty += "f\n";
        }
        dirty += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    let expected = read_as("clean.obj", clean_obj).unwrap();
    let loaded = read_as("dirty.obj", dirty.clone()).unwrap();
    assert_eq!(triangles(&loaded.surface), triangles(&expected.surface));
    assert_eq!(
        loaded.warnings,
        vec!["skipped 2 faces with fewer than 3 vertices (the first at line 11)"]
    );
    // An error after skipped faces still names its own line (15: the fifth quad).
    let e = read_err("dirty.obj", dirty.replacen("f 1 5 7 3", "f 1 5 9 3", 1));
    assert_eq!(
        (e.location, e.message.as_str()),
        (Some(Location::Line(15)), "vertex index 9 is out of range: the file has 8 vertices")
    );

    // OFF: seven declared faces, one of two vertices (line 13).
    let off = box_off().replacen("8 6 0", "8 7 0", 1).replacen(
        "4 0 1 5 4 ",
        "2 0 1 0.1 0.2 0.3 1.0\n4 0 1 5 4 ",
        1,
    );
    let loaded = read_as("dirty.off", off).unwrap();
    assert_eq!(
        triangles(&loaded.surface),
        triangles(&read_as("c.off", box_off()).unwrap().surface)
    );
    assert_eq!(
        loaded.warnings,
        vec!["skipped 1 faces with fewer than 3 vertices (the first at line 13)"]
    );

    // ASCII PLY: a one-vertex face.
    let clean = ascii_box_ply();
    let face_line = 1 + clean.lines().position(|l| l == "4 0 1 5 4").unwrap();
    let dirty = clean.replacen("element face 6", "element face 7", 1).replacen(
        "4 0 1 5 4\n",
        "1 0\n4 0 1 5 4\n",
        1,
    );
    let loaded = read_as("dirty.ply", dirty).unwrap();
    assert_eq!(triangles(&loaded.surface), triangles(&read_as("c.ply", clean).unwrap().surface));
    assert_eq!(
        loaded.warnings,
        vec![format!("skipped 1 faces with fewer than 3 vertices (the first at line {face_line})")]
    );
}

/// Every LF of a text file made a CR: the file must read as the LF one does, and an
/// error must name the same line.
#[test]
fn cr_line_ends_read_like_lf() {
    let obj = {
        let mut s = String::from("# box\no box\n");
        for p in box_corners(ORIGIN, SIZE) {
            s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
        }
        for q in BOX_QUADS {
            s += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
        }
        s
    };
    let stl = ascii_solid("box", &box_triangles(ORIGIN, SIZE), "\n");
    let mut binary_ply = vec![];
    ply(&mut binary_ply, &box_mesh(ORIGIN, SIZE), PlyEncoding::BinaryLittleEndian).unwrap();
    let header_end = binary_ply.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let mut cr_binary_ply = binary_ply.clone();
    for b in &mut cr_binary_ply[..header_end] {
        if *b == b'\n' {
            *b = b'\r';
        }
    }
    let cr = |s: &str| s.replace('\n', "\r").into_bytes();
    let cases: Vec<(&str, Vec<u8>, Vec<u8>, Format)> = vec![
        ("box.obj", obj.clone().into_bytes(), cr(&obj), Format::Obj),
        ("-", obj.clone().into_bytes(), cr(&obj), Format::Obj),
        ("box.off", box_off().into_bytes(), cr(&box_off()), Format::Off),
        ("-", box_off().into_bytes(), cr(&box_off()), Format::Off),
        ("box.ply", ascii_box_ply().into_bytes(), cr(&ascii_box_ply()), Format::PlyAscii),
        ("box.stl", stl.clone().into_bytes(), cr(&stl), Format::StlAscii),
        ("-", stl.clone().into_bytes(), cr(&stl), Format::StlAscii),
        ("box.ply", binary_ply, cr_binary_ply, Format::PlyBinaryLittleEndian),
    ];
    for (name, lf, cr, format) in cases {
        let expected = read_as(name, lf).unwrap();
        let loaded = read_as(name, cr).unwrap();
        assert_eq!(loaded.format, format, "{name}");
        assert_eq!(triangles(&loaded.surface), triangles(&expected.surface), "{format}");
        assert_eq!(volume(&loaded.surface), BOX_VOLUME, "{format}");
        assert_eq!(loaded.objects, expected.objects, "{format}");
        assert!(loaded.warnings.is_empty(), "{format}: {:?}", loaded.warnings);
    }
    // Errors name the line the LF file has it on.
    let bad_obj = obj.replacen("f 1 3 4 2", "f 1 3 4 9", 1);
    let line = 1 + bad_obj.lines().position(|l| l == "f 1 3 4 9").unwrap() as u64;
    assert_eq!(read_err("bad.obj", cr(&bad_obj)).location, Some(Location::Line(line)));
    let bad_off = box_off().replacen("4 0 2 3 1 ", "4 0 2 3 x ", 1);
    assert_eq!(read_err("bad.off", cr(&bad_off)).location, Some(Location::Line(11)));

    // Text points and polygons.
    let points = "x y z\n0 0 0\n1 0 0\n0 1 0\n";
    let expected = read_points_bytes(Path::new("p.xyz"), points.into()).unwrap();
    let loaded = read_points_bytes(Path::new("p.xyz"), cr(points)).unwrap();
    assert_eq!(loaded.points, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    assert_eq!(loaded, expected);
    let e = read_points_bytes(Path::new("p.xyz"), cr("0 0 0\n1 0\n")).unwrap_err();
    assert_eq!(e.location, Some(Location::Line(2)));
    for (name, text) in [
        ("lot.txt", "x y\n0 0\n4 0\n4 2\n0 2\n\n1 1\n2 1\n2 1.5\n"),
        ("lot.wkt", "POLYGON ((0 0, 4 0, 4 2, 0 2, 0 0),\n(1 1, 2 1, 2 1.5, 1 1))\n"),
    ] {
        let expected = read_polygons_bytes(Path::new(name), text.as_bytes()).unwrap();
        let loaded = read_polygons_bytes(Path::new(name), &cr(text)).unwrap();
        assert_eq!(loaded, expected, "{name}");
        assert_eq!(loaded.features[0].polygons[0].holes.len(), 1, "{name}");
    }
    let e = read_polygons_bytes(Path::new("lot.wkt"), &cr("POLYGON ((0 0, 1 0,\n1 x, 0 0))"))
        .unwrap_err();
    assert_eq!(e.location, Some(Location::Line(2)));
}

#[test]
fn a_zip_that_is_not_a_3mf_package_says_so() {
    let stl = ascii_solid("box", &box_triangles(ORIGIN, SIZE), "\n");
    let zip = zip_of(&[("box.stl", stl.as_bytes())]);
    let e = read_err("box.3mf", zip.clone());
    assert_eq!(e.to_string(), "box.3mf: not a 3MF package (no 3D/3dmodel.model)");
    // Standard input, unnamed, is an archive of one mesh by its signature.
    let faces = read_as("box.stl", stl.as_bytes()).unwrap().face_count();
    assert_eq!(read_as("-", zip.clone()).unwrap().face_count(), faces);
    // Bytes named `.zip` (an upload to `meshvol serve`) are an archive of one mesh, as a
    // `.zip` file is: read as the STL it holds.
    assert_eq!(read_as("box.zip", zip.clone()).unwrap().face_count(), faces);
    // A `.zip` file is an archive of one mesh: read as the STL it holds.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("box.zip");
    std::fs::write(&path, &zip).unwrap();
    let loaded = meshvol_io::read(&path).unwrap();
    assert_eq!(loaded.face_count(), read_as("box.stl", stl.as_bytes()).unwrap().face_count());
    // The corpus's zipped sets, where present: its one STL (the `__MACOSX/._` copy passed
    // over), as the member read alone.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/trimesh-models");
    let zipped = dir.join("ascii.stl.zip");
    if zipped.is_file() {
        let loaded = meshvol_io::read(&zipped).unwrap();
        let mut archive = zip::ZipArchive::new(std::fs::File::open(&zipped).unwrap()).unwrap();
        let mut member = Vec::new();
        std::io::Read::read_to_end(&mut archive.by_name("fuji_obj.stl").unwrap(), &mut member)
            .unwrap();
        let alone = read_as("fuji_obj.stl", member).unwrap();
        assert_eq!((loaded.format, loaded.face_count()), (alone.format, alone.face_count()));
    } else {
        println!("corpus not found at {}, skipping", dir.display());
    }
}

#[test]
fn points_from_bytes_take_the_format_from_the_content() {
    let text = "# scan\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
    let cloud = read_points_bytes(Path::new("-"), text.into()).unwrap();
    assert_eq!(cloud.source, PointSource::Text);
    assert_eq!(
        cloud.points,
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    );
    let dir = tempfile::tempdir().unwrap();
    let file = write_temp(dir.path(), "scan.xyz", text.as_bytes());
    assert_eq!(meshvol_io::read_points(&file).unwrap(), cloud);

    let mut bytes = vec![];
    ply(&mut bytes, &box_mesh(ORIGIN, SIZE), PlyEncoding::BinaryBigEndian).unwrap();
    for name in ["-", "box.ply", "box.dat"] {
        let cloud = read_points_bytes(Path::new(name), bytes.clone()).unwrap();
        assert_eq!(cloud.source, PointSource::Mesh(Format::PlyBinaryBigEndian), "{name}");
        assert_eq!(cloud.points, box_corners(ORIGIN, SIZE), "{name}");
    }
    let e = read_points_bytes(Path::new("-"), b"0 0 0\n1 two 3\n".to_vec()).unwrap_err();
    assert_eq!(e.to_string(), "-: line 2: expected numbers x y z, found 'two'");
}

#[test]
fn polygons_from_standard_input_take_the_format_from_the_content() {
    let cases = [
        ("lot.wkt", "POLYGON ((0 0, 4 0, 4 2, 0 2, 0 0))"),
        ("lot.wkt", "SRID=25832;MULTIPOLYGON (((0 0, 4 0, 4 2, 0 2, 0 0)))"),
        ("lot.geojson", r#"{"type": "Polygon", "coordinates": [[[0,0],[4,0],[4,2],[0,2],[0,0]]]}"#),
        ("lot.txt", "0 0\n4 0\n4 2\n0 2\n"),
        ("lot.txt", "x,y\n0,0\n4,0\n4,2\n0,2\n"),
        ("lot.txt", "easting northing\n0 0\n4 0\n4 2\n0 2\n"),
    ];
    for (name, text) in cases {
        let expected = read_polygons_bytes(Path::new(name), text.as_bytes()).unwrap();
        let from_stdin = read_polygons_bytes(Path::new("-"), text.as_bytes()).unwrap();
        assert_eq!(from_stdin, expected, "{text}");
        let p = meshvol::polygon::area_properties(&from_stdin.features[0].polygons);
        assert_eq!(p.area, 8.0, "{text}");
    }
}
