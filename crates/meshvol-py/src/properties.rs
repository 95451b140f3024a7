//! `meshvol.MassProperties`: what `meshvol volume` reports about a solid.

use crate::dict::Fields;
use crate::errors::{bad_argument, mesh_error};
use crate::mesh::PyMesh;
use meshvol::topology::Check;
use meshvol_report::inertial::{inertial, RobotFormat};
use meshvol_report::subject::Subject;
use meshvol_report::units::UnitsArg;
use meshvol_report::volume::{volume, VolumeOptions, VolumeReport, NO_FACES};
use numpy::ndarray::arr2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

/// Volume, area, centroid and inertia of a solid: the report of `meshvol volume --json`,
/// whose keys are its attributes and the keys of to_dict().
///
/// volume is the solid's; signed_volume the surface's as wound: positive for outward
/// normals (counter-clockwise seen from outside) and negative for inward ones
/// (OpenSCAD's polyhedron()). volume_error_bound bounds |volume - the exact volume of the
/// polyhedron the float64 coordinates describe|. centroid is None when the volume is zero
/// within that bound; inertia is then zero. inertia is about the centroid and scaled by
/// density, as are principal_moments (ascending); principal_axes[k] (row k) is the unit
/// axis of principal_moments[k], a right-handed frame. Checked (the default), the check's
/// facts are attributes too (verdict, closed, shells, ...), as in the command's JSON.
#[pyclass(module = "meshvol", name = "MassProperties", frozen)]
pub struct PyMassProperties {
    report: VolumeReport,
    fields: Fields,
}

impl PyMassProperties {
    fn inertial(&self, format: RobotFormat) -> PyResult<String> {
        inertial(&self.report, format).map_err(bad_argument)
    }

    pub fn new(report: VolumeReport) -> PyResult<Self> {
        Ok(PyMassProperties { fields: Fields::new(&report)?, report })
    }

    /// With `timings`, the same with the stages' timings as its last key.
    pub fn timed(
        self,
        timings: Option<Vec<meshvol_report::timings::StageTiming>>,
    ) -> PyResult<Self> {
        Ok(PyMassProperties { fields: self.fields.with_timings(timings)?, report: self.report })
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

/// The report of `meshvol volume` on `mesh`: its checked solid with `check`, else its
/// surface as wound; the warnings beyond the reader's are issued as MeshWarnings.
pub fn measure(
    py: Python<'_>,
    mesh: &PyMesh,
    check: Option<&Check>,
    density: Option<&Bound<'_, PyAny>>,
    exact: bool,
    units: Option<&str>,
) -> PyResult<PyMassProperties> {
    require_faces(&mesh.mesh)?;
    let density = crate::units::density_or_one(density)?;
    let units = units.map(str::parse::<UnitsArg>).transpose().map_err(bad_argument)?;
    let options = VolumeOptions { density, units, exact };
    let subject = Subject { source: &mesh.source, surface: &mesh.mesh, check };
    let report = py.detach(|| volume(&subject, &options)).map_err(mesh_error)?;
    mesh.warn(py, &report.warnings)?;
    PyMassProperties::new(report)
}

#[pymethods]
impl PyMassProperties {
    /// The centroid, a float64 array of 3, or None when the volume is zero.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    /// The 3x3 inertia tensor about the centroid, scaled by density.
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arr2(&self.report.inertia).into_pyarray(py)
    }

    /// The principal moments of inertia, ascending.
    #[getter]
    fn principal_moments<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.report.principal_moments)
    }

    /// The principal axes: row k is the unit axis of principal_moments[k].
    #[getter]
    fn principal_axes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arr2(&self.report.principal_axes).into_pyarray(py)
    }

    /// The vertices' bounding box as a (2, 3) float64 array, [min, max] (as trimesh's
    /// mesh.bounds; `lo, hi = mp.bounds` unpacks it); None without vertices. In
    /// to_dict() (the command's JSON) it is {"min": [...], "max": [...]}.
    #[getter]
    fn bounds<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        let b = self.report.bounds.as_ref()?;
        Some(arr2(&[b.min, b.max]).into_pyarray(py))
    }

    /// Each shell's facts as Shell objects (as Check.shell_details), checked; [] with
    /// check=False.
    #[getter]
    fn shell_details(&self) -> PyResult<Vec<crate::shell::PyShell>> {
        let Some(facts) = &self.report.check else { return Ok(Vec::new()) };
        facts.shell_details.iter().map(crate::shell::PyShell::new).collect()
    }

    /// The `<inertial>` element of a URDF link: mass, centre of mass and inertia tensor.
    /// The report must be in metres (units="mm:m", or a file declaring metres) and the
    /// density in kg/m³.
    fn to_urdf(&self) -> PyResult<String> {
        self.inertial(RobotFormat::Urdf)
    }

    /// The `<inertial>` element of an SDF link (as to_urdf, in SDF's form).
    fn to_sdf(&self) -> PyResult<String> {
        self.inertial(RobotFormat::Sdf)
    }

    /// MuJoCo's `<inertial pos mass fullinertia>` element (as to_urdf, in MJCF's form).
    fn to_mjcf(&self) -> PyResult<String> {
        self.inertial(RobotFormat::Mjcf)
    }

    fn __repr__(&self) -> String {
        let r = &self.report;
        let centroid = match r.centroid {
            Some([x, y, z]) => format!("({x:?}, {y:?}, {z:?})"),
            None => "None".to_string(),
        };
        format!(
            "MassProperties(volume={:?}, signed_volume={:?}, volume_error_bound={:e}, \
             area={:?}, centroid={centroid}, mass={:?})",
            r.volume, r.signed_volume, r.volume_error_bound, r.area, r.mass
        )
    }
}

crate::dict::report_methods!(PyMassProperties, "MassProperties");
