//! `Mesh.below`: the part of the solid under a plane (what `meshvol below` reports).

use crate::dict::Fields;
use crate::errors::{bad_argument, mesh_error};
use crate::mesh::PyMesh;
use crate::properties::require_faces;
use meshvol_report::below::{below, BelowOptions, BelowReport, Waterline};
use meshvol_report::quantities::Quantities;
use numpy::PyArray1;
use pyo3::prelude::*;

/// The part of a solid under a plane: the report of `meshvol below --json`, whose keys
/// are its attributes and the keys of to_dict(): normal and level (the part is where
/// normal·x <= level), volume, centroid (centre of buoyancy), wetted_area, section_area
/// and section_centroid (the waterplane), warnings.
#[pyclass(module = "meshvol", name = "Below", frozen)]
pub struct PyBelow {
    report: BelowReport,
    fields: Fields,
}

#[pymethods]
impl PyBelow {
    /// The plane's unit normal, a float64 array of 3.
    #[getter]
    fn normal<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.report.normal)
    }

    /// The part's centroid (centre of buoyancy), a float64 array of 3, or None.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    /// The section's centroid, a float64 array of 3, or None.
    #[getter]
    fn section_centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.section_centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    fn __repr__(&self) -> String {
        format!("Below(level={:?}, volume={:?})", self.report.level, self.report.volume)
    }
}

crate::dict::report_methods!(PyBelow, "Below");

#[pymethods]
impl PyMesh {
    /// The part of the solid below a plane (`meshvol below`): plane=(nx, ny, nz, d) for
    /// the part where n·x <= d, or any plane `meshvol below --plane` takes ('z=H',
    /// 'nx,ny,nz,d', 'px,py,pz,nx,ny,nz', or [point, normal]); or volume=V for the level along direction (default z)
    /// that holds V below it (a draft). heel and trim turn the normal by that many
    /// degrees about x, then about y. check=True (the default) measures the checked
    /// solid, as every command does.
    ///
    /// plane and direction take any sequence or NumPy array of 4 (or (2, 3)) and 3 numbers. units
    /// and density as the command's --units and --density ('mm:m', '1025kg/m3': the
    /// displaced mass). timings=True adds `timings`, as in mass_properties.
    #[pyo3(
        signature = (plane = None, volume = None, direction = None, heel = 0.0, trim = 0.0, check = true, units = None, density = None, timings = false),
        text_signature = "(self, plane=None, volume=None, direction=(0.0, 0.0, 1.0), heel=0.0, trim=0.0, check=True, units=None, density=None, timings=False)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn below(
        &self,
        py: Python<'_>,
        plane: Option<&Bound<'_, PyAny>>,
        volume: Option<f64>,
        direction: Option<&Bound<'_, PyAny>>,
        heel: f64,
        trim: f64,
        check: bool,
        units: Option<&str>,
        density: Option<&Bound<'_, PyAny>>,
        timings: bool,
    ) -> PyResult<PyBelow> {
        let unit_options = crate::units::options(units, density)?;
        require_faces(&self.mesh)?;
        let plane = plane.map(crate::convert::plane_arg).transpose()?;
        let direction = match direction {
            Some(d) => crate::convert::vector3(d, "direction")?,
            None => [0.0, 0.0, 1.0],
        };
        let waterline = match (plane, volume) {
            (Some(p), None) => {
                let (normal, d) = p.normal_offset();
                Waterline::Plane { normal, d }
            }
            (None, Some(volume)) => Waterline::Volume { direction, volume },
            _ => return Err(bad_argument("give plane=(nx, ny, nz, d) or volume=V, not both")),
        };
        if ![heel, trim].iter().all(|x| x.is_finite()) {
            return Err(bad_argument("heel and trim must be finite numbers of degrees"));
        }
        let options = BelowOptions { waterline, heel, trim };
        let clock = timings.then(crate::timings::Clock::new);
        let report = self.with_subject(py, check, clock.as_ref(), |subject| {
            py.detach(|| below(&subject, &options)).map_err(mesh_error)
        })?;
        let report = report.in_units(&unit_options, self.source.unit).map_err(mesh_error)?;
        self.warn(py, &report.warnings)?;
        let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
        Ok(PyBelow { fields, report })
    }
}
