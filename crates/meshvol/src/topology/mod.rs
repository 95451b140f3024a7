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
//!
//!    **Sheets**: at a non-manifold edge the faces are sorted by their angle around it
//!    (exactly) and paired with neighbours, following the file's winding where it
//!    allows, into locally manifold sheets; with an odd number, one face is left alone.
//!    Two bodies touching along an edge are thus two closed shells.
//! 4. **Shells**: connected components of faces through sheets' edges. Within a shell,
//!    orientation is propagated across them; a shell where that is impossible (a Möbius
//!    strip, a Klein bottle) is *non-orientable*.
//! 5. **Holes**: the edges left open (boundary edges, faces alone at non-manifold
//!    edges, the seams of non-orientable shells) chain into loops; each loop is capped
//!    with a fan from its centroid, so that every shell is closed as a chain and every
//!    command measures one and the same solid. `volume_uncertainty` adds, per cap, its
//!    area times the rim's largest distance from the cap's plane: zero for a flat hole
//!    (a missing planar face is recovered exactly), large for a ragged one.
//! 6. **Nesting**: from the corners of up to 32 triangles spread over each shell, rays
//!    count signed crossings (winding numbers) with every other orientable shell whose
//!    box overlaps, closed or closed by its caps (a shell with holes, its caps under
//!    half its faces' area, contains what lies inside it capped, as the solid measures
//!    it), using exact orientation predicates and a [`Bvh`] (a ray that grazes an edge
//!    tries the next axis direction; a corner on another surface is skipped). Inside
//!    for every sample: the shell is *nested*; inside for some and outside for others:
//!    the two *overlap*. A shell inside an odd number of others bounds a *cavity*. The
//!    solid's volume is Σ ±|shell volume|, + for solids and − for cavities, whatever
//!    each shell's winding in the file. Where the file names separate objects (bodies),
//!    nesting pairs shells of one body only; between bodies it finds *overlapping
//!    bodies* (`bodies.rs`).
//! 7. **Crossings**: pairs of triangles where an edge of one passes strictly through
//!    the interior of the other, found through a [`Bvh`] (never all pairs), skipping
//!    pairs that share a vertex. Pairs from one shell are *self-intersections*; from two
//!    shells, *overlapping shells*, whose common volume a plain sum counts twice.
//!    Touching (shared planes, an edge lying on a face) is not crossing. The search
//!    runs after steps 3–5 have dropped their edge table, so that the two largest
//!    arrays of a check are never held at once.
//! 8. **Euler characteristic** V − E + F per shell, and genus (2 − χ)/2 for closed
//!    orientable shells.
//!
//! # Stages and files
//! [`check`] gathers the faces' corners (`loops.rs`), welds them, drops them, and runs
//! the stages in order on the welded vertices; the crossing search runs after stages
//! 3–5 and the nesting candidates, and its triangles then serve the nesting rays.
//!
//! | stage | what it finds | file |
//! | --- | --- | --- |
//! | 1. weld | vertices from corners | `weld.rs` |
//! | 2. faces | collapsed, flat, duplicate and double-wall faces; the kept ones | `faces.rs` |
//! | 3. edges | edge uses, boundary and non-manifold edges and vertices, neighbours | `edges.rs` |
//! | 3b. sheets | faces around a non-manifold edge paired by their angular order | `sheets.rs` |
//! | 4. shells | connected components and orientation (a parallel union–find with parities), open shells | `shells.rs` |
//! | 5. holes | open edges in loops, their caps, capped shell volumes | `holes.rs` |
//! | 3–5 in order | the stages that need no triangles, run one after the other | `connect.rs` |
//! | 6. nesting | candidates, containment rays, overlaps, roles, the volume | `nesting.rs` |
//! | 6b. bodies | nesting within each body; overlapping bodies; the solid's bodies | `bodies.rs` |
//! | 7. crossings | triangles in space, crossing face pairs | `crossings.rs` |
//! | 8. Euler | χ and genus per shell | `euler.rs` |
//! | | exact orientation predicates for stages 6 and 7 | `predicates.rs` |
//! | | the solid as a surface or a mesh | `solid.rs` |
//! | | the check of an assembly of placed parts, from one check per part | `assembled.rs` |
//! | | the winding, verdict, doubts and warnings in words | `verdict.rs` |
//! | | what a check finds: `Check`, `Orientation`, `BodyOverlap` | `report.rs` |
//! | | why a check stops (`CheckError`), each stage's start (`enter`) | `error.rs` |
//!
//! [`Check::solid`] gives a [`Surface`] of the solid: shells turned outward (cavities
//! inward), collapsed and duplicate faces dropped (flat ones kept), holes capped, so that
//! [`crate::mass_properties`] of it gives the solid's volume, centroid and inertia.

mod assembled;
mod bodies;
mod connect;
mod crossings;
mod edges;
mod error;
mod euler;
mod faces;
mod holes;
mod loops;
mod nesting;
pub(crate) mod predicates;
mod report;
mod sheets;
mod shells;
mod solid;
mod verdict;
pub(crate) mod weld;

pub use assembled::check_assembled;
pub use bodies::Body;
pub(crate) use crossings::SpatialIndex;
pub use error::CheckError;
pub use nesting::Shell;
pub use report::{BodyOverlap, Check, Orientation};
pub use solid::{AsWoundView, Measured, Solid, SolidView};
pub use verdict::volume_warnings;

use crate::bvh::Bvh;
use crate::properties::Bounds;
use crate::vector::norm;
use crate::Surface;
use connect::connect;
use error::enter;
use loops::Loops;
use rayon::prelude::*;
use std::collections::BTreeSet;
use std::ops::Range;

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
    /// Keep the crossing search's spatial order and hierarchy of the triangles (about
    /// 34 bytes a triangle) for a body of the solid to take
    /// ([`crate::overlap::Body::of_solid`]) instead of building them again: what
    /// `intersect` asks for. Kept only with `intersections` and an exact weld.
    pub keep_spatial_index: bool,
}

impl Default for CheckOptions {
    fn default() -> Self {
        CheckOptions {
            weld: Weld::Auto,
            intersections: true,
            examples: 5,
            keep_spatial_index: false,
        }
    }
}

/// Checks the topology of `surface`, one body ([`check_in_stages`] takes several).
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
    check_in_stages(surface, &[], options, &())
}

/// What a long check is doing, for a progress display: its
/// [`Progress::stage`](crate::progress::Progress::stage) is called with the name of each
/// stage as it starts (`welding`, `finding edges`, `finding shells`, ...); a closure
/// taking the name will do.
pub use crate::progress::StageReport;

/// [`check`], calling `stage` as each stage starts, of a surface whose faces are the
/// separate `bodies` given (runs of faces covering them all, as a file's objects): nesting
/// pairs shells within a body only, and what lies across bodies is reported as
/// [`Check::overlapping_bodies`]. No runs: the whole surface is one body.
pub fn check_in_stages<S: Surface + ?Sized>(
    surface: &S,
    bodies: &[Range<usize>],
    options: &CheckOptions,
    stage: StageReport<'_>,
) -> Result<Check, CheckError> {
    enter(stage, "gathering faces")?;
    let loops = Loops::of(surface)?;
    enter(stage, "welding")?;
    // The corners' positions are needed for welding only (see `loops.rs`); the vertices
    // are at the same positions. Read as the f32 a file stored them in where the surface
    // has them (a binary STL): half the bytes, the same weld.
    // An indexed triangle mesh welds its positions, not its corners.
    let indexed = surface.indexed_triangles().filter(|(_, t)| loops.corner_count() == 3 * t.len());
    let exact = match indexed {
        Some((positions, triangles)) => weld::exact_indexed(positions, triangles),
        None => match loops.corners_f32(surface) {
            Some(corners) => weld_gathered(surface, &corners),
            None => weld_gathered(surface, &loops.corners(surface)),
        },
    };
    let diagonal = Bounds::of_points(&exact.positions).map_or(0.0, |b| norm(b.size()));
    Ok(match options.weld {
        Weld::Exact => analyse(surface, &loops, &exact, None, bodies, options, stage)?,
        Weld::Tolerance(t) => {
            let welded = exact.within(t);
            drop(exact);
            analyse(surface, &loops, &welded, Some(t), bodies, options, stage)?
        }
        Weld::Auto => {
            let exact_check = analyse(surface, &loops, &exact, None, bodies, options, stage)?;
            if exact_check.boundary_edges == 0 || diagonal == 0.0 {
                exact_check
            } else {
                enter(stage, "welding again within a tolerance")?;
                let t = AUTO_WELD * diagonal;
                let welded = exact.within(t);
                drop(exact);
                let welded = analyse(surface, &loops, &welded, Some(t), bodies, options, stage)?;
                if welded.boundary_edges < exact_check.boundary_edges {
                    welded
                } else {
                    exact_check
                }
            }
        }
    })
}

/// Welds the corners gathered from `surface`, once it is told that it will not be read
/// for a while: under an exact weld no later stage reads it (they read the welded
/// vertices, at the corners' positions), so a mapped file's pages need not stay in
/// memory beside the check's arrays (a binary STL's 50 bytes a triangle).
fn weld_gathered<S: Surface + ?Sized, C: weld::Corner>(surface: &S, corners: &[C]) -> weld::Welded {
    surface.release_pages();
    weld::exact(corners)
}

/// Checks the faces `loops` of `surface`, welded with `tolerance`: the stages in order.
fn analyse<S: Surface + ?Sized>(
    surface: &S,
    loops: &Loops,
    welded: &weld::Welded,
    tolerance: Option<f64>,
    bodies: &[Range<usize>],
    options: &CheckOptions,
    stage: StageReport<'_>,
) -> Result<Check, CheckError> {
    let faces = surface.face_count();
    enter(stage, "sorting out degenerate and duplicate faces")?;
    let classes = faces::classify(loops, welded);
    let kept = &classes.kept;

    // The connectivity analysis, then the crossing search: one after the other, so that
    // the edge table and the triangles in space (the two largest arrays of a check)
    // are never held at once. (Run side by side on 2 cores, a 5M-triangle check peaked
    // at 283–297 bytes a triangle, one after the other at 227–231; a 1M check takes
    // 0.54–0.57 s this way against 0.47–0.49 s.)
    let connected = match tolerance {
        // The corners' own positions, bit for bit, without reading the surface again.
        None => connect(&loops.welded_fans(welded), loops, welded, kept, stage)?,
        Some(_) => connect(surface, loops, welded, kept, stage)?,
    };
    let space = if options.intersections {
        enter(stage, "ordering triangles in space")?;
        let (triangles, bvh) = crossings::triangles_in_space(loops, &classes.spatial, welded);
        enter(stage, "finding crossings")?;
        let crossing = crossings::crossing_pairs(&triangles, &bvh);
        Some((triangles, bvh, crossing))
    } else {
        None
    };
    // Triangles (fans of kept faces) in spatial order, with their corners inline, and
    // a hierarchy over their boxes: only when something asks for them.
    let (triangles, bvh, crossing) = match space {
        Some((triangles, bvh, crossing)) => (triangles, bvh, Some(crossing)),
        None if connected.candidates.any() => {
            let (triangles, bvh) = crossings::triangles_in_space(loops, &classes.spatial, welded);
            (triangles, bvh, None)
        }
        None => (crossings::Triangles::default(), Bvh::default(), None),
    };
    let mut overlapping_shells = BTreeSet::new();
    enter(stage, "nesting shells")?;
    let mut containers = nesting::containers(
        &triangles,
        &bvh,
        &connected.shells,
        &connected.caps,
        &connected.candidates,
        &mut overlapping_shells,
    );
    let keep = options.keep_spatial_index && tolerance.is_none() && crossing.is_some();
    let spatial_index = if keep {
        Some(triangles.into_index(bvh))
    } else {
        drop((triangles, bvh));
        None
    };
    let crossings = crossing.map(|pairs| {
        crossings::face_pairs(
            pairs,
            &connected.shells.of_face,
            options.examples,
            &mut overlapping_shells,
        )
    });
    let body_of_shell = bodies::of_shells(bodies, &connected.shells, kept);
    let overlapping_bodies =
        bodies::split(&body_of_shell, &mut containers, &mut overlapping_shells);
    let roles = nesting::roles(
        &containers,
        &connected.shell_signed,
        &connected.shells,
        &connected.counts,
        &connected.caps.per_shell,
        kept,
        &connected.edge_counts.face_inconsistent,
    );
    let orientation = if roles.shells.is_empty() {
        None
    } else if roles.shells.iter().all(|s| s.wound_outward == Some(true)) {
        Some(Orientation::Outward)
    } else if roles.shells.iter().all(|s| s.wound_outward == Some(false)) {
        Some(Orientation::Inward)
    } else {
        Some(Orientation::Mixed)
    };

    enter(stage, "building the solid")?;
    let (flip, flip_shell, shell_of_face) =
        (&connected.shells.flip, &roles.flip_shell, &connected.shells.of_face);
    let face_flip: Vec<bool> = (0..faces)
        .into_par_iter()
        .map(|f| kept[f] && (flip[f] ^ flip_shell[shell_of_face[f] as usize]))
        .collect();
    let cap_flip: Vec<bool> =
        connected.caps.shell.iter().map(|&s| flip_shell[s as usize]).collect();
    let mut solid_vertices =
        Vec::with_capacity(welded.positions.len() + connected.caps.centres.len());
    solid_vertices.par_extend(welded.positions.par_iter().copied());
    solid_vertices.extend(connected.caps.centres);
    let mut solid = Solid::new(
        solid::Faces {
            kept,
            flip: &face_flip,
            shell: shell_of_face,
            corners: welded.corner_vertex.par_iter().copied().collect(),
            start: loops.start.par_iter().map(|&s| s as usize).collect(),
        },
        solid_vertices,
        solid::Caps {
            points: connected.caps.points,
            ids: connected.caps.ids,
            flip: &cap_flip,
            shell: &connected.caps.shell,
        },
        tolerance.is_none(),
    );

    let count = |flags: &[bool]| flags.par_iter().filter(|&&f| f).count();
    let kept_faces = count(kept);
    let closed = kept_faces > 0
        && connected.edge_counts.boundary == 0
        && connected.edge_counts.non_manifold == 0;
    solid.mark_balanced(closed && connected.edge_counts.consistently_oriented);
    Ok(Check {
        weld_tolerance: tolerance,
        vertices: connected.vertices.used,
        edges: connected.edges,
        faces,
        closed,
        boundary_edges: connected.edge_counts.boundary,
        boundary_loops: connected.caps.per_shell.iter().sum(),
        non_manifold_edges: connected.edge_counts.non_manifold,
        unpaired_at_non_manifold_edges: connected.unpaired,
        non_manifold_vertices: connected.vertices.non_manifold,
        degenerate_faces: (0..faces)
            .into_par_iter()
            .filter(|&f| classes.collapsed[f] || classes.flat[f])
            .count(),
        flat_faces: count(&classes.flat),
        duplicate_faces: count(&classes.duplicate),
        double_wall_faces: count(&classes.double_wall),
        consistently_oriented: connected.edge_counts.consistently_oriented,
        orientation,
        cavities: roles.shells.iter().filter(|s| s.cavity).count(),
        shells: roles.shells,
        overlapping_shells: overlapping_shells.into_iter().collect(),
        overlapping_bodies,
        self_intersections: crossings.as_ref().map(|c| c.self_intersections),
        intersection_examples: crossings.map(|c| c.examples).unwrap_or_default(),
        euler_characteristic: connected.vertices.used as i64 - connected.edges as i64
            + kept_faces as i64,
        volume: roles.volume,
        volume_uncertainty: connected.caps.volume_uncertainty,
        solid,
        spatial_index,
        object_of_shell: (!bodies.is_empty()).then_some(body_of_shell),
    })
}
