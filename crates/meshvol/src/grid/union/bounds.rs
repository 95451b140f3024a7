//! Bounds per cell: each body's volume in every cell of the base grid from the
//! column–clamp kernel, which also marks the cells whose closed box the body's surface
//! meets (*touches*). A body that does not touch a cell holds all of it or none, so a
//! cell is exact (some body fills it, or at most one touches it: that body's volume) or
//! *open*, with `max_i v_i ≤ vol(∪ ∩ C) ≤ min(|C|, Σ_i v_i)` over the touching bodies.
//! Each body's faces are also binned by the columns their boxes meet, for the later
//! stages.

use crate::grid::cells::{cell_volumes, cover, for_each_piece, zeroed, Block, Piece, Units};
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

/// What the union is in one cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Cell {
    /// Exactly this volume.
    Exact(f64),
    /// Two or more bodies touch it: the union lies in `[lower, upper]`.
    Open { lower: f64, upper: f64 },
}

/// One cell's tally over the bodies, from which it is exact or open.
#[derive(Clone, Copy, Default)]
pub(super) struct Tally {
    /// Some body fills the cell without touching it.
    pub full: bool,
    /// Bodies touching it (2 means 2 or more).
    pub touching: u8,
    /// Max and Σ of the touching bodies' volumes.
    max: f64,
    sum: f64,
}

impl Tally {
    /// Counts a body whose volume in the cell is `v` and which `touches` it or not.
    pub fn add(&mut self, v: f64, touches: bool, cell_volume: f64) {
        // A closed solid's volume in a cell lies in [0, |C|]; clamped, max ≤ Σ holds and
        // the bounds stay ordered whatever the input (`UnionVolume::bodies_not_solid`).
        // (max/min also send NaN to 0.)
        let v = v.max(0.0).min(cell_volume);
        if touches {
            self.touching = (self.touching + 1).min(2);
            self.max = self.max.max(v);
            self.sum += v;
        } else if v > 0.5 * cell_volume {
            self.full = true;
        }
    }

    pub fn cell(&self, cell_volume: f64) -> Cell {
        if self.full {
            Cell::Exact(cell_volume)
        } else if self.touching <= 1 {
            Cell::Exact(self.sum)
        } else {
            Cell::Open { lower: self.max.min(cell_volume), upper: self.sum.min(cell_volume) }
        }
    }
}

/// The bodies on a grid: per-cell facts from the kernel, and faces binned by column.
pub(super) struct Bodies<'a, S: ?Sized> {
    pub bodies: Vec<Oriented<'a, S>>,
    pub grid: Grid,
    pub units: Units,
    pub tally: Vec<Tally>,
    pub bins: Vec<ColumnBins>,
    /// Bodies with a cell volume outside `[0, |C|]` beyond [`SOLID_SLACK`].
    pub not_solid: Vec<usize>,
}

impl<'a, S: Surface + ?Sized> Bodies<'a, S> {
    /// The facts of `bodies` on `grid`, telling `progress` the stage `bounds` and the
    /// bodies done.
    pub fn new(
        bodies: Vec<Oriented<'a, S>>,
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
        // Rounding leaves a solid's cell volumes within about 1e-15 |C| of [0, |C|].
        let slack = SOLID_SLACK * cell_volume;
        for (b, body) in bodies.iter().enumerate() {
            touched.fill(0);
            let v = cell_volumes(body, &grid, &Block::whole(grid.counts), Some(&mut touched))?;
            if v.iter().any(|&x| !(-slack..=cell_volume + slack).contains(&x)) {
                not_solid.push(b);
            }
            for c in 0..cells {
                tally[c].add(v[c], touched[c] != 0, cell_volume);
            }
            done.add(1);
        }
        let bins = bodies.iter().map(|b| ColumnBins::new(b, &grid)).collect();
        let units = Units::new(&grid);
        Ok(Bodies { bodies, grid, units, tally, bins, not_solid })
    }

    pub fn cell(&self, c: usize) -> Cell {
        self.tally[c].cell(self.grid.cell_volume())
    }

    /// For column `c`: which bodies touch each layer (`touch[b * nz + k]`).
    pub fn column_touches(&self, c: usize) -> Vec<bool> {
        let nz = self.grid.counts[2];
        let whole = Block::whole(self.grid.counts);
        let mut touch = vec![false; self.bodies.len() * nz];
        for (b, body) in self.bodies.iter().enumerate() {
            for &f in self.bins[b].column(c) {
                body.fan(f as usize, |p, q, r| {
                    let t =
                        Piece::triangle(self.units.map(p), self.units.map(q), self.units.map(r));
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
}
