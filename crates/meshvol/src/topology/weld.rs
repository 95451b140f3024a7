//! Welding: one vertex per distinct position.
//!
//! Corners are sorted by their coordinates' bit patterns (after snapping to a grid of
//! the weld tolerance, when one is given) and equal keys share a vertex. Sorting, not
//! hashing, because it runs in parallel and numbers the vertices in a fixed order
//! (by position) whatever the thread count.

use crate::Point;
use rayon::prelude::*;

/// The welded vertices and, for each corner, its vertex.
pub(crate) struct Welded {
    /// Vertex of each corner.
    pub corner_vertex: Vec<u32>,
    /// Position of each vertex (the first corner's, in key order).
    pub positions: Vec<Point>,
    /// Corners sorted by vertex: `order[vertex_start[v]..vertex_start[v + 1]]`.
    pub order: Vec<u32>,
    pub vertex_start: Vec<u32>,
}

fn key(p: Point, tolerance: Option<f64>) -> [u64; 3] {
    p.map(|x| {
        let x = match tolerance {
            Some(t) => (x / t).round(),
            None => x,
        };
        // +0.0 and −0.0 are the same position.
        (x + 0.0).to_bits()
    })
}

/// Welds `corners`: exactly equal positions, or positions that snap to the same point
/// of a grid with pitch `tolerance`.
pub(crate) fn weld(corners: &[Point], tolerance: Option<f64>) -> Welded {
    let keys: Vec<[u64; 3]> = corners.par_iter().map(|&p| key(p, tolerance)).collect();
    let mut order: Vec<u32> = (0..corners.len() as u32).collect();
    order.par_sort_unstable_by(|&a, &b| keys[a as usize].cmp(&keys[b as usize]).then(a.cmp(&b)));
    let mut corner_vertex = vec![0u32; corners.len()];
    let mut positions = Vec::new();
    let mut vertex_start = Vec::new();
    for (rank, &c) in order.iter().enumerate() {
        if rank == 0 || keys[c as usize] != keys[order[rank - 1] as usize] {
            positions.push(corners[c as usize]);
            vertex_start.push(rank as u32);
        }
        corner_vertex[c as usize] = positions.len() as u32 - 1;
    }
    vertex_start.push(order.len() as u32);
    Welded { corner_vertex, positions, order, vertex_start }
}
