//! Cut and fill between two height fields: the volume of the existing surface above a
//! design (cut) and below it (fill), over the plan where both are defined, exactly for
//! piecewise-linear surfaces.
//!
//! # Math
//! With e(x, y) the existing surface, g(x, y) the design and F their common footprint,
//!
//! ```text
//! cut  = ∫_F max(e − g, 0) dA        area_cut  = |{e > g} ∩ F|
//! fill = ∫_F max(g − e, 0) dA        area_fill = |{e < g} ∩ F|
//! ```
//!
//! Both surfaces are triangulations ([`Terrain`]: each triangle's plan, checked not to
//! overlap another's). Overlay their plans: every pair of an existing and a design
//! triangle that overlap (found in time near-linear in the triangles and the pairs, [`pairs`]: by
//! sectors around shared corners, else by tree queries) gives a convex *piece*,
//! one triangle clipped by the other's three edges (Sutherland–Hodgman). On a piece
//! both surfaces are linear, so d = e − g is linear too: its value at each corner comes
//! from the corner's barycentric weights in each triangle. Cut the piece at the line
//! d = 0; on each part ∫ d dA is exact from a fan of triangles, each contributing its
//! area times the mean of its corners' d. The pieces tile F, so the sums are the
//! integrals, with no sampling: only rounding. A design level z = Z needs no overlay:
//! the pieces are the existing triangles, d = z − Z.
//!
//! Per-cell values ([`cell_cut_fill`]) cut each piece further along the cell lines of a
//! plan grid before integrating, so they add up to the totals up to rounding.
//!
//! Coordinates are taken relative to the centre of the common box, which keeps the
//! digits of terrains far from the origin (map coordinates). Pieces are summed in fixed
//! tasks (of shared points or query triangles, or of triangles) combined in order, with compensated sums: the
//! same bits at any thread count.
//!
//! ```
//! use meshvol::cutfill::{cut_fill, Design, Terrain};
//! use meshvol::Mesh;
//! // The unit square at height 1, against the design z = x: cut ∫ (1 − x) = 1/2.
//! let v = vec![[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]];
//! let flat = Mesh::from_triangles(v, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
//! let v = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 0.0]];
//! let ramp = Mesh::from_triangles(v, vec![[0, 1, 3], [1, 2, 3]]).unwrap();
//! let (existing, design) = (Terrain::new(&flat).unwrap(), Terrain::new(&ramp).unwrap());
//! let r = cut_fill(&existing, Design::Surface(&design));
//! assert!((r.cut - 0.5).abs() < 1e-15 && r.fill == 0.0 && r.area_cut == 1.0);
//! ```

mod cells;
mod overlaps;
mod pairs;
mod piece;
mod plan;
mod sectors;
mod terrain;
#[cfg(test)]
mod tests;

pub use cells::{
    cell_cut_fill, cell_cut_fill_with, CellCutFill, PlanGrid, PlanGridError, MAX_CELLS,
};
pub use terrain::{Terrain, TerrainError};

use crate::accumulate::ordered_reduce;
use crate::progress::{Counter, Progress};
use pairs::Pairs;
use piece::{amounts, Piece, Sums};
use plan::{box_union, Facet, PlanBox};
use std::ops::Range;

/// What the existing surface is compared with.
#[derive(Clone, Copy, Debug)]
pub enum Design<'a> {
    /// A second surface.
    Surface(&'a Terrain),
    /// The plane z = level.
    Level(f64),
}

/// Cut and fill over the common footprint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutFill {
    /// ∫ max(existing − design, 0) dA.
    pub cut: f64,
    /// ∫ max(design − existing, 0) dA.
    pub fill: f64,
    /// The area where the existing surface is above the design.
    pub area_cut: f64,
    /// The area where it is below.
    pub area_fill: f64,
    /// The area of the common footprint.
    pub footprint_area: f64,
    /// The box of the common footprint, [min, max] of x and y; `None` when empty.
    pub footprint_bounds: Option<[[f64; 2]; 2]>,
}

/// Triangles per parallel task against a level.
const FACET_CHUNK: usize = 4096;

/// The pieces of the common footprint, produced task by task.
struct Overlay<'a> {
    existing: &'a Terrain,
    /// The coordinates' origin (see the module docs).
    origin: [f64; 2],
    design: Overlaid<'a>,
}

enum Overlaid<'a> {
    Level(f64),
    Surface { design: &'a Terrain, pairs: Box<Pairs> },
}

impl<'a> Overlay<'a> {
    /// `None` when the footprints' boxes do not overlap with some area.
    fn new(existing: &'a Terrain, design: Design<'a>) -> Option<Overlay<'a>> {
        let ours = existing.plan_bounds()?;
        let (common, design) = match design {
            Design::Level(z) => (ours, Overlaid::Level(z)),
            Design::Surface(design) => {
                let theirs = design.plan_bounds()?;
                let common = [
                    [ours[0][0].max(theirs[0][0]), ours[0][1].max(theirs[0][1])],
                    [ours[1][0].min(theirs[1][0]), ours[1][1].min(theirs[1][1])],
                ];
                if !(common[0][0] < common[1][0] && common[0][1] < common[1][1]) {
                    return None;
                }
                let pairs = Pairs::new(&existing.facets, &design.facets);
                (common, Overlaid::Surface { design, pairs: Box::new(pairs) })
            }
        };
        let origin = [0, 1].map(|a| 0.5 * (common[0][a] + common[1][a]));
        Some(Overlay { existing, origin, design })
    }

    /// Tasks (triangles, or [`Pairs`]' tasks) and how many make a chunk.
    fn tasks(&self) -> (usize, usize) {
        match &self.design {
            Overlaid::Level(_) => (self.existing.facets.len(), FACET_CHUNK),
            Overlaid::Surface { pairs, .. } => (pairs.task_count(), 1),
        }
    }

    /// A facet's corners relative to the origin, d = 0.
    fn local(&self, f: &Facet) -> [[f64; 3]; 3] {
        f.xy.map(|p| [p[0] - self.origin[0], p[1] - self.origin[1], 0.0])
    }

    /// Calls `each` with every piece of the tasks in `tasks`, in a fixed order.
    fn pieces(&self, tasks: Range<usize>, mut each: impl FnMut(&Piece)) {
        match &self.design {
            Overlaid::Level(level) => {
                for f in &self.existing.facets[tasks] {
                    let [a, b, c] = self.local(f);
                    let d = f.z.map(|z| z - level);
                    let piece =
                        Piece::triangle([a[0], a[1], d[0]], [b[0], b[1], d[1]], [c[0], c[1], d[2]]);
                    each(&piece);
                }
            }
            Overlaid::Surface { design, pairs } => {
                let (ours, theirs) = (&self.existing.facets, &design.facets);
                let mut tried = 0;
                for task in tasks {
                    pairs.pairs(task, ours, theirs, &mut tried, |e, g| {
                        if let Some(piece) = self.clip(&ours[e], &theirs[g]) {
                            each(&piece);
                        }
                    });
                }
            }
        }
    }

    /// The piece where triangles `e` (existing) and `g` (design) overlap, with d at its
    /// corners; `None` when they do not.
    fn clip(&self, e: &Facet, g: &Facet) -> Option<Piece> {
        let corners = self.local(e);
        let mut piece = Piece::triangle(corners[0], corners[1], corners[2]);
        let edges = self.local(g);
        for k in 0..3 {
            let (p, q) = (edges[k], edges[(k + 1) % 3]);
            piece = piece.keep(|x| (q[0] - p[0]) * (x[1] - p[1]) - (q[1] - p[1]) * (x[0] - p[0]));
            if piece.is_empty() {
                return None;
            }
        }
        for corner in piece.corners_mut() {
            corner[2] = height(&corners, &e.z, *corner) - height(&edges, &g.z, *corner);
        }
        Some(piece)
    }
}

/// The height at `x` of the plane through the triangle `t` (local corners) at heights
/// `z`: the corners' heights weighted by the areas of the triangles `x` makes with the
/// opposite edges (barycentric weights; they sum to the triangle's area wherever `x` is).
fn height(t: &[[f64; 3]; 3], z: &[f64; 3], x: [f64; 3]) -> f64 {
    let w =
        |p: [f64; 3], q: [f64; 3]| (p[0] - x[0]) * (q[1] - x[1]) - (p[1] - x[1]) * (q[0] - x[0]);
    let weights = [w(t[1], t[2]), w(t[2], t[0]), w(t[0], t[1])];
    let total = weights[0] + weights[1] + weights[2];
    (weights[0] * z[0] + weights[1] * z[1] + weights[2] * z[2]) / total
}

/// The box of a piece's corners, moved back by `origin`.
fn piece_box(piece: &Piece, origin: [f64; 2]) -> PlanBox {
    let mut b = [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]];
    for c in piece.corners() {
        for a in 0..2 {
            b[0][a] = b[0][a].min(c[a] + origin[a]);
            b[1][a] = b[1][a].max(c[a] + origin[a]);
        }
    }
    b
}

fn union_box(a: Option<PlanBox>, b: Option<PlanBox>) -> Option<PlanBox> {
    match (a, b) {
        (Some(a), Some(b)) => Some(box_union(&a, &b)),
        (a, b) => a.or(b),
    }
}

/// Cut and fill of `existing` against `design` over their common footprint.
pub fn cut_fill(existing: &Terrain, design: Design<'_>) -> CutFill {
    cut_fill_with(existing, design, &())
}

/// [`cut_fill`], telling `progress` its stages and the tasks (of pairs of triangles,
/// or of triangles against a level) done.
pub fn cut_fill_with(existing: &Terrain, design: Design<'_>, progress: &dyn Progress) -> CutFill {
    let empty = CutFill {
        cut: 0.0,
        fill: 0.0,
        area_cut: 0.0,
        area_fill: 0.0,
        footprint_area: 0.0,
        footprint_bounds: None,
    };
    progress.stage("pairing the surfaces' triangles");
    let Some(overlay) = Overlay::new(existing, design) else {
        return empty;
    };
    let (tasks, chunk) = overlay.tasks();
    progress.stage("integrating cut and fill");
    let done = Counter::new(progress, tasks);
    let reduced = ordered_reduce(
        tasks,
        chunk,
        |range| {
            let mut sums = Sums::default();
            let mut bounds = None;
            let units = range.len();
            overlay.pieces(range, |piece| {
                let a = amounts(piece);
                sums.add(&a);
                // Triangles that only touch clip to slivers of no area (or rounding's):
                // they are not footprint.
                if a[4] > 0.0 {
                    bounds = union_box(bounds, Some(piece_box(piece, overlay.origin)));
                }
            });
            done.add(units);
            (sums, bounds)
        },
        |total, (sums, bounds)| {
            total.0.merge(&sums);
            total.1 = union_box(total.1, bounds);
        },
    );
    let Some((sums, bounds)) = reduced else {
        return empty;
    };
    CutFill {
        cut: sums.cut.value(),
        fill: sums.fill.value(),
        area_cut: sums.area_cut.value(),
        area_fill: sums.area_fill.value(),
        footprint_area: sums.footprint.value(),
        footprint_bounds: bounds,
    }
}
