//! `meshvol.convex_hull` and `meshvol.hull_volume`: the convex hull of a point cloud
//! (what `meshvol hull` reports).

use crate::convert::coordinates;
use crate::errors::{invalid, mesh_error};
use crate::mesh::PyMesh;
use meshvol::hull::{self, Degeneracy, Hull, HullError};
use numpy::PyArray1;
use pyo3::prelude::*;

/// The convex hull of a point set, with the names of the keys of `meshvol hull --json`.
///
/// mesh is the hull as an outward-wound triangle Mesh over a subset of the points, or
/// None when the points are degenerate; degenerate then says why ('no points',
/// 'coincident', 'collinear' or 'coplanar') and the volume is 0.
#[pyclass(module = "meshvol", name = "Hull", frozen)]
pub struct PyHull {
    /// Points given.
    #[pyo3(get)]
    points: usize,
    /// Vertices of the hull.
    #[pyo3(get)]
    hull_vertices: usize,
    /// Triangles of the hull.
    #[pyo3(get)]
    hull_faces: usize,
    /// The hull's volume.
    #[pyo3(get)]
    volume: f64,
    /// A bound on the volume's rounding error (the hull's vertices taken as exact).
    #[pyo3(get)]
    volume_error_bound: f64,
    /// The hull's surface area.
    #[pyo3(get)]
    area: f64,
    centroid: Option<[f64; 3]>,
    /// Why the hull has no volume, or None.
    #[pyo3(get)]
    degenerate: Option<&'static str>,
    /// The hull as a Mesh, or None for degenerate points.
    #[pyo3(get)]
    mesh: Option<Py<PyMesh>>,
}

#[pymethods]
impl PyHull {
    /// The centroid of the hull's solid, a float64 array of 3, or None.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    fn __repr__(&self) -> String {
        match self.degenerate {
            Some(why) => format!("Hull(points={}, degenerate='{why}', volume=0)", self.points),
            None => format!(
                "Hull(points={}, hull_vertices={}, hull_faces={}, volume={:?})",
                self.points, self.hull_vertices, self.hull_faces, self.volume
            ),
        }
    }
}

/// The hull of `points`, an (n, 3) array, with the GIL released.
fn hull_of(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<(usize, Hull)> {
    let points = coordinates::<3>(points, "points")?;
    let hull = py.detach(|| hull::convex_hull(&points)).map_err(|e| match e {
        HullError::NonFinite { .. } => invalid(e),
        e => mesh_error(e),
    })?;
    Ok((points.len(), hull))
}

/// The convex hull of points, an (n, 3) array: its mesh, volume, area and centroid.
/// Degenerate sets (no points, all equal, collinear, coplanar) have volume 0 and say why.
#[pyfunction]
pub fn convex_hull(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<PyHull> {
    let (count, hull) = hull_of(py, points)?;
    let degenerate = hull.degeneracy.map(|d| match d {
        Degeneracy::NoPoints => "no points",
        Degeneracy::AllCoincide => "coincident",
        Degeneracy::Collinear => "collinear",
        Degeneracy::Coplanar => "coplanar",
    });
    let volume = hull.volume();
    let (hull_vertices, hull_faces) =
        hull.mesh.as_ref().map_or((0, 0), |m| (m.vertex_count(), m.face_count()));
    let mesh = match hull.mesh {
        Some(m) => Some(Py::new(py, PyMesh::from(m))?),
        None => None,
    };
    Ok(PyHull {
        points: count,
        hull_vertices,
        hull_faces,
        volume,
        volume_error_bound: hull.properties.volume_error_bound,
        area: hull.properties.area,
        centroid: hull.properties.centroid,
        degenerate,
        mesh,
    })
}

/// The volume of the convex hull of points, an (n, 3) array (0 for degenerate sets):
/// convex_hull(points).volume.
#[pyfunction]
pub fn hull_volume(py: Python<'_>, points: &Bound<'_, PyAny>) -> PyResult<f64> {
    Ok(hull_of(py, points)?.1.volume())
}
