//! Grids: `Mesh.grid` (per-cell volumes), `Mesh.profile` (volume below each level) and
//! `meshvol.union` (the volume of overlapping bodies as a certified interval).

use crate::dict::Fields;
use crate::errors::{bad_argument, mesh_error};
use crate::load::MeshArg;
use crate::mesh::PyMesh;
use meshvol::grid::{self, Axis, Levels, Region};
use meshvol::{mass_properties, Mesh, Surface};
use meshvol_io::grid_out::CellValues;
use meshvol_report::grid::{check_memory, choose, Spacing};
use meshvol_report::profile::ProfileReport;
use meshvol_report::quantities::Quantities;
use meshvol_report::reported_cells;
use meshvol_report::subject::Subject;
use meshvol_report::union::UnionReport;
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use rayon::prelude::*;

/// `pitch` as three cell sizes: one number for cubic cells, or three.
fn pitch_of(pitch: &Bound<'_, PyAny>) -> PyResult<[f64; 3]> {
    let sizes = match pitch.extract::<f64>() {
        Ok(h) => [h; 3],
        Err(_) => {
            let v =
                crate::convert::float_argument(pitch, "pitch", &[3], "a number or (hx, hy, hz)")?;
            [v[0], v[1], v[2]]
        }
    };
    if sizes.iter().any(|h| !(h.is_finite() && *h > 0.0)) {
        return Err(bad_argument(format!(
            "pitch must be positive; got ({}, {}, {})",
            sizes[0], sizes[1], sizes[2]
        )));
    }
    Ok(sizes)
}

/// `region` as cell ranges: three (start, end) pairs of whole numbers ≥ 0 (the core
/// checks them against the grid).
fn region_of(region: &Bound<'_, PyAny>) -> PyResult<Region> {
    let v =
        crate::convert::int_argument(region, "region", &[3, 2], "((i0, i1), (j0, j1), (k0, k1))")?;
    let mut ranges = [0..0, 0..0, 0..0];
    for (a, pair) in v.chunks_exact(2).enumerate() {
        let (start, end) = (pair[0], pair[1]);
        let (Ok(s), Ok(e)) = (usize::try_from(start), usize::try_from(end)) else {
            return Err(bad_argument(format!(
                "region must be ((i0, i1), (j0, j1), (k0, k1)) of cell indices ≥ 0; got \
                 ({start}, {end}) along {}",
                ["x", "y", "z"][a]
            )));
        };
        ranges[a] = s..e;
    }
    Ok(ranges)
}

/// `cells` as three positive counts.
pub fn counts_of(cells: &Bound<'_, PyAny>) -> PyResult<[usize; 3]> {
    let counts = crate::convert::int_argument(cells, "cells", &[3], "(nx, ny, nz)")?;
    if counts.iter().any(|&n| n < 1) {
        return Err(bad_argument(format!(
            "cells must be three positive whole numbers; got ({}, {}, {})",
            counts[0], counts[1], counts[2]
        )));
    }
    Ok([0, 1, 2].map(|a| usize::try_from(counts[a]).unwrap_or(usize::MAX)))
}

/// The grid `cells` or `pitch` and `bounds` describe (the mesh's bounding box without
/// bounds), as `meshvol grid` chooses it.
fn grid_of<'py, S: Surface>(
    py: Python<'py>,
    mesh: &S,
    cells: Option<&Bound<'py, PyAny>>,
    bounds: Option<&Bound<'py, PyAny>>,
    pitch: Option<&Bound<'py, PyAny>>,
) -> PyResult<grid::Grid> {
    let spacing = match (cells, pitch) {
        (Some(_), Some(_)) => return Err(bad_argument("give cells or pitch, not both")),
        (Some(counts), None) => Spacing::Cells(counts_of(counts)?),
        (None, Some(pitch)) => Spacing::Pitch(pitch_of(pitch)?),
        (None, None) => return Err(bad_argument("give cells=(nx, ny, nz) or pitch=h")),
    };
    let bounds = bounds.map(|b| crate::convert::bounds(b, "bounds")).transpose()?;
    let mesh_bounds = match bounds {
        Some(_) => None,
        None => py.detach(|| mass_properties(mesh)).bounds,
    };
    Ok(choose(bounds, mesh_bounds, spacing, "bounds").map_err(mesh_error)?.0)
}

/// The cut-cell geometry of `mesh` on the grid the arguments describe, as a
/// `meshvol.CutCells` (a dict of arrays named as `meshvol grid --moments` writes them),
/// lengths, areas and volumes in the report's units (apertures and fractions are ratios).
/// Where `Mesh.cells` measures: the grid (`cells`, `bounds`, `pitch`) and the block.
pub struct Place<'a, 'py> {
    pub cells: Option<&'a Bound<'py, PyAny>>,
    pub bounds: Option<&'a Bound<'py, PyAny>>,
    pub pitch: Option<&'a Bound<'py, PyAny>>,
    pub region: Option<&'a Bound<'py, PyAny>>,
}

pub fn cut_cells<'py, S: Surface>(
    py: Python<'py>,
    mesh: &S,
    Place { cells, bounds, pitch, region }: Place<'_, 'py>,
    extras: grid::Extras,
    scale: &meshvol_report::units::Scale,
    on: &meshvol_opencl::Where,
) -> PyResult<Bound<'py, PyAny>> {
    use numpy::ndarray::{Array, IxDyn};
    let grid = grid_of(py, mesh, cells, bounds, pitch)?;
    let arrays = grid::CutCells::bytes_with(&grid, extras) / grid.array_bytes().max(1);
    let region = region.map(region_of).transpose()?;
    match &region {
        None => check_memory(grid.counts, arrays, "grid").map_err(mesh_error)?,
        Some(region) => {
            // Computed up to the grid's far x and y faces, then cut back.
            let [nx, ny, _] = grid.counts;
            let (i0, j0) = (region[0].start.min(nx), region[1].start.min(ny));
            let reach = [nx - i0, ny - j0, region[2].len()];
            check_memory(reach, arrays, "block").map_err(mesh_error)?;
        }
    }
    let region = region.unwrap_or_else(|| grid.counts.map(|n| 0..n));
    let cpu =
        || grid::cut_cells_extras(mesh, &grid, &region, extras, &()).map_err(|e| e.to_string());
    let fell_back = std::sync::Mutex::new(Vec::new());
    let warn = |w: &str| fell_back.lock().unwrap_or_else(|e| e.into_inner()).push(w.to_string());
    let c = py.detach(|| -> Result<_, String> {
        // On the CPU or an OpenCL device (the same bits), as `grid --backend` chooses;
        // the extra arrays on the CPU (`Mesh.cells` refused 'opencl' for them).
        let mut c = match extras == grid::Extras::default() {
            true => on.cut_cells(mesh, &grid, &region, &(), cpu, warn)?,
            false => cpu()?,
        };
        // In the report's units, where they are (the one conversion every grid sink
        // takes): at 256³ the arrays are 1.9 GB, the only copy.
        reported_cells::cut_cells(scale, &mut c)?;
        Ok(c)
    });
    let fell_back = fell_back.into_inner().unwrap_or_else(|e| e.into_inner());
    crate::errors::warn_all(py, &fell_back)?;
    let mut c = c.map_err(mesh_error)?;
    let [nx, ny, nz] = c.shape();
    let fraction = c.fraction();
    let dict = pyo3::types::PyDict::new(py);
    // Moved into NumPy without a copy.
    let put = |name: &str, shape: Vec<usize>, values: Vec<f64>| {
        let array = Array::from_shape_vec(IxDyn(&shape), values).map_err(mesh_error)?;
        dict.set_item(name, array.into_pyarray(py))
    };
    let (cells, vectors) = (vec![nx, ny, nz], vec![nx, ny, nz, 3]);
    let [ax, ay, az] = std::mem::take(&mut c.aperture);
    let [cx, cy, cz] = std::mem::take(&mut c.aperture_centroid);
    put("volume", cells.clone(), c.volume)?;
    put("fraction", cells.clone(), fraction)?;
    put("centroid", vectors.clone(), c.centroid.into_flattened())?;
    put("boundary_area", cells, c.boundary_area)?;
    put("boundary_vector", vectors.clone(), c.boundary_vector.into_flattened())?;
    put("boundary_centroid", vectors, c.boundary_centroid.into_flattened())?;
    put("aperture_x", vec![nx + 1, ny, nz], ax)?;
    put("aperture_y", vec![nx, ny + 1, nz], ay)?;
    put("aperture_z", vec![nx, ny, nz + 1], az)?;
    if !c.inertia.is_empty() {
        put("inertia", vec![nx, ny, nz, 3, 3], c.inertia.into_flattened().into_flattened())?;
    }
    let shapes = [[nx + 1, ny, nz, 3], [nx, ny + 1, nz, 3], [nx, ny, nz + 1, 3]];
    let names = ["aperture_x_centroid", "aperture_y_centroid", "aperture_z_centroid"];
    for ((name, shape), points) in names.into_iter().zip(shapes).zip([cx, cy, cz]) {
        if !points.is_empty() {
            put(name, shape.to_vec(), points.into_flattened())?;
        }
    }
    let class = py.import("meshvol._grid")?.getattr("CutCells")?;
    // c.grid is in the report's units: the block's corner as the grid computes it.
    let g = c.grid;
    let origin: [f64; 3] = [0, 1, 2].map(|a| g.origin[a] + c.region[a].start as f64 * g.cell[a]);
    class.call1((dict, origin, g.cell))
}

/// `backend=` and `opencl_device=` as `grid --backend` and `--opencl-device` take them.
pub fn backend(backend: &str, device: Option<usize>) -> PyResult<meshvol_opencl::Where> {
    let backend = backend.parse().map_err(bad_argument)?;
    Ok(meshvol_opencl::Where { backend, device })
}

/// Where `Mesh.grid` measures: `cells`, `bounds`, `fraction`, `pitch`, `region`.
pub type GridPlace<'a, 'py> = (
    Option<&'a Bound<'py, PyAny>>,
    Option<&'a Bound<'py, PyAny>>,
    bool,
    Option<&'a Bound<'py, PyAny>>,
    Option<&'a Bound<'py, PyAny>>,
);

/// The cell volumes of `mesh` (a checked solid, or a surface as wound) on the grid the
/// arguments describe, or of the block `region` of it, as a `meshvol.Grid`; the kernel's
/// stages timed on `clock` when given.
#[allow(clippy::too_many_arguments)]
pub fn cell_volumes<'py, S: Surface>(
    py: Python<'py>,
    mesh: &S,
    (cells, bounds, fraction, pitch, region): GridPlace<'_, 'py>,
    scale: &meshvol_report::units::Scale,
    on: &meshvol_opencl::Where,
    clock: Option<&crate::timings::Clock>,
) -> PyResult<Bound<'py, PyAny>> {
    let grid = grid_of(py, mesh, cells, bounds, pitch)?;
    let block = region.map(region_of).transpose()?;
    let start = block.as_ref().map_or([0; 3], |r| [r[0].start, r[1].start, r[2].start]);
    let region = block.clone().unwrap_or_else(|| grid.counts.map(|n| 0..n));
    let shape = region.clone().map(|r| r.len());
    check_memory(shape, 1, if block.is_some() { "block" } else { "grid" }).map_err(mesh_error)?;
    // On the CPU or an OpenCL device (the same bits), as `grid --backend` chooses.
    let fell_back = std::sync::Mutex::new(Vec::new());
    let cpu = || {
        match (&block, clock) {
            (None, Some(clock)) => grid::cell_volumes_with(mesh, &grid, clock),
            (None, None) => grid::cell_volumes(mesh, &grid),
            (Some(block), _) => grid::cell_volumes_region(mesh, &grid, block),
        }
        .map_err(|e| e.to_string())
    };
    let warn = |w: &str| fell_back.lock().unwrap_or_else(|e| e.into_inner()).push(w.to_string());
    // With timings=True, a device's stages (building the kernel, laying out the slabs,
    // uploading, the kernel, reading back) are timed as the CPU kernel's are.
    let device: &dyn meshvol::progress::Progress = match clock {
        Some(clock) => clock,
        None => &(),
    };
    let volumes = py.detach(|| on.cell_volumes(mesh, &grid, &region, device, cpu, warn));
    let fell_back = fell_back.into_inner().unwrap_or_else(|e| e.into_inner());
    crate::errors::warn_all(py, &fell_back)?;
    let mut volumes = volumes.map_err(mesh_error)?;
    // In the report's units (the one conversion every grid sink takes), then what the
    // array holds, as the command's .npy: fractions, masses with a density, or volumes.
    let reported = reported_cells::grid(scale, &grid).map_err(mesh_error)?;
    let values = CellValues::asked(fraction, scale.mass_per_volume());
    let cell = reported.cell_volume();
    py.detach(|| {
        reported_cells::volumes(scale, &mut volumes);
        if values != CellValues::Volume {
            volumes.par_iter_mut().for_each(|v| *v = values.of(*v, cell));
        }
    });
    let array = Array3::from_shape_vec(shape, volumes).map_err(mesh_error)?;
    let g = reported;
    let origin: [f64; 3] = [0, 1, 2].map(|a| g.origin[a] + start[a] as f64 * g.cell[a]);
    let class = py.import("meshvol._grid")?.getattr("Grid")?;
    class.call1((array.into_pyarray(py), origin, g.cell, fraction))
}

/// A profile along an axis, with the names of the keys of `meshvol profile --json`:
/// levels (n + 1), the volume below each level, the volume of each of the n slabs
/// between levels, and the area of the solid's cross-section at each level. The arrays
/// are float64 and belong to this object.
#[pyclass(module = "meshvol", name = "Profile", frozen)]
pub struct PyProfile {
    report: ProfileReport,
    fields: Fields,
}

impl PyProfile {
    /// With `timings`, the same with the stages' timings as its last key.
    pub fn timed(
        self,
        timings: Option<Vec<meshvol_report::timings::StageTiming>>,
    ) -> PyResult<Self> {
        Ok(PyProfile { fields: self.fields.with_timings(timings)?, report: self.report })
    }

    /// The report's warnings.
    pub fn warnings(&self) -> &[String] {
        &self.report.warnings
    }
}

#[pymethods]
impl PyProfile {
    /// The levels: n + 1 coordinates along the axis.
    #[getter]
    fn levels<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.report.levels)
    }

    /// The volume below each level.
    #[getter]
    fn volume_below<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.report.volume_below)
    }

    /// The volume between levels k and k + 1 (n values).
    #[getter]
    fn slab_volume<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.report.slab_volume)
    }

    /// The area of the cross-section at each level.
    #[getter]
    fn section_area<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.report.section_area)
    }

    fn __repr__(&self) -> String {
        let r = &self.report;
        format!("Profile(axis='{}', slabs={})", r.axis, r.slab_volume.len())
    }
}

/// The profile of `subject` along `axis`.
pub fn profile(
    py: Python<'_>,
    subject: &Subject<'_, Mesh>,
    axis: &str,
    levels: Option<i64>,
    step: Option<f64>,
    units: &meshvol_report::units::UnitOptions,
) -> PyResult<PyProfile> {
    let axis = match axis {
        "x" | "X" => Axis::X,
        "y" | "Y" => Axis::Y,
        "z" | "Z" => Axis::Z,
        other => return Err(bad_argument(format!("axis must be 'x', 'y' or 'z'; got '{other}'"))),
    };
    let levels = match (levels, step) {
        (Some(_), Some(_)) => return Err(bad_argument("give levels or step, not both")),
        (Some(n), None) if n < 1 => {
            return Err(bad_argument(format!("levels must be at least 1; got {n}")));
        }
        (Some(n), None) => Levels::Count(usize::try_from(n).unwrap_or(usize::MAX)),
        (None, Some(h)) if !(h.is_finite() && h > 0.0) => {
            return Err(bad_argument(format!("step must be a positive number; got {h}")));
        }
        (None, Some(h)) => Levels::Step(h),
        (None, None) => return Err(bad_argument("give levels=n or step=h")),
    };
    let report = py
        .detach(|| meshvol_report::profile::profile(subject, axis, levels))
        .map_err(mesh_error)?
        .in_units(units, subject.source.unit)
        .map_err(mesh_error)?;
    Ok(PyProfile { fields: Fields::new(&report)?, report })
}

/// The volume of a union of bodies as a certified interval [lower, upper], with the
/// names of the keys of `meshvol union --json`; plus the bodies measured turned
/// outward because they were wound inward (flipped), and the grid columns that could
/// not be resolved exactly (their bounds stay in the interval).
#[pyclass(module = "meshvol", name = "Union", frozen)]
pub struct PyUnion {
    report: UnionReport,
    fields: Fields,
}

#[pymethods]
impl PyUnion {
    fn __repr__(&self) -> String {
        let r = &self.report;
        format!(
            "Union(lower={:?}, upper={:?}, bodies={}, sum_of_volumes={:?})",
            r.interval.lower, r.interval.upper, r.bodies, r.sum_of_volumes
        )
    }
}

/// The volume of the union of closed bodies, as a certified interval, without a
/// boolean mesh (the report of `meshvol union`).
///
/// meshes is a list of meshes (meshvol.Mesh, objects with .vertices and .faces, such as
/// trimesh.Trimesh, or paths read as meshvol.load reads them); a single mesh or path,
/// or a list of one, stands for its bodies (each
/// outermost shell with its cavities), as a single file does for the command.
/// Refinement stops once upper - lower <= tolerance * lower. check=True (the default)
/// measures each mesh's checked solid, with holes capped and the caps' uncertainty
/// widening the interval; check=False the surfaces as wound. units and density as the
/// command's --units and --density. timings=True adds `timings`: each mesh's check
/// (run again), then measuring, as the command's --timings.
#[pyfunction]
#[pyo3(signature = (meshes, tolerance = 1e-6, check = true, units = None, density = None, timings = false))]
pub fn union(
    py: Python<'_>,
    meshes: &Bound<'_, PyAny>,
    tolerance: f64,
    check: bool,
    units: Option<&str>,
    density: Option<&Bound<'_, PyAny>>,
    timings: bool,
) -> PyResult<PyUnion> {
    let options = crate::units::options(units, density)?;
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(bad_argument(format!("tolerance must be a positive number; got {tolerance}")));
    }
    let single = meshes.cast::<PyMesh>().is_ok()
        || crate::convert::mesh_like(meshes)?.is_some()
        || crate::load::is_path(meshes)?;
    let given: Vec<MeshArg<'_>> = if single {
        vec![MeshArg::of(meshes)?]
    } else {
        meshes.try_iter()?.map(|item| MeshArg::of(&item?)).collect::<PyResult<_>>()?
    };
    let meshes: Vec<&Bound<'_, PyMesh>> = given.iter().map(|m| &m.mesh).collect();
    if meshes.is_empty() {
        return Err(mesh_error("no bodies: give at least one mesh"));
    }
    let clock = timings.then(crate::timings::Clock::new);
    let timed: Vec<meshvol::topology::Check> = match (&clock, check) {
        (Some(c), true) => {
            meshes.iter().map(|m| m.get().timed_check(py, c)).collect::<PyResult<_>>()?
        }
        _ => Vec::new(),
    };
    let mut subjects =
        meshes.iter().map(|m| m.get().subject(py, check)).collect::<PyResult<Vec<_>>>()?;
    for (s, c) in subjects.iter_mut().zip(&timed) {
        s.check = Some(c);
    }
    crate::timings::stage(clock.as_ref(), "measuring");
    let report =
        py.detach(|| meshvol_report::union::union(&subjects, tolerance)).map_err(mesh_error)?;
    let files: Vec<(&str, Option<meshvol_io::LengthUnit>)> =
        subjects.iter().map(|s| (s.source.name(), s.source.unit)).collect();
    let report = report.in_units(&options, &files).map_err(mesh_error)?;
    crate::load::warn_for(py, &given, &report.warnings)?;
    let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
    Ok(PyUnion { fields, report })
}

crate::dict::report_methods!(PyProfile, "Profile");

crate::dict::report_methods!(PyUnion, "Union");
