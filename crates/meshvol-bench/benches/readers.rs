//! Reading files: each format read from a file (the page cache warm) and measured with
//! `mass_properties`, throughput in input bytes per second. The files are a UV sphere of
//! about a million triangles written by meshvol-io's writers into a temporary directory
//! (ASCII formats: a quarter of that, to keep the files near 60 MB).
//!
//! Run: `cargo bench -p meshvol-bench --bench readers`

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use meshvol::{mass_properties, Mesh};
use meshvol_bench::sphere_with_triangles;
use meshvol_io::write::{self, PlyEncoding};
use std::hint::black_box;

/// Writes `mesh` with `writer` to `dir/name`.
fn file(
    dir: &Path,
    name: &str,
    mesh: &Mesh,
    writer: impl Fn(&mut BufWriter<File>, &Mesh) -> std::io::Result<()>,
) -> PathBuf {
    let path = dir.join(name);
    let mut out = BufWriter::new(File::create(&path).unwrap());
    writer(&mut out, mesh).unwrap();
    drop(out);
    path
}

fn readers(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let large = sphere_with_triangles(1_000_000);
    let small = sphere_with_triangles(250_000);
    let d = dir.path();
    let files = [
        file(d, "sphere-binary.stl", &large, write::stl_binary),
        file(d, "sphere-binary-le.ply", &large, |w, m| {
            write::ply(w, m, PlyEncoding::BinaryLittleEndian)
        }),
        file(d, "sphere-binary-be.ply", &large, |w, m| {
            write::ply(w, m, PlyEncoding::BinaryBigEndian)
        }),
        file(d, "sphere.glb", &large, write::glb),
        file(d, "sphere-ascii.stl", &small, |w, m| write::stl_ascii(w, "sphere", m)),
        file(d, "sphere-ascii.ply", &small, |w, m| write::ply(w, m, PlyEncoding::Ascii)),
        file(d, "sphere.obj", &small, write::obj),
    ];
    let mut group = c.benchmark_group("read+mass_properties");
    group.sample_size(10);
    for path in &files {
        let bytes = std::fs::metadata(path).unwrap().len();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        group.throughput(Throughput::Bytes(bytes));
        group.bench_with_input(BenchmarkId::from_parameter(name), path, |b, path| {
            b.iter(|| {
                let loaded = meshvol_io::read(path).unwrap();
                black_box(mass_properties(&loaded.surface))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, readers);
criterion_main!(benches);
