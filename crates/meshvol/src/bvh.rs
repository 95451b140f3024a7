//! A bounding-volume hierarchy over axis-aligned boxes, for "which boxes overlap this
//! one?" queries (self-intersections, overlapping shells, ray casting).
//!
//! Built as a linear BVH: the caller puts its items in [`Bvh::spatial_order`] (sorted
//! by the Morton code of their box centres, so items close in space are close in the
//! order, and so is the caller's data about them); ranges of that order are halved
//! until a node holds at most [`LEAF_SIZE`] items, and node boxes are computed
//! bottom-up. Queries walk the tree with an explicit stack; pair searches walk two.
//! Written here because the general crates (parry's Qbvh, `bvh`) bring their own
//! vector types and far more than these two queries need.

use crate::properties::Bounds;
use crate::Point;
use rayon::prelude::*;

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

/// Nodes with more items than this split their pair searches across threads.
const PARALLEL_ITEMS: u32 = 4096;

/// Items per leaf.
const LEAF_SIZE: usize = 8;

#[derive(Clone, Debug)]
struct Node {
    bounds: Bounds,
    /// Leaf: items `start..start + count`; inner: `count == 0` and the children are
    /// nodes `start` and `start + 1`.
    start: u32,
    count: u32,
    /// The items under this node: `begin..end`.
    begin: u32,
    end: u32,
}

/// Deeper than any tree built here (depth ≤ log₂ of the item count + 1).
const STACK: usize = 64;

/// A bounding-volume hierarchy over items identified by their index.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    boxes: Vec<Bounds>,
}

/// Whether closed boxes `a` and `b` overlap. All six comparisons, combined without
/// short-circuiting: the outcome is unpredictable, and one branch mispredicts less
/// than six (this test is most of a pair search's time).
#[inline(always)]
fn overlaps(a: &Bounds, b: &Bounds) -> bool {
    (a.min[0] <= b.max[0])
        & (b.min[0] <= a.max[0])
        & (a.min[1] <= b.max[1])
        & (b.min[1] <= a.max[1])
        & (a.min[2] <= b.max[2])
        & (b.min[2] <= a.max[2])
}

impl Bvh {
    /// The order of items at `centres` that puts items close in space close together:
    /// by the Morton code of their centres. Items given to [`Bvh::new`] in this order
    /// make a tight tree (and data stored in this order is read nearly sequentially).
    pub fn spatial_order(centres: &[Point]) -> Vec<u32> {
        let mut frame = Bounds::EMPTY;
        centres.iter().for_each(|&c| frame.include(c));
        let size = frame.size();
        let code = |i: usize| {
            let c = centres[i];
            let cell = |k: usize| {
                let t = if size[k] > 0.0 { (c[k] - frame.min[k]) / size[k] } else { 0.0 };
                (t * 2097151.0) as u64 // 21 bits per axis
            };
            morton(cell(0), cell(1), cell(2))
        };
        let mut keyed: Vec<(u64, u32)> =
            (0..centres.len()).into_par_iter().map(|i| (code(i), i as u32)).collect();
        keyed.par_sort_unstable();
        keyed.into_iter().map(|(_, i)| i).collect()
    }

    /// Builds the hierarchy over `boxes` (item i has box `boxes[i]`), grouping
    /// consecutive items: pass them in [`Bvh::spatial_order`].
    pub fn new(boxes: Vec<Bounds>) -> Bvh {
        if boxes.is_empty() {
            return Bvh::default();
        }
        // Top-down: halve ranges; children always come after their parent.
        let node = |begin: usize, end: usize| Node {
            bounds: Bounds::EMPTY,
            start: 0,
            count: 0,
            begin: begin as u32,
            end: end as u32,
        };
        let mut nodes = Vec::with_capacity(2 * boxes.len().div_ceil(LEAF_SIZE));
        nodes.push(node(0, boxes.len()));
        let mut next = 0;
        while next < nodes.len() {
            let (start, end) = (nodes[next].begin as usize, nodes[next].end as usize);
            if end - start <= LEAF_SIZE {
                nodes[next].start = start as u32;
                nodes[next].count = (end - start) as u32;
            } else {
                let mid = start + (end - start) / 2;
                nodes[next].start = nodes.len() as u32;
                nodes.push(node(start, mid));
                nodes.push(node(mid, end));
            }
            next += 1;
        }
        // Bottom-up boxes.
        for n in (0..nodes.len()).rev() {
            let node = &nodes[n];
            let mut bounds = Bounds::EMPTY;
            if node.count > 0 {
                let items = &boxes[node.start as usize..(node.start + node.count) as usize];
                items.iter().for_each(|b| bounds.merge(b));
            } else {
                bounds = nodes[node.start as usize].bounds;
                bounds.merge(&nodes[node.start as usize + 1].bounds);
            }
            nodes[n].bounds = bounds;
        }
        Bvh { nodes, boxes }
    }

    /// Calls `visit(item)` for every item whose box overlaps `query` (closed boxes:
    /// touching counts).
    pub fn overlapping(&self, query: &Bounds, mut visit: impl FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; STACK];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if !overlaps(&node.bounds, query) {
                continue;
            }
            if node.count > 0 {
                for i in node.start as usize..(node.start + node.count) as usize {
                    if overlaps(&self.boxes[i], query) {
                        visit(i);
                    }
                }
            } else {
                stack[top] = node.start;
                stack[top + 1] = node.start + 1;
                top += 2;
            }
        }
    }

    /// Every unordered pair of distinct items whose boxes overlap, passed to `test`;
    /// returns what `test` kept, sorted.
    ///
    /// A dual-tree traversal: pairs of nodes whose boxes overlap are split (the larger
    /// node first) down to pairs of leaves, so the work is proportional to the pairs of
    /// nearby nodes rather than a full query per item; the top levels run in parallel.
    pub fn overlapping_pairs<T: Ord + Send>(
        &self,
        test: impl Fn(usize, usize) -> Option<T> + Sync,
    ) -> Vec<T> {
        let mut found = Vec::new();
        if !self.nodes.is_empty() {
            self.pairs_under(0, 0, &test, &mut found);
        }
        found.par_sort_unstable();
        found
    }

    /// Adds to `found` what `test` keeps of the overlapping pairs with one item under
    /// node `a` and the other under node `b` (each pair once when `a == b`). Splits
    /// big nodes across threads, then walks small ones with [`Bvh::pairs_in_thread`].
    fn pairs_under<T: Send>(
        &self,
        a: usize,
        b: usize,
        test: &(impl Fn(usize, usize) -> Option<T> + Sync),
        found: &mut Vec<T>,
    ) {
        let (na, nb) = (&self.nodes[a], &self.nodes[b]);
        if !overlaps(&na.bounds, &nb.bounds) {
            return;
        }
        if (na.end - na.begin).max(nb.end - nb.begin) <= PARALLEL_ITEMS {
            return self.pairs_in_thread(a, b, test, found);
        }
        let (x, y) = if a == b {
            let (l, r) = (na.start as usize, na.start as usize + 1);
            let (mut x, y) =
                rayon::join(|| self.collect_pairs(l, l, test), || self.collect_pairs(r, r, test));
            x.extend(self.collect_pairs(l, r, test));
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
    fn pairs_in_thread<T>(
        &self,
        a: usize,
        b: usize,
        test: &impl Fn(usize, usize) -> Option<T>,
        found: &mut Vec<T>,
    ) {
        // Each step pushes at most 3 pairs and descends a level: a few times the depth.
        let mut stack: Vec<(u32, u32)> = Vec::with_capacity(4 * STACK);
        stack.push((a as u32, b as u32));
        while let Some((a, b)) = stack.pop() {
            let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
            if !overlaps(&na.bounds, &nb.bounds) {
                continue;
            }
            if na.count > 0 && nb.count > 0 {
                self.leaf_pairs(na, nb, a == b, test, found);
            } else if a == b {
                let (l, r) = (na.start, na.start + 1);
                stack.extend([(l, r), (r, r), (l, l)]);
            } else {
                let (keep, split) = self.split(a as usize, b as usize);
                let first = self.nodes[split].start;
                stack.extend([(keep as u32, first + 1), (keep as u32, first)]);
            }
        }
    }

    /// The pairs of two leaves (of one leaf with itself, when `same`).
    #[inline]
    fn leaf_pairs<T>(
        &self,
        na: &Node,
        nb: &Node,
        same: bool,
        test: &impl Fn(usize, usize) -> Option<T>,
        found: &mut Vec<T>,
    ) {
        // Only items that reach the other leaf's box can be in a pair.
        let reaching = |n: &Node, other: &Bounds| {
            let mut items = [0u32; LEAF_SIZE];
            let mut len = 0;
            for p in n.start..n.start + n.count {
                items[len] = p;
                len += overlaps(&self.boxes[p as usize], other) as usize;
            }
            (items, len)
        };
        let (pa, la) = reaching(na, &nb.bounds);
        let (pb, lb) = if same { (pa, la) } else { reaching(nb, &na.bounds) };
        for (i, &p) in pa[..la].iter().enumerate() {
            let from = if same { i + 1 } else { 0 };
            for &q in &pb[from..lb] {
                if overlaps(&self.boxes[p as usize], &self.boxes[q as usize]) {
                    found.extend(test(p as usize, q as usize));
                }
            }
        }
    }

    fn collect_pairs<T: Send>(
        &self,
        a: usize,
        b: usize,
        test: &(impl Fn(usize, usize) -> Option<T> + Sync),
    ) -> Vec<T> {
        let mut found = Vec::new();
        self.pairs_under(a, b, test, &mut found);
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn morton_interleaves_bits() {
        assert_eq!(morton(1, 0, 0), 1);
        assert_eq!(morton(0, 1, 0), 2);
        assert_eq!(morton(0, 0, 1), 4);
        assert_eq!(morton(3, 0, 0), 0b1001);
        assert_eq!(morton(0x1f_ffff, 0x1f_ffff, 0x1f_ffff), (1u64 << 63) - 1);
    }

    #[test]
    fn finds_exactly_the_overlapping_boxes() {
        // A 20×20 lattice of unit boxes with gaps; compare with brute force.
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
        let bvh = Bvh::new(boxes.clone());
        let spatial_bvh = Bvh::new(spatial.clone());
        for q in [
            Bounds { min: [0.5, 0.5, 0.5], max: [3.2, 2.0, 0.6] },
            Bounds { min: [-5.0; 3], max: [-4.0; 3] },
            Bounds { min: [1.0, 1.0, 1.0], max: [1.5, 1.5, 2.0] }, // touches a corner
        ] {
            let mut found = vec![];
            bvh.overlapping(&q, |i| found.push(i));
            found.sort();
            let brute: Vec<usize> = (0..boxes.len()).filter(|&i| overlaps(&boxes[i], &q)).collect();
            assert_eq!(found, brute);
            let mut found: Vec<usize> = vec![];
            spatial_bvh.overlapping(&q, |i| found.push(order[i] as usize));
            found.sort();
            assert_eq!(found, brute);
        }
        let mut none = 0;
        Bvh::new(vec![]).overlapping(&boxes[0], |_| none += 1);
        assert_eq!(none, 0);
        // Every overlapping pair exactly once.
        let pairs = bvh.overlapping_pairs(|a, b| Some((a.min(b), a.max(b))));
        let brute: Vec<(usize, usize)> = (0..boxes.len())
            .flat_map(|a| (a + 1..boxes.len()).map(move |b| (a, b)))
            .filter(|&(a, b)| overlaps(&boxes[a], &boxes[b]))
            .collect();
        assert_eq!(pairs, brute);
        let mut pairs = spatial_bvh.overlapping_pairs(|a, b| {
            let (a, b) = (order[a] as usize, order[b] as usize);
            Some((a.min(b), a.max(b)))
        });
        pairs.sort();
        assert_eq!(pairs, brute);
    }
}
