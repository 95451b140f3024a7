//! Convex hulls of a million points on a sphere (every point a vertex) and in a ball,
//! against parry3d-f64's quickhull where it finishes in seconds, and of the points of
//! an .xyz file named by `MESHVOL_HULL_POINTS`, to compare with other programs on the
//! same points without their reading.
//!
//! Run: `cargo bench -p meshvol-bench --bench hull`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use meshvol::hull::convex_hull;
use parry3d_f64::math::Vector3;
use parry3d_f64::transformation::convex_hull as parry_hull;
use std::hint::black_box;

/// `n` points uniformly in the unit ball (by rejection), or on the unit sphere.
fn cloud(n: usize, on_sphere: bool) -> Vec<[f64; 3]> {
    let mut state = 0x853c_49e6_748f_ea9b_u64;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        2.0 * (state >> 11) as f64 / (1u64 << 53) as f64 - 1.0
    };
    let mut points = Vec::with_capacity(n);
    while points.len() < n {
        let p = [unit(), unit(), unit()];
        let r = p.iter().map(|x| x * x).sum::<f64>().sqrt();
        if r <= 1.0 && r > 0.1 {
            points.push(if on_sphere { p.map(|x| x / r) } else { p });
        }
    }
    points
}

fn hulls(c: &mut Criterion) {
    let mut group = c.benchmark_group("hull");
    group.sample_size(10);
    for (name, on_sphere) in [("sphere", true), ("ball", false)] {
        for n in [100_000, 1_000_000] {
            let points = cloud(n, on_sphere);
            group.bench_function(BenchmarkId::new(format!("meshvol/{name}"), n), |b| {
                b.iter(|| black_box(convex_hull(&points).unwrap().volume()))
            });
            // parry costs about n·h: seconds for 10⁵ points on a sphere, minutes for 10⁶.
            if !on_sphere || n <= 100_000 {
                let vectors: Vec<Vector3> =
                    points.iter().map(|&[x, y, z]| Vector3::new(x, y, z)).collect();
                group.bench_function(BenchmarkId::new(format!("parry3d-f64/{name}"), n), |b| {
                    b.iter(|| black_box(parry_hull(&vectors).1.len()))
                });
            }
        }
    }
    if let Ok(path) = std::env::var("MESHVOL_HULL_POINTS") {
        let points = meshvol_io::points::read_points(path.as_ref()).unwrap().points;
        group.bench_function(format!("meshvol/{path}"), |b| {
            b.iter(|| black_box(convex_hull(&points).unwrap().volume()))
        });
    }
    group.finish();
}

criterion_group!(benches, hulls);
criterion_main!(benches);
