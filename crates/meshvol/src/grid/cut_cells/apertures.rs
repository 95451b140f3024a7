//! The x and y apertures, from the cells' boundary vectors.
//!
//! The divergence theorem with the constant field `e_x` on the part of the solid in the
//! tube of cells `(·, j, k)` beyond the plane `x = x_i` gives
//!
//! ```text
//! A_x(i, j, k) = Σ_{m ≥ i} ∫ n_x dA over the surface in cell (m, j, k)
//!              + ∫ n_x dA over the surface in the tube beyond the grid (x ≥ x_nx)
//! ```
//!
//! the solid's cross-section in that cell face: the z apertures' suffix sum of
//! projected areas, turned to x (and to y). The sums run from the grid's far face down,
//! compensated (TwoSum), in the same order for every cell. The surface beyond the far
//! face is cut from the few faces that reach it.
//!
//! The face centroids follow from the same theorem with the linear fields `(y', 0, 0)`
//! and `(z', 0, 0)` (local to the tube; no flux through its walls): the first moments of
//! the wetted part of the face are `Σ_{m ≥ i} ∫ y' n_x dA` (and `z'`) over the same
//! surface. On a plane `z = z_k` they are the column's suffix sums of `∫ x' n_z dA` and
//! `∫ y' n_z dA`, which the volume's centroid hands down already ([`super::kernel`]).

use super::arrays::CutCells;
use super::integrals::{face_moments, surface_part};
use super::kernel::{add_surface, face_areas, finish_boundary_centroids, polygon_normal, Extra};
use crate::accumulate::CompensatedSum;
use crate::grid::cells::{cover, sweep_axis, Piece, Units};
use crate::grid::clip::Polygon;
use crate::grid::OCCUPANCY_TOLERANCE;
use crate::{Point, Surface};
use rayon::prelude::*;

/// `∫ n_x dA`, `∫ n_y dA` over the surface beyond the grid's far x face, per tube `(j, k)`,
/// and beyond its far y face, per tube `(i, k)`; in grid units (faces of area 1); each
/// with its first moments across the tube and in z (local to the tube), when `extras`
/// is not empty. Parts lying on a far face are the surface of the cells beside it (the
/// far faces are closed): they are added to those cells' surface sums (and `extras`)
/// instead.
fn beyond<S: Surface + ?Sized>(
    surface: &S,
    cells: &mut CutCells,
    extras: &mut [Extra],
) -> [Vec<[f64; 3]>; 2] {
    let grid = cells.grid;
    let [nx, ny, nz] = grid.counts;
    let units = Units::new(&grid);
    let scale = face_areas(grid.cell);
    let far = [nx as f64, ny as f64];
    let reaches = |face: usize| {
        let mut hit = false;
        surface.fan(face, |a, b, c| {
            let t = [units.map(a), units.map(b), units.map(c)];
            hit |= (0..2).any(|d| t.iter().any(|p| p[d] >= far[d]));
        });
        hit
    };
    let faces: Vec<usize> =
        (0..surface.face_count()).into_par_iter().filter(|&f| reaches(f)).collect();
    let mut sums = [vec![[0.0; 3]; ny * nz], vec![[0.0; 3]; nx * nz]];
    let moments = !extras.is_empty();
    for face in faces {
        let normal = polygon_normal(surface, face, &units, scale);
        surface.fan(face, |a, b, c| {
            let t = Piece::triangle(units.map(a), units.map(b), units.map(c));
            for axis in 0..2 {
                let (mut inside, mut past) = (Piece::EMPTY, Piece::EMPTY);
                t.split_axis_into(axis, far[axis], &mut inside, &mut past);
                let on_face = past.range(axis) == (far[axis], far[axis]);
                // Across the tube: y for the x face, x for the y face; then z.
                let (across, n_across) = if axis == 0 { (1, ny) } else { (0, nx) };
                let r = past.range(across);
                let cells_across = cover(r.0, r.1, n_across, false);
                let sums = &mut sums[axis];
                sweep_axis(&past, across, r, cells_across, false, |m, strip| {
                    let z = strip.range(2);
                    sweep_axis(strip, 2, z, cover(z.0, z.1, nz, false), false, |k, part| {
                        if !on_face {
                            let s = &mut sums[m * nz + k];
                            s[0] += normal_component(part, axis);
                            if moments {
                                let mut corner = [m as f64, m as f64, k as f64];
                                corner[axis] = far[axis];
                                let f = face_moments(part, corner);
                                s[1] += f[2 * axis];
                                s[2] += f[2 * axis + 1];
                            }
                            return true;
                        }
                        let mut at = [m, m, k];
                        at[axis] = far[axis] as usize - 1;
                        let Some(n) = cells.local(at) else {
                            return true;
                        };
                        if let Some(extra) = extras.get_mut(n) {
                            let f = face_moments(part, at.map(|x| x as f64));
                            for (e, t) in extra.face.iter_mut().zip(f) {
                                *e += t;
                            }
                        }
                        if let Some((vector, centre)) = surface_part(part, at.map(|x| x as f64)) {
                            add_surface(
                                (&mut cells.boundary_area[n], &mut cells.boundary_vector[n]),
                                &mut cells.boundary_centroid[n],
                                (vector, centre, normal),
                                scale,
                            );
                        }
                        true
                    });
                    true
                });
            }
        });
    }
    sums
}

/// `∫ n_axis dA` of a planar polygon: half its fan's summed cross products on `axis`.
fn normal_component<const N: usize>(part: &Polygon<N>, axis: usize) -> f64 {
    let v = part.vertices();
    if v.len() < 3 {
        return 0.0;
    }
    let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
    let o = v[0];
    let mut twice = 0.0;
    for w in v[1..].windows(2) {
        let (a, b) = (w[0], w[1]);
        twice += (a[p] - o[p]) * (b[q] - o[q]) - (a[q] - o[q]) * (b[p] - o[p]);
    }
    0.5 * twice
}

/// Tubes `(j, k)` a task sums along x in [`fill`] (32 KiB of each plane's apertures).
const TUBES: usize = 4096;

/// The sums beyond the grid's far x and y faces ([`beyond`]), per tube.
pub(super) type Beyond = [Vec<[f64; 3]>; 2];

/// Fills `cells.aperture[0]` and `[1]` from the boundary vectors, and finishes the surface
/// centroids: the cells' region must reach the grid's far y face, and the far x face
/// unless `carried` holds the x sums of every tube at the plane where the region ends
/// (what this returned for the cells beyond: the sums run from the far faces down).
/// Returns the sums beyond the far faces (with moments when `extras` is not empty, for
/// [`face_centroids`]) and the x sums at the region's first plane.
pub(super) fn fill<S: Surface + ?Sized>(
    surface: &S,
    cells: &mut CutCells,
    extras: &mut [Extra],
    carried: Option<Vec<CompensatedSum>>,
) -> (Beyond, Vec<CompensatedSum>) {
    let beyond = beyond(surface, cells, extras);
    let [beyond_x, beyond_y] = &beyond;
    let grid = cells.grid;
    let nz = grid.counts[2];
    let [bx, by, bz] = cells.shape();
    let [i0, j0, k0] = cells.region.clone().map(|r| r.start);
    debug_assert!((carried.is_some() || i0 + bx == grid.counts[0]) && j0 + by == grid.counts[1]);
    let face = [grid.cell[1] * grid.cell[2], grid.cell[0] * grid.cell[2]];
    let (vectors, areas) = (&cells.boundary_vector, &cells.boundary_area);
    let centroids = &mut cells.boundary_centroid;
    let [aperture_x, aperture_y, _] = &mut cells.aperture;

    // x: every tube (j, k) from the far face down; runs of tubes in parallel, each in one
    // task (a task per plane waited at every plane for both workers: on a busy machine,
    // for a descheduled one). Each tube's sum is the same whatever the runs.
    let plane = by * bz;
    let tube = |t: usize| (j0 + t / bz) * nz + k0 + t % bz;
    let start = |b: f64| CompensatedSum::from_parts(b, 0.0);
    let mut state =
        carried.unwrap_or_else(|| (0..plane).map(|t| start(beyond_x[tube(t)][0])).collect());
    let mut runs: Vec<Vec<&mut [f64]>> =
        (0..plane.div_ceil(TUBES)).map(|_| Vec::with_capacity(bx + 1)).collect();
    for planes in aperture_x.chunks_mut(plane) {
        for (run, part) in runs.iter_mut().zip(planes.chunks_mut(TUBES)) {
            run.push(part);
        }
    }
    runs.into_par_iter().zip(state.par_chunks_mut(TUBES)).enumerate().for_each(
        |(r, (mut planes, state))| {
            for (a, s) in planes[bx].iter_mut().zip(state.iter()) {
                *a = s.value();
            }
            for i in (0..bx).rev() {
                let first = i * plane + r * TUBES;
                let cells = &vectors[first..first + state.len()];
                for ((a, s), v) in planes[i].iter_mut().zip(state.iter_mut()).zip(cells) {
                    s.add(v[0] / face[0]);
                    *a = s.value();
                }
            }
        },
    );

    // y: within each slab x = i, from the far face down; and the slab's surface
    // centroids, now that every part is in (one pass over the slab for both).
    let slabs = aperture_y.par_chunks_mut((by + 1) * bz).zip(centroids.par_chunks_mut(plane));
    slabs.enumerate().for_each(|(i, (out, centroids))| {
        let cells_i = &vectors[i * plane..(i + 1) * plane];
        let slab = &areas[i * plane..(i + 1) * plane];
        finish_boundary_centroids(&grid, [i0 + i, j0, k0], bz, centroids, slab);
        let first = (i0 + i) * nz + k0;
        let mut state: Vec<CompensatedSum> =
            beyond_y[first..first + bz].iter().map(|b| start(b[0])).collect();
        for (a, s) in out[by * bz..].iter_mut().zip(&state) {
            *a = s.value();
        }
        for j in (0..by).rev() {
            let row = &cells_i[j * bz..(j + 1) * bz];
            for ((a, s), v) in out[j * bz..(j + 1) * bz].iter_mut().zip(&mut state).zip(row) {
                s.add(v[1] / face[1]);
                *a = s.value();
            }
        }
    });
    (beyond, state)
}

/// The centroids of the wetted parts of the cell faces (world; NaN where the aperture is
/// within [`OCCUPANCY_TOLERANCE`] of 0, the face's middle where it is within it of ±1),
/// from the apertures `fill` left, the cells' face moments, the z faces' moments
/// `planes` (per column, as the z apertures) and the sums `beyond` the far faces. The
/// moments are summed as the apertures are: compensated, from the far faces down, the x
/// ones from `carried` (as [`fill`]'s) where the region stops short of the far x face.
/// Returns the centroids and the x moments' sums at the region's first plane.
pub(super) fn face_centroids(
    cells: &CutCells,
    extras: &[Extra],
    planes: &[[f64; 2]],
    [beyond_x, beyond_y]: &Beyond,
    carried: Option<Vec<[CompensatedSum; 2]>>,
) -> ([Vec<Point>; 3], Vec<[CompensatedSum; 2]>) {
    let grid = cells.grid;
    let nz = grid.counts[2];
    let [bx, by, bz] = cells.shape();
    let [i0, j0, k0] = cells.region.clone().map(|r| r.start);
    let plane = by * bz;
    // The point of a face: `at` its grid corner, `moments` along axes `p` and `q`.
    let point = |at: [usize; 3], aperture: f64, (p, q): (usize, usize), moments: [f64; 2]| {
        let empty = aperture.abs() <= OCCUPANCY_TOLERANCE;
        let full = (aperture.abs() - 1.0).abs() <= OCCUPANCY_TOLERANCE;
        let mut local = [0.0; 3];
        for (d, m) in [(p, moments[0]), (q, moments[1])] {
            local[d] = if full { 0.5 } else { (m / aperture).clamp(0.0, 1.0) };
        }
        [0, 1, 2].map(|d| {
            if empty {
                f64::NAN
            } else {
                grid.origin[d] + (at[d] as f64 + local[d]) * grid.cell[d]
            }
        })
    };
    let start = |b: [f64; 3]| [1, 2].map(|d| CompensatedSum::from_parts(b[d], 0.0));
    let value = |s: &[CompensatedSum; 2]| s.map(|s| s.value());

    // x: tube by tube from the far face down.
    let mut x = vec![[0.0; 3]; (bx + 1) * plane];
    let state: Vec<[CompensatedSum; 2]> = x
        .par_chunks_mut(bx + 1)
        .enumerate()
        .map(|(t, out)| {
            let (j, k) = (t / bz, t % bz);
            let mut state = match &carried {
                Some(carried) => carried[t],
                None => start(beyond_x[(j0 + j) * nz + k0 + k]),
            };
            for i in (0..=bx).rev() {
                if i < bx {
                    let f = extras[i * plane + t].face;
                    state[0].add(f[0]);
                    state[1].add(f[1]);
                }
                let at = [i0 + i, j0 + j, k0 + k];
                out[i] = point(at, cells.aperture[0][i * plane + t], (1, 2), value(&state));
            }
            state
        })
        .collect();
    // Out of the tubes' order into C order over (NX + 1, NY, NZ).
    let mut aperture_x = vec![[0.0; 3]; (bx + 1) * plane];
    aperture_x.par_chunks_mut(plane).enumerate().for_each(|(i, out)| {
        for (t, o) in out.iter_mut().enumerate() {
            *o = x[t * (bx + 1) + i];
        }
    });
    drop(x);

    // y: within each slab x = i, from the far face down.
    let mut aperture_y = vec![[0.0; 3]; bx * (by + 1) * bz];
    aperture_y.par_chunks_mut((by + 1) * bz).enumerate().for_each(|(i, out)| {
        let first = (i0 + i) * nz + k0;
        for k in 0..bz {
            let mut state = start(beyond_y[first + k]);
            for j in (0..=by).rev() {
                if j < by {
                    let f = extras[i * plane + j * bz + k].face;
                    state[0].add(f[2]);
                    state[1].add(f[3]);
                }
                let n = j * bz + k;
                let a = cells.aperture[1][i * (by + 1) * bz + n];
                out[n] = point([i0 + i, j0 + j, k0 + k], a, (0, 2), value(&state));
            }
        }
    });

    // z: the moments the columns' finish left, per plane.
    let columns = bz + 1;
    let aperture_z: Vec<Point> = (0..bx * by * columns)
        .into_par_iter()
        .map(|n| {
            let (c, k) = (n / columns, n % columns);
            let at = [i0 + c / by, j0 + c % by, k0 + k];
            point(at, cells.aperture[2][n], (0, 1), planes[n])
        })
        .collect();
    ([aperture_x, aperture_y, aperture_z], state)
}
