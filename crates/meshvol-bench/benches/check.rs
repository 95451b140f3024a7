//! Topology checks on a 1M-triangle mesh: an indexed sphere, and the same sphere as an
//! unwelded triangle soup (as from STL), with and without the crossing search.
//!
//! Run: `cargo bench -p meshvol-bench --bench check`

use criterion::{criterion_group, criterion_main, Criterion};
use meshvol::topology::{check, CheckOptions};
use meshvol::{Faces, Mesh};
use meshvol_bench::sphere_with_triangles;
use std::hint::black_box;

fn soup(mesh: &Mesh) -> Mesh {
    let Faces::Triangles(tris) = mesh.faces() else { unreachable!() };
    let p: Vec<[f64; 3]> =
        tris.iter().flat_map(|t| t.map(|i| mesh.positions()[i as usize])).collect();
    let t = (0..tris.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    Mesh::from_triangles(p, t).unwrap()
}

fn checks(c: &mut Criterion) {
    let mut group = c.benchmark_group("check");
    group.sample_size(10);
    let indexed = sphere_with_triangles(1_000_000);
    let unwelded = soup(&indexed);
    let topology_only = CheckOptions { intersections: false, ..CheckOptions::default() };
    for (name, mesh) in [("indexed-1M", &indexed), ("soup-1M", &unwelded)] {
        group.bench_function(format!("{name}/full"), |b| {
            b.iter(|| black_box(check(mesh, &CheckOptions::default())))
        });
        group.bench_function(format!("{name}/no-intersections"), |b| {
            b.iter(|| black_box(check(mesh, &topology_only)))
        });
    }
    group.finish();
}

criterion_group!(benches, checks);
criterion_main!(benches);
