//! The `meshvol.MeshError` family, and the conversions from the core library's errors.
//!
//! Messages are the core's `Display` texts, the same the `meshvol` command prints after
//! `meshvol: error:`. Arguments that are out of range (a negative density, an axis
//! named `w`) raise plain `ValueError`, and arguments of the wrong type `TypeError`, as
//! Python functions do.

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::fmt::Display;

create_exception!(
    meshvol,
    MeshError,
    PyValueError,
    "Base class of meshvol's errors (a ValueError): a file that cannot be read, arrays \
     that do not form a mesh, or a measurement that cannot be made. The message is the \
     one the meshvol command prints."
);
create_exception!(
    meshvol,
    ReadError,
    MeshError,
    "A file could not be read. Attributes: path (str), location (str or None: 'line 12', \
     'byte 84', 'face 3', an archive part's line, a JSON path), line, byte and face (int \
     or None, whichever the location is), and reason (the message without path and \
     location)."
);
create_exception!(
    meshvol,
    InvalidMeshError,
    MeshError,
    "Arrays (vertices, faces, points, polygon rings) that cannot be used as given: a wrong \
     shape or dtype, a non-finite coordinate, a vertex index out of range, a face with \
     fewer than three vertices."
);

create_exception!(
    meshvol,
    LossyWriteError,
    MeshError,
    "Mesh.save refused to keep a file that does not read back as the mesh's solid: its \
     format (STL and GLB store float32 coordinates) changed the volume beyond the stated \
     tolerance, or collapsed or duplicated faces. Nothing was written. The message names \
     the file and the change; save as .ply or .obj (float64), or pass allow_lossy=True."
);

create_exception!(
    meshvol,
    MeshWarning,
    pyo3::exceptions::PyUserWarning,
    "A measurement was made, but of a solid that may not be the one meant: the surface is \
     open (holes were capped), non-manifold, overlapping or self-intersecting, or faces were \
     left out or turned. The message names the reason, as the meshvol command's warnings do."
);

/// The `stacklevel` that points a warning at the user's line: the first Python frame
/// (from the innermost) that is not in the meshvol package itself (meshvol.dask,
/// meshvol.measure call the native code from Python). A native function has no frame of
/// its own, so level 1 is the frame that called it.
fn user_stacklevel(py: Python<'_>) -> i32 {
    let walk = || -> PyResult<i32> {
        let package = py.import("meshvol")?.getattr("__file__")?;
        let package: String =
            py.import("os.path")?.call_method1("dirname", (package,))?.extract()?;
        let mut frame = py.import("sys")?.call_method1("_getframe", (0,))?;
        let mut level = 1;
        while !frame.is_none() {
            let file: String = frame.getattr("f_code")?.getattr("co_filename")?.extract()?;
            if !file.starts_with(&package) {
                break;
            }
            level += 1;
            frame = frame.getattr("f_back")?;
        }
        Ok(level)
    };
    walk().unwrap_or(1)
}

/// Issues `message` as a warning of `category`, at the user's line.
fn warn_at_user(py: Python<'_>, category: &Bound<'_, PyAny>, message: &str) -> PyResult<()> {
    let text = std::ffi::CString::new(message.replace('\0', " ")).unwrap_or_default();
    PyErr::warn(py, category, &text, user_stacklevel(py))
}

/// Issues each of `messages` as a [`MeshWarning`], pointing at the line that called
/// meshvol.
pub fn warn_all(py: Python<'_>, messages: &[String]) -> PyResult<()> {
    let category = py.get_type::<MeshWarning>();
    for m in messages {
        warn_at_user(py, &category, m)?;
    }
    Ok(())
}

/// Issues a DeprecationWarning at the user's line.
pub fn deprecated(py: Python<'_>, message: &str) -> PyResult<()> {
    let category = py.get_type::<pyo3::exceptions::PyDeprecationWarning>();
    warn_at_user(py, &category, message)
}

/// The exception for a file that cannot be opened: `meshvol.MeshFileNotFoundError`
/// (a FileNotFoundError), `MeshPermissionError` (a PermissionError),
/// `MeshIsADirectoryError` (an IsADirectoryError), or `MeshOSError` (an OSError); each is
/// also a ReadError (so a MeshError), with OSError's errno, strerror and filename, and
/// ReadError's path and reason.
pub fn open_error(py: Python<'_>, path: &std::path::Path, e: &std::io::Error) -> PyErr {
    let make = || -> PyResult<PyErr> {
        use std::io::ErrorKind;
        let class = match e.kind() {
            ErrorKind::NotFound => "MeshFileNotFoundError",
            ErrorKind::PermissionDenied => "MeshPermissionError",
            ErrorKind::IsADirectory => "MeshIsADirectoryError",
            _ => "MeshOSError",
        };
        let class = py.import("meshvol._errors")?.getattr(class)?;
        let errno = e.raw_os_error().unwrap_or(match e.kind() {
            ErrorKind::NotFound => 2,
            ErrorKind::PermissionDenied => 13,
            ErrorKind::IsADirectory => 21,
            _ => 5,
        });
        // The OS's words without Rust's " (os error 2)".
        let text = e.to_string();
        let reason = match text.rfind(" (os error ") {
            Some(i) => text[..i].to_string(),
            None => text,
        };
        let value = class.call1((errno, &reason, path.as_os_str()))?;
        value.setattr("path", path.as_os_str())?;
        for key in ["location", "line", "byte", "face"] {
            value.setattr(key, py.None())?;
        }
        value.setattr("reason", &reason)?;
        Ok(PyErr::from_value(value))
    };
    make().unwrap_or_else(|err| err)
}

/// A [`MeshError`] with `message`.
pub fn mesh_error(message: impl Display) -> PyErr {
    MeshError::new_err(message.to_string())
}

/// An [`InvalidMeshError`] with `message`.
pub fn invalid(message: impl Display) -> PyErr {
    InvalidMeshError::new_err(message.to_string())
}

/// A `ValueError` for an argument out of range.
pub fn bad_argument(message: impl Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// The exception for a mesh that was not written: `OSError` when the file could not be
/// written, [`LossyWriteError`] when it was not the solid meant, [`MeshError`] otherwise.
pub fn write_error(e: &meshvol_report::written::WriteError) -> PyErr {
    use meshvol_report::written::WriteError;
    let message = e.message("allow_lossy=True");
    match e {
        WriteError::Io(_) => pyo3::exceptions::PyOSError::new_err(message),
        WriteError::Failed(_) => MeshError::new_err(message),
        WriteError::Changed(_) => LossyWriteError::new_err(message),
    }
}

/// A [`ReadError`] carrying the file's path and the place of the problem.
pub fn read_error(py: Python<'_>, e: &meshvol_io::ReadError) -> PyErr {
    use meshvol_io::Location;
    let err = ReadError::new_err(e.to_string());
    let value = err.value(py);
    let (line, byte, face) = match &e.location {
        Some(Location::Line(l)) => (Some(*l), None, None),
        Some(Location::Byte(b)) => (None, Some(*b), None),
        Some(Location::Face(f)) => (None, None, Some(*f as u64)),
        _ => (None, None, None),
    };
    let attributes = [
        value.setattr("path", e.path.as_os_str()),
        value.setattr("location", e.location.as_ref().map(ToString::to_string)),
        value.setattr("line", line),
        value.setattr("byte", byte),
        value.setattr("face", face),
        value.setattr("reason", &e.message),
    ];
    match attributes.into_iter().find_map(Result::err) {
        Some(failed) => failed,
        None => err,
    }
}
