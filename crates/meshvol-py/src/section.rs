//! `Mesh.section`: the cross-section of the solid by a plane (what `meshvol section`
//! reports), and `Mesh.bodies`: the solid's bodies as meshes of their own.

use crate::dict::Fields;
use crate::errors::{bad_argument, mesh_error};
use crate::mesh::PyMesh;
use crate::properties::require_faces;
use meshvol::polygon::Polygon;
use meshvol::{Faces, Mesh, Surface};
use meshvol_report::quantities::Quantities;
use meshvol_report::section::{section, SectionReport};
use numpy::ndarray::{arr2, Array2};
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyList;
use std::collections::HashMap;

/// The cross-section of a solid by a plane: the report of `meshvol section --json`,
/// whose keys are its attributes and the keys of to_dict(): plane (origin, normal and
/// the 2D axes u, v), area, signed_area, perimeter, centroid (2D, in the plane's
/// coordinates: a point is origin + s·u + t·v), centroid_3d, inertia (about the
/// centroid, in the plane's axes), polygons, holes, loops, segments, open_chains,
/// units, warnings. principal_moments (ascending) and principal_axes (rows, in the
/// plane's 2D coordinates) as AreaProperties has them; outlines are the polygons
/// themselves, to_wkt() and to_geojson() as the command's --wkt and --geojson.
#[pyclass(module = "meshvol", name = "Section", frozen)]
pub struct PySection {
    report: SectionReport,
    fields: Fields,
    /// In the file's coordinates (the outline is not converted by units, as in the CLI).
    polygons: Vec<Polygon>,
}

fn points_array<'py>(py: Python<'py>, points: &[[f64; 2]]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    Ok(Array2::from_shape_vec((points.len(), 2), flat).map_err(mesh_error)?.into_pyarray(py))
}

#[pymethods]
impl PySection {
    /// The centroid in the plane's 2D coordinates, a float64 array of 2, or None.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    /// The centroid in space, a float64 array of 3, or None.
    #[getter]
    fn centroid_3d<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.centroid_3d.map(|c| PyArray1::from_slice(py, &c))
    }

    /// The principal second moments of the section's area, ascending (zeros without
    /// area).
    #[getter]
    fn principal_moments<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let i = self.report.inertia.unwrap_or_default();
        PyArray1::from_slice(py, &crate::polygon::ascending(&i).0)
    }

    /// Row k is the unit axis of principal_moments[k], in the plane's 2D coordinates.
    #[getter]
    fn principal_axes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let i = self.report.inertia.unwrap_or_default();
        arr2(&crate::polygon::ascending(&i).1).into_pyarray(py)
    }

    /// The section's polygons in the plane's 2D coordinates (the file's units): a list
    /// of (exterior, holes), exterior an (n, 2) float64 array, holes a list of them.
    #[getter]
    fn outlines<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for p in &self.polygons {
            let holes = PyList::empty(py);
            for h in &p.holes {
                holes.append(points_array(py, h)?)?;
            }
            list.append((points_array(py, &p.exterior)?, holes))?;
        }
        Ok(list)
    }

    /// The section as a WKT MULTIPOLYGON (`meshvol section --wkt`).
    fn to_wkt(&self) -> PyResult<String> {
        let mut out = Vec::new();
        meshvol_io::wkt::write_multipolygon(&mut out, &self.polygons).map_err(mesh_error)?;
        Ok(String::from_utf8_lossy(&out).trim_end().to_string())
    }

    /// The section as a GeoJSON Feature, as a dict (`meshvol section --geojson`).
    fn to_geojson<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let mut properties = serde_json::Map::new();
        properties.insert("file".into(), self.report.file.clone().into());
        properties.insert("area".into(), self.report.area.into());
        if let Ok(plane) = serde_json::to_value(&self.report.plane) {
            properties.insert("plane".into(), plane);
        }
        let mut out = Vec::new();
        meshvol_io::geojson::write_feature(&mut out, &self.polygons, properties)
            .map_err(mesh_error)?;
        py.import("json")?.call_method1("loads", (String::from_utf8_lossy(&out).as_ref(),))
    }

    fn __repr__(&self) -> String {
        let r = &self.report;
        format!("Section(area={:?}, perimeter={:?}, polygons={})", r.area, r.perimeter, r.polygons)
    }
}

crate::dict::report_methods!(PySection, "Section");

/// The mesh of one body: its faces' fans, vertices shared where positions are equal.
fn body_mesh<S: Surface>(body: &S) -> Result<Mesh, meshvol::MeshError> {
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    for face in 0..body.face_count() {
        body.fan(face, |a, b, c| {
            let t = [a, b, c].map(|p| {
                let key = p.map(|x| (x + 0.0).to_bits());
                *index.entry(key).or_insert_with(|| {
                    positions.push(p);
                    (positions.len() - 1) as u32
                })
            });
            triangles.push(t);
        });
    }
    Mesh::new(positions, Faces::Triangles(triangles))
}

#[pymethods]
impl PyMesh {
    /// The cross-section of the solid by a plane (`meshvol section`): its area,
    /// perimeter, centroid and second moments, and its outline.
    ///
    /// plane: 'z=H' (or 'x=H', 'y=H': 2D coordinates (x, y), (y, z), (x, z), as the
    /// command's --plane z=H; any text the command's --plane takes), [point, normal] (any
    /// (2, 3) array-like), or (nx, ny, nz, d) for the plane n·x = d (as Mesh.below takes
    /// it). check=True (the default) cuts
    /// the checked solid, as the command does; check=False the surface as wound. units
    /// as in mass_properties ('mm:cm'; the outline stays in the file's coordinates).
    /// density as the command's --density: a mass per area ('62.8kg/m2', or a number
    /// per reported area unit), giving `mass`, that of a sheet with the section's outline.
    /// timings=True adds `timings`, as in mass_properties.
    #[pyo3(signature = (plane, check = true, units = None, density = None, timings = false))]
    fn section(
        &self,
        py: Python<'_>,
        plane: &Bound<'_, PyAny>,
        check: bool,
        units: Option<&str>,
        density: Option<&Bound<'_, PyAny>>,
        timings: bool,
    ) -> PyResult<PySection> {
        require_faces(&self.mesh)?;
        let plane = crate::convert::plane_arg(plane)?
            .plane()
            .map_err(|e| bad_argument(format!("plane: {e}")))?;
        let options = crate::units::area_options(units, density)?;
        let clock = timings.then(crate::timings::Clock::new);
        let (report, polygons) = self.with_subject(py, check, clock.as_ref(), |subject| {
            Ok(py.detach(|| section(&subject, &plane)))
        })?;
        let report = report.in_units(&options, self.source.unit).map_err(mesh_error)?;
        self.warn(py, &report.warnings)?;
        let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
        Ok(PySection { fields, report, polygons })
    }

    /// The solid's bodies as meshes of their own, in the order `meshvol union` numbers
    /// them: each outermost shell with the shells nested in it (its cavities, wound
    /// inward, and islands in them), caps on holes included, so that
    /// body.mass_properties() is that body's volume, area, centroid, inertia and mass
    /// (trimesh's split() then mass_properties). The volumes add up to the solid's.
    /// check=False: the surface's connected parts as wound. The reasons to doubt the
    /// solid are issued as MeshWarnings, as by every measure.
    #[pyo3(signature = (check = true))]
    fn bodies(&self, py: Python<'_>, check: bool) -> PyResult<Vec<PyMesh>> {
        require_faces(&self.mesh)?;
        let subject = self.subject(py, check)?;
        // The reasons to doubt the solid are the bodies' too (their meshes are closed:
        // measuring them again would not say that caps were added).
        self.warn(py, &subject.warnings())?;
        let meshes = py.detach(|| {
            subject.bodies().iter().map(|b| body_mesh(&b.surface)).collect::<Result<Vec<_>, _>>()
        });
        Ok(meshes.map_err(mesh_error)?.into_iter().map(PyMesh::from).collect())
    }
}
