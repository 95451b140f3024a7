//! A body's edges and vertex graph from its welded triangles, in parallel and the same
//! at any thread count: each corner's edge grouped under its lower end (a counting
//! sort by vertex, [`Buckets::new_increasing`]), each group sorted by (upper end,
//! corner); edges numbered by lower end, then upper end, through a prefix sum of the
//! groups' edge counts. Every group then writes its own edges and corners, so the
//! numbering and every array are fixed by the triangles alone.

use crate::buckets::{for_each_range_mut, starts, Buckets, SharedItems};
use rayon::prelude::*;

/// What [`edge_table`] finds.
pub(super) struct EdgeTable {
    /// Per edge, its ends, the lower id first.
    pub edges: Vec<[u32; 2]>,
    /// Per triangle, its edges: edge i runs from corner i to corner i + 1.
    pub face_edges: Vec<[u32; 3]>,
    /// Per edge, the first triangle with area that has it (the first that has it when
    /// none has area).
    pub owner: Vec<u32>,
    /// The edges whose lower end is vertex v are `first_edge[v]..first_edge[v + 1]`.
    pub first_edge: Vec<u32>,
    /// Whether every edge is used as often in one direction as in the other.
    pub closed: bool,
}

/// The edges of `triangles` (ids below `vertices`; `flat[t]`: triangle t has no area).
pub(super) fn edge_table(triangles: &[[u32; 3]], flat: &[bool], vertices: usize) -> EdgeTable {
    let ends = |c: usize| {
        let (t, i) = (triangles[c / 3], c % 3);
        (t[i], t[(i + 1) % 3])
    };
    // (upper end, corner 3t + i) under the lower end; the corner's direction is read
    // back from the triangle.
    let by_low = Buckets::new_increasing(vertices, 3 * triangles.len(), |range| {
        range.map(move |c| {
            let (u, v) = ends(c);
            (u.min(v), (u.max(v), c as u32))
        })
    });
    // A group's runs of one upper end are its edges.
    let count: Vec<u32> = (0..vertices)
        .into_par_iter()
        .map(|v| by_low.get(v).chunk_by(|p, q| p.0 == q.0).count() as u32)
        .collect();
    let first_edge = starts(count.into_iter());
    let edge_count = first_edge[vertices] as usize;
    let mut edges = vec![[0u32; 2]; edge_count];
    let mut owner = vec![0u32; edge_count];
    let mut face_edges = vec![[0u32; 3]; triangles.len()];
    let (edges_out, owner_out) = (SharedItems::new(&mut edges), SharedItems::new(&mut owner));
    let corner_edge = SharedItems::new(face_edges.as_flattened_mut());
    let unbalanced: usize = (0..vertices)
        .into_par_iter()
        .with_min_len(1024)
        .map(|low| {
            let mut unbalanced = 0;
            let runs = by_low.get(low).chunk_by(|p, q| p.0 == q.0);
            for (id, run) in (first_edge[low] as usize..).zip(runs) {
                let mut balance = 0i32;
                let mut with_area = None;
                for &(_, corner) in run {
                    let (t, i) = ((corner / 3) as usize, (corner % 3) as usize);
                    balance += if triangles[t][i] as usize == low { 1 } else { -1 };
                    if with_area.is_none() && !flat[t] {
                        with_area = Some(t as u32);
                    }
                    // SAFETY: every corner is in exactly one group, each edge id in one
                    // group's range `first_edge[low]..first_edge[low + 1]`.
                    unsafe { corner_edge.write(corner as usize, id as u32) };
                }
                unsafe {
                    edges_out.write(id, [low as u32, run[0].0]);
                    owner_out.write(id, with_area.unwrap_or(run[0].1 / 3));
                }
                unbalanced += usize::from(balance != 0);
            }
            unbalanced
        })
        .sum();
    EdgeTable { edges, face_edges, owner, first_edge, closed: unbalanced == 0 }
}

/// The vertex graph as adjacency lists (neighbour, edge), by vertex, each list in
/// increasing edge order: first the edges where the vertex is the upper end (their
/// lower ends are below it, so their ids too), then those where it is the lower end
/// (`first_edge[v]..first_edge[v + 1]`).
pub(super) fn vertex_graph(edges: &[[u32; 2]], first_edge: &[u32]) -> (Vec<u32>, Vec<(u32, u32)>) {
    let vertices = first_edge.len() - 1;
    let by_high = Buckets::new_increasing(vertices, edges.len(), |range| {
        range.map(|id| (edges[id][1], id as u32))
    });
    let degree = |v: usize| by_high.get(v).len() as u32 + first_edge[v + 1] - first_edge[v];
    let start = starts((0..vertices).map(degree));
    let mut adjacent = vec![(0u32, 0u32); 2 * edges.len()];
    let range = |v: usize| start[v] as usize..start[v + 1] as usize;
    for_each_range_mut(&mut adjacent, vertices, &range, &|v, list| {
        let upper = by_high.get(v).iter().map(|&id| (edges[id as usize][0], id));
        let lower = (first_edge[v]..first_edge[v + 1]).map(|id| (edges[id as usize][1], id));
        list.iter_mut().zip(upper.chain(lower)).for_each(|(slot, item)| *slot = item);
    });
    (start, adjacent)
}
