//! The memory guard's estimate against the peak it bounds: each format's file of a
//! generated sphere read and checked, its heap counted by the allocator (and the file's
//! own bytes, mapped while it is read), must stay under what `meshvol_io::memory`
//! estimates before reading it (docs/security.md). The margin is printed: a guard far
//! above the peak would refuse files that fit.
//!
//! One test in its own binary: the counting allocator sees every thread of the process.

use meshvol::shapes::uv_sphere;
use meshvol::topology::{check_assembled, CheckOptions};
use meshvol::{Mesh, Surface};
use meshvol_io::Limits;
use std::io::Write;
use std::path::Path;

#[path = "../../meshvol/tests/counting_allocator/mod.rs"]
mod counting_allocator;

/// Coordinates as exporters write them: six decimals (shorter text than the shortest
/// round trip meshvol's writers use, so more triangles a byte: the case the estimate
/// from the file's size must cover).
fn xyz(p: [f64; 3]) -> String {
    format!("{:.6} {:.6} {:.6}", p[0], p[1], p[2])
}

fn obj(mesh: &Mesh) -> Vec<u8> {
    let mut s = String::new();
    for p in mesh.positions() {
        s += &format!("v {}\n", xyz(*p));
    }
    for t in triangles(mesh) {
        s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s.into_bytes()
}

fn off(mesh: &Mesh) -> Vec<u8> {
    let mut s = format!("OFF\n{} {} 0\n", mesh.positions().len(), mesh.face_count());
    for p in mesh.positions() {
        s += &format!("{}\n", xyz(*p));
    }
    for t in triangles(mesh) {
        s += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
    }
    s.into_bytes()
}

fn ply_header(mesh: &Mesh, format: &str) -> String {
    format!(
        "ply\nformat {format} 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.positions().len(),
        mesh.face_count()
    )
}

fn ply_ascii(mesh: &Mesh) -> Vec<u8> {
    let mut s = ply_header(mesh, "ascii");
    for p in mesh.positions() {
        s += &format!("{}\n", xyz(*p));
    }
    for t in triangles(mesh) {
        s += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
    }
    s.into_bytes()
}

/// Scanners' PLY: `float` positions, `uchar` counts, `int` indices.
fn ply_binary(mesh: &Mesh) -> Vec<u8> {
    let mut out = ply_header(mesh, "binary_little_endian").into_bytes();
    for p in mesh.positions() {
        for x in p {
            out.extend_from_slice(&(*x as f32).to_le_bytes());
        }
    }
    for t in triangles(mesh) {
        out.push(3);
        for i in t {
            out.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    out
}

fn stl_ascii(mesh: &Mesh) -> Vec<u8> {
    let mut s = String::from("solid sphere\n");
    mesh_triangles(mesh, |[a, b, c]| {
        s += &format!(
            "facet normal 0 0 0\nouter loop\nvertex {}\nvertex {}\nvertex {}\nendloop\nendfacet\n",
            xyz(a),
            xyz(b),
            xyz(c)
        );
    });
    (s + "endsolid sphere\n").into_bytes()
}

fn three_mf(mesh: &Mesh) -> Vec<u8> {
    let mut model = String::from(
        r#"<?xml version="1.0" encoding="UTF-8"?><model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources><object id="1" type="model"><mesh><vertices>"#,
    );
    for p in mesh.positions() {
        model += &format!(r#"<vertex x="{:.6}" y="{:.6}" z="{:.6}"/>"#, p[0], p[1], p[2]);
    }
    model += "</vertices><triangles>";
    for t in triangles(mesh) {
        model += &format!(r#"<triangle v1="{}" v2="{}" v3="{}"/>"#, t[0], t[1], t[2]);
    }
    model +=
        r#"</triangles></mesh></object></resources><build><item objectid="1"/></build></model>"#;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    let rels = r#"<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>"#;
    for (name, text) in [("_rels/.rels", rels), ("3D/3dmodel.model", &model)] {
        zip.start_file(name, options).unwrap();
        zip.write_all(text.as_bytes()).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

/// The GLB's JSON with its binary chunk as a base64 data URI: a self-contained `.gltf`.
fn gltf(glb: &[u8]) -> Vec<u8> {
    use base64::Engine;
    let chunk = |at: usize| {
        let len = u32::from_le_bytes(glb[at..at + 4].try_into().unwrap()) as usize;
        (&glb[at + 8..at + 8 + len], at + 8 + len)
    };
    let (json, next) = chunk(12);
    let (bin, _) = chunk(next);
    let mut json: serde_json::Value = serde_json::from_slice(json).unwrap();
    let data = base64::engine::general_purpose::STANDARD.encode(bin);
    json["buffers"][0]["uri"] = format!("data:application/octet-stream;base64,{data}").into();
    serde_json::to_vec(&json).unwrap()
}

fn triangles(mesh: &Mesh) -> Vec<[usize; 3]> {
    let mut out = Vec::new();
    for f in 0..mesh.face_count() {
        let face = mesh.face(f);
        out.push([face[0] as usize, face[1] as usize, face[2] as usize]);
    }
    out
}

fn mesh_triangles(mesh: &Mesh, mut each: impl FnMut([[f64; 3]; 3])) {
    for f in 0..mesh.face_count() {
        mesh.fan(f, |a, b, c| each([a, b, c]));
    }
}

/// The heap's peak while `path` is read and, if `checked`, checked, plus the file's
/// bytes (mapped, or held, while it is read), and the file's triangles.
fn peak(path: &Path, checked: bool) -> (u128, usize) {
    let unlimited = Limits { memory: None, checked, ..Limits::from_env() };
    let (triangles, heap) = counting_allocator::peak_above_start(|| {
        let loaded = meshvol_io::read_file_within(path, &unlimited).unwrap();
        let triangles = loaded.triangle_count();
        if checked {
            let bodies = loaded.body_faces();
            let c = check_assembled(
                &loaded.surface,
                loaded.assembly.as_ref(),
                &bodies,
                &CheckOptions::default(),
                &(),
            )
            .unwrap();
            assert!(c.bounds_a_volume());
        }
        triangles
    });
    (heap as u128 + std::fs::metadata(path).unwrap().len() as u128, triangles)
}

/// The bytes of a figure such as `1.2 MiB` in a refusal's "needs about 1.2 MiB;".
fn estimate_in(message: &str) -> f64 {
    let figure = message.split("needs about ").nth(1).unwrap().split(';').next().unwrap();
    let (value, unit) = figure.split_once(' ').unwrap();
    let scale = match unit {
        "KiB" => 1024.0,
        "MiB" => 1024.0 * 1024.0,
        _ => panic!("{message}"),
    };
    value.parse::<f64>().unwrap() * scale
}

#[test]
fn the_estimate_bounds_the_peak_of_every_format() {
    // 100,800 triangles: large enough that the per-triangle arrays dominate.
    let mesh = uv_sphere(1.0, 300, 169).triangulated();
    let dir = tempfile::tempdir().unwrap();
    let mut stl = Vec::new();
    meshvol_io::write::stl_binary(&mut stl, &mesh).unwrap();
    let mut glb = Vec::new();
    meshvol_io::write::glb(&mut glb, &mesh).unwrap();
    let files = [
        ("sphere.stl", stl),
        ("ascii.stl", stl_ascii(&mesh)),
        ("sphere.obj", obj(&mesh)),
        ("sphere.off", off(&mesh)),
        ("ascii.ply", ply_ascii(&mesh)),
        ("binary.ply", ply_binary(&mesh)),
        ("sphere.gltf", gltf(&glb)),
        ("sphere.glb", glb),
        ("sphere.3mf", three_mf(&mesh)),
    ];
    for (name, bytes) in files {
        let path = dir.path().join(name);
        std::fs::write(&path, &bytes).unwrap();
        for checked in [false, true] {
            let (peak, triangles) = peak(&path, checked);
            // Refused with a byte less than the peak: the estimate is at least the peak.
            let short = Limits { memory: Some(peak - 1), checked, ..Limits::from_env() };
            let e = meshvol_io::read_file_within(&path, &short).unwrap_err().to_string();
            let estimate = estimate_in(&e);
            let t = triangles as f64;
            eprintln!(
                "{name} checked={checked}: file {:.1} B/tri, peak {:.1} B/tri, estimate {:.1} \
                 B/tri ({:.2}x)",
                bytes.len() as f64 / t,
                peak as f64 / t,
                estimate / t,
                estimate / peak as f64
            );
            // Not far above it: the guard does not refuse what fits with room to spare.
            assert!(estimate < 2.0 * peak as f64, "{name} checked={checked}: {e}");
        }
    }
}
