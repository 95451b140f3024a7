//! How the kernel lays a grid out: world points in grid units ([`Units`]), the region
//! it walks ([`Block`]), its columns cut into tiles ([`Tiling`]), the faces binned by
//! the tiles they meet ([`Bins`]), and the cells an interval covers ([`cover`]). The
//! sweeps (`cells.rs`), the cut cells, the union and the device's tile work share it.

use super::Grid;
use crate::accumulate::CHUNK_FACES;
use crate::{Point, Surface};
use rayon::prelude::*;
use std::ops::Range;

/// ⌊x⌋ for |x| < 2⁶³ without a library call (targets without SSE4.1 call `floor`).
#[inline(always)]
pub(crate) fn floor(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x {
        t - 1.0
    } else {
        t
    }
}

/// ⌈x⌉ for |x| < 2⁶³.
#[inline(always)]
pub(crate) fn ceil(x: f64) -> f64 {
    -floor(-x)
}

/// The cells `[start, end)` along an axis with `n` cells that the interval `[lo, hi]`
/// (grid units) meets: with `closed`, every cell whose closed interval it touches;
/// otherwise the cells it overlaps with positive length (one cell when `lo = hi`).
#[inline(always)]
pub(crate) fn cover(lo: f64, hi: f64, n: usize, closed: bool) -> (usize, usize) {
    // Clamping first keeps the casts in range; it changes no answer.
    let limit = n as f64 + 2.0;
    let (lo, hi) = (lo.max(-2.0).min(limit), hi.max(-2.0).min(limit));
    let (start, end) = if closed {
        (ceil(lo) - 1.0, floor(hi) + 1.0)
    } else {
        let start = floor(lo);
        (start, ceil(hi).max(start + 1.0))
    };
    let clamp = |x: f64| x.max(0.0).min(n as f64) as usize;
    (clamp(start), clamp(end))
}

/// Maps world points to grid units.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Units {
    origin: Point,
    cell: [f64; 3],
}

impl Units {
    pub(crate) fn new(grid: &Grid) -> Units {
        Units { origin: grid.origin, cell: grid.cell }
    }

    #[inline(always)]
    pub(crate) fn map(&self, p: Point) -> Point {
        [
            (p[0] - self.origin[0]) / self.cell[0],
            (p[1] - self.origin[1]) / self.cell[1],
            (p[2] - self.origin[2]) / self.cell[2],
        ]
    }
}

/// A region of a grid as the kernel walks it: the grid's counts and the cell ranges
/// along each axis. Its columns are numbered `c = (i − x.start)·width + (j − y.start)`
/// (`width` = the region's y count), so a run of them is a contiguous slice of the
/// region's cells in C order.
#[derive(Clone, Debug)]
pub(crate) struct Block {
    pub(crate) counts: [usize; 3],
    pub(crate) region: [Range<usize>; 3],
}

impl Block {
    pub(crate) fn whole(counts: [usize; 3]) -> Block {
        Block { counts, region: counts.map(|n| 0..n) }
    }

    /// Cells along each axis.
    pub(crate) fn shape(&self) -> [usize; 3] {
        [0, 1, 2].map(|a| self.region[a].len())
    }

    pub(crate) fn columns(&self) -> usize {
        self.region[0].len() * self.region[1].len()
    }

    /// Area accumulators per column: the region's layers and every one above them.
    pub(crate) fn areas(&self) -> usize {
        self.counts[2] + 1 - self.region[2].start
    }
}

/// How the columns are cut into tiles.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tiling {
    pub(crate) columns: usize,
    pub(crate) per_tile: usize,
}

impl Tiling {
    /// At least eight tiles per thread where the block allows, and at most 2²⁰ scratch
    /// areas (8 MiB) per tile. The result does not depend on the choice.
    pub(crate) fn new(block: &Block) -> Tiling {
        let columns = block.columns();
        let threads = rayon::current_num_threads().max(1);
        let by_threads = columns.div_ceil(8 * threads);
        let by_memory = ((1usize << 20) / block.areas()).max(1);
        Tiling { columns, per_tile: by_threads.min(by_memory).max(1) }
    }

    pub(crate) fn tiles(&self) -> usize {
        self.columns.div_ceil(self.per_tile)
    }

    pub(crate) fn range(&self, tile: usize) -> Range<usize> {
        tile * self.per_tile..((tile + 1) * self.per_tile).min(self.columns)
    }
}

/// One chunk of faces binned by tile: the faces of tile `t` are
/// `start + faces[offsets[t]..offsets[t + 1]]`, in face order.
struct ChunkBins {
    start: usize,
    offsets: Vec<u32>,
    faces: Vec<u32>,
}

/// Faces binned by the tiles their xy bounding box meets (faces over no column of the
/// block are in no tile, and are never cut).
pub(crate) struct Bins {
    chunks: Vec<ChunkBins>,
}

impl Bins {
    pub(crate) fn new<S: Surface + ?Sized>(
        surface: &S,
        grid: &Grid,
        block: &Block,
        tiling: &Tiling,
        closed: bool,
    ) -> Bins {
        let units = Units::new(grid);
        let [nx, ny, _] = grid.counts;
        let [x, y, _] = &block.region;
        let width = y.len();
        let faces = surface.face_count();
        let tiles = tiling.tiles();
        let per_tile = tiling.per_tile;
        // The block's rows and columns face `f`'s bounding box meets, counted from the
        // block's first.
        let cover_of = |f: usize| {
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            surface.fan(f, |a, b, c| {
                for p in [a, b, c] {
                    let u = units.map(p);
                    for k in 0..2 {
                        lo[k] = if u[k] < lo[k] { u[k] } else { lo[k] };
                        hi[k] = if u[k] > hi[k] { u[k] } else { hi[k] };
                    }
                }
            });
            let (i0, i1) = cover(lo[0], hi[0], nx, closed);
            let (j0, j1) = cover(lo[1], hi[1], ny, closed);
            let (i0, i1) = (i0.max(x.start), i1.min(x.end));
            let (j0, j1) = (j0.max(y.start), j1.min(y.end));
            if i0 >= i1 || j0 >= j1 {
                (0, 0, 0, 0)
            } else {
                (i0 - x.start, i1 - x.start, j0 - y.start, j1 - y.start)
            }
        };
        // Calls `add(tile)` once for each tile that rows i0..i1 × columns j0..j1 meet, in
        // increasing order.
        let tiles_of = |(i0, i1, j0, j1): (usize, usize, usize, usize),
                        add: &mut dyn FnMut(usize)| {
            let mut next = 0;
            for i in i0..i1 {
                let first = ((i * width + j0) / per_tile).max(next);
                let last = (i * width + j1 - 1) / per_tile;
                for t in first..=last {
                    add(t);
                }
                next = next.max(last + 1);
            }
        };
        let chunks = (0..faces.div_ceil(CHUNK_FACES))
            .into_par_iter()
            .map(|chunk| {
                let range = chunk * CHUNK_FACES..((chunk + 1) * CHUNK_FACES).min(faces);
                let covers: Vec<_> = range.clone().map(cover_of).collect();
                let mut counts = vec![0u32; tiles + 1];
                for &c in &covers {
                    tiles_of(c, &mut |t| counts[t + 1] += 1);
                }
                for t in 0..tiles {
                    counts[t + 1] += counts[t];
                }
                let mut fill = counts.clone();
                let mut binned = vec![0u32; counts[tiles] as usize];
                for (f, &c) in covers.iter().enumerate() {
                    tiles_of(c, &mut |t| {
                        binned[fill[t] as usize] = f as u32;
                        fill[t] += 1;
                    });
                }
                ChunkBins { start: range.start, offsets: counts, faces: binned }
            })
            .collect();
        Bins { chunks }
    }

    /// The faces binned to `tile`, in face order.
    pub(crate) fn faces(&self, tile: usize) -> impl Iterator<Item = usize> + '_ {
        self.chunks.iter().flat_map(move |c| {
            let (a, b) = (c.offsets[tile] as usize, c.offsets[tile + 1] as usize);
            c.faces[a..b].iter().map(move |&f| c.start + f as usize)
        })
    }
}
