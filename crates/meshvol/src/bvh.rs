//! A bounding-volume hierarchy over axis-aligned boxes, for "which boxes overlap this
//! one?" queries (self-intersections, overlapping shells, ray casting).
//!
//! Built top-down: split the items at the median of their box centres along the longest
//! axis of the node's box (`select_nth_unstable`, O(n) per level, so O(n log n)), until
//! a node holds at most [`LEAF_SIZE`] items. Queries walk the tree with an explicit
//! stack. Written here because the general crates (parry's Qbvh, `bvh`) bring their own
//! vector types and far more than these two queries need.

use crate::properties::Bounds;

/// Items per leaf.
const LEAF_SIZE: usize = 4;

#[derive(Clone, Debug)]
struct Node {
    bounds: Bounds,
    /// Leaf: items `start..start + count` of `order`; inner: `count == 0` and the children
    /// are nodes `start` and `start + 1`.
    start: u32,
    count: u32,
}

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
        let mut bvh = Bvh {
            nodes: Vec::new(),
            order: (0..boxes.len() as u32).collect(),
            leaf_boxes: Vec::new(),
        };
        if boxes.is_empty() {
            return bvh;
        }
        bvh.nodes.reserve(2 * boxes.len() / LEAF_SIZE + 1);
        bvh.nodes.push(Node { bounds: boxes[0], start: 0, count: 0 });
        // (node, item range) still to split
        let mut stack = vec![(0usize, 0usize, boxes.len())];
        while let Some((node, start, end)) = stack.pop() {
            let items = &mut bvh.order[start..end];
            let bounds =
                items.iter().fold(boxes[items[0] as usize], |b, &i| union(&b, &boxes[i as usize]));
            bvh.nodes[node].bounds = bounds;
            if end - start <= LEAF_SIZE {
                bvh.nodes[node].start = start as u32;
                bvh.nodes[node].count = (end - start) as u32;
                continue;
            }
            let size = bounds.size();
            let axis = (0..3).fold(0, |a, k| if size[k] > size[a] { k } else { a });
            let centre = |i: &u32| boxes[*i as usize].min[axis] + boxes[*i as usize].max[axis];
            let mid = (end - start) / 2;
            items.select_nth_unstable_by(mid, |a, b| centre(a).total_cmp(&centre(b)));
            let left = bvh.nodes.len();
            bvh.nodes.push(Node { bounds, start: 0, count: 0 });
            bvh.nodes.push(Node { bounds, start: 0, count: 0 });
            bvh.nodes[node].start = left as u32;
            stack.push((left, start, start + mid));
            stack.push((left + 1, start + mid, end));
        }
        bvh.leaf_boxes = bvh.order.iter().map(|&i| boxes[i as usize]).collect();
        bvh
    }

    /// Calls `visit(item)` for every item whose box overlaps `query` (closed boxes:
    /// touching counts).
    pub fn overlapping(&self, query: &Bounds, mut visit: impl FnMut(usize)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = Vec::with_capacity(64);
        stack.push(0usize);
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
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
                stack.push(node.start as usize);
                stack.push(node.start as usize + 1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
    }
}
