//! Stage 2, faces: which faces are collapsed, flat or duplicates, and so which ones the
//! later stages see.
//!
//! A face with a repeated welded vertex is *collapsed*. One with distinct vertices but
//! zero vector area Σ (cᵢ − c₀) × (cᵢ₊₁ − c₀) is *flat*: it keeps its edges but has no
//! interior. Faces with the same vertex set are *duplicates*: grouped by their smallest
//! vertex and sorted by (sorted vertex list, face), each vertex set is a run in face
//! order; in a run, copies wound opposite ways cancel in pairs (a *double wall*) and of
//! the rest the first stays.

use super::loops::Loops;
use super::weld::Welded;
use crate::buckets::{for_each_range_mut, Buckets, SharedItems};
use rayon::prelude::*;

/// Groups of faces (by smallest vertex) settled per parallel task.
const GROUPS_PER_TASK: usize = 4096;

/// Per face: what stage 2 found.
pub(super) struct FaceClasses {
    /// A repeated welded vertex: left out of everything.
    pub collapsed: Vec<bool>,
    /// Distinct vertices, zero vector area.
    pub flat: Vec<bool>,
    /// Dropped for having the vertex set of another face.
    pub duplicate: Vec<bool>,
    /// Dropped in an opposite pair (also `duplicate`).
    pub double_wall: Vec<bool>,
    /// Neither collapsed nor duplicate: the faces of edges, shells and the solid.
    pub kept: Vec<bool>,
    /// Kept and not flat: the faces with an interior, which the crossing search and
    /// nesting rays see.
    pub spatial: Vec<bool>,
}

/// A face's welded vertices, sorted: faces with the same vertex set have equal ones.
trait VertexSet: Ord + Copy + Send + Sync {
    /// The smallest vertex.
    fn first(&self) -> u32;
    /// Whether a vertex comes twice (the face is collapsed).
    fn repeated(&self) -> bool;
}

/// A triangle's three vertices, sorted in registers: no copy of the corners' vertices
/// to sort in place, and comparisons of three numbers rather than of slices (on a
/// 5M-triangle sphere this stage took 0.15-0.19 s, copying and comparing slices).
impl VertexSet for [u32; 3] {
    fn first(&self) -> u32 {
        self[0]
    }

    fn repeated(&self) -> bool {
        self[0] == self[1] || self[1] == self[2]
    }
}

/// A polygon's vertices, sorted in a copy of the corners' vertices.
impl VertexSet for &[u32] {
    fn first(&self) -> u32 {
        self[0]
    }

    fn repeated(&self) -> bool {
        self.windows(2).any(|w| w[0] == w[1])
    }
}

/// Classifies the faces `loops`, welded as `welded`.
pub(super) fn classify(loops: &Loops, welded: &Welded) -> FaceClasses {
    let faces = loops.face_count();
    if loops.corner_count() == 3 * faces {
        let ids = welded.corner_vertex.as_chunks::<3>().0;
        let sorted = |f: u32| {
            let [a, b, c] = ids[f as usize];
            let (low, high) = (a.min(b), a.max(b));
            [low.min(c), high.min(low.max(c)), high.max(c)]
        };
        return classify_sets(loops, welded, sorted);
    }
    // Each face's welded vertices sorted: a repeat is two equal neighbours (O(k log k)
    // for a k-gon; comparing every pair cost 35 s for a 3·10⁵-gon).
    let mut sorted_ids: Vec<u32> = welded.corner_vertex.par_iter().copied().collect();
    for_each_range_mut(&mut sorted_ids, faces, &|f| loops.face(f), &|_, ids| ids.sort_unstable());
    classify_sets(loops, welded, |f: u32| &sorted_ids[loops.face(f as usize)])
}

/// [`classify`], each face's vertex set given by `set_of`.
fn classify_sets<K: VertexSet>(
    loops: &Loops,
    welded: &Welded,
    set_of: impl Fn(u32) -> K + Sync,
) -> FaceClasses {
    let faces = loops.face_count();
    // Collapsed faces (a repeated welded vertex) are left out of everything; flat faces
    // (distinct vertices, zero vector area: slivers) stay in the edge table but have no
    // interior, so they stay out of the spatial triangles.
    let (collapsed, flat): (Vec<bool>, Vec<bool>) = (0..faces)
        .into_par_iter()
        .map(|f| {
            let repeated = set_of(f as u32).repeated();
            (repeated, !repeated && loops.doubled_vector_area(f, welded) == [0.0; 3])
        })
        .unzip();
    // Duplicates: the same vertex set as another face. Faces grouped by their smallest
    // vertex, each group sorted by (sorted vertex list, face): faces with one vertex set
    // form a run, in face order.
    let mut by_vertices = Buckets::new_increasing(welded.positions.len(), faces, |range| {
        range.filter(|&f| !collapsed[f]).map(|f| (set_of(f as u32).first(), f as u32))
    });
    by_vertices.for_each_mut(|group| {
        if group.len() > 1 {
            group.sort_unstable_by(|&a, &b| set_of(a).cmp(&set_of(b)).then(a.cmp(&b)))
        }
    });
    // A vertex set's copies share their smallest vertex, so each run lies in one group:
    // groups are settled in parallel, each face (in one group) written once.
    let mut duplicate = vec![false; faces];
    let mut double_wall = vec![false; faces];
    let (duplicate_out, double_wall_out) =
        (SharedItems::new(&mut duplicate), SharedItems::new(&mut double_wall));
    let settle = |items: &[u32]| {
        let mut i = 0;
        while i < items.len() {
            let run = items[i..].iter().take_while(|&&g| set_of(g) == set_of(items[i])).count();
            if run > 1 {
                let corners = |f: u32| &welded.corner_vertex[loops.face(f as usize)];
                let first = corners(items[i]);
                let (same, opposite): (Vec<u32>, Vec<u32>) = items[i..i + run]
                    .iter()
                    .partition(|&&g| !opposite_direction(first, corners(g)));
                // Opposite copies cancel in pairs (an internal double wall); of the rest,
                // one copy stays.
                let pairs = same.len().min(opposite.len());
                for &g in same[..pairs].iter().chain(&opposite[..pairs]) {
                    // SAFETY: each face is in one group, settled by one task.
                    unsafe {
                        double_wall_out.write(g as usize, true);
                        duplicate_out.write(g as usize, true);
                    }
                }
                let rest = if same.len() > pairs { &same[pairs..] } else { &opposite[pairs..] };
                for &g in rest.iter().skip(1) {
                    // SAFETY: as above.
                    unsafe { duplicate_out.write(g as usize, true) };
                }
            }
            i += run;
        }
    };
    let groups = by_vertices.start.len() - 1;
    (0..groups.div_ceil(GROUPS_PER_TASK)).into_par_iter().for_each(|t| {
        for k in t * GROUPS_PER_TASK..((t + 1) * GROUPS_PER_TASK).min(groups) {
            let group = by_vertices.get(k);
            if group.len() > 1 {
                settle(group);
            }
        }
    });
    drop(by_vertices);
    let kept: Vec<bool> =
        (0..faces).into_par_iter().map(|f| !collapsed[f] && !duplicate[f]).collect();
    // The faces with an interior: those the crossing search and nesting rays see.
    let spatial: Vec<bool> = (0..faces).into_par_iter().map(|f| kept[f] && !flat[f]).collect();
    FaceClasses { collapsed, flat, duplicate, double_wall, kept, spatial }
}

/// Whether `face` runs through the vertices of `first` (the same vertex set, distinct
/// vertices) in the opposite cyclic direction: each read from its smallest vertex, one
/// forward and the other backward. (For triangles this is the parity of the
/// permutation; a polygon whose order is neither counts as the same direction.)
fn opposite_direction(first: &[u32], face: &[u32]) -> bool {
    let n = first.len();
    if n != face.len() || n == 0 {
        return false;
    }
    let start = |ids: &[u32]| (0..n).min_by_key(|&k| ids[k]).unwrap_or(0);
    let (i, j) = (start(first), start(face));
    (0..n).all(|k| first[(i + k) % n] == face[(j + n - k) % n])
}
