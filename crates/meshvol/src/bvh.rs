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
    fn get(&self, i: u32) -> Box32 {
        let i = i as usize;
        let (min, max) = (&self.min, &self.max);
        Box32 {
            min: [min[0][i], min[1][i], min[2][i], 0.0],
            max: [max[0][i], max[1][i], max[2][i], 0.0],
        }
    }
}

/// The bits of `mask`, lowest first.
fn bits(mut mask: u32) -> impl Iterator<Item = u32> {
    std::iter::from_fn(move || {
        let bit = mask.trailing_zeros();
        mask &= mask.wrapping_sub(1);
        (bit < 32).then_some(bit)
    })
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
struct Walk<'a, F> {
    tags: Option<&'a Tagging<'a>>,
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

impl Bvh {
    /// The order of items at `centres` that puts items close in space close together:
    /// by the Morton code of their centres. Items given to [`Bvh::new`] in this order
    /// make a tight tree (and data stored in this order is read nearly sequentially).
    pub fn spatial_order(centres: &[Point]) -> Vec<u32> {
        Bvh::spatial_order_of(centres.len(), |i| centres[i])
    }

    /// [`Bvh::spatial_order`] of the centres `centre(i)`, `i < n`, without a list of
    /// them (24 bytes an item, written once and read twice).
    pub(crate) fn spatial_order_of(n: usize, centre: impl Fn(usize) -> Point + Sync) -> Vec<u32> {
        let codes = morton_codes(n, centre);
        // A counting sort by the codes' top bits (about one group per item), then each
        // group sorted by its full codes: no comparison sort over all items.
        let top = n.max(2).ilog2().min(18);
        let mut order = Buckets::new(1 << top, n, |range| {
            range.map(|i| ((codes[i] >> (63 - top)) as u32, i as u32))
        });
        order.for_each_mut(|group| group.sort_unstable_by_key(|&i| (codes[i as usize], i)));
        order.items
    }

    /// A hierarchy over `boxes` in [`Bvh::spatial_order`] of their centres: the order
    /// (the tree's item k is box `order[k]`) and the tree.
    pub(crate) fn over_boxes(boxes: &[Bounds]) -> (Vec<u32>, Bvh) {
        let centres: Vec<Point> =
            boxes.iter().map(|b| [0, 1, 2].map(|k| 0.5 * b.min[k] + 0.5 * b.max[k])).collect();
        let order = Bvh::spatial_order(&centres);
        let bvh = Bvh::new(order.len(), |k| Box32::around(&boxes[order[k] as usize]));
        (order, bvh)
    }

    /// Builds the hierarchy over `items` items, item i with box `box_of(i)`, grouping
    /// consecutive items: number them in [`Bvh::spatial_order`]. (The boxes are read
    /// straight into the leaves: a list of them would cost 32 bytes an item.)
    pub(crate) fn new(items: usize, box_of: impl Fn(usize) -> Box32 + Sync) -> Bvh {
        if items == 0 {
            return Bvh::default();
        }
        // Top-down: split ranges between whole leaves, the left child taking half of
        // the leaves (rounded up), so that only the last leaf of all may be partial;
        // children always come after their parent.
        let node = |begin: usize, end: usize| Node {
            bounds: Box32::EMPTY,
            start: 0,
            count: 0,
            begin: begin as u32,
            end: end as u32,
        };
        // A full binary tree: 2L − 1 nodes for L leaves, allocated and first touched by
        // all the workers at once, each level's children written in place after it.
        let leaf_count = items.div_ceil(LEAF_SIZE);
        let mut nodes = filled(2 * leaf_count - 1, node(0, 0));
        nodes[0] = node(0, items);
        // Level by level, each in parallel (a node's children and leaf number from a
        // prefix sum over its level): the same numbering as a breadth-first queue.
        let splits = |n: &Node| (n.end - n.begin) as usize > LEAF_SIZE;
        let (mut levels, mut leaves_before) = (vec![0u32], 0);
        let (mut begin, mut end) = (0, 1);
        while begin < end {
            levels.push(end as u32);
            let (done, rest) = nodes.split_at_mut(end);
            let level = &mut done[begin..];
            let leaf_rank = par_starts(level.len(), |i| usize::from(!splits(&level[i])));
            // Every node before i that is not a leaf has two children before i's.
            let child = |i: usize| 2 * (i - leaf_rank[i]);
            let children = child(level.len());
            let range = |i: usize| child(i)..child(i + 1);
            for_each_range_mut(&mut rest[..children], level.len(), &range, &|i, out| {
                if let [left, right] = out {
                    let (start, end) = (level[i].begin as usize, level[i].end as usize);
                    let mid = start + (end - start).div_ceil(LEAF_SIZE).div_ceil(2) * LEAF_SIZE;
                    (*left, *right) = (node(start, mid), node(mid, end));
                }
            });
            level.par_iter_mut().enumerate().for_each(|(i, n)| {
                if splits(n) {
                    n.start = (end + child(i)) as u32;
                } else {
                    n.start = (leaves_before + leaf_rank[i]) as u32;
                    n.count = n.end - n.begin;
                }
            });
            leaves_before += leaf_rank[level.len()];
            (begin, end) = (end, end + children);
        }
        // Leaves are numbered in node order, so the leaves' nodes are the nodes with
        // items, in order.
        let leaf_nodes = par_compact(nodes.len(), |n| nodes[n].count > 0, |n| n as u32);
        debug_assert!(end == nodes.len() && leaf_nodes.len() == leaf_count);
        // Leaves' boxes (most of the reading) in parallel, written in place (a filtered
        // collect would append them on one thread), then inner nodes bottom-up.
        let (mut leaves, mut bounds) = (Vec::new(), filled(nodes.len(), Box32::EMPTY));
        let mut leaf_bounds = Vec::new();
        leaf_nodes
            .par_iter()
            .map(|&n| {
                let (node, mut bounds) = (&nodes[n as usize], Box32::EMPTY);
                let mut boxes = [Box32::EMPTY; LEAF_SIZE];
                for (b, i) in boxes.iter_mut().zip(node.begin as usize..node.end as usize) {
                    *b = box_of(i);
                    bounds.merge(b);
                }
                (LeafBoxes::of(&boxes[..node.count as usize]), bounds)
            })
            .unzip_into_vecs(&mut leaves, &mut leaf_bounds);
        for (&n, b) in leaf_nodes.iter().zip(leaf_bounds) {
            bounds[n as usize] = b;
        }
        let mut bvh = Bvh { nodes, leaves, leaf_nodes, levels };
        bvh.bottom_up(&mut bounds, |l, r| {
            let mut b = *l;
            b.merge(r);
            b
        });
        bvh.nodes.par_iter_mut().zip(bounds).for_each(|(n, b)| n.bounds = b);
        bvh
    }

    /// Sets `values[n] = combine(values[left], values[right])` for every inner node n,
    /// children before parents: a level at a time, from the deepest, each level in
    /// parallel when it is large (the same operations in any order: no node reads its
    /// own level).
    fn bottom_up<T: Copy + Send + Sync>(
        &self,
        values: &mut [T],
        combine: impl Fn(&T, &T) -> T + Sync,
    ) {
        const PARALLEL_LEVEL: usize = 1 << 12;
        for k in (0..self.levels.len().saturating_sub(1)).rev() {
            let (begin, end) = (self.levels[k] as usize, self.levels[k + 1] as usize);
            let (upper, lower) = values.split_at_mut(end);
            let set = |(i, value): (usize, &mut T)| {
                let node = &self.nodes[begin + i];
                if node.count == 0 {
                    let left = node.start as usize - end;
                    *value = combine(&lower[left], &lower[left + 1]);
                }
            };
            let level = &mut upper[begin..];
            if level.len() >= PARALLEL_LEVEL {
                level.par_iter_mut().enumerate().for_each(set);
            } else {
                level.iter_mut().enumerate().for_each(set);
            }
        }
    }

    /// Calls `visit(item)` for every item whose box overlaps `query` (closed boxes:
    /// touching counts), and perhaps for items that miss it by less than an f32 rounding.
    pub fn overlapping(&self, query: &Bounds, visit: impl FnMut(usize)) {
        self.overlapping_where(query, |_, _, _| true, visit);
    }

    /// Like [`Bvh::overlapping`], with a say for the caller at every node: the walk
    /// enters a node whose box meets `query` only when `enter(node, min, max)` accepts
    /// it (the node's box, rounded outward, in f64), so a caller that knows more about
    /// its query than its box (a thin triangle across a box's corner) prunes subtrees.
    /// Nodes are numbered as in [`Bvh::node_tags`].
    pub(crate) fn overlapping_where(
        &self,
        query: &Bounds,
        mut enter: impl FnMut(usize, [f64; 2], [f64; 2]) -> bool,
        mut visit: impl FnMut(usize),
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let query = &Box32::around(query);
        let mut stack = [0u32; STACK];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let n = stack[top] as usize;
            let node = &self.nodes[n];
            if !overlaps(&node.bounds, query) {
                continue;
            }
            let (lo, hi) = (node.bounds.min, node.bounds.max);
            let corners = ([lo[0], lo[1]].map(f64::from), [hi[0], hi[1]].map(f64::from));
            if !enter(n, corners.0, corners.1) {
                continue;
            }
            if node.count > 0 {
                let hits = self.leaves[node.start as usize].overlapping(query) & node.lanes();
                bits(hits).for_each(|i| visit((node.begin + i) as usize));
            } else {
                stack[top] = node.start;
                stack[top + 1] = node.start + 1;
                top += 2;
            }
        }
    }

    /// The items under node `node`.
    pub(crate) fn items(&self, node: u32) -> Range<usize> {
        let n = &self.nodes[node as usize];
        n.begin as usize..n.end as usize
    }

    /// Each node's box recomputed from its items' boxes `item_box(i)` (the items moved,
    /// say, as a body placed by a pose): leaves from their items, inner nodes from their
    /// children. Tight, in whatever frame the item boxes are; for
    /// [`Bvh::leaf_pairs_between`].
    pub(crate) fn refit(&self, item_box: impl Fn(usize) -> Bounds + Sync) -> Vec<Bounds> {
        let mut boxes: Vec<Bounds> = self
            .nodes
            .par_iter()
            .map(|n| {
                let mut b = Bounds::EMPTY;
                if n.count > 0 {
                    for i in n.begin as usize..n.end as usize {
                        b.merge(&item_box(i));
                    }
                }
                b
            })
            .collect();
        self.bottom_up(&mut boxes, |l, r| {
            let mut b = *l;
            b.merge(r);
            b
        });
        boxes
    }

    /// The pairs of leaves, one of this tree and one of `other`, whose boxes as placed
    /// (`boxes`, `other_boxes`: [`Bvh::refit`], both in one frame) overlap,
    /// as node numbers ([`Bvh::items`] gives their items); in the order of a depth-first walk, so
    /// the same every time. A dual-tree walk: node pairs whose boxes miss are dropped
    /// whole, the larger node of the others split, so two bodies that meet along a
    /// curve cost about the leaves near the curve, not a query per item.
    pub(crate) fn leaf_pairs_between(
        &self,
        other: &Bvh,
        boxes: &[Bounds],
        other_boxes: &[Bounds],
    ) -> Vec<(u32, u32)> {
        let mut pairs = Vec::new();
        if self.nodes.is_empty() || other.nodes.is_empty() {
            return pairs;
        }
        let meets =
            |p: &Bounds, q: &Bounds| (0..3).all(|k| p.min[k] <= q.max[k] && q.min[k] <= p.max[k]);
        let mut stack: Vec<(u32, u32)> = vec![(0, 0)];
        while let Some((m, n)) = stack.pop() {
            if !meets(&boxes[m as usize], &other_boxes[n as usize]) {
                continue;
            }
            let (p, q) = (&self.nodes[m as usize], &other.nodes[n as usize]);
            let (p_leaf, q_leaf) = (p.count > 0, q.count > 0);
            if p_leaf && q_leaf {
                pairs.push((m, n));
            } else if q_leaf || (!p_leaf && p.end - p.begin >= q.end - q.begin) {
                stack.push((p.start + 1, n));
                stack.push((p.start, n));
            } else {
                stack.push((m, q.start + 1));
                stack.push((m, q.start));
            }
        }
        pairs
    }

    /// Per node, the tags (up to three per item, [`NO_TAG`] for none) that every item
    /// under it has, for [`Bvh::overlapping_where`]'s `enter`.
    pub(crate) fn node_tags(&self, tags: &[[u32; 3]]) -> Vec<[u32; 3]> {
        self.shared_tags(tags)
    }

    /// Every unordered pair of distinct items whose boxes overlap (and perhaps some that
    /// miss by less than an f32 rounding), passed to `test`; returns what `test` kept,
    /// sorted.
    ///
    /// A dual-tree traversal: pairs of nodes whose boxes overlap are split (the larger
    /// node first) down to pairs of leaves, so the work is proportional to the pairs of
    /// nearby nodes rather than a full query per item; the top levels run in parallel.
    ///
    /// With `tags` (up to three per item, [`NO_TAG`] for none), no pair of items sharing
    /// a tag reaches `test`: node pairs whose items all share a tag are skipped
    /// unvisited (the triangles around a vertex of degree k overlap near it, k²/2 pairs
    /// that a search for crossings between non-neighbours need not walk), and in a pair
    /// of leaves an item's tags are compared with the other leaf's in SIMD lanes, which
    /// masks its neighbours off with its box tests (on a 1M-triangle sphere, 6.3M of the
    /// 8.6M pairs of overlapping boxes are neighbours: tested one by one, they were
    /// most of the walk's branches, mispredicted half the time).
    pub fn overlapping_pairs<T: Ord + Send>(
        &self,
        tags: Option<&[[u32; 3]]>,
        test: impl Fn(usize, usize) -> Option<T> + Sync,
    ) -> Vec<T> {
        let mut found = Vec::new();
        if !self.nodes.is_empty() {
            let tagging = tags.map(|tags| self.tagging(tags));
            let walk = Walk { tags: tagging.as_ref(), test: &test };
            self.pairs_under(0, 0, &walk, &mut found);
        }
        found.par_sort_unstable();
        found
    }

    /// The tags of items, nodes and leaves for a pair search.
    fn tagging<'a>(&self, tags: &'a [[u32; 3]]) -> Tagging<'a> {
        let leaves =
            self.leaf_nodes.par_iter().map(|&n| LeafTags::of(&tags[self.items(n)])).collect();
        Tagging { items: tags, shared: self.shared_tags(tags), leaves }
    }

    /// Per node, the tags every item under it has (unused slots [`NO_TAG`]): leaves from
    /// their items, inner nodes from their children (which come after them).
    fn shared_tags(&self, tags: &[[u32; 3]]) -> Vec<[u32; 3]> {
        let common = |a: [u32; 3], b: &[u32; 3]| a.map(|t| if b.contains(&t) { t } else { NO_TAG });
        let mut shared: Vec<[u32; 3]> = self
            .nodes
            .par_iter()
            .map(|n| match n.count {
                0 => [NO_TAG; 3],
                _ => {
                    let items = &tags[n.begin as usize..n.end as usize];
                    items[1..].iter().fold(items[0], &common)
                }
            })
            .collect();
        self.bottom_up(&mut shared, |l, r| common(*l, r));
        shared
    }

    /// Adds to `found` what `test` keeps of the overlapping pairs with one item under
    /// node `a` and the other under node `b` (each pair once when `a == b`). Splits
    /// big nodes across threads, then walks small ones with [`Bvh::pairs_in_thread`].
    fn pairs_under<T: Send, F: Fn(usize, usize) -> Option<T> + Sync>(
        &self,
        a: usize,
        b: usize,
        test: &Walk<'_, F>,
        found: &mut Vec<T>,
    ) {
        let (na, nb) = (&self.nodes[a], &self.nodes[b]);
        if !overlaps(&na.bounds, &nb.bounds) || test.tags.is_some_and(|t| t.share_a_tag(a, b)) {
            return;
        }
        if (na.end - na.begin).max(nb.end - nb.begin) <= PARALLEL_ITEMS {
            return self.pairs_in_thread(a, b, test, found);
        }
        let (x, y) = if a == b {
            // The pairs across the two children alongside those within each: no thread
            // waits for both halves before the seam between them starts.
            let (l, r) = (na.start as usize, na.start as usize + 1);
            let ((mut x, y), across) = rayon::join(
                || {
                    rayon::join(
                        || self.collect_pairs(l, l, test),
                        || self.collect_pairs(r, r, test),
                    )
                },
                || self.collect_pairs(l, r, test),
            );
            x.extend(across);
            (x, y)
        } else {
            let (keep, split) = self.split(a, b);
            let first = self.nodes[split].start as usize;
            rayon::join(
                || self.collect_pairs(keep, first, test),
                || self.collect_pairs(keep, first + 1, test),
            )
        };
        found.extend(x);
        found.extend(y);
    }

    /// Of two distinct nodes, not both leaves: (the one kept, the one whose children
    /// are paired with it): the inner one, the larger when both are inner.
    fn split(&self, a: usize, b: usize) -> (usize, usize) {
        let (na, nb) = (&self.nodes[a], &self.nodes[b]);
        let split_a = na.count == 0 && (nb.count > 0 || na.end - na.begin >= nb.end - nb.begin);
        if split_a {
            (b, a)
        } else {
            (a, b)
        }
    }

    /// [`Bvh::pairs_under`] in this thread, with an explicit stack of node pairs.
    fn pairs_in_thread<T, F: Fn(usize, usize) -> Option<T>>(
        &self,
        a: usize,
        b: usize,
        test: &Walk<'_, F>,
        found: &mut Vec<T>,
    ) {
        let _: ControlFlow<()> = self.walk_pairs(a, b, test.tags, |i, j| {
            found.extend((test.test)(i, j));
            ControlFlow::Continue(())
        });
    }

    /// The first pair of distinct items whose boxes overlap (perhaps missing by less
    /// than an f32 rounding) that `test` accepts, in one thread; `None` when no pair
    /// is accepted. Stops at the first, so a crowd of overlaps costs no more than one.
    /// `tags` skip node pairs as in [`Bvh::overlapping_pairs`].
    pub fn first_overlapping_pair(
        &self,
        tags: Option<&[[u32; 3]]>,
        test: impl Fn(usize, usize) -> bool,
    ) -> Option<(usize, usize)> {
        if self.nodes.is_empty() {
            return None;
        }
        let tagging = tags.map(|tags| self.tagging(tags));
        let found = self.walk_pairs(0, 0, tagging.as_ref(), |i, j| {
            if test(i, j) {
                ControlFlow::Break((i, j))
            } else {
                ControlFlow::Continue(())
            }
        });
        match found {
            ControlFlow::Break(pair) => Some(pair),
            ControlFlow::Continue(()) => None,
        }
    }

    /// Visits the overlapping pairs with one item under node `a` and the other under
    /// node `b` (each pair once when `a == b`), but no pair sharing one of `tags`,
    /// until `visit` breaks.
    fn walk_pairs<B>(
        &self,
        a: usize,
        b: usize,
        tags: Option<&Tagging>,
        mut visit: impl FnMut(usize, usize) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        // Each step pushes at most 3 pairs and descends a level: a few times the depth.
        let mut stack: Vec<(u32, u32)> = Vec::with_capacity(4 * STACK);
        stack.push((a as u32, b as u32));
        while let Some((a, b)) = stack.pop() {
            let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
            if !overlaps(&na.bounds, &nb.bounds)
                || tags.is_some_and(|t| t.share_a_tag(a as usize, b as usize))
            {
                continue;
            }
            if na.count > 0 && nb.count > 0 {
                self.leaf_pairs(na, nb, a == b, tags, &mut visit)?;
            } else if a == b {
                let (l, r) = (na.start, na.start + 1);
                stack.extend([(l, r), (r, r), (l, l)]);
            } else {
                let (keep, split) = self.split(a as usize, b as usize);
                let first = self.nodes[split].start;
                stack.extend([(keep as u32, first + 1), (keep as u32, first)]);
            }
        }
        ControlFlow::Continue(())
    }

    /// The pairs of two leaves (of one leaf with itself, when `same`).
    #[inline]
    fn leaf_pairs<B>(
        &self,
        na: &Node,
        nb: &Node,
        same: bool,
        tags: Option<&Tagging>,
        visit: &mut impl FnMut(usize, usize) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        let (a, b) = (&self.leaves[na.start as usize], &self.leaves[nb.start as usize]);
        // Only items that reach the other leaf's box can be in a pair.
        let reaching = a.overlapping(&nb.bounds) & na.lanes();
        for i in bits(reaching) {
            let mut partners = b.overlapping(&a.get(i)) & nb.lanes();
            if same {
                partners &= !((2 << i) - 1); // later items only: each pair once
            }
            if let Some(t) = tags {
                let item = &t.items[(na.begin + i) as usize];
                partners &= !t.leaves[nb.start as usize].sharing(item);
            }
            for j in bits(partners) {
                visit((na.begin + i) as usize, (nb.begin + j) as usize)?;
            }
        }
        ControlFlow::Continue(())
    }

    fn collect_pairs<T: Send, F: Fn(usize, usize) -> Option<T> + Sync>(
        &self,
        a: usize,
        b: usize,
        test: &Walk<'_, F>,
    ) -> Vec<T> {
        let mut found = Vec::new();
        self.pairs_under(a, b, test, &mut found);
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tree as a breadth-first queue builds it, one node at a time: the reference
    /// for the level-by-level build. (begin, end, start, count) per node and the
    /// leaves' node numbers in order.
    fn queue_built(items: usize) -> (Vec<[u32; 4]>, Vec<usize>) {
        let (mut nodes, mut leaves, mut next) = (vec![[0, items as u32, 0, 0]], Vec::new(), 0);
        while next < nodes.len() {
            let [begin, end, ..] = nodes[next].map(|x| x as usize);
            if end - begin <= LEAF_SIZE {
                nodes[next][2] = leaves.len() as u32;
                nodes[next][3] = (end - begin) as u32;
                leaves.push(next);
            } else {
                let mid = begin + (end - begin).div_ceil(LEAF_SIZE).div_ceil(2) * LEAF_SIZE;
                nodes[next][2] = nodes.len() as u32;
                nodes.push([begin as u32, mid as u32, 0, 0]);
                nodes.push([mid as u32, end as u32, 0, 0]);
            }
            next += 1;
        }
        (nodes, leaves)
    }

    #[test]
    fn the_level_by_level_build_numbers_nodes_as_a_queue_and_bounds_hold_their_items() {
        let item = |i: usize| {
            let c = [(i * 37 % 101) as f64, (i * 11 % 53) as f64 * 0.5, (i % 7) as f64];
            Bounds { min: c, max: [c[0] + 1.5, c[1] + 0.25, c[2] + (i % 3) as f64] }
        };
        for items in [1, 15, 16, 17, 33, 1000, 70_001] {
            let (queue, leaves) = queue_built(items);
            for threads in [1, 2, 5] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let bvh = pool.install(|| Bvh::new(items, |i| Box32::around(&item(i))));
                let got: Vec<[u32; 4]> =
                    bvh.nodes.iter().map(|n| [n.begin, n.end, n.start, n.count]).collect();
                assert_eq!(got, queue, "{items} items, {threads} threads");
                assert_eq!(bvh.leaves.len(), leaves.len());
                let boxes = pool.install(|| bvh.refit(item));
                for (n, node) in bvh.nodes.iter().enumerate() {
                    let mut union = Bounds::EMPTY;
                    (node.begin as usize..node.end as usize).for_each(|i| union.merge(&item(i)));
                    assert_eq!(boxes[n], union, "{items} items: node {n}'s refitted box");
                    assert_eq!(node.bounds, Box32::around(&union), "{items} items: node {n}");
                }
            }
        }
    }

    #[test]
    fn morton_interleaves_bits() {
        assert_eq!(morton(1, 0, 0), 1);
        assert_eq!(morton(0, 1, 0), 2);
        assert_eq!(morton(0, 0, 1), 4);
        assert_eq!(morton(3, 0, 0), 0b1001);
        assert_eq!(morton(0x1f_ffff, 0x1f_ffff, 0x1f_ffff), (1u64 << 63) - 1);
    }

    #[test]
    fn f32_boxes_contain_their_f64_boxes_tightly() {
        let mut rng = crate::test_rng::XorShift::new(0x853c49e6748fea9bu64);
        let mut values = vec![0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300, 0.1, -0.1, 16777217.0];
        for _ in 0..100_000 {
            let x = f64::from_bits(rng.next_u64());
            if x.is_finite() {
                values.push(x);
            }
        }
        for x in values {
            let (down, up) = (f32_down(x), f32_up(x));
            assert!(f64::from(down) <= x && x <= f64::from(up), "{x}");
            // Tight: x's nearest f32 is one of the two, and they are x when x is an f32.
            let nearest = x as f32;
            assert!(nearest == down || nearest == up, "{x}");
            if f64::from(nearest) == x {
                assert!(down == nearest && up == nearest, "{x}");
            }
        }
    }

    #[test]
    fn spatial_order_is_the_order_of_the_morton_codes() {
        // Clustered points (many share top bits, some share whole codes).
        let mut rng = crate::test_rng::XorShift::new(0x2545f4914f6cdd1du64);
        let mut next = || rng.unit();
        let points: Vec<Point> = (0..60_000)
            .map(|i| {
                let spread = if i % 3 == 0 { 1e-7 } else { 1.0 };
                [next() * spread, next() * spread, (next() * 8.0).floor()]
            })
            .collect();
        let codes = morton_codes(points.len(), |i| points[i]);
        let mut expected: Vec<u32> = (0..points.len() as u32).collect();
        expected.sort_by_key(|&i| (codes[i as usize], i));
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            assert_eq!(pool.install(|| Bvh::spatial_order(&points)), expected);
        }
    }

    /// Exact overlap of f64 boxes, for the brute-force answers.
    fn overlap(a: &Bounds, b: &Bounds) -> bool {
        (0..3).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k])
    }

    #[test]
    fn random_boxes_of_every_size_give_the_brute_force_pairs_and_queries() {
        // Points, slivers and boxes spanning most of the space, at f32 values (so the
        // f32 boxes are the boxes), in an item count that leaves partial leaves.
        let mut rng = crate::test_rng::XorShift::new(0x9e3779b97f4a7c15u64);
        let mut next = || rng.unit() as f32 as f64;
        let boxes: Vec<Bounds> = (0..3001)
            .map(|i| {
                let size = match i % 4 {
                    0 => 0.0,
                    1 => 0.01,
                    2 => 0.05,
                    _ => 0.5,
                };
                let min = [next(), next(), next()];
                let max = [0, 1, 2].map(|k| (min[k] + size * next()) as f32 as f64);
                Bounds { min, max }
            })
            .collect();
        let bvh = Bvh::new(boxes.len(), |i| Box32::around(&boxes[i]));
        let pairs = bvh.overlapping_pairs(None, |a, b| Some((a.min(b), a.max(b))));
        let brute: Vec<(usize, usize)> = (0..boxes.len())
            .flat_map(|a| (a + 1..boxes.len()).map(move |b| (a, b)))
            .filter(|&(a, b)| overlap(&boxes[a], &boxes[b]))
            .collect();
        assert!(brute.len() > 10_000);
        assert!(pairs == brute, "{} pairs found, {} overlap", pairs.len(), brute.len());
        // Tagged (runs of 100 items sharing a tag, as the triangles around a vertex of
        // high degree do, and tags shared across runs), the pairs that share no tag are
        // exactly those that share none; NO_TAG in a slot matches nothing.
        let tags: Vec<[u32; 3]> =
            (0..boxes.len() as u32).map(|i| [i / 100, 1000 + i % 3, NO_TAG]).collect();
        let apart =
            |&(a, b): &(usize, usize)| !tags[a].iter().any(|t| *t != NO_TAG && tags[b].contains(t));
        let tagged = bvh.overlapping_pairs(Some(&tags), |a, b| Some((a.min(b), a.max(b))));
        let kept: Vec<(usize, usize)> = brute.iter().copied().filter(apart).collect();
        assert!(kept.len() > 1000 && kept.len() < brute.len(), "{}", kept.len());
        assert_eq!(tagged, kept);
        // The first pair found with tags shares none; with one tag for all, none is found.
        let first = bvh.first_overlapping_pair(Some(&tags), |_, _| true).unwrap();
        let first = (first.0.min(first.1), first.0.max(first.1));
        assert!(kept.contains(&first), "{first:?}");
        let one_tag = vec![[NO_TAG, 7, NO_TAG]; boxes.len()];
        assert_eq!(bvh.first_overlapping_pair(Some(&one_tag), |_, _| true), None);
        let no_tags = vec![[NO_TAG; 3]; boxes.len()];
        assert_eq!(bvh.overlapping_pairs(Some(&no_tags), |a, b| Some((a.min(b), a.max(b)))), brute);
        // Queries, some reaching infinity (as rays' boxes do).
        let (inf, x) = (f64::INFINITY, 0.5);
        for q in [
            Bounds { min: [x, x, x], max: [inf, x, x] },
            Bounds { min: [-inf, x, 0.25], max: [x, x, 0.75] },
            Bounds { min: [-inf; 3], max: [inf; 3] },
            Bounds { min: [0.1, 0.2, 0.3], max: [0.4, 0.45, 0.5] },
        ] {
            let mut found = vec![];
            bvh.overlapping(&q, |i| found.push(i));
            found.sort();
            let brute: Vec<usize> = (0..boxes.len()).filter(|&i| overlap(&boxes[i], &q)).collect();
            assert_eq!(found, brute);
        }
    }

    #[test]
    fn leaf_pairs_of_two_trees_hold_every_overlapping_pair_of_items() {
        // Two sets of random boxes, the second moved by a shift applied to its node
        // boxes (as a pose is): every pair of items whose boxes overlap, once moved,
        // lies in exactly one leaf pair found.
        let mut rng = crate::test_rng::XorShift::new(17);
        let mut make = |count: usize, size: f64| -> Vec<Bounds> {
            (0..count)
                .map(|_| {
                    let min = [0; 3].map(|_| rng.unit() as f32 as f64);
                    let max = min.map(|x| (x + size * rng.unit()) as f32 as f64);
                    Bounds { min, max }
                })
                .collect()
        };
        let (first, second) = (make(1500, 0.1), make(999, 0.2));
        let shift = 0.25;
        let moved =
            |b: &Bounds| Bounds { min: b.min.map(|x| x + shift), max: b.max.map(|x| x + shift) };
        let tree = |boxes: &[Bounds]| Bvh::new(boxes.len(), |i| Box32::around(&boxes[i]));
        let (p, q) = (tree(&first), tree(&second));
        let leaves =
            p.leaf_pairs_between(&q, &p.refit(|i| first[i]), &q.refit(|i| moved(&second[i])));
        let mut found: Vec<(usize, usize)> = leaves
            .iter()
            .flat_map(|&(m, n)| {
                let items_b = q.items(n);
                p.items(m).flat_map(move |i| items_b.clone().map(move |j| (i, j)))
            })
            .filter(|&(i, j)| overlap(&first[i], &moved(&second[j])))
            .collect();
        let count = found.len();
        found.sort_unstable();
        found.dedup();
        assert_eq!(found.len(), count, "a pair of leaves found twice");
        let brute: Vec<(usize, usize)> = (0..first.len())
            .flat_map(|i| (0..second.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| overlap(&first[i], &moved(&second[j])))
            .collect();
        assert!(brute.len() > 1000, "{}", brute.len());
        assert_eq!(found, brute);
    }

    #[test]
    fn finds_exactly_the_overlapping_boxes() {
        // A 20×20 lattice of unit boxes with gaps (all values f32: the f32 boxes are
        // the boxes); compare with brute force.
        let boxes: Vec<Bounds> = (0..400)
            .map(|i| {
                let (x, y) = ((i % 20) as f64 * 1.5, (i / 20) as f64 * 1.5);
                Bounds { min: [x, y, 0.0], max: [x + 1.0, y + 1.0, 1.0] }
            })
            .collect();
        // In the given (row) order and in spatial order: the same answers.
        let centre = |b: &Bounds| [0, 1, 2].map(|k| 0.5 * (b.min[k] + b.max[k]));
        let centres: Vec<Point> = boxes.iter().map(centre).collect();
        let order = Bvh::spatial_order(&centres);
        assert_eq!(order.len(), boxes.len());
        let spatial: Vec<Bounds> = order.iter().map(|&i| boxes[i as usize]).collect();
        let tree = |boxes: &[Bounds]| Bvh::new(boxes.len(), |i| Box32::around(&boxes[i]));
        let (bvh, spatial_bvh) = (tree(&boxes), tree(&spatial));
        for q in [
            Bounds { min: [0.5, 0.5, 0.5], max: [3.2, 2.0, 0.6] },
            Bounds { min: [-5.0; 3], max: [-4.0; 3] },
            Bounds { min: [1.0, 1.0, 1.0], max: [1.5, 1.5, 2.0] }, // touches a corner
        ] {
            let mut found = vec![];
            bvh.overlapping(&q, |i| found.push(i));
            found.sort();
            let brute: Vec<usize> = (0..boxes.len()).filter(|&i| overlap(&boxes[i], &q)).collect();
            assert_eq!(found, brute);
            let mut found: Vec<usize> = vec![];
            spatial_bvh.overlapping(&q, |i| found.push(order[i] as usize));
            found.sort();
            assert_eq!(found, brute);
        }
        let mut none = 0;
        Bvh::new(0, |_| Box32::EMPTY).overlapping(&boxes[0], |_| none += 1);
        assert_eq!(none, 0);
        // Every overlapping pair exactly once.
        let pairs = bvh.overlapping_pairs(None, |a, b| Some((a.min(b), a.max(b))));
        let brute: Vec<(usize, usize)> = (0..boxes.len())
            .flat_map(|a| (a + 1..boxes.len()).map(move |b| (a, b)))
            .filter(|&(a, b)| overlap(&boxes[a], &boxes[b]))
            .collect();
        assert_eq!(pairs, brute);
        let mut pairs = spatial_bvh.overlapping_pairs(None, |a, b| {
            let (a, b) = (order[a] as usize, order[b] as usize);
            Some((a.min(b), a.max(b)))
        });
        pairs.sort();
        assert_eq!(pairs, brute);
    }
}
