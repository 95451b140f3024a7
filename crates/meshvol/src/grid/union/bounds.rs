//! Bounds per cell: each body's volume in every cell of the base grid from the
//! column–clamp kernel, which also marks the cells whose closed box the body's surface
//! meets (*touches*). A body that does not touch a cell holds all of it or none, so a
//! cell is exact (some body fills it, or at most one touches it: that body's volume) or
//! *open*, with `max_i v_i ≤ vol(∪ ∩ C) ≤ min(|C|, Σ_i v_i)` over the touching bodies.
//! Each body's faces are also binned by the columns their boxes meet, for the later
//! stages.

use crate::grid::cells::{cell_volumes, cover, zeroed, Block, Units};
use crate::grid::{Grid, GridError};
use crate::progress::{Counter, Progress};
use crate::surface::Oriented;
use crate::{Point, Surface};
use rayon::prelude::*;

/// A body whose volume in a cell leaves `[−s·|C|, (1 + s)·|C|]` for this `s` is not a
/// closed solid: rounding in a valid solid's column sums stays some 10⁶ times below it.
const SOLID_SLACK: f64 = 1e-9;

/// Faces per column (closed footprint): column c's faces are
/// `faces[offsets[c]..offsets[c + 1]]`, in face order.
pub(super) struct ColumnBins {
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

    pub fn column(&self, c: usize) -> &[u32] {
        &self.faces[self.offsets[c]..self.offsets[c + 1]]
    }
}

/// The bounding box of face `f`'s vertices, mapped by `map`.
pub(super) fn face_box<S: Surface + ?Sized>(
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

/// Which combination of the bodies is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// The union: the points inside some body.
    Union,
    /// The intersection: the points inside every body.
    Intersection,
}

/// What the union (or intersection) is in one cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Cell {
    /// Exactly this volume.
    Exact(f64),
    /// Two or more bodies touch it: the combination lies in `[lower, upper]`.
    Open { lower: f64, upper: f64 },
}

/// One cell's tally over the bodies, from which it is exact or open.
#[derive(Clone, Copy, Default, bytemuck::Zeroable)]
pub(super) struct Tally {
    /// A body that does not touch the cell decides it: for a union, one that fills it
    /// (the union is the whole cell); for an intersection, one that misses it (empty).
    /// Pieces of the other bodies in a settled cell are not on the boundary.
    pub settled: bool,
    /// Bodies touching it (saturating).
    pub touching: u8,
    /// Max, min and Σ of the touching bodies' volumes.
    max: f64,
    min: f64,
    sum: f64,
}

impl Tally {
    /// Counts a body whose volume in the cell is `v` and which `touches` it or not.
    pub fn add(&mut self, v: f64, touches: bool, cell_volume: f64, rule: Rule) {
        // A closed solid's volume in a cell lies in [0, |C|]; clamped, max ≤ Σ holds and
        // the bounds stay ordered whatever the input (`UnionVolume::bodies_not_solid`).
        // (max/min also send NaN to 0.)
        let v = v.max(0.0).min(cell_volume);
        if touches {
            self.min = if self.touching == 0 { v } else { self.min.min(v) };
            self.touching = self.touching.saturating_add(1);
            self.max = self.max.max(v);
            self.sum += v;
        } else {
            let fills = v > 0.5 * cell_volume;
            self.settled |= match rule {
                Rule::Union => fills,
                Rule::Intersection => !fills,
            };
        }
    }

    pub fn cell(&self, cell_volume: f64, rule: Rule) -> Cell {
        match rule {
            Rule::Union if self.settled => Cell::Exact(cell_volume),
            Rule::Union if self.touching <= 1 => Cell::Exact(self.sum),
            Rule::Union => {
                Cell::Open { lower: self.max.min(cell_volume), upper: self.sum.min(cell_volume) }
            }
            Rule::Intersection if self.settled => Cell::Exact(0.0),
            // Every body fills it.
            Rule::Intersection if self.touching == 0 => Cell::Exact(cell_volume),
            Rule::Intersection if self.touching == 1 => Cell::Exact(self.sum),
            Rule::Intersection => {
                // Bonferroni: |∩ X_i| ≥ Σ |X_i| − (t − 1)|C| for t sets in C.
                let t = f64::from(self.touching);
                let lower = (self.sum - (t - 1.0) * cell_volume).max(0.0);
                Cell::Open { lower: lower.min(self.min), upper: self.min }
            }
        }
    }
}

/// The bodies on a grid: per-cell facts from the kernel, and faces binned by column.
pub(super) struct Bodies<'a, S: ?Sized> {
    pub bodies: Vec<Oriented<'a, S>>,
    pub rule: Rule,
    pub grid: Grid,
    pub units: Units,
    pub tally: Vec<Tally>,
    pub bins: Vec<ColumnBins>,
    /// Per body, the cells it touches, in increasing order: kept from the kernel's
    /// marks, so the later stages need not cut the faces again to find them.
    touches: Vec<Vec<usize>>,
    /// Bodies with a cell volume outside `[0, |C|]` beyond [`SOLID_SLACK`].
    pub not_solid: Vec<usize>,
}

impl<'a, S: Surface + ?Sized> Bodies<'a, S> {
    /// The facts of `bodies` on `grid`, telling `progress` the stage `bounds` and the
    /// bodies done.
    pub fn new(
        bodies: Vec<Oriented<'a, S>>,
        rule: Rule,
        grid: Grid,
        progress: &dyn Progress,
    ) -> Result<Self, GridError> {
        progress.stage("bounds");
        let done = Counter::new(progress, bodies.len());
        let cells = grid.cell_count();
        let cell_volume = grid.cell_volume();
        let mut tally: Vec<Tally> = zeroed(cells)?;
        let mut touched = vec![0u8; cells];
        let mut not_solid = Vec::new();
        let mut touches = Vec::with_capacity(bodies.len());
        // Rounding leaves a solid's cell volumes within about 1e-15 |C| of [0, |C|].
        let slack = SOLID_SLACK * cell_volume;
        for (b, body) in bodies.iter().enumerate() {
            touched.fill(0);
            let v = cell_volumes(body, &grid, &Block::whole(grid.counts), Some(&mut touched))?;
            if v.iter().any(|&x| !(-slack..=cell_volume + slack).contains(&x)) {
                not_solid.push(b);
            }
            for c in 0..cells {
                tally[c].add(v[c], touched[c] != 0, cell_volume, rule);
            }
            touches.push(touched.iter().enumerate().filter(|t| *t.1 != 0).map(|t| t.0).collect());
            done.add(1);
        }
        let bins = bodies.iter().map(|b| ColumnBins::new(b, &grid)).collect();
        let units = Units::new(&grid);
        Ok(Bodies { bodies, rule, grid, units, tally, bins, touches, not_solid })
    }

    pub fn cell(&self, c: usize) -> Cell {
        self.tally[c].cell(self.grid.cell_volume(), self.rule)
    }

    /// For column `c`: which bodies touch each layer (`touch[b * nz + k]`).
    pub fn column_touches(&self, c: usize) -> Vec<bool> {
        let nz = self.grid.counts[2];
        let mut touch = vec![false; self.bodies.len() * nz];
        for (b, cells) in self.touches.iter().enumerate() {
            let first = cells.partition_point(|&x| x < c * nz);
            let end = cells.partition_point(|&x| x < (c + 1) * nz);
            for &x in &cells[first..end] {
                touch[b * nz + x - c * nz] = true;
            }
        }
        touch
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::cells::{for_each_piece, Piece};
    use crate::shapes::{cuboid, uv_sphere};

    /// The touches of column `c` found by cutting its faces again (the kernel's own
    /// marking, one column at a time).
    fn by_cutting<S: Surface>(model: &Bodies<'_, S>, c: usize) -> Vec<bool> {
        let nz = model.grid.counts[2];
        let whole = Block::whole(model.grid.counts);
        let mut touch = vec![false; model.bodies.len() * nz];
        for (b, body) in model.bodies.iter().enumerate() {
            for &f in model.bins[b].column(c) {
                body.fan(f as usize, |p, q, r| {
                    let m = |v| model.units.map(v);
                    let t = Piece::triangle(m(p), m(q), m(r));
                    for_each_piece(&t, &whole, &(c..c + 1), true, |_, piece| {
                        let z = piece.range(2);
                        let (k0, k1) = cover(z.0, z.1, nz, true);
                        touch[b * nz + k0..b * nz + k1].fill(true);
                    });
                });
            }
        }
        touch
    }

    #[test]
    fn kept_touches_are_the_cut_ones() {
        // A sphere and a box whose faces lie on grid planes (closed boxes touched from
        // both sides), on a grid with the box's corners at cell corners.
        let a = uv_sphere(1.0, 24, 12);
        let b = cuboid([-0.5, -0.25, 0.0], [1.5, 0.75, 1.0]);
        let grid = Grid::from_bounds([-1.0, -1.0, -1.0], [1.5, 1.0, 1.0], [10, 8, 8]).unwrap();
        let bodies = vec![Oriented::new(&a, false), Oriented::new(&b, false)];
        let model = Bodies::new(bodies, Rule::Union, grid, &()).unwrap();
        let mut marked = 0;
        for c in 0..grid.counts[0] * grid.counts[1] {
            let touch = model.column_touches(c);
            assert_eq!(touch, by_cutting(&model, c), "column {c}");
            marked += touch.iter().filter(|&&t| t).count();
        }
        assert!(marked > 100, "{marked}");
    }
}
