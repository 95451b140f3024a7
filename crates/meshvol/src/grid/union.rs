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
//! kernel run on a 2×2×2 grid over the cell and only the triangles of the touching bodies
//! that lie in the cell's column at or above its bottom (those below add nothing to any
//! layer of it; those above add their projected area). Refinement goes on level by level
//! while the total gap Σ(upper − lower) exceeds the tolerance and refining shrinks it:
//! a cell whose children's gaps add up to more than [`STALL`] of its own (two surfaces
//! that touch or lie on each other, where every child still holds both) is not refined
//! further, and there are at most [`MAX_DEPTH`] levels of at most 2¹⁸ open cells each.
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
//! The column–clamp integral of the kept pieces, together with the pieces of cells that
//! are not open (kept unless a body fills the cell), is the union's volume in each cell
//! of the column: exact up to rounding. The same resolution, applied to every column of
//! a given grid, gives [`union_cell_volumes`].
//!
//! # Honesty
//! The interval adds up exact columns, exact cells and the bounds of open leaves, and is
//! widened by `2⁻³⁶ · Σ_i ∫|n_z| dA_i · H` (H the grid's height) for floating-point
//! rounding: a column sum carries about `u · (terms)`, and this allowance is some 10⁵
//! times the largest such error seen in the tests.

use super::cells::{
    add_faces, cell_volumes, cover, finish_column, for_each_piece, sweep_layers, LayerSink, Piece,
    Units,
};
use super::clip::Polygon;
use super::{Grid, GridError};
use crate::accumulate::CompensatedSum;
use crate::surface::Oriented;
use crate::{mass_properties, Point, Surface};
use rayon::prelude::*;
use robust::{orient2d, orient3d, Coord, Coord3D};

/// A cell whose children's gaps add up to more than this fraction of its own gap is not
/// refined further: a curve where two surfaces cross leaves about a quarter of the gap
/// in the children, two surfaces lying on each other about half.
pub const STALL: f64 = 0.4;

/// Refinement levels at most: each halves the cell size.
pub const MAX_DEPTH: usize = 4;

/// Open cells per refinement level at most: a level that would hold more is not made.
const MAX_OPEN: usize = 1 << 18;

/// A body whose volume in a cell leaves `[−s·|C|, (1 + s)·|C|]` for this `s` is not a
/// closed solid: rounding in a valid solid's column sums stays some 10⁶ times below it.
const SOLID_SLACK: f64 = 1e-9;

/// Sub-pieces have at most this many vertices (a piece cut by many lines).
const SUB: usize = 32;

/// Why a union cannot be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum UnionError {
    #[error("no bodies")]
    NoBodies,
    #[error(transparent)]
    Grid(#[from] GridError),
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

/// Faces per column (closed footprint): column c's faces are
/// `faces[offsets[c]..offsets[c + 1]]`, in face order.
struct ColumnBins {
    offsets: Vec<usize>,
    faces: Vec<u32>,
}

impl ColumnBins {
    fn new<S: Surface + ?Sized>(surface: &S, grid: &Grid) -> ColumnBins {
        let units = Units::new(grid);
        let [nx, ny, _] = grid.counts;
        let covers: Vec<(usize, usize, usize, usize)> = (0..surface.face_count())
            .into_par_iter()
            .map(|f| {
                let (lo, hi) = face_box(surface, f, |p| units.map(p));
                let (i0, i1) = cover(lo[0], hi[0], nx, true);
                let (j0, j1) = cover(lo[1], hi[1], ny, true);
                (i0, i1, j0, j1)
            })
            .collect();
        let mut offsets = vec![0usize; nx * ny + 1];
        for &(i0, i1, j0, j1) in &covers {
            for i in i0..i1 {
                for j in j0..j1 {
                    offsets[i * ny + j + 1] += 1;
                }
            }
        }
        for c in 0..nx * ny {
            offsets[c + 1] += offsets[c];
        }
        let mut fill = offsets.clone();
        let mut faces = vec![0u32; offsets[nx * ny]];
        for (f, &(i0, i1, j0, j1)) in covers.iter().enumerate() {
            for i in i0..i1 {
                for j in j0..j1 {
                    faces[fill[i * ny + j]] = f as u32;
                    fill[i * ny + j] += 1;
                }
            }
        }
        ColumnBins { offsets, faces }
    }

    fn column(&self, c: usize) -> &[u32] {
        &self.faces[self.offsets[c]..self.offsets[c + 1]]
    }
}

/// The bounding box of face `f`'s vertices, mapped by `map`.
fn face_box<S: Surface + ?Sized>(
    surface: &S,
    f: usize,
    map: impl Fn(Point) -> Point,
) -> (Point, Point) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    surface.fan(f, |a, b, c| {
        for p in [a, b, c] {
            let u = map(p);
            for k in 0..3 {
                lo[k] = lo[k].min(u[k]);
                hi[k] = hi[k].max(u[k]);
            }
        }
    });
    (lo, hi)
}

/// What the union is in one cell.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Cell {
    /// Exactly this volume.
    Exact(f64),
    /// Two or more bodies touch it: the union lies in `[lower, upper]`.
    Open { lower: f64, upper: f64 },
}

/// Classifies a cell from the bodies' volumes in it and whether they touch it.
fn classify(cell_volume: f64, bodies: impl Iterator<Item = (f64, bool)>) -> Cell {
    let (mut touching, mut max, mut sum, mut full) = (0, 0.0f64, 0.0, false);
    for (v, touches) in bodies {
        // A closed solid's volume in a cell lies in [0, |C|]; clamped, max ≤ Σ holds and
        // the bounds stay ordered whatever the input (`UnionVolume::bodies_not_solid`).
        let v = v.max(0.0).min(cell_volume);
        if touches {
            touching += 1;
            max = max.max(v);
            sum += v;
        } else if v > 0.5 * cell_volume {
            full = true;
        }
    }
    if full {
        Cell::Exact(cell_volume)
    } else if touching <= 1 {
        Cell::Exact(sum)
    } else {
        Cell::Open { lower: max.min(cell_volume), upper: sum.min(cell_volume) }
    }
}

/// The bodies on a grid: per-cell facts from the kernel, and faces binned by column.
struct Bodies<'a, S: ?Sized> {
    bodies: Vec<Oriented<'a, S>>,
    grid: Grid,
    units: Units,
    /// Per cell: some body fills it without touching it.
    full: Vec<bool>,
    /// Per cell: bodies touching it (2 means 2 or more).
    touching: Vec<u8>,
    /// Per cell: max and Σ of the touching bodies' volumes.
    max: Vec<f64>,
    sum: Vec<f64>,
    bins: Vec<ColumnBins>,
    /// Bodies with a cell volume outside `[0, |C|]` beyond [`SOLID_SLACK`].
    not_solid: Vec<usize>,
}

impl<'a, S: Surface + ?Sized> Bodies<'a, S> {
    fn new(bodies: Vec<Oriented<'a, S>>, grid: Grid) -> Result<Self, GridError> {
        let cells = grid.cell_count();
        let cell_volume = grid.cell_volume();
        let mut full = vec![false; cells];
        let mut touching = vec![0u8; cells];
        let mut max = super::cells::zeroed(cells)?;
        let mut sum = super::cells::zeroed(cells)?;
        let mut touched = vec![0u8; cells];
        let mut not_solid = Vec::new();
        // Rounding leaves a solid's cell volumes within about 1e-15 |C| of [0, |C|].
        let slack = SOLID_SLACK * cell_volume;
        for (b, body) in bodies.iter().enumerate() {
            touched.fill(0);
            let mut v = cell_volumes(body, &grid, Some(&mut touched))?;
            if v.iter().any(|&x| !(-slack..=cell_volume + slack).contains(&x)) {
                not_solid.push(b);
            }
            // Clamped, the bounds below stay ordered (max ≤ Σ) for any input.
            // (max/min also send NaN to 0.)
            v.iter_mut().for_each(|x| *x = x.max(0.0).min(cell_volume));
            for c in 0..cells {
                if touched[c] != 0 {
                    touching[c] = (touching[c] + 1).min(2);
                    max[c] = max[c].max(v[c]);
                    sum[c] += v[c];
                } else if v[c] > 0.5 * cell_volume {
                    full[c] = true;
                }
            }
        }
        let bins = bodies.iter().map(|b| ColumnBins::new(b, &grid)).collect();
        let units = Units::new(&grid);
        Ok(Bodies { bodies, grid, units, full, touching, max, sum, bins, not_solid })
    }

    fn cell(&self, c: usize) -> Cell {
        let cell_volume = self.grid.cell_volume();
        if self.full[c] {
            Cell::Exact(cell_volume)
        } else if self.touching[c] <= 1 {
            Cell::Exact(self.sum[c])
        } else {
            Cell::Open { lower: self.max[c].min(cell_volume), upper: self.sum[c].min(cell_volume) }
        }
    }

    /// For column `c`: which bodies touch each layer (`touch[b * nz + k]`).
    fn column_touches(&self, c: usize) -> Vec<bool> {
        let [nx, ny, nz] = self.grid.counts;
        let mut touch = vec![false; self.bodies.len() * nz];
        for (b, body) in self.bodies.iter().enumerate() {
            for &f in self.bins[b].column(c) {
                body.fan(f as usize, |p, q, r| {
                    let t =
                        Piece::triangle(self.units.map(p), self.units.map(q), self.units.map(r));
                    for_each_piece(&t, [nx, ny], &(c..c + 1), true, |_, piece| {
                        let z = piece.range(2);
                        let (k0, k1) = cover(z.0, z.1, nz, true);
                        touch[b * nz + k0..b * nz + k1].fill(true);
                    });
                });
            }
        }
        touch
    }

    /// The union's volume in each cell of column `c`, exactly (module docs), and how
    /// many open cells that resolved; `None` where a piece needed more than [`SUB`]
    /// sides or a resolved value falls outside its cell's bounds.
    fn exact_column(&self, c: usize) -> Option<(Vec<f64>, usize)> {
        let [nx, ny, nz] = self.grid.counts;
        let (i, j) = (c / ny, c % ny);
        let touch = self.column_touches(c);
        let m = self.bodies.len();
        let base = c * nz;
        // Open layers: their touching bodies, cutters and ray triangles.
        let mut open: Vec<Option<OpenLayer>> = (0..nz).map(|_| None).collect();
        let mut resolved = 0;
        for (k, slot) in open.iter_mut().enumerate() {
            if self.full[base + k] || self.touching[base + k] < 2 {
                continue;
            }
            let bodies: Vec<usize> = (0..m).filter(|&b| touch[b * nz + k]).collect();
            if bodies.len() < 2 {
                continue;
            }
            let lo = [i as f64, j as f64, k as f64];
            let mut cutters = Vec::new();
            for &b in &bodies {
                for &f in self.bins[b].column(c) {
                    self.bodies[b].fan(f as usize, |p, q, r| {
                        let unit = [p, q, r].map(|x| self.units.map(x));
                        let meets = (0..3).all(|a| {
                            let (mn, mx) = (
                                unit.iter().map(|v| v[a]).fold(f64::INFINITY, f64::min),
                                unit.iter().map(|v| v[a]).fold(f64::NEG_INFINITY, f64::max),
                            );
                            mn <= lo[a] + 1.0 && mx >= lo[a]
                        });
                        if meets {
                            cutters.push(Cutter { body: b, world: [p, q, r], unit });
                        }
                    });
                }
            }
            *slot = Some(OpenLayer { bodies, cutters });
            resolved += 1;
        }
        // Ray triangles per body: the column's non-vertical triangles.
        let rays: Vec<Vec<[Point; 3]>> = (0..m)
            .map(|b| {
                let mut tris = Vec::new();
                for &f in self.bins[b].column(c) {
                    self.bodies[b].fan(f as usize, |p, q, r| {
                        let t = [p, q, r].map(|x| self.units.map(x));
                        if orient2d(xy(t[0]), xy(t[1]), xy(t[2])) != 0.0 {
                            tris.push(t);
                        }
                    });
                }
                tris
            })
            .collect();
        let mut direct = vec![0.0; nz];
        let mut area = vec![0.0; nz + 1];
        let mut failed = false;
        for (b, body) in self.bodies.iter().enumerate() {
            for &f in self.bins[b].column(c) {
                body.fan(f as usize, |p, q, r| {
                    let unit = [p, q, r].map(|x| self.units.map(x));
                    let t = Piece::triangle(unit[0], unit[1], unit[2]);
                    if t.area() == 0.0 {
                        return;
                    }
                    for_each_piece(&t, [nx, ny], &(c..c + 1), false, |_, piece| {
                        let mut sink = KeptSink {
                            owner: self,
                            column: c,
                            body: b,
                            triangle: [p, q, r],
                            unit,
                            open: &open,
                            rays: &rays,
                            direct: &mut direct,
                            area: &mut area,
                            failed: &mut failed,
                        };
                        sweep_layers(piece, piece.range(2), nz, &mut sink);
                    });
                });
            }
        }
        if failed {
            return None;
        }
        let cell_volume = self.grid.cell_volume();
        finish_column(&mut direct, &area, cell_volume);
        // The resolved values must respect every cell's bounds; where they do not (a
        // configuration the classification got wrong), the column keeps its bounds.
        let slack = 1e-9 * cell_volume;
        let consistent = direct.iter().enumerate().all(|(k, &u)| match self.cell(base + k) {
            Cell::Exact(v) => (u - v).abs() <= slack,
            Cell::Open { lower, upper } => lower - slack <= u && u <= upper + slack,
        });
        consistent.then_some((direct, resolved))
    }
}

/// A triangle of another body that meets an open cell.
struct Cutter {
    body: usize,
    world: [Point; 3],
    unit: [Point; 3],
}

/// An open cell of a column being resolved.
struct OpenLayer {
    bodies: Vec<usize>,
    cutters: Vec<Cutter>,
}

fn xy(p: Point) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}

fn xyz(p: Point) -> Coord3D<f64> {
    Coord3D { x: p[0], y: p[1], z: p[2] }
}

/// Whether `p`, perturbed by (ε, ε²), lies left of the directed line a → b.
fn left_of(a: Point, b: Point, p: Point) -> bool {
    let o = orient2d(xy(a), xy(b), xy(p));
    if o != 0.0 {
        return o > 0.0;
    }
    // d/dε of orient2d(a, b, p + (ε, ε²)) is a_y − b_y; then b_x − a_x.
    if a[1] != b[1] {
        a[1] > b[1]
    } else {
        b[0] > a[0]
    }
}

/// Signed crossings of the vertical ray up from `p` with `triangles` (±1 by the sign of
/// the triangle's n_z): 1 inside an outward closed surface, 0 outside.
fn winding(p: Point, triangles: &[[Point; 3]]) -> i32 {
    let mut w = 0;
    for t in triangles {
        let up = orient2d(xy(t[0]), xy(t[1]), xy(t[2])) > 0.0;
        let [a, b, c] = if up { *t } else { [t[0], t[2], t[1]] };
        if left_of(a, b, p) && left_of(b, c, p) && left_of(c, a, p) {
            // orient3d(a, b, c, p) > 0: p below the plane of the counter-clockwise (a, b, c).
            if orient3d(xyz(a), xyz(b), xyz(c), xyz(p)) > 0.0 {
                w += if up { 1 } else { -1 };
            }
        }
    }
    w
}

/// Triangles of two bodies closer than this (grid cells) to lying in one plane count as
/// coplanar: faces that coincide up to the rounding of their coordinates (a quad split
/// along the other diagonal, a copy moved and moved back).
pub const COPLANAR_TOLERANCE: f64 = 1e-10;

/// Whether `u` lies in the plane of `t`: exactly (world coordinates), or within
/// [`COPLANAR_TOLERANCE`] (grid units `tu`, `uu`).
fn coplanar(t: &[Point; 3], u: &[Point; 3], tu: &[Point; 3], uu: &[Point; 3]) -> bool {
    if u.iter().all(|&v| orient3d(xyz(t[0]), xyz(t[1]), xyz(t[2]), xyz(v)) == 0.0) {
        return true;
    }
    let (e1, e2) = ([0, 1, 2].map(|k| tu[1][k] - tu[0][k]), [0, 1, 2].map(|k| tu[2][k] - tu[0][k]));
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    length > 0.0
        && uu.iter().all(|v| {
            let d = (0..3).map(|k| n[k] * (v[k] - tu[0][k])).sum::<f64>();
            d.abs() <= COPLANAR_TOLERANCE * length
        })
}

/// Adds the kept parts of one body's pieces to a column's sums.
struct KeptSink<'s, 'a, S: ?Sized> {
    owner: &'s Bodies<'a, S>,
    column: usize,
    body: usize,
    triangle: [Point; 3],
    unit: [Point; 3],
    open: &'s [Option<OpenLayer>],
    rays: &'s [Vec<[Point; 3]>],
    direct: &'s mut [f64],
    area: &'s mut [f64],
    failed: &'s mut bool,
}

impl<S: Surface + ?Sized> KeptSink<'_, '_, S> {
    /// The kept area and ∫ (z − layer) dA of `part`, which lies in cell `layer`.
    fn kept<const N: usize>(&mut self, layer: usize, part: &Polygon<N>) -> (f64, f64) {
        let nz = self.owner.grid.counts[2];
        let cell = self.column * nz + layer;
        if self.owner.full[cell] {
            return (0.0, 0.0);
        }
        let Some(open) = &self.open[layer] else {
            return part.area_and_moment(layer as f64);
        };
        match resolve(part, layer as f64, self.body, [&self.triangle, &self.unit], open, self.rays)
        {
            Some(kept) => kept,
            None => {
                *self.failed = true;
                (0.0, 0.0)
            }
        }
    }
}

impl<S: Surface + ?Sized> LayerSink for KeptSink<'_, '_, S> {
    fn slab<const N: usize>(&mut self, layer: usize, part: &Polygon<N>) {
        let (area, moment) = self.kept(layer, part);
        self.direct[layer] += moment;
        self.area[layer] += area;
    }

    fn above<const N: usize>(&mut self, part: &Polygon<N>) {
        // On or above the top plane: classified with the top cell, whose closed box it
        // touches.
        let top = self.area.len() - 1;
        let (area, _) = self.kept(top - 1, part);
        self.area[top] += area;
    }
}

/// Splits `part` (of body `body`'s triangle `triangle`, in an open cell at height
/// `layer`) along the other bodies' surfaces and returns the kept sub-pieces' area and
/// ∫ (z − layer) dA; `None` when a sub-piece would need more than [`SUB`] sides.
fn resolve<const N: usize>(
    part: &Polygon<N>,
    layer: f64,
    body: usize,
    [triangle, unit]: [&[Point; 3]; 2],
    open: &OpenLayer,
    rays: &[Vec<[Point; 3]>],
) -> Option<(f64, f64)> {
    let mut first = Polygon::<SUB>::EMPTY;
    for &v in part.vertices() {
        first.push(v);
    }
    let mut pieces = vec![first];
    let plane = plane_of(part);
    let mut coplanar_cutters = Vec::new();
    for (index, cutter) in open.cutters.iter().enumerate() {
        if cutter.body == body {
            continue;
        }
        if coplanar(triangle, &cutter.world, unit, &cutter.unit) {
            coplanar_cutters.push(index);
            let u = cutter.unit;
            for (p, q) in [(u[0], u[1]), (u[1], u[2]), (u[2], u[0])] {
                cut(&mut pieces, p, q)?;
            }
        } else if let Some((p, q)) = plane.and_then(|pl| crossing(&cutter.unit, pl)) {
            cut(&mut pieces, p, q)?;
        }
    }
    let (mut area, mut moment) = (0.0, 0.0);
    let own_up = orient2d(xy(triangle[0]), xy(triangle[1]), xy(triangle[2])) > 0.0;
    for piece in &pieces {
        let (a, m) = piece.area_and_moment(layer);
        if a == 0.0 {
            continue;
        }
        let point = centroid(piece, a);
        let kept = open.bodies.iter().filter(|&&other| other != body).all(|&other| {
            let on = coplanar_cutters
                .iter()
                .map(|&i| &open.cutters[i])
                .find(|t| t.body == other && inside_triangle(&t.unit, point));
            match on {
                Some(t) => {
                    let up = orient2d(xy(t.world[0]), xy(t.world[1]), xy(t.world[2])) > 0.0;
                    up == own_up && body < other
                }
                None => winding(point, &rays[other]) <= 0,
            }
        });
        if kept {
            area += a;
            moment += m;
        }
    }
    Some((area, moment))
}

/// The plane z = z0 + gx·x + gy·y through a non-vertical polygon, from its first,
/// farthest and middle vertices; `None` when it is vertical or degenerate.
fn plane_of<const N: usize>(part: &Polygon<N>) -> Option<[f64; 3]> {
    let v = part.vertices();
    if v.len() < 3 {
        return None;
    }
    // The triangle of largest projected area among (v0, vk, vk+1).
    let o = v[0];
    let (mut best, mut cross) = (1, 0.0f64);
    for k in 1..v.len() - 1 {
        let c = (v[k][0] - o[0]) * (v[k + 1][1] - o[1]) - (v[k][1] - o[1]) * (v[k + 1][0] - o[0]);
        if c.abs() > cross.abs() {
            best = k;
            cross = c;
        }
    }
    if cross == 0.0 {
        return None;
    }
    let (a, b) = (v[best], v[best + 1]);
    let (ax, ay, az) = (a[0] - o[0], a[1] - o[1], a[2] - o[2]);
    let (bx, by, bz) = (b[0] - o[0], b[1] - o[1], b[2] - o[2]);
    let gx = (az * by - bz * ay) / cross;
    let gy = (ax * bz - bx * az) / cross;
    Some([o[2] - gx * o[0] - gy * o[1], gx, gy])
}

/// Where triangle `t` crosses the plane z = p0 + p1·x + p2·y: the segment's two ends
/// (xy matters), or `None` when it does not cross it along a segment.
fn crossing(t: &[Point; 3], plane: [f64; 3]) -> Option<(Point, Point)> {
    let d = t.map(|v| v[2] - (plane[0] + plane[1] * v[0] + plane[2] * v[1]));
    let mut ends = [[0.0; 3]; 3];
    let mut n = 0;
    for k in 0..3 {
        let (u, w, du, dw) = (t[k], t[(k + 1) % 3], d[k], d[(k + 1) % 3]);
        if du == 0.0 {
            ends[n] = u;
            n += 1;
        }
        if (du < 0.0 && dw > 0.0) || (du > 0.0 && dw < 0.0) {
            let s = du / (du - dw);
            ends[n] = [0, 1, 2].map(|a| u[a] + s * (w[a] - u[a]));
            n += 1;
        }
        if n == 3 {
            break;
        }
    }
    (n >= 2 && (ends[0][0] != ends[1][0] || ends[0][1] != ends[1][1])).then(|| (ends[0], ends[1]))
}

/// Cuts every piece that the segment p–q's box meets and its line crosses.
fn cut(pieces: &mut Vec<Polygon<SUB>>, p: Point, q: Point) -> Option<()> {
    let line = |v: &Point| (q[0] - p[0]) * (v[1] - p[1]) - (q[1] - p[1]) * (v[0] - p[0]);
    let (x0, x1) = (p[0].min(q[0]), p[0].max(q[0]));
    let (y0, y1) = (p[1].min(q[1]), p[1].max(q[1]));
    // Only the pieces from before this cut: the two halves of a split lie on their
    // sides of the line (up to the rounding of the new vertices).
    for k in 0..pieces.len() {
        let s = pieces[k];
        let (sx, sy) = (s.range(0), s.range(1));
        let meets = sx.0 <= x1 && sx.1 >= x0 && sy.0 <= y1 && sy.1 >= y0;
        let (mut neg, mut pos) = (false, false);
        for v in s.vertices() {
            let d = line(v);
            neg |= d < 0.0;
            pos |= d > 0.0;
        }
        if meets && neg && pos {
            if s.vertices().len() + 1 > SUB {
                return None;
            }
            let (mut below, mut above) = (Polygon::EMPTY, Polygon::EMPTY);
            s.split_into(line, None, &mut below, &mut above);
            pieces[k] = below;
            pieces.push(above);
        }
    }
    Some(())
}

/// The centroid of a polygon (xy) with z the mean of z over it (z linear).
fn centroid<const N: usize>(piece: &Polygon<N>, area: f64) -> Point {
    let v = piece.vertices();
    let o = v[0];
    let mut sum = [0.0; 3];
    for k in 1..v.len() - 1 {
        let (a, b) = (v[k], v[k + 1]);
        let w = 0.5 * ((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]));
        for d in 0..3 {
            sum[d] += w * ((a[d] - o[d]) + (b[d] - o[d])) / 3.0;
        }
    }
    [0, 1, 2].map(|d| o[d] + sum[d] / area)
}

/// Whether p's xy lies inside triangle t's xy projection (floating point: callers split
/// pieces along t's edges first, so p is well inside or outside).
fn inside_triangle(t: &[Point; 3], p: Point) -> bool {
    let side = |a: Point, b: Point| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    let s = [side(t[0], t[1]), side(t[1], t[2]), side(t[2], t[0])];
    s.iter().all(|&x| x > 0.0) || s.iter().all(|&x| x < 0.0)
}

/// An open cell during refinement: its box (world), the base column it lies in, and
/// for each touching body the faces of its column at or above its bottom.
struct OpenCell {
    column: usize,
    lo: Point,
    size: Point,
    faces: Vec<(usize, Vec<u32>)>,
    lower: f64,
    upper: f64,
}

/// What refining one open cell gives.
struct Refined {
    column: usize,
    /// Σ of the children that are exactly known.
    exact: f64,
    /// Children still open.
    open: Vec<OpenCell>,
    stalled: bool,
}

/// The faces of `faces` whose box meets the closed column over `lo..lo + size` (xy) at
/// or above `lo.z`.
fn faces_in_column<S: Surface + ?Sized>(
    body: &S,
    faces: &[u32],
    lo: Point,
    size: Point,
) -> Vec<u32> {
    faces
        .iter()
        .copied()
        .filter(|&f| {
            let (a, b) = face_box(body, f as usize, |p| p);
            a[0] <= lo[0] + size[0]
                && b[0] >= lo[0]
                && a[1] <= lo[1] + size[1]
                && b[1] >= lo[1]
                && b[2] >= lo[2]
        })
        .collect()
}

fn refine<S: Surface + ?Sized>(
    bodies: &[Oriented<'_, S>],
    cell: &OpenCell,
) -> Result<Refined, GridError> {
    let half = cell.size.map(|s| 0.5 * s);
    let sub = Grid::new(cell.lo, half, [2, 2, 2])?;
    let units = Units::new(&sub);
    let child_volume = sub.cell_volume();
    // Per touching body: its volume and touch in each child.
    let per_body: Vec<([f64; 8], [u8; 8])> = cell
        .faces
        .iter()
        .map(|(b, faces)| {
            let (mut cells, mut area, mut touched) = ([0.0; 8], [0.0; 12], [0u8; 8]);
            let faces = faces.iter().map(|&f| f as usize);
            add_faces::<_, true>(
                &bodies[*b],
                faces,
                &units,
                [2, 2, 2],
                &(0..4),
                &mut cells,
                &mut area,
                &mut touched,
            );
            for (direct, area) in cells.chunks_mut(2).zip(area.chunks(3)) {
                finish_column(direct, area, child_volume);
            }
            (cells, touched)
        })
        .collect();
    let mut exact = 0.0;
    let mut open = Vec::new();
    for child in 0..8 {
        let state = classify(child_volume, per_body.iter().map(|(v, t)| (v[child], t[child] != 0)));
        match state {
            Cell::Exact(v) => exact += v,
            Cell::Open { lower, upper } => {
                let (i, j, k) = (child >> 2, (child >> 1) & 1, child & 1);
                let lo = [0, 1, 2].map(|a| cell.lo[a] + [i, j, k][a] as f64 * half[a]);
                let faces = cell
                    .faces
                    .iter()
                    .zip(&per_body)
                    .filter(|(_, (_, t))| t[child] != 0)
                    .map(|((b, faces), _)| (*b, faces_in_column(&bodies[*b], faces, lo, half)))
                    .collect();
                open.push(OpenCell { column: cell.column, lo, size: half, faces, lower, upper });
            }
        }
    }
    let gap: f64 = open.iter().map(|c| c.upper - c.lower).sum();
    let stalled = gap > STALL * (cell.upper - cell.lower);
    Ok(Refined { column: cell.column, exact, open, stalled })
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
    if bodies.is_empty() {
        return Err(UnionError::NoBodies);
    }
    let mut oriented = Vec::new();
    let mut flipped = Vec::new();
    let mut sum_of_volumes = CompensatedSum::default();
    let mut largest = 0.0f64;
    let (mut min, mut max) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut projected = 0.0;
    let mut triangles = 0;
    for (i, body) in bodies.iter().enumerate() {
        let mp = mass_properties(body);
        sum_of_volumes.add(mp.signed_volume.abs());
        largest = largest.max(mp.signed_volume.abs());
        triangles += mp.triangles;
        if mp.signed_volume < 0.0 {
            flipped.push(i);
        }
        if let Some(b) = mp.bounds {
            for a in 0..3 {
                min[a] = min[a].min(b.min[a]);
                max[a] = max[a].max(b.max[a]);
            }
        }
        let mut p = 0.0;
        for f in 0..body.face_count() {
            body.fan(f, |a, b, c| {
                p += ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])).abs() * 0.5;
            });
        }
        projected += p;
        oriented.push(Oriented::new(body, mp.signed_volume < 0.0));
    }
    let sum_of_volumes = sum_of_volumes.value();
    // Also true for no vertices at all (min = +∞).
    let flat = (0..3).any(|a| max[a] <= min[a] || max[a].is_nan() || min[a].is_nan());
    if flat {
        // No body encloses any volume.
        let grid = Grid::new([0.0; 3], [1.0; 3], [1, 1, 1])?;
        return Ok(UnionVolume {
            lower: 0.0,
            upper: 0.0,
            bodies: bodies.len(),
            sum_of_volumes,
            cells_refined: 0,
            cells_resolved_exactly: 0,
            columns_unresolved: 0,
            grid,
            flipped,
            bodies_not_solid: Vec::new(),
        });
    }
    let target = triangles.clamp(1 << 15, 1 << 18);
    let grid = base_grid(min, max, target)?;
    let allowance = projected * (max[2] - min[2]) * 2f64.powi(-36);
    let model = Bodies::new(oriented, grid)?;
    let [_, _, nz] = grid.counts;
    let columns = grid.counts[0] * grid.counts[1];

    // Per base column: exact part and the open leaves' bounds.
    let mut exact = vec![0.0; columns];
    let mut lower = vec![0.0; columns];
    let mut upper = vec![0.0; columns];
    let mut level = Vec::new();
    let mut open_columns = Vec::new();
    for c in 0..columns {
        let mut has_open = false;
        for k in 0..nz {
            match model.cell(c * nz + k) {
                Cell::Exact(v) => exact[c] += v,
                Cell::Open { .. } => has_open = true,
            }
        }
        if has_open {
            open_columns.push(c);
        }
    }
    // Base open cells, with their touching bodies' faces.
    let base_open: Vec<Vec<OpenCell>> = open_columns
        .par_iter()
        .map(|&c| {
            let touch = model.column_touches(c);
            let (i, j) = (c / grid.counts[1], c % grid.counts[1]);
            (0..nz)
                .filter_map(|k| match model.cell(c * nz + k) {
                    Cell::Open { lower, upper } => {
                        let lo =
                            [0, 1, 2].map(|a| grid.origin[a] + [i, j, k][a] as f64 * grid.cell[a]);
                        let faces = (0..model.bodies.len())
                            .filter(|&b| touch[b * nz + k])
                            .map(|b| {
                                let all = model.bins[b].column(c);
                                (b, faces_in_column(&model.bodies[b], all, lo, grid.cell))
                            })
                            .collect();
                        Some(OpenCell { column: c, lo, size: grid.cell, faces, lower, upper })
                    }
                    Cell::Exact(_) => None,
                })
                .collect()
        })
        .collect();
    for cell in base_open.into_iter().flatten() {
        lower[cell.column] += cell.lower;
        upper[cell.column] += cell.upper;
        level.push(cell);
    }
    let total = |exact: &[f64], bound: &[f64]| {
        let mut s = CompensatedSum::default();
        exact.iter().chain(bound).for_each(|&x| s.add(x));
        s.value()
    };
    let mut cells_refined = 0;
    let mut depth = 0;
    while !level.is_empty() && depth < MAX_DEPTH && 8 * level.len() <= MAX_OPEN {
        let gap = total(&upper, &[]) - total(&lower, &[]);
        let low = total(&exact, &lower);
        if gap <= tolerance * low.abs() {
            break;
        }
        let refined: Vec<Refined> =
            level.par_iter().map(|cell| refine(&model.bodies, cell)).collect::<Result<_, _>>()?;
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
    let (mut cells_resolved_exactly, mut columns_unresolved) = (0, 0);
    if gap > tolerance * low.abs() {
        // Resolve every column that still holds an open leaf.
        let targets: Vec<usize> = (0..columns).filter(|&c| upper[c] > lower[c]).collect();
        let results: Vec<Option<(Vec<f64>, usize)>> =
            targets.par_iter().map(|&c| model.exact_column(c)).collect();
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
        // For solids the union holds the largest body and is held by their sum: facts
        // that bound the interval whatever its cells' rounding.
        low = low.max(largest);
        high = high.min(sum_of_volumes);
    }
    // Ordered for any input: per-column bounds are updated in place (rounding), and a
    // body that is not a solid makes the bounds meaningless (then it is listed).
    let (low, high) = (low.min(high), low.max(high));
    Ok(UnionVolume {
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
    })
}

/// The union's volume in every cell of `grid`: exact where at most one body touches a
/// cell, resolved exactly (module docs) in the columns of cells that two or more touch.
/// Returns the cell volumes and the number of columns that could not be resolved (their
/// open cells hold the lower bound, `max_i v_i`).
pub fn union_cell_volumes<S: Surface>(
    bodies: &[S],
    grid: &Grid,
) -> Result<(Vec<f64>, usize), GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    let oriented =
        bodies.iter().map(|b| Oriented::new(b, mass_properties(b).signed_volume < 0.0)).collect();
    let model = Bodies::new(oriented, grid)?;
    let [_, _, nz] = grid.counts;
    let mut out = super::cells::zeroed(grid.cell_count())?;
    let unresolved: usize = out
        .par_chunks_mut(nz)
        .enumerate()
        .map(|(c, cells)| {
            let mut open = false;
            for (k, v) in cells.iter_mut().enumerate() {
                *v = match model.cell(c * nz + k) {
                    Cell::Exact(x) => x,
                    Cell::Open { lower, .. } => {
                        open = true;
                        lower
                    }
                };
            }
            if !open {
                return 0;
            }
            match model.exact_column(c) {
                Some((exact, _)) => {
                    cells.copy_from_slice(&exact);
                    0
                }
                None => 1,
            }
        })
        .sum();
    Ok((out, unresolved))
}
