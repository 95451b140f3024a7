//! Exact resolution of what refinement leaves open, one column of the base grid at a
//! time: each piece of a body's triangle in an open cell is split along the other
//! touching bodies' surfaces into sub-pieces no other surface crosses, and a sub-piece
//! is kept when it is on the union's boundary (module docs of [`super`]): outside every
//! other body by a vertical ray with exact predicates and a symbolic perturbation, or on
//! a coplanar face shared the same way round with a later body. For the intersection
//! ([`Rule::Intersection`]) a sub-piece off the other bodies' faces is kept when inside
//! every other body instead.

use super::bounds::{Bodies, Cell, Rule};
use super::plan::{plan_box, PlanBox, PlanIndex};
use crate::grid::cells::{
    cover, finish_column, for_each_piece, sweep_layers, Block, LayerSink, Piece,
};
use crate::grid::clip::Polygon;
use crate::vector::{cross, dot, orient2d, orient3d, sub};
use crate::{Point, Surface};

/// Sub-pieces have at most this many vertices (a piece cut by many lines).
const SUB: usize = 32;

impl<S: Surface + ?Sized> Bodies<'_, S> {
    /// The union's volume in each cell of column `c`, exactly (module docs of [`super`]), and how
    /// many open cells that resolved; `None` where a piece needed more than [`SUB`]
    /// sides or a resolved value falls outside its cell's bounds.
    pub(super) fn exact_column(&self, c: usize) -> Option<(Vec<f64>, usize)> {
        self.exact_column_with(c, None)
    }

    /// [`Self::exact_column`], handing the kept pieces (the boundary of the union or
    /// intersection in the column) to `boundary` where given.
    pub(crate) fn exact_column_with(
        &self,
        c: usize,
        mut boundary: Option<&mut dyn KeptPieces>,
    ) -> Option<(Vec<f64>, usize)> {
        let [_, ny, nz] = self.grid.counts;
        let whole = Block::whole(self.grid.counts);
        let (i, j) = (c / ny, c % ny);
        let origin = [i as f64, j as f64];
        // An intersection's column whose every cell some body misses keeps no piece.
        let cells = &self.tally[c * nz..(c + 1) * nz];
        if self.rule == Rule::Intersection && cells.iter().all(|t| t.settled) {
            return Some((vec![0.0; nz], 0));
        }
        let touch = self.column_touches(c);
        let m = self.bodies.len();
        let base = c * nz;
        // Open layers: their touching bodies, then their cutters.
        let mut open: Vec<Option<OpenLayer>> = (0..nz).map(|_| None).collect();
        let mut resolved = 0;
        for (k, slot) in open.iter_mut().enumerate() {
            if self.tally[base + k].settled || self.tally[base + k].touching < 2 {
                continue;
            }
            let bodies: Vec<usize> = (0..m).filter(|&b| touch[b * nz + k]).collect();
            if bodies.len() < 2 {
                continue;
            }
            *slot = Some(OpenLayer { bodies, cutters: Vec::new(), indices: Vec::new() });
            resolved += 1;
        }
        // One pass over the column's triangles: each is a cutter of the open layers its
        // closed box meets (where its body touches), and a ray triangle of its body when
        // it is not vertical.
        // A column without an open layer (most of the moments' pass) casts no ray and
        // cuts nothing: its pieces are kept or dropped by their cells alone.
        let mut rays = Vec::with_capacity(m);
        let (x, y) = (i as f64, j as f64);
        for (b, body) in self.bodies.iter().enumerate().filter(|_| resolved > 0) {
            let mut tris = Vec::new();
            for &f in self.bins[b].column(c) {
                body.fan(f as usize, |p, q, r| {
                    let unit = [p, q, r].map(|v| self.units.map(v));
                    let plan = plan_box(&unit);
                    let ccw = counter_clockwise(&unit);
                    let z = unit.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                        (lo.min(v[2]), hi.max(v[2]))
                    });
                    if plan[0] <= x + 1.0 && plan[1] >= x && plan[2] <= y + 1.0 && plan[3] >= y {
                        let (k0, k1) = cover(z.0, z.1, nz, true);
                        let sides = ccw.map(|(corners, _)| sides(corners));
                        for layer in open[k0..k1].iter_mut().flatten() {
                            if layer.bodies.contains(&b) {
                                layer.cutters.push(Cutter {
                                    body: b,
                                    world: [p, q, r],
                                    unit,
                                    plan,
                                    sides,
                                });
                            }
                        }
                    }
                    if let Some((corners, up)) = ccw {
                        tris.push(RayTriangle { corners, plan, up });
                    }
                });
            }
            let boxes: Vec<PlanBox> = tris.iter().map(|t| t.plan).collect();
            rays.push(Rays { index: PlanIndex::new(origin, &boxes, 1), tris });
        }
        for layer in open.iter_mut().flatten() {
            // One index per body: a piece is cut by the other bodies' triangles only, and
            // its own body's (most of a cell's, for the finer mesh) are never looked at.
            // The cutters were pushed body by body, so each body's are one run.
            let mut start = 0;
            for run in layer.cutters.chunk_by(|t, u| t.body == u.body) {
                let boxes: Vec<PlanBox> = run.iter().map(|t| t.plan).collect();
                let index = PlanIndex::new(origin, &boxes, 1);
                layer.indices.push(BodyCutters { body: run[0].body, start, index });
                start += run.len();
            }
        }
        let mut scratch = Scratch::default();
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
                    for_each_piece(&t, &whole, &(c..c + 1), false, |_, piece| {
                        let mut sink = KeptSink {
                            owner: self,
                            column: c,
                            body: b,
                            triangle: [p, q, r],
                            unit,
                            open: &open,
                            rays: &rays,
                            scratch: &mut scratch,
                            direct: &mut direct,
                            area: &mut area,
                            failed: &mut failed,
                            // Reborrowed for this piece (an object's lifetime shortens
                            // only at a coercion, not inside an Option).
                            boundary: boundary.as_mut().map(|b| &mut **b as &mut dyn KeptPieces),
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

/// Receives the pieces a column's resolution keeps: what the boundary passes add up
/// (the intersection's moments and interface,
/// [`BoundarySums`](super::frames::BoundarySums)) or keep (the
/// union's boundary, [`super::boundary`]).
pub(crate) trait KeptPieces {
    /// Adds a kept piece; `cell` is the grid's cell size.
    fn add(&mut self, piece: KeptPiece<'_>, cell: Point);
}

/// A piece a column's resolution keeps: `vertices` (in grid units, in its triangle's
/// winding) of `body`'s `triangle` (the column's coordinates, as oriented); `interface`:
/// it was kept off every other body's faces, not on a face it shares with one.
#[derive(Clone, Copy)]
pub(crate) struct KeptPiece<'a> {
    pub(crate) body: usize,
    pub(crate) triangle: &'a [Point; 3],
    pub(crate) vertices: &'a [Point],
    pub(crate) interface: bool,
}

/// A triangle of a touching body that meets an open cell.
struct Cutter {
    body: usize,
    world: [Point; 3],
    unit: [Point; 3],
    plan: PlanBox,
    /// Its edges' outward unit normals in plan and offsets (`nx·x + ny·y ≤ offset`
    /// holds on it), where its plan projection has area.
    sides: Option<[[f64; 3]; 3]>,
}

/// Plan distances this far (grid units) past an edge of a cutter put a point outside
/// it: some 10⁴ times the rounding of the distances (coordinates below 2¹⁰).
const APART: f64 = 1e-9;

/// The outward sides of a triangle's plan projection, from its corners
/// counter-clockwise in plan ([`Cutter::sides`]).
fn sides([a, b, c]: [Point; 3]) -> [[f64; 3]; 3] {
    let side = |p: Point, q: Point| {
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        let length = (dx * dx + dy * dy).sqrt();
        let (nx, ny) = (dy / length, -dx / length);
        [nx, ny, nx * p[0] + ny * p[1]]
    };
    [side(a, b), side(b, c), side(c, a)]
}

impl Cutter {
    /// Whether `part` lies wholly beyond one of the cutter's edges in plan (so the
    /// cutter can neither cut it nor hold any point of it): a separating-axis test,
    /// sharper than boxes for slivers (the fans at a UV sphere's poles), whose boxes meet
    /// far more pieces than the slivers do.
    fn apart<const N: usize>(&self, part: &Polygon<N>) -> bool {
        self.sides.is_some_and(|sides| {
            sides.iter().any(|&[nx, ny, offset]| {
                part.vertices().iter().all(|v| nx * v[0] + ny * v[1] > offset + APART)
            })
        })
    }
}

/// An open cell of a column being resolved: its touching bodies and their triangles
/// that meet it (body by body), indexed in plan per body.
struct OpenLayer {
    bodies: Vec<usize>,
    cutters: Vec<Cutter>,
    indices: Vec<BodyCutters>,
}

/// One body's cutters of an open layer: `cutters[start + item]` for the index's items.
struct BodyCutters {
    body: usize,
    start: usize,
    index: PlanIndex,
}

/// A non-vertical triangle for the ray test: its corners counter-clockwise in plan,
/// whether that is its own order (n_z > 0), and its plan box (a cheap first reject).
struct RayTriangle {
    corners: [Point; 3],
    plan: PlanBox,
    up: bool,
}

/// One body's non-vertical triangles in a column, indexed in plan, for the ray test.
struct Rays {
    tris: Vec<RayTriangle>,
    index: PlanIndex,
}

/// Buffers reused for every piece of a column.
#[derive(Default)]
struct Scratch {
    pieces: Vec<Polygon<SUB>>,
    coplanar: Vec<usize>,
    near: Vec<u32>,
    /// The pieces [`resolve`] kept, by index into `pieces`, and whether each was kept
    /// off every other body's faces (inside or outside them), not on a shared face.
    kept: Vec<(usize, bool)>,
}

/// A point's plan coordinates.
fn xy(p: Point) -> [f64; 2] {
    [p[0], p[1]]
}

/// Triangle `t` counter-clockwise in plan, and whether that is its own order (n_z > 0);
/// `None` when its plan projection has no area (a vertical triangle).
fn counter_clockwise(t: &[Point; 3]) -> Option<([Point; 3], bool)> {
    let turn = orient2d(xy(t[0]), xy(t[1]), xy(t[2]));
    (turn != 0.0).then(|| if turn > 0.0 { (*t, true) } else { ([t[0], t[2], t[1]], false) })
}

/// Whether triangle `t` faces up (n_z > 0), exactly.
fn faces_up(t: &[Point; 3]) -> bool {
    orient2d(xy(t[0]), xy(t[1]), xy(t[2])) > 0.0
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

/// Signed crossings of the vertical ray up from `p` with a body's triangles in the
/// column (±1 by the sign of the triangle's n_z): 1 inside an outward closed surface, 0
/// outside. Only the triangles filed in p's bin can hold p in plan.
fn winding(p: Point, rays: &Rays) -> i32 {
    let mut w = 0;
    for &t in rays.index.at(p[0], p[1]) {
        let RayTriangle { corners: [a, b, c], plan, up } = rays.tris[t as usize];
        // Outside the closed plan box, p is outside the triangle whatever the
        // perturbation (it moves p by less than any distance between floats).
        if p[0] < plan[0] || p[0] > plan[1] || p[1] < plan[2] || p[1] > plan[3] {
            continue;
        }
        if left_of(a, b, p) && left_of(b, c, p) && left_of(c, a, p) {
            // orient3d(a, b, c, p) > 0: p below the plane of the counter-clockwise (a, b, c).
            if orient3d(a, b, c, p) > 0.0 {
                w += if up { 1 } else { -1 };
            }
        }
    }
    w
}

/// `orient3d(t, v)`: its sign is exact. A corner of `t` is 0 without the predicate,
/// which needs its slowest, exact stage to prove a zero: shared vertices (a fan's
/// centre common to two meshes) would otherwise make it the costliest test of a column.
fn side_of(t: &[Point; 3], v: Point) -> f64 {
    if t.contains(&v) {
        return 0.0;
    }
    orient3d(t[0], t[1], t[2], v)
}

/// Triangles of two bodies closer than this (grid cells) to lying in one plane count as
/// coplanar: faces that coincide up to the rounding of their coordinates (a quad split
/// along the other diagonal, a copy moved and moved back).
pub const COPLANAR_TOLERANCE: f64 = 1e-10;

/// Whether `u` lies in the plane of `t`: exactly (world coordinates), or within
/// [`COPLANAR_TOLERANCE`] (grid units `tu`, `uu`).
fn coplanar(t: &[Point; 3], u: &[Point; 3], tu: &[Point; 3], uu: &[Point; 3]) -> bool {
    if u.iter().all(|&v| side_of(t, v) == 0.0) {
        return true;
    }
    let n = cross(sub(tu[1], tu[0]), sub(tu[2], tu[0]));
    let length = dot(n, n).sqrt();
    length > 0.0 && uu.iter().all(|&v| dot(n, sub(v, tu[0])).abs() <= COPLANAR_TOLERANCE * length)
}

/// Adds the kept parts of one body's pieces to a column's sums.
struct KeptSink<'s, 'a, S: ?Sized> {
    owner: &'s Bodies<'a, S>,
    column: usize,
    body: usize,
    triangle: [Point; 3],
    unit: [Point; 3],
    open: &'s [Option<OpenLayer>],
    rays: &'s [Rays],
    scratch: &'s mut Scratch,
    direct: &'s mut [f64],
    area: &'s mut [f64],
    failed: &'s mut bool,
    boundary: Option<&'s mut dyn KeptPieces>,
}

impl<S: Surface + ?Sized> KeptSink<'_, '_, S> {
    /// The kept area and ∫ (z − layer) dA of `part`, which lies in cell `layer`.
    fn kept<const N: usize>(&mut self, layer: usize, part: &Polygon<N>) -> (f64, f64) {
        let nz = self.owner.grid.counts[2];
        let cell = self.column * nz + layer;
        if self.owner.tally[cell].settled {
            return (0.0, 0.0);
        }
        let cell_size = self.owner.grid.cell;
        let Some(open) = &self.open[layer] else {
            // Its body alone touches the cell: inside the other bodies (which fill it,
            // else the cell would be settled).
            if let Some(sums) = self.boundary.as_deref_mut() {
                let (body, triangle) = (self.body, &self.triangle);
                let piece =
                    KeptPiece { body, triangle, vertices: part.vertices(), interface: true };
                sums.add(piece, cell_size);
            }
            return part.area_and_moment(layer as f64);
        };
        let own = [&self.triangle, &self.unit];
        let rule = self.owner.rule;
        match resolve(part, layer as f64, self.body, own, open, rule, self.rays, self.scratch) {
            Some(kept) => {
                if let Some(sums) = self.boundary.as_deref_mut() {
                    let (body, triangle) = (self.body, &self.triangle);
                    for &(k, interface) in &self.scratch.kept {
                        let vertices = self.scratch.pieces[k].vertices();
                        sums.add(KeptPiece { body, triangle, vertices, interface }, cell_size);
                    }
                }
                kept
            }
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
        // touches. An intersection's grid has room above the bodies' common box, so
        // whatever lies there is outside some body.
        if self.owner.rule == Rule::Intersection {
            return;
        }
        let top = self.area.len() - 1;
        let (area, _) = self.kept(top - 1, part);
        self.area[top] += area;
    }
}

/// Splits `part` (of body `body`'s triangle `triangle`, in an open cell at height
/// `layer`) along the other bodies' surfaces and returns the kept sub-pieces' area and
/// ∫ (z − layer) dA; `None` when a sub-piece would need more than [`SUB`] sides.
#[allow(clippy::too_many_arguments)]
fn resolve<const N: usize>(
    part: &Polygon<N>,
    layer: f64,
    body: usize,
    [triangle, unit]: [&[Point; 3]; 2],
    open: &OpenLayer,
    rule: Rule,
    rays: &[Rays],
    scratch: &mut Scratch,
) -> Option<(f64, f64)> {
    let Scratch { pieces, coplanar: coplanar_cutters, near, kept: kept_pieces } = scratch;
    kept_pieces.clear();
    let mut first = Polygon::<SUB>::EMPTY;
    for &v in part.vertices() {
        first.push(v);
    }
    pieces.clear();
    pieces.push(first);
    coplanar_cutters.clear();
    // Only cutters whose plan box meets the part's can cut it (a cut needs the segment's
    // box to meet a piece's) or hold a centroid of it.
    let (px, py) = (part.range(0), part.range(1));
    for cutters in open.indices.iter().filter(|c| c.body != body) {
        cutters.index.meeting(&[px.0, px.1, py.0, py.1], near);
        for &item in near.iter() {
            let index = cutters.start + item as usize;
            let cutter = &open.cutters[index];
            let [x0, x1, y0, y1] = cutter.plan;
            if x0 > px.1 || x1 < px.0 || y0 > py.1 || y1 < py.0 || cutter.apart(part) {
                continue;
            }
            if coplanar(triangle, &cutter.world, unit, &cutter.unit) {
                coplanar_cutters.push(index);
                let u = cutter.unit;
                for (p, q) in [(u[0], u[1]), (u[1], u[2]), (u[2], u[0])] {
                    cut(pieces, p, q)?;
                }
            } else if let Some((p, q)) = crossing(&cutter.unit, unit) {
                cut(pieces, p, q)?;
            }
        }
    }
    let (mut area, mut moment) = (0.0, 0.0);
    let own_up = faces_up(triangle);
    for (index, piece) in pieces.iter().enumerate() {
        let (a, m) = piece.area_and_moment(layer);
        if a == 0.0 {
            continue;
        }
        let point = centroid(piece, a);
        let mut off_faces = true;
        let kept = open.bodies.iter().filter(|&&other| other != body).all(|&other| {
            let on = coplanar_cutters
                .iter()
                .map(|&i| &open.cutters[i])
                .find(|t| t.body == other && inside_triangle(&t.unit, point));
            match on {
                Some(t) => {
                    off_faces = false;
                    let up = faces_up(&t.world);
                    up == own_up && body < other
                }
                None => {
                    let inside = winding(point, &rays[other]) > 0;
                    inside == (rule == Rule::Intersection)
                }
            }
        });
        if kept {
            area += a;
            moment += m;
            kept_pieces.push((index, off_faces));
        }
    }
    Some((area, moment))
}

/// Where triangle `t` crosses the plane of triangle `own` (both in grid units): the
/// segment's two ends (xy matters), or `None` when it does not cross it along a segment.
///
/// Which side of the plane each corner lies on is exact (`orient3d`), so a triangle
/// that only touches the plane at a shared vertex (two meshes of one shape meeting at a
/// pole, an assembly's common corners) does not cut: rounding in a fitted plane used to
/// turn such a touch into a short crossing through the vertex, once per triangle of a
/// fan, chopping the fan's tips into slivers that each needed a ray test.
fn crossing(t: &[Point; 3], own: &[Point; 3]) -> Option<(Point, Point)> {
    // Signed volumes: exact signs, magnitudes ∝ the corners' distances to the plane.
    let d = t.map(|v| side_of(own, v));
    let mut ends = [[0.0; 3]; 3];
    let mut n = 0;
    for k in 0..3 {
        let (u, w, du, dw) = (t[k], t[(k + 1) % 3], d[k], d[(k + 1) % 3]);
        if du == 0.0 {
            ends[n] = u;
            n += 1;
        }
        if (du < 0.0 && dw > 0.0) || (du > 0.0 && dw < 0.0) {
            // In [0, 1]: |du − dw| ≥ |du| and rounding is monotone.
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
        if sx.0 > x1 || sx.1 < x0 || sy.0 > y1 || sy.1 < y0 {
            continue;
        }
        let (mut neg, mut pos) = (false, false);
        for v in s.vertices() {
            let d = line(v);
            neg |= d < 0.0;
            pos |= d > 0.0;
        }
        if neg && pos {
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

#[cfg(test)]
#[path = "resolve_tests.rs"]
mod tests;
