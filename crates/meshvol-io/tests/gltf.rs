//! glTF and GLB: node transforms, primitive modes, buffers, errors.

mod common;

use base64::Engine;
use common::*;
use meshvol_io::{Format, LengthUnit, Location};

/// The unit cube's eight corners as f32 bytes, and its twelve outward triangles as u16.
fn cube_buffer() -> (Vec<u8>, usize) {
    let mut bin = vec![];
    for p in box_corners([0.0; 3], [1.0; 3]) {
        for c in p {
            bin.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    let positions = bin.len();
    for q in BOX_QUADS {
        for i in [q[0], q[1], q[2], q[0], q[2], q[3]] {
            bin.extend_from_slice(&(i as u16).to_le_bytes());
        }
    }
    (bin, positions)
}

/// A .gltf with the cube in a data: URI, and `nodes` / `scenes` JSON as given.
fn cube_gltf(nodes: &str, extra: &str) -> String {
    let (bin, positions) = cube_buffer();
    let data = base64::engine::general_purpose::STANDARD.encode(&bin);
    format!(
        r#"{{"asset":{{"version":"2.0"}},{extra}"nodes":{nodes},
        "meshes":[{{"name":"cube","primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3"}},
                     {{"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}}],
        "bufferViews":[{{"buffer":0,"byteLength":{positions}}},
                       {{"buffer":0,"byteOffset":{positions},"byteLength":72}}],
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{data}"}}]}}"#,
        bin.len()
    )
}

#[test]
fn glb_written_and_read_back() {
    let mesh = box_mesh([1.0, 2.0, 3.0], [2.0, 3.0, 4.0]);
    let mut bytes = vec![];
    meshvol_io::write::glb(&mut bytes, &mesh).unwrap();
    for name in ["b.glb", "b.gltf", "b", "-"] {
        let loaded = read_as(name, bytes.clone()).unwrap();
        assert_eq!(loaded.format, Format::Glb);
        assert_eq!(loaded.unit, Some(LengthUnit::Metre));
        assert_eq!(loaded.face_count(), 12);
        assert!(loaded.objects.is_empty());
        assert_eq!(volume(&loaded.surface), 24.0);
    }
}

#[test]
fn node_transforms_compose_down_the_tree() {
    // Node 0: translate (10, 0, 0), child 1: scale 2 (volume 8), child 2: a quarter turn
    // and mirror in x by matrix (volume 1, mirrored: the winding is reversed back).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let nodes = format!(
        r#"[{{"name":"root","translation":[10,0,0],"children":[1,2]}},
            {{"name":"big","scale":[2,2,2],"mesh":0}},
            {{"mesh":0,"rotation":[0,0,{h},{h}],"children":[3]}},
            {{"name":"mirrored","matrix":[-1,0,0,0, 0,1,0,0, 0,0,1,0, 5,0,0,1],"mesh":0}},
            {{"name":"not in the scene","mesh":0}}]"#
    );
    let text = cube_gltf(&nodes, r#""scene":1,"scenes":[{"nodes":[4]},{"nodes":[0]}],"#);
    let loaded = read_as("scene.gltf", text).unwrap();
    assert_eq!(loaded.format, Format::Gltf);
    let names: Vec<&str> = loaded.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["big", "cube", "mirrored"]);
    let v: Vec<f64> = loaded
        .objects
        .iter()
        .map(|o| volume(&meshvol::surface::FaceRange::new(&loaded.surface, o.faces.clone())))
        .collect();
    assert_close(v[0], 8.0, 1e-12);
    assert_close(v[1], 1.0, 1e-12);
    assert_close(v[2], 1.0, 1e-12);
    // Where the corners went: "big" spans x in [10, 12]; the turned cube spans x in
    // [9, 10] (a quarter turn about z maps x to y, y to -x); the mirrored one, placed
    // in the turned frame at x in [4, 5] → y in [4, 5].
    let t = triangles(&meshvol::surface::FaceRange::new(
        &loaded.surface,
        loaded.objects[0].faces.clone(),
    ));
    assert!(t.iter().flatten().all(|p| (10.0..=12.0).contains(&p[0])));
    let t = triangles(&meshvol::surface::FaceRange::new(
        &loaded.surface,
        loaded.objects[1].faces.clone(),
    ));
    assert!(t.iter().flatten().all(|p| (9.0 - 1e-12..=10.0 + 1e-12).contains(&p[0])));
    let t = triangles(&meshvol::surface::FaceRange::new(
        &loaded.surface,
        loaded.objects[2].faces.clone(),
    ));
    assert!(t.iter().flatten().all(|p| (4.0 - 1e-12..=5.0 + 1e-12).contains(&p[1])), "{t:?}");
}

/// One primitive as its own document: positions (f32 VEC3) and optional u8 indices.
fn primitive(points: &[[f32; 3]], indices: Option<&[u8]>, mode: u32) -> Vec<u8> {
    let mut bin: Vec<u8> = points.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
    let positions = bin.len();
    let (index_attr, index_accessor) = match indices {
        Some(i) => {
            bin.extend_from_slice(i);
            (
                r#","indices":1"#.to_string(),
                format!(
                    r#",{{"bufferView":1,"componentType":5121,"count":{},"type":"SCALAR"}}"#,
                    i.len()
                ),
            )
        }
        None => (String::new(), String::new()),
    };
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"mode":{mode}{index_attr}}}]}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3"}}{index_accessor}],
        "bufferViews":[{{"buffer":0,"byteLength":{positions}}},{{"buffer":0,"byteOffset":{positions},"byteLength":{}}}],
        "buffers":[{{"byteLength":{}}}]}}"#,
        points.len(),
        bin.len() - positions,
        bin.len()
    );
    glb_container(json.as_bytes(), &bin)
}

/// A GLB from its JSON and BIN chunks.
fn glb_container(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let mut json = json.to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&((28 + json.len() + bin.len()) as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out
}

const TETRA: [[f32; 3]; 4] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

#[test]
fn triangles_strips_and_fans() {
    // Indexed triangles.
    let l = read_as("t.glb", primitive(&TETRA, Some(&[0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]), 4))
        .unwrap();
    assert_eq!(volume(&l.surface), 1.0 / 6.0);
    // Not indexed: the same triangles spelled out.
    let spelled: Vec<[f32; 3]> =
        [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3].iter().map(|&i| TETRA[i]).collect();
    let l = read_as("t.glb", primitive(&spelled, None, 4)).unwrap();
    assert_eq!(volume(&l.surface), 1.0 / 6.0);
    // A strip 0 2 1 3 0 2 walks all four faces; even triangles keep their order, odd
    // ones swap, so the closed surface comes out consistently wound (±1/6 only then).
    let l = read_as("t.glb", primitive(&TETRA, Some(&[0, 2, 1, 3, 0, 2]), 5)).unwrap();
    assert_eq!(l.face_count(), 4);
    assert_close(volume(&l.surface).abs(), 1.0 / 6.0, 1e-15);
    // A fan around the apex (0, 0, 1) over the square's corners, then the base as a fan.
    let square: Vec<[f32; 3]> =
        vec![[0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let sides = read_as("t.glb", primitive(&square, Some(&[0, 1, 2, 3, 4, 1]), 6)).unwrap();
    let base = read_as("t.glb", primitive(&square, Some(&[1, 4, 3, 2]), 6)).unwrap();
    assert_eq!((sides.face_count(), base.face_count()), (4, 2));
    assert_close(volume(&sides.surface) + volume(&base.surface), 1.0 / 3.0, 1e-15);
    // Points and lines: skipped with a warning.
    let l = read_as("t.glb", primitive(&TETRA, None, 0)).unwrap();
    assert_eq!(l.face_count(), 0);
    assert_eq!(l.warnings, ["skipped 1 point and line primitives (no volume)"]);
}

#[test]
fn external_buffers_beside_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let (bin, positions) = cube_buffer();
    write_temp(dir.path(), "cube data.bin", &bin);
    let text = cube_gltf(r#"[{"mesh":0}]"#, "").replace(
        &format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&bin)
        ),
        "cube%20data.bin",
    );
    assert!(text.contains("cube%20data.bin") && positions == 96);
    let path = write_temp(dir.path(), "cube.gltf", text.as_bytes());
    let loaded = meshvol_io::read(&path).unwrap();
    assert_close(volume(&loaded.surface), 1.0, 1e-15);
    std::fs::remove_file(dir.path().join("cube data.bin")).unwrap();
    let e = meshvol_io::read(&path).unwrap_err();
    assert_eq!(e.location, Some(Location::Json("buffers[0]".into())));
    assert!(e.message.contains("cannot read"), "{e}");
}

#[test]
fn sparse_and_quantized_positions() {
    // Positions as normalized u16 (KHR_mesh_quantization), corner 3 moved by a sparse
    // substitution from (0, 0, 0) to (0, 0, 1): the tetrahedron.
    let mut bin = vec![];
    for p in [[0u16, 0, 0], [65535, 0, 0], [0, 65535, 0], [0, 0, 0]] {
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    bin.extend_from_slice(&[3, 0, 0, 0]); // sparse index (u8), padded
    for c in [0u16, 0, 65535, 0] {
        bin.extend_from_slice(&c.to_le_bytes()); // sparse value, padded
    }
    let json = r#"{"asset":{"version":"2.0"},"extensionsUsed":["KHR_mesh_quantization"],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
        "accessors":[{"bufferView":0,"componentType":5123,"normalized":true,"count":4,"type":"VEC3",
                      "sparse":{"count":1,"indices":{"bufferView":1,"componentType":5121},
                                "values":{"bufferView":2}}},
                     {"bufferView":3,"componentType":5125,"count":12,"type":"SCALAR"}],
        "bufferViews":[{"buffer":0,"byteLength":24},{"buffer":0,"byteOffset":24,"byteLength":1},
                       {"buffer":0,"byteOffset":28,"byteLength":6},{"buffer":0,"byteOffset":36,"byteLength":48}],
        "buffers":[{"byteLength":84}]}"#;
    for i in [0u32, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let loaded = read_as("q.glb", glb_container(json.as_bytes(), &bin)).unwrap();
    assert_eq!(volume(&loaded.surface), 1.0 / 6.0);
    // Without the extension, integer positions are not glTF: an error, not numbers
    // read as something they are not.
    let plain = json.replace(r#""extensionsUsed":["KHR_mesh_quantization"],"#, "");
    let e = read_as("q.glb", glb_container(plain.as_bytes(), &bin)).unwrap_err();
    assert_eq!(e.location, Some(Location::Json("accessors[0]".into())));
    assert!(e.message.contains("only FLOAT"), "{e}");
}

#[test]
fn errors_name_the_item() {
    let bad = |text: &str, location: Location, message: &str| {
        let e = read_err("e.gltf", text.to_string());
        assert_eq!(e.location, Some(location), "{e}");
        assert!(e.message.contains(message), "{e}");
    };
    let cube = cube_gltf(r#"[{"mesh":0}]"#, "");
    bad(
        &cube.replace(r#""count":36"#, r#""count":37"#),
        Location::Json("accessors[1]".into()),
        "do not fit",
    );
    bad(
        &cube.replace(r#""count":8,"#, r#""count":7,"#),
        Location::Json("accessors[1]".into()),
        "out of range: POSITION has 7",
    );
    let cycle = cube_gltf(
        r#"[{"mesh":0,"children":[1]},{"children":[0]}]"#,
        r#""scenes":[{"nodes":[0]}],"#,
    );
    bad(&cycle, Location::Json("nodes[0]".into()), "reached twice");
    bad(&cube_gltf(r#"[{"mesh":3}]"#, ""), Location::Json("nodes[0].mesh".into()), "no mesh 3");
    bad(
        &cube.replace(r#""version":"2.0""#, r#""version":"1.0""#),
        Location::Json("asset.version".into()),
        "1.0",
    );
    bad(
        &cube.replace(
            r#""asset""#,
            r#""extensionsRequired":["KHR_draco_mesh_compression"],"asset""#,
        ),
        Location::Json("extensionsRequired".into()),
        "draco",
    );
    bad("{\n\"nodes\": [}", Location::Line(2), "not a glTF document");

    let glb = primitive(&TETRA, None, 4);
    let e = read_err("e.glb", glb[..glb.len() - 4].to_vec());
    assert_eq!(e.location, Some(Location::Byte((glb.len() - 4) as u64)));
    assert!(e.message.contains("truncated"), "{e}");
    let mut v1 = glb.clone();
    v1[4] = 1;
    assert!(read_err("e.glb", v1).message.contains("version 1"));
}

/// The cube's .gltf with its buffer in the file named by `uri` (written by the caller).
fn cube_gltf_with_file(uri: &str) -> String {
    let data_uri = cube_gltf(r#"[{"mesh":0}]"#, "");
    let start = data_uri.find("data:application").unwrap();
    let end = start + data_uri[start..].find('"').unwrap();
    format!("{}{uri}{}", &data_uri[..start], &data_uri[end..])
}

#[test]
fn buffers_are_read_from_the_gltf_folder_only() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("models/part");
    std::fs::create_dir_all(&sub).unwrap();
    let (bin, _) = cube_buffer();
    // A file next to the glTF is read, and only byteLength bytes of it (the rest of a
    // larger file is not read: 1 MiB of garbage after the cube's bytes).
    let mut padded = bin.clone();
    padded.resize(bin.len() + (1 << 20), 0xff);
    std::fs::write(sub.join("cube data.bin"), &padded).unwrap();
    std::fs::write(dir.path().join("secret.bin"), &bin).unwrap();
    let gltf = sub.join("part.gltf");
    std::fs::write(&gltf, cube_gltf_with_file("cube%20data.bin")).unwrap();
    let loaded = meshvol_io::read(&gltf).unwrap();
    assert_eq!(volume(&loaded.surface), 1.0);
    // Out of the folder: parent steps (plain or percent-encoded), absolute paths,
    // devices, and a symbolic link that leads out.
    std::os::unix::fs::symlink(dir.path().join("secret.bin"), sub.join("link.bin")).unwrap();
    for uri in [
        "../../secret.bin",
        "%2e%2e/%2e%2e/secret.bin",
        "./../../secret.bin",
        "/dev/zero",
        "../../../../../../../../dev/zero",
        "file:///etc/passwd",
        "link.bin",
    ] {
        std::fs::write(&gltf, cube_gltf_with_file(uri)).unwrap();
        let e = meshvol_io::read(&gltf).unwrap_err();
        assert_eq!(e.location, Some(Location::Json("buffers[0]".into())), "{uri}: {e}");
        assert!(e.message.contains("folder") || e.message.contains("regular file"), "{uri}: {e}");
    }
    // From standard input there is no folder to read from.
    let e = read_as("-", cube_gltf_with_file("cube%20data.bin").into_bytes()).unwrap_err();
    assert!(e.message.contains("standard input"), "{e}");
}

/// A `.gltf` in a zip archive reads its external buffers from the archive, beside it
/// there: from a file, from bytes named `.zip` (an upload), and from standard input.
#[test]
fn buffers_of_a_gltf_in_a_zip_are_read_from_the_zip() {
    let dir = tempfile::tempdir().unwrap();
    let (bin, _) = cube_buffer();
    let gltf = cube_gltf_with_file("cube%20data.bin");
    // A cube.bin at the top holds other bytes: only the one beside the glTF is its buffer.
    let archive = zip_of(&[
        ("models/cube.gltf", gltf.as_bytes()),
        ("models/cube data.bin", &bin),
        ("cube data.bin", &[0u8; 96]),
        ("readme.txt", b"a cube"),
    ]);
    let path = write_temp(dir.path(), "cube.zip", &archive);
    // The unit cube, as the same glTF with its buffer in a data: URI reads.
    let plain = read_as("cube.gltf", cube_gltf(r#"[{"mesh":0}]"#, "")).unwrap();
    assert_eq!(volume(&plain.surface), 1.0);
    for loaded in [
        meshvol_io::read(&path).unwrap(),
        read_as("cube.zip", archive.clone()).unwrap(),
        read_as("-", archive).unwrap(),
    ] {
        assert_eq!(loaded.format, Format::Gltf);
        assert_eq!(triangles(&loaded.surface), triangles(&plain.surface));
    }
    // A buffer the archive lacks, or one outside the glTF's folder in it, is an error at
    // the buffer that says what to do: never the system's "Not a directory".
    for (uri, says) in [("cube.bin", "zip the .glb"), ("../cube%20data.bin", "folder")] {
        let archive = zip_of(&[
            ("models/cube.gltf", cube_gltf_with_file(uri).as_bytes()),
            ("cube data.bin", &bin),
        ]);
        let path = write_temp(dir.path(), "broken.zip", &archive);
        let e = meshvol_io::read(&path).unwrap_err();
        assert_eq!(e.location, Some(Location::Json("buffers[0]".into())), "{uri}: {e}");
        assert!(e.message.contains(says) && !e.message.contains("os error"), "{uri}: {e}");
        assert!(e.to_string().contains("broken.zip/models/cube.gltf"), "{e}");
    }
}

#[test]
fn a_mesh_placed_by_many_nodes_is_decoded_once() {
    // 10⁴ nodes place the unit cube side by side: volume 10⁴ exactly, one object each.
    let n = 10_000;
    let nodes: Vec<String> = (0..n)
        .map(|i| format!(r#"{{"mesh":0,"translation":[{},{},0]}}"#, 2 * (i % 100), 2 * (i / 100)))
        .collect();
    let loaded = read_as("many.gltf", cube_gltf(&format!("[{}]", nodes.join(",")), "")).unwrap();
    assert_eq!(loaded.objects.len(), n);
    assert_eq!(loaded.face_count(), 12 * n);
    assert_eq!(meshvol::exact_signed_volume(&loaded.surface).unwrap(), n as f64);
    // The assembly names the one primitive and its 10⁴ placements, and checking from it
    // finds what checking every copy finds.
    let assembly = loaded.assembly.as_ref().expect("a mesh placed many times");
    assert_eq!((assembly.parts.len(), assembly.placements.len()), (1, n));
    use meshvol::topology::{check, check_assembled, CheckOptions};
    let options = CheckOptions::default();
    let whole = check(&loaded.surface, &options).unwrap();
    let parts = check_assembled(&loaded.surface, Some(assembly), &[], &options, &|_| {}).unwrap();
    let facts = |c: &meshvol::topology::Check| {
        (c.shells.len(), c.vertices, c.edges, c.closed, c.orientation, c.volume)
    };
    assert_eq!(facts(&parts), facts(&whole));
    assert_eq!(
        facts(&whole),
        (n, 8 * n, 18 * n, true, Some(meshvol::topology::Orientation::Outward), n as f64)
    );
}
