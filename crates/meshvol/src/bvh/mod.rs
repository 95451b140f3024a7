//! A bounding-volume hierarchy over axis-aligned boxes, for "which boxes overlap this
//! one?" queries (self-intersections, overlapping shells, ray casting).
//!
//! Built as a linear BVH: the caller puts its items in [`Bvh::spatial_order`] (sorted
//! by the Morton code of their box centres, by a counting sort on the codes' top bits,
//! so items close in space are close in the order, and so is the caller's data about
//! them); ranges of that order are split in two, at a multiple of [`LEAF_SIZE`] that
//! halves their count of leaves, until a node holds at most [`LEAF_SIZE`] items, so
//! every leaf but the last is full; node boxes are computed bottom-up. Queries walk the
//! tree with an explicit stack; pair searches walk two.
//!
//! Boxes are stored in f32, rounded outward ([`Box32`]): a box test is then two 4-lane
//! comparisons on 32 bytes instead of six on 48. Rounding outward only adds candidates
//! (boxes that miss by less than an f32 rounding), and every caller tests its
//! candidates exactly. A leaf's boxes are stored by coordinate ([`LeafBoxes`]), so one
//! box is tested against eight of a leaf's in six 8-lane comparisons that give a bit mask
//! of the hits: the leaves' box tests were most of a pair search's time (measured on a
//! 1M-triangle sphere: 9.3M overlapping pairs among 1.4M pairs of 8-item leaves). With
//! the tests this cheap, 16-item leaves (half the node pairs) came out ahead of 8.
//! Full leaves, not halved counts: halving 5M items gives leaves of 9–10 (5M / 2¹⁹),
//! 1M items leaves of 15–16, so a 5M sphere's search walked 5.1 node pairs and 1.14
//! leaf pairs a triangle against 3.0 and 0.68 at 1M, for the same 8.7 box pairs.
//!
//! | stage | file |
//! |---|---|
//! | boxes (`Box32`, a leaf's `LeafBoxes`), nodes, the tree's layout, Morton codes | `mod.rs` |
//! | spatial order (a counting sort of the Morton codes), build (top-down split, boxes bottom-up), refit | `build.rs` |
//! | one box against the tree | `query.rs` |
//! | pairs of overlapping items (one tree, two trees, the first pair) | `pairs.rs` |
//!
//! Written here because the general crates (parry's Qbvh, `bvh`) bring their own
//! vector types and far more than these two queries need.

use crate::buckets::{filled, for_each_range_mut, par_compact, par_starts, Buckets};
use crate::properties::Bounds;
use crate::Point;
use rayon::prelude::*;
use std::ops::{ControlFlow, Range};
use wide::{f32x8, u32x8};

/// Interleaves the low 21 bits of x, y and z: x in bits 0, 3, 6, …
fn morton(x: u64, y: u64, z: u64) -> u64 {
    let spread = |mut v: u64| {
        v &= 0x1f_ffff;
        v = (v | v << 32) & 0x1f00000000ffff;
        v = (v | v << 16) & 0x1f0000ff0000ff;
        v = (v | v << 8) & 0x100f00f00f00f00f;
        v = (v | v << 4) & 0x10c30c30c30c30c3;
        (v | v << 2) & 0x1249249249249249
    };
    spread(x) | spread(y) << 1 | spread(z) << 2
}

/// The Morton code of each point `point(i)`, `i < n`, on a 2²¹ grid per axis over their
/// box (read twice, never stored: a caller's points may be its items' centres, found
/// afresh from their corners each time).
fn morton_codes(n: usize, point: impl Fn(usize) -> Point + Sync) -> Vec<u64> {
    let include = |mut b: Bounds, i: usize| {
        b.include(point(i));
        b
    };
    let merged = |mut a: Bounds, b: Bounds| {
        a.merge(&b);
        a
    };
    // Minima and maxima do not depend on the order: the same box as Bounds::of_points.
    let frame = (0..n)
        .into_par_iter()
        .with_min_len(1 << 14)
        .fold(|| Bounds::EMPTY, include)
        .reduce(|| Bounds::EMPTY, merged);
    let size = frame.size();
    (0..n)
        .into_par_iter()
        .map(|i| {
            let c = point(i);
            let cell = |k: usize| {
                let t = if size[k] > 0.0 { (c[k] - frame.min[k]) / size[k] } else { 0.0 };
                (t * 2097151.0) as u64 // 21 bits per axis
            };
            morton(cell(0), cell(1), cell(2))
        })
        .collect()
}

/// Nodes with more items than this split their pair searches across threads.
const PARALLEL_ITEMS: u32 = 4096;

/// Items per leaf.
const LEAF_SIZE: usize = 16;

/// Boxes per SIMD comparison.
const LANES: usize = 8;

/// An axis-aligned box in f32, rounded outward (it contains the f64 box it was made
/// from), as two 4-lane rows whose fourth lanes are 0 so they never decide a test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Box32 {
    min: [f32; 4],
    max: [f32; 4],
}

/// The largest f32 at most `x`.
fn f32_down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) <= x {
        y
    } else if y > 0.0 {
        f32::from_bits(y.to_bits() - 1)
    } else if y < 0.0 {
        f32::from_bits(y.to_bits() + 1)
    } else {
        -f32::from_bits(1) // below a tiny positive x that rounded to 0
    }
}

/// The smallest f32 at least `x`.
fn f32_up(x: f64) -> f32 {
    -f32_down(-x)
}

impl Box32 {
    /// Contains nothing: the identity of [`Box32::merge`].
    const EMPTY: Box32 = Box32 {
        min: [f32::INFINITY, f32::INFINITY, f32::INFINITY, 0.0],
        max: [f32::NEG_INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY, 0.0],
    };

    pub fn around(b: &Bounds) -> Box32 {
        // `+ 0.0` turns −0 into +0: a box around −0 is the box around +0, bit for bit
        // (a check's welded points may keep −0 where a body's points have +0).
        let [x, y, z] = b.min.map(|x| f32_down(x) + 0.0);
        let [u, v, w] = b.max.map(|x| f32_up(x) + 0.0);
        Box32 { min: [x, y, z, 0.0], max: [u, v, w, 0.0] }
    }

    fn merge(&mut self, other: &Box32) {
        for k in 0..3 {
            self.min[k] = self.min[k].min(other.min[k]);
            self.max[k] = self.max[k].max(other.max[k]);
        }
    }
}

/// Whether closed boxes `a` and `b` overlap. All comparisons, combined without
/// short-circuiting: the outcome is unpredictable, and one branch mispredicts less
/// than six (this test is most of a pair search's time).
#[inline(always)]
fn overlaps(a: &Box32, b: &Box32) -> bool {
    let mut all = true;
    for k in 0..4 {
        all &= (a.min[k] <= b.max[k]) & (b.min[k] <= a.max[k]);
    }
    all
}

/// The boxes of a leaf's items by coordinate, lane i for item i (lanes past the leaf's
/// items hold empty boxes, and are masked off too: a query may reach infinity).
#[derive(Clone, Copy, Debug)]
#[repr(align(32))]
struct LeafBoxes {
    min: [[f32; LEAF_SIZE]; 3],
    max: [[f32; LEAF_SIZE]; 3],
}

impl LeafBoxes {
    fn of(boxes: &[Box32]) -> LeafBoxes {
        let mut leaf = LeafBoxes {
            min: [[f32::INFINITY; LEAF_SIZE]; 3],
            max: [[f32::NEG_INFINITY; LEAF_SIZE]; 3],
        };
        for (i, b) in boxes.iter().enumerate() {
            for k in 0..3 {
                leaf.min[k][i] = b.min[k];
                leaf.max[k][i] = b.max[k];
            }
        }
        leaf
    }

    /// Bit i set when lane i's box overlaps `query` (closed boxes).
    #[inline(always)]
    fn overlapping(&self, query: &Box32) -> u32 {
        let mut mask = 0;
        for group in 0..LEAF_SIZE / LANES {
            let lanes = |row: &[f32; LEAF_SIZE]| f32x8::from(row.as_chunks::<LANES>().0[group]);
            let mut hits = f32x8::splat(f32::from_bits(u32::MAX)); // all bits set: true
            for k in 0..3 {
                hits &= lanes(&self.min[k]).simd_le(f32x8::splat(query.max[k]));
                hits &= f32x8::splat(query.min[k]).simd_le(lanes(&self.max[k]));
            }
            mask |= hits.to_bitmask() << (LANES * group);
        }
        mask
    }

    /// Lane i's box. Indexed in place: `self.min.map(|m| m[i])` copied each 16-lane
    /// row to the stack before taking one lane (six row copies an item in the pair
    /// search's profile).
    #[inline(always)]
    fn get(&self, i: usize) -> Box32 {
        let (min, max) = (&self.min, &self.max);
        Box32 {
            min: [min[0][i], min[1][i], min[2][i], 0.0],
            max: [max[0][i], max[1][i], max[2][i], 0.0],
        }
    }
}

/// The items a leaf's lane mask selects, lowest first: the leaf's first item plus each
/// set bit's lane. (A named type, so that a pair search can hand an item's partners to
/// its caller.)
struct Lanes {
    mask: u32,
    first: usize,
}

impl Lanes {
    fn of(mask: u32, first: usize) -> Lanes {
        Lanes { mask, first }
    }
}

impl Iterator for Lanes {
    type Item = usize;

    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        let bit = self.mask.trailing_zeros();
        self.mask &= self.mask.wrapping_sub(1);
        (bit < 32).then_some(self.first + bit as usize)
    }
}

/// The tags of a leaf's items by slot, lane i for item i ([`NO_TAG`] past the leaf's
/// items), so that one item's tags are compared with a leaf's in 8-lane comparisons.
#[derive(Clone, Copy, Debug)]
#[repr(align(32))]
struct LeafTags {
    slots: [[u32; LEAF_SIZE]; 3],
}

impl LeafTags {
    fn of(items: &[[u32; 3]]) -> LeafTags {
        let mut leaf = LeafTags { slots: [[NO_TAG; LEAF_SIZE]; 3] };
        for (i, tags) in items.iter().enumerate() {
            for k in 0..3 {
                leaf.slots[k][i] = tags[k];
            }
        }
        leaf
    }

    /// Bit i set when lane i's item has one of `query`'s tags ([`NO_TAG`] matches
    /// nothing).
    #[inline(always)]
    fn sharing(&self, query: &[u32; 3]) -> u32 {
        let mut mask = 0;
        for group in 0..LEAF_SIZE / LANES {
            let lanes = |row: &[u32; LEAF_SIZE]| u32x8::from(row.as_chunks::<LANES>().0[group]);
            let mut hits = u32x8::splat(0);
            for &t in query.iter().filter(|&&t| t != NO_TAG) {
                let t = u32x8::splat(t);
                for row in &self.slots {
                    hits |= lanes(row).simd_eq(t);
                }
            }
            mask |= hits.to_bitmask() << (LANES * group);
        }
        mask
    }
}

#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Box32,
    /// Leaf: `count` items, whose boxes are `leaves[start]`; inner: `count == 0` and
    /// the children are nodes `start` and `start + 1`.
    start: u32,
    count: u32,
    /// The items under this node: `begin..end`.
    begin: u32,
    end: u32,
}

impl Node {
    /// The lanes of a leaf's [`LeafBoxes`] that hold items.
    fn lanes(&self) -> u32 {
        (1 << self.count) - 1
    }
}

/// Deeper than any tree built here (depth ≤ log₂ of the item count + 1).
const STACK: usize = 64;

/// No tag: see [`Bvh::overlapping_pairs`].
pub const NO_TAG: u32 = u32::MAX;

/// The items' tags as a pair search reads them: per item, per node (the tags all its
/// items share) and per leaf by slot.
struct Tagging<'a> {
    items: &'a [[u32; 3]],
    shared: Vec<[u32; 3]>,
    leaves: Vec<LeafTags>,
}

impl Tagging<'_> {
    /// Whether every item under node `a` shares a tag with every item under node `b`.
    fn share_a_tag(&self, a: usize, b: usize) -> bool {
        let s = &self.shared;
        s[a].iter().any(|&t| t != NO_TAG && s[b].contains(&t))
    }
}

/// What a search for overlapping pairs carries down the tree.
struct Walk<'a, G, F> {
    tags: Option<&'a Tagging<'a>>,
    prepare: &'a G,
    test: &'a F,
}

/// A bounding-volume hierarchy over items identified by their index.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    leaves: Vec<LeafBoxes>,
    /// The node of each leaf.
    leaf_nodes: Vec<u32>,
    /// The nodes at depth k are `levels[k]..levels[k + 1]` (breadth-first order).
    levels: Vec<u32>,
}

/// The centre of the box around a triangle's corners, by which the crossing search and
/// the overlap's bodies put triangles in spatial order: it does not depend on the order
/// of the corners, so a triangle turned over (as a check's solid turns a shell) keeps
/// its place, and a body can take the order its check found. (Halves are added, so it
/// never overflows.)
pub(crate) fn triangle_centre([a, b, c]: [Point; 3]) -> Point {
    std::array::from_fn(|k| 0.5 * a[k].min(b[k]).min(c[k]) + 0.5 * a[k].max(b[k]).max(c[k]))
}

mod build;
mod pairs;
mod query;
#[cfg(test)]
mod tests;
