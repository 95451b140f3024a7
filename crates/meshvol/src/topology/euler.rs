//! Stage 8, Euler characteristic: χ = V − E + F per shell, and the genus (2 − χ)/2 of a
//! closed orientable one (a sphere 0, a torus 1).
//!
//! F counts the shell's kept faces, E its edges (an edge belongs to each shell that
//! has a sheet there), V its vertices: a vertex belongs to each shell one of whose kept
//! faces uses it, once (a vertex is shared by shells only at non-manifold points), in
//! whatever order the faces come.

use super::edges::Edges;
use super::loops::Loops;
use super::shells::fold_runs;
use super::shells::Shells;
use super::weld::Welded;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

/// One shell's counts.
pub(super) struct ShellCounts {
    pub faces: usize,
    pub euler_characteristic: i64,
}

/// The counts of each of `shells`, from the `kept` faces of `loops`, the `edges`
/// (each its uses) and the number of vertices kept faces use.
pub(super) fn per_shell(
    loops: &Loops,
    welded: &Welded,
    kept: &[bool],
    shells: &Shells,
    edges: &Edges,
    used_vertices: usize,
) -> Vec<ShellCounts> {
    if shells.count == 1 {
        // A lone shell has every kept face, every edge (each has a kept face's use)
        // and every used vertex: the whole surface's counts, without walking corners
        // and sheets (4% of a check of a 1M-triangle sphere).
        let faces = kept.par_iter().filter(|&&k| k).count();
        let euler_characteristic = used_vertices as i64 - edges.len() as i64 + faces as i64;
        return vec![ShellCounts { faces, euler_characteristic }];
    }
    let shell_of_face = &shells.of_face;
    let faces: Vec<usize> = shells.fold_faces(kept, |n, _| *n += 1, |n, m| *n += m);
    // An edge counts once in each shell that has a sheet there (a non-manifold edge
    // between two bodies is an edge of each). Integer counts, in parallel.
    let edges_in: Vec<usize> = {
        const CHUNK: usize = 1 << 14;
        let runs: Vec<Vec<(u32, usize)>> = (0..edges.len().div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let (mut runs, mut here) = (Vec::<(u32, usize)>::new(), Vec::new());
                for g in (c * CHUNK..((c + 1) * CHUNK).min(edges.len())).map(|i| edges.get(i)) {
                    here.clear();
                    here.extend(g.chunks(2).map(|sheet| shell_of_face[sheet[0].face() as usize]));
                    here.sort_unstable();
                    here.dedup();
                    for &s in &here {
                        match runs.last_mut() {
                            Some((last, n)) if *last == s => *n += 1,
                            _ => runs.push((s, 1)),
                        }
                    }
                }
                runs
            })
            .collect();
        let mut edges_in = vec![0usize; shells.count];
        for &(s, n) in runs.iter().flatten() {
            edges_in[s as usize] += n;
        }
        edges_in
    };
    let vertices = vertices_per_shell(loops, welded, kept, shells);
    (0..shells.count)
        .map(|s| ShellCounts {
            faces: faces[s],
            euler_characteristic: vertices[s] - edges_in[s] as i64 + faces[s] as i64,
        })
        .collect()
}

/// (2 − χ)/2 for a closed orientable shell.
pub(super) fn genus(closed: bool, orientable: bool, euler_characteristic: i64) -> Option<i64> {
    let chi = euler_characteristic;
    (closed && orientable && chi % 2 == 0).then_some((2 - chi) / 2)
}

/// Per shell: its vertices, each counted once per run of consecutive kept faces of the
/// shell that use it (faces in order). A vertex used by one shell only counts once
/// there: those are found in parallel (each vertex's shell settled by compare-and-swap),
/// and only the corners of vertices shared by shells are walked in order.
fn vertices_per_shell(loops: &Loops, welded: &Welded, kept: &[bool], shells: &Shells) -> Vec<i64> {
    const NONE: u32 = u32::MAX;
    const SHARED: u32 = u32::MAX - 1;
    let shell_of_face = &shells.of_face;
    let only: Vec<AtomicU32> =
        (0..welded.positions.len()).into_par_iter().map(|_| AtomicU32::new(NONE)).collect();
    (0..kept.len()).into_par_iter().filter(|&f| kept[f]).for_each(|f| {
        let s = shell_of_face[f];
        for c in loops.face(f) {
            let v = &only[welded.corner_vertex[c] as usize];
            let mut seen = v.load(Relaxed);
            while seen != s && seen != SHARED {
                let next = if seen == NONE { s } else { SHARED };
                match v.compare_exchange(seen, next, Relaxed, Relaxed) {
                    Ok(_) => break,
                    Err(now) => seen = now,
                }
            }
        }
    });
    let only: Vec<u32> = only.into_par_iter().map(AtomicU32::into_inner).collect();
    let key = |v: usize| (only[v] < SHARED).then_some(only[v]);
    let mut vertices: Vec<i64> =
        fold_runs(only.len(), shells.count, key, |n, _| *n += 1, |n, m| *n += m);
    // Shared vertices: each counts once in every shell that uses it.
    let mut shared: Vec<(u32, u32)> = (0..kept.len())
        .into_par_iter()
        .filter(|&f| kept[f])
        .flat_map_iter(|f| {
            let only = &only;
            loops.face(f).filter_map(move |c| {
                let v = welded.corner_vertex[c];
                (only[v as usize] == SHARED).then_some((v, shell_of_face[f]))
            })
        })
        .collect();
    // Each (vertex, shell) pair once, whatever order the faces come in.
    shared.par_sort_unstable();
    shared.dedup();
    for (_, s) in shared {
        vertices[s as usize] += 1;
    }
    vertices
}
