//! Reports as Python values: every result class keeps the report the `meshvol` command
//! prints (`meshvol_report`) serialized once, and its `to_dict()` and plain attributes
//! come from that serialization, so their keys are the command's JSON keys.

use pyo3::exceptions::PyAttributeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::Serialize;
use serde_json::Value;

/// A report's JSON object: the text the command prints, and its values by key.
pub struct Fields {
    json: String,
    values: serde_json::Map<String, Value>,
}

impl Fields {
    /// Serializes `report` (a struct: a JSON object).
    pub fn new(report: &impl Serialize) -> PyResult<Fields> {
        let json = serde_json::to_string(report).map_err(crate::errors::mesh_error)?;
        // The values straight from the report, not parsed back from the text: serde_json's
        // parser may round a float's last bit, and attributes must be to_dict()'s bits.
        match serde_json::to_value(report) {
            Ok(Value::Object(values)) => Ok(Fields { json, values }),
            Ok(_) => Err(crate::errors::mesh_error("a report is not a JSON object")),
            Err(e) => Err(crate::errors::mesh_error(e)),
        }
    }

    /// The same object with a `timings` list as its last key (`timings=True`, as the
    /// command's `--timings` adds it).
    pub fn with_timings(
        self,
        timings: Option<Vec<meshvol_report::timings::StageTiming>>,
    ) -> PyResult<Fields> {
        let Some(t) = timings else { return Ok(self) };
        let line = meshvol_report::timings::with_timings(&self.json, &t)
            .map_err(crate::errors::mesh_error)?;
        let mut values = self.values;
        values
            .insert("timings".into(), serde_json::to_value(&t).map_err(crate::errors::mesh_error)?);
        Ok(Fields { json: line.trim_end().to_string(), values })
    }

    /// The value of key `name`, as a new Python object; AttributeError without it.
    ///
    /// Counts are also `*_count` attributes ([`COUNTS`]: `vertex_count` is the key
    /// `vertices`); where the key is the name of an array elsewhere (`Mesh.vertices`,
    /// `Mesh.faces`), the key as an attribute still gives the count but with a
    /// DeprecationWarning (`to_dict()` keeps the command's keys).
    pub fn get<'py>(
        &self,
        py: Python<'py>,
        owner: &str,
        name: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        if let Some((_, key)) = COUNTS.iter().find(|(alias, _)| *alias == name) {
            if let Some(v @ Value::Number(_)) = self.values.get(*key) {
                return to_python(py, v);
            }
        }
        match self.values.get(name) {
            Some(v) => {
                if let (Value::Number(_), Some((alias, _))) =
                    (v, COUNTS.iter().find(|(_, key)| *key == name && DEPRECATED.contains(key)))
                {
                    crate::errors::deprecated(
                        py,
                        &format!(
                            "{owner}.{name} is a count and is now {owner}.{alias} ({name} names \
                             an array elsewhere, as Mesh.{name}); {owner}.{name} will be removed"
                        ),
                    )?;
                }
                to_python(py, v)
            }
            None => Err(PyAttributeError::new_err(format!(
                "'{owner}' object has no attribute '{name}'"
            ))),
        }
    }

    /// `dir()` of an object whose other attributes are these keys: its class's names and
    /// the keys, so that tab completion and `inspect` see every attribute.
    pub fn dir(&self, object: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
        let mut names: Vec<String> = object.get_type().dir()?.extract()?;
        names.extend(self.values.keys().filter(|k| !self.is_deprecated(k)).cloned());
        for (alias, key) in COUNTS {
            if matches!(self.values.get(key), Some(Value::Number(_))) {
                names.push(alias.to_string());
            }
        }
        names.sort();
        names.dedup();
        Ok(names)
    }

    /// The whole object as a new dict, its keys in the command's order (Python's json
    /// keeps the order of the text; serde_json's maps would sort them).
    pub fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let json = py.import("json")?;
        Ok(json.call_method1("loads", (&self.json,))?.cast_into::<PyDict>()?)
    }
}

impl Fields {
    /// Whether the attribute `key` is a count kept under an array's name.
    fn is_deprecated(&self, key: &str) -> bool {
        DEPRECATED.contains(&key) && matches!(self.values.get(key), Some(Value::Number(_)))
    }
}

/// Counts as attributes: (attribute, the report's key).
const COUNTS: [(&str, &str); 6] = [
    ("vertex_count", "vertices"),
    ("face_count", "faces"),
    ("triangle_count", "triangles"),
    ("point_count", "points"),
    ("hull_vertex_count", "hull_vertices"),
    ("hull_face_count", "hull_faces"),
];

/// Keys that are counts in a report but arrays on a Mesh: deprecated as attributes.
const DEPRECATED: [&str; 2] = ["vertices", "faces"];

/// A JSON value as plain Python values: None, bool, int, float, str, list, dict.
pub fn to_python<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => u.into_pyobject(py)?.into_any(),
            (None, Some(i)) => i.into_pyobject(py)?.into_any(),
            _ => n.as_f64().unwrap_or(f64::NAN).into_pyobject(py)?.into_any(),
        },
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(to_python(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(map) => {
            let d = PyDict::new(py);
            for (k, item) in map {
                d.set_item(k, to_python(py, item)?)?;
            }
            d.into_any()
        }
    })
}

/// The methods every result class has (its pyclass holds its report's [`Fields`] as
/// `fields`): the report's keys as attributes and in `dir()`, and `to_dict()`.
macro_rules! report_methods {
    ($class:ty, $name:literal) => {
        #[pyo3::pymethods]
        impl $class {
            /// A key of the report, as a plain value.
            fn __getattr__<'py>(
                &self,
                py: pyo3::Python<'py>,
                name: &str,
            ) -> pyo3::PyResult<pyo3::Bound<'py, pyo3::PyAny>> {
                self.fields.get(py, $name, name)
            }

            fn __dir__(slf: &pyo3::Bound<'_, Self>) -> pyo3::PyResult<Vec<String>> {
                slf.get().fields.dir(slf.as_any())
            }

            /// The report as a dict of plain Python values: the keys, order and structure
            /// of the command's JSON (docs/json.md).
            fn to_dict<'py>(
                &self,
                py: pyo3::Python<'py>,
            ) -> pyo3::PyResult<pyo3::Bound<'py, pyo3::types::PyDict>> {
                self.fields.to_dict(py)
            }
        }
    };
}
pub(crate) use report_methods;
