//! Can the volume be trusted? Topology of a surface: welding, edges, shells, winding,
//! nesting, overlaps, holes, and the solid the surface most plausibly bounds.
//!
//! # What is computed
//! 1. **Weld** corners into vertices (exact positions, or snapped to a tolerance grid).
//! 2. **Faces**: a face with a repeated vertex (collapsed by welding) is *degenerate*
//!    and left out of everything below (and out of the solid). A face with distinct
//!    vertices but zero vector area (a sliver, one corner on the segment between two
//!    others, or a flat fold) is *degenerate* and *flat*: it stays in the edges, shells,
//!    orientation and solid (its volume is zero), but having no interior it is left out
//!    of the triangles the crossing search (7) and nesting rays (6) test, where it could
//!    only graze. Faces with the same vertex set are *duplicates*: among them, copies
//!    traversing it in opposite cyclic directions cancel in pairs, both dropped (a
//!    *double wall*: the shared face of two parts exported with both); of the rest,
//!    copies in the same direction collapse to the first. (Direction: each face read
//!    from its smallest vertex, forward against backward; a polygon whose order is
//!    neither counts as the same direction.) Dropped duplicates are left out of
//!    everything below.
//! 3. **Edges**: the undirected edges of the remaining faces (flat ones included:
//!    closedness and manifoldness are decided on every face with distinct vertices, so
//!    a sliver filling a T-junction closes it), with their uses. One use:
//!    *boundary*; two: *manifold*, and *consistent* when the two faces traverse it in
//!    opposite directions; more: *non-manifold*. A vertex whose faces form more than one
//!    fan around it (a bowtie) is a *non-manifold vertex*.
//! 4. **Shells**: connected components of faces through shared edges. Within a shell,
//!    orientation is propagated across manifold edges; a shell where that is impossible
//!    (a Möbius strip, a Klein bottle) is *non-orientable*.
//! 5. **Holes**: boundary edges chain into loops; each loop is capped with a fan from
//!    its centroid, so open shells still get a volume. `volume_uncertainty` adds, per
//!    cap, its area times the rim's largest distance from the cap's plane: zero for a
//!    flat hole (a missing planar face is recovered exactly), large for a ragged one.
//! 6. **Nesting**: from the corners of up to 32 triangles spread over each shell, rays
//!    count signed crossings (winding numbers) with every other closed shell whose box
//!    overlaps, using exact orientation predicates and a [`Bvh`] (a ray that grazes an
//!    edge tries the next axis direction; a corner on another surface is skipped). Inside for every sample: the shell is *nested*;
//!    inside for some and outside for others: the two *overlap*. A shell inside an odd
//!    number of others bounds a *cavity*. The solid's volume is Σ ±|shell volume|, +
//!    for solids and − for cavities, whatever each shell's winding in the file.
//! 7. **Crossings**: pairs of triangles where an edge of one passes strictly through
//!    the interior of the other, found through a [`Bvh`] (never all pairs), skipping
//!    pairs that share a vertex. Pairs from one shell are *self-intersections*; from two
//!    shells, *overlapping shells*, whose common volume a plain sum counts twice.
//!    Touching (shared planes, an edge lying on a face) is not crossing. The search
//!    (parallel) runs beside steps 3–6 (mostly sequential walks), so that on few cores
//!    neither leaves one idle.
//! 8. **Euler characteristic** V − E + F per shell, and genus (2 − χ)/2 for closed
//!    orientable shells.
//!
//! [`Check::solid`] gives a [`Surface`] of the solid: shells turned outward (cavities
//! inward), collapsed and duplicate faces dropped (flat ones kept), holes capped, so that
//! [`crate::mass_properties`] of it gives the solid's volume, centroid and inertia.

mod predicates;
mod solid;
mod weld;

pub use solid::{Measured, Solid, SolidView};

use crate::buckets::{for_each_range_mut, Buckets, SharedItems};
use crate::union_find::UnionFind;

use crate::accumulate::CompensatedSum;
use crate::bvh::{Box32, Bvh};
use crate::properties::Bounds;
use crate::vector::{add, cross, dot, norm, scale, sub};
use crate::{Point, Surface};
use rayon::prelude::*;

/// How corners are welded into vertices.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Weld {
    /// Exactly equal positions only.
    Exact,
    /// Positions that snap to the same point of a grid with this pitch.
    Tolerance(f64),
    /// Exactly; and if that leaves boundary edges, again within [`AUTO_WELD`] times the
    /// bounding box diagonal, keeping whichever leaves fewer. Files written in float32
    /// often repeat a vertex with coordinates that differ in the last bits (a CAD
    /// exporter's rounding), which opens cracks no user means to have.
    Auto,
}

/// Triangles per shell whose corners are classified against other shells for nesting
/// and overlap.
const NESTING_SAMPLES: usize = 32;

/// The relative tolerance [`Weld::Auto`] retries with.
pub const AUTO_WELD: f64 = 1e-9;

/// How to check.
#[derive(Clone, Copy, Debug)]
pub struct CheckOptions {
    pub weld: Weld,
    /// Look for crossing triangles (self-intersections, overlapping shells).
    pub intersections: bool,
    /// How many example face pairs to keep.
    pub examples: usize,
}

impl Default for CheckOptions {
    fn default() -> Self {
        CheckOptions { weld: Weld::Auto, intersections: true, examples: 5 }
    }
}

/// How the file's faces are wound.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orientation {
    /// Every shell is wound so its normals point out of the solid (counter-clockwise
    /// seen from outside); cavities' normals point into the void.
    Outward,
    /// Every shell is wound the other way (clockwise seen from outside, as OpenSCAD's
    /// polyhedron() wants).
    Inward,
    /// Some shells one way, some the other, or faces within a shell disagree.
    Mixed,
}

impl Orientation {
    /// `outward`, `inward` or `mixed`: the names reports use.
    pub fn name(self) -> &'static str {
        match self {
            Orientation::Outward => "outward",
            Orientation::Inward => "inward",
            Orientation::Mixed => "mixed",
        }
    }

    /// The winding seen from outside: `ccw` for outward normals, `cw` for OpenSCAD's
    /// convention; `None` when shells disagree.
    pub fn winding(self) -> Option<&'static str> {
        match self {
            Orientation::Outward => Some("ccw"),
            Orientation::Inward => Some("cw"),
            Orientation::Mixed => None,
        }
    }
}

/// One connected component of faces.
#[derive(Clone, Debug, PartialEq)]
pub struct Shell {
    /// Faces in the shell (flat faces included; collapsed and dropped duplicate faces
    /// are in no shell).
    pub faces: usize,
    /// Every edge used by exactly two faces.
    pub closed: bool,
    /// Orientation could be propagated consistently over the shell.
    pub orientable: bool,
    /// Its faces are consistently wound in the file.
    pub consistently_oriented: bool,
    /// Volume enclosed (holes capped), positive.
    pub volume: f64,
    /// The shell bounds a void inside another shell.
    pub cavity: bool,
    /// The smallest shell containing this one.
    pub parent: Option<usize>,
    /// Whether the file winds it the right way for its role (outward for a solid,
    /// inward for a cavity); `None` when not consistently oriented.
    pub wound_outward: Option<bool>,
    /// Boundary loops (holes) in this shell.
    pub boundary_loops: usize,
    /// V − E + F.
    pub euler_characteristic: i64,
    /// (2 − χ)/2 for closed orientable shells.
    pub genus: Option<i64>,
}

/// The facts [`check`] finds. See the module docs for the definitions.
#[derive(Clone, Debug)]
pub struct Check {
    /// The weld tolerance used; `None` for exact welding.
    pub weld_tolerance: Option<f64>,
    /// Welded vertices used by faces.
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
    /// Every edge used by exactly two faces (after dropping collapsed and duplicate
    /// faces; flat faces count), and at least one face.
    pub closed: bool,
    pub boundary_edges: usize,
    pub boundary_loops: usize,
    pub non_manifold_edges: usize,
    pub non_manifold_vertices: usize,
    /// Faces with a repeated welded vertex (collapsed by welding; left out of
    /// everything) plus flat faces.
    pub degenerate_faces: usize,
    /// Faces with distinct vertices but zero vector area (slivers: a corner on the
    /// segment between two others). They count among `degenerate_faces`, and stay in
    /// the edges, shells and solid: only the crossing search and nesting rays skip them.
    pub flat_faces: usize,
    /// Faces dropped for having the vertex set of another face: copies wound the same
    /// way beyond the first, and both faces of each opposite pair (`double_wall_faces`).
    pub duplicate_faces: usize,
    /// Faces dropped because they cancelled in pairs with a copy wound the opposite
    /// way: an internal double wall, such as the shared face of two boxes exported
    /// with both boxes. Counted in `duplicate_faces` too.
    pub double_wall_faces: usize,
    /// Every manifold edge's two faces traverse it in opposite directions.
    pub consistently_oriented: bool,
    /// `None` when there is no shell to judge.
    pub orientation: Option<Orientation>,
    pub shells: Vec<Shell>,
    pub cavities: usize,
    /// Pairs of shells whose surfaces cross.
    pub overlapping_shells: Vec<[usize; 2]>,
    /// Crossing face pairs within a shell; `None` when not looked for.
    pub self_intersections: Option<usize>,
    /// A few crossing face pairs, each once: within shells first, then between shells.
    pub intersection_examples: Vec<[usize; 2]>,
    /// V − E + F of the whole surface.
    pub euler_characteristic: i64,
    /// The solid's volume: Σ ±|shell volume| (cavities negative), holes capped.
    pub volume: f64,
    /// How much the caps on holes could be off (0 when closed).
    pub volume_uncertainty: f64,
    solid: Solid,
}

impl Check {
    /// The surface bounds a volume: closed, manifold, orientable, without crossings.
    pub fn bounds_a_volume(&self) -> bool {
        self.closed
            && self.non_manifold_edges == 0
            && self.shells.iter().all(|s| s.orientable)
            && self.overlapping_shells.is_empty()
            && self.self_intersections.unwrap_or(0) == 0
    }

    /// The solid as a surface over `surface` (which must be the one checked): shells
    /// turned outward (cavities inward), collapsed and duplicate faces dropped, holes
    /// capped.
    pub fn solid<'a, S: Surface + ?Sized>(&'a self, surface: &'a S) -> solid::SolidView<'a, S> {
        self.solid.view(surface)
    }

    /// The solid as a welded mesh, ready to write: shells turned outward (cavities
    /// inward), collapsed and duplicate faces dropped, and, with `with_caps`, holes
    /// capped.
    pub fn solid_mesh(&self, with_caps: bool) -> crate::Mesh {
        self.solid.mesh(with_caps)
    }

    /// A one-line verdict, most important fact first: "closed, 2 shells, 1 cavity:
    /// volume is exact", or what stops the surface from bounding a volume.
    pub fn verdict(&self) -> String {
        let c = self;
        let shells = plural(c.shells.len(), "shell", "shells");
        let cavities = match c.cavities {
            0 => String::new(),
            n => format!(", {}", plural(n, "cavity", "cavities")),
        };
        if c.shells.is_empty() {
            return c.no_faces_left();
        }
        if c.bounds_a_volume() {
            let wound = match c.orientation {
                Some(Orientation::Outward) => "",
                Some(Orientation::Inward) => " (wound inward)",
                _ => " (shells wound inconsistently; corrected)",
            };
            return format!("closed, {shells}{cavities}: volume is exact{wound}");
        }
        let mut problems = Vec::new();
        if c.boundary_loops > 0 {
            problems.push(format!(
                "open ({}, capped: volume ± {:.3e})",
                plural(c.boundary_loops, "hole", "holes"),
                c.volume_uncertainty
            ));
        }
        if !c.overlapping_shells.is_empty() {
            problems.push(format!(
                "{} overlap (their common volume is counted twice: use `meshvol union`)",
                plural(c.overlapping_shells.len(), "pair of shells", "pairs of shells")
            ));
        }
        if let Some(n) = c.self_intersections.filter(|&n| n > 0) {
            problems.push(plural(n, "self-intersection", "self-intersections"));
        }
        if c.non_manifold_edges > 0 {
            problems.push(plural(c.non_manifold_edges, "non-manifold edge", "non-manifold edges"));
        }
        if c.shells.iter().any(|s| !s.orientable) {
            problems.push("not orientable (no inside and outside)".into());
        }
        format!("does not bound a volume: {}; {shells}{cavities}", problems.join(", "))
    }

    /// Why no face is left to bound a volume.
    fn no_faces_left(&self) -> String {
        if self.double_wall_faces > 0 {
            "no usable faces: every face cancels with a twin wound the other way (a \
             double-sided surface), so nothing bounds a volume; measure it unchecked (as
             wound) instead"
                .into()
        } else {
            "no usable faces: nothing bounds a volume".into()
        }
    }

    /// What [`Check::solid`] changes: (faces flipped, faces dropped, cap triangles).
    pub fn repairs(&self) -> (usize, usize, usize) {
        self.solid.changes()
    }

    /// The solid's bodies: each outermost shell with the shells nested in it (its
    /// cavities, and islands in those), as faces of [`Check::solid`]. Bodies are
    /// numbered as their outermost shells are, in shell order; overlapping shells are
    /// separate bodies. Each body is a solid of its own (cavities wound inward), so
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
            .map(|(faces, shell)| Body { shell, faces })
            .collect()
    }

    /// Why the solid of [`Check::solid`] may not be the one the file means, one reason a
    /// line, empty when it is beyond doubt: holes capped, non-manifold edges, shells
    /// that cannot be oriented, overlapping shells, self-intersections, faces wound
    /// against their shell and duplicate faces left out. (Degenerate faces hold no
    /// volume and are not a doubt.) Every measurement of the solid carries these.
    pub fn doubts(&self) -> Vec<String> {
        let mut doubts = Vec::new();
        if self.shells.is_empty() {
            doubts.push(self.no_faces_left());
            return doubts;
        }
        if self.boundary_loops > 0 {
            doubts.push(format!(
                "open: {} capped, so the volume is uncertain by ± {:.3e}",
                plural(self.boundary_loops, "hole", "holes"),
                self.volume_uncertainty
            ));
        }
        if self.non_manifold_edges > 0 {
            doubts.push(format!(
                "{} (more than two faces meet): the solid is a guess",
                plural(self.non_manifold_edges, "non-manifold edge", "non-manifold edges")
            ));
        }
        let non_orientable = self.shells.iter().filter(|s| !s.orientable).count();
        if non_orientable > 0 {
            doubts.push(format!(
                "{} not orientable (no inside and outside)",
                plural(non_orientable, "shell is", "shells are")
            ));
        }
        if !self.overlapping_shells.is_empty() {
            doubts.push(format!(
                "{} overlap: their common volume is counted twice (the union counts it once)",
                plural(self.overlapping_shells.len(), "pair of shells", "pairs of shells")
            ));
        }
        if let Some(n) = self.self_intersections.filter(|&n| n > 0) {
            doubts.push(format!(
                "{}: the surface crosses itself, so some volume may count twice or with the wrong sign",
                plural(n, "self-intersecting face pair", "self-intersecting face pairs")
            ));
        }
        if !self.consistently_oriented {
            doubts.push(
                "faces are wound against their neighbours: they were turned to agree with their \
                 shells"
                    .to_string(),
            );
        } else if self.orientation == Some(Orientation::Mixed) {
            let against = self.shells.iter().filter(|s| s.wound_outward == Some(false)).count();
            doubts.push(format!(
                "{} wound against {} role (a cavity wound like a solid, or a solid like a \
                 cavity): turned to it",
                plural(against, "shell is", "shells are"),
                if against == 1 { "its" } else { "their" }
            ));
        }
        if self.duplicate_faces > 0 {
            doubts.push(format!(
                "{} left out (the same vertices as another face)",
                plural(self.duplicate_faces, "duplicate face", "duplicate faces")
            ));
        }
        doubts
    }
}

/// What a volume report must say about its numbers beyond the check's doubts: that the
/// measured solid encloses nothing, or that the file winds its faces inward (as wound,
/// or as the check found them). `as_wound` and `solid` are the mass properties of the
/// surface as wound and of the measured solid; `check` the check made, if any.
pub fn volume_warnings(
    check: Option<&Check>,
    as_wound: &crate::MassProperties,
    solid: &crate::MassProperties,
) -> Vec<String> {
    if solid.centroid.is_none() {
        return vec![
            "the volume is zero within rounding: the surface encloses no solid (flat, or \
                     open?); centroid and inertia are undefined"
                .to_string(),
        ];
    }
    let inward = check.is_none_or(|c| c.orientation == Some(Orientation::Inward));
    if as_wound.signed_volume < 0.0 && inward {
        return vec!["signed volume is negative: faces are wound inward (clockwise seen from \
                     outside, as OpenSCAD's polyhedron() expects); volume reports the solid's \
                     magnitude"
            .to_string()];
    }
    Vec::new()
}

/// One body of a checked solid: see [`Check::bodies`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Body {
    /// Its outermost shell.
    pub shell: usize,
    /// Its faces, as indices of the faces of [`Check::solid`].
    pub faces: Vec<usize>,
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// One use of an undirected edge: by face `face`, from corner `corner` to the next.
#[derive(Clone, Copy)]
struct EdgeUse {
    key: u64,
    face: u32,
    corner: u32,
    /// Traversed from the smaller vertex to the larger.
    forward: bool,
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

/// Faces as loops of corners.
struct Loops {
    corners: Vec<Point>,
    start: Vec<usize>,
}

impl Loops {
    /// The faces' corners, gathered in parallel: sizes first, then each face's fan
    /// written into its place.
    fn of<S: Surface + ?Sized>(surface: &S) -> Loops {
        let faces = surface.face_count();
        let sizes: Vec<usize> = (0..faces)
            .into_par_iter()
            .map(|f| {
                let mut triangles = 0;
                surface.fan(f, |_, _, _| triangles += 1);
                if triangles == 0 {
                    0
                } else {
                    triangles + 2
                }
            })
            .collect();
        let mut start = Vec::with_capacity(faces + 1);
        start.push(0);
        for size in sizes {
            start.push(start.last().unwrap_or(&0) + size);
        }
        let range = |f: usize| start[f]..start[f + 1];
        let mut corners = vec![[0.0; 3]; start[faces]];
        for_each_range_mut(&mut corners, faces, &range, &|f, corners| {
            let mut next = 0;
            surface.fan(f, |a, b, c| {
                if next == 0 {
                    corners[0] = a;
                    next = 1;
                }
                corners[next] = b;
                corners[next + 1] = c;
                next += 1;
            });
        });
        Loops { corners, start }
    }

    fn face(&self, f: usize) -> std::ops::Range<usize> {
        self.start[f]..self.start[f + 1]
    }

    /// The corner after `c` in its face.
    fn next(&self, f: usize, c: usize) -> usize {
        if c + 1 == self.start[f + 1] {
            self.start[f]
        } else {
            c + 1
        }
    }

    /// The corner before `c` in its face.
    fn previous(&self, f: usize, c: usize) -> usize {
        if c == self.start[f] {
            self.start[f + 1] - 1
        } else {
            c - 1
        }
    }
}

/// Why a surface could not be checked.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum CheckError {
    #[error("{corners} face corners: checks index corners with 32 bits (at most 4294967295)")]
    TooLarge { corners: usize },
}

/// Checks the topology of `surface`.
///
/// ```
/// use meshvol::shapes::cuboid;
/// use meshvol::topology::{check, CheckOptions, Orientation};
/// let c = check(&cuboid([0.0; 3], [2.0; 3]), &CheckOptions::default()).unwrap();
/// assert!(c.closed && c.bounds_a_volume());
/// assert_eq!(c.orientation, Some(Orientation::Outward));
/// assert_eq!((c.shells.len(), c.euler_characteristic, c.volume), (1, 2, 8.0));
/// ```
pub fn check<S: Surface + ?Sized>(
    surface: &S,
    options: &CheckOptions,
) -> Result<Check, CheckError> {
    let loops = Loops::of(surface);
    if u32::try_from(loops.corners.len()).is_err() {
        return Err(CheckError::TooLarge { corners: loops.corners.len() });
    }
    Ok(match options.weld {
        Weld::Exact => analyse(surface, &loops, None, options),
        Weld::Tolerance(t) => analyse(surface, &loops, Some(t), options),
        Weld::Auto => {
            let exact = analyse(surface, &loops, None, options);
            let diagonal = match loops.corners.first() {
                None => 0.0,
                Some(&first) => {
                    let b = loops.corners.iter().fold(
                        Bounds { min: first, max: first },
                        |mut b, &p| {
                            b.min = [0, 1, 2].map(|k| b.min[k].min(p[k]));
                            b.max = [0, 1, 2].map(|k| b.max[k].max(p[k]));
                            b
                        },
                    );
                    norm(b.size())
                }
            };
            if exact.boundary_edges == 0 || diagonal == 0.0 {
                exact
            } else {
                let welded = analyse(surface, &loops, Some(AUTO_WELD * diagonal), options);
                if welded.boundary_edges < exact.boundary_edges {
                    welded
                } else {
                    exact
                }
            }
        }
    })
}

/// Checks the faces `loops` of `surface`, welded with `tolerance`.
fn analyse<S: Surface + ?Sized>(
    surface: &S,
    loops: &Loops,
    tolerance: Option<f64>,
    options: &CheckOptions,
) -> Check {
    let faces = surface.face_count();
    let welded = weld::weld(&loops.corners, tolerance);
    let vid = |c: usize| welded.corner_vertex[c];

    // Collapsed faces (a repeated welded vertex) are left out of everything; flat faces
    // (distinct vertices, zero vector area: slivers) stay in the edge table but have no
    // interior, so they stay out of the spatial triangles.
    let (collapsed, flat): (Vec<bool>, Vec<bool>) = (0..faces)
        .into_par_iter()
        .map(|f| {
            let r = loops.face(f);
            let repeated = (r.start..r.end).any(|i| (r.start..i).any(|j| vid(j) == vid(i)));
            let apex = loops.corners[r.start];
            let area = (r.start + 1..r.end - 1).fold([0.0; 3], |s, c| {
                add(s, cross(sub(loops.corners[c], apex), sub(loops.corners[c + 1], apex)))
            });
            (repeated, !repeated && area == [0.0; 3])
        })
        .unzip();
    // Duplicates: the same vertex set as another face. Faces grouped by their smallest
    // vertex, each group sorted by (sorted vertex list, face): faces with one vertex set
    // form a run, in face order.
    let mut sorted_ids: Vec<u32> = welded.corner_vertex.clone();
    for_each_range_mut(&mut sorted_ids, faces, &|f| loops.face(f), &|_, ids| ids.sort_unstable());
    let ids_of = |f: u32| &sorted_ids[loops.face(f as usize)];
    let mut by_vertices = Buckets::new(welded.positions.len(), faces, |range| {
        range.filter(|&f| !collapsed[f]).map(|f| (ids_of(f as u32)[0], f as u32))
    });
    by_vertices.for_each_mut(|group| {
        if group.len() > 1 {
            group.sort_unstable_by(|&a, &b| ids_of(a).cmp(ids_of(b)).then(a.cmp(&b)))
        }
    });
    let mut duplicate = vec![false; faces];
    let mut double_wall = vec![false; faces];
    let items = &by_vertices.items;
    let mut i = 0;
    while i < items.len() {
        let run = items[i..].iter().take_while(|&&g| ids_of(g) == ids_of(items[i])).count();
        if run > 1 {
            let corners = |f: u32| &welded.corner_vertex[loops.face(f as usize)];
            let first = corners(items[i]);
            let (same, opposite): (Vec<u32>, Vec<u32>) =
                items[i..i + run].iter().partition(|&&g| !opposite_direction(first, corners(g)));
            // Opposite copies cancel in pairs (an internal double wall); of the rest, one
            // copy stays.
            let pairs = same.len().min(opposite.len());
            for &g in same[..pairs].iter().chain(&opposite[..pairs]) {
                double_wall[g as usize] = true;
                duplicate[g as usize] = true;
            }
            let rest = if same.len() > pairs { &same[pairs..] } else { &opposite[pairs..] };
            for &g in rest.iter().skip(1) {
                duplicate[g as usize] = true;
            }
        }
        i += run;
    }
    drop((sorted_ids, by_vertices));
    let kept: Vec<bool> = (0..faces).map(|f| !collapsed[f] && !duplicate[f]).collect();
    // The faces with an interior: those the crossing search and nesting rays see.
    let spatial: Vec<bool> = (0..faces).map(|f| kept[f] && !flat[f]).collect();

    // The crossing search (parallel, and the longest part) runs beside the connectivity
    // analysis (mostly sequential walks over edges and shells), so that on few cores
    // neither leaves one idle.
    let (space, connected) = rayon::join(
        || {
            options.intersections.then(|| {
                let (triangles, bvh) = triangles_in_space(loops, &spatial, &welded);
                let crossing = crossing_pairs(&triangles, &bvh);
                (triangles, bvh, crossing)
            })
        },
        || connect(surface, loops, &welded, &kept),
    );
    let Connected {
        used_vertices,
        non_manifold_vertices,
        edges,
        edges_per_shell,
        boundary_edges,
        non_manifold_edges,
        consistently_oriented,
        face_inconsistent,
        shell_of_face,
        shell_count,
        flip,
        orientable,
        shell_open,
        loops_found,
        caps:
            Caps {
                points: caps,
                ids: cap_ids,
                centres,
                shell: cap_shell,
                per_shell: shell_loops,
                volume_uncertainty,
            },
        shell_signed,
        shell_bounds,
        candidates,
    } = connected;
    // Triangles (fans of kept faces) in spatial order, with their corners inline, and
    // a hierarchy over their boxes: only when something asks for them.
    let nesting = candidates.iter().any(|c| !c.is_empty());
    let (triangles, bvh, crossing) = match space {
        Some((triangles, bvh, crossing)) => (triangles, bvh, Some(crossing)),
        None if nesting => {
            let (triangles, bvh) = triangles_in_space(loops, &spatial, &welded);
            (triangles, bvh, None)
        }
        None => (Triangles::default(), Bvh::default(), None),
    };

    // Sample up to NESTING_SAMPLES triangles' corners spread over each shell.
    let mut shell_triangles = vec![0usize; shell_count];
    for &f in &triangles.face {
        shell_triangles[shell_of_face[f as usize] as usize] += 1;
    }
    let mut samples: Vec<Vec<Point>> = vec![Vec::new(); shell_count];
    let mut seen_in_shell = vec![0usize; shell_count];
    for (i, &f) in triangles.face.iter().enumerate() {
        let s = shell_of_face[f as usize] as usize;
        let stride = shell_triangles[s].div_ceil(NESTING_SAMPLES);
        if seen_in_shell[s].is_multiple_of(stride) && !candidates[s].is_empty() {
            samples[s].extend(triangles.points(i));
        }
        seen_in_shell[s] += 1;
    }
    // Far enough that an oblique segment from any vertex leaves every shell's box.
    let reach = {
        let all = shell_bounds.iter().flatten().fold(None, |acc: Option<Bounds>, b| {
            let mut all = acc.unwrap_or(*b);
            all.merge(b);
            Some(all)
        });
        all.map_or(1.0, |b| 4.0 * norm(b.size()) + 1.0)
    };
    // For each shell, how many of its samples lie inside / outside each candidate.
    let classify = |a: usize| -> Vec<(usize, usize, usize)> {
        let candidates = &candidates[a];
        let mut counts: Vec<(usize, usize, usize)> =
            candidates.iter().map(|&b| (b, 0, 0)).collect();
        let mut winding = vec![0i64; candidates.len()];
        for &p in &samples[a] {
            // Rays along each axis direction in turn, until one crosses cleanly; then
            // an oblique segment to beyond the mesh (it meets many boxes, so it is the
            // last resort, for symmetric meshes where every axis ray hits an edge).
            let clean = (0..=predicates::RAY_FRAMES.len()).any(|frame| {
                let oblique = frame == predicates::RAY_FRAMES.len();
                let q = add(p, scale(predicates::OBLIQUE, reach));
                let ray = if oblique {
                    let mut b = Bounds::of(p);
                    b.include(q);
                    b
                } else {
                    let (min, max) = predicates::ray_box(p, frame);
                    Bounds { min, max }
                };
                winding.fill(0);
                let mut grazed = false;
                bvh.overlapping(&ray, |i| {
                    let face = triangles.face[i] as usize;
                    let s = shell_of_face[face] as usize;
                    if grazed || s == a {
                        return;
                    }
                    let Ok(k) = candidates.binary_search(&s) else { return };
                    let v = triangles.points(i);
                    let crossing = if oblique {
                        predicates::segment_crossing(p, q, v[0], v[1], v[2])
                    } else {
                        let rotate = predicates::RAY_FRAMES[frame];
                        let v = v.map(rotate);
                        predicates::ray_crossing(rotate(p), v[0], v[1], v[2])
                    };
                    match crossing {
                        Some(w) => winding[k] += if flip[face] { -w } else { w } as i64,
                        None => grazed = true,
                    }
                });
                !grazed
            });
            if !clean {
                continue; // on another surface: this sample cannot tell
            }
            for (c, &w) in counts.iter_mut().zip(&winding) {
                if w != 0 {
                    c.1 += 1;
                } else {
                    c.2 += 1;
                }
            }
        }
        counts
    };
    let classified: Vec<Vec<(usize, usize, usize)>> =
        (0..shell_count).into_par_iter().map(classify).collect();
    // Inside every sample that could tell: nested. Inside for some, outside for others:
    // the surfaces cross, and the shells overlap.
    let mut overlapping_shells = std::collections::BTreeSet::new();
    let containers: Vec<Vec<usize>> = classified
        .iter()
        .enumerate()
        .map(|(a, counts)| {
            for &(b, inside, outside) in counts {
                if inside > 0 && outside > 0 {
                    overlapping_shells.insert([a.min(b), a.max(b)]);
                }
            }
            counts.iter().filter(|c| c.1 > 0 && c.2 == 0).map(|c| c.0).collect()
        })
        .collect();

    // Crossing triangles, as face pairs.
    let mut self_intersections = None;
    let mut intersection_examples = Vec::new();
    if let Some(mut pairs) = crossing {
        // Polygon faces fan into several triangles: count each crossing face pair once.
        pairs.par_sort_unstable();
        pairs.dedup();
        let same_shell = |&[f, g]: &[usize; 2]| shell_of_face[f] == shell_of_face[g];
        let mut within = 0;
        for pair in &pairs {
            if same_shell(pair) {
                within += 1;
            } else {
                let (sf, sg) = (shell_of_face[pair[0]] as usize, shell_of_face[pair[1]] as usize);
                overlapping_shells.insert([sf.min(sg), sf.max(sg)]);
            }
        }
        // Self-intersections first, so that a count above zero always has an example.
        let (mut examples, between): (Vec<[usize; 2]>, Vec<[usize; 2]>) =
            pairs.iter().partition(|p| same_shell(p));
        examples.extend(between);
        examples.truncate(options.examples);
        intersection_examples = examples;
        self_intersections = Some(within);
    }

    // Roles: nesting depth parity decides solid or cavity.
    let mut shells = Vec::with_capacity(shell_count);
    let mut per_shell = vec![(0usize, 0usize, false); shell_count]; // faces, edges, inconsistent
    for f in (0..faces).filter(|&f| kept[f]) {
        let s = shell_of_face[f] as usize;
        per_shell[s].0 += 1;
        per_shell[s].2 |= face_inconsistent[f];
    }
    for (s, &edges) in edges_per_shell.iter().enumerate() {
        per_shell[s].1 = edges;
    }
    let mut shell_vertices = vec![0i64; shell_count];
    {
        let mut last_shell_of_vertex = vec![u32::MAX; welded.positions.len()];
        for f in (0..faces).filter(|&f| kept[f]) {
            let s = shell_of_face[f];
            for c in loops.face(f) {
                let v = vid(c) as usize;
                if last_shell_of_vertex[v] != s {
                    // A vertex can be shared by shells only at non-manifold points; count
                    // it once per shell visit run, which is exact for manifold meshes.
                    last_shell_of_vertex[v] = s;
                    shell_vertices[s as usize] += 1;
                }
            }
        }
    }
    let mut flip_shell = vec![false; shell_count];
    let mut volume = CompensatedSum::default();
    for s in 0..shell_count {
        let depth = containers[s].len();
        let cavity = depth % 2 == 1;
        let parent = containers[s]
            .iter()
            .copied()
            .min_by(|&a, &b| shell_signed[a].abs().total_cmp(&shell_signed[b].abs()));
        let (faces_in, edges_in, inconsistent) = per_shell[s];
        let positive_as_propagated = shell_signed[s] >= 0.0;
        // The first face keeps its file winding, so as-propagated is as-wound when the
        // shell is consistent.
        let wound_outward =
            (!inconsistent && orientable[s]).then_some(positive_as_propagated != cavity);
        flip_shell[s] = positive_as_propagated == cavity;
        let v = shell_signed[s].abs();
        volume.add(if cavity { -v } else { v });
        let chi = shell_vertices[s] - edges_in as i64 + faces_in as i64;
        let closed = !shell_open[s];
        shells.push(Shell {
            faces: faces_in,
            closed,
            orientable: orientable[s],
            consistently_oriented: !inconsistent,
            volume: v,
            cavity,
            parent,
            wound_outward,
            boundary_loops: shell_loops[s],
            euler_characteristic: chi,
            genus: (closed && orientable[s] && chi % 2 == 0).then_some((2 - chi) / 2),
        });
    }
    let orientation = if shells.is_empty() {
        None
    } else if shells.iter().all(|s| s.wound_outward == Some(true)) {
        Some(Orientation::Outward)
    } else if shells.iter().all(|s| s.wound_outward == Some(false)) {
        Some(Orientation::Inward)
    } else {
        Some(Orientation::Mixed)
    };

    let face_flip: Vec<bool> = (0..faces)
        .into_par_iter()
        .map(|f| kept[f] && (flip[f] ^ flip_shell[shell_of_face[f] as usize]))
        .collect();
    let cap_flip: Vec<bool> = cap_shell.iter().map(|&s| flip_shell[s as usize]).collect();
    let weld::Welded { corner_vertex, positions: mut vertices, .. } = welded;
    vertices.extend(centres);
    let solid = Solid::new(
        solid::Faces {
            kept: &kept,
            flip: &face_flip,
            shell: &shell_of_face,
            corners: corner_vertex,
            start: loops.start.clone(),
        },
        vertices,
        solid::Caps { points: caps, ids: cap_ids, flip: &cap_flip, shell: &cap_shell },
    );

    let kept_faces = kept.iter().filter(|&&k| k).count();
    Check {
        weld_tolerance: tolerance,
        vertices: used_vertices,
        edges,
        faces,
        closed: kept_faces > 0 && boundary_edges == 0 && non_manifold_edges == 0,
        boundary_edges,
        boundary_loops: loops_found.len(),
        non_manifold_edges,
        non_manifold_vertices,
        degenerate_faces: (0..faces).filter(|&f| collapsed[f] || flat[f]).count(),
        flat_faces: flat.iter().filter(|&&d| d).count(),
        duplicate_faces: duplicate.iter().filter(|&&d| d).count(),
        double_wall_faces: double_wall.iter().filter(|&&d| d).count(),
        consistently_oriented,
        orientation,
        cavities: shells.iter().filter(|s| s.cavity).count(),
        shells,
        overlapping_shells: overlapping_shells.into_iter().collect(),
        self_intersections,
        intersection_examples,
        euler_characteristic: used_vertices as i64 - edges as i64 + kept_faces as i64,
        volume: volume.value(),
        volume_uncertainty,
        solid,
    }
}

/// What the check derives from how faces connect, by edges and vertices: edge counts,
/// shells, orientation, boundary loops and their caps, per-shell volumes and boxes.
struct Connected {
    /// Vertices used by kept faces.
    used_vertices: usize,
    non_manifold_vertices: usize,
    edges: usize,
    edges_per_shell: Vec<usize>,
    boundary_edges: usize,
    non_manifold_edges: usize,
    consistently_oriented: bool,
    face_inconsistent: Vec<bool>,
    shell_of_face: Vec<u32>,
    shell_count: usize,
    /// Per face: reversed to agree with its shell's first face.
    flip: Vec<bool>,
    orientable: Vec<bool>,
    shell_open: Vec<bool>,
    /// Boundary loops as (shell, vertices in order).
    loops_found: Vec<(u32, Vec<u32>)>,
    caps: Caps,
    /// Per shell: its volume as propagated from its first face, holes capped.
    shell_signed: Vec<f64>,
    shell_bounds: Vec<Option<Bounds>>,
    /// Per shell: the closed shells whose boxes overlap its own.
    candidates: Vec<Vec<usize>>,
}

/// The fans capping boundary loops, as points and as vertex ids (each centre a new
/// vertex after the welded ones), with their shells.
struct Caps {
    points: Vec<[Point; 3]>,
    ids: Vec<[u32; 3]>,
    centres: Vec<Point>,
    shell: Vec<u32>,
    /// Boundary loops per shell.
    per_shell: Vec<usize>,
    /// Per cap, its area times the rim's largest distance from its plane, summed.
    volume_uncertainty: f64,
}

/// Edges, shells, orientation, caps and per-shell volumes of the kept faces.
fn connect<S: Surface + ?Sized>(
    surface: &S,
    loops: &Loops,
    welded: &weld::Welded,
    kept: &[bool],
) -> Connected {
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
    let used_vertices = per_vertex.iter().filter(|p| p.1 > 0).count();
    let non_manifold_vertices = per_vertex.iter().filter(|p| p.1 > 1).count();
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
    drop(around);
    // The uses of each edge (a run of equal keys), found in parallel.
    let group_start: Vec<usize> = (0..uses.len())
        .into_par_iter()
        .filter(|&i| i == 0 || uses[i].key != uses[i - 1].key)
        .chain(rayon::iter::once(uses.len()))
        .collect();
    let groups: Vec<&[EdgeUse]> = group_start.par_windows(2).map(|w| &uses[w[0]..w[1]]).collect();
    drop(group_start);

    let mut shells_of = UnionFind::new(faces);
    let (mut boundary_edges, mut non_manifold_edges) = (0, 0);
    let mut consistently_oriented = true;
    let mut face_inconsistent = vec![false; faces];
    for g in &groups {
        for e in &g[1..] {
            shells_of.join(g[0].face, e.face);
        }
        match g.len() {
            1 => boundary_edges += 1,
            2 => {
                let same = g[0].forward == g[1].forward;
                if same {
                    consistently_oriented = false;
                    face_inconsistent[g[0].face as usize] = true;
                    face_inconsistent[g[1].face as usize] = true;
                }
            }
            _ => non_manifold_edges += 1,
        }
    }
    // Each face's neighbours across manifold edges, and whether the two traverse the
    // edge the same way, for orientation propagation: at the corner that starts the
    // edge in the face (so laid out like the corners, and found without sorting).
    const NO_NEIGHBOUR: (u32, bool) = (u32::MAX, false);
    let mut neighbour = vec![NO_NEIGHBOUR; loops.corners.len()];
    let shared = SharedItems::new(&mut neighbour);
    groups.par_iter().filter(|g| g.len() == 2).for_each(|g| {
        let same = g[0].forward == g[1].forward;
        // SAFETY: every corner starts one edge use, which is in one group.
        unsafe {
            shared.write(g[0].corner as usize, (g[1].face, same));
            shared.write(g[1].corner as usize, (g[0].face, same));
        }
    });

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
            for &(h, same) in across.filter(|n| **n != NO_NEIGHBOUR) {
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

    // Boundary loops, following each face's propagated direction, and their caps.
    let boundary: Vec<(u32, u32, u32)> = groups
        .iter()
        .filter(|g| g.len() == 1)
        .map(|g| {
            let e = g[0];
            let (c, n) = (e.corner as usize, loops.next(e.face as usize, e.corner as usize));
            let (u, v) = if flip[e.face as usize] { (vid(n), vid(c)) } else { (vid(c), vid(n)) };
            (u, v, shell_of_face[e.face as usize])
        })
        .collect();
    let loops_found = boundary_loops(&boundary);
    let mut caps: Vec<[Point; 3]> = Vec::new();
    // The same caps as vertex ids, each centre a new vertex after the welded ones.
    let mut cap_ids: Vec<[u32; 3]> = Vec::new();
    let mut centres: Vec<Point> = Vec::new();
    let mut cap_shell: Vec<u32> = Vec::new();
    let mut shell_loops = vec![0usize; shell_count];
    let mut volume_uncertainty = 0.0;
    for (shell, ring) in &loops_found {
        shell_loops[*shell as usize] += 1;
        let pts: Vec<Point> = ring.iter().map(|&v| welded.positions[v as usize]).collect();
        let centre = scale(pts.iter().fold([0.0; 3], |s, &p| add(s, p)), 1.0 / pts.len() as f64);
        let centre_id = (welded.positions.len() + centres.len()) as u32;
        centres.push(centre);
        let mut vector_area = [0.0; 3];
        for i in 0..pts.len() {
            let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
            // The cap traverses each rim edge against its face: (centre, q, p).
            caps.push([centre, q, p]);
            cap_ids.push([centre_id, ring[(i + 1) % ring.len()], ring[i]]);
            cap_shell.push(*shell);
            vector_area = add(vector_area, cross(sub(q, centre), sub(p, centre)));
        }
        let area = norm(vector_area) / 2.0;
        if area > 0.0 {
            let n = scale(vector_area, 0.5 / area);
            let thickness = pts.iter().map(|&p| dot(sub(p, centre), n).abs()).fold(0.0, f64::max);
            volume_uncertainty += area * thickness;
        }
    }

    // Per-shell signed volume (propagated orientation, holes capped), about a local point.
    let reference = loops.corners.first().copied().unwrap_or([0.0; 3]);
    let six_volume = |a: Point, b: Point, c: Point| {
        let (a, b, c) = (sub(a, reference), sub(b, reference), sub(c, reference));
        dot(a, cross(b, c))
    };
    let face_six: Vec<f64> = (0..faces)
        .into_par_iter()
        .map(|f| {
            if !kept[f] {
                return 0.0;
            }
            let mut s = 0.0;
            surface.fan(f, |a, b, c| s += six_volume(a, b, c));
            if flip[f] {
                -s
            } else {
                s
            }
        })
        .collect();
    let mut shell_six = vec![CompensatedSum::default(); shell_count];
    for f in (0..faces).filter(|&f| kept[f]) {
        shell_six[shell_of_face[f] as usize].add(face_six[f]);
    }
    for (cap, &s) in caps.iter().zip(&cap_shell) {
        shell_six[s as usize].add(six_volume(cap[0], cap[1], cap[2]));
    }
    let shell_signed: Vec<f64> = shell_six.iter().map(|s| s.value() / 6.0).collect();

    // Nesting and overlap concern closed, orientable shells.
    let mut shell_open = vec![false; shell_count];
    for g in groups.iter().filter(|g| g.len() != 2) {
        shell_open[shell_of_face[g[0].face as usize] as usize] = true;
    }
    let solid_shell: Vec<bool> =
        (0..shell_count).map(|s| orientable[s] && !shell_open[s]).collect();
    let mut shell_bounds: Vec<Option<Bounds>> = vec![None; shell_count];
    for f in (0..faces).filter(|&f| kept[f]) {
        let bounds = &mut shell_bounds[shell_of_face[f] as usize];
        for c in loops.face(f) {
            let p = welded.positions[vid(c) as usize];
            bounds.get_or_insert(Bounds::of(p)).include(p);
        }
    }
    // For each shell, the closed shells whose boxes overlap its own (found through a
    // hierarchy over the shells' boxes: files with 100 000 parts are common).
    let shell_tree =
        Bvh::new(shell_bounds.iter().map(|b| Box32::around(&b.unwrap_or(Bounds::EMPTY))).collect());
    let candidates: Vec<Vec<usize>> = (0..shell_count)
        .into_par_iter()
        .map(|a| {
            let mut near = Vec::new();
            if let Some(ba) = shell_bounds[a] {
                shell_tree.overlapping(&ba, |b| {
                    if b != a && solid_shell[b] {
                        near.push(b);
                    }
                });
            }
            near.sort_unstable();
            near
        })
        .collect();

    let mut edges_per_shell = vec![0usize; shell_count];
    for g in &groups {
        edges_per_shell[shell_of_face[g[0].face as usize] as usize] += 1;
    }
    Connected {
        used_vertices,
        non_manifold_vertices,
        edges: groups.len(),
        edges_per_shell,
        boundary_edges,
        non_manifold_edges,
        consistently_oriented,
        face_inconsistent,
        shell_of_face,
        shell_count,
        flip,
        orientable,
        shell_open,
        loops_found,
        caps: Caps {
            points: caps,
            ids: cap_ids,
            centres,
            shell: cap_shell,
            per_shell: shell_loops,
            volume_uncertainty,
        },
        shell_signed,
        shell_bounds,
        candidates,
    }
}

/// The triangles of the kept faces' fans, as parallel arrays: the crossing search
/// reads `ids` for every nearby pair and their points only for pairs sharing no vertex.
#[derive(Default)]
struct Triangles<'a> {
    /// Welded vertices.
    ids: Vec<[u32; 3]>,
    face: Vec<u32>,
    /// The welded vertices' positions. (Read through `ids` rather than copied per
    /// triangle: the copy, 72 bytes a triangle, cost more than the scattered reads.)
    positions: &'a [Point],
}

impl Triangles<'_> {
    fn points(&self, i: usize) -> [Point; 3] {
        self.ids[i].map(|v| self.positions[v as usize])
    }
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

/// Whether two triangles share a vertex: nine comparisons without short-circuiting
/// (most pairs tested are neighbours, in no predictable pattern).
#[inline(always)]
fn shares_a_vertex(t: &[u32; 3], u: &[u32; 3]) -> bool {
    t.iter().fold(false, |shared, v| shared | (*v == u[0]) | (*v == u[1]) | (*v == u[2]))
}

/// The kept faces' triangles in spatial order (neighbours in space are neighbours in
/// memory, which the hierarchy's searches then read), and the hierarchy over them.
fn triangles_in_space<'a>(
    loops: &Loops,
    kept: &[bool],
    welded: &'a weld::Welded,
) -> (Triangles<'a>, Bvh) {
    // Each fan triangle as (face, corner of its second vertex).
    let fans: Vec<(u32, u32)> = (0..kept.len())
        .into_par_iter()
        .filter(|&f| kept[f])
        .flat_map_iter(|f| {
            let r = loops.face(f);
            (r.start + 1..r.end - 1).map(move |c| (f as u32, c as u32))
        })
        .collect();
    let corners = |(f, c): (u32, u32)| [loops.start[f as usize], c as usize, c as usize + 1];
    // Ordered by the face's own corners (read in sequence), not the welded vertices.
    let centres: Vec<Point> = fans
        .par_iter()
        .map(|&fan| {
            let p = corners(fan).map(|c| loops.corners[c]);
            [0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k]) / 3.0)
        })
        .collect();
    let order = Bvh::spatial_order(&centres);
    drop(centres);
    let (ids, (face, boxes)): (Vec<_>, (Vec<_>, Vec<Box32>)) = order
        .par_iter()
        .map(|&i| {
            let fan = fans[i as usize];
            let ids = corners(fan).map(|c| welded.corner_vertex[c]);
            let points = ids.map(|v| welded.positions[v as usize]);
            let mut bounds = Bounds::of(points[0]);
            bounds.include(points[1]);
            bounds.include(points[2]);
            (ids, (fan.0, Box32::around(&bounds)))
        })
        .unzip();
    (Triangles { ids, face, positions: &welded.positions }, Bvh::new(boxes))
}

/// The pairs of kept faces whose fan triangles cross, sorted.
fn crossing_pairs(triangles: &Triangles, bvh: &Bvh) -> Vec<[usize; 2]> {
    let test = |i: usize, j: usize| {
        if shares_a_vertex(&triangles.ids[i], &triangles.ids[j]) {
            return None; // neighbours meet at shared vertices by design
        }
        let (f, g) = (triangles.face[i] as usize, triangles.face[j] as usize);
        predicates::triangles_cross(triangles.points(i), triangles.points(j))
            .then_some([f.min(g), f.max(g)])
    };
    bvh.overlapping_pairs(test)
}

/// Chains boundary edges (u, v, shell) into loops of vertices: following each edge's
/// direction where the next edge continues it, against it where only that continues
/// (across the seam of a non-orientable strip).
fn boundary_loops(edges: &[(u32, u32, u32)]) -> Vec<(u32, Vec<u32>)> {
    // Every edge listed at both ends: (vertex, edge, the edge starts there).
    let mut ends: Vec<(u32, usize, bool)> =
        edges.iter().enumerate().flat_map(|(i, e)| [(e.0, i, true), (e.1, i, false)]).collect();
    ends.sort_unstable_by_key(|&(v, i, starts)| (v, !starts, i));
    let mut used = vec![false; edges.len()];
    let mut loops = Vec::new();
    for first in 0..edges.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut ring = vec![edges[first].0];
        let mut at = edges[first].1;
        while at != edges[first].0 {
            ring.push(at);
            let from = ends.partition_point(|e| e.0 < at);
            // A loop stays in its shell: shells touching at a vertex each cap their own
            // holes, so that each shell (and each body) is closed by its own caps.
            let shell = edges[first].2;
            let next = ends[from..]
                .iter()
                .take_while(|e| e.0 == at)
                .find(|e| !used[e.1] && edges[e.1].2 == shell);
            let Some(&(_, e, starts)) = next else { break }; // a broken chain: close it here
            used[e] = true;
            at = if starts { edges[e].1 } else { edges[e].0 };
        }
        loops.push((edges[first].2, ring));
    }
    loops
}
