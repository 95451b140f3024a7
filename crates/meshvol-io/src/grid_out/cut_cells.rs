//! The cut-cell geometry of a grid ([`CutCells`]) as NumPy `.npz` and VTK `.vti`.
//!
//! - **`.npz`**: a zip of `.npy` arrays (stored, not compressed, so `numpy.load(…,
//!   mmap_mode=…)` readers and any zip tool read them): `origin` and `cell_size` (3,),
//!   `volume` and `fraction` (NX, NY, NZ), `centroid`, `boundary_vector` and
//!   `boundary_centroid` (NX, NY, NZ, 3), `boundary_area` (NX, NY, NZ), and the
//!   apertures `aperture_x` (NX+1, NY, NZ), `aperture_y` (NX, NY+1, NZ) and `aperture_z`
//!   (NX, NY, NZ+1), all float64 in C order; where computed, `inertia` (NX, NY, NZ, 3, 3)
//!   and the face centroids `aperture_x_centroid` (NX+1, NY, NZ, 3), `aperture_y_centroid`
//!   and `aperture_z_centroid`. A grid of volumes alone (no `--moments`) has `origin`,
//!   `cell_size`, `volume` and `fraction`.
//! - **`.vti`**: the cell arrays `volume`, `fraction`, `centroid`, `boundary_area`,
//!   `boundary_vector`, `boundary_centroid` (3 components for the vectors), and the
//!   apertures as field arrays (VTK `FieldData`, which has no shape): `aperture_x` with
//!   `(NX+1)·NY·NZ` tuples in VTK's order, x fastest (`(k·NY + j)·(NX+1) + i`), and
//!   likewise `aperture_y` and `aperture_z`; where computed, the cell array `inertia` (9
//!   components, row by row) and the field arrays `aperture_x_centroid`, … (3 components,
//!   in the apertures' order).
//!
//! [`cut_cell_arrays`] lists the cut-cell arrays (name, shape, values) once, for the
//! `.npz` and for the Zarr group (`zarr::ZarrGroup`, feature `zarr`): `volume`,
//! `fraction`, `centroid`, `boundary_area`, `boundary_vector`, `boundary_centroid`,
//! `aperture_x`, `aperture_y`, `aperture_z`, and where computed `inertia` (shape
//! `(NX, NY, NZ, 3, 3)`) and `aperture_x_centroid`, `aperture_y_centroid`,
//! `aperture_z_centroid` (the apertures' shapes with a last axis of 3).

use super::{check_len, npy_array, vti_arrays, CellValues, VtiArray, VtiField};
use meshvol::grid::{CutCells, Grid};
use std::io::{self, Seek, Write};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, ZipWriter};

/// The names of the face centroids' arrays.
const CENTROIDS: [&str; 3] = ["aperture_x_centroid", "aperture_y_centroid", "aperture_z_centroid"];

/// Adds `name.npy` (float64 `values` of `shape`) to a zip.
fn entry<W: Write + Seek>(
    zip: &mut ZipWriter<W>,
    name: &str,
    shape: &[usize],
    values: impl ExactSizeIterator<Item = f64>,
) -> io::Result<()> {
    let large = values.len() as u64 * 8 >= u32::MAX as u64;
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Stored)
        .large_file(large);
    zip.start_file(format!("{name}.npy"), options).map_err(io::Error::other)?;
    npy_array(zip, shape, values)
}

/// A `.npz` of a grid's cell volumes: `origin`, `cell_size`, `volume`, `fraction`, and
/// given a `density` (mass per volume unit), `mass`.
pub fn npz<W: Write + Seek>(
    out: W,
    grid: &Grid,
    volumes: &[f64],
    density: Option<f64>,
) -> io::Result<()> {
    check_len(grid, volumes)?;
    npz_arrays(out, grid, volume_arrays(&grid.counts, volumes, grid.cell_volume(), density))
}

/// A `.vti` file with cell arrays `volume` and `fraction`, and with a `density` (mass
/// per volume unit) `mass`.
pub fn vti(
    out: &mut impl Write,
    grid: &Grid,
    volumes: &[f64],
    density: Option<f64>,
) -> io::Result<()> {
    check_len(grid, volumes)?;
    let arrays = volume_arrays(&grid.counts, volumes, grid.cell_volume(), density);
    let written: Vec<_> = arrays
        .iter()
        .map(|a| move |c: usize, _: usize| a.written_as.of(a.values[c], a.cell))
        .collect();
    let cells: Vec<VtiArray> = arrays
        .iter()
        .zip(&written)
        .map(|(a, values)| VtiArray { name: a.name, components: 1, values })
        .collect();
    vti_arrays(out, grid, &cells, &[])
}

/// A `.npz` of a grid's `origin`, `cell_size` and `arrays`.
fn npz_arrays<W: Write + Seek>(out: W, grid: &Grid, arrays: Vec<CellArray>) -> io::Result<()> {
    let mut zip = ZipWriter::new(out);
    entry(&mut zip, "origin", &[3], grid.origin.into_iter())?;
    entry(&mut zip, "cell_size", &[3], grid.cell.into_iter())?;
    for array in arrays {
        entry(&mut zip, array.name, &array.shape, array.written())?;
    }
    zip.finish().map_err(io::Error::other)?;
    Ok(())
}

/// One float64 array of the cut-cell geometry: its name, its shape (the cells' along x,
/// y and z, one more along the axis of an array on faces, and a last axis of 3 for
/// vectors) and its values in C order, each written as [`CellValues::of`] makes it.
pub struct CellArray<'a> {
    pub name: &'static str,
    pub shape: Vec<usize>,
    pub values: &'a [f64],
    /// What is written of each value: the value (`Volume`), or for the arrays made from
    /// the volumes, `Fraction` (of `cell`) or `Mass`.
    pub written_as: CellValues,
    pub cell: f64,
}

impl CellArray<'_> {
    /// The values as written.
    pub fn written(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.values.iter().map(|&v| self.written_as.of(v, self.cell))
    }
}

/// The arrays every grid file makes of the cells' `volumes` (of `shape`, in cells of
/// volume `cell`), named and ordered as written: `volume`, `fraction`, and given a
/// `density` (mass per volume unit), `mass`.
fn volume_arrays<'a>(
    shape: &[usize],
    volumes: &'a [f64],
    cell: f64,
    density: Option<f64>,
) -> Vec<CellArray<'a>> {
    let of_volumes = |name, written_as| CellArray {
        name,
        shape: shape.to_vec(),
        values: volumes,
        written_as,
        cell,
    };
    let mut arrays = vec![
        of_volumes("volume", CellValues::Volume),
        of_volumes("fraction", CellValues::Fraction),
    ];
    arrays.extend(density.map(|rho| of_volumes("mass", CellValues::Mass(rho))));
    arrays
}

/// The arrays of `cells` as every cut-cell output names and orders them (module docs),
/// over the cells' region: the whole grid, or a block of it; given a `density` (mass
/// per volume unit), `mass` after `fraction`.
pub fn cut_cell_arrays(cells: &CutCells, density: Option<f64>) -> Vec<CellArray<'_>> {
    let shape = cells.shape();
    let vectors = vec![shape[0], shape[1], shape[2], 3];
    let cell = cells.grid.cell_volume();
    let array = |name, shape: Vec<usize>, values| CellArray {
        name,
        shape,
        values,
        written_as: CellValues::Volume,
        cell,
    };
    let mut arrays = volume_arrays(&shape, &cells.volume, cell, density);
    arrays.extend([
        array("centroid", vectors.clone(), cells.centroid.as_flattened()),
        array("boundary_area", shape.to_vec(), &cells.boundary_area),
        array("boundary_vector", vectors.clone(), cells.boundary_vector.as_flattened()),
        array("boundary_centroid", vectors, cells.boundary_centroid.as_flattened()),
    ]);
    for (axis, name) in ["aperture_x", "aperture_y", "aperture_z"].into_iter().enumerate() {
        let mut faces = shape.to_vec();
        faces[axis] += 1;
        arrays.push(array(name, faces, &cells.aperture[axis]));
    }
    if !cells.inertia.is_empty() {
        let tensors = vec![shape[0], shape[1], shape[2], 3, 3];
        arrays.push(array("inertia", tensors, cells.inertia.as_flattened().as_flattened()));
    }
    for (axis, name) in CENTROIDS.into_iter().enumerate() {
        let centroids = &cells.aperture_centroid[axis];
        if !centroids.is_empty() {
            let mut faces = vec![shape[0], shape[1], shape[2], 3];
            faces[axis] += 1;
            arrays.push(array(name, faces, centroids.as_flattened()));
        }
    }
    arrays
}

/// A `.npz` of the cut-cell geometry (module docs), with `mass` given a `density`.
pub fn npz_cut_cells<W: Write + Seek>(
    out: W,
    cells: &CutCells,
    density: Option<f64>,
) -> io::Result<()> {
    check_len(&cells.grid, &cells.volume)?;
    npz_arrays(out, &cells.grid, cut_cell_arrays(cells, density))
}

/// A `.vti` of the cut-cell geometry (module docs), with the cell array `mass` given a
/// `density`.
pub fn vti_cut_cells(
    out: &mut impl Write,
    cells: &CutCells,
    density: Option<f64>,
) -> io::Result<()> {
    let grid = &cells.grid;
    let cell = grid.cell_volume();
    let rho = density.unwrap_or(1.0);
    let [nx, ny, nz] = grid.counts;
    let inertia = |c: usize, m: usize| cells.inertia[c][m / 3][m % 3];
    let arrays = [
        VtiArray { name: "volume", components: 1, values: &|c, _| cells.volume[c] },
        VtiArray { name: "fraction", components: 1, values: &|c, _| cells.volume[c] / cell },
        VtiArray { name: "centroid", components: 3, values: &|c, m| cells.centroid[c][m] },
        VtiArray { name: "boundary_area", components: 1, values: &|c, _| cells.boundary_area[c] },
        VtiArray {
            name: "boundary_vector",
            components: 3,
            values: &|c, m| cells.boundary_vector[c][m],
        },
        VtiArray {
            name: "boundary_centroid",
            components: 3,
            values: &|c, m| cells.boundary_centroid[c][m],
        },
        VtiArray { name: "inertia", components: 9, values: &inertia },
        VtiArray { name: "mass", components: 1, values: &|c, _| cells.volume[c] * rho },
    ];
    // The extra arrays last, written where computed or asked for.
    let wanted = [true, true, true, true, true, true, !cells.inertia.is_empty(), density.is_some()];
    let arrays: Vec<VtiArray> =
        arrays.into_iter().zip(wanted).filter(|(_, w)| *w).map(|(a, _)| a).collect();
    // Each aperture array in VTK's order (x fastest) over its own shape.
    let shapes = [[nx + 1, ny, nz], [nx, ny + 1, nz], [nx, ny, nz + 1]];
    let c_order = move |axis: usize, t: usize| {
        let [sx, sy, sz] = shapes[axis];
        let (i, j, k) = (t % sx, t / sx % sy, t / (sx * sy));
        (i * sy + j) * sz + k
    };
    let vtk = |axis: usize| move |t: usize, _| cells.aperture[axis][c_order(axis, t)];
    let (ax, ay, az) = (vtk(0), vtk(1), vtk(2));
    let centre =
        |axis: usize| move |t: usize, m: usize| cells.aperture_centroid[axis][c_order(axis, t)][m];
    let (cx, cy, cz) = (centre(0), centre(1), centre(2));
    let tuples = |axis: usize| shapes[axis].iter().product();
    let fields = [
        VtiField {
            array: VtiArray { name: "aperture_x", components: 1, values: &ax },
            tuples: tuples(0),
        },
        VtiField {
            array: VtiArray { name: "aperture_y", components: 1, values: &ay },
            tuples: tuples(1),
        },
        VtiField {
            array: VtiArray { name: "aperture_z", components: 1, values: &az },
            tuples: tuples(2),
        },
        VtiField {
            array: VtiArray { name: CENTROIDS[0], components: 3, values: &cx },
            tuples: tuples(0),
        },
        VtiField {
            array: VtiArray { name: CENTROIDS[1], components: 3, values: &cy },
            tuples: tuples(1),
        },
        VtiField {
            array: VtiArray { name: CENTROIDS[2], components: 3, values: &cz },
            tuples: tuples(2),
        },
    ];
    let fields = &fields[..if cells.aperture_centroid[0].is_empty() { 3 } else { 6 }];
    vti_arrays(out, grid, &arrays, fields)
}
