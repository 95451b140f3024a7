//! Pairs of items whose boxes overlap: within one tree, between two, or the first one.

use super::*;

impl Bvh {
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
    ///
    /// `prepare(i)` is what `test` needs of item i (i itself, if it needs it), made once
    /// for all of i's partners in a leaf: `test(&prepare(i), j)` (3.4 partners an item
    /// on that sphere, so the first triangle's plane is found once, not 3.4 times).
    pub fn overlapping_pairs<P, T: Ord + Send>(
        &self,
        tags: Option<&[[u32; 3]]>,
        prepare: impl Fn(usize) -> P + Sync,
        test: impl Fn(&P, usize) -> Option<T> + Sync,
    ) -> Vec<T> {
        let mut found = Vec::new();
        if !self.nodes.is_empty() {
            let tagging = tags.map(|tags| self.tagging(tags));
            let walk = Walk { tags: tagging.as_ref(), prepare: &prepare, test: &test };
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
    fn pairs_under<P, T: Send, G: Fn(usize) -> P + Sync, F: Fn(&P, usize) -> Option<T> + Sync>(
        &self,
        a: usize,
        b: usize,
        test: &Walk<'_, G, F>,
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
    fn pairs_in_thread<P, T, G: Fn(usize) -> P, F: Fn(&P, usize) -> Option<T>>(
        &self,
        a: usize,
        b: usize,
        test: &Walk<'_, G, F>,
        found: &mut Vec<T>,
    ) {
        let _: ControlFlow<()> = self.walk_pairs(a, b, test.tags, |i, partners| {
            let prepared = (test.prepare)(i);
            found.extend(partners.filter_map(|j| (test.test)(&prepared, j)));
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
        let found = self.walk_pairs(0, 0, tagging.as_ref(), |i, mut partners| {
            match partners.find(|&j| test(i, j)) {
                Some(j) => ControlFlow::Break((i, j)),
                None => ControlFlow::Continue(()),
            }
        });
        match found {
            ControlFlow::Break(pair) => Some(pair),
            ControlFlow::Continue(()) => None,
        }
    }

    /// Visits the overlapping pairs with one item under node `a` and the other under
    /// node `b` (each pair once when `a == b`), but no pair sharing one of `tags`,
    /// until `visit` breaks: `visit(i, partners)` with an item i and its partners in
    /// a leaf (at least one).
    fn walk_pairs<B>(
        &self,
        a: usize,
        b: usize,
        tags: Option<&Tagging>,
        mut visit: impl FnMut(usize, Lanes) -> ControlFlow<B>,
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
        visit: &mut impl FnMut(usize, Lanes) -> ControlFlow<B>,
    ) -> ControlFlow<B> {
        let (a, b) = (&self.leaves[na.start as usize], &self.leaves[nb.start as usize]);
        // Only items that reach the other leaf's box can be in a pair.
        let reaching = a.overlapping(&nb.bounds) & na.lanes();
        for (i, item) in Lanes::of(reaching, 0).map(|i| (i, na.begin as usize + i)) {
            let mut partners = b.overlapping(&a.get(i)) & nb.lanes();
            if same {
                partners &= !((2 << i) - 1); // later items only: each pair once
            }
            if partners == 0 {
                continue;
            }
            if let Some(t) = tags {
                partners &= !t.leaves[nb.start as usize].sharing(&t.items[item]);
                if partners == 0 {
                    continue;
                }
            }
            visit(item, Lanes::of(partners, nb.begin as usize))?;
        }
        ControlFlow::Continue(())
    }

    fn collect_pairs<P, T: Send, G: Fn(usize) -> P + Sync, F: Fn(&P, usize) -> Option<T> + Sync>(
        &self,
        a: usize,
        b: usize,
        test: &Walk<'_, G, F>,
    ) -> Vec<T> {
        let mut found = Vec::new();
        self.pairs_under(a, b, test, &mut found);
        found
    }
}
