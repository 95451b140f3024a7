//! Which triangles of the existing surface and of the design overlap in plan: the
//! pairs the overlay clips, found in time near-linear in the triangles and the pairs.
//!
//! Pairs split by whether the two triangles share a corner (the same plan point):
//!
//! - **Sharing a corner**: decided by their sectors around it ([`super::sectors`]): a
//!   merge of two sorted lists per shared point, whatever the boxes do.
//! - **Apart**: candidates from [`Bvh`] queries, one triangle against a tree of the
//!   other surface's triangles. A query enters a node only when its box meets the
//!   query's, when the query triangle's edge lines do not leave the box wholly outside
//!   (exact `orient2d`: a thin triangle across a box's corner misses the box), and when
//!   not every triangle under the node shares a corner with the query (those are the
//!   first kind: a fan's slivers all meet near their apex). Leaves give the candidates,
//!   each decided exactly by separating edge lines.
//!
//! A query is only as cheap as the boxes in its tree are tight. A sliver's box can be
//! far larger than the sliver (one from a cone's apex to its rim at 45° has a box half
//! the cone's), and every triangle near the sliver's box would meet it. So triangles
//! are *fat* (box at most [`SLIVER`] times their area) or *slivers*, and each pair is
//! found by one query, from its thinner side into a tree that holds no slivers where it
//! can:
//!
//! | existing | design | found by |
//! |---|---|---|
//! | any | fat | the existing triangle, in the tree of fat design triangles |
//! | sliver | sliver | the existing triangle, in the tree of design slivers |
//! | fat | sliver | the design sliver, in the tree of fat existing triangles |
//!
//! A sliver then walks only the nodes of fat triangles along it, and a fat triangle
//! never meets the huge boxes of slivers. Two slivers apart are tried when their
//! boxes meet; slivers from two different points cross each other in a constant
//! fraction of those pairs (and slivers from one point are never tried: they share it).
//!
//! # Cost
//!
//! Measured with `meshvol cutfill A --design B --json` (whole process, 2 shared cores,
//! cones of radius 100 fanned from (0, 0) with jittered angles; the grid is a plane of
//! 20 000 triangles over the cone's box), against the bucket grid this replaced, which
//! paired every two triangles whose boxes met in a bucket:
//!
//! | A against B | pairs, about | before | now |
//! |---|---|---|---|
//! | fan 2000 / fan 10 000, one apex | 1.2·10⁴ | 144 s | 0.02–0.03 s |
//! | fan 20 000 / fan 100 000, one apex | 1.2·10⁵ | > 200 s (stopped) | 0.14–0.21 s |
//! | fan 20 000 / grid | 2·10⁶ | 31 s, 320 MB | 0.73–0.89 s, 70 MB |
//! | grid / fan 100 000 | 10⁷ | > 200 s (stopped) | 3.6–3.8 s, 110 MB |
//!
//! The last two are bound by their pairs (each sliver crosses a hundred grid triangles,
//! and each pair is a piece to clip and integrate); both runs that finished before gave the same bits now.
//!
//! The work is split into tasks (shared points, then chunks of query triangles) that
//! each list their pairs in a fixed order, so the overlay's sums have the same bits at
//! any thread count.

use super::overlaps::interiors_overlap;
use super::plan::{facet_box, Facet, PlanBox};
use super::sectors::{Corners, Sector};
use crate::bvh::{Bvh, NO_TAG};
use crate::vector::orient2d;
use crate::Bounds;
use std::ops::Range;

/// A triangle whose box is more than this many times its area is a sliver (a box is at
/// least twice its triangle, and exactly twice for a right triangle along the axes).
const SLIVER: f64 = 8.0;

/// Query triangles per parallel task.
const QUERIES_PER_TASK: usize = 1024;

fn is_sliver(f: &Facet) -> bool {
    let [a, b, c] = f.xy;
    let twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let [lo, hi] = facet_box(f);
    // A box or an area that is not a number makes a sliver too.
    let fat = (hi[0] - lo[0]) * (hi[1] - lo[1]) <= SLIVER * 0.5 * twice.abs();
    !fat
}

fn bounds(b: &PlanBox) -> Bounds {
    Bounds { min: [b[0][0], b[0][1], 0.0], max: [b[1][0], b[1][1], 0.0] }
}

/// Whether two triangles' corner tags share a point.
fn share(a: &[u32; 3], b: &[u32; 3]) -> bool {
    a.iter().any(|&t| t != NO_TAG && b.contains(&t))
}

/// Whether an edge line of counter-clockwise `t` has the box [lo, hi] wholly on its
/// outer side (or on it): then no triangle inside the box overlaps `t`.
fn misses_box(t: &[[f64; 2]; 3], lo: [f64; 2], hi: [f64; 2]) -> bool {
    let corners = [lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
    (0..3).any(|i| {
        let (p, q) = (t[i], t[(i + 1) % 3]);
        corners.iter().all(|&c| orient2d(p, q, c) <= 0.0)
    })
}

/// A tree over some triangles of one surface.
struct Tree {
    bvh: Bvh,
    /// The triangle (index into the surface's facets) of each item.
    items: Vec<u32>,
    /// Per node, the corners all its triangles share.
    shared: Vec<[u32; 3]>,
}

impl Tree {
    fn new(facets: &[Facet], members: impl Iterator<Item = usize>, tags: &[[u32; 3]]) -> Tree {
        let members: Vec<usize> = members.collect();
        let boxes: Vec<Bounds> = members.iter().map(|&f| bounds(&facet_box(&facets[f]))).collect();
        let (order, bvh) = Bvh::over_boxes(&boxes);
        let items: Vec<u32> = order.iter().map(|&i| members[i as usize] as u32).collect();
        let item_tags: Vec<[u32; 3]> = items.iter().map(|&f| tags[f as usize]).collect();
        let shared = bvh.node_tags(&item_tags);
        Tree { bvh, items, shared }
    }

    /// Calls `each(f)` for the triangles `f` of the tree that overlap `t` (corner tags
    /// `t_tags`) without sharing a corner with it; counts the candidates tried.
    fn overlapping(
        &self,
        t: &Facet,
        t_tags: &[u32; 3],
        facets: &[Facet],
        tags: &[[u32; 3]],
        tried: &mut usize,
        mut each: impl FnMut(usize),
    ) {
        let enter =
            |node: usize, lo, hi| !share(&self.shared[node], t_tags) && !misses_box(&t.xy, lo, hi);
        self.bvh.overlapping_where(&bounds(&facet_box(t)), enter, |item| {
            let f = self.items[item] as usize;
            if !share(&tags[f], t_tags) {
                *tried += 1;
                if interiors_overlap(&t.xy, &facets[f].xy) {
                    each(f);
                }
            }
        });
    }
}

/// One parallel task.
enum Task {
    /// Uses of shared points ([`Corners::tasks`]).
    Corners(Range<usize>),
    /// Existing triangles, each queried against the design.
    Existing(Range<usize>),
    /// Design slivers (indices into `Pairs::design_slivers`), each queried against the
    /// fat existing triangles.
    DesignSlivers(Range<usize>),
}

/// The overlapping pairs of two surfaces, task by task.
pub(crate) struct Pairs {
    corners: Corners,
    design_fat: Tree,
    design_thin: Tree,
    existing_fat: Tree,
    design_slivers: Vec<u32>,
    tasks: Vec<Task>,
}

impl Pairs {
    pub fn new(existing: &[Facet], design: &[Facet]) -> Pairs {
        let corners = Corners::new(existing, design);
        let slivers = |facets: &[Facet]| -> Vec<bool> { facets.iter().map(is_sliver).collect() };
        let (thin_e, thin_d) = (slivers(existing), slivers(design));
        let design_slivers: Vec<u32> =
            (0..design.len() as u32).filter(|&g| thin_d[g as usize]).collect();
        let tags_d = &corners.design;
        let design_fat = Tree::new(design, (0..design.len()).filter(|&g| !thin_d[g]), tags_d);
        let design_thin = Tree::new(design, design_slivers.iter().map(|&g| g as usize), tags_d);
        let tags_e = &corners.existing;
        let existing_fat = Tree::new(existing, (0..existing.len()).filter(|&e| !thin_e[e]), tags_e);
        let chunks = |n: usize| {
            (0..n.div_ceil(QUERIES_PER_TASK))
                .map(move |i| i * QUERIES_PER_TASK..((i + 1) * QUERIES_PER_TASK).min(n))
        };
        let mut tasks: Vec<Task> = corners.tasks().into_iter().map(Task::Corners).collect();
        tasks.extend(chunks(existing.len()).map(Task::Existing));
        tasks.extend(chunks(design_slivers.len()).map(Task::DesignSlivers));
        Pairs { corners, design_fat, design_thin, existing_fat, design_slivers, tasks }
    }

    pub fn task_count(&self) -> usize {
        self.tasks.len()
    }

    /// Calls `each(e, g)` for the overlapping pairs (indices of the existing and the
    /// design triangle) of task `task`, in a fixed order; counts the box candidates
    /// tried into `tried`.
    pub fn pairs(
        &self,
        task: usize,
        existing: &[Facet],
        design: &[Facet],
        tried: &mut usize,
        mut each: impl FnMut(usize, usize),
    ) {
        let (tags_e, tags_d) = (&self.corners.existing, &self.corners.design);
        match &self.tasks[task] {
            Task::Corners(uses) => {
                let mut scratch: Vec<Sector> = Vec::new();
                self.corners.pairs(uses.clone(), existing, design, &mut scratch, |e, g| {
                    *tried += 1;
                    each(e, g)
                });
            }
            Task::Existing(range) => {
                for e in range.clone() {
                    let (t, tags) = (&existing[e], &tags_e[e]);
                    self.design_fat.overlapping(t, tags, design, tags_d, tried, |g| each(e, g));
                    if is_sliver(t) {
                        self.design_thin
                            .overlapping(t, tags, design, tags_d, tried, |g| each(e, g));
                    }
                }
            }
            Task::DesignSlivers(range) => {
                for &g in &self.design_slivers[range.clone()] {
                    let (t, tags) = (&design[g as usize], &tags_d[g as usize]);
                    self.existing_fat
                        .overlapping(t, tags, existing, tags_e, tried, |e| each(e, g as usize));
                }
            }
        }
    }
}
