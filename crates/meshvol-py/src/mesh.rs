//! `meshvol.Mesh` and `meshvol.load`.

use crate::convert;
use crate::errors::{invalid, mesh_error};
use meshvol::assembly::Assembly;
use meshvol::overlap::Body;
use meshvol::topology::{self, Check, CheckError, CheckOptions};
use meshvol::{Faces, Mesh, MeshError};
use meshvol_report::intersect::prepare;
use meshvol_report::subject::{Source, Subject};
use numpy::ndarray::ArrayView2;
use numpy::{Element, PyArray1, PyArray2};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

/// A surface mesh: float64 vertices and faces (triangles, or polygons of any size) that
/// index them.
///
/// Mesh(vertices, faces) builds one from arrays: vertices an (n, 3) array (float64 used
/// as is; float32 and integers widened to float64), faces an (m, 3) integer array of any
/// integer dtype, an (m, k) one for faces of k vertices, or a list of polygons (lists of
/// vertex indices, of any sizes). Mesh(obj) takes obj.vertices and obj.faces, so a
/// trimesh.Trimesh (or another meshvol.Mesh) can be passed as it is.
///
/// The arrays are copied once and checked: every coordinate finite, every index in
/// range, every face at least three vertices; anything else raises InvalidMeshError.
/// A Mesh never changes after it is built.
#[pyclass(module = "meshvol", name = "Mesh", frozen)]
pub struct PyMesh {
    pub(crate) mesh: Mesh,
    /// Where it came from: a file (as the readers found it), or arrays.
    pub(crate) source: Source,
    /// How the file assembled it from placed parts, when it repeats a part.
    pub(crate) assembly: Option<Arc<Assembly>>,
    /// The check with default options, made on first use and kept: every measurement
    /// of the solid starts from it.
    checked: OnceLock<Check>,
    /// Its checked solid prepared for intersections' boundary method, made on first use
    /// and kept, so a loop over poses prepares nothing again (`None` inside: the check
    /// does not vouch for the solid; the grid method measures it).
    prepared: OnceLock<Option<Body>>,
}

impl From<Mesh> for PyMesh {
    fn from(mesh: Mesh) -> Self {
        let source = Source::arrays(mesh.vertex_count());
        PyMesh::of(mesh, source, None)
    }
}

impl PyMesh {
    pub(crate) fn of(mesh: Mesh, source: Source, assembly: Option<Arc<Assembly>>) -> PyMesh {
        PyMesh { mesh, source, assembly, checked: OnceLock::new(), prepared: OnceLock::new() }
    }

    /// The checked solid prepared for the boundary method of intersections
    /// ([`meshvol_report::intersect::prepare`]), computed once; `None` with `check`
    /// false (the surface as wound is measured by the grid method).
    pub(crate) fn prepared(&self, py: Python<'_>, check: bool) -> PyResult<Option<&Body>> {
        if !check {
            return Ok(None);
        }
        if let Some(p) = self.prepared.get() {
            return Ok(p.as_ref());
        }
        let subject = self.subject(py, true)?;
        let p = py.detach(|| prepare(&subject));
        Ok(self.prepared.get_or_init(|| p).as_ref())
    }

    /// The check with default options (`meshvol check`'s), computed once.
    pub(crate) fn checked(&self, py: Python<'_>) -> PyResult<&Check> {
        if let Some(c) = self.checked.get() {
            return Ok(c);
        }
        let c = py
            .detach(|| self.check_with(&CheckOptions::default()))
            .map_err(crate::errors::mesh_error)?;
        Ok(self.checked.get_or_init(|| c))
    }

    /// The check of this mesh with `options` (from its parts when it is an assembly).
    pub(crate) fn check_with(&self, options: &CheckOptions) -> Result<Check, CheckError> {
        let bodies = self.source.body_faces();
        topology::check_assembled(&self.mesh, self.assembly.as_deref(), &bodies, options, &())
    }

    /// What a measurement is taken of: with `check`, the solid the surface bounds (as
    /// every command measures by default); without, the surface as wound.
    pub(crate) fn subject(&self, py: Python<'_>, check: bool) -> PyResult<Subject<'_, Mesh>> {
        let check = if check { Some(self.checked(py)?) } else { None };
        Ok(Subject { source: &self.source, surface: &self.mesh, check })
    }

    /// The check with default options run again, its stages timed on `clock` (and kept
    /// when none was).
    pub(crate) fn timed_check(
        &self,
        py: Python<'_>,
        clock: &crate::timings::Clock,
    ) -> PyResult<Check> {
        clock.start("checking");
        let options = CheckOptions::default();
        let bodies = self.source.body_faces();
        let owned = py
            .detach(|| {
                let assembly = self.assembly.as_deref();
                topology::check_assembled(&self.mesh, assembly, &bodies, &options, clock)
            })
            .map_err(crate::errors::mesh_error)?;
        if self.checked.get().is_none() {
            let _ = self.checked.set(owned.clone());
        }
        Ok(owned)
    }

    /// `f` of the subject, as [`PyMesh::subject`] gives it; with a clock (`timings=True`)
    /// the check runs again, its stages timed (and is kept when none was), then
    /// `measuring` starts.
    pub(crate) fn with_subject<R>(
        &self,
        py: Python<'_>,
        check: bool,
        clock: Option<&crate::timings::Clock>,
        f: impl FnOnce(Subject<'_, Mesh>) -> PyResult<R>,
    ) -> PyResult<R> {
        let Some(clock) = clock.filter(|_| check) else {
            let subject = self.subject(py, check)?;
            crate::timings::stage(clock, "measuring");
            return f(subject);
        };
        let owned = self.timed_check(py, clock)?;
        clock.start("measuring");
        f(Subject { source: &self.source, surface: &self.mesh, check: Some(&owned) })
    }

    /// Issues a report's warnings as MeshWarnings, less the reader's (given once, in
    /// `Mesh.warnings`).
    pub(crate) fn warn(&self, py: Python<'_>, warnings: &[String]) -> PyResult<()> {
        let new: Vec<String> =
            warnings.iter().filter(|w| !self.source.warnings.contains(w)).cloned().collect();
        crate::errors::warn_all(py, &new)
    }
}

/// A mesh from a vertex array and a face array or polygon list.
pub fn from_arrays(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
) -> PyResult<Mesh> {
    let positions = convert::coordinates::<3>(vertices, "vertices")?;
    if u32::try_from(positions.len()).is_err() {
        return Err(invalid(MeshError::TooManyVertices { vertices: positions.len() }));
    }
    let faces = convert::faces(faces, positions.len())?;
    py.detach(|| Mesh::new(positions, faces)).map_err(invalid)
}

/// `obj` as a Mesh: itself when it is one, else built from its `.vertices` and `.faces`.
pub fn mesh_of<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyMesh>> {
    if let Ok(mesh) = obj.cast::<PyMesh>() {
        return Ok(mesh.clone());
    }
    match convert::mesh_like(obj)? {
        Some((vertices, faces)) => {
            let mesh = from_arrays(obj.py(), &vertices, &faces)?;
            Bound::new(obj.py(), PyMesh::from(mesh))
        }
        None => Err(PyTypeError::new_err(format!(
            "expected a mesh (a meshvol.Mesh, or an object with .vertices and .faces such as a \
             trimesh.Trimesh); got {}",
            obj.get_type().name()?
        ))),
    }
}

/// A read-only NumPy array over `values` (n rows of N), owned by `owner`.
fn read_only_view<'py, T: Element, const N: usize>(
    owner: &Bound<'py, PyMesh>,
    values: &[[T; N]],
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let view =
        ArrayView2::from_shape((values.len(), N), values.as_flattened()).map_err(mesh_error)?;
    // SAFETY: the array's base object is `owner`, which keeps the mesh alive; a Mesh is
    // frozen (never mutated), so `values` is never reallocated or written while the
    // array exists, and the array is made read-only before Python sees it.
    let array = unsafe { PyArray2::borrow_from_array(&view, owner.clone().into_any()) };
    let flags = PyDict::new(owner.py());
    flags.set_item("write", false)?;
    array.call_method("setflags", (), Some(&flags))?;
    Ok(array)
}

#[pymethods]
impl PyMesh {
    #[new]
    #[pyo3(signature = (vertices, faces = None))]
    fn new(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        faces: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        if let Some(faces) = faces {
            return Ok(PyMesh::from(from_arrays(py, vertices, faces)?));
        }
        if let Ok(other) = vertices.cast::<PyMesh>() {
            return Ok(PyMesh {
                mesh: other.get().mesh.clone(),
                source: other.get().source.clone(),
                assembly: other.get().assembly.clone(),
                checked: other.get().checked.clone(),
                prepared: other.get().prepared.clone(),
            });
        }
        match convert::mesh_like(vertices)? {
            Some((v, f)) => Ok(PyMesh::from(from_arrays(py, &v, &f)?)),
            None => Err(PyTypeError::new_err(
                "Mesh(vertices, faces): give the faces too, or one object with .vertices and \
                 .faces (such as a trimesh.Trimesh)",
            )),
        }
    }

    /// The (n, 3) float64 vertex array: a read-only view of the mesh's own memory (no
    /// copy). Copy it (`numpy.array(mesh.vertices)`) to change it.
    #[getter]
    fn vertices<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        read_only_view(slf, slf.get().mesh.positions())
    }

    /// The faces: for a triangle mesh a read-only (m, 3) uint32 view of the mesh's own
    /// memory (no copy); for a mesh with larger faces, a list of lists of vertex indices
    /// (`face_indices` and `face_offsets` are arrays for every mesh).
    #[getter]
    fn faces<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        match slf.get().mesh.faces() {
            Faces::Triangles(triangles) => Ok(read_only_view(slf, triangles)?.into_any()),
            Faces::Polygons { offsets, indices } => {
                let list = PyList::empty(slf.py());
                for w in offsets.windows(2) {
                    list.append(PyList::new(slf.py(), &indices[w[0]..w[1]])?)?;
                }
                Ok(list.into_any())
            }
        }
    }

    /// Every mesh's faces as two arrays, whatever their sizes (the compressed-row form of
    /// VTK and PyVista): face f's vertex indices are
    /// `face_indices[face_offsets[f]:face_offsets[f + 1]]`. `face_indices` is uint32 (a
    /// new array; for a triangle mesh, `faces.ravel()`), `face_offsets` uint64 with
    /// `face_count + 1` entries starting at 0.
    #[getter]
    fn face_indices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        match self.mesh.faces() {
            Faces::Triangles(triangles) => {
                PyArray1::from_iter(py, triangles.iter().flatten().copied())
            }
            Faces::Polygons { indices, .. } => PyArray1::from_slice(py, indices),
        }
    }

    /// See `face_indices`.
    #[getter]
    fn face_offsets<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u64>> {
        match self.mesh.faces() {
            Faces::Triangles(triangles) => {
                PyArray1::from_iter(py, (0..=triangles.len() as u64).map(|f| 3 * f))
            }
            Faces::Polygons { offsets, .. } => {
                PyArray1::from_iter(py, offsets.iter().map(|&o| o as u64))
            }
        }
    }

    /// The number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }

    /// The number of faces.
    #[getter]
    fn face_count(&self) -> usize {
        self.mesh.face_count()
    }

    /// The number of triangles in the faces' fans (a face of k vertices counts k - 2).
    #[getter]
    fn triangle_count(&self) -> usize {
        self.mesh.triangle_count()
    }

    /// Whether every face is a triangle.
    #[getter]
    fn is_triangle_mesh(&self) -> bool {
        matches!(self.mesh.faces(), Faces::Triangles(_))
    }

    /// The file format the mesh was read from (`stl-binary`, `obj`, `3mf`, ...), or None
    /// for a mesh built from arrays.
    #[getter]
    fn format(&self) -> Option<&'static str> {
        self.source.format
    }

    /// The path the mesh was read from, as given to load(); None for arrays.
    #[getter]
    fn file(&self) -> Option<&str> {
        self.source.file.as_deref()
    }

    /// The length unit the file declares (`mm`, `m`, ...: 3MF and glTF declare one), or
    /// None. Measurements are always in the file's own coordinates.
    #[getter]
    fn unit(&self) -> Option<&'static str> {
        self.source.unit.map(|u| u.symbol())
    }

    /// What the reader read but did not use, or had to guess (as the command warns).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.source.warnings.clone()
    }

    /// The file's named parts when it has two or more: (name, first face, end face)
    /// tuples, faces [first, end) of this mesh. Empty otherwise.
    #[getter]
    fn objects(&self) -> Vec<(String, usize, usize)> {
        self.source.objects.iter().map(|o| (o.name.clone(), o.faces.start, o.faces.end)).collect()
    }

    /// Pickling (multiprocessing, Dask): a Mesh travels as its vertex and face arrays and
    /// is rebuilt as Mesh(vertices, faces), so where it was read from (file, format,
    /// warnings, objects) stays behind; every measurement is the same.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let arrays = (Self::vertices(slf)?, Self::faces(slf)?).into_pyobject(slf.py())?;
        Ok((slf.get_type().into_any(), arrays))
    }

    /// Writes the mesh to path, in the format its extension names: .ply (binary, float64
    /// coordinates), .obj (every bit, as decimals), .stl (binary, float32) or .glb
    /// (float32); Check.solid_mesh(caps=True).save("part.ply") writes what `meshvol repair
    /// --cap -o part.ply` writes.
    ///
    /// The file is then read back (as meshvol.load reads it), checked and measured, and
    /// must be the same solid as this mesh: the same volume within the stated tolerance
    /// (rounding bounds, caps, and for float32 formats 1e-6 of the volume), the same
    /// triangles and shells, no face collapsed or duplicated. float32 coordinates far
    /// from the origin for the mesh's size break that. Then nothing is written (a file
    /// already at path is left as it was) and LossyWriteError says what changed; with
    /// allow_lossy=True the file is kept and a MeshWarning says what changed.
    ///
    /// Returns what was written, as read back: a dict with the keys of the `written`
    /// object of `meshvol repair --json` (file, format, coordinates, intended_volume,
    /// volume, tolerance, intended_triangles, triangles, collapsed_faces,
    /// duplicate_faces, closed, same_solid). Raises OSError when the file cannot be
    /// written, MeshError for an extension it cannot write.
    #[pyo3(signature = (path, allow_lossy = false))]
    fn save<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
        allow_lossy: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let written = py
            .detach(|| meshvol_report::written::write_mesh(&self.mesh, &path, allow_lossy))
            .map_err(|e| crate::errors::write_error(&e))?;
        crate::errors::warn_all(py, &written.warning().into_iter().collect::<Vec<_>>())?;
        crate::dict::Fields::new(&written)?.to_dict(py)
    }

    /// The same surface with every face replaced by its fan of triangles.
    fn triangulated(&self, py: Python<'_>) -> PyMesh {
        PyMesh::from(py.detach(|| self.mesh.triangulated()))
    }

    /// The same mesh with every face's winding reversed (inward-wound files, such as
    /// OpenSCAD's, turned outward).
    fn flipped(&self, py: Python<'_>) -> PyMesh {
        PyMesh::from(py.detach(|| self.mesh.flipped()))
    }

    fn __repr__(&self) -> String {
        let format = self.source.format.map(|f| format!(", format='{f}'")).unwrap_or_default();
        format!(
            "Mesh(vertices={}, faces={}, triangles={}{format})",
            self.mesh.vertex_count(),
            self.mesh.face_count(),
            self.mesh.triangle_count()
        )
    }
}
