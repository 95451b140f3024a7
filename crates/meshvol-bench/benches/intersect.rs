//! The overlap of two 10k-triangle spheres in a loop over rigid poses (the simulation
//! use of `meshvol::grid::intersection`): each pose reads B's faces moved
//! (`meshvol::surface::Moved`), with and without the interface's two extra passes.
//!
//! Run: `cargo bench -p meshvol-bench --bench intersect`

use criterion::{criterion_group, criterion_main, Criterion};
use meshvol::assembly::Affine;
use meshvol::grid::intersection;
use meshvol::surface::Moved;
use meshvol_bench::sphere_with_triangles;
use std::hint::black_box;

/// 100 poses of B: turns about a tilted axis and shifts that keep the spheres
/// overlapping (centres 0.3 to 1.2 apart, radius 1).
fn poses() -> Vec<Affine> {
    (0..100)
        .map(|k| {
            let t = k as f64 * 0.061;
            let (s, c) = t.sin_cos();
            let d = 0.3 + 0.9 * (k as f64 / 100.0);
            Affine([[c, -s, 0.0, d * c], [s, c, 0.0, d * s], [0.0, 0.0, 1.0, 0.2 * s]])
        })
        .collect()
}

fn pose_loop(c: &mut Criterion) {
    let mut group = c.benchmark_group("intersect");
    group.sample_size(10);
    let a = sphere_with_triangles(10_000);
    let poses = poses();
    group.bench_function("10k-10k/100-poses", |bench| {
        bench.iter(|| {
            for pose in &poses {
                let b = Moved::new(&a, Some(*pose));
                black_box(intersection(&Moved::new(&a, None), &b, 1e-9).unwrap());
            }
        })
    });
    group.finish();
}

criterion_group!(benches, pose_loop);
criterion_main!(benches);
