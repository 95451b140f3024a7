//! Welding: one vertex per position.
//!
//! Exact welding hashes each corner's coordinate bits once, groups the corner ids into
//! slices of the hash range (a counting sort of 4-byte ids, not of the 24-byte keys),
//! and welds each slice in parallel through its own hash table, which holds its keys
//! inline and is small enough for the cache. A corner's *representative* is the first
//! corner at its position; vertices are numbered in order of first use by a prefix
//! sum, the same at any thread count. (On the three million corners of a
//! million-triangle soup, 2 cores: a comparison sort of the keys took 0.54 s on one
//! core; slices carrying the keys, 0.19–0.25 s; this, 0.11–0.15 s.)
//!
//! Welding with a tolerance t first welds exactly, then joins distinct positions whose
//! coordinates all differ by at most t (transitively: a chain of close points becomes
//! one vertex). Candidates come from a hashed grid of cells of size 2t: the points
//! within t of a point lie in the 2 × 2 × 2 cells its box of half-width t touches.

use crate::buckets::{filled, par_compact, prefetch, Buckets, SharedItems};
use crate::union_find::UnionFind;
use crate::Point;
use hashbrown::HashTable;
use rayon::prelude::*;
use std::hash::BuildHasher;

/// The welded vertices and, for each corner, its vertex.
#[derive(Clone)]
pub(crate) struct Welded {
    /// Vertex of each corner.
    pub corner_vertex: Vec<u32>,
    /// Position of each vertex: that of its first corner. Vertices are numbered in
    /// order of their first corner.
    pub positions: Vec<Point>,
    /// The first corner of each vertex.
    pub first_corner: Vec<u32>,
}

/// The bits of a position, with −0.0 and +0.0 the same.
fn bits(p: Point) -> [u64; 3] {
    p.map(|x| (x + 0.0).to_bits())
}

/// A corner's position as welding reads it: in f64, or in the f32 a file stored it in
/// (half the bytes to gather and to compare). Two f32 positions are equal exactly when
/// their widenings to f64 are (widening is exact), so both weld alike, bit for bit.
pub(crate) trait Corner: Copy + Send + Sync {
    /// Its bits, with −0.0 and +0.0 the same.
    type Key: Copy + Eq + Send + Sync;
    fn key(self) -> Self::Key;
    fn hash(key: Self::Key) -> u64;
    fn point(self) -> Point;
}

impl Corner for Point {
    type Key = [u64; 3];
    #[inline(always)]
    fn key(self) -> [u64; 3] {
        bits(self)
    }
    #[inline(always)]
    fn hash(key: [u64; 3]) -> u64 {
        position_hash(key)
    }
    #[inline(always)]
    fn point(self) -> Point {
        self
    }
}

impl Corner for [f32; 3] {
    type Key = [u32; 3];
    #[inline(always)]
    fn key(self) -> [u32; 3] {
        self.map(|x| (x + 0.0).to_bits())
    }
    #[inline(always)]
    fn hash(key: [u32; 3]) -> u64 {
        position_hash(key.map(u64::from))
    }
    #[inline(always)]
    fn point(self) -> Point {
        self.map(f64::from)
    }
}

/// The hash of a position's bits: foldhash's folded multiply (the two halves of a
/// 128-bit product, xored) over the three words, with the digits of π as constants.
/// (`foldhash`'s `hash_one` of the key, a slice to its hasher, took 78 instructions a
/// corner, 3% of a million-triangle check's; this takes a dozen.) Which hash it is
/// changes no result: a corner's representative is the first corner at its position
/// whatever the hash, which only decides the work's split and the tables' layout.
#[inline(always)]
fn position_hash([x, y, z]: [u64; 3]) -> u64 {
    const K: [u64; 4] = [
        0x243f_6a88_85a3_08d3,
        0x1319_8a2e_0370_7344,
        0xa409_3822_299f_31d0,
        0x082e_fa98_ec4e_6c89,
    ];
    let fold = |a: u64, b: u64| {
        let product = u128::from(a) * u128::from(b);
        (product as u64) ^ ((product >> 64) as u64)
    };
    fold(fold(x ^ K[0], y ^ K[1]) ^ z ^ K[2], K[3])
}

/// Slices of the hash range welded in parallel: at least this many, and more for large
/// inputs, so that a slice's table stays small enough for the cache.
const SLICES: usize = 256;

/// Corners a slice holds at most (about): [`SLICES`] up to 4M corners, more beyond, so
/// that a slice's table (32 bytes an entry) stays near half a megabyte. (With 256
/// slices whatever the size, a 5M-triangle sphere's tables held 58k corners, 1.9 MB
/// each: welding took 1.06–2.2 CPU s there against 0.21–0.36 s at 1M; with this and
/// the prefetch, 0.82–1.6 s against 0.15–0.16 s. `meshvol volume --timings`, 2 cores
/// busy with other work, so the spread is wide.)
const SLICE_CORNERS: usize = 16384;

/// How many corners ahead a slice's loop prefetches.
const PREFETCH_AHEAD: usize = 16;

/// For each corner, the first corner at exactly its position.
fn exact_representatives<C: Corner>(corners: &[C]) -> Vec<u32> {
    let hash = |c: usize| C::hash(corners[c].key());
    // Middle bits pick the slice: hashbrown uses the top bits as tags and the low bits
    // for positions, which must still vary within a slice.
    // A power of two: the slice is a bit field of the hash. Which slice a position falls
    // in changes nothing but the work's split: a corner's representative is the first
    // corner at its position, whatever the slices. The hash is computed again wherever
    // it is needed (a dozen instructions) rather than kept, 8 bytes a corner that the
    // slices' scattered reads would also have to fetch.
    let count = corners.len().div_ceil(SLICE_CORNERS).next_power_of_two().clamp(SLICES, 1 << 16);
    let slice = |c: usize| ((hash(c) >> 32) as usize % count) as u32;
    let slices = Buckets::new(count, corners.len(), |range| range.map(|c| (slice(c), c as u32)));
    let mut representative = filled(corners.len(), 0u32);
    let out = SharedItems::new(&mut representative);
    // A table per parallel task, cleared for each of its slices: made afresh for each
    // slice, each was a large allocation of its own (1024 of them for 5M triangles).
    let new_table = HashTable::<(C::Key, u32)>::new;
    (0..count).into_par_iter().for_each_init(new_table, |table, k| {
        let items = slices.get(k);
        // Keys inline: comparing them reads the table only (small enough for the cache).
        table.clear();
        table.reserve(items.len(), |e| C::hash(e.0));
        for (n, &c) in items.iter().enumerate() {
            // A slice's corners are scattered over the arrays: load ahead.
            if let Some(&ahead) = items.get(n + PREFETCH_AHEAD) {
                prefetch(&corners[ahead as usize]);
            }
            let key = corners[c as usize].key();
            let entry = table.entry(C::hash(key), |e| e.0 == key, |e| C::hash(e.0));
            // SAFETY: every corner is in exactly one slice, so each is written once.
            unsafe { out.write(c as usize, entry.or_insert((key, c)).get().1) };
        }
    });
    representative
}

/// Numbers the vertices given each corner's representative (the first corner of its
/// vertex, so `representative[c] <= c`): vertex numbers count the representatives
/// before, a prefix sum taken in parallel blocks. A vertex's position is that of its
/// first corner, `position(c)`.
fn number(representative: &[u32], position: impl Fn(usize) -> Point + Sync) -> Welded {
    const BLOCK: usize = 1 << 16;
    let corners = representative.len();
    let firsts = |range: std::ops::Range<usize>| {
        range.filter(|&c| representative[c] as usize == c).count() as u32
    };
    let blocks = corners.div_ceil(BLOCK);
    let block_range = |b: usize| b * BLOCK..((b + 1) * BLOCK).min(corners);
    let mut before: Vec<u32> =
        (0..blocks).into_par_iter().map(|b| firsts(block_range(b))).collect();
    let mut total = 0;
    for count in &mut before {
        (*count, total) = (total, total + *count);
    }
    // The vertex number of each representative, then of every corner through it.
    let mut corner_vertex = filled(corners, 0u32);
    corner_vertex.par_chunks_mut(BLOCK).enumerate().for_each(|(b, out)| {
        let mut next = before[b];
        for (c, v) in block_range(b).zip(out) {
            if representative[c] as usize == c {
                (*v, next) = (next, next + 1);
            }
        }
    });
    let shared = SharedItems::new(&mut corner_vertex);
    (0..corners).into_par_iter().for_each(|c| {
        let r = representative[c] as usize;
        if r != c {
            // SAFETY: corner c is written by this iteration only, and what it reads, its
            // representative's number, was written in the pass before and is not
            // written in this one.
            unsafe { shared.write(c, shared.read(r)) };
        }
    });
    // Representatives in corner order are the vertices in number order.
    let first_corner = par_compact(corners, |c| representative[c] as usize == c, |c| c as u32);
    let positions = first_corner.par_iter().map(|&c| position(c as usize)).collect();
    Welded { corner_vertex, positions, first_corner }
}

/// Welds corners at exactly equal positions.
pub(crate) fn exact<C: Corner>(corners: &[C]) -> Welded {
    number(&exact_representatives(corners), |c| corners[c].point())
}

/// [`exact`] of the corners of indexed triangles (corner 3t + i at
/// `positions[triangles[t][i]]`, every index in range), bit for bit, welding the
/// positions instead of the corners: a triangle mesh has about half as many positions
/// as triangles, a sixth of its corners. Positions at one point are grouped (each under
/// the first of them), then each corner's representative is the first corner of its
/// group, found in one pass in corner order. (On a 1M-triangle OBJ, 2 cores: welding
/// 0.054–0.12 s → 0.014–0.016 s, without the corners' 72 MB of positions.)
pub(crate) fn exact_indexed(positions: &[Point], triangles: &[[u32; 3]]) -> Welded {
    let ids = triangles.as_flattened();
    let group = exact_representatives(positions);
    // Serial: one pass in corner order over a table of 4 bytes a position.
    let mut first = filled(positions.len(), u32::MAX);
    for (c, &v) in ids.iter().enumerate() {
        let slot = &mut first[group[v as usize] as usize];
        if *slot == u32::MAX {
            *slot = c as u32;
        }
    }
    let mut representative = Vec::new();
    ids.par_iter()
        .map(|&v| first[group[v as usize] as usize])
        .collect_into_vec(&mut representative);
    number(&representative, |c| positions[ids[c] as usize])
}

impl Welded {
    /// Welds these (exactly welded) vertices further: those whose coordinates differ
    /// by at most `t` become one. Each corner's position is its exact vertex's, bit for
    /// bit, so the corners themselves are not needed.
    pub(crate) fn within(&self, t: f64) -> Welded {
        if t > 0.0 {
            join_close(self, t)
        } else {
            self.clone()
        }
    }

    /// The position of corner `c`'s vertex.
    pub(crate) fn at(&self, c: usize) -> Point {
        self.positions[self.corner_vertex[c] as usize]
    }
}

/// [`Welded::within`] for t > 0.
fn join_close(exact: &Welded, t: f64) -> Welded {
    let points = &exact.positions;
    let size = 2.0 * t;
    let cell = |p: Point| p.map(|x| (x / size).floor() as i64);
    let mut by_cell: Vec<([i64; 3], u32)> =
        points.par_iter().enumerate().map(|(i, &p)| (cell(p), i as u32)).collect();
    by_cell.par_sort_unstable();
    // Each occupied cell's run in `by_cell`.
    let state = foldhash::fast::FixedState::with_seed(0);
    let mut runs: HashTable<([i64; 3], u32, u32)> = HashTable::new();
    for (i, &(c, _)) in by_cell.iter().enumerate() {
        let hash = state.hash_one(c);
        let entry = runs.entry(hash, |r| r.0 == c, |r| state.hash_one(r.0));
        entry.or_insert((c, i as u32, i as u32)).into_mut().2 = i as u32 + 1;
    }
    let mut clusters = UnionFind::new(points.len());
    for (i, &p) in points.iter().enumerate() {
        // Every q within t of p lies in a cell between those of p − t and p + t
        // (rounding is monotone, so this holds in floating point too): 2 per axis.
        let (low, high) = (cell(p.map(|x| x - t)), cell(p.map(|x| x + t)));
        for c in (low[0]..=high[0]).flat_map(|x| {
            (low[1]..=high[1]).flat_map(move |y| (low[2]..=high[2]).map(move |z| [x, y, z]))
        }) {
            let Some(&(_, begin, end)) = runs.find(state.hash_one(c), |r| r.0 == c) else {
                continue;
            };
            for &(_, j) in &by_cell[begin as usize..end as usize] {
                let q = points[j as usize];
                if (j as usize) < i && (0..3).all(|k| (p[k] - q[k]).abs() <= t) {
                    clusters.join(i as u32, j);
                }
            }
        }
    }
    // Vertices are numbered by first corner, so a cluster's smallest vertex holds its
    // first corner.
    let representative: Vec<u32> = exact
        .corner_vertex
        .iter()
        .map(|&v| exact.first_corner[clusters.find(v) as usize])
        .collect();
    // A representative is the first corner of an exact vertex, at that vertex's position.
    number(&representative, |c| exact.at(c))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn weld(corners: &[Point], tolerance: Option<f64>) -> Welded {
        let exact = exact(corners);
        match tolerance {
            Some(t) => exact.within(t),
            None => exact,
        }
    }

    #[test]
    fn welds_within_the_tolerance_across_cell_borders() {
        // 0.0 and −0.0 are one position; 1e-9 apart straddling a cell border still weld.
        let t = 1e-6;
        let corners =
            [[0.0, 0.0, 0.0], [-0.0, 0.0, 0.0], [t * 4.0 - 1e-9, 1.0, 1.0], [t * 4.0, 1.0, 1.0]];
        let exact = weld(&corners, None);
        assert_eq!(exact.positions.len(), 3);
        assert_eq!(exact.corner_vertex, [0, 0, 1, 2]);
        let w = weld(&corners, Some(t));
        assert_eq!(w.positions.len(), 2);
        assert_eq!(w.corner_vertex, [0, 0, 1, 1]);
        assert_eq!(w.positions[1], corners[2]);
        assert_eq!(w.first_corner, [0, 2]);
        // Farther than the tolerance: separate.
        let apart = weld(&[[0.0; 3], [2e-6, 0.0, 0.0]], Some(t));
        assert_eq!(apart.positions.len(), 2);
    }

    #[test]
    fn exact_weld_numbers_by_first_use_at_any_thread_count() {
        // 200 000 corners drawn from 5 000 positions (with −0.0 for some zeros): the
        // vertex numbers must be those a map from position to first corner gives.
        let mut rng = crate::test_rng::XorShift::new(0x9e3779b97f4a7c15u64);
        let mut next = || rng.next_u64();
        let pool: Vec<Point> = (0..5000)
            .map(|i| [(i % 17) as f64 * 0.5, (i / 17) as f64, if i % 3 == 0 { 0.0 } else { 1.0 }])
            .collect();
        let corners: Vec<Point> = (0..200_000)
            .map(|_| {
                let p = pool[(next() % 5000) as usize];
                if next() % 2 == 0 {
                    p.map(|x| if x == 0.0 { -0.0 } else { x })
                } else {
                    p
                }
            })
            .collect();
        let mut first = std::collections::HashMap::new();
        let expected: Vec<u32> = corners
            .iter()
            .map(|&p| {
                let n = first.len() as u32;
                *first.entry(bits(p)).or_insert(n)
            })
            .collect();
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let w = pool.install(|| weld(&corners, None));
            assert_eq!(w.corner_vertex, expected);
            assert_eq!(w.positions.len(), first.len());
            for (c, &v) in expected.iter().enumerate() {
                assert_eq!(bits(w.positions[v as usize]), bits(corners[c]));
                assert!(w.first_corner[v as usize] as usize <= c);
                assert_eq!(w.corner_vertex[w.first_corner[v as usize] as usize], v);
            }
        }
    }

    #[test]
    fn f32_corners_weld_as_their_widenings() {
        // f32 positions with −0.0 for some zeros, and neighbours one f32 step apart:
        // welded as f32 keys, the same vertices, numbers and positions (bit for bit) as
        // the f64 weld of the same corners widened.
        let mut rng = crate::test_rng::XorShift::new(0x5851_f42d_4c95_7f2d);
        let pool: Vec<[f32; 3]> = (0..3000)
            .map(|i| {
                let x = (i % 13) as f32 * 0.1;
                let y = if i % 7 == 0 { 0.0 } else { (i / 13) as f32 * 0.37 };
                let z = if i % 5 == 0 { f32::from_bits(x.to_bits() + 1) } else { 1.5 };
                [x, y, z]
            })
            .collect();
        let corners: Vec<[f32; 3]> = (0..120_000)
            .map(|_| {
                let p = pool[(rng.next_u64() % 3000) as usize];
                if rng.next_u64().is_multiple_of(2) {
                    p.map(|x| if x == 0.0 { -0.0 } else { x })
                } else {
                    p
                }
            })
            .collect();
        let widened: Vec<Point> = corners.iter().map(|p| p.map(f64::from)).collect();
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (narrow, wide) = pool.install(|| (exact(&corners), exact(&widened)));
            assert_eq!(narrow.corner_vertex, wide.corner_vertex);
            assert_eq!(narrow.first_corner, wide.first_corner);
            let bits = |w: &Welded| w.positions.iter().map(|&p| super::bits(p)).collect::<Vec<_>>();
            assert_eq!(bits(&narrow), bits(&wide));
            // Signs of zero as the first corner had them.
            for (v, &c) in narrow.first_corner.iter().enumerate() {
                let p = narrow.positions[v];
                assert!((0..3).all(|k| p[k].to_bits() == widened[c as usize][k].to_bits()));
            }
        }
    }

    #[test]
    fn agrees_with_brute_force_on_random_clusters() {
        // Points jittered around a few centres, some chains: compare the tolerance
        // weld's partition with the transitive closure of "all coordinates within t".
        let mut rng = crate::test_rng::XorShift::new(0x2545f4914f6cdd1du64);
        let mut next = || rng.unit();
        let t = 0.01;
        let corners: Vec<Point> = (0..600)
            .map(|i| {
                let centre = [(i % 7) as f64 * 0.05, (i % 5) as f64 * 0.03, 0.0];
                centre.map(|x| x + (next() - 0.5) * 0.03)
            })
            .collect();
        let w = weld(&corners, Some(t));
        let n = corners.len();
        let mut label: Vec<usize> = (0..n).collect();
        loop {
            let mut changed = false;
            for i in 0..n {
                for j in 0..n {
                    let close = (0..3).all(|k| (corners[i][k] - corners[j][k]).abs() <= t);
                    if close && label[j] < label[i] {
                        label[i] = label[j];
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        for i in 0..n {
            for j in 0..n {
                assert_eq!(label[i] == label[j], w.corner_vertex[i] == w.corner_vertex[j]);
            }
        }
    }

    #[test]
    fn indexed_triangles_weld_as_their_corners() {
        // 30 000 triangles over 12 000 positions drawn from 3 000 points (so most
        // points are stored several times, some with −0.0 for a zero, and some
        // positions are used by no triangle): welding the positions must give what
        // welding every corner gives, bit for bit (positions' signs of zero included).
        let mut rng = crate::test_rng::XorShift::new(0x2545_f491_4f6c_dd1d);
        let points: Vec<Point> = (0..3000)
            .map(|i| [(i % 13) as f64, (i / 13 % 7) as f64 - 3.0, (i / 91) as f64])
            .collect();
        let positions: Vec<Point> = (0..12_000)
            .map(|_| {
                let p = points[rng.below(3000) as usize];
                if rng.below(2) == 0 {
                    p.map(|x| if x == 0.0 { -0.0 } else { x })
                } else {
                    p
                }
            })
            .collect();
        let triangles: Vec<[u32; 3]> =
            (0..30_000).map(|_| [0; 3].map(|_| rng.below(11_000) as u32)).collect();
        let corners: Vec<Point> =
            triangles.iter().flatten().map(|&v| positions[v as usize]).collect();
        let show = |w: &Welded| {
            let positions: Vec<_> = w.positions.iter().map(|p| p.map(f64::to_bits)).collect();
            (w.corner_vertex.clone(), positions, w.first_corner.clone())
        };
        let by_corner = show(&exact(&corners));
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let indexed = pool.install(|| exact_indexed(&positions, &triangles));
            assert_eq!(show(&indexed), by_corner, "{threads} threads");
        }
    }
}
