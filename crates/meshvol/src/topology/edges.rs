//! Stage 3, edges: the undirected edges of the kept faces and their uses, and the fans
//! around each vertex.
//!
//! Each kept corner is listed under its vertex (with its face); from that one table, per
//! vertex v: the uses of the edges (v, w) whose smaller vertex is v, and the fans of
//! corners around v, two corners being in one fan when their faces share an edge at v
//! (a [`UnionFind`] over the corners). A vertex in more than one fan is a bowtie:
//! *non-manifold*. Sorting v's uses by (w, corner) makes each edge's uses a run, in
//! face order; an edge with one use is *boundary*, two *manifold* (and *consistent*
//! when traversed in opposite directions), more *non-manifold* (its uses are then
//! paired into sheets by `sheets.rs`).
//!
//! This table is the check's peak of memory, so it is kept small: 8 bytes a corner by
//! vertex, 12 bytes an edge use (v is implied by the group a use is in).

use super::loops::Loops;
use super::weld::Welded;
use crate::buckets::{filled, for_each_range_mut, par_starts, Buckets, SharedItems};
use crate::union_find::UnionFind;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};

/// One use of an undirected edge (v, w), v < w, listed under v: by a face, from corner
/// `corner` to the next. Faces are numbered below 2³¹ ([`super::check`] refuses more),
/// so the direction rides in the top bit of the face.
#[derive(Clone, Copy)]
pub(super) struct EdgeUse {
    /// The larger vertex w.
    other: u32,
    pub corner: u32,
    face_and_direction: u32,
}

const TOP: u32 = 1 << 31;

impl EdgeUse {
    fn new(other: u32, face: u32, corner: u32, forward: bool) -> EdgeUse {
        EdgeUse { other, corner, face_and_direction: face | if forward { TOP } else { 0 } }
    }

    pub fn face(&self) -> u32 {
        self.face_and_direction & !TOP
    }

    /// Traversed from the smaller vertex to the larger.
    pub fn forward(&self) -> bool {
        self.face_and_direction & TOP != 0
    }
}

/// The edges: each a run of its uses, in order of (smaller vertex, larger vertex).
pub(super) struct Edges {
    uses: Vec<EdgeUse>,
    /// Edge i's uses are `uses[start[i]..start[i + 1]]`.
    start: Vec<u32>,
}

impl Edges {
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    pub fn get(&self, i: usize) -> &[EdgeUse] {
        &self.uses[self.start[i] as usize..self.start[i + 1] as usize]
    }

    pub fn par_iter(&self) -> impl ParallelIterator<Item = &[EdgeUse]> {
        (0..self.len()).into_par_iter().map(|i| self.get(i))
    }

    /// Runs `f` on every edge's uses, in parallel, letting it reorder them; returns the
    /// sum of what `f` returns.
    pub fn groups_mut(&mut self, f: impl Fn(&mut [EdgeUse]) -> usize + Sync) -> usize {
        let total = AtomicUsize::new(0);
        let start = &self.start;
        let range = |i: usize| start[i] as usize..start[i + 1] as usize;
        for_each_range_mut(&mut self.uses, start.len() - 1, &range, &|_, uses| {
            let n = f(uses);
            if n > 0 {
                total.fetch_add(n, Relaxed);
            }
        });
        total.into_inner()
    }
}

/// A kept corner, seen from its vertex. (The vertices before and after it in its face
/// are looked up when needed: storing them doubled this table, which is at the check's
/// peak of memory.)
/// Ordered by corner: the order corners are listed in (face by face).
#[derive(Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Around {
    corner: u32,
    face: u32,
}

/// How many vertices the kept faces use, and how many of those are non-manifold.
pub(super) struct VertexCounts {
    pub used: usize,
    pub non_manifold: usize,
}

/// The edges of the kept faces, each its uses in face order, and the vertex counts.
pub(super) fn edges(loops: &Loops, welded: &Welded, kept: &[bool]) -> (Edges, VertexCounts) {
    let faces = kept.len();
    let vid = |c: usize| welded.corner_vertex[c];
    // Each kept corner by its vertex, with its face: the edges and the fans around a
    // vertex are then read from one place.
    let vertex_count = welded.positions.len();
    let around = Buckets::new_increasing(vertex_count, faces, |range| {
        range.filter(|&f| kept[f]).flat_map(|f| {
            loops.face(f).map(move |c| (vid(c), Around { corner: c as u32, face: f as u32 }))
        })
    });
    // The vertices before and after a corner in its face.
    let sides = |k: &Around| {
        let (f, c) = (k.face as usize, k.corner as usize);
        (vid(loops.previous(f, c)), vid(loops.next(f, c)))
    };
    // Per vertex: the edge uses whose smaller vertex it is, and the fans of corners
    // around it, two corners being in one fan when their faces share an edge there. A
    // vertex in more than one fan (a bowtie) is non-manifold. Each end (w, i), the other
    // vertex w of corner i's edge, is one u64, w above i: sorted as numbers, in the
    // order of the pairs, at one comparison each (the pairs' sort was 5% of a check).
    let fans_and_uses = |(ends, fans): &mut (Vec<u64>, UnionFind), v: usize| {
        let corners = around.get(v);
        let end = |w: u32, i: usize| (u64::from(w) << 32) | i as u64;
        let other = |end: u64| (end >> 32) as usize;
        ends.clear();
        for (i, k) in corners.iter().enumerate() {
            let (previous, next) = sides(k);
            ends.extend([end(previous, i), end(next, i)]);
        }
        let uses = ends.iter().map(|&e| u32::from(other(e) > v)).sum::<u32>();
        ends.sort_unstable();
        fans.reset(corners.len());
        let mut count = corners.len() as u32;
        for w in ends.windows(2) {
            if other(w[0]) == other(w[1]) && fans.join(w[0] as u32, w[1] as u32) {
                count -= 1;
            }
        }
        (uses, count)
    };
    let per_vertex: Vec<(u32, u32)> = (0..vertex_count)
        .into_par_iter()
        .map_init(|| (Vec::new(), UnionFind::new(0)), fans_and_uses)
        .collect();
    let vertices = VertexCounts {
        used: per_vertex.par_iter().filter(|p| p.1 > 0).count(),
        non_manifold: per_vertex.par_iter().filter(|p| p.1 > 1).count(),
    };
    // Edge uses grouped by smaller vertex, then sorted by (larger vertex, corner):
    // corners number faces in order, so the uses of an edge come in face order.
    let use_start = par_starts(vertex_count, |v| per_vertex[v].0 as usize);
    drop(per_vertex);
    let unused = EdgeUse::new(0, 0, 0, false);
    let mut uses = filled(use_start[vertex_count], unused);
    let vertex_uses = |v: usize| use_start[v]..use_start[v + 1];
    for_each_range_mut(&mut uses, vertex_count, &vertex_uses, &|v, out| {
        let mut next = 0;
        for k in around.get(v) {
            let (f, c) = (k.face, k.corner);
            let (before, after) = sides(k);
            if after as usize > v {
                out[next] = EdgeUse::new(after, f, c, true);
                next += 1;
            }
            if before as usize > v {
                let corner = loops.previous(f as usize, c as usize) as u32;
                out[next] = EdgeUse::new(before, f, corner, false);
                next += 1;
            }
        }
        out.sort_unstable_by_key(|e| (e.other, e.corner));
    });
    drop(around);
    // Each edge is a run of equal `other` among its smaller vertex's uses: counted per
    // vertex, then each run's first use written in place. (Uses number below the
    // corners, which fit 32 bits.)
    let run_starts = |v: usize| {
        let group = &uses[vertex_uses(v)];
        (0..group.len()).filter(move |&i| i == 0 || group[i].other != group[i - 1].other)
    };
    let runs: Vec<u32> =
        (0..vertex_count).into_par_iter().map(|v| run_starts(v).count() as u32).collect();
    let first_edge = par_starts(vertex_count, |v| runs[v] as usize);
    drop(runs);
    let mut start = filled(first_edge[vertex_count] + 1, 0u32);
    let vertex_edges = |v: usize| first_edge[v]..first_edge[v + 1];
    let (start_of_edges, end) = start.split_at_mut(first_edge[vertex_count]);
    end[0] = uses.len() as u32;
    for_each_range_mut(start_of_edges, vertex_count, &vertex_edges, &|v, out| {
        for (at, i) in out.iter_mut().zip(run_starts(v)) {
            *at = (use_start[v] + i) as u32;
        }
    });
    (Edges { uses, start }, vertices)
}

/// What the edges say on their own: how many are boundary and non-manifold, and which
/// faces are wound against a neighbour.
pub(super) struct EdgeCounts {
    pub boundary: usize,
    pub non_manifold: usize,
    /// Every sheet's two faces at an edge (a manifold edge's two faces, or a pair at a
    /// non-manifold edge) traverse it in opposite directions.
    pub consistently_oriented: bool,
    /// Per face: wound the same way as a neighbour across a sheet's edge.
    pub face_inconsistent: Vec<bool>,
}

/// Counts the `edges` (each its uses) of `faces` faces.
pub(super) fn count(edges: &Edges, faces: usize) -> EdgeCounts {
    // Per edge: (boundary, non-manifold) counts, and the faces of sheets wound the same
    // way (rare), gathered in parallel; integer sums and a list in edge order.
    let (boundary, non_manifold) = edges
        .par_iter()
        .map(|g| match g.len() {
            1 => (1, 0),
            2 => (0, 0),
            _ => (0, 1),
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    // Each sheet's two faces (see `sheets.rs`): a manifold edge is one sheet.
    let against: Vec<u32> = edges
        .par_iter()
        .flat_map_iter(|g| {
            g.chunks_exact(2)
                .filter(|pair| pair[0].forward() == pair[1].forward())
                .flat_map(|pair| [pair[0].face(), pair[1].face()])
        })
        .collect();
    let mut face_inconsistent = vec![false; faces];
    for &f in &against {
        face_inconsistent[f as usize] = true;
    }
    EdgeCounts {
        boundary,
        non_manifold,
        consistently_oriented: against.is_empty(),
        face_inconsistent,
    }
}

/// A face across a manifold edge, and whether the two faces traverse the edge the same
/// way (in the top bit: faces number below 2³¹ − 1).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) struct Neighbour(u32);

impl Neighbour {
    /// At a corner that starts no manifold edge.
    pub const NONE: Neighbour = Neighbour(u32::MAX);

    fn new(face: u32, same: bool) -> Neighbour {
        Neighbour(face | if same { TOP } else { 0 })
    }

    pub fn face(self) -> u32 {
        self.0 & !TOP
    }

    pub fn same(self) -> bool {
        self.0 & TOP != 0
    }
}

/// Each face's neighbours across its sheets' edges (manifold edges, and pairs at
/// non-manifold edges), for orientation propagation: at the corner that starts the edge
/// in the face (so laid out like the corners, and found without sorting);
/// [`Neighbour::NONE`] elsewhere.
pub(super) fn neighbours(edges: &Edges, corners: usize) -> Vec<Neighbour> {
    let mut neighbour = filled(corners, Neighbour::NONE);
    let shared = SharedItems::new(&mut neighbour);
    edges.par_iter().filter(|g| g.len() >= 2).for_each(|g| {
        for pair in g.chunks_exact(2) {
            let same = pair[0].forward() == pair[1].forward();
            // SAFETY: every corner starts one edge use, which is in one group.
            unsafe {
                shared.write(pair[0].corner as usize, Neighbour::new(pair[1].face(), same));
                shared.write(pair[1].corner as usize, Neighbour::new(pair[0].face(), same));
            }
        }
    });
    neighbour
}
