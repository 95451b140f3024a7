//! `meshvol.load`: a mesh file read as the command reads it, from a path or a binary file
//! object, into a `Mesh` that keeps where it came from (format, declared unit, objects,
//! bodies, the reader's warnings).

use crate::errors::read_error;
use crate::mesh::PyMesh;
use meshvol_report::subject::Source;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;

/// The extensions `file_type` may name.
const FILE_TYPES: [&str; 7] = ["stl", "obj", "off", "ply", "3mf", "gltf", "glb"];

/// `file_type` checked: an extension, without its dot, lower case.
fn file_type_of(file_type: Option<&str>) -> PyResult<Option<String>> {
    let Some(t) = file_type else { return Ok(None) };
    let t = t.trim().trim_start_matches('.').to_ascii_lowercase();
    if FILE_TYPES.contains(&t.as_str()) {
        Ok(Some(t))
    } else {
        Err(crate::errors::bad_argument(format!(
            "file_type must be one of {}; got '{t}'",
            FILE_TYPES.join(", ")
        )))
    }
}

/// A path given as str, bytes or os.PathLike.
fn path_of(file: &Bound<'_, PyAny>) -> PyResult<Option<PathBuf>> {
    let os = file.py().import("os")?;
    let Ok(path) = os.call_method1("fspath", (file,)) else { return Ok(None) };
    let path = os.call_method1("fsdecode", (path,))?;
    Ok(Some(path.extract()?))
}

/// What `load` reads: the bytes of a file object (with the name it goes by), or a path.
enum LoadSource {
    Path(PathBuf),
    Stream { name: String, bytes: Vec<u8> },
}

fn load_source(file: &Bound<'_, PyAny>) -> PyResult<LoadSource> {
    if let Some(path) = path_of(file)? {
        return Ok(LoadSource::Path(path));
    }
    if !file.hasattr("read")? {
        return Err(PyTypeError::new_err(format!(
            "load() takes a path (str, bytes or os.PathLike) or a binary file object; got {}",
            file.get_type().name()?
        )));
    }
    let data = file.call_method0("read")?;
    let bytes: Vec<u8> = if let Ok(b) = data.cast::<pyo3::types::PyBytes>() {
        b.as_bytes().to_vec()
    } else if data.is_instance_of::<pyo3::types::PyString>() {
        return Err(PyTypeError::new_err(
            "load() read text from the file object: open it in binary mode ('rb'), or pass io.BytesIO",
        ));
    } else {
        file.py().import("builtins")?.getattr("bytes")?.call1((data,))?.extract()?
    };
    let name = match file.getattr("name").ok().and_then(|n| path_of(&n).ok().flatten()) {
        Some(p) => p.display().to_string(),
        None => "<file object>".to_string(),
    };
    Ok(LoadSource::Stream { name, bytes })
}

/// Reads a mesh file: STL (binary or ASCII), OBJ, OFF, PLY, 3MF, glTF/GLB, the format
/// chosen by extension and content as the command does.
///
/// file is a path (str, bytes or os.PathLike) or a binary file object (anything with
/// read() returning bytes: open(path, "rb"), io.BytesIO, a zip member). file_type
/// ('stl', 'obj', 'off', 'ply', '3mf', 'gltf', 'glb') names the format when the name
/// does not (a file object without a name is otherwise recognised by its content).
///
/// A file that cannot be opened raises the OSError Python raises for it
/// (FileNotFoundError, PermissionError, IsADirectoryError: meshvol.MeshFileNotFoundError
/// and its siblings), which is also a meshvol.ReadError; a file that cannot be read as a
/// mesh raises ReadError naming the file and the place of the problem.
#[pyfunction]
#[pyo3(signature = (file, file_type = None))]
pub fn load(py: Python<'_>, file: &Bound<'_, PyAny>, file_type: Option<&str>) -> PyResult<PyMesh> {
    let file_type = file_type_of(file_type)?;
    let (name, loaded) = match load_source(file)? {
        LoadSource::Path(path) => {
            let opened = std::fs::metadata(&path).and_then(|m| {
                if m.is_dir() {
                    Err(std::io::Error::from(std::io::ErrorKind::IsADirectory))
                } else {
                    std::fs::File::open(&path).map(drop)
                }
            });
            if let Err(e) = opened {
                return Err(crate::errors::open_error(py, &path, &e));
            }
            let loaded = match &file_type {
                None => py.detach(|| meshvol_io::read(&path)),
                Some(t) => {
                    let bytes = std::fs::read(&path)
                        .map_err(|e| crate::errors::open_error(py, &path, &e))?;
                    let typed = path.with_extension(t);
                    py.detach(|| meshvol_io::read_bytes(&typed, bytes)).map_err(|mut e| {
                        e.path.clone_from(&path);
                        e
                    })
                }
            };
            (path.display().to_string(), loaded)
        }
        LoadSource::Stream { name, bytes } => {
            let typed = match &file_type {
                Some(t) => PathBuf::from(format!("stream.{t}")),
                None => PathBuf::from(&name),
            };
            let loaded = py.detach(|| meshvol_io::read_bytes(&typed, bytes)).map_err(|mut e| {
                e.path = PathBuf::from(&name);
                e
            });
            (name, loaded)
        }
    };
    let loaded = loaded.map_err(|e| read_error(py, &e))?;
    let source = Source::of(&name, &loaded);
    let assembly = loaded.assembly.map(Arc::new);
    let surface = loaded.surface;
    let mesh = py.detach(|| surface.into_mesh()).map_err(|e| {
        let error = meshvol_io::ReadError {
            path: PathBuf::from(&name),
            location: None,
            message: e.to_string(),
            budget: None,
        };
        read_error(py, &error)
    })?;
    Ok(PyMesh::of(mesh, source, assembly))
}
