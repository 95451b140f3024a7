//! The volume of the union of several closed bodies, without a boolean mesh, as a
//! certified interval.
//!
//! # Bounds per cell
//! On a grid over the bodies, the column–clamp kernel gives every body's volume v_i in
//! every cell C and marks the cells whose closed box the body's surface meets (it
//! *touches* them). A body that does not touch C contains all of C or none of it. So:
//!
//! - if some body contains C without touching it, the union fills C: `|C|`;
//! - if at most one body touches C (and none fills it), the union in C is that body's
//!   volume there, exactly;
//! - otherwise C is *open*: `max_i v_i ≤ vol(∪ ∩ C) ≤ min(|C|, Σ_i v_i)` over the bodies
//!   touching C.
//!
//! # Refinement
//! Open cells are cut into 2×2×2 children and the same is done for each child, with the
//! kernel run on a 2×2×2 grid over the cell. The kernel needs, in each of the cell's
//! four child columns, every face of the column at or above the cell's bottom; but a
//! face wholly above the cell only adds its signed projected area over the child column
//! to every layer (× the layer's height): a 2D quantity (for a closed body, the faces
//! above a plane project to the body's cross-section there). So a cell carries, per
//! touching body, only its *list*, the faces whose boxes meet its box (widened by
//! 10⁻⁹ of a base cell, more than any rounding between the grids' units), and its
//! *field*, the signed projected area of the body's other faces above it, over a lattice
//! of fine squares of its footprint (2^[`MAX_DEPTH`] to a base cell's side: what the
//! quadrants of the deepest cells refined need). Every other face of the column lies
//! wholly below the cell or beside it and adds nothing. A child's list is the part of
//! its parent's list that meets it; its field is its parent's over its footprint plus,
//! for a lower child, the parent's listed faces wholly above it. A base column's cells
//! get theirs from one pass over its faces, so a level costs the faces
//! its cells meet, not the columns above them. Refinement goes on level by level while
//! the total gap Σ(upper − lower) exceeds the tolerance and refining shrinks it:
//! a cell whose children's gaps add up to more than [`STALL`] of its own (two surfaces
//! that touch or lie on each other, where every child still holds both) is not refined
//! further, and there are at most [`MAX_DEPTH`] levels of at most 2¹⁸ open cells each.
//!
//! Refinement only pays where it can meet the tolerance or close whole columns (a
//! column with an open leaf is resolved exactly whatever its leaves' bounds). So one open
//! base column in 8 (`policy::SAMPLE_EVERY`) is refined one level first; refinement goes
//! on (reusing the sample) when the open gap, shrunk [`MAX_DEPTH`] times by the sample's
//! ratio of children's gap to parents', would meet the tolerance, or when a quarter of
//! the sampled columns closed. Otherwise (surfaces crossing or lying on each other in
//! most open cells) the open columns go straight to exact resolution.
//!
//! # Exact resolution
//! What refinement leaves open is resolved exactly, one column of the base grid at a
//! time, since columns are independent in the column–clamp method. In a cell, the
//! union's boundary is the part of each body's surface outside all other bodies. Each
//! piece of a triangle in an open cell is split along its intersections with the other
//! touching bodies' triangles (the lines where their planes cross, and the edges of
//! triangles lying in its own plane) into convex sub-pieces that no other surface
//! crosses. A sub-piece of body i is kept when, for every other body j touching the cell:
//!
//! - it lies in the plane of a triangle of j and inside it (*coplanar*): kept if the two
//!   face the same way and i < j (two copies of one boundary: the first body keeps it),
//!   dropped if they face opposite ways (two bodies glued face to face: inside the union);
//! - otherwise its centroid is outside j: the vertical ray up from it crosses j's
//!   triangles in the column with signed crossings (±1 by the triangle's n_z) summing to
//!   0 (exact orientation predicates; a ray through an edge or vertex is decided by a
//!   fixed symbolic perturbation of the point, so each sheet counts once).
//!
//! A column's triangles are indexed in plan (uniform bins over its footprint; an open
//! cell's cutters one index per body): a ray tests only the triangles filed in its
//! point's bin, and a piece is cut only by the other bodies' triangles whose plan boxes
//! meet its own and which no edge of theirs separates from it in plan, so a column costs
//! about its triangles and the pieces they are cut into, not their product. A cutter's
//! corners are put on the sides of the piece's plane by exact orientation (a corner
//! shared with the piece's triangle is on it), so triangles that only touch the plane at
//! a common vertex, as the fans at two UV spheres' shared poles do, do not cut.
//!
//! The column–clamp integral of the kept pieces, together with the pieces of cells that
//! are not open (kept unless a body fills the cell), is the union's volume in each cell
//! of the column: exact up to rounding. The same resolution, applied to every column of
//! a given grid, gives [`union_cell_volumes`].
//!
//! # The intersection
//! Every stage takes a [`Rule`]: [`Rule::Intersection`] changes only the bounds of a
//! cell (`Tally::cell`: a body missing it settles it at 0; two touching bodies give
//! `max(0, Σ v_i − (t − 1)|C|) ≤ vol ≤ min_i v_i`), the keep rule of exact resolution
//! (a sub-piece is kept inside, not outside, the other bodies) and the grid (the bodies'
//! common box, with room); see [`super::intersection`].
//!
//! # Stages and files
//!
//! | stage | file |
//! | --- | --- |
//! | bounds per cell, each body's touched cells (kept from the kernel), faces binned by column | `bounds.rs` |
//! | a base column's open cells: lists and fields, one pass over its faces | `column.rs` |
//! | whether refinement pays: a sample refined one level | `policy.rs` |
//! | refinement of open cells | `refine.rs` |
//! | bins in plan over a column, for rays and cuts | `plan.rs` |
//! | exact resolution of open columns | `resolve.rs` |
//! | the frames a triangle is counted in, a column's kept pieces summed in a frame, every column resolved in one | `frames.rs` |
//! | the union's boundary: every column's kept pieces, in three frames ([`union_boundary`]) | `boundary.rs` |
//! | the union's volume in every cell of a given grid ([`union_cell_volumes`]) | `cells.rs` |
//! | the driver: base grid, levels, the interval, progress | `mod.rs` |
//!
//! # Honesty
//! The interval adds up exact columns, exact cells and the bounds of open leaves, and is
//! widened by `2⁻³⁶ · Σ_i ∫|n_z| dA_i · H` (H the grid's height) for floating-point
//! rounding: a column sum carries about `u · (terms)`, and this allowance is some 10⁵
//! times the largest such error seen in the tests.

mod boundary;
mod bounds;
mod cells;
mod column;
mod frames;
mod plan;
mod policy;
mod refine;
mod resolve;

pub use boundary::{union_boundary, union_boundary_with, UnionBoundary};
pub use cells::{union_cell_volumes, union_cell_volumes_with};
pub(crate) use frames::{counted_in, BoundaryTotal, Frame, Interface};
pub use refine::{MAX_DEPTH, STALL};
pub use resolve::COPLANAR_TOLERANCE;
pub(crate) use resolve::{KeptPiece, KeptPieces};

use super::{Grid, GridError};
use crate::accumulate::CompensatedSum;
use crate::progress::{Counter, Progress};
use crate::surface::Oriented;
use crate::{mass_properties, MassProperties, Point, Surface};
pub(crate) use bounds::Rule;
use bounds::{Bodies, Cell};
use frames::{boundary_pass, counted_columns, resolve_every_column};
use rayon::prelude::*;
use refine::{refine, OpenCell, Refined};

/// Open cells per refinement level at most: a level that would hold more is not made.
const MAX_OPEN: usize = 1 << 18;

/// Why a union cannot be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum UnionError {
    #[error("no bodies")]
    NoBodies,
    #[error(transparent)]
    Grid(#[from] GridError),
    /// Exact resolution could not settle some columns ([`union_boundary`]).
    #[error("the union's boundary could not be resolved in {columns} columns of its grid (volumes outside a cell's bounds, as bodies that are not solids give, or pieces cut into more than 32 sides even on finer columns), so its cut cells cannot be given")]
    Unresolved { columns: usize },
}

/// The union's volume: the certified interval `[lower, upper]`, and how it was found.
#[derive(Clone, Debug, PartialEq)]
pub struct UnionVolume {
    pub lower: f64,
    pub upper: f64,
    /// How many bodies.
    pub bodies: usize,
    /// Σ of the bodies' volumes (each |signed volume|).
    pub sum_of_volumes: f64,
    /// Cells cut into 2×2×2 children.
    pub cells_refined: usize,
    /// Open cells of the base grid resolved exactly (in their columns).
    pub cells_resolved_exactly: usize,
    /// Columns that could not be resolved (a piece cut into more than 32 sides, or
    /// resolved values outside a cell's bounds): their bounds stay in the interval.
    pub columns_unresolved: usize,
    /// The base grid.
    pub grid: Grid,
    /// Bodies wound inward, measured turned outward.
    pub flipped: Vec<usize>,
    /// Bodies that are not closed solids: some cell's volume of theirs left `[0, |C|]`
    /// by more than rounding (an open or self-overlapping surface). The per-cell bounds
    /// assume closed solids, so with any body listed here the interval is only ordered,
    /// not certified, and may exceed `sum_of_volumes`: callers should warn or refuse. A
    /// body not listed may still be open where its cell volumes happen to stay in range
    /// (a missing face on the grid's bottom plane adds nothing): this is a symptom found
    /// on the way, not a closedness check.
    pub bodies_not_solid: Vec<usize>,
}

impl UnionVolume {
    /// The midpoint of the interval.
    pub fn volume(&self) -> f64 {
        0.5 * (self.lower + self.upper)
    }
}

/// A grid of about `target` cubic-ish cells over `min..max`.
fn base_grid(min: Point, max: Point, target: usize) -> Result<Grid, GridError> {
    let size = [0, 1, 2].map(|a| max[a] - min[a]);
    let longest = size.iter().cloned().fold(0.0, f64::max);
    let volume: f64 = size.iter().map(|&s| s.max(longest * 1e-3)).product();
    let h = (volume / target as f64).cbrt();
    let counts = size.map(|s| ((s / h).ceil() as usize).clamp(1, 1024));
    Grid::from_bounds(min, max, counts)
}

/// The volume of the union of `bodies` (each a closed surface; one wound inward is
/// turned outward and listed in `flipped`), to within `tolerance` of the lower bound
/// where refinement and exact resolution allow. See the module docs.
///
/// ```
/// use meshvol::grid::union;
/// use meshvol::shapes::cuboid;
/// // Two 2×2×2 boxes overlapping in a unit cube: 8 + 8 − 1.
/// let a = cuboid([0.0; 3], [2.0; 3]);
/// let b = cuboid([1.0; 3], [3.0; 3]);
/// let u = union(&[a, b], 1e-9).unwrap();
/// assert!(u.lower <= 15.0 && 15.0 <= u.upper && u.upper - u.lower < 1e-8);
/// ```
pub fn union<S: Surface>(bodies: &[S], tolerance: f64) -> Result<UnionVolume, UnionError> {
    union_with(bodies, tolerance, &())
}

/// [`union`], telling `progress` its stages (`bounds`, one `refining` per level,
/// `resolving columns`) and, in each, the bodies, cells or columns done.
pub fn union_with<S: Surface>(
    bodies: &[S],
    tolerance: f64,
    progress: &dyn Progress,
) -> Result<UnionVolume, UnionError> {
    let properties: Vec<MassProperties> = bodies.iter().map(|b| mass_properties(b)).collect();
    combine(bodies, &properties, Rule::Union, tolerance, false, progress).map(|(u, _)| u)
}

/// The bodies as [`combine`] measures them: turned outward, with the box its grid
/// covers and what the interval's final clamp needs of their volumes.
struct Setup<'a, S> {
    oriented: Vec<Oriented<'a, S>>,
    flipped: Vec<usize>,
    sum_of_volumes: f64,
    largest: f64,
    smallest: f64,
    triangles: usize,
    min: Point,
    max: Point,
    /// No volume to find: no body encloses any, or (intersection) their boxes are apart.
    flat: bool,
}

/// The bodies as measured, from their mass properties (`properties[i]` of `bodies[i]`:
/// the volume's sign and size, the triangles, the box).
fn setup<'a, S: Surface>(
    bodies: &'a [S],
    properties: &[MassProperties],
    rule: Rule,
) -> Setup<'a, S> {
    let mut oriented = Vec::new();
    let mut flipped = Vec::new();
    let mut sum_of_volumes = CompensatedSum::default();
    let (mut largest, mut smallest) = (0.0f64, f64::INFINITY);
    let (mut min, mut max) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let (mut common_min, mut common_max) = ([f64::NEG_INFINITY; 3], [f64::INFINITY; 3]);
    let mut triangles = 0;
    for (i, body) in bodies.iter().enumerate() {
        let mp = &properties[i];
        sum_of_volumes.add(mp.signed_volume.abs());
        largest = largest.max(mp.signed_volume.abs());
        smallest = smallest.min(mp.signed_volume.abs());
        triangles += mp.triangles;
        if mp.signed_volume < 0.0 {
            flipped.push(i);
        }
        let (lo, hi) =
            mp.bounds.map_or(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]), |b| (b.min, b.max));
        for a in 0..3 {
            min[a] = min[a].min(lo[a]);
            max[a] = max[a].max(hi[a]);
            common_min[a] = common_min[a].max(lo[a]);
            common_max[a] = common_max[a].min(hi[a]);
        }
        oriented.push(Oriented::new(body, mp.signed_volume < 0.0));
    }
    if rule == Rule::Intersection {
        // The intersection lies in the bodies' common box: the grid covers it with room
        // on every side, so no piece of its boundary is on the grid's faces.
        (min, max) = (common_min, common_max);
        let longest = (0..3).map(|a| max[a] - min[a]).fold(0.0, f64::max);
        for a in 0..3 {
            let room = 1e-6 * longest;
            (min[a], max[a]) = (min[a] - room, max[a] + room);
        }
    }
    // Also true for no vertices at all (min = +∞), and for bodies whose boxes are apart.
    let flat = (0..3).any(|a| max[a] <= min[a] || max[a].is_nan() || min[a].is_nan())
        || (rule == Rule::Intersection && (0..3).any(|a| common_max[a] <= common_min[a]));
    Setup {
        oriented,
        flipped,
        sum_of_volumes: sum_of_volumes.value(),
        largest,
        smallest,
        triangles,
        min,
        max,
        flat,
    }
}

impl<S> Setup<'_, S> {
    /// The base grid: about one cell per triangle, between 2¹⁵ and 2¹⁸ cells.
    fn grid(&self) -> Result<Grid, GridError> {
        base_grid(self.min, self.max, self.triangles.clamp(1 << 15, 1 << 18))
    }
}

/// The union's or the intersection's volume (module docs; `intersect` for the
/// intersection's bounds and grid) and, with `boundary`, the sums of its boundary's
/// pieces kept in every column (moments and interface, `frames::BoundarySums`; `None` where a
/// column fails to resolve, and for no volume: then the volume is 0).
pub(crate) fn combine<S: Surface>(
    bodies: &[S],
    properties: &[MassProperties],
    rule: Rule,
    tolerance: f64,
    boundary: bool,
    progress: &dyn Progress,
) -> Result<(UnionVolume, Option<(Point, BoundaryTotal)>), UnionError> {
    if bodies.is_empty() {
        return Err(UnionError::NoBodies);
    }
    let setup = setup(bodies, properties, rule);
    let (min, max) = (setup.min, setup.max);
    let Setup { sum_of_volumes, largest, smallest, .. } = setup;
    if setup.flat {
        let grid = Grid::new([0.0; 3], [1.0; 3], [1, 1, 1])?;
        return Ok((
            UnionVolume {
                lower: 0.0,
                upper: 0.0,
                bodies: bodies.len(),
                sum_of_volumes,
                cells_refined: 0,
                cells_resolved_exactly: 0,
                columns_unresolved: 0,
                grid,
                flipped: setup.flipped,
                bodies_not_solid: Vec::new(),
            },
            None,
        ));
    }
    // The projected area of the faces that meet the grid, for the rounding allowance.
    let mut projected = 0.0;
    for body in bodies {
        for f in 0..body.face_count() {
            body.fan(f, |a, b, c| {
                let meets = (0..3).all(|k| {
                    a[k].min(b[k]).min(c[k]) <= max[k] && a[k].max(b[k]).max(c[k]) >= min[k]
                });
                if meets {
                    projected +=
                        ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs() * 0.5;
                }
            });
        }
    }
    let grid = setup.grid()?;
    let allowance = projected * (max[2] - min[2]) * 2f64.powi(-36);
    let flipped = setup.flipped;
    let model = Bodies::new(setup.oriented, rule, grid, progress)?;
    let [_, _, nz] = grid.counts;
    let columns = grid.counts[0] * grid.counts[1];

    // Per base column: exact part and the open leaves' bounds.
    let mut exact = vec![0.0; columns];
    let mut lower = vec![0.0; columns];
    let mut upper = vec![0.0; columns];
    let mut level = Vec::new();
    let mut open_columns = Vec::new();
    let mut cells_resolved_exactly_first = 0;
    for c in 0..columns {
        let (i, j) = (c / grid.counts[1], c % grid.counts[1]);
        let mut has_open = false;
        for k in 0..nz {
            match model.cell(c * nz + k) {
                Cell::Exact(v) => exact[c] += v,
                Cell::Open { lower: l, upper: u } => {
                    has_open = true;
                    lower[c] += l;
                    upper[c] += u;
                    // Its parts are found when it is refined (`Bodies::open_cells`).
                    let at = [i as f64, j as f64, k as f64];
                    let parts = Vec::new();
                    level.push(OpenCell { column: c, at, level: 0, parts, lower: l, upper: u });
                }
            }
        }
        if has_open {
            open_columns.push(c);
        }
    }
    // With the boundary wanted, every column is resolved anyway (its kept pieces are
    // the moments' and the interface's): those resolutions settle the open columns, and
    // refinement, which only narrows what resolution then closes, is skipped. Where a
    // column fails to resolve, the interval is found as without the boundary.
    let mut sums = None;
    if boundary {
        if let Some((columns, total)) = resolve_every_column(&model, Frame::Identity, progress) {
            for (c, (cells, resolved)) in columns.into_iter().enumerate() {
                if upper[c] > lower[c] {
                    let mut s = CompensatedSum::default();
                    cells.iter().for_each(|&v| s.add(v));
                    exact[c] = s.value();
                    lower[c] = 0.0;
                    upper[c] = 0.0;
                    cells_resolved_exactly_first += resolved;
                }
            }
            level.clear();
            sums = Some(total);
        }
    }
    let total = |exact: &[f64], bound: &[f64]| {
        let mut s = CompensatedSum::default();
        exact.iter().chain(bound).for_each(|&x| s.add(x));
        s.value()
    };
    let mut cells_refined = 0;
    let mut depth = 0;
    // The base level's sampled columns, refined before deciding whether to refine.
    let mut sampled = Vec::new();
    while !level.is_empty() && depth < MAX_DEPTH && 8 * level.len() <= MAX_OPEN {
        let gap = total(&upper, &[]) - total(&lower, &[]);
        let low = total(&exact, &lower);
        if gap <= tolerance * low.abs() {
            break;
        }
        if depth == 0 {
            let pays;
            (sampled, pays) = policy::sample(&model, &open_columns, gap, tolerance * low.abs())?;
            if !pays {
                break;
            }
        }
        progress.stage("refining");
        let done = Counter::new(progress, level.len());
        let refine_all = |cells: &[OpenCell]| -> Result<Vec<Refined>, GridError> {
            let refined =
                cells.iter().map(|cell| refine(&model.bodies, model.rule, &grid, cell)).collect();
            done.add(cells.len());
            refined
        };
        let per_chunk: Vec<Result<Vec<Refined>, GridError>> = if depth == 0 {
            // The base level, column by column: each column's cells get their parts
            // from one pass over its faces; the sample's are taken as they are.
            let sampled = std::mem::take(&mut sampled);
            open_columns
                .par_iter()
                .zip(sampled.into_par_iter())
                .map(|(&c, known)| match known {
                    Some(refined) => {
                        done.add(refined.len());
                        Ok(refined)
                    }
                    None => refine_all(&model.open_cells(c)),
                })
                .collect()
        } else {
            level.par_chunks(64).map(refine_all).collect()
        };
        let per_chunk: Vec<Vec<Refined>> = per_chunk.into_iter().collect::<Result<_, _>>()?;
        let refined = per_chunk.into_iter().flatten();
        cells_refined += level.len();
        for cell in &level {
            lower[cell.column] -= cell.lower;
            upper[cell.column] -= cell.upper;
        }
        let mut next = Vec::new();
        for r in refined {
            exact[r.column] += r.exact;
            for child in r.open {
                lower[child.column] += child.lower;
                upper[child.column] += child.upper;
                if !r.stalled {
                    next.push(child);
                }
            }
        }
        level = next;
        depth += 1;
    }
    let gap = total(&upper, &[]) - total(&lower, &[]);
    let low = total(&exact, &lower);
    let (mut cells_resolved_exactly, mut columns_unresolved) = (cells_resolved_exactly_first, 0);
    if gap > tolerance * low.abs() {
        // Resolve every column that still holds an open leaf.
        let targets: Vec<usize> = (0..columns).filter(|&c| upper[c] > lower[c]).collect();
        progress.stage("resolving columns");
        let done = Counter::new(progress, targets.len());
        let results: Vec<Option<(Vec<f64>, usize)>> = targets
            .par_iter()
            .map(|&c| {
                let result = model.exact_column(c);
                done.add(1);
                result
            })
            .collect();
        for (&c, result) in targets.iter().zip(results) {
            match result {
                Some((cells, resolved)) => {
                    let mut s = CompensatedSum::default();
                    cells.iter().for_each(|&v| s.add(v));
                    exact[c] = s.value();
                    lower[c] = 0.0;
                    upper[c] = 0.0;
                    cells_resolved_exactly += resolved;
                }
                None => columns_unresolved += 1,
            }
        }
    }
    let (mut low, mut high) = (total(&exact, &lower), total(&exact, &upper));
    if model.not_solid.is_empty() {
        // For solids the union holds the largest body and is held by their sum, the
        // intersection is held by the smallest: facts that bound the interval whatever
        // its cells' rounding.
        match rule {
            Rule::Union => {
                low = low.max(largest);
                high = high.min(sum_of_volumes);
            }
            Rule::Intersection => {
                low = low.max(0.0);
                high = high.min(smallest);
            }
        }
    }
    // Ordered for any input: per-column bounds are updated in place (rounding), and a
    // body that is not a solid makes the bounds meaningless (then it is listed).
    let (low, high) = (low.min(high), low.max(high));
    let volume = UnionVolume {
        lower: low - allowance,
        upper: high + allowance,
        bodies: bodies.len(),
        sum_of_volumes,
        cells_refined,
        cells_resolved_exactly,
        columns_unresolved,
        grid,
        flipped,
        bodies_not_solid: model.not_solid,
    };
    Ok((volume, sums.map(|s| (grid.origin, s))))
}

/// [`boundary_pass`] over the combination of `bodies` (already turned into `frame`) on
/// their own base grid, without the volume's refinement: `None` for no volume or where
/// a column fails to resolve.
pub(crate) fn boundary_in_frame<S: Surface>(
    bodies: &[S],
    properties: &[MassProperties],
    rule: Rule,
    frame: Frame,
    progress: &dyn Progress,
) -> Result<Option<BoundaryTotal>, UnionError> {
    let setup = setup(bodies, properties, rule);
    if setup.flat {
        return Ok(None);
    }
    let Some(grid) = counted_columns(bodies, frame, &setup.grid()?)? else {
        return Ok(Some(BoundaryTotal::default()));
    };
    let model = Bodies::new(setup.oriented, rule, grid, progress)?;
    Ok(boundary_pass(&model, frame, progress))
}
