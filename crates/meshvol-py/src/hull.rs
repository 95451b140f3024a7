//! `meshvol.convex_hull` and `meshvol.hull_volume`: the convex hull of a point cloud
//! (what `meshvol hull` reports).

use crate::convert::coordinates;
use crate::dict::Fields;
use crate::errors::{invalid, mesh_error};
use crate::mesh::PyMesh;
use meshvol::hull::{self, Hull, HullError};
use meshvol_report::hull::HullReport;
use meshvol_report::quantities::Quantities;
use numpy::PyArray1;
use pyo3::prelude::*;

/// The convex hull of a point set: the report of `meshvol hull --json`, whose keys are
/// its attributes (points, hull_vertices, hull_faces, volume, volume_error_bound, area,
/// degenerate, warnings, ...) and the keys of to_dict().
///
/// mesh is the hull as an outward-wound triangle Mesh over a subset of the points, or
/// None when the points are degenerate; degenerate then says why ('no points',
/// 'coincident', 'collinear' or 'coplanar') and the volume is 0.
#[pyclass(module = "meshvol", name = "Hull", frozen)]
pub struct PyHull {
    report: HullReport,
    fields: Fields,
    /// The hull as a Mesh, or None for degenerate points.
    #[pyo3(get)]
    mesh: Option<Py<PyMesh>>,
}

#[pymethods]
impl PyHull {
    /// The centroid of the hull's solid, a float64 array of 3, or None.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    fn __repr__(&self) -> String {
        let r = &self.report;
        match r.degenerate {
            Some(why) => format!("Hull(points={}, degenerate='{why}', volume=0)", r.points),
            None => format!(
                "Hull(points={}, hull_vertices={}, hull_faces={}, volume={:?})",
                r.points, r.hull_vertices, r.hull_faces, r.volume
            ),
        }
    }
}

/// The hull of `points`, an (n, 3) array, with the GIL released; the kernel's stages
/// timed on `clock` when given.
fn hull_of(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    clock: Option<&crate::timings::Clock>,
) -> PyResult<(usize, Hull)> {
    let points = coordinates::<3>(points, "points")?;
    crate::timings::stage(clock, "measuring");
    let hull = py.detach(|| match clock {
        Some(clock) => hull::convex_hull_with(&points, clock),
        None => hull::convex_hull(&points),
    });
    let hull = hull.map_err(|e| match e {
        HullError::NonFinite { .. } => invalid(e),
        e => mesh_error(e),
    })?;
    Ok((points.len(), hull))
}

/// The convex hull of points, an (n, 3) array: its mesh, volume, area and centroid.
/// Degenerate sets (no points, all equal, collinear, coplanar) have volume 0 and say why.
/// units and density as the command's --units and --density (the mesh stays in the
/// points' coordinates). timings=True adds `timings`, the kernel's stages with their
/// wall and CPU seconds.
#[pyfunction]
#[pyo3(signature = (points, units = None, density = None, timings = false))]
pub fn convex_hull(
    py: Python<'_>,
    points: &Bound<'_, PyAny>,
    units: Option<&str>,
    density: Option<&Bound<'_, PyAny>>,
    timings: bool,
) -> PyResult<PyHull> {
    let options = crate::units::options(units, density)?;
    let clock = timings.then(crate::timings::Clock::new);
    let (count, hull) = hull_of(py, points, clock.as_ref())?;
    let report = meshvol_report::hull::hull(None, None, count, &hull, Vec::new())
        .in_units(&options, None)
        .map_err(mesh_error)?;
    let mesh = match hull.mesh {
        Some(m) => Some(Py::new(py, PyMesh::from(m))?),
        None => None,
    };
    let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
    Ok(PyHull { fields, report, mesh })
}

/// The volume of the convex hull of points, an (n, 3) array (0 for degenerate sets):
/// convex_hull(points).volume.
#[pyfunction]
pub fn hull_volume(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<f64> {
    Ok(hull_of(py, points, None)?.1.volume())
}

crate::dict::report_methods!(PyHull, "Hull");
