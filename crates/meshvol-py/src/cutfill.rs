//! `meshvol.cutfill`: cut and fill between an existing surface and a design surface or
//! level (what `meshvol cutfill` reports), with per-cell arrays on request.

use crate::dict::Fields;
use crate::errors::{bad_argument, mesh_error};
use crate::load::{warn_for, MeshArg};
use meshvol::cutfill::CellCutFill;
use meshvol_report::cutfill::{cutfill as report, cutfill_with, Against, CutFillReport, Spacing};
use meshvol_report::quantities::Quantities;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;

/// Cut and fill between two surfaces: the report of `meshvol cutfill --json`, whose keys
/// are its attributes and the keys of to_dict(): design and level, cut, fill, net,
/// area_cut, area_fill, footprint_area, footprint_bounds, existing_area, design_area,
/// grid (counts, origin and cell of the plan grid, or None), warnings. With cells or
/// pitch, cut_cells and fill_cells are the per-cell volumes.
#[pyclass(module = "meshvol", name = "CutFill", frozen)]
pub struct PyCutFill {
    report: CutFillReport,
    fields: Fields,
    cells: Option<CellCutFill>,
}

impl PyCutFill {
    /// One of the per-cell arrays as an (nx, ny) array.
    fn cells<'py>(
        &self,
        py: Python<'py>,
        pick: impl Fn(&CellCutFill) -> &Vec<f64>,
    ) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        let (Some(cells), Some(grid)) = (&self.cells, &self.report.grid) else {
            return Ok(None);
        };
        let shape = (grid.counts[0], grid.counts[1]);
        let array = Array2::from_shape_vec(shape, pick(cells).clone()).map_err(mesh_error)?;
        Ok(Some(array.into_pyarray(py)))
    }
}

#[pymethods]
impl PyCutFill {
    /// The cut volume in each plan cell, an (nx, ny) float64 array (cell (i, j) spans
    /// origin + (i, j)·cell to origin + (i+1, j+1)·cell); None without cells or pitch.
    #[getter]
    fn cut_cells<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        self.cells(py, |c| &c.cut)
    }

    /// The fill volume in each plan cell, as cut_cells.
    #[getter]
    fn fill_cells<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        self.cells(py, |c| &c.fill)
    }

    /// The footprint's plan box as a (2, 2) float64 array [[x0, y0], [x1, y1]], or None.
    #[getter]
    fn footprint_bounds<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.report.footprint_bounds.map(|b| numpy::ndarray::arr2(&b).into_pyarray(py))
    }

    fn __repr__(&self) -> String {
        let r = &self.report;
        format!("CutFill(cut={:?}, fill={:?}, net={:?})", r.cut, r.fill, r.net)
    }
}

crate::dict::report_methods!(PyCutFill, "CutFill");

/// Cut and fill between an existing surface and a design (`meshvol cutfill`).
///
/// existing and design are height fields z = f(x, y) (terrains), each a path or a mesh
/// (meshvol.Mesh, or an object with .vertices and .faces); give design, or level=Z for
/// the plane z = Z. cells=(nx, ny) or pitch=p adds per-cell volumes over the common
/// footprint's box (cut_cells, fill_cells). A surface that folds over itself in plan
/// raises MeshError naming its faces. units as the command's --units ('m:yd': cubic
/// yards, also for cut_cells and fill_cells; level and pitch in the files' units);
/// density as its --density ('1.8t/m3'): `mass`, the mass of the fill. timings=True
/// adds `timings`, the kernel's stages with their wall and CPU seconds.
#[pyfunction]
#[pyo3(signature = (existing, design = None, level = None, cells = None, pitch = None, units = None, density = None, timings = false))]
#[allow(clippy::too_many_arguments)]
pub fn cutfill(
    py: Python<'_>,
    existing: &Bound<'_, PyAny>,
    design: Option<&Bound<'_, PyAny>>,
    level: Option<f64>,
    cells: Option<&Bound<'_, PyAny>>,
    pitch: Option<f64>,
    units: Option<&str>,
    density: Option<&Bound<'_, PyAny>>,
    timings: bool,
) -> PyResult<PyCutFill> {
    let options = crate::units::options(units, density)?;
    let cells = cells
        .map(|c| crate::convert::int_argument(c, "cells", &[2], "(nx, ny)"))
        .transpose()?
        .map(|c| [c[0], c[1]]);
    let spacing = match (cells, pitch) {
        (Some(_), Some(_)) => return Err(bad_argument("give cells=(nx, ny) or pitch=p, not both")),
        (Some(counts), None) => {
            if counts.iter().any(|&n| n < 1) {
                return Err(bad_argument(format!(
                    "cells must be at least 1 along x and y; got {counts:?}"
                )));
            }
            let counts = counts.map(|n| usize::try_from(n).unwrap_or(usize::MAX));
            Some(Spacing::Cells(counts))
        }
        (None, Some(p)) if !(p.is_finite() && p > 0.0) => {
            return Err(bad_argument(format!("pitch must be a positive number; got {p}")));
        }
        (None, Some(p)) => Some(Spacing::Pitch(p)),
        (None, None) => None,
    };
    let mut given = vec![MeshArg::of(existing)?];
    if let Some(d) = design {
        given.push(MeshArg::of(d)?);
    }
    let existing = given[0].mesh.get();
    let design_mesh = given.get(1).map(|d| d.mesh.get());
    let against = match (design_mesh, level) {
        (Some(d), None) => Against::Surface { source: &d.source, surface: &d.mesh },
        (None, Some(z)) => Against::Level(z),
        _ => return Err(bad_argument("give design=SURFACE or level=Z, not both")),
    };
    let clock = timings.then(crate::timings::Clock::new);
    crate::timings::stage(clock.as_ref(), "measuring");
    let (report, mut cells) = py
        .detach(|| match &clock {
            Some(clock) => cutfill_with(&existing.source, &existing.mesh, against, spacing, clock),
            None => report(&existing.source, &existing.mesh, against, spacing),
        })
        .map_err(mesh_error)?;
    let mut files = vec![(existing.source.name(), existing.source.unit)];
    files.extend(design_mesh.map(|d| (d.source.name(), d.source.unit)));
    let report = report.in_units(&options, &files).map_err(mesh_error)?;
    let (scale, _) =
        meshvol_report::units::Scale::resolve_all(&options, &files).map_err(mesh_error)?;
    if let Some(c) = cells.as_mut() {
        meshvol_report::reported_cells::volumes(&scale, &mut c.cut);
        meshvol_report::reported_cells::volumes(&scale, &mut c.fill);
    }
    warn_for(py, &given, &report.warnings)?;
    let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
    Ok(PyCutFill { fields, report, cells })
}
