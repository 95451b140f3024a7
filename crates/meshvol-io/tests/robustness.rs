//! Random mutations of valid files: every reader returns Ok or Err, never panics.

mod common;

use std::panic::{catch_unwind, AssertUnwindSafe};

use common::*;
use meshvol_io::write::PlyEncoding;

fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let tris = box_triangles([0.0, 0.0, 0.0], [1.0, 2.0, 3.0]);
    let mut obj = String::new();
    for p in box_corners([0.0; 3], [1.0, 2.0, 3.0]) {
        obj += &format!("v {} {} {} 1 0 0\n", p[0], p[1], p[2]);
    }
    obj += "vn 0 0 1\nvt 0 0\nl 1 2\n";
    for (i, q) in BOX_QUADS.iter().enumerate() {
        if i % 2 == 0 {
            obj += &format!("f {}/1/1 {}//1 {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
        } else {
            let n = q.map(|k| k as i64 - 8);
            obj += &format!("f {} {} {} {}\r\n", n[0], n[1], n[2], n[3]);
        }
    }
    let mesh = box_mesh([0.0; 3], [1.0, 2.0, 3.0]);
    let ply = |encoding| {
        let mut out = vec![];
        meshvol_io::write::ply(&mut out, &mesh, encoding).unwrap();
        out
    };
    let mut glb = vec![];
    meshvol_io::write::glb(&mut glb, &mesh).unwrap();
    let mut off = String::from("OFF\n# box\n8 6 12\n");
    for p in box_corners([0.0; 3], [1.0, 2.0, 3.0]) {
        off += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    for q in BOX_QUADS {
        off += &format!("4 {} {} {} {} 1 0 0\n", q[0], q[1], q[2], q[3]);
    }
    vec![
        ("m.stl", binary_stl("solid binary", &tris)),
        ("m.stl", ascii_solid("a", &tris, "\n").into_bytes()),
        (
            "m.stl",
            (ascii_solid("", &tris[..3], "\r\n") + &ascii_solid("b", &tris[3..], "\n"))
                .into_bytes(),
        ),
        ("m.obj", obj.into_bytes()),
        ("m.off", off.into_bytes()),
        ("m.ply", ply(PlyEncoding::Ascii)),
        ("m.ply", ply(PlyEncoding::BinaryLittleEndian)),
        ("m.ply", ply(PlyEncoding::BinaryBigEndian)),
        ("m.glb", glb),
        (
            "m.3mf",
            three_mf(&format!(
                r#"<model unit="inch"><resources><object id="1">{}</object><object id="2"><components><component objectid="1" transform="1 0 0 0 1 0 0 0 1 5 0 0"/></components></object></resources><build><item objectid="1"/><item objectid="2"/></build></model>"#,
                three_mf_box_mesh([0.0; 3], [1.0, 2.0, 3.0])
            )),
        ),
    ]
}

#[test]
fn mutated_files_never_panic() {
    // MESHVOL_IO_FUZZ_ROUNDS=100000 for a longer run.
    let rounds: usize =
        std::env::var("MESHVOL_IO_FUZZ_ROUNDS").ok().and_then(|r| r.parse().ok()).unwrap_or(1500);
    let seed: u64 =
        std::env::var("MESHVOL_IO_FUZZ_SEED").ok().and_then(|r| r.parse().ok()).unwrap_or(1);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15 ^ seed);
    let (mut ok, mut err) = (0, 0);
    for (name, seed) in seeds() {
        assert!(read_as(name, seed.clone()).is_ok(), "seed {name} must read");
        for round in 0..rounds {
            let input = mutate(&mut rng, &seed);
            // Through the extension's reader and through sniffing.
            for as_name in [name, "m.bin"] {
                let result = catch_unwind(AssertUnwindSafe(|| read_as(as_name, input.clone())));
                match result {
                    Ok(Ok(loaded)) => {
                        ok += 1;
                        // What was read can be measured.
                        assert!(volume(&loaded.surface).is_finite());
                    }
                    Ok(Err(e)) => {
                        err += 1;
                        assert!(e.to_string().starts_with(as_name), "{e}");
                        assert!(!e.message.is_empty());
                    }
                    Err(_) => {
                        let path = std::env::temp_dir()
                            .join(format!("meshvol-io-panic-{round}-{as_name}"));
                        std::fs::write(&path, &input).unwrap();
                        panic!(
                            "{as_name} round {round} panicked; input saved to {}",
                            path.display()
                        );
                    }
                }
            }
        }
    }
    println!("{ok} read, {err} rejected");
    assert!(ok > 100 && err > 100, "{ok} read, {err} rejected");
}

#[test]
fn random_bytes_never_panic() {
    let mut rng = Rng(12345);
    for round in 0..2000 {
        let n = rng.below(300);
        let input: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
        for name in ["r.stl", "r.obj", "r.off", "r.ply", "r.3mf", "r.gltf", "r.glb", "r"] {
            let result = catch_unwind(AssertUnwindSafe(|| read_as(name, input.clone())));
            assert!(result.is_ok(), "{name} round {round} panicked on {input:?}");
        }
    }
}
