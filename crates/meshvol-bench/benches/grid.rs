//! Grid kernels: per-cell volumes of a 1M-triangle sphere on 256³ and 512³ grids, its
//! cut-cell geometry (moments, surface and apertures) on 256³ beside the volumes alone, a
//! profile, and the union of 20 overlapping spheres of 20k triangles at tolerance 1e-6.
//! Peers (trimesh voxelize, manifold3d booleans) are timed in `bench/compare/run`.
//!
//! Run: `cargo bench -p meshvol-bench --bench grid`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use meshvol::grid::{cell_volumes, cut_cells, profile, union, Axis, Grid, Levels};
use meshvol::Mesh;
use meshvol_bench::sphere_with_triangles;
use std::hint::black_box;

/// Twenty unit spheres of about 20k triangles, centres 1.2 apart on a 5×4 lattice with
/// alternating heights: each overlaps its neighbours.
pub fn overlapping_spheres() -> Vec<Mesh> {
    let sphere = sphere_with_triangles(20_000);
    (0..20)
        .map(|k| {
            let c = [1.2 * (k % 5) as f64, 1.2 * (k / 5) as f64, 0.3 * (k % 2) as f64];
            let p = sphere
                .positions()
                .iter()
                .map(|p| [p[0] + c[0], p[1] + c[1], p[2] + c[2]])
                .collect();
            Mesh::new(p, sphere.faces().clone()).expect("a moved sphere is valid")
        })
        .collect()
}

fn grids(c: &mut Criterion) {
    let mut group = c.benchmark_group("grid");
    group.sample_size(10);
    let mesh = sphere_with_triangles(1_000_000);
    group.throughput(Throughput::Elements(mesh.triangle_count() as u64));
    for n in [256, 512] {
        let grid = Grid::from_bounds([-1.0; 3], [1.0; 3], [n, n, n]).unwrap();
        group.bench_with_input(BenchmarkId::new("sphere-1M", format!("{n}^3")), &grid, |b, g| {
            b.iter(|| black_box(cell_volumes(&mesh, g).unwrap()))
        });
    }
    let grid = Grid::from_bounds([-1.0; 3], [1.0; 3], [256; 3]).unwrap();
    group.bench_function("sphere-1M-cut-cells/256^3", |b| {
        b.iter(|| black_box(cut_cells(&mesh, &grid).unwrap()))
    });
    group.bench_function("profile-1M-1000-levels", |b| {
        b.iter(|| black_box(profile(&mesh, Axis::Z, Levels::Count(1000)).unwrap()))
    });
    group.finish();

    let mut group = c.benchmark_group("union");
    group.sample_size(10);
    let spheres = overlapping_spheres();
    group.bench_function("20-spheres-20k-1e-6", |b| {
        b.iter(|| black_box(union(&spheres, 1e-6).unwrap()))
    });
    group.finish();
}

criterion_group!(benches, grids);
criterion_main!(benches);
