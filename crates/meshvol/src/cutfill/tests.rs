//! The overlay's pairs against all pairs, on fans of slivers (shared and distinct
//! apexes, against each other and against ordinary triangles), and closed forms.

use super::overlaps::interiors_overlap;
use super::pairs::Pairs;
use super::piece::{amounts, Sums};
use super::{cut_fill, Design, Overlay, Terrain};
use crate::test_rng::XorShift;
use crate::Mesh;
use std::f64::consts::TAU;

/// A fan from `apex` to rim points at `angles` (increasing, gaps under π) and
/// distances `radii`, closed into a full turn when `closed`; rim at height 0.
fn fan(apex: [f64; 3], angles: &[f64], radii: &[f64], closed: bool) -> Terrain {
    let mut positions = vec![apex];
    for (a, r) in angles.iter().zip(radii) {
        positions.push([apex[0] + r * a.cos(), apex[1] + r * a.sin(), 0.0]);
    }
    let k = angles.len() as u32;
    let slivers = if closed { k } else { k - 1 };
    let faces = (0..slivers).map(|i| [0, 1 + i, 1 + (i + 1) % k]).collect();
    Terrain::new(&Mesh::from_triangles(positions, faces).unwrap()).unwrap()
}

/// A random fan of `n` slivers over `turns` (½ to 1) of a turn from `apex`.
fn random_fan(rng: &mut XorShift, apex: [f64; 3], n: usize, turns: f64) -> Terrain {
    let closed = turns >= 1.0;
    let points = if closed { n } else { n + 1 };
    loop {
        let steps: Vec<f64> = (0..points).map(|_| 0.2 + rng.unit()).collect();
        let total: f64 = steps[..n].iter().sum();
        let start = TAU * rng.unit();
        let mut a = start;
        let angles: Vec<f64> = steps
            .iter()
            .map(|s| {
                let here = a;
                a += turns * TAU * s / total;
                here
            })
            .collect();
        let gaps = (0..n).map(|i| {
            if i + 1 < points {
                angles[i + 1] - angles[i]
            } else {
                start + TAU - angles[i]
            }
        });
        if gaps.into_iter().all(|g| g < 3.0) {
            let radii: Vec<f64> = (0..points).map(|_| 0.5 + rng.unit()).collect();
            return fan(apex, &angles, &radii, closed);
        }
    }
}

/// An ordinary TIN: `k`×`k` squares over [−s, s]², each cut in two.
fn sheet(k: usize, s: f64, z: impl Fn(f64, f64) -> f64) -> Terrain {
    let at = |i: usize| -s + 2.0 * s * i as f64 / k as f64;
    let positions =
        (0..=k).flat_map(|j| (0..=k).map(move |i| (at(i), at(j)))).map(|(x, y)| [x, y, z(x, y)]);
    let id = |i: usize, j: usize| (j * (k + 1) + i) as u32;
    let faces = (0..k)
        .flat_map(|j| (0..k).map(move |i| (i, j)))
        .flat_map(|(i, j)| {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            [[a, b, c], [a, c, d]]
        })
        .collect();
    Terrain::new(&Mesh::from_triangles(positions.collect(), faces).unwrap()).unwrap()
}

/// The overlay's pairs, sorted, and the box candidates tried.
fn overlay_pairs(existing: &Terrain, design: &Terrain) -> (Vec<(usize, usize)>, usize) {
    let pairs = Pairs::new(&existing.facets, &design.facets);
    let (mut found, mut tried) = (Vec::new(), 0);
    for task in 0..pairs.task_count() {
        pairs.pairs(task, &existing.facets, &design.facets, &mut tried, |e, g| found.push((e, g)));
    }
    found.sort_unstable();
    (found, tried)
}

fn all_pairs(existing: &Terrain, design: &Terrain) -> Vec<(usize, usize)> {
    let mut found = Vec::new();
    for (e, a) in existing.facets.iter().enumerate() {
        for (g, b) in design.facets.iter().enumerate() {
            if interiors_overlap(&a.xy, &b.xy) {
                found.push((e, g));
            }
        }
    }
    found
}

/// Cut and fill from every pair of triangles clipped (the overlay without a search).
fn all_pairs_cut_fill(existing: &Terrain, design: &Terrain) -> [f64; 5] {
    let overlay = Overlay::new(existing, Design::Surface(design)).unwrap();
    let mut sums = Sums::default();
    for e in &existing.facets {
        for g in &design.facets {
            if let Some(piece) = overlay.clip(e, g) {
                sums.add(&amounts(&piece));
            }
        }
    }
    [sums.cut, sums.fill, sums.area_cut, sums.area_fill, sums.footprint].map(|s| s.value())
}

fn assert_close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() <= 1e-11 * a.abs().max(b.abs()).max(1.0), "{what}: {a} vs {b}");
}

fn check_against_all_pairs(existing: &Terrain, design: &Terrain, what: &str) {
    let (found, _) = overlay_pairs(existing, design);
    let mut unique = found.clone();
    unique.dedup();
    assert_eq!(unique.len(), found.len(), "{what}: a pair twice");
    assert_eq!(found, all_pairs(existing, design), "{what}");
    let r = cut_fill(existing, Design::Surface(design));
    let all = all_pairs_cut_fill(existing, design);
    let ours = [r.cut, r.fill, r.area_cut, r.area_fill, r.footprint_area];
    for (k, name) in ["cut", "fill", "area_cut", "area_fill", "footprint"].iter().enumerate() {
        assert_close(ours[k], all[k], &format!("{what}: {name}"));
    }
}

#[test]
fn random_fans_against_all_pairs() {
    let mut rng = XorShift::new(0x5eed_fa17);
    for round in 0..60 {
        let turns =
            |rng: &mut XorShift| if rng.below(3) == 0 { 1.0 } else { 0.5 + 0.5 * rng.unit() };
        let (t1, t2) = (turns(&mut rng), turns(&mut rng));
        let (n1, n2) = (3 + rng.below(40) as usize, 3 + rng.below(40) as usize);
        let a = [0.25, -0.5, 2.0];
        // Same apex (other heights), or a distinct one nearby.
        let b = match round % 3 {
            0 | 1 => [a[0], a[1], 1.0 + rng.unit()],
            _ => [a[0] + 0.6 * rng.unit() - 0.3, a[1] + 0.6 * rng.unit() - 0.3, 1.5],
        };
        let existing = random_fan(&mut rng, a, n1, t1);
        let design = random_fan(&mut rng, b, n2, t2);
        check_against_all_pairs(&existing, &design, &format!("round {round}"));
        check_against_all_pairs(&design, &existing, &format!("round {round}, swapped"));
    }
}

#[test]
fn fans_against_ordinary_triangles() {
    let mut rng = XorShift::new(77);
    let ramp = sheet(6, 1.2, |x, y| 0.3 * x - 0.2 * y + 1.0);
    for apex in [[0.0, 0.0, 2.0], [0.4, 0.4, 2.0], [0.13, -0.31, 2.0]] {
        // Apexes at, near and away from the sheet's corners.
        let cone = random_fan(&mut rng, apex, 50, 1.0);
        check_against_all_pairs(&cone, &ramp, &format!("{apex:?}"));
        check_against_all_pairs(&ramp, &cone, &format!("{apex:?} swapped"));
    }
}

#[test]
fn candidates_stay_near_the_pairs_found() {
    // Two fans from one apex: every box meets every other there (2·10⁷ box pairs), the
    // triangles overlap in at most n1 + n2 pairs.
    let mut rng = XorShift::new(3);
    let cone = random_fan(&mut rng, [0.0, 0.0, 1.0], 2000, 1.0);
    let other = random_fan(&mut rng, [0.0, 0.0, 0.5], 10_000, 1.0);
    let (found, tried) = overlay_pairs(&cone, &other);
    assert!(found.len() <= 12_000 && tried <= 2 * 12_000, "{} pairs, {tried} tried", found.len());
    // A fan against a fine sheet, the apex at a sheet corner and off it.
    let ramp = sheet(60, 1.6, |x, _| x);
    for apex in [[0.0, 0.0, 1.0], [0.011, 0.017, 1.0]] {
        let cone = random_fan(&mut rng, apex, 3000, 1.0);
        for (e, d) in [(&cone, &ramp), (&ramp, &cone)] {
            let (found, tried) = overlay_pairs(e, d);
            let n = cone.triangle_count() + ramp.triangle_count();
            assert!(tried <= 4 * (found.len() + n), "{} pairs, {tried} tried", found.len());
        }
    }
}

/// A pyramid from `apex` over the regular `sides`-gon of radius 1 around it, each face
/// cut into `parts` slivers at random points of its rim edge.
fn split_pyramid(rng: &mut XorShift, apex: [f64; 3], sides: usize, parts: usize) -> Terrain {
    let corner = |i: usize| {
        let a = TAU * i as f64 / sides as f64;
        [apex[0] + a.cos(), apex[1] + a.sin()]
    };
    let mut positions = vec![apex];
    for i in 0..sides {
        let (p, q) = (corner(i), corner(i + 1));
        let mut ts: Vec<f64> = (1..parts).map(|_| rng.unit()).collect();
        ts.sort_by(f64::total_cmp);
        for t in std::iter::once(0.0).chain(ts) {
            positions.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), 0.0]);
        }
    }
    let k = positions.len() as u32 - 1;
    let faces = (0..k).map(|i| [0, 1 + i, 1 + (i + 1) % k]).collect();
    Terrain::new(&Mesh::from_triangles(positions, faces).unwrap()).unwrap()
}

#[test]
fn cones_in_closed_form() {
    let mut rng = XorShift::new(11);
    let sides = 7;
    let base = 0.5 * sides as f64 * (TAU / sides as f64).sin();
    // Two cones from one apex over one heptagon, their faces cut apart differently:
    // the difference of two pyramids, (h1 − h2)·base/3, all cut.
    let tall = split_pyramid(&mut rng, [0.3, 0.2, 5.0], sides, 300);
    let low = split_pyramid(&mut rng, [0.3, 0.2, 2.0], sides, 1000);
    let r = cut_fill(&tall, Design::Surface(&low));
    assert_close(r.cut, 3.0 * base / 3.0, "cut");
    assert!(r.fill.abs() < 1e-12 && r.area_fill.abs() < 1e-12, "{r:?}");
    assert_close(r.area_cut, base, "area");
    assert_close(r.footprint_area, base, "footprint");
    // A cone against the level z = L as a surface (two triangles) and as a level: the
    // top, a pyramid scaled by (h − L)/h, is the cut.
    let (h, level) = (5.0, 2.0);
    let plane = sheet(1, 3.0, |_, _| level);
    let scale = (h - level) / h;
    let cut = base * scale * scale * (h - level) / 3.0;
    let fill = base * level - (base * h / 3.0 - cut);
    for r in [cut_fill(&tall, Design::Surface(&plane)), cut_fill(&tall, Design::Level(level))] {
        assert_close(r.cut, cut, "cut against a level");
        assert_close(r.fill, fill, "fill against a level");
        assert_close(r.area_cut, base * scale * scale, "area cut against a level");
    }
}

#[test]
fn progress_counts_the_tasks_and_changes_nothing() {
    use super::{cell_cut_fill, cell_cut_fill_with, cut_fill_with, PlanGrid};
    use crate::progress::testing::Record;
    let mut rng = XorShift::new(5);
    let cone = random_fan(&mut rng, [0.0, 0.0, 1.0], 5000, 1.0);
    let ramp = sheet(40, 1.6, |x, _| x);
    for design in [Design::Surface(&ramp), Design::Level(0.5)] {
        let record = Record::default();
        assert_eq!(cut_fill_with(&cone, design, &record), cut_fill(&cone, design));
        assert_eq!(record.counted_stages(), ["integrating cut and fill"]);
        let grid = PlanGrid::new([-1.0, -1.0], [0.25, 0.25], [8, 8]).unwrap();
        let record = Record::default();
        let cells = cell_cut_fill_with(&cone, design, &grid, &record);
        assert_eq!(cells, cell_cut_fill(&cone, design, &grid));
        assert_eq!(record.counted_stages(), ["integrating cut and fill per cell"]);
    }
}

#[test]
fn fans_give_the_same_bits_at_any_thread_count() {
    use super::{cell_cut_fill, PlanGrid};
    let mut rng = XorShift::new(8);
    let cone = random_fan(&mut rng, [0.0, 0.0, 1.0], 3000, 1.0);
    let other = random_fan(&mut rng, [0.0, 0.0, 0.5], 7000, 1.0);
    let apart = random_fan(&mut rng, [0.2, 0.1, 0.5], 300, 1.0);
    let ramp = sheet(30, 1.6, |x, y| x * y);
    let grid = PlanGrid::new([-1.0, -1.0], [0.3, 0.3], [7, 7]).unwrap();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let designs = [&other, &apart, &ramp].map(Design::Surface);
            let totals = designs.map(|d| cut_fill(&cone, d));
            let cells = designs.map(|d| cell_cut_fill(&cone, d, &grid));
            (totals, cells, cut_fill(&ramp, Design::Surface(&cone)))
        })
    };
    let one = run(1);
    for threads in [2, 5] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}
