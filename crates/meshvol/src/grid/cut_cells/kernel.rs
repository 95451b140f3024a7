//! The cut-cell kernel: the volume kernel's sweeps with a sink that keeps, per cell, the
//! moments of the solid and the surface's own integrals, and per column the areas and
//! area moments handed down to the layers below.
//!
//! The cells' arrays are filled in place, tile by tile as `grid` fills its volumes: the
//! terms in face order during the sweep, then one pass per column from the top down
//! turning them into world values. Only the columns' handed-down sums are scratch.

use super::integrals::{handed_down, projected, surface_part};
use super::CutCells;
use crate::accumulate::CompensatedSum;
use crate::grid::cells::{
    for_each_piece, sweep_layers, zeroed, Bins, Block, LayerSink, Piece, Tiling, Units,
};
use crate::grid::clip::Polygon;
use crate::grid::{Grid, GridError, OCCUPANCY_TOLERANCE};
use crate::progress::{Counter, Progress};
use crate::{Point, Surface};
use rayon::prelude::*;
use std::ops::Range;

/// Slices of the cell arrays: a tile's, or one column's of it.
struct CellSlices<'a> {
    volume: &'a mut [f64],
    centroid: &'a mut [Point],
    boundary_area: &'a mut [f64],
    boundary_vector: &'a mut [Point],
    boundary_centroid: &'a mut [Point],
}

impl CellSlices<'_> {
    /// The cells `range` of these.
    fn part(&mut self, range: Range<usize>) -> CellSlices<'_> {
        CellSlices {
            volume: &mut self.volume[range.clone()],
            centroid: &mut self.centroid[range.clone()],
            boundary_area: &mut self.boundary_area[range.clone()],
            boundary_vector: &mut self.boundary_vector[range.clone()],
            boundary_centroid: &mut self.boundary_centroid[range],
        }
    }
}

/// One tile's slices of the cell arrays, and of the z apertures (`depth + 1` per column).
struct TileCells<'a> {
    cells: CellSlices<'a>,
    aperture_z: &'a mut [f64],
}

/// World scale of a grid-unit area vector's components: `(dy·dz, dx·dz, dx·dy)`.
pub(super) fn face_areas(cell: [f64; 3]) -> [f64; 3] {
    [cell[1] * cell[2], cell[0] * cell[2], cell[0] * cell[1]]
}

/// Receives one column's parts. During the sweep `volume` holds `∫ z' n_z dA` and
/// `centroid` holds `(∫ x'z', ∫ y'z', ½∫ z'²) n_z dA` of the parts in each cell, and
/// `boundary_centroid` the area-weighted local centroids; `handed[m]` the area and its x
/// and y moments of the parts in layer `first + m` (the last entry: above the grid).
struct MomentSink<'a> {
    cells: CellSlices<'a>,
    handed: &'a mut [[f64; 3]],
    /// The projected area of the parts lying on the grid's top face.
    on_top: &'a mut f64,
    first: usize,
    column: [f64; 2],
    scale: [f64; 3],
    /// The face's unit normal when it is a polygon ([`add_surface`]).
    normal: Option<Point>,
}

impl LayerSink for MomentSink<'_> {
    #[inline(always)]
    fn slab<const N: usize>(&mut self, layer: usize, part: &Polygon<N>) {
        let Some(local) = layer.checked_sub(self.first) else {
            return;
        };
        let [i, j] = self.column;
        if local >= self.cells.volume.len() {
            let h = handed_down(part, [i, j]);
            for d in 0..3 {
                self.handed[local][d] += h[d];
            }
            return;
        }
        let corner = [i, j, layer as f64];
        let p = projected(part, corner);
        let h = &mut self.handed[local];
        h[0] += p.area;
        h[1] += p.area_x;
        h[2] += p.area_y;
        self.cells.volume[local] += p.z;
        let m = &mut self.cells.centroid[local];
        m[0] += p.xz;
        m[1] += p.yz;
        m[2] += p.zz_half;
        self.surface(local, part, corner);
    }

    #[inline(always)]
    fn above<const N: usize>(&mut self, part: &Polygon<N>) {
        let top = self.handed.len() - 1;
        let h = handed_down(part, self.column);
        for d in 0..3 {
            self.handed[top][d] += h[d];
        }
        // A part lying on the grid's top face is the top layer's surface (the grid's far
        // faces are closed), and not beyond it for the aperture there.
        let (z0, z1) = part.range(2);
        let layer = self.first + top - 1;
        if z0 == z1 && z0 == (layer + 1) as f64 && top - 1 < self.cells.volume.len() {
            *self.on_top += h[0];
            let [i, j] = self.column;
            self.surface(top - 1, part, [i, j, layer as f64]);
        }
    }
}

impl MomentSink<'_> {
    /// Adds a part to the surface sums of cell `local` (`corner`: its first corner).
    #[inline(always)]
    fn surface<const N: usize>(&mut self, local: usize, part: &Polygon<N>, corner: [f64; 3]) {
        if let Some((vector, centre)) = surface_part(part, corner) {
            add_surface(
                (&mut self.cells.boundary_area[local], &mut self.cells.boundary_vector[local]),
                &mut self.cells.boundary_centroid[local],
                (vector, centre, self.normal),
                self.scale,
            );
        }
    }
}

/// Adds a part's area vector (grid units) and local centroid to a cell's surface sums:
/// its world area, world area vector, and world area × local centroid.
///
/// A polygon face's fan may fold over itself (a non-convex face: its triangles cover
/// some of it with both windings), so a part's area counts with the sign of its vector
/// along the face's unit `normal` (world): the parts of one face then add up to the
/// face's own area. A triangle (no `normal`) counts its vector's length.
#[inline(always)]
pub(super) fn add_surface(
    (area, vector): (&mut f64, &mut Point),
    weighted: &mut Point,
    (part_vector, centre, normal): (Point, Point, Option<Point>),
    scale: Point,
) {
    let world = [0, 1, 2].map(|d| part_vector[d] * scale[d]);
    let size = match normal {
        Some(n) => world[0] * n[0] + world[1] * n[1] + world[2] * n[2],
        None => (world[0] * world[0] + world[1] * world[1] + world[2] * world[2]).sqrt(),
    };
    *area += size;
    for d in 0..3 {
        vector[d] += world[d];
        weighted[d] += size * centre[d];
    }
}

/// The unit normal (world) of face `face` when it is a polygon of more than one triangle
/// whose area vector is not zero; `None` for a triangle (see [`add_surface`]).
pub(super) fn polygon_normal<S: Surface + ?Sized>(
    surface: &S,
    face: usize,
    units: &Units,
    scale: Point,
) -> Option<Point> {
    let (mut total, mut triangles) = ([0.0; 3], 0);
    surface.fan(face, |a, b, c| {
        let [a, b, c] = [a, b, c].map(|p| units.map(p));
        let (e, f) = ([0, 1, 2].map(|d| b[d] - a[d]), [0, 1, 2].map(|d| c[d] - a[d]));
        let cross =
            [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]];
        for d in 0..3 {
            total[d] += cross[d] * scale[d];
        }
        triangles += 1;
    });
    let length = (total[0] * total[0] + total[1] * total[1] + total[2] * total[2]).sqrt();
    (triangles > 1 && length > 0.0).then(|| total.map(|x| x / length))
}

/// Turns the area-weighted local surface centroids of the cells of `first` (a slab of a
/// region, `plane` cells of `[_, ny, nz]` each) into world centroids (the middle of a cell
/// without surface), once every part has been added.
pub(super) fn finish_boundary_centroids(
    grid: &Grid,
    first: [usize; 3],
    [_, ny, nz]: [usize; 3],
    centroids: &mut [Point],
    areas: &[f64],
) {
    for (n, (c, &w)) in centroids.iter_mut().zip(areas).enumerate() {
        let at = [first[0] + n / (ny * nz), first[1] + n / nz % ny, first[2] + n % nz];
        *c = [0, 1, 2]
            .map(|d| grid.origin[d] + (at[d] as f64 + within(c[d], w, w == 0.0)) * grid.cell[d]);
    }
}

/// `m / v` as a position within a cell, clamped to [0, 1] (rounding can push the ratio
/// of two small sums past the cell), or the middle for an empty or full cell.
#[inline(always)]
fn within(m: f64, v: f64, empty: bool) -> f64 {
    if empty {
        0.5
    } else {
        (m / v).clamp(0.0, 1.0)
    }
}

/// Turns a column's sums into world values: the suffix sums of the handed-down terms,
/// taken from the grid's top down exactly as [`crate::grid::cells::finish_column`] does
/// for the volumes (so the volumes are the same bits), the centroids, and the z
/// apertures at the planes `first..=first + depth`.
#[allow(clippy::too_many_arguments)]
fn finish_column(
    cells: &mut TileCells,
    range: Range<usize>,
    apertures: Range<usize>,
    (handed, on_top): (&[[f64; 3]], f64),
    [i, j, first]: [usize; 3],
    grid: &Grid,
) {
    let scale = grid.cell_volume();
    let [mut area, mut area_x, mut area_y] = [CompensatedSum::default(); 3];
    let depth = range.len();
    let cell_at = |d: usize, local: f64, k: usize| {
        grid.origin[d] + ([i, j, k][d] as f64 + local) * grid.cell[d]
    };
    for k in (0..handed.len() - 1).rev() {
        let above = handed[k + 1];
        area.add(above[0]);
        area_x.add(above[1]);
        area_y.add(above[2]);
        if k < depth {
            let n = range.start + k;
            let layer = first + k;
            let v = cells.cells.volume[n] + area.value();
            cells.cells.volume[n] = v * scale;
            let m = cells.cells.centroid[n];
            let moment = [m[0] + area_x.value(), m[1] + area_y.value(), m[2] + 0.5 * area.value()];
            let magnitude = v.abs();
            let trivial =
                magnitude <= OCCUPANCY_TOLERANCE || (magnitude - 1.0).abs() <= OCCUPANCY_TOLERANCE;
            cells.cells.centroid[n] =
                [0, 1, 2].map(|d| cell_at(d, within(moment[d], v, trivial), layer));
            // The plane at the bottom of layer `first + k + 1`: everything above it (on
            // the grid's top face, but the parts lying on it).
            let beyond = if k + 2 == handed.len() { on_top } else { 0.0 };
            cells.aperture_z[apertures.start + k + 1] = area.value() - beyond;
        }
    }
    let mut bottom = area;
    bottom.add(handed[0][0]);
    cells.aperture_z[apertures.start] = bottom.value();
}

/// The cut-cell values of the cells of `block` of `grid` (validated), from `surface`'s
/// faces, and the z apertures of its columns; the x and y apertures are left to
/// [`super::apertures`] and the surface centroids to [`finish_boundary_centroids`].
pub(super) fn cut_cells<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    block: &Block,
    progress: &dyn Progress,
) -> Result<CutCells, GridError> {
    let [bx, by, depth] = block.shape();
    let len = bx * by * depth;
    let mut out = CutCells {
        grid: *grid,
        region: block.region.clone(),
        volume: zeroed(len)?,
        centroid: zeroed(len)?,
        boundary_area: zeroed(len)?,
        boundary_vector: zeroed(len)?,
        boundary_centroid: zeroed(len)?,
        aperture: [
            zeroed((bx + 1) * by * depth)?,
            zeroed(bx * (by + 1) * depth)?,
            zeroed(len + bx * by)?,
        ],
    };
    let nz = grid.counts[2];
    let (x0, y0, first) = (block.region[0].start, block.region[1].start, block.region[2].start);
    let areas = block.areas();
    let columns = block.columns();
    let threads = rayon::current_num_threads().max(1);
    // Three handed-down sums a layer: at most 2²⁰ of them (24 MiB) a tile.
    let per_tile = columns.div_ceil(8 * threads).min(((1 << 20) / (3 * areas)).max(1)).max(1);
    let tiling = Tiling { columns, per_tile };
    progress.stage("sorting faces into tiles of columns");
    let bins = Bins::new(surface, grid, block, &tiling, false);
    progress.stage("cutting faces into cells");
    let done = Counter::new(progress, tiling.tiles());
    let units = Units::new(grid);
    let scale = face_areas(grid.cell);
    // An indexed triangle mesh has no polygon faces to look at.
    let polygons = surface.indexed_triangles().is_none();
    let (tile_cells, tile_planes) = (per_tile * depth, per_tile * (depth + 1));
    // Column `c` of the block is cell column (x0 + c / by, y0 + c % by) of the grid.
    let column_of = |c: usize| [x0 + c / by, y0 + c % by];
    let [_, _, aperture_z] = &mut out.aperture;
    out.volume
        .par_chunks_mut(tile_cells)
        .zip(out.centroid.par_chunks_mut(tile_cells))
        .zip(out.boundary_area.par_chunks_mut(tile_cells))
        .zip(out.boundary_vector.par_chunks_mut(tile_cells))
        .zip(out.boundary_centroid.par_chunks_mut(tile_cells))
        .zip(aperture_z.par_chunks_mut(tile_planes))
        .enumerate()
        .for_each(|(tile, (((((volume, centroid), area), vector), centre), aperture_z))| {
            let mut cells = TileCells {
                cells: CellSlices {
                    volume,
                    centroid,
                    boundary_area: area,
                    boundary_vector: vector,
                    boundary_centroid: centre,
                },
                aperture_z,
            };
            let run = tiling.range(tile);
            let mut handed = vec![[0.0; 3]; run.len() * areas];
            let mut on_top = vec![0.0; run.len()];
            for face in bins.faces(tile) {
                let normal =
                    if polygons { polygon_normal(surface, face, &units, scale) } else { None };
                surface.fan(face, |a, b, c| {
                    let t = Piece::triangle(units.map(a), units.map(b), units.map(c));
                    for_each_piece(&t, block, &run, false, |column, piece| {
                        let [i, j] = column_of(run.start + column);
                        let cells_of = column * depth..(column + 1) * depth;
                        let mut sink = MomentSink {
                            cells: cells.cells.part(cells_of),
                            handed: &mut handed[column * areas..(column + 1) * areas],
                            on_top: &mut on_top[column],
                            first,
                            column: [i as f64, j as f64],
                            scale,
                            normal,
                        };
                        sweep_layers(piece, piece.range(2), nz, &mut sink);
                    });
                });
            }
            for column in 0..run.len() {
                let [i, j] = column_of(run.start + column);
                finish_column(
                    &mut cells,
                    column * depth..(column + 1) * depth,
                    column * (depth + 1)..(column + 1) * (depth + 1),
                    (&handed[column * areas..(column + 1) * areas], on_top[column]),
                    [i, j, first],
                    grid,
                );
            }
            done.add(1);
        });
    Ok(out)
}
