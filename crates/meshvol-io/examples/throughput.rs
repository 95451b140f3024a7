//! Read throughput of the readers on generated files.
//!
//! ```text
//! cargo run --release -p meshvol-io --example throughput -- /tmp/meshvol-io-bench
//! ```
//!
//! Writes (once) into the directory: a torus as a ~100 MB ASCII STL, a ~100 MB OBJ, a
//! 1M-triangle binary STL, binary PLY and GLB, and an ASCII PLY of 400k triangles; then
//! reads each a few times and prints the best time in MB/s, and the time of
//! `mass_properties` on what was read.
//! A second argument reads only the files whose path contains it (`obj`, `ascii`, ...).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use meshvol::{Point, Surface};

/// A torus (major radius 3, minor 1) over an n × m grid: vertex (i, j), outward triangles.
fn torus(n: usize, m: usize) -> (Vec<Point>, Vec<[usize; 3]>) {
    let mut p = Vec::with_capacity(n * m);
    for i in 0..n {
        let u = i as f64 * std::f64::consts::TAU / n as f64;
        for j in 0..m {
            let v = j as f64 * std::f64::consts::TAU / m as f64;
            let r = 3.0 + v.cos();
            p.push([r * u.cos(), r * u.sin(), v.sin()]);
        }
    }
    let id = |i: usize, j: usize| (i % n) * m + j % m;
    let mut t = Vec::with_capacity(2 * n * m);
    for i in 0..n {
        for j in 0..m {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            t.push([a, b, c]);
            t.push([a, c, d]);
        }
    }
    (p, t)
}

fn generate(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let ascii = dir.join("torus-ascii.stl");
    let obj = dir.join("torus.obj");
    let binary = dir.join("torus-binary.stl");
    if !ascii.exists() {
        // ~250 bytes per facet: 400k facets ≈ 100 MB.
        let (p, t) = torus(500, 400);
        let mut w = BufWriter::new(File::create(&ascii)?);
        writeln!(w, "solid torus")?;
        for tri in &t {
            writeln!(w, "  facet normal 0.000000e+00 0.000000e+00 0.000000e+00\n    outer loop")?;
            for &v in tri {
                let [x, y, z] = p[v];
                writeln!(w, "      vertex {x:.6e} {y:.6e} {z:.6e}")?;
            }
            writeln!(w, "    endloop\n  endfacet")?;
        }
        writeln!(w, "endsolid torus")?;
    }
    if !obj.exists() {
        // ~40 bytes per vertex line, ~25 per face, two faces per vertex.
        let (p, t) = torus(1500, 1000);
        let mut w = BufWriter::new(File::create(&obj)?);
        writeln!(w, "# torus\no torus")?;
        for [x, y, z] in &p {
            writeln!(w, "v {x:.7} {y:.7} {z:.7}")?;
        }
        for [a, b, c] in &t {
            writeln!(w, "f {} {} {}", a + 1, b + 1, c + 1)?;
        }
    }
    if !binary.exists() {
        let (p, t) = torus(1000, 500);
        let mut w = BufWriter::new(File::create(&binary)?);
        let mut header = [b' '; 80];
        header[..11].copy_from_slice(b"solid torus");
        w.write_all(&header)?;
        w.write_all(&(t.len() as u32).to_le_bytes())?;
        for tri in &t {
            w.write_all(&[0u8; 12])?;
            for &v in tri {
                for c in p[v] {
                    w.write_all(&(c as f32).to_le_bytes())?;
                }
            }
            w.write_all(&[0u8; 2])?;
        }
    }
    // The other formats through meshvol-io's writers.
    let as_mesh = |n: usize, m: usize| {
        let (p, t) = torus(n, m);
        let t = t.iter().map(|tri| tri.map(|v| v as u32)).collect();
        meshvol::Mesh::from_triangles(p, t).expect("a valid torus")
    };
    let ply = dir.join("torus-binary.ply");
    let glb = dir.join("torus.glb");
    let ply_ascii = dir.join("torus-ascii.ply");
    if !ply.exists() || !glb.exists() {
        let mesh = as_mesh(1000, 500);
        let mut w = BufWriter::new(File::create(&ply)?);
        meshvol_io::write::ply(&mut w, &mesh, meshvol_io::write::PlyEncoding::BinaryLittleEndian)?;
        drop(w);
        meshvol_io::write::glb(&mut BufWriter::new(File::create(&glb)?), &mesh)?;
    }
    if !ply_ascii.exists() {
        let mesh = as_mesh(500, 400);
        let mut w = BufWriter::new(File::create(&ply_ascii)?);
        meshvol_io::write::ply(&mut w, &mesh, meshvol_io::write::PlyEncoding::Ascii)?;
    }
    Ok(vec![ascii, obj, binary, ply, glb, ply_ascii])
}

fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "/tmp/meshvol-io-bench".into());
    let only = std::env::args().nth(2).unwrap_or_default();
    let files = generate(Path::new(&dir)).expect("generate the files");
    println!("{} threads", rayon::current_num_threads());
    for path in files {
        if !path.to_string_lossy().contains(&only) {
            continue;
        }
        let size = std::fs::metadata(&path).unwrap().len() as f64 / 1e6;
        let mut best = f64::INFINITY;
        let mut kernel = f64::INFINITY;
        let mut summary = String::new();
        for _ in 0..5 {
            let t = Instant::now();
            let loaded = meshvol_io::read(&path).unwrap();
            let dt = t.elapsed().as_secs_f64();
            best = best.min(dt);
            let t = Instant::now();
            std::hint::black_box(meshvol::mass_properties(&loaded.surface));
            kernel = kernel.min(t.elapsed().as_secs_f64());
            // A volume, outside the timing, to show the surface is whole.
            let mut six = 0.0;
            for f in 0..loaded.surface.face_count() {
                loaded.surface.fan(f, |a, b, c| {
                    six += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                        + a[2] * (b[0] * c[1] - b[1] * c[0]);
                });
            }
            summary = format!(
                "{} triangles, volume {:.4} (torus 6π² = {:.4})",
                loaded.triangle_count(),
                six / 6.0,
                6.0 * std::f64::consts::PI.powi(2)
            );
            drop(loaded);
        }
        println!(
            "{:<20} {:>8.1} MB  read {:>7.1} ms {:>6.0} MB/s  mass_properties {:>6.1} ms  {summary}",
            path.file_name().unwrap().to_string_lossy(),
            size,
            best * 1e3,
            size / best,
            kernel * 1e3
        );
    }
}
