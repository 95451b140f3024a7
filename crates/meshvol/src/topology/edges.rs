//! Stage 3, edges: the undirected edges of the kept faces and their uses, and the fans
//! around each vertex.
//!
//! Each kept corner is listed under its vertex with the vertices before and after it in
//! its face; from that one table, per vertex v: the uses of the edges whose smaller
//! vertex is v (each edge (v, w) keyed v·2³² + w), and the fans of corners around v, two
//! corners being in one fan when their faces share an edge at v (a [`UnionFind`] over
//! the corners). A vertex in more than one fan is a bowtie: *non-manifold*. Sorting the
//! uses by (key, corner) makes each edge's uses a run, in face order; an edge with one
//! use is *boundary*, two *manifold* (and *consistent* when traversed in opposite
//! directions), more *non-manifold*.

use super::loops::Loops;
use super::weld::Welded;
use crate::buckets::{for_each_range_mut, Buckets, SharedItems};
use crate::union_find::UnionFind;
use rayon::prelude::*;

/// One use of an undirected edge: by face `face`, from corner `corner` to the next.
#[derive(Clone, Copy)]
pub(super) struct EdgeUse {
    pub key: u64,
    pub face: u32,
    pub corner: u32,
    /// Traversed from the smaller vertex to the larger.
    pub forward: bool,
}

/// A kept corner, seen from its vertex.
#[derive(Clone, Copy, Default)]
struct Around {
    corner: u32,
    face: u32,
    /// The vertices before and after it in its face.
    previous: u32,
    next: u32,
}

/// How many vertices the kept faces use, and how many of those are non-manifold.
pub(super) struct VertexCounts {
    pub used: usize,
    pub non_manifold: usize,
}

/// The uses of the kept faces' edges, sorted by (edge key, corner), and the vertex
/// counts.
pub(super) fn edge_uses(
    loops: &Loops,
    welded: &Welded,
    kept: &[bool],
) -> (Vec<EdgeUse>, VertexCounts) {
    let faces = kept.len();
    let vid = |c: usize| welded.corner_vertex[c];
    // Each kept corner by its vertex, with its face and the vertices before and after
    // it: the edges and the fans around a vertex are then read from one place.
    let vertex_count = welded.positions.len();
    let around = Buckets::new(vertex_count, faces, |range| {
        range.filter(|&f| kept[f]).flat_map(|f| {
            loops.face(f).map(move |c| {
                let (previous, next) = (vid(loops.previous(f, c)), vid(loops.next(f, c)));
                (vid(c), Around { corner: c as u32, face: f as u32, previous, next })
            })
        })
    });
    // Per vertex: the edge uses whose smaller vertex it is, and the fans of corners
    // around it, two corners being in one fan when their faces share an edge there. A
    // vertex in more than one fan (a bowtie) is non-manifold.
    let fans_and_uses = |(ends, fans): &mut (Vec<(u32, u32)>, UnionFind), v: usize| {
        let corners = around.get(v);
        let low = |w: u32| (w as usize > v) as u32;
        let uses = corners.iter().map(|k| low(k.previous) + low(k.next)).sum::<u32>();
        ends.clear();
        for (i, k) in corners.iter().enumerate() {
            ends.extend([(k.previous, i as u32), (k.next, i as u32)]);
        }
        ends.sort_unstable();
        fans.reset(corners.len());
        let mut count = corners.len() as u32;
        for w in ends.windows(2) {
            if w[0].0 == w[1].0 && fans.join(w[0].1, w[1].1) {
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
        used: per_vertex.iter().filter(|p| p.1 > 0).count(),
        non_manifold: per_vertex.iter().filter(|p| p.1 > 1).count(),
    };
    // Edge uses grouped by smaller vertex, then sorted by (larger vertex, corner):
    // corners number faces in order, so the uses of an edge come in face order.
    let mut use_start = Vec::with_capacity(vertex_count + 1);
    use_start.push(0);
    for &(uses, _) in &per_vertex {
        use_start.push(use_start[use_start.len() - 1] + uses as usize);
    }
    drop(per_vertex);
    let unused = EdgeUse { key: 0, face: 0, corner: 0, forward: false };
    let mut uses = vec![unused; use_start[vertex_count]];
    let vertex_uses = |v: usize| use_start[v]..use_start[v + 1];
    for_each_range_mut(&mut uses, vertex_count, &vertex_uses, &|v, out| {
        let mut next = 0;
        for k in around.get(v) {
            let (f, c) = (k.face, k.corner);
            if k.next as usize > v {
                let key = ((v as u64) << 32) | u64::from(k.next);
                out[next] = EdgeUse { key, face: f, corner: c, forward: true };
                next += 1;
            }
            if k.previous as usize > v {
                let key = ((v as u64) << 32) | u64::from(k.previous);
                let corner = loops.previous(f as usize, c as usize) as u32;
                out[next] = EdgeUse { key, face: f, corner, forward: false };
                next += 1;
            }
        }
        out.sort_unstable_by_key(|e| (e.key, e.corner));
    });
    (uses, vertices)
}

/// The uses of each edge (a run of equal keys in `uses`), found in parallel.
pub(super) fn edges(uses: &[EdgeUse]) -> Vec<&[EdgeUse]> {
    let group_start: Vec<usize> = (0..uses.len())
        .into_par_iter()
        .filter(|&i| i == 0 || uses[i].key != uses[i - 1].key)
        .chain(rayon::iter::once(uses.len()))
        .collect();
    group_start.par_windows(2).map(|w| &uses[w[0]..w[1]]).collect()
}

/// What the edges say on their own: how many are boundary and non-manifold, and which
/// faces are wound against a neighbour.
pub(super) struct EdgeCounts {
    pub boundary: usize,
    pub non_manifold: usize,
    /// Every manifold edge's two faces traverse it in opposite directions.
    pub consistently_oriented: bool,
    /// Per face: wound the same way as a neighbour across a manifold edge.
    pub face_inconsistent: Vec<bool>,
}

/// Counts the `edges` (each its uses) of `faces` faces.
pub(super) fn count(edges: &[&[EdgeUse]], faces: usize) -> EdgeCounts {
    let (mut boundary, mut non_manifold) = (0, 0);
    let mut consistently_oriented = true;
    let mut face_inconsistent = vec![false; faces];
    for g in edges {
        match g.len() {
            1 => boundary += 1,
            2 => {
                let same = g[0].forward == g[1].forward;
                if same {
                    consistently_oriented = false;
                    face_inconsistent[g[0].face as usize] = true;
                    face_inconsistent[g[1].face as usize] = true;
                }
            }
            _ => non_manifold += 1,
        }
    }
    EdgeCounts { boundary, non_manifold, consistently_oriented, face_inconsistent }
}

/// A corner that starts no manifold edge.
pub(super) const NO_NEIGHBOUR: (u32, bool) = (u32::MAX, false);

/// Each face's neighbours across manifold edges, and whether the two traverse the edge
/// the same way, for orientation propagation: at the corner that starts the edge in the
/// face (so laid out like the corners, and found without sorting); [`NO_NEIGHBOUR`]
/// elsewhere.
pub(super) fn neighbours(edges: &[&[EdgeUse]], corners: usize) -> Vec<(u32, bool)> {
    let mut neighbour = vec![NO_NEIGHBOUR; corners];
    let shared = SharedItems::new(&mut neighbour);
    edges.par_iter().filter(|g| g.len() == 2).for_each(|g| {
        let same = g[0].forward == g[1].forward;
        // SAFETY: every corner starts one edge use, which is in one group.
        unsafe {
            shared.write(g[0].corner as usize, (g[1].face, same));
            shared.write(g[1].corner as usize, (g[0].face, same));
        }
    });
    neighbour
}
