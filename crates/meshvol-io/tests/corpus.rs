//! The shared corpus of real files (../shared/corpus), when it is present.

mod common;

use std::path::{Path, PathBuf};

use common::*;
use meshvol_io::{read, Format};

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
            if ["stl", "obj", "off"].contains(&ext.to_ascii_lowercase().as_str()) {
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

    // Two cubes in one ASCII STL: warned about, measured together.
    let two = read(&models.join("multibody.stl")).unwrap();
    assert_eq!(two.format, Format::StlAscii);
    assert!(two.warnings.iter().any(|w| w.contains("2 solids")), "{:?}", two.warnings);

    // Broken on purpose.
    assert!(read(&models.join("notenoughindices.obj")).is_err());
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
