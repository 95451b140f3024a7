//! `meshvol.load`: a mesh file read as the command reads it, from a path or a binary file
//! object, into a `Mesh` that keeps where it came from (format, declared unit, objects,
//! bodies, the reader's warnings); and every mesh argument, which may be a path.

use crate::errors::read_error;
use crate::mesh::{mesh_of, PyMesh};
use meshvol_io::compressed::COMPRESSED_EXTENSIONS;
use meshvol_io::InputKind;
use meshvol_report::subject::Source;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;

/// `file_type` checked: a format's extension, without its dot, lower case ('stl'), or
/// one compressed ('stl.gz', 'ply.zst'), or a compression alone ('gz', 'zip': the format
/// then by the content, or the zip member's name): the endings the command reads.
fn file_type_of(file_type: Option<&str>) -> PyResult<Option<String>> {
    let Some(t) = file_type else { return Ok(None) };
    let t = t.trim().trim_start_matches('.').to_ascii_lowercase();
    let formats = InputKind::Mesh.extensions();
    let endings = InputKind::Mesh.name_endings();
    let known = endings.iter().any(|e| e.strip_prefix('.') == Some(t.as_str()))
        || COMPRESSED_EXTENSIONS.contains(&t.as_str());
    if known {
        Ok(Some(t))
    } else {
        Err(crate::errors::bad_argument(format!(
            "file_type must be one of {}, one of those compressed ('stl.gz', '.bz2', '.zst'), \
             or a compression alone ({}); got '{t}'",
            formats.join(", "),
            COMPRESSED_EXTENSIONS.join(", ")
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
/// ('stl', 'obj', 'off', 'ply', '3mf', 'gltf', 'glb', each also compressed: 'stl.gz',
/// 'obj.bz2', 'ply.zst'; or a compression alone: 'gz', 'bz2', 'zst', 'zip') names the
/// format when the name does not, as the file's ending would (a file object without a
/// name is otherwise recognised by its content).
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

/// A mesh argument as every call that takes meshes takes it: a meshvol.Mesh, an object
/// with .vertices and .faces (a trimesh.Trimesh), or a path (str, bytes, os.PathLike)
/// read as [`load`] reads it.
pub struct MeshArg<'py> {
    pub mesh: Bound<'py, PyMesh>,
    /// Read here from a path: its reader's warnings not given yet (a Mesh given keeps
    /// them in `Mesh.warnings`).
    pub read_here: bool,
}

impl<'py> MeshArg<'py> {
    pub fn of(obj: &Bound<'py, PyAny>) -> PyResult<MeshArg<'py>> {
        if obj.cast::<PyMesh>().is_err() && is_path(obj)? {
            let mesh = Bound::new(obj.py(), load(obj.py(), obj, None)?)?;
            return Ok(MeshArg { mesh, read_here: true });
        }
        Ok(MeshArg { mesh: mesh_of(obj)?, read_here: false })
    }
}

/// Whether `obj` is a path: str, bytes or os.PathLike.
pub fn is_path(obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    Ok(path_of(obj)?.is_some())
}

/// Issues a report's warnings as MeshWarnings, less the reader's warnings of the meshes
/// given as meshes (those of a file read here are the report's to give, as the command
/// gives them).
pub fn warn_for(py: Python<'_>, meshes: &[MeshArg<'_>], warnings: &[String]) -> PyResult<()> {
    let given = |w: &String| {
        meshes.iter().any(|m| !m.read_here && m.mesh.get().source.warnings.contains(w))
    };
    let new: Vec<String> = warnings.iter().filter(|w| !given(w)).cloned().collect();
    crate::errors::warn_all(py, &new)
}
