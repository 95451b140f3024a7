//! The shared corpus of real files (../shared/corpus), when it is present: every file
//! reads or fails clearly, facts known from outside, and agreement with trimesh's
//! volumes (tests/data/corpus-trimesh.json, written by scripts/corpus-reference.py).

mod common;

use std::path::{Path, PathBuf};

use common::*;
use meshvol_io::{read, Format, FormatSource, LengthUnit};

/// The mesh formats read; the corpus's `.zip` sets (zipped STL and OBJ files, glTF
/// scenes with textures) are not opened.
const EXTENSIONS: [&str; 7] = ["stl", "obj", "off", "ply", "3mf", "gltf", "glb"];

fn corpus() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("corpus not found at {}, skipping", dir.display());
        None
    }
}

fn mesh_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> =
        std::fs::read_dir(dir).unwrap().filter_map(|e| e.ok()).map(|e| e.path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            mesh_files(&path, out);
        } else if let Some(ext) = path.extension().and_then(|e| e.to_str()) {
            if EXTENSIONS.contains(&ext.to_ascii_lowercase().as_str()) {
                out.push(path);
            }
        }
    }
}

#[test]
fn every_corpus_file_reads_or_fails_clearly() {
    let Some(dir) = corpus() else { return };
    let mut files = vec![];
    mesh_files(&dir, &mut files);
    assert!(!files.is_empty());
    for path in &files {
        match read(path) {
            Ok(loaded) => {
                let v = volume(&loaded.surface);
                assert!(v.is_finite(), "{}", path.display());
                println!(
                    "ok   {} [{}] {} vertices, {} faces, {} triangles, volume {v:.6}{}",
                    path.display(),
                    loaded.format,
                    loaded.vertex_count(),
                    loaded.face_count(),
                    loaded.triangle_count(),
                    if loaded.warnings.is_empty() {
                        String::new()
                    } else {
                        format!(" ({})", loaded.warnings.join("; "))
                    }
                );
            }
            Err(e) => {
                let shown = e.to_string();
                assert!(shown.starts_with(&path.display().to_string()), "{shown}");
                println!("err  {shown}");
            }
        }
    }
}

#[test]
fn known_facts() {
    let Some(dir) = corpus() else { return };
    let models = dir.join("trimesh-models");
    let cube = read(&models.join("unit_cube.STL")).unwrap();
    assert_eq!(cube.format, Format::StlBinary);
    assert_eq!(cube.face_count(), 12);
    assert_close(volume(&cube.surface).abs(), 1.0, 1e-6);

    // A tessellated unit sphere: a little under 4π/3.
    let sphere = read(&models.join("unit_sphere.STL")).unwrap();
    let v = volume(&sphere.surface).abs();
    assert!(
        v < 4.0 / 3.0 * std::f64::consts::PI && v > 0.95 * 4.0 / 3.0 * std::f64::consts::PI,
        "{v}"
    );

    // OBJ with negative indices: a cube of side 2 written with quads.
    let neg = read(&models.join("negative_indices.obj")).unwrap();
    assert_eq!((neg.vertex_count(), neg.face_count()), (8, 6));
    assert_close(volume(&neg.surface).abs(), 8.0, 1e-12);

    // OFF cube with comments (edge 1.632993·√2 ≈ 2.3094, rotated): volume = edge³.
    for name in ["comments.off", "whitespace.off"] {
        let off = read(&models.join(name)).unwrap();
        assert_eq!((off.vertex_count(), off.face_count()), (8, 6), "{name}");
        let edge = (2.0f64 * 1.632993f64.powi(2)).sqrt();
        assert_close(volume(&off.surface).abs(), edge.powi(3), 1e-4);
    }

    // Two bodies in one ASCII STL: two objects.
    let two = read(&models.join("multibody.stl")).unwrap();
    assert_eq!(two.format, Format::StlAscii);
    let names: Vec<&str> = two.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["bodyB", "bodyA"]);

    // 3MF: units and objects. featuretype is in inches; the same part as an STL.
    let part = read(&models.join("featuretype.3MF")).unwrap();
    assert_eq!((part.format, part.unit), (Format::ThreeMf, Some(LengthUnit::Inch)));
    let stl = read(&models.join("featuretype.STL")).unwrap();
    assert_close(volume(&part.surface) / volume(&stl.surface), 1.0, 1e-3);
    let pyramids = read(&models.join("pyramids.3mf")).unwrap();
    assert_eq!(pyramids.unit, Some(LengthUnit::Millimetre));
    assert_eq!(pyramids.objects.len(), 9, "{:?}", pyramids.objects);
    // Items 1..3 place the same object: equal volumes, different places.
    let v = |i: usize| {
        volume(&meshvol::surface::FaceRange::new(
            &pyramids.surface,
            pyramids.objects[i].faces.clone(),
        ))
    };
    assert_close(v(1), v(0), 1e-9 * v(0));
    // counterXP places five copies of one component with rotations: the same volume as
    // the STL export of the whole (counter.unitsmm.STL) to the STL's f32 rounding.
    let placed = read(&models.join("counterXP.3MF")).unwrap();
    let exported = read(&models.join("counter.unitsmm.STL")).unwrap();
    assert_close(volume(&placed.surface) / volume(&exported.surface), 1.0, 1e-6);

    // glTF: metres; nodes are objects; the default scene only.
    let boxes = read(&models.join("BoxInterleaved.glb")).unwrap();
    assert_eq!((boxes.format, boxes.unit), (Format::Glb, Some(LengthUnit::Metre)));
    assert_close(volume(&boxes.surface), 1.0, 1e-6);
    let scene = read(&models.join("TestScene.gltf")).unwrap();
    assert_eq!(scene.format, Format::Gltf);
    assert!(scene.objects.len() >= 2, "{:?}", scene.objects);

    // PLY: a point cloud reads with no faces; the textured ASCII fuze has extra values.
    let points = read(&models.join("points_bin.ply")).unwrap();
    assert_eq!((points.face_count(), points.vertex_count()), (0, 5));
    let fuze = read(&models.join("fuze_ascii.ply")).unwrap();
    let binary = read(&models.join("fuze.ply")).unwrap();
    assert_eq!(fuze.format_source, FormatSource::Extension);
    assert_close(volume(&fuze.surface), volume(&binary.surface), 1e-9);

    // Broken on purpose: line 9 is a face of two vertices, skipped (as trimesh does);
    // line 10 is a triangle.
    let short = read(&models.join("notenoughindices.obj")).unwrap();
    assert_eq!((short.face_count(), short.vertex_count()), (1, 3));
    assert_eq!(
        short.warnings,
        vec!["skipped 1 faces with fewer than 3 vertices (the first at line 9)"]
    );
    // NaN in a colour column only: fine.
    assert!(read(&models.join("nancolor.obj")).is_ok());
}

#[test]
fn mutated_corpus_files_never_panic() {
    let Some(dir) = corpus() else { return };
    let mut files = vec![];
    mesh_files(&dir, &mut files);
    let mut rng = Rng(99);
    for path in files {
        let bytes = std::fs::read(&path).unwrap();
        if bytes.len() > 100_000 {
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        for _ in 0..40 {
            let input = mutate(&mut rng, &bytes);
            if let Err(e) = read_as(&name, input) {
                assert!(e.to_string().starts_with(&name), "{e}");
            }
        }
    }
}

/// Closed meshes (trimesh: watertight and consistently wound) where meshvol and trimesh
/// differ by more than the relative 1e-6, with the reason. None so far. Files that are
/// not closed are not compared: their "volume" depends on the reference point of the
/// sum (multibody.stl: both bodies watertight but inconsistently wound, trimesh 0.01404
/// about its reference, meshvol's kernel -0.00248 about its own, the plain origin sum
/// 0.00370).
const TRIMESH_EXCEPTIONS: &[(&str, &str)] = &[];

/// meshvol's volume against trimesh's for every closed mesh of the corpus. Three files
/// differ by more than rounding, far below 1e-6, and the cause is known where checked:
/// - sphere.ply (4.0e-9): ASCII coordinates declared `float`; trimesh rounds the
///   decimals to f32 (volume 4.152740112525789 by a plain sum over f32-rounded values),
///   meshvol parses the digits written to f64 (4.152740129088976 by the same sum).
/// - counterXP.3MF (1.0e-9): the exact volume of the file's decimals and transforms, in
///   rational arithmetic, is 888808.1287328213; meshvol gives 888808.1287328196,
///   trimesh 888808.1278410442 (the same with `process=False`, so not vertex merging).
/// - pins.glb (2.7e-9): not traced; node transforms as in counterXP.
#[test]
fn volumes_agree_with_trimesh() {
    let Some(dir) = corpus() else { return };
    let reference: serde_json::Value =
        serde_json::from_str(include_str!("data/corpus-trimesh.json")).unwrap();
    let files = reference["files"].as_object().unwrap();
    let mut compared = 0;
    let mut disagree = vec![];
    for (name, r) in files {
        let closed = r["watertight"].as_bool() == Some(true)
            && r["winding_consistent"].as_bool() == Some(true);
        if !closed {
            continue;
        }
        let expected = r["volume"].as_f64().unwrap();
        let loaded = read(&dir.join(name)).unwrap_or_else(|e| panic!("trimesh reads it: {e}"));
        let v = meshvol::mass_properties(&loaded.surface).signed_volume;
        let relative = (v - expected).abs() / expected.abs();
        let exception = TRIMESH_EXCEPTIONS.iter().find(|(file, _)| file == name);
        println!("{name}: meshvol {v}, trimesh {expected}, relative {relative:.1e}");
        if relative > 1e-6 && exception.is_none() {
            disagree.push(format!("{name}: meshvol {v}, trimesh {expected}"));
        }
        compared += 1;
    }
    println!("{compared} closed meshes compared with trimesh {}", reference["trimesh_version"]);
    assert!(compared >= 40, "{compared}");
    assert!(disagree.is_empty(), "{disagree:#?}");
}

/// Every body of a checked manifold file is closed by its own caps: measured alone, each gives
/// the signed sum of its shells' volumes (solids +, cavities −), and the bodies add up
/// to the solid. A cap that closed another shell's hole (a boundary loop wandering
/// across a vertex where two shells touch, as in featuretype.3MF) breaks this.
#[test]
fn bodies_add_up_to_the_solid() {
    use meshvol::surface::FaceSubset;
    use meshvol::topology::{check, CheckOptions};
    let Some(dir) = corpus() else { return };
    let mut files = vec![];
    mesh_files(&dir, &mut files);
    let options = CheckOptions { intersections: false, ..CheckOptions::default() };
    for path in files.iter().filter(|p| std::fs::metadata(p).is_ok_and(|m| m.len() < 2 << 20)) {
        let Ok(loaded) = read(path) else { continue };
        let Ok(c) = check(&loaded.surface, &options) else { continue };
        // Where edges are shared by more than two faces, or a shell has no inside, the
        // capped shells are not closed and their volumes depend on the reference point.
        if c.non_manifold_edges > 0 || c.shells.iter().any(|s| !s.orientable) {
            continue;
        }
        let solid = c.solid(&loaded.surface);
        // Rounding scales with the box the surface spans, not with what it encloses.
        let size = meshvol::mass_properties(&loaded.surface).bounds.map_or(0.0, |b| {
            let d = b.size();
            d[0] * d[1] * d[2]
        });
        let scale = c.shells.iter().map(|s| s.volume).sum::<f64>().max(size);
        let mut total = 0.0;
        for body in c.bodies() {
            let measured =
                meshvol::mass_properties(&FaceSubset::new(solid, body.faces.clone())).signed_volume;
            // The shells of this body: the outer one and those nested in it.
            let in_body = |mut s: usize| loop {
                if s == body.shell {
                    return true;
                }
                match c.shells[s].parent {
                    Some(p) => s = p,
                    None => return false,
                }
            };
            let expected: f64 = (0..c.shells.len())
                .filter(|&s| in_body(s))
                .map(|s| if c.shells[s].cavity { -c.shells[s].volume } else { c.shells[s].volume })
                .sum();
            assert!(
                (measured - expected).abs() <= 1e-9 * scale,
                "{}: body of shell {}: measured {measured}, its shells {expected}",
                path.display(),
                body.shell
            );
            total += measured;
        }
        assert!((total - c.volume).abs() <= 1e-9 * scale, "{}", path.display());
    }
}
