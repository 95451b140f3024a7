//! `meshvol.Shell`: one shell of a checked mesh, as `meshvol check` reports it (in
//! `Check.shell_details` and `MassProperties.shell_details`).

use crate::dict::Fields;
use meshvol_report::check::ShellReport;
use pyo3::prelude::*;

/// One shell (connected component of faces) of a checked mesh: an entry of
/// `shell_details` in `meshvol check --json`, whose keys are its attributes (faces,
/// closed, orientable, volume, cavity, parent, wound_outward, boundary_loops,
/// euler_characteristic, genus) and the keys of to_dict().
#[pyclass(module = "meshvol", name = "Shell", frozen)]
pub struct PyShell {
    report: ShellReport,
    fields: Fields,
}

impl PyShell {
    /// A Shell object of a report's shell.
    pub fn new(s: &ShellReport) -> PyResult<PyShell> {
        Ok(PyShell { fields: Fields::new(s)?, report: s.clone() })
    }
}

#[pymethods]
impl PyShell {
    /// shell["volume"]: a key of the report, as a dict entry (shell_details were dicts
    /// once; code that indexes them keeps working).
    fn __getitem__<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        self.fields
            .get(py, "Shell", key)
            .map_err(|_| pyo3::exceptions::PyKeyError::new_err(key.to_string()))
    }

    fn __repr__(&self) -> String {
        let r = &self.report.0;
        let py_bool = |b: bool| if b { "True" } else { "False" };
        format!(
            "Shell(faces={}, closed={}, volume={:?}, cavity={})",
            r.faces,
            py_bool(r.closed),
            r.volume,
            py_bool(r.cavity)
        )
    }
}
crate::dict::report_methods!(PyShell, "Shell");
