//! In-memory mass properties: meshvol against parry3d-f64's `MassProperties::from_trimesh`
//! on the same arrays, and meshvol's exact mode.
//!
//! and the volume alone (`meshvol::volume`) against the mass properties.
//!
//! Run: `cargo bench -p meshvol-bench --bench mass_properties` (`-- volume/` for the
//! second group only)

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use meshvol::{
    exact_signed_volume, mass_properties, signed_volume, triangles_signed_volume, Faces,
};
use meshvol_bench::sphere_with_triangles;
use parry3d_f64::mass_properties::MassProperties as ParryMassProperties;
use parry3d_f64::math::Vector;
use std::hint::black_box;

fn in_memory(c: &mut Criterion) {
    let mut group = c.benchmark_group("mass_properties");
    group.sample_size(10);
    for triangles in [1_000_000, 10_000_000] {
        let mesh = sphere_with_triangles(triangles);
        let Faces::Triangles(tris) = mesh.faces() else { unreachable!() };
        let vertices: Vec<Vector> =
            mesh.positions().iter().map(|p| Vector::new(p[0], p[1], p[2])).collect();
        group.throughput(Throughput::Elements(tris.len() as u64));
        group.bench_with_input(BenchmarkId::new("meshvol", triangles), &mesh, |b, m| {
            b.iter(|| black_box(mass_properties(m)))
        });
        let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        group.bench_with_input(BenchmarkId::new("meshvol-1-thread", triangles), &mesh, |b, m| {
            b.iter(|| one_thread.install(|| black_box(mass_properties(m))))
        });
        group.bench_with_input(BenchmarkId::new("meshvol-exact", triangles), &mesh, |b, m| {
            b.iter(|| black_box(exact_signed_volume(m)))
        });
        group.bench_function(BenchmarkId::new("parry3d-f64", triangles), |b| {
            b.iter(|| black_box(ParryMassProperties::from_trimesh(1.0, &vertices, tris)))
        });
    }
    group.finish();
}

/// The volume alone (`meshvol::volume`) against the full mass properties, at the sizes
/// of bench/compare's in-process section, on the caller's pool and on one thread.
fn volume_only(c: &mut Criterion) {
    let mut group = c.benchmark_group("volume");
    group.sample_size(20);
    for triangles in [100_000, 1_000_000] {
        let mesh = sphere_with_triangles(triangles);
        let Faces::Triangles(tris) = mesh.faces() else { unreachable!() };
        let tris64: Vec<[i64; 3]> = tris.iter().map(|t| t.map(i64::from)).collect();
        group.throughput(Throughput::Elements(tris.len() as u64));
        group.bench_with_input(BenchmarkId::new("signed_volume", triangles), &mesh, |b, m| {
            b.iter(|| black_box(signed_volume(m)))
        });
        group.bench_function(BenchmarkId::new("triangles_signed_volume-i64", triangles), |b| {
            b.iter(|| black_box(triangles_signed_volume(mesh.positions(), &tris64)))
        });
        group.bench_with_input(BenchmarkId::new("mass_properties", triangles), &mesh, |b, m| {
            b.iter(|| black_box(mass_properties(m)))
        });
        let one_thread = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        group.bench_with_input(
            BenchmarkId::new("signed_volume-1-thread", triangles),
            &mesh,
            |b, m| b.iter(|| one_thread.install(|| black_box(signed_volume(m)))),
        );
    }
    group.finish();
}

criterion_group!(benches, in_memory, volume_only);
criterion_main!(benches);
