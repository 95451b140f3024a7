//! Binary and ASCII STL.

mod common;

use common::*;
use meshvol::Surface;
use meshvol_io::{read, Format, LoadedSurface, Location};

const ORIGIN: [f64; 3] = [1.5, -2.0, 0.25];
const SIZE: [f64; 3] = [2.0, 3.0, 4.0];
const BOX_VOLUME: f64 = 24.0;

#[test]
fn binary_whose_header_starts_with_solid() {
    let bytes = binary_stl("solid this is binary", &box_triangles(ORIGIN, SIZE));
    let dir = tempfile::tempdir().unwrap();
    let path = write_temp(dir.path(), "box.stl", &bytes);
    let loaded = read(&path).unwrap();
    assert_eq!(loaded.format, Format::StlBinary);
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert_eq!((loaded.face_count(), loaded.triangle_count(), loaded.vertex_count()), (12, 12, 36));
    let LoadedSurface::StlSoup(soup) = &loaded.surface else { panic!("not a soup") };
    assert_eq!(soup.triangle_count(), 12);
    assert!(soup.header().starts_with(b"solid this is binary"));
    assert_close(volume(soup), BOX_VOLUME, 1e-12);
    assert_close(volume(&loaded.surface), BOX_VOLUME, 1e-12);
    // The soup yields exactly the file's triangles, widened from f32.
    assert_eq!(triangles(soup), box_triangles(ORIGIN, SIZE));
    let mesh = loaded.surface.into_mesh().unwrap();
    assert_eq!(mesh.vertex_count(), 36);
    assert_close(volume(&mesh), BOX_VOLUME, 1e-12);
}

#[test]
fn binary_upper_case_extension_and_f32_widening() {
    let tris = vec![[[0.1, 0.2, 0.3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]];
    let loaded = read_as("PART.STL", binary_stl("", &tris)).unwrap();
    assert_eq!(loaded.format, Format::StlBinary);
    let got = triangles(&loaded.surface);
    assert_eq!(got[0][0], [0.1f32 as f64, 0.2f32 as f64, 0.3f32 as f64]);
}

#[test]
fn binary_with_trailing_bytes_warns() {
    let mut bytes = binary_stl("x", &tetra_triangles());
    bytes.extend_from_slice(b"\0\0\0junk");
    let loaded = read_as("t.stl", bytes).unwrap();
    assert_eq!(loaded.format, Format::StlBinary);
    assert_eq!(loaded.face_count(), 4);
    assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-7);
    assert_eq!(loaded.warnings.len(), 1);
    assert!(loaded.warnings[0].contains("7 bytes"), "{:?}", loaded.warnings);
}

#[test]
fn binary_truncated() {
    let mut bytes = binary_stl("solid x", &box_triangles(ORIGIN, SIZE));
    bytes.truncate(84 + 50 * 5 + 7);
    let e = read_err("t.stl", bytes);
    assert_eq!(e.location, Some(Location::Byte(341)));
    assert_eq!(
        e.message,
        "truncated: header claims 12 triangles (needs 684 bytes) but the file has 341 bytes"
    );
}

#[test]
fn binary_header_claiming_4e9_triangles_fails_fast() {
    for header in ["", "solid huge"] {
        let mut bytes = binary_stl(header, &tetra_triangles());
        bytes[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
        // Refused from the header: allocating for 4·10⁹ triangles would abort instead.
        let e = read_err("huge.stl", bytes);
        assert!(e.message.contains("4000000000 triangles"), "{e}");
        assert!(e.message.contains("200000000084 bytes"), "{e}");
        // Through the file system as well (memory-mapped).
        let dir = tempfile::tempdir().unwrap();
        let mut bytes = binary_stl(header, &tetra_triangles());
        bytes[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
        let path = write_temp(dir.path(), "huge.stl", &bytes);
        let e = read(&path).unwrap_err();
        assert!(e.message.contains("truncated"), "{e}");
    }
}

#[test]
fn binary_nan_and_infinity_name_the_face_and_byte() {
    let mut tris = box_triangles(ORIGIN, SIZE);
    tris[7][2][1] = f64::NAN;
    let e = read_err("nan.stl", binary_stl("", &tris));
    assert_eq!(e.location, Some(Location::Face(7)));
    // Record 7 starts at 84 + 350; vertex 2's y is 12 + 24 + 4 bytes in.
    assert!(e.message.contains("byte 474"), "{e}");
    assert!(e.message.contains("NaN"), "{e}");
    assert!(e.to_string().starts_with("nan.stl: face 7: "), "{e}");

    let mut tris = tetra_triangles();
    tris[3][0][0] = f64::INFINITY;
    let e = read_err("inf.stl", binary_stl("", &tris));
    assert_eq!(e.location, Some(Location::Face(3)));

    // Non-finite normals are not read, so they are no error.
    let mut bytes = binary_stl("", &tetra_triangles());
    bytes[84..88].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(read_as("normal.stl", bytes).is_ok());
}

#[test]
fn binary_nan_found_in_a_large_file_is_the_first_one() {
    let base = box_triangles(ORIGIN, SIZE);
    let mut tris: Vec<_> = base.iter().cycle().take(100_000).copied().collect();
    tris[70_001][0][2] = f64::NAN;
    tris[90_000][1][2] = f64::NAN;
    let e = read_err("big.stl", binary_stl("", &tris));
    assert_eq!(e.location, Some(Location::Face(70_001)));
}

#[test]
fn binary_zero_triangles_and_short_files() {
    let loaded = read_as("empty.stl", binary_stl("nothing", &[])).unwrap();
    assert_eq!(loaded.format, Format::StlBinary);
    assert_eq!(loaded.face_count(), 0);
    assert_eq!(volume(&loaded.surface), 0.0);

    let e = read_err("empty.stl", Vec::new());
    assert_eq!(e.message, "empty file");
    let e = read_err("short.stl", vec![0u8; 50]);
    assert!(e.message.contains("too short"), "{e}");
    let e = read_err("short.stl", b"solidity".to_vec());
    assert!(e.message.contains("too short"), "{e}");
}

#[test]
fn ascii_openscad_style_bare_solid_and_crlf() {
    let text = ascii_solid("", &box_triangles(ORIGIN, SIZE), "\r\n");
    assert!(text.starts_with("solid\r\n") && text.ends_with("endsolid\r\n"), "{text}");
    let loaded = read_as("scad.stl", text.clone()).unwrap();
    assert_eq!(loaded.format, Format::StlAscii);
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert_eq!((loaded.face_count(), loaded.vertex_count()), (12, 36));
    assert_close(volume(&loaded.surface), BOX_VOLUME, 1e-12);
    // Exactly the written coordinates (parsed as f64, no f32 rounding).
    assert_eq!(triangles(&loaded.surface), box_triangles(ORIGIN, SIZE));

    // Through the file system too, with no final newline.
    let dir = tempfile::tempdir().unwrap();
    let path = write_temp(dir.path(), "scad.stl", text.trim_end().as_bytes());
    let loaded = read(&path).unwrap();
    assert_close(volume(&loaded.surface), BOX_VOLUME, 1e-12);
}

#[test]
fn ascii_any_case_any_whitespace_bom() {
    let t = tetra_triangles();
    let mut text = String::from("\u{feff}  SOLID Tetra Name With Spaces\n");
    for tri in &t {
        text += "FaCeT\tNORMAL nan nan nan OUTER\n\n LOOP";
        for p in tri {
            text += &format!(" VERTEX\t{}  {}\n{} ", p[0], p[1], p[2]);
        }
        text += "ENDLOOP ENDFACET\t";
    }
    text += "ENDSOLID Tetra Name With Spaces";
    let loaded = read_as("t.stl", text).unwrap();
    assert_eq!(loaded.format, Format::StlAscii);
    assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-15);
}

#[test]
fn ascii_several_solids_are_objects() {
    let a = box_triangles(ORIGIN, SIZE);
    let b = box_triangles([10.0, 10.0, 10.0], [1.0, 1.0, 1.0]);
    let text = ascii_solid("bodyA", &a, "\n") + &ascii_solid("body B", &b, "\n");
    let loaded = read_as("two.stl", text).unwrap();
    assert_eq!(loaded.face_count(), 24);
    assert_close(volume(&loaded.surface), BOX_VOLUME + 1.0, 1e-12);
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let objects: Vec<_> =
        loaded.objects.iter().map(|o| (o.name.as_str(), o.faces.clone())).collect();
    assert_eq!(objects, [("bodyA", 0..12), ("body B", 12..24)]);
    let second = meshvol::surface::FaceRange::new(&loaded.surface, loaded.objects[1].faces.clone());
    assert_close(volume(&second), 1.0, 1e-12);
    // One solid: no object list.
    let one = read_as("one.stl", ascii_solid("only", &a, "\n")).unwrap();
    assert!(one.objects.is_empty());
}

#[test]
fn ascii_large_file_in_parallel_chunks() {
    // Many boxes: more than one 1 MiB chunk; facets are cut at `facet` lines.
    let mut text = String::from("solid many\n");
    let mut expected = 0.0;
    for i in 0..3000 {
        let s = 1.0 + (i % 7) as f64;
        let tris = box_triangles([i as f64, 0.0, -(i as f64)], [s, 1.0, 0.5]);
        expected += s * 0.5;
        let block = ascii_solid("x", &tris, "\n");
        // Only the facets of the block.
        let facets: String =
            block.lines().skip(1).take(tris.len() * 7).map(|l| format!("{l}\n")).collect();
        text += &facets;
    }
    text += "endsolid many\n";
    assert!(text.len() > 3 << 20);
    let loaded = read_as("many.stl", text.clone()).unwrap();
    assert_eq!(loaded.face_count(), 36_000);
    assert_close(volume(&loaded.surface), expected, 1e-6);

    // An error deep in the file names its line.
    let line = 200_001;
    let mut lines: Vec<&str> = text.lines().collect();
    assert!(lines[line - 1].trim_start().starts_with("vertex"));
    lines[line - 1] = "vertex 1 2";
    let e = read_err("many.stl", lines.join("\n"));
    assert_eq!(e.location, Some(Location::Line(line as u64)));
    assert_eq!(
        e.to_string(),
        format!("many.stl: line {line}: expected 3 coordinates after 'vertex', found 2")
    );
}

#[test]
fn ascii_errors_carry_lines() {
    let good = ascii_solid("t", &tetra_triangles(), "\n");
    let cases: &[(&str, &str, u64, &str)] = &[
        ("vertex 1e0 0e0 0e0", "vertex 1 0", 6, "expected 3 coordinates after 'vertex', found 2"),
        ("vertex 1e0 0e0 0e0", "vertex 1 nan 0", 6, "non-finite coordinate 'nan'"),
        ("vertex 1e0 0e0 0e0", "vertex 1 1e999 0", 6, "non-finite coordinate '1e999'"),
        ("vertex 1e0 0e0 0e0", "vertex 1 2x 0", 6, "invalid number '2x'"),
        (
            "vertex 1e0 0e0 0e0",
            "vertex 1 0 0\nvertex 1 0 0",
            2,
            "facet has 4 vertices; an STL facet needs exactly 3",
        ),
        (
            "    endloop\n  endfacet\n  facet",
            "    endloop\n  facet",
            8,
            "expected 'endfacet', found 'facet'",
        ),
    ];
    for (from, to, line, message) in cases {
        let bad = good.replacen(from, to, 1);
        assert_ne!(bad, good);
        let e = read_err("e.stl", bad);
        assert_eq!(
            (e.location.clone(), e.message.as_str()),
            (Some(Location::Line(*line)), *message),
            "{to}"
        );
    }
    // A facet with two vertices: the error is at the facet's line.
    let mut lines: Vec<&str> = good.lines().collect();
    lines.remove(4);
    let e = read_err("e.stl", lines.join("\n"));
    assert_eq!(e.location, Some(Location::Line(2)));
    assert!(e.message.contains("2 vertices"), "{e}");
    // A file that ends inside a facet.
    let cut = &good[..good.find("endloop").unwrap()];
    let e = read_err("e.stl", cut);
    assert!(e.message.contains("end of the file"), "{e}");
    // A file that ends after a facet without endsolid: accepted with a warning.
    let cut = &good[..good.rfind("endsolid").unwrap()];
    let loaded = read_as("e.stl", cut).unwrap();
    assert_close(volume(&loaded.surface), 1.0 / 6.0, 1e-15);
    assert!(loaded.warnings[0].contains("without 'endsolid'"), "{:?}", loaded.warnings);
    // Text after endsolid that is not a solid.
    let e = read_err("e.stl", good.clone() + "garbage\n");
    assert_eq!(e.message, "expected 'solid', found 'garbage'");
}

#[test]
fn ascii_empty_solid() {
    let loaded = read_as("e.stl", "solid empty\nendsolid empty\n").unwrap();
    assert_eq!(loaded.format, Format::StlAscii);
    assert_eq!(loaded.face_count(), 0);
    assert!(matches!(loaded.surface, LoadedSurface::Mesh(_)));
}

#[test]
fn binary_and_ascii_agree() {
    let tris = box_triangles([0.5, 0.25, 0.125], [1.0, 2.0, 4.0]); // exact in f32
    let b = read_as("b.stl", binary_stl("solid b", &tris)).unwrap();
    let a = read_as("a.stl", ascii_solid("a", &tris, "\n")).unwrap();
    assert_eq!(triangles(&a.surface), triangles(&b.surface));
    assert_eq!(a.surface.face_count(), b.surface.face_count());
}

#[test]
fn binary_soup_measures_as_its_mesh_bit_for_bit() {
    // A soup says its faces are triangles, so the mass properties read it four faces a
    // SIMD step; its mesh (three vertices a triangle) takes the indexed arrays' lanes.
    // 4k + 3 triangles (a remainder), a corner at −0.0, off the origin.
    let mut tris = Vec::new();
    for k in 0..7 {
        let o = [k as f64 * 2.5 - 4.0, 1.25 * k as f64, -0.5];
        tris.extend(box_triangles(o, [1.0, 2.0, 0.5]));
    }
    tris.push([[-0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    tris.push([[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    tris.push([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]);
    assert_eq!(tris.len() % 4, 3);
    let loaded = read_as("boxes.stl", binary_stl("", &tris)).unwrap();
    let LoadedSurface::StlSoup(soup) = &loaded.surface else { panic!("not a soup") };
    assert!(soup.faces_are_triangles() && loaded.surface.faces_are_triangles());
    let mesh = soup.to_mesh().unwrap();
    let expected = format!("{:?}", meshvol::mass_properties(&mesh));
    assert_eq!(format!("{:?}", meshvol::mass_properties(soup)), expected);
    assert_eq!(format!("{:?}", meshvol::mass_properties(&loaded.surface)), expected);
    // Seven boxes of 1; the three open triangles meet the origin, adding no volume.
    assert_close(meshvol::mass_properties(soup).signed_volume, 7.0, 1e-12);
}

#[test]
fn binary_soup_checks_as_its_mesh() {
    // A soup gives its corners as the file's f32 values, and the check welds those;
    // its mesh (three f64 vertices a triangle) is welded in f64: the same facts, bit
    // for bit. Two boxes sharing a corner written as −0.0 and 0.0, a third one f32
    // step off (not welded: a crack), and a face repeated.
    let mut tris = box_triangles([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
    tris.extend(box_triangles([-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]));
    for t in &mut tris[12..] {
        for p in t.iter_mut() {
            *p = p.map(|x| if x == 0.0 { -0.0 } else { x });
        }
    }
    let step = f64::from(f32::from_bits(2.0f32.to_bits() + 1));
    let mut third = box_triangles([2.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
    third[0][0][0] = if third[0][0][0] == 2.0 { step } else { third[0][0][0] };
    tris.extend(third);
    tris.push(tris[3]);
    let loaded = read_as("boxes.stl", binary_stl("", &tris)).unwrap();
    let LoadedSurface::StlSoup(soup) = &loaded.surface else { panic!("not a soup") };
    assert!(Surface::triangle_f32(soup, 0).is_some());
    let mesh = soup.to_mesh().unwrap();
    assert!(mesh.triangle_f32(0).is_none());
    let options = meshvol::topology::CheckOptions {
        weld: meshvol::topology::Weld::Exact,
        ..Default::default()
    };
    let of_soup = meshvol::topology::check(soup, &options).unwrap();
    let of_mesh = meshvol::topology::check(&mesh, &options).unwrap();
    assert_eq!(format!("{of_soup:?}"), format!("{of_mesh:?}"));
    // Independently: 3 boxes of 8 corners, the first two sharing one (23), and the
    // third box's corner moved in one triangle, a 24th vertex that opens it (the
    // crack); one face is a duplicate.
    assert_eq!((of_soup.vertices, of_soup.duplicate_faces), (24, 1));
    assert!(of_soup.boundary_edges > 0);
}
