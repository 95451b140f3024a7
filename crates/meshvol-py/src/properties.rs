//! `meshvol.MassProperties`: what `meshvol volume` reports about a solid.

use crate::errors::{bad_argument, mesh_error};
use meshvol::accumulate::UNIT_ROUNDOFF;
use meshvol::{exact_signed_volume, mass_properties, Bounds, MassProperties, Principal, Surface};
use numpy::ndarray::arr2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A box's (min, max) corners as NumPy arrays.
type Corners<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The command's message for a surface without faces.
const NO_FACES: &str = "no faces: there is no surface to measure";

/// Volume, area, centroid and inertia of a solid, with the names of the keys of
/// `meshvol volume --json`.
///
/// volume is |signed_volume|; signed_volume is positive for outward normals
/// (counter-clockwise seen from outside) and negative for inward ones (OpenSCAD's
/// polyhedron()). volume_error_bound bounds |signed_volume - the exact signed volume of
/// the polyhedron the float64 coordinates describe|. centroid is None when the volume is
/// zero within that bound; inertia is then zero. inertia is about the centroid and
/// scaled by density, as are principal_moments (ascending); principal_axes[k] (row k)
/// is the unit axis of principal_moments[k], a right-handed frame.
#[pyclass(module = "meshvol", name = "MassProperties", frozen)]
pub struct PyMassProperties {
    /// Faces measured.
    #[pyo3(get)]
    faces: usize,
    /// Triangles in the faces' fans.
    #[pyo3(get)]
    triangles: usize,
    /// |signed_volume|.
    #[pyo3(get)]
    volume: f64,
    /// The sum of signed tetrahedron volumes: positive for outward normals.
    #[pyo3(get)]
    signed_volume: f64,
    /// A bound on the rounding error of signed_volume.
    #[pyo3(get)]
    volume_error_bound: f64,
    /// Whether signed_volume is the correctly rounded exact value.
    #[pyo3(get)]
    exact: bool,
    /// Total face area.
    #[pyo3(get)]
    area: f64,
    centroid: Option<[f64; 3]>,
    inertia: [[f64; 3]; 3],
    principal_moments: [f64; 3],
    principal_axes: [[f64; 3]; 3],
    /// The density mass and inertia are scaled by.
    #[pyo3(get)]
    density: f64,
    /// density * volume.
    #[pyo3(get)]
    mass: f64,
    bounds: Option<Bounds>,
    /// Why the measured solid may not be the one meant (empty when beyond doubt or
    /// unchecked).
    #[pyo3(get)]
    warnings: Vec<String>,
}

impl PyMassProperties {
    fn new(mp: &MassProperties, density: f64, exact: bool) -> Self {
        // Coordinates beyond about 1e75 overflow the second moments; the eigen-solver
        // is only given finite tensors (it asserts on others in debug builds).
        let principal = if mp.inertia.iter().flatten().all(|x| x.is_finite()) {
            mp.principal()
        } else {
            Principal { moments: [f64::NAN; 3], axes: [[f64::NAN; 3]; 3] }
        };
        let volume = mp.signed_volume.abs();
        PyMassProperties {
            faces: mp.faces,
            triangles: mp.triangles,
            volume,
            signed_volume: mp.signed_volume,
            volume_error_bound: mp.volume_error_bound,
            exact,
            area: mp.area,
            centroid: mp.centroid,
            inertia: mp.inertia.map(|row| row.map(|x| x * density)),
            principal_moments: principal.moments.map(|x| x * density),
            principal_axes: principal.axes,
            density,
            mass: density * volume,
            bounds: mp.bounds,
            warnings: Vec::new(),
        }
    }
}

/// Checks a density as the command does: positive and finite.
pub fn check_density(density: f64) -> PyResult<()> {
    if density.is_finite() && density > 0.0 {
        Ok(())
    } else {
        Err(bad_argument(format!("density must be a positive number; got {density}")))
    }
}

/// Refuses a mesh without faces, as the command does.
pub fn require_faces(mesh: &meshvol::Mesh) -> PyResult<()> {
    if mesh.face_count() == 0 {
        Err(mesh_error(NO_FACES))
    } else {
        Ok(())
    }
}

/// Mass properties of `surface`, with the correctly rounded exact volume when `exact`.
fn properties<S: Surface + ?Sized>(
    surface: &S,
    exact: bool,
) -> Result<MassProperties, meshvol::ExactError> {
    let mut mp = mass_properties(surface);
    if exact {
        mp.signed_volume = exact_signed_volume(surface)?;
        // Correctly rounded: within half an ulp.
        mp.volume_error_bound = UNIT_ROUNDOFF * mp.signed_volume.abs();
    }
    Ok(mp)
}

/// Measures the solid `surface` of `mesh` (checked as `checked` says, or as wound)
/// with the GIL released, as `meshvol volume` does: the properties are the solid's,
/// `signed_volume`, `faces` and `triangles` the surface's as wound; `warnings` are
/// followed by the report's own (a zero or inward volume).
pub fn measure_solid<S: Surface + ?Sized>(
    py: Python<'_>,
    mesh: &meshvol::Mesh,
    checked: Option<&meshvol::topology::Check>,
    surface: &S,
    density: f64,
    exact: bool,
    mut warnings: Vec<String>,
) -> PyResult<PyMassProperties> {
    check_density(density)?;
    let repaired = checked.is_some_and(|c| c.repairs() != (0, 0, 0));
    let (as_wound, solid) = py
        .detach(|| {
            let as_wound = properties(mesh, exact)?;
            let solid = if repaired { properties(surface, exact)? } else { as_wound };
            Ok::<_, meshvol::ExactError>((as_wound, solid))
        })
        .map_err(mesh_error)?;
    let report = meshvol::topology::volume_warnings(checked, &as_wound, &solid);
    crate::errors::warn_all(py, &report)?;
    warnings.extend(report);
    let mut measured = PyMassProperties::new(&solid, density, exact);
    measured.signed_volume = as_wound.signed_volume;
    measured.faces = as_wound.faces;
    measured.triangles = as_wound.triangles;
    measured.warnings = warnings;
    Ok(measured)
}

#[pymethods]
impl PyMassProperties {
    /// The centroid, a float64 array of 3, or None when the volume is zero.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    /// The 3x3 inertia tensor about the centroid, scaled by density.
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arr2(&self.inertia).into_pyarray(py)
    }

    /// The principal moments of inertia, ascending.
    #[getter]
    fn principal_moments<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.principal_moments)
    }

    /// The principal axes: row k is the unit axis of principal_moments[k].
    #[getter]
    fn principal_axes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arr2(&self.principal_axes).into_pyarray(py)
    }

    /// The vertices' bounding box as (min, max) float64 arrays of 3.
    #[getter]
    fn bounds<'py>(&self, py: Python<'py>) -> Option<Corners<'py>> {
        self.bounds.map(|b| (PyArray1::from_slice(py, &b.min), PyArray1::from_slice(py, &b.max)))
    }

    /// The values as a dict of plain Python numbers and lists, with the keys and
    /// structure of `meshvol volume --json` (bounds as {"min": [...], "max": [...]}).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("faces", self.faces)?;
        d.set_item("triangles", self.triangles)?;
        d.set_item("volume", self.volume)?;
        d.set_item("signed_volume", self.signed_volume)?;
        d.set_item("volume_error_bound", self.volume_error_bound)?;
        d.set_item("exact", self.exact)?;
        d.set_item("area", self.area)?;
        d.set_item("centroid", self.centroid)?;
        d.set_item("inertia", self.inertia)?;
        d.set_item("principal_moments", self.principal_moments)?;
        d.set_item("principal_axes", self.principal_axes)?;
        d.set_item("density", self.density)?;
        d.set_item("mass", self.mass)?;
        let bounds = match self.bounds {
            Some(b) => {
                let bounds = PyDict::new(py);
                bounds.set_item("min", b.min)?;
                bounds.set_item("max", b.max)?;
                Some(bounds)
            }
            None => None,
        };
        d.set_item("bounds", bounds)?;
        d.set_item("warnings", &self.warnings)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let centroid = match self.centroid {
            Some([x, y, z]) => format!("({x:?}, {y:?}, {z:?})"),
            None => "None".to_string(),
        };
        format!(
            "MassProperties(volume={:?}, signed_volume={:?}, volume_error_bound={:e}, \
             area={:?}, centroid={centroid}, mass={:?})",
            self.volume, self.signed_volume, self.volume_error_bound, self.area, self.mass
        )
    }
}
