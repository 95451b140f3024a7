//! Every input in fuzz/regressions/ (one folder per fuzz target) is read as the target
//! reads it, on every test run: a mesh the kernel can measure, or an error naming the
//! file, never a panic. The hostile files of the security review are here too (glTF
//! buffers pointing outside their folder, integer positions), and must be errors.

mod common;
use meshvol::Surface;
use std::path::Path;

/// The file name a fuzz target reads its input as.
fn name_for(target: &str) -> &'static str {
    match target {
        "stl" => "m.stl",
        "obj" => "m.obj",
        "off" => "m.off",
        "ply" => "m.ply",
        "threemf" | "threemf_model" => "m.3mf",
        "gltf" => "m.gltf",
        "glb" => "m.glb",
        _ => "-",
    }
}

#[test]
fn every_regression_input_is_read_or_refused_cleanly() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions");
    let mut read = 0;
    for target in std::fs::read_dir(&root).unwrap() {
        let target = target.unwrap();
        if !target.file_type().unwrap().is_dir() {
            continue;
        }
        let target_name = target.file_name().into_string().unwrap();
        let name = name_for(&target_name);
        for file in std::fs::read_dir(target.path()).unwrap() {
            let path = file.unwrap().path();
            let mut bytes = std::fs::read(&path).unwrap();
            if target_name == "threemf_model" {
                bytes = common::three_mf(&String::from_utf8_lossy(&bytes));
            }
            match common::read_as(name, bytes) {
                Ok(loaded) => {
                    let faces = loaded.surface.face_count();
                    assert!(loaded.objects.iter().all(|o| o.faces.end <= faces), "{path:?}");
                    let _ = meshvol::mass_properties(&loaded.surface);
                }
                Err(e) => assert!(e.to_string().starts_with(name), "{path:?}: {e}"),
            }
            read += 1;
        }
    }
    assert!(read >= 10, "only {read} regression inputs found in {root:?}");
}

#[test]
fn hostile_gltf_inputs_are_errors() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions/gltf");
    for file in ["parent-uri", "percent-parent-uri", "dev-zero-uri", "integer-position"] {
        let bytes = std::fs::read(root.join(format!("{file}.gltf"))).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = common::write_temp(dir.path(), "m.gltf", &bytes);
        assert!(meshvol_io::read(&path).is_err(), "{file}");
    }
}
