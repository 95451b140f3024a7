//! Stage 4, shells: connected components of the kept faces through shared edges, and
//! the orientation propagated over each.
//!
//! Faces are joined across every sheet's edge (a manifold edge, or a pair of faces at a
//! non-manifold edge: see `sheets.rs`) in a [`UnionFind`] and shells numbered by their
//! first face, so that two bodies touching along an edge are two shells. Then a
//! breadth-first walk from each shell's first face gives every face the winding that
//! agrees with it across those edges (`flip`); a face reached two ways that disagree
//! makes the shell *non-orientable*. A shell with a face alone at an edge (a boundary
//! edge, or the odd face out at a non-manifold one) is *open*.

use super::edges::{Edges, Neighbour};
use super::loops::Loops;
use crate::union_find::UnionFind;

/// The shells of the kept faces.
pub(super) struct Shells {
    /// Per face: its shell (`u32::MAX` for faces not kept).
    pub of_face: Vec<u32>,
    pub count: usize,
    /// Per face: reversed to agree with its shell's first face.
    pub flip: Vec<bool>,
    /// Per shell: orientation could be propagated consistently.
    pub orientable: Vec<bool>,
    /// Per shell: one of its faces is alone at an edge (a boundary edge, or the odd face
    /// out at a non-manifold edge).
    pub open: Vec<bool>,
}

/// The shells of the `kept` faces of `loops`, from their `edges` (each its uses) and
/// each corner's `neighbour` across its manifold edge.
pub(super) fn shells(
    loops: &Loops,
    kept: &[bool],
    edges: &Edges,
    neighbour: &[Neighbour],
) -> Shells {
    let faces = kept.len();
    let mut shells_of = UnionFind::new(faces);
    for g in edges.iter() {
        for pair in g.chunks_exact(2) {
            shells_of.join(pair[0].face(), pair[1].face());
        }
    }
    // Shells, numbered by their first face.
    let mut shell_of_face = vec![u32::MAX; faces];
    let mut shell_count = 0u32;
    let mut shell_of_root = vec![u32::MAX; faces];
    for f in (0..faces).filter(|&f| kept[f]) {
        let root = shells_of.find(f as u32) as usize;
        if shell_of_root[root] == u32::MAX {
            shell_of_root[root] = shell_count;
            shell_count += 1;
        }
        shell_of_face[f] = shell_of_root[root];
    }
    let shell_count = shell_count as usize;

    // Orientation propagation: flip[f] makes f agree with its shell's first face.
    let mut flip = vec![false; faces];
    let mut seen = vec![false; faces];
    let mut orientable = vec![true; shell_count];
    let mut queue = std::collections::VecDeque::new();
    for f in (0..faces).filter(|&f| kept[f]) {
        if seen[f] {
            continue;
        }
        seen[f] = true;
        queue.push_back(f as u32);
        while let Some(g) = queue.pop_front() {
            let across = neighbour[loops.face(g as usize)].iter();
            for (h, same) in across.filter(|&&n| n != Neighbour::NONE).map(|n| (n.face(), n.same()))
            {
                let want = flip[g as usize] ^ same;
                if !seen[h as usize] {
                    seen[h as usize] = true;
                    flip[h as usize] = want;
                    queue.push_back(h);
                } else if flip[h as usize] != want {
                    orientable[shell_of_face[f] as usize] = false;
                }
            }
        }
    }

    let mut open = vec![false; shell_count];
    for g in edges.iter().filter(|g| g.len() % 2 == 1) {
        let alone = g[g.len() - 1];
        open[shell_of_face[alone.face() as usize] as usize] = true;
    }
    Shells { of_face: shell_of_face, count: shell_count, flip, orientable, open }
}
