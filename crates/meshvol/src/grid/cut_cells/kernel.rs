//! The cut-cell kernel: the volume kernel's sweeps with a sink that keeps, per cell, the
//! moments of the solid and the surface's own integrals, and per column the areas and
//! area moments handed down to the layers below.
//!
//! The cells' arrays are filled in place, tile by tile as `grid` fills its volumes: the
//! terms in face order during the sweep, then one pass per column from the top down
//! turning them into world values. Only the columns' handed-down sums are scratch.
//!
//! The sums that only the second moments and the face centroids need ([`Extra`]) are
//! behind the const parameter `X`: without them the sweep is compiled without them.

use super::arrays::CutCells;
use super::integrals::{face_moments, handed_down, projected, second, surface_part};
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

/// One tile's slices of the cell arrays, and of the z apertures (`depth + 1` per column);
/// with `X`, of the extra sums per cell and the z faces' moments per plane (else empty).
struct TileCells<'a> {
    cells: CellSlices<'a>,
    aperture_z: &'a mut [f64],
    extra: &'a mut [Extra],
    planes: &'a mut [[f64; 2]],
}

/// A cell's sums for the second moments and the face centroids.
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Zeroable)]
pub(super) struct Extra {
    /// During the sweep the in-layer terms of [`second`]'s first six; once the column is
    /// finished, the solid's second moments about the cell's centroid, world units,
    /// `(xx, yy, zz, xy, yz, zx)`.
    pub(super) second: [f64; 6],
    /// [`face_moments`] of the surface in the cell (grid units).
    pub(super) face: [f64; 4],
}

/// The extra sums handed down a column with `X`: `(∫ x'², ∫ y'², ∫ x'y') n_z dA` per
/// layer, and the first moments of the parts on the grid's top face.
struct HandedExtra<'a> {
    second: &'a mut [[f64; 3]],
    on_top: &'a mut [f64; 2],
}

/// World scale of a grid-unit area vector's components: `(dy·dz, dx·dz, dx·dy)`.
pub(super) fn face_areas(cell: [f64; 3]) -> [f64; 3] {
    [cell[1] * cell[2], cell[0] * cell[2], cell[0] * cell[1]]
}

/// Receives one column's parts. During the sweep `volume` holds `∫ z' n_z dA` and
/// `centroid` holds `(∫ x'z', ∫ y'z', ½∫ z'²) n_z dA` of the parts in each cell, and
/// `boundary_centroid` the area-weighted local centroids; `handed[m]` the area and its x
/// and y moments of the parts in layer `first + m` (the last entry: above the grid).
struct MomentSink<'a, const X: bool> {
    cells: CellSlices<'a>,
    extra: &'a mut [Extra],
    handed_extra: HandedExtra<'a>,
    handed: &'a mut [[f64; 3]],
    /// The projected area of the parts lying on the grid's top face.
    on_top: &'a mut f64,
    first: usize,
    column: [f64; 2],
    scale: [f64; 3],
    /// The face's unit normal when it is a polygon ([`add_surface`]).
    normal: Option<Point>,
}

impl<const X: bool> LayerSink for MomentSink<'_, X> {
    #[inline(always)]
    fn slab<const N: usize>(&mut self, layer: usize, part: &Polygon<N>) {
        let Some(local) = layer.checked_sub(self.first) else {
            return;
        };
        let [i, j] = self.column;
        let corner = [i, j, layer as f64];
        if local >= self.cells.volume.len() {
            let h = handed_down(part, [i, j]);
            for d in 0..3 {
                self.handed[local][d] += h[d];
            }
            if X {
                self.hand_down(local, part, corner);
            }
            return;
        }
        if X {
            let s = second(part, corner);
            for (e, t) in self.extra[local].second.iter_mut().zip(&s[..6]) {
                *e += t;
            }
            for (h, t) in self.handed_extra.second[local].iter_mut().zip(&s[6..]) {
                *h += t;
            }
        }
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
        if X {
            let [i, j] = self.column;
            self.hand_down(top, part, [i, j, 0.0]);
        }
        // A part lying on the grid's top face is the top layer's surface (the grid's far
        // faces are closed), and not beyond it for the aperture there.
        let (z0, z1) = part.range(2);
        let layer = self.first + top - 1;
        if z0 == z1 && z0 == (layer + 1) as f64 && top - 1 < self.cells.volume.len() {
            *self.on_top += h[0];
            if X {
                self.handed_extra.on_top[0] += h[1];
                self.handed_extra.on_top[1] += h[2];
            }
            let [i, j] = self.column;
            self.surface(top - 1, part, [i, j, layer as f64]);
        }
    }
}

impl<const X: bool> MomentSink<'_, X> {
    /// Adds a part's degree-2 column terms to those handed down from layer `local`.
    #[inline(always)]
    fn hand_down<const N: usize>(&mut self, local: usize, part: &Polygon<N>, corner: [f64; 3]) {
        let s = second(part, corner);
        for (h, t) in self.handed_extra.second[local].iter_mut().zip(&s[6..]) {
            *h += t;
        }
    }

    /// Adds a part to the surface sums of cell `local` (`corner`: its first corner).
    #[inline(always)]
    fn surface<const N: usize>(&mut self, local: usize, part: &Polygon<N>, corner: [f64; 3]) {
        if X {
            let m = face_moments(part, corner);
            for (e, t) in self.extra[local].face.iter_mut().zip(m) {
                *e += t;
            }
        }
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

/// Turns the area-weighted local surface centroids of the cells of a slab `x = first[0]`
/// of a region (rows of `nz` cells along z, from `first`) into world centroids (the
/// middle of a cell without surface), once every part has been added.
pub(super) fn finish_boundary_centroids(
    grid: &Grid,
    first: [usize; 3],
    nz: usize,
    centroids: &mut [Point],
    areas: &[f64],
) {
    // Row by row: a cell's index from its position without a division per cell (three
    // integer divisions a cell were most of this pass).
    let rows = centroids.chunks_mut(nz.max(1)).zip(areas.chunks(nz.max(1)));
    for (j, (row, weights)) in rows.enumerate() {
        let at = [first[0] as f64, (first[1] + j) as f64];
        for (k, (c, &w)) in row.iter_mut().zip(weights).enumerate() {
            let at = [at[0], at[1], (first[2] + k) as f64];
            *c = [0, 1, 2]
                .map(|d| grid.origin[d] + (at[d] + within(c[d], w, w == 0.0)) * grid.cell[d]);
        }
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

/// A column's handed-down sums: per layer and on the grid's top face; with `X` the extra
/// ones too (else empty).
struct ColumnSums<'a> {
    handed: &'a [[f64; 3]],
    on_top: f64,
    second: &'a [[f64; 3]],
    on_top_moments: [f64; 2],
}

/// Turns a column's sums into world values: the suffix sums of the handed-down terms,
/// taken from the grid's top down exactly as [`crate::grid::cells::finish_column`] does
/// for the volumes (so the volumes are the same bits), the centroids, and the z
/// apertures at the planes `first..=first + depth`; with `X`, the second moments about
/// the centroids and the z faces' moments too (the same suffix sums).
fn finish_column<const X: bool>(
    cells: &mut TileCells,
    range: Range<usize>,
    apertures: Range<usize>,
    sums: ColumnSums,
    [i, j, first]: [usize; 3],
    grid: &Grid,
) {
    let ColumnSums { handed, on_top, second, on_top_moments } = sums;
    let scale = grid.cell_volume();
    let [mut area, mut area_x, mut area_y] = [CompensatedSum::default(); 3];
    let mut squares = [CompensatedSum::default(); 3];
    let depth = range.len();
    let cell_at = |d: usize, local: f64, k: usize| {
        grid.origin[d] + ([i, j, k][d] as f64 + local) * grid.cell[d]
    };
    // The centroid of an empty or full cell, across the column.
    let middle = [cell_at(0, 0.5, 0), cell_at(1, 0.5, 0)];
    for k in (0..handed.len() - 1).rev() {
        let above = handed[k + 1];
        // A layer without surface in the column hands down zeros, and adding a zero
        // leaves a compensated sum's bits as they are (its two parts start at +0, and
        // round-to-nearest never makes them −0): most layers are skipped so.
        if above[0] != 0.0 || above[1] != 0.0 || above[2] != 0.0 {
            area.add(above[0]);
            area_x.add(above[1]);
            area_y.add(above[2]);
        }
        if X {
            for (s, t) in squares.iter_mut().zip(second[k + 1]) {
                s.add(t);
            }
        }
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
            let local = moment.map(|m| within(m, v, trivial));
            cells.cells.centroid[n] = if trivial {
                [middle[0], middle[1], cell_at(2, 0.5, layer)]
            } else {
                [0, 1, 2].map(|d| cell_at(d, local[d], layer))
            };
            // The plane at the bottom of layer `first + k + 1`: everything above it (on
            // the grid's top face, but the parts lying on it).
            let top = k + 2 == handed.len();
            let beyond = if top { on_top } else { 0.0 };
            cells.aperture_z[apertures.start + k + 1] = area.value() - beyond;
            if X {
                let e = &mut cells.extra[n];
                let l = e.second;
                let [xx, yy, xy] = squares.map(|s| s.value());
                let (a, ax, ay) = (area.value(), area_x.value(), area_y.value());
                // (xx, yy, zz, xy, yz, zx) about the cell's corner, grid units.
                let about_corner = [
                    l[0] + xx,
                    l[1] + yy,
                    l[5] + a / 3.0,
                    l[2] + xy,
                    l[4] + 0.5 * ay,
                    l[3] + 0.5 * ax,
                ];
                e.second = central(about_corner, moment, v, (local, trivial), grid.cell);
                let off = if top { on_top_moments } else { [0.0; 2] };
                cells.planes[apertures.start + k + 1] = [ax - off[0], ay - off[1]];
            }
        }
    }
    let mut bottom = area;
    bottom.add(handed[0][0]);
    cells.aperture_z[apertures.start] = bottom.value();
    if X {
        let [mut x, mut y] = [area_x, area_y];
        x.add(handed[0][1]);
        y.add(handed[0][2]);
        cells.planes[apertures.start] = [x.value(), y.value()];
    }
}

/// The second moments `(xx, yy, zz, xy, yz, zx)` of a cell's solid about its reported
/// centroid, world units, from those about its corner (`m2`), its first moment `m1` and
/// volume `v` (grid units) and its centroid `c` (local, clamped): `m2 − c m1ᵀ − m1 cᵀ +
/// v c cᵀ`, exact about any point, so the centroid's clamping cannot break the parallel
/// axis theorem. An empty cell has none; a full one the box's own, `d_a² / 12`.
fn central(m2: [f64; 6], m1: Point, v: f64, (c, trivial): (Point, bool), cell: Point) -> [f64; 6] {
    const PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0)];
    let volume = cell[0] * cell[1] * cell[2];
    let mut out = [0.0; 6];
    for (n, &(a, b)) in PAIRS.iter().enumerate() {
        let local = if !trivial {
            m2[n] - c[a] * m1[b] - m1[a] * c[b] + v * c[a] * c[b]
        } else if v.abs() <= OCCUPANCY_TOLERANCE || a != b {
            0.0
        } else {
            v.signum() / 12.0
        };
        out[n] = local * cell[a] * cell[b] * volume;
    }
    out
}

/// The sweep's results: the cut cells, and with `X` each cell's [`Extra`] and the
/// moments `(∫ x', ∫ y') dA` (grid units) of each z face's wetted part (else empty).
pub(super) type Swept = (CutCells, Vec<Extra>, Vec<[f64; 2]>);

/// The cut cells' arrays for `block` of `grid`, zeroed (the sweeps add into them), but
/// for the extra ones, left empty.
pub(super) fn allocated(
    grid: &Grid,
    block: &Block,
    progress: &dyn Progress,
) -> Result<CutCells, GridError> {
    let [bx, by, depth] = block.shape();
    let len = bx * by * depth;
    // Its own stage: at 256³ the arrays are 1.9 GB, and their first touch (the system
    // zeroing fresh pages) can take longer than the sweeps.
    progress.stage("allocating the cells' arrays");
    Ok(CutCells {
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
        inertia: Vec::new(),
        aperture_centroid: Default::default(),
    })
}

/// The cut-cell values of the cells of `block` of `grid` (validated), from `surface`'s
/// faces, and the z apertures of its columns; the x and y apertures are left to
/// [`super::apertures`] and the surface centroids to [`finish_boundary_centroids`].
pub(super) fn cut_cells<S: Surface + ?Sized, const X: bool>(
    surface: &S,
    grid: &Grid,
    block: &Block,
    progress: &dyn Progress,
) -> Result<Swept, GridError> {
    let [bx, by, depth] = block.shape();
    let len = bx * by * depth;
    let mut out = allocated(grid, block, progress)?;
    let mut extra: Vec<Extra> = if X { zeroed(len)? } else { Vec::new() };
    let mut planes: Vec<[f64; 2]> = if X { zeroed(len + bx * by)? } else { Vec::new() };
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
    // The extra arrays by tile, or an empty slice for every tile.
    let tiles = tiling.tiles();
    let extra_tiles: Vec<&mut [Extra]> = if X {
        extra.chunks_mut(tile_cells).collect()
    } else {
        (0..tiles).map(|_| Default::default()).collect()
    };
    let plane_tiles: Vec<&mut [[f64; 2]]> = if X {
        planes.chunks_mut(tile_planes).collect()
    } else {
        (0..tiles).map(|_| Default::default()).collect()
    };
    out.volume
        .par_chunks_mut(tile_cells)
        .zip(out.centroid.par_chunks_mut(tile_cells))
        .zip(out.boundary_area.par_chunks_mut(tile_cells))
        .zip(out.boundary_vector.par_chunks_mut(tile_cells))
        .zip(out.boundary_centroid.par_chunks_mut(tile_cells))
        .zip(aperture_z.par_chunks_mut(tile_planes))
        .zip(extra_tiles.into_par_iter().zip(plane_tiles))
        .enumerate()
        .for_each(|(tile, (tile_arrays, (extra, planes)))| {
            let (((((volume, centroid), area), vector), centre), aperture_z) = tile_arrays;
            let mut cells = TileCells {
                cells: CellSlices {
                    volume,
                    centroid,
                    boundary_area: area,
                    boundary_vector: vector,
                    boundary_centroid: centre,
                },
                aperture_z,
                extra,
                planes,
            };
            let run = tiling.range(tile);
            let mut handed = vec![[0.0; 3]; run.len() * areas];
            let mut on_top = vec![0.0; run.len()];
            let extra_len = if X { run.len() } else { 0 };
            let mut handed_second = vec![[0.0; 3]; extra_len * areas];
            let mut on_top_moments = vec![[0.0; 2]; extra_len];
            for face in bins.faces(tile) {
                let normal =
                    if polygons { polygon_normal(surface, face, &units, scale) } else { None };
                surface.fan(face, |a, b, c| {
                    let t = Piece::triangle(units.map(a), units.map(b), units.map(c));
                    for_each_piece(&t, block, &run, false, |column, piece| {
                        let [i, j] = column_of(run.start + column);
                        let cells_of = column * depth..(column + 1) * depth;
                        let column_areas = column * areas..(column + 1) * areas;
                        let mut no_top = [0.0; 2];
                        let mut sink = MomentSink::<X> {
                            extra: if X { &mut cells.extra[cells_of.clone()] } else { &mut [] },
                            cells: cells.cells.part(cells_of),
                            handed_extra: HandedExtra {
                                second: if X {
                                    &mut handed_second[column_areas.clone()]
                                } else {
                                    &mut []
                                },
                                on_top: if X { &mut on_top_moments[column] } else { &mut no_top },
                            },
                            handed: &mut handed[column_areas],
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
                let sums = ColumnSums {
                    handed: &handed[column * areas..(column + 1) * areas],
                    on_top: on_top[column],
                    second: if X {
                        &handed_second[column * areas..(column + 1) * areas]
                    } else {
                        &[]
                    },
                    on_top_moments: if X { on_top_moments[column] } else { [0.0; 2] },
                };
                finish_column::<X>(
                    &mut cells,
                    column * depth..(column + 1) * depth,
                    column * (depth + 1)..(column + 1) * (depth + 1),
                    sums,
                    [i, j, first],
                    grid,
                );
            }
            done.add(1);
        });
    Ok((out, extra, planes))
}
