//! Stage 4, shells: connected components of the kept faces through shared edges, and
//! the orientation propagated over each.
//!
//! Faces are joined across every sheet's edge (a manifold edge, or a pair of faces at a
//! non-manifold edge: see `sheets.rs`) in a union–find that also keeps each face's
//! parity to its parent (whether the two are wound against each other as the sheets
//! ask), so that a face's parity to its root is its `flip`: the winding that agrees with
//! the shell's first face across those edges. Joins run in parallel (compare-and-swap
//! links, the smaller root always winning, so the components and their roots, each
//! shell's first face, do not depend on the order). A shell where some sheet's two
//! faces then disagree is *non-orientable*: no winding agrees across every edge. Where
//! a consistent winding exists it is unique given the first face's, so `flip` is the
//! same whatever the order of joins; in a non-orientable shell it depends on the order,
//! so there a breadth-first walk from the first face, in face and corner order, gives
//! the flips (as before joins ran in parallel). Shells are numbered by their first face,
//! so that two bodies touching along an edge are two shells. A shell with a face alone
//! at an edge (a boundary edge, or the odd face out at a non-manifold one) is *open*.

use super::edges::{neighbours, Edges, Neighbour};
use super::loops::Loops;
use crate::buckets::{filled, starts, SharedItems};
use rayon::prelude::*;
use std::sync::atomic::{
    AtomicU32,
    Ordering::{AcqRel, Relaxed},
};

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

/// The shells of the `kept` faces of `loops`, from their `edges` (each its uses).
pub(super) fn shells(loops: &Loops, kept: &[bool], edges: &Edges) -> Shells {
    let faces = kept.len();
    let links = ParityLinks::new(faces);
    // Across a sheet's edge, two faces run the edge the same way when one must turn.
    edges.par_iter().for_each(|g| {
        for pair in g.chunks_exact(2) {
            let same = pair[0].forward() == pair[1].forward();
            links.join(pair[0].face(), pair[1].face(), same);
        }
    });
    // Each face's root (its shell's first face: the smallest) and parity to it.
    let resolved: Vec<(u32, bool)> =
        (0..faces as u32).into_par_iter().map(|f| links.find(f)).collect();
    drop(links);
    let mut flip: Vec<bool> = resolved.par_iter().map(|&(_, parity)| parity).collect();

    // Shells, numbered by their first face: the kept faces that are their own roots,
    // counted in parallel blocks, then every face through its root.
    const BLOCK: usize = 1 << 16;
    let is_first = |f: usize| kept[f] && resolved[f].0 as usize == f;
    let blocks = faces.div_ceil(BLOCK);
    let block_range = |b: usize| b * BLOCK..((b + 1) * BLOCK).min(faces);
    let firsts: Vec<u32> = (0..blocks)
        .into_par_iter()
        .map(|b| block_range(b).filter(|&f| is_first(f)).count() as u32)
        .collect();
    let before = starts(firsts.into_iter());
    let shell_count = before[blocks] as usize;
    let mut shell_of_face = filled(faces, u32::MAX);
    shell_of_face.par_chunks_mut(BLOCK).enumerate().for_each(|(b, out)| {
        let mut next = before[b];
        for (f, s) in block_range(b).zip(out) {
            if is_first(f) {
                (*s, next) = (next, next + 1);
            }
        }
    });
    let shared = SharedItems::new(&mut shell_of_face);
    (0..faces).into_par_iter().for_each(|f| {
        let root = resolved[f].0 as usize;
        if kept[f] && root != f {
            // SAFETY: face f is written by this iteration only; its root, a first face,
            // was written in the pass before and is not written in this one.
            unsafe { shared.write(f, shared.read(root)) };
        }
    });
    drop(resolved);

    // Orientable unless some sheet's two faces disagree after propagation.
    let mut orientable = vec![true; shell_count];
    let disagree: Vec<u32> = edges
        .par_iter()
        .flat_map_iter(|g| {
            g.chunks_exact(2)
                .filter(|pair| {
                    let (a, b) = (pair[0].face() as usize, pair[1].face() as usize);
                    let same = pair[0].forward() == pair[1].forward();
                    flip[a] ^ flip[b] != same
                })
                .map(|pair| shell_of_face[pair[0].face() as usize])
        })
        .collect();
    for &s in &disagree {
        orientable[s as usize] = false;
    }
    if !disagree.is_empty() {
        // Non-orientable shells: their flips from a breadth-first walk, as documented.
        let neighbour = neighbours(edges, loops.corner_count());
        let mut seen = vec![false; faces];
        let first_face_of: Vec<usize> = {
            let mut first = vec![usize::MAX; shell_count];
            for f in (0..faces).filter(|&f| kept[f]) {
                let s = shell_of_face[f] as usize;
                if first[s] == usize::MAX {
                    first[s] = f;
                }
            }
            first
        };
        for s in (0..shell_count).filter(|&s| !orientable[s]) {
            walk(loops, &neighbour, first_face_of[s], &mut seen, &mut flip);
        }
    }

    let mut open = vec![false; shell_count];
    let alone: Vec<u32> = edges
        .par_iter()
        .filter(|g| g.len() % 2 == 1)
        .map(|g| shell_of_face[g[g.len() - 1].face() as usize])
        .collect();
    for &s in &alone {
        open[s as usize] = true;
    }
    Shells { of_face: shell_of_face, count: shell_count, flip, orientable, open }
}

impl Shells {
    /// Per shell: `add(&mut acc, f)` over its kept faces f, from `T::default()`. Faces
    /// are taken in fixed chunks in parallel, a chunk's faces of one shell in a row
    /// folded together, then the chunks' runs merged in order with `merge`: the same
    /// folds in the same order at any thread count.
    pub fn fold_faces<T: Default + Clone + Send>(
        &self,
        kept: &[bool],
        add: impl Fn(&mut T, usize) + Sync,
        merge: impl Fn(&mut T, &T),
    ) -> Vec<T> {
        fold_runs(kept.len(), self.count, |f| kept[f].then(|| self.of_face[f]), add, merge)
    }
}

/// Per key below `keys`: `add(&mut acc, i)` over the items i below `items` whose
/// `key_of(i)` is that key (`None`: no key), folded in fixed chunks in parallel (a
/// chunk's items of one key in a row together), then merged in chunk order.
pub(super) fn fold_runs<T: Default + Clone + Send>(
    items: usize,
    keys: usize,
    key_of: impl Fn(usize) -> Option<u32> + Sync,
    add: impl Fn(&mut T, usize) + Sync,
    merge: impl Fn(&mut T, &T),
) -> Vec<T> {
    const CHUNK: usize = 1 << 14;
    let runs: Vec<Vec<(u32, T)>> = (0..items.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut runs: Vec<(u32, T)> = Vec::new();
            for i in c * CHUNK..((c + 1) * CHUNK).min(items) {
                let Some(k) = key_of(i) else { continue };
                match runs.last_mut() {
                    Some((last, acc)) if *last == k => add(acc, i),
                    _ => {
                        let mut acc = T::default();
                        add(&mut acc, i);
                        runs.push((k, acc));
                    }
                }
            }
            runs
        })
        .collect();
    let mut out = vec![T::default(); keys];
    for (k, acc) in runs.iter().flatten() {
        merge(&mut out[*k as usize], acc);
    }
    out
}

/// Orientation propagation over the shell of face `first` by a breadth-first walk from
/// it: `flip[f]` makes f agree with `first` across the edge it was reached by.
fn walk(
    loops: &Loops,
    neighbour: &[Neighbour],
    first: usize,
    seen: &mut [bool],
    flip: &mut [bool],
) {
    let mut queue = std::collections::VecDeque::new();
    seen[first] = true;
    flip[first] = false;
    queue.push_back(first as u32);
    while let Some(g) = queue.pop_front() {
        let across = neighbour[loops.face(g as usize)].iter();
        for (h, same) in across.filter(|&&n| n != Neighbour::NONE).map(|n| (n.face(), n.same())) {
            if !seen[h as usize] {
                seen[h as usize] = true;
                flip[h as usize] = flip[g as usize] ^ same;
                queue.push_back(h);
            }
        }
    }
}

/// A union–find over faces for parallel joins, each face holding its parent and its
/// parity to it (the top bit; faces number below 2³¹ − 1): whether the two are wound
/// against each other. Every link, made by a join or shortened by path halving, holds
/// a parity the joins imply; links only ever point to smaller faces, so the walk ends
/// and each component's root is its smallest face.
struct ParityLinks(Vec<AtomicU32>);

const PARITY: u32 = 1 << 31;

impl ParityLinks {
    fn new(n: usize) -> Self {
        ParityLinks((0..n as u32).into_par_iter().map(AtomicU32::new).collect())
    }

    /// The root of `x` and the parity of `x` to it.
    fn find(&self, mut x: u32) -> (u32, bool) {
        let mut parity = false;
        loop {
            let link = self.0[x as usize].load(Relaxed);
            let (up, a) = (link & !PARITY, link & PARITY != 0);
            if up == x {
                return (x, parity);
            }
            let next = self.0[up as usize].load(Relaxed);
            let (top, b) = (next & !PARITY, next & PARITY != 0);
            if top != up {
                // Path halving: x now links to its grandparent, parities composed. A
                // failed swap only means another thread shortened it first.
                let halved = top | if a ^ b { PARITY } else { 0 };
                let _ = self.0[x as usize].compare_exchange(link, halved, Relaxed, Relaxed);
                parity ^= a ^ b;
                x = top;
            } else {
                parity ^= a;
                x = up;
            }
        }
    }

    /// Joins the components of `a` and `b`, asking that their parities differ by
    /// `differ`. (A component that cannot honour every request is non-orientable; the
    /// caller finds that afterwards.)
    fn join(&self, a: u32, b: u32, differ: bool) {
        loop {
            let ((ra, pa), (rb, pb)) = (self.find(a), self.find(b));
            if ra == rb {
                return;
            }
            let (low, high) = (ra.min(rb), ra.max(rb));
            let link = low | if pa ^ pb ^ differ { PARITY } else { 0 };
            // Only a root links, and only to a smaller face: the swap fails when `high`
            // stopped being a root meanwhile, and the join tries again.
            if self.0[high as usize].compare_exchange(high, link, AcqRel, Relaxed).is_ok() {
                return;
            }
        }
    }
}
