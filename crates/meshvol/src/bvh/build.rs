//! Building the tree: the spatial order, the top-down split, the boxes bottom-up, and
//! refitting the boxes to moved items.

use super::*;

/// Groups of the spatial order's counting sort up to this size are sorted on the stack,
/// larger ones in a buffer of their own.
const SMALL_GROUP: usize = 64;

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
        // Each group sorted as (code, item) pairs, on the stack when it is small: looking
        // the codes up at each comparison read them scattered, 40 MB for 5M items.
        order.for_each_mut(|group| {
            if group.len() < 2 {
                return;
            }
            let (mut small, mut large) = ([(0u64, 0u32); SMALL_GROUP], Vec::new());
            let keyed = match group.len() {
                n if n <= SMALL_GROUP => &mut small[..n],
                n => {
                    large.resize(n, (0, 0));
                    &mut large[..]
                }
            };
            for (k, &i) in keyed.iter_mut().zip(group.iter()) {
                *k = (codes[i as usize], i);
            }
            keyed.sort_unstable();
            for (i, k) in group.iter_mut().zip(keyed.iter()) {
                *i = k.1;
            }
        });
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
    pub(super) fn bottom_up<T: Copy + Send + Sync>(
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
}
