//! One box against the tree: the items whose boxes overlap it.

use super::*;

impl Bvh {
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
                Lanes::of(hits, node.begin as usize).for_each(&mut visit);
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
}
