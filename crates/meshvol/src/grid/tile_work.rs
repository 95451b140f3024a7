//! The column–clamp kernel's input laid out for a device: the triangles in grid units
//! and, per tile of columns, the triangles it cuts, in face order.
//!
//! A device (an OpenCL kernel, `meshvol-opencl`) gives the same bits as
//! [`cell_volumes`](super::cell_volumes) only if every cell receives the same terms in
//! the same order. Two of the CPU kernel's stages decide those terms without any
//! per-cell arithmetic, and are done here, by the CPU kernel's own code, so that a
//! device repeats only the arithmetic of the sweeps:
//!
//! - the map to grid units ([`Units`](super::cells::Units): one division per
//!   coordinate), and the skip of triangles with no projected area (`add_faces`
//!   drops them before any sweep when it marks no cells);
//! - the binning of faces by tile ([`Bins`](super::cells::Bins)), in face order, each
//!   face's fan triangles in fan order.
//!
//! What a device does with it is `add_faces` and `finish_column` for one tile: the
//! strip, column and layer sweeps of each listed triangle, the sink's sums, and the
//! compensated suffix sum per column. A tile owns its run of cells and of area
//! accumulators, so the tiles are independent and any number may run at once.
//!
//! The cut cells ([`cut_tile_work`](super::cut_cells::cut_tile_work)) lay out the same
//! way, with two differences that are their kernel's: every triangle is kept (a wall,
//! without projected area, still has a surface in its cells), and each triangle carries
//! its face's unit normal where the face is a polygon (the sign its parts' areas count
//! with).

use super::cells::{Bins, Block, Piece, Tiling, Units};
use super::{check_region, Grid, GridError, Region};
use crate::{Point, Surface};

/// The work of one grid (or one block of it) for a device.
#[derive(Clone, Debug)]
pub struct TileWork {
    /// Triangles in grid units (cell `(i, j, k)` is `[i, i+1] × [j, j+1] × [k, k+1]`),
    /// nine coordinates each (`a`, `b`, `c`); for the volumes, those with zero projected
    /// area left out.
    pub triangles: Vec<[f64; 9]>,
    /// For the cut cells, one per triangle: its face's unit normal (world) and 1 where
    /// the face is a polygon with one, else zeros; empty for the volumes.
    pub normals: Vec<[f64; 4]>,
    /// Tile `t` cuts the triangles `entries[offsets[t]..offsets[t + 1]]`, in this order.
    pub offsets: Vec<u64>,
    pub entries: Vec<u32>,
    /// The grid's cells along each axis.
    pub counts: [usize; 3],
    /// The block's first cell along each axis, and its cells along each.
    pub start: [usize; 3],
    pub shape: [usize; 3],
    /// Columns per tile (the last tile may have fewer).
    pub per_tile: usize,
    /// Area accumulators per column: the block's layers and every one above them.
    pub areas: usize,
    /// dx·dy·dz: the results are scaled by it.
    pub scale: f64,
}

impl TileWork {
    /// Columns of the block (`shape[0] · shape[1]`).
    pub fn columns(&self) -> usize {
        self.shape[0] * self.shape[1]
    }

    /// Tiles of the block.
    pub fn tiles(&self) -> usize {
        self.offsets.len() - 1
    }
}

/// The work of `region` of `grid` for `surface`, in tiles of `per_tile` columns (at
/// least one). The cell volumes a device computes from it are those of
/// [`cell_volumes_region`](super::cell_volumes_region), whatever `per_tile` is.
pub fn tile_work<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    region: &Region,
    per_tile: usize,
) -> Result<TileWork, GridError> {
    laid_out(surface, grid, region, per_tile, None::<fn(usize) -> Option<Point>>)
}

/// [`tile_work`]; with `normal` (a face's unit normal, if it is a polygon with one), the
/// cut cells' layout instead: every triangle kept, each with its face's normal.
pub(crate) fn laid_out<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    region: &Region,
    per_tile: usize,
    normal: Option<impl Fn(usize) -> Option<Point>>,
) -> Result<TileWork, GridError> {
    let grid = Grid::new(grid.origin, grid.cell, grid.counts)?;
    check_region(&grid, region)?;
    let block = Block { counts: grid.counts, region: region.clone() };
    let tiling = Tiling { columns: block.columns(), per_tile: per_tile.max(1) };
    let units = Units::new(&grid);
    // Each face's triangles once: face `f` has triangles first[f]..first[f + 1].
    let faces = surface.face_count();
    let mut triangles = Vec::new();
    let mut normals = Vec::new();
    let mut first = Vec::with_capacity(faces + 1);
    for face in 0..faces {
        first.push(triangles.len());
        let n = match normal.as_ref().map(|normal| normal(face)) {
            Some(Some(n)) => [n[0], n[1], n[2], 1.0],
            _ => [0.0; 4],
        };
        surface.fan(face, |a, b, c| {
            let (a, b, c) = (units.map(a), units.map(b), units.map(c));
            if normal.is_some() || Piece::triangle(a, b, c).area() != 0.0 {
                triangles.push([a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]]);
                if normal.is_some() {
                    normals.push(n);
                }
            }
        });
    }
    first.push(triangles.len());
    if triangles.len() > u32::MAX as usize {
        return Err(GridError::TooManyTriangles { triangles: triangles.len() });
    }
    let bins = Bins::new(surface, &grid, &block, &tiling, false);
    let tiles = tiling.tiles();
    let mut offsets = Vec::with_capacity(tiles + 1);
    let mut entries = Vec::new();
    offsets.push(0);
    for tile in 0..tiles {
        for face in bins.faces(tile) {
            entries.extend((first[face]..first[face + 1]).map(|t| t as u32));
        }
        offsets.push(entries.len() as u64);
    }
    Ok(TileWork {
        triangles,
        normals,
        offsets,
        entries,
        counts: grid.counts,
        start: region.clone().map(|r| r.start),
        shape: block.shape(),
        per_tile: tiling.per_tile,
        areas: block.areas(),
        scale: grid.cell_volume(),
    })
}
