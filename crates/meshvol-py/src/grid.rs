//! Grids: `Mesh.grid` (per-cell volumes), `Mesh.profile` (volume below each level) and
//! `meshvol.union` (the volume of overlapping bodies as a certified interval).

use crate::errors::{bad_argument, mesh_error};
use crate::mesh::{mesh_of, PyMesh};
use meshvol::grid::{self, bytes_text, Axis, FaceSubset, Grid, GridError, Levels};
use meshvol::{mass_properties, Surface};
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray1, PyArray3};
use pyo3::prelude::*;

/// Memory the system can still hand out, from /proc/meminfo (None elsewhere).
fn available_memory() -> Option<u128> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses a grid whose cell array would not fit in the memory available (the
/// command's check: an allocation the system overcommits would kill the process later).
fn check_memory(grid: &Grid) -> PyResult<()> {
    let need = grid.array_bytes();
    match available_memory() {
        Some(available) if need > available => {
            let [nx, ny, nz] = grid.counts;
            let cells = nx as u128 * ny as u128 * nz as u128;
            Err(mesh_error(format!(
                "a {nx}×{ny}×{nz} grid has {cells} cells and would need {} of memory; {} is \
                 available: use fewer cells",
                bytes_text(need),
                bytes_text(available)
            )))
        }
        _ => Ok(()),
    }
}

/// `pitch` as three cell sizes: one number for cubic cells, or three.
fn pitch_of(pitch: &Bound<'_, PyAny>) -> PyResult<[f64; 3]> {
    let sizes = match pitch.extract::<f64>() {
        Ok(h) => [h; 3],
        Err(_) => pitch
            .extract::<[f64; 3]>()
            .map_err(|_| bad_argument("pitch must be a number or three numbers (hx, hy, hz)"))?,
    };
    if sizes.iter().any(|h| !(h.is_finite() && *h > 0.0)) {
        return Err(bad_argument(format!(
            "pitch must be positive; got ({}, {}, {})",
            sizes[0], sizes[1], sizes[2]
        )));
    }
    Ok(sizes)
}

/// The cell volumes of `mesh` (a checked solid, or a surface as wound) on the grid the
/// arguments describe.
pub fn cell_volumes<'py, S: Surface>(
    py: Python<'py>,
    mesh: &S,
    cells: Option<[i64; 3]>,
    bounds: Option<([f64; 3], [f64; 3])>,
    fraction: bool,
    pitch: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let (min, max, from_mesh) = match bounds {
        Some((min, max)) => (min, max, false),
        None => match py.detach(|| mass_properties(mesh)).bounds {
            Some(b) => (b.min, b.max, true),
            None => return Err(mesh_error("no vertices: there is no surface to measure")),
        },
    };
    let grid = match (cells, pitch) {
        (Some(_), Some(_)) => return Err(bad_argument("give cells or pitch, not both")),
        (Some(counts), None) => {
            if counts.iter().any(|&n| n < 1) {
                return Err(bad_argument(format!(
                    "cells must be three positive whole numbers; got ({}, {}, {})",
                    counts[0], counts[1], counts[2]
                )));
            }
            let counts = counts.map(|n| usize::try_from(n).unwrap_or(usize::MAX));
            Grid::from_bounds(min, max, counts)
        }
        (None, Some(pitch)) => Grid::with_pitch(min, max, pitch_of(pitch)?),
        (None, None) => return Err(bad_argument("give cells=(nx, ny, nz) or pitch=h")),
    }
    .map_err(|e| match e {
        GridError::EmptyBounds { .. } if from_mesh => {
            mesh_error(format!("{e}; the mesh is flat: give bounds"))
        }
        e => mesh_error(e),
    })?;
    check_memory(&grid)?;
    let mut volumes = py.detach(|| grid::cell_volumes(mesh, &grid)).map_err(mesh_error)?;
    if fraction {
        let cell = grid.cell_volume();
        volumes.iter_mut().for_each(|v| *v /= cell);
    }
    let array = Array3::from_shape_vec(grid.counts, volumes).map_err(mesh_error)?;
    Ok(array.into_pyarray(py))
}

/// A profile along an axis, with the names of the keys of `meshvol profile --json`:
/// levels (n + 1), the volume below each level, the volume of each of the n slabs
/// between levels, and the area of the solid's cross-section at each level. The arrays
/// are float64 and belong to this object.
#[pyclass(module = "meshvol", name = "Profile", frozen)]
pub struct PyProfile {
    /// 'x', 'y' or 'z'.
    #[pyo3(get)]
    axis: &'static str,
    levels: Py<PyArray1<f64>>,
    volume_below: Py<PyArray1<f64>>,
    slab_volume: Py<PyArray1<f64>>,
    section_area: Py<PyArray1<f64>>,
}

#[pymethods]
impl PyProfile {
    /// The levels: n + 1 coordinates along the axis.
    #[getter]
    fn levels<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.levels.bind(py).clone()
    }

    /// The volume below each level.
    #[getter]
    fn volume_below<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.volume_below.bind(py).clone()
    }

    /// The volume between levels k and k + 1 (n values).
    #[getter]
    fn slab_volume<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.slab_volume.bind(py).clone()
    }

    /// The area of the cross-section at each level.
    #[getter]
    fn section_area<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.section_area.bind(py).clone()
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let slabs = self.slab_volume.bind(py).len().unwrap_or(0);
        format!("Profile(axis='{}', slabs={slabs})", self.axis)
    }
}

/// The profile of `mesh` (a checked solid, or a surface as wound) along `axis`.
pub fn profile<S: Surface>(
    py: Python<'_>,
    mesh: &S,
    axis: &str,
    levels: Option<i64>,
    step: Option<f64>,
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
    let p = py.detach(|| grid::profile(mesh, axis, levels)).map_err(mesh_error)?;
    Ok(PyProfile {
        axis: p.axis.name(),
        levels: p.levels.into_pyarray(py).unbind(),
        volume_below: p.volume_below.into_pyarray(py).unbind(),
        slab_volume: p.slab_volume.into_pyarray(py).unbind(),
        section_area: p.section_area.into_pyarray(py).unbind(),
    })
}

/// The volume of a union of bodies as a certified interval [lower, upper], with the
/// names of the keys of `meshvol union --json`; plus the bodies measured turned
/// outward because they were wound inward (flipped), and the grid columns that could
/// not be resolved exactly (their bounds stay in the interval).
#[pyclass(module = "meshvol", name = "Union", frozen, get_all)]
pub struct PyUnion {
    /// The union's volume is at least this.
    lower: f64,
    /// The union's volume is at most this.
    upper: f64,
    /// The midpoint of [lower, upper].
    volume: f64,
    /// How many bodies.
    bodies: usize,
    /// The sum of the bodies' volumes (overlaps counted twice).
    sum_of_volumes: f64,
    /// Cells cut into 2x2x2 children.
    cells_refined: usize,
    /// Cells resolved exactly.
    cells_resolved_exactly: usize,
    /// Grid columns left unresolved.
    columns_unresolved: usize,
    /// Bodies wound inward, measured turned outward.
    flipped: Vec<usize>,
    /// How far the caps on the bodies' holes could put the volume off; the interval is
    /// widened by it (0 for closed bodies).
    volume_uncertainty: f64,
    /// Why the bodies' solids may not be the ones meant (also issued as MeshWarnings).
    warnings: Vec<String>,
}

#[pymethods]
impl PyUnion {
    fn __repr__(&self) -> String {
        format!(
            "Union(lower={:?}, upper={:?}, bodies={}, sum_of_volumes={:?})",
            self.lower, self.upper, self.bodies, self.sum_of_volumes
        )
    }
}

/// The volume of the union of closed bodies, as a certified interval, without a
/// boolean mesh (the numbers of `meshvol union`).
///
/// meshes is a list of meshes (meshvol.Mesh or objects with .vertices and .faces, such
/// as trimesh.Trimesh); a single mesh, or a list of one, stands for its bodies (each
/// outermost shell with its cavities), as a single file does for the command.
/// Refinement stops once upper - lower <= tolerance * lower. check=True (the default)
/// measures each mesh's checked solid, with holes capped and the caps' uncertainty
/// widening the interval; check=False the surfaces as wound.
#[pyfunction]
#[pyo3(signature = (meshes, tolerance = 1e-6, check = true))]
pub fn union(
    py: Python<'_>,
    meshes: &Bound<'_, PyAny>,
    tolerance: f64,
    check: bool,
) -> PyResult<PyUnion> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(bad_argument(format!("tolerance must be a positive number; got {tolerance}")));
    }
    let single = meshes.cast::<PyMesh>().is_ok() || crate::convert::mesh_like(meshes)?.is_some();
    let meshes: Vec<Bound<'_, PyMesh>> = if single {
        vec![mesh_of(meshes)?]
    } else {
        meshes.try_iter()?.map(|item| mesh_of(&item?)).collect::<PyResult<_>>()?
    };
    if meshes.is_empty() {
        return Err(mesh_error("no bodies: give at least one mesh"));
    }
    let mut measured = Vec::new();
    let mut warnings = Vec::new();
    let mut uncertainty = 0.0;
    for m in &meshes {
        let (checked, surface, doubts) = m.get().measured(py, check)?;
        uncertainty += checked.map_or(0.0, |c| c.volume_uncertainty);
        warnings.extend(doubts);
        measured.push((checked, surface, &m.get().mesh));
    }
    let mut u = py
        .detach(|| {
            let bodies: Vec<FaceSubset<_>> = match measured.as_slice() {
                [(Some(c), surface, _)] => {
                    c.bodies().into_iter().map(|b| FaceSubset::new(*surface, b.faces)).collect()
                }
                [(None, surface, mesh)] => {
                    grid::shells(*mesh).into_iter().map(|f| FaceSubset::new(*surface, f)).collect()
                }
                many => many.iter().map(|(_, surface, _)| FaceSubset::all(*surface)).collect(),
            };
            if bodies.is_empty() {
                return Err("no faces: there is no body to measure".to_string());
            }
            grid::union(&bodies, tolerance).map_err(|e| e.to_string())
        })
        .map_err(mesh_error)?;
    // Caps on holes are guesses: the interval must hold whatever the missing faces were.
    u.lower = (u.lower - uncertainty).max(0.0);
    u.upper += uncertainty;
    let not_solid: Vec<String> = u
        .bodies_not_solid
        .iter()
        .map(|b| {
            format!(
                "body {b}: not a closed solid (its volume in some cells leaves [0, cell \
                 volume]): the interval is ordered but not certified"
            )
        })
        .collect();
    crate::errors::warn_all(py, &not_solid)?;
    warnings.extend(not_solid);
    Ok(PyUnion {
        lower: u.lower,
        upper: u.upper,
        volume: u.volume(),
        bodies: u.bodies,
        sum_of_volumes: u.sum_of_volumes,
        cells_refined: u.cells_refined,
        cells_resolved_exactly: u.cells_resolved_exactly,
        columns_unresolved: u.columns_unresolved,
        flipped: u.flipped,
        volume_uncertainty: uncertainty,
        warnings,
    })
}
