//! Bodies: the separate objects a file names (3MF objects and components, glTF mesh
//! instances), given to the check as runs of faces, and the bodies of the checked solid.
//!
//! Nesting decides cavities inside a body, never between bodies: a shell that lies
//! inside a shell of another body is a solid of its own, not a cavity, because a part in
//! its packaging or a bolt in a housing are two parts, not a part with a hole. A shell
//! belongs to the body of its first face (a shell welded across two bodies, as two
//! objects sharing a face's corners make, is one shell all the same). What nesting and
//! the crossings find between bodies is kept apart, as overlapping bodies: the solid's
//! volume is then the bodies' sum, counting their common volume twice, and `union` the
//! union.
//!
//! Without bodies (a single-object file: one body of every face) a shell inside an odd
//! number of others is a cavity, as slicers read one model.

use super::report::{BodyOverlap, Check};
use super::shells::Shells;
use std::collections::BTreeSet;
use std::ops::Range;

/// Each shell's body: the run of `bodies` holding its first kept face; all 0 without
/// bodies. Faces outside every run (the runs should cover them) count as one more body.
pub(super) fn of_shells(bodies: &[Range<usize>], shells: &Shells, kept: &[bool]) -> Vec<usize> {
    if bodies.is_empty() {
        return vec![0; shells.count];
    }
    // The fold visits a shell's faces in order (chunks merged in order): the first one
    // kept is the smallest.
    let first = shells.fold_faces(
        kept,
        |first: &mut Option<usize>, f| {
            first.get_or_insert(f);
        },
        |first, other| {
            if first.is_none() {
                *first = *other;
            }
        },
    );
    first.into_iter().map(|f| of_face(bodies, f.unwrap_or(usize::MAX))).collect()
}

/// The run of `bodies` holding face `f`, or `bodies.len()` for none.
pub(super) fn of_face(bodies: &[Range<usize>], f: usize) -> usize {
    let run = bodies.partition_point(|r| r.start <= f);
    match run.checked_sub(1) {
        Some(b) if bodies[b].contains(&f) => b,
        _ => bodies.len(),
    }
}

/// Splits what nesting and the crossings found by body: `containers` keeps, for each
/// shell, only the containers in its own body, and `overlapping_shells` only pairs
/// within one body; the rest become overlapping bodies, sorted. A shell inside an odd
/// number of another body's shells lies in that body's material (inside an even number,
/// in a cavity of it: no common volume).
pub(super) fn split(
    body_of_shell: &[usize],
    containers: &mut [Vec<usize>],
    overlapping_shells: &mut BTreeSet<[usize; 2]>,
) -> Vec<BodyOverlap> {
    let pair = |a: usize, b: usize| [a.min(b), a.max(b)];
    let mut crossing = BTreeSet::new();
    overlapping_shells.retain(|&[s, t]| {
        let (a, b) = (body_of_shell[s], body_of_shell[t]);
        if a != b {
            crossing.insert(pair(a, b));
        }
        a == b
    });
    let mut nested = BTreeSet::new();
    for (s, within) in containers.iter_mut().enumerate() {
        let own = body_of_shell[s];
        let mut others: Vec<usize> =
            within.iter().map(|&c| body_of_shell[c]).filter(|&b| b != own).collect();
        others.sort_unstable();
        for run in others.chunk_by(|a, b| a == b) {
            if run.len() % 2 == 1 && !crossing.contains(&pair(own, run[0])) {
                nested.insert(pair(own, run[0]));
            }
        }
        within.retain(|&c| body_of_shell[c] == own);
    }
    let crossing = crossing.into_iter().map(|bodies| BodyOverlap { bodies, nested: false });
    let mut all: Vec<BodyOverlap> = crossing
        .chain(nested.into_iter().map(|bodies| BodyOverlap { bodies, nested: true }))
        .collect();
    all.sort_unstable();
    all
}

impl Check {
    /// The solid's bodies: each outermost shell with the shells nested in it (its
    /// cavities, and islands in those), as faces of [`Check::solid`]. Bodies are
    /// numbered as their outermost shells are, in shell order; overlapping shells are
    /// separate bodies, and so is each object of a file whose objects are bodies (see
    /// the module docs). Each body is a solid of its own (cavities wound inward), so
    /// measuring one gives its volume with its cavities subtracted.
    ///
    /// ```
    /// use meshvol::shapes::cuboid;
    /// use meshvol::topology::{check, CheckOptions};
    /// use meshvol::{mass_properties, Mesh, Surface};
    /// // A 2×2×2 box with a centred 1×1×1 cavity (both wound outward in the file).
    /// let (outer, inner) = (cuboid([0.0; 3], [2.0; 3]), cuboid([0.5; 3], [1.5; 3]));
    /// let mesh = Mesh::concatenate(&[outer, inner]);
    /// let c = check(&mesh, &CheckOptions::default()).unwrap();
    /// let bodies = c.bodies();
    /// assert_eq!((bodies.len(), bodies[0].shell, bodies[0].faces.len()), (1, 0, 12));
    /// assert_eq!(mass_properties(&c.solid(&mesh)).signed_volume, 7.0);
    /// ```
    pub fn bodies(&self) -> Vec<Body> {
        let root = |mut s: usize| {
            // Parents are strictly larger shells, so the walk ends.
            while let Some(p) = self.shells[s].parent {
                s = p;
            }
            s
        };
        let roots: Vec<usize> =
            (0..self.shells.len()).filter(|&s| self.shells[s].parent.is_none()).collect();
        let mut body_of_root = vec![usize::MAX; self.shells.len()];
        for (b, &r) in roots.iter().enumerate() {
            body_of_root[r] = b;
        }
        let group: Vec<usize> = (0..self.shells.len()).map(|s| body_of_root[root(s)]).collect();
        self.solid
            .faces_by(roots.len(), |s| group[s])
            .into_iter()
            .zip(roots)
            .map(|(faces, shell)| {
                let object = self.object_of_shell.as_ref().map(|o| o[shell]);
                Body { shell, object, faces }
            })
            .collect()
    }
}

/// One body of a checked solid: see [`Check::bodies`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Body {
    /// Its outermost shell.
    pub shell: usize,
    /// The object (of the bodies given to the check) it belongs to; `None` when none
    /// were given.
    pub object: Option<usize>,
    /// Its faces, as indices of the faces of [`Check::solid`].
    pub faces: Vec<usize>,
}
