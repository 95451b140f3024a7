//! A bounding-volume hierarchy over axis-aligned boxes, for "which boxes overlap this
//! one?" queries (self-intersections, overlapping shells, ray casting).
//!
//! Built as a linear BVH: items sorted (in parallel) by the Morton code of their box
//! centres, so items close in space are close in the order; then ranges of that order
//! are halved until a node holds at most [`LEAF_SIZE`] items, and node boxes are
//! computed bottom-up. Queries walk the tree with an explicit stack. Written here because the general crates (parry's Qbvh, `bvh`) bring their own
//! vector types and far more than these two queries need.

use crate::properties::Bounds;
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

/// Items per leaf.
const LEAF_SIZE: usize = 4;

#[derive(Clone, Debug)]
struct Node {
    bounds: Bounds,
    /// Leaf: items `start..start + count` of `order`; inner: `count == 0` and the children
    /// are nodes `start` and `start + 1`.
    start: u32,
    count: u32,
    /// The positions (in `order`) of the items under this node: `begin..end`.
    begin: u32,
    end: u32,
}

/// Deeper than any tree built here (depth ≤ log₂ of the item count + 1).
const STACK: usize = 64;

/// A bounding-volume hierarchy over items identified by their index.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    /// `boxes[order[i]]`, stored in leaf order so a leaf's boxes are contiguous.
    leaf_boxes: Vec<Bounds>,
}

fn union(a: &Bounds, b: &Bounds) -> Bounds {
    Bounds {
        min: [0, 1, 2].map(|k| a.min[k].min(b.min[k])),
        max: [0, 1, 2].map(|k| a.max[k].max(b.max[k])),
    }
}

fn overlaps(a: &Bounds, b: &Bounds) -> bool {
    (0..3).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k])
}

impl Bvh {
    /// Builds the hierarchy over `boxes` (item i has box `boxes[i]`).
    pub fn new(boxes: &[Bounds]) -> Bvh {
        if boxes.is_empty() {
            return Bvh::default();
        }
        let centre = |b: &Bounds| [0, 1, 2].map(|k| 0.5 * (b.min[k] + b.max[k]));
        let all =
            boxes.iter().fold(Bounds { min: centre(&boxes[0]), max: centre(&boxes[0]) }, |a, b| {
                let c = centre(b);
                union(&a, &Bounds { min: c, max: c })
            });
        let size = all.size();
        let mut keyed: Vec<(u64, u32)> = boxes
            .par_iter()
            .enumerate()
            .map(|(i, b)| {
                let c = centre(b);
                let cell = |k: usize| {
                    let t = if size[k] > 0.0 { (c[k] - all.min[k]) / size[k] } else { 0.0 };
                    (t * 2097151.0) as u64 // 21 bits per axis
                };
                (morton(cell(0), cell(1), cell(2)), i as u32)
            })
            .collect();
        keyed.par_sort_unstable();
        let order: Vec<u32> = keyed.into_iter().map(|(_, i)| i).collect();

        // Top-down: halve ranges; children always come after their parent.
        let empty = Bounds { min: [f64::INFINITY; 3], max: [f64::NEG_INFINITY; 3] };
        let mut nodes =
            vec![Node { bounds: empty, start: 0, count: 0, begin: 0, end: order.len() as u32 }];
        let mut ranges = vec![(0usize, order.len())];
        let mut next = 0;
        while next < nodes.len() {
            let (start, end) = ranges[next];
            if end - start <= LEAF_SIZE {
                nodes[next].start = start as u32;
                nodes[next].count = (end - start) as u32;
            } else {
                let mid = start + (end - start) / 2;
                nodes[next].start = nodes.len() as u32;
                nodes.push(Node {
                    bounds: empty,
                    start: 0,
                    count: 0,
                    begin: start as u32,
                    end: mid as u32,
                });
                nodes.push(Node {
                    bounds: empty,
                    start: 0,
                    count: 0,
                    begin: mid as u32,
                    end: end as u32,
                });
                ranges.push((start, mid));
                ranges.push((mid, end));
            }
            next += 1;
        }
        // Bottom-up boxes.
        let leaf_boxes: Vec<Bounds> = order.iter().map(|&i| boxes[i as usize]).collect();
        for n in (0..nodes.len()).rev() {
            let node = &nodes[n];
            nodes[n].bounds = if node.count > 0 {
                let items = &leaf_boxes[node.start as usize..(node.start + node.count) as usize];
                items.iter().fold(empty, |a, b| union(&a, b))
            } else {
                union(&nodes[node.start as usize].bounds, &nodes[node.start as usize + 1].bounds)
            };
        }
        Bvh { nodes, order, leaf_boxes }
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
                let range = node.start as usize..(node.start + node.count) as usize;
                for (&i, b) in self.order[range.clone()].iter().zip(&self.leaf_boxes[range]) {
                    if overlaps(b, query) {
                        visit(i as usize);
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
        let mut found =
            if self.nodes.is_empty() { Vec::new() } else { self.pairs_under(0, 0, &test) };
        found.par_sort_unstable();
        found
    }

    fn pairs_under<T: Send>(
        &self,
        a: usize,
        b: usize,
        test: &(impl Fn(usize, usize) -> Option<T> + Sync),
    ) -> Vec<T> {
        let (na, nb) = (&self.nodes[a], &self.nodes[b]);
        if !overlaps(&na.bounds, &nb.bounds) {
            return Vec::new();
        }
        let items = |n: &Node| n.start as usize..(n.start + n.count) as usize;
        let size = |n: &Node| n.end - n.begin;
        match (na.count > 0, nb.count > 0) {
            (true, true) => {
                let mut found = Vec::new();
                for p in items(na) {
                    let from = if a == b { p + 1 } else { nb.start as usize };
                    for q in from..nb.start as usize + nb.count as usize {
                        if overlaps(&self.leaf_boxes[p], &self.leaf_boxes[q]) {
                            found.extend(test(self.order[p] as usize, self.order[q] as usize));
                        }
                    }
                }
                found
            }
            _ if a == b => {
                let (l, r) = (na.start as usize, na.start as usize + 1);
                let big = size(na) > 4096;
                let (mut x, (y, z)) = if big {
                    rayon::join(
                        || self.pairs_under(l, l, test),
                        || {
                            rayon::join(
                                || self.pairs_under(r, r, test),
                                || self.pairs_under(l, r, test),
                            )
                        },
                    )
                } else {
                    (
                        self.pairs_under(l, l, test),
                        (self.pairs_under(r, r, test), self.pairs_under(l, r, test)),
                    )
                };
                x.extend(y);
                x.extend(z);
                x
            }
            (leaf_a, _) => {
                // Split the inner node (the larger one when both are inner).
                let split_a = !leaf_a && (nb.count > 0 || size(na) >= size(nb));
                let (keep, split) = if split_a { (b, a) } else { (a, b) };
                let first = self.nodes[split].start as usize;
                let mut x = self.pairs_under(keep, first, test);
                x.extend(self.pairs_under(keep, first + 1, test));
                x
            }
        }
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
        let bvh = Bvh::new(&boxes);
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
        }
        let mut none = 0;
        Bvh::new(&[]).overlapping(&boxes[0], |_| none += 1);
        assert_eq!(none, 0);
        // Every overlapping pair exactly once.
        let pairs = bvh.overlapping_pairs(|a, b| Some((a.min(b), a.max(b))));
        let brute: Vec<(usize, usize)> = (0..boxes.len())
            .flat_map(|a| (a + 1..boxes.len()).map(move |b| (a, b)))
            .filter(|&(a, b)| overlaps(&boxes[a], &boxes[b]))
            .collect();
        assert_eq!(pairs, brute);
    }
}
