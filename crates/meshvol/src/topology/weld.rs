//! Welding: one vertex per position.
//!
//! Exact welding sorts corners by their coordinates' bit patterns, and equal keys share a
//! vertex: sorting rather than hashing runs in parallel and numbers vertices in a fixed
//! order whatever the thread count.
//!
//! Welding with a tolerance t first welds exactly, then joins distinct positions whose
//! coordinates all differ by at most t (transitively: a chain of close points becomes
//! one vertex). Candidates come from a grid of cells of size t: two such points lie in
//! the same or neighbouring cells, so each position looks at 27 cells only.

use crate::Point;
use rayon::prelude::*;

/// The welded vertices and, for each corner, its vertex.
pub(crate) struct Welded {
    /// Vertex of each corner.
    pub corner_vertex: Vec<u32>,
    /// Position of each vertex (that of its first corner in key order).
    pub positions: Vec<Point>,
    /// Corners sorted by vertex: `order[vertex_start[v]..vertex_start[v + 1]]`.
    pub order: Vec<u32>,
    pub vertex_start: Vec<u32>,
}

/// Corners with equal `key`s become one vertex; vertices are numbered in key order.
fn group_by_key<K: Ord + Send + Sync>(
    corners: &[Point],
    key: impl Fn(usize) -> K + Sync,
) -> Welded {
    // (key, corner) pairs sorted directly: comparisons read contiguous memory.
    let mut keyed: Vec<(K, u32)> =
        (0..corners.len()).into_par_iter().map(|c| (key(c), c as u32)).collect();
    keyed.par_sort_unstable();
    let mut corner_vertex = vec![0u32; corners.len()];
    let mut positions = Vec::new();
    let mut vertex_start = Vec::new();
    for (rank, (k, c)) in keyed.iter().enumerate() {
        if rank == 0 || *k != keyed[rank - 1].0 {
            positions.push(corners[*c as usize]);
            vertex_start.push(rank as u32);
        }
        corner_vertex[*c as usize] = positions.len() as u32 - 1;
    }
    vertex_start.push(keyed.len() as u32);
    let order = keyed.into_iter().map(|(_, c)| c).collect();
    Welded { corner_vertex, positions, order, vertex_start }
}

/// Welds corners at exactly equal positions, or (with `tolerance`) at positions whose
/// coordinates differ by at most the tolerance.
pub(crate) fn weld(corners: &[Point], tolerance: Option<f64>) -> Welded {
    // +0.0 and −0.0 are the same position.
    let bits = |p: Point| p.map(|x| (x + 0.0).to_bits());
    let exact = group_by_key(corners, |c| bits(corners[c]));
    let Some(t) = tolerance.filter(|t| *t > 0.0) else { return exact };

    let points = &exact.positions;
    let cell = |p: Point| p.map(|x| (x / t).floor() as i64);
    let mut by_cell: Vec<([i64; 3], u32)> =
        points.iter().enumerate().map(|(i, &p)| (cell(p), i as u32)).collect();
    by_cell.par_sort_unstable();
    let mut parent: Vec<u32> = (0..points.len() as u32).collect();
    fn root(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    for (i, &p) in points.iter().enumerate() {
        let home = cell(p);
        for d in 0..27i64 {
            let step = [d % 3 - 1, (d / 3) % 3 - 1, d / 9 - 1];
            let c = [0, 1, 2].map(|k| home[k].saturating_add(step[k]));
            let start = by_cell.partition_point(|e| e.0 < c);
            for &(_, j) in by_cell[start..].iter().take_while(|e| e.0 == c) {
                let q = points[j as usize];
                if (j as usize) < i && (0..3).all(|k| (p[k] - q[k]).abs() <= t) {
                    let (a, b) = (root(&mut parent, i as u32), root(&mut parent, j));
                    // The smaller index is the root: the result does not depend on order.
                    parent[a.max(b) as usize] = a.min(b);
                }
            }
        }
    }
    let cluster: Vec<u32> = (0..points.len() as u32).map(|v| root(&mut parent, v)).collect();
    group_by_key(corners, |c| cluster[exact.corner_vertex[c] as usize])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welds_within_the_tolerance_across_cell_borders() {
        // 0.0 and −0.0 are one position; 1e-9 apart straddling a cell border still weld.
        let t = 1e-6;
        let corners =
            [[0.0, 0.0, 0.0], [-0.0, 0.0, 0.0], [t * 3.0 - 1e-9, 1.0, 1.0], [t * 3.0, 1.0, 1.0]];
        let exact = weld(&corners, None);
        assert_eq!(exact.positions.len(), 3);
        let w = weld(&corners, Some(t));
        assert_eq!(w.positions.len(), 2);
        assert_eq!(w.corner_vertex[2], w.corner_vertex[3]);
        // Farther than the tolerance: separate.
        let apart = weld(&[[0.0; 3], [2e-6, 0.0, 0.0]], Some(t));
        assert_eq!(apart.positions.len(), 2);
    }
}
