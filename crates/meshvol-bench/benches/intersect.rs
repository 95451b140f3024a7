//! The overlap of two 10k-triangle spheres over 1,000 random rigid poses (the simulation
//! use of `meshvol::grid::intersection_placed`): each body prepared once
//! (`meshvol::overlap::Body`), each pose gives the whole result (interval, moments,
//! contact), by the boundary method where it settles the pose and the grid method where
//! not (the count of each is printed); then the grid method alone, for comparison.
//!
//! Before criterion's own measurement (one pose per iteration, cycling through the
//! poses), the 1,000 poses are timed one by one and their median and quartiles printed:
//! the figure ("median over 1,000 random overlapping poses").
//!
//! Run: `cargo bench -p meshvol-bench --bench intersect` (`RAYON_NUM_THREADS=2` for the
//! issue's 2 cores).

use criterion::{criterion_group, criterion_main, Criterion};
use meshvol::assembly::Affine;
use meshvol::grid::{intersection, intersection_placed, Intersection, Method};
use meshvol::overlap::Body;
use meshvol::shapes::uv_sphere;
use meshvol::surface::Moved;
use meshvol::Mesh;
use std::hint::black_box;
use std::time::Instant;

/// The mesh of `cargo run -p meshvol-io --example sphere -- 10000 a.stl` (100 segments,
/// 50 rings: 9,800 triangles), at radius 1.
fn sphere() -> Mesh {
    uv_sphere(1.0, 100, 50).triangulated()
}

/// A uniform number in [0, 1) from a SplitMix64 state.
fn uniform(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// `count` poses of B: a uniformly random rotation (Shoemake's quaternion) and a shift
/// uniform in the ball of radius 1.5, so the unit spheres always overlap (centres less
/// than 2 apart), from shallow contact to one nearly inside the other.
fn random_poses(count: usize) -> Vec<Affine> {
    let mut state = 27;
    let tau = std::f64::consts::TAU;
    (0..count)
        .map(|_| {
            let (u1, u2, u3) = (uniform(&mut state), uniform(&mut state), uniform(&mut state));
            let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
            let (w, x) = (a * (tau * u2).sin(), a * (tau * u2).cos());
            let (y, z) = (b * (tau * u3).sin(), b * (tau * u3).cos());
            let t = loop {
                let v = [0; 3].map(|_| 2.0 * uniform(&mut state) - 1.0);
                if v.iter().map(|c| c * c).sum::<f64>() <= 1.0 {
                    break v.map(|c| 1.5 * c);
                }
            };
            Affine([
                [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w), t[0]],
                [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w), t[1]],
                [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y), t[2]],
            ])
        })
        .collect()
}

/// Times `at` at each pose, prints the median and quartiles, and returns how many
/// poses each method measured.
fn timed(what: &str, poses: &[Affine], at: impl Fn(&Affine) -> Intersection) {
    let (mut seconds, mut boundary) = (Vec::new(), 0);
    for pose in poses {
        let start = Instant::now();
        let i = black_box(at(pose));
        seconds.push(start.elapsed().as_secs_f64());
        boundary += usize::from(i.method == Method::Boundary);
    }
    seconds.sort_by(f64::total_cmp);
    let ms = |q: usize| seconds[q * (seconds.len() - 1) / 4] * 1e3;
    println!(
        "intersect 10k-10k, {what}, {} random overlapping poses on {} threads: median {:.3} \
         ms per pose (quartiles {:.3}, {:.3} ms; fastest {:.3} ms); {boundary} poses by the \
         boundary method",
        seconds.len(),
        rayon::current_num_threads(),
        ms(2),
        ms(1),
        ms(3),
        ms(0)
    );
}

fn pose_loop(c: &mut Criterion) {
    let a = sphere();
    let body = Body::new(&a);
    let poses = random_poses(1000);
    let placed = |pose: &Affine| {
        let bodies = [Some(&body), Some(&body)];
        intersection_placed(&a, &a, bodies, [None, Some(*pose)], 1e-9, &()).unwrap()
    };
    let by_grid = |pose: &Affine| {
        intersection(&Moved::new(&a, None), &Moved::new(&a, Some(*pose)), 1e-9).unwrap()
    };
    timed("prepared bodies", &poses, placed);
    timed("grid method", &poses[..100], by_grid);
    let mut group = c.benchmark_group("intersect");
    group.sample_size(10);
    let mut next = 0;
    group.bench_function("10k-10k/random-pose", |bench| {
        bench.iter(|| {
            next = (next + 1) % poses.len();
            black_box(placed(&poses[next]))
        })
    });
    group.finish();
}

criterion_group!(benches, pose_loop);
criterion_main!(benches);
