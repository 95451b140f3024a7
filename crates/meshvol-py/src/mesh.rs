//! `meshvol.Mesh` and `meshvol.load`.

use crate::check::{self, PyCheck};
use crate::convert;
use crate::errors::{invalid, mesh_error};
use crate::grid::{self, PyProfile};
use crate::properties::{self, PyMassProperties};
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

    /// Volume, area, centroid and inertia of the solid the surface bounds: the report
    /// of `meshvol volume`. By default the solid is the checked one (welded, shells
    /// turned outward, cavities subtracted, duplicate faces dropped, holes capped), and
    /// why it may not be the one meant is issued as MeshWarnings and listed in
    /// `warnings`; check=False measures the surface as wound (`meshvol volume
    /// --no-check`). signed_volume is always the surface's as wound (negative for
    /// inward winding), as in the command's JSON.
    ///
    /// density scales mass, inertia and principal moments: a number, or text with a unit
    /// as the command's --density takes it ('7.85g/cm3', with units naming the file's
    /// length unit). exact=True replaces the
    /// volume by the correctly rounded exact one (a few times slower). units converts
    /// as the command's --units does: 'FILE[:REPORT]' ('mm:cm', 'in:mL') or ':REPORT'
    /// from the unit the file declares (3MF, glTF); files that declare one are reported
    /// in it by default.
    ///
    /// timings=True adds `timings`, the stages (the check's, then measuring) with their
    /// wall and CPU seconds, as the command's --timings: the check then runs again.
    #[pyo3(signature = (density = None, exact = false, check = true, units = None, timings = false), text_signature = "(self, density=1.0, exact=False, check=True, units=None, timings=False)")]
    fn mass_properties(
        &self,
        py: Python<'_>,
        density: Option<&Bound<'_, PyAny>>,
        exact: bool,
        check: bool,
        units: Option<&str>,
        timings: bool,
    ) -> PyResult<PyMassProperties> {
        let clock = timings.then(crate::timings::Clock::new);
        let measured = self.with_subject(py, check, clock.as_ref(), |subject| {
            properties::measure(py, self, subject.check, density, exact, units)
        })?;
        measured.timed(clock.map(|c| c.finish()))
    }

    /// The topology facts of `meshvol check`: closed? manifold? winding? shells,
    /// cavities, overlaps, self-intersections; and the solid's volume.
    ///
    /// weld_tolerance: None welds exactly equal positions, and when that leaves holes,
    /// again within 1e-9 of the bounding box diagonal; 0 welds exact positions only; a
    /// positive number welds positions that close. intersections=False skips the search
    /// for crossing triangles.
    ///
    /// units and density as the command's --units and --density (the solid's volume in
    /// those units, and its mass).
    /// timings=True adds `timings`: the check's stages, as the command's --timings.
    #[pyo3(signature = (weld_tolerance = None, intersections = true, units = None, density = None, timings = false))]
    fn check(
        slf: &Bound<'_, Self>,
        weld_tolerance: Option<f64>,
        intersections: bool,
        units: Option<&str>,
        density: Option<&Bound<'_, PyAny>>,
        timings: bool,
    ) -> PyResult<PyCheck> {
        let options = crate::units::options(units, density)?;
        check::check(slf, weld_tolerance, intersections, &options, timings)
    }

    /// The volume of the solid in each cell of a regular grid, as a meshvol.Grid: its
    /// values are an (nx, ny, nz) float64 array, exact up to rounding (negative where the
    /// surface is wound inward), and it says where the cells are (origin, spacing,
    /// bounds). np.asarray(grid) is the array; NumPy functions and operators take the
    /// Grid as it.
    ///
    /// cells=(nx, ny, nz) cells between bounds=[[x0, y0, z0], [x1, y1, z1]] (any (2, 3)
    /// array-like, such as trimesh's mesh.bounds; default: the mesh's bounding box); or
    /// pitch=h (or (hx, hy, hz)): cells of that size from the lower bound, enough of
    /// them to cover the upper one (the grid's bounds then reach past it). fraction=True
    /// divides each cell's volume by the cell's.
    ///
    /// region=((i0, i1), (j0, j1), (k0, k1)) returns only the block of cells i0 <= i <
    /// i1, j0 <= j < j1, k0 <= k < k1 of that grid: the same bits as the whole grid's
    /// [i0:i1, j0:j1, k0:k1], computed from the faces over the block's columns alone
    /// (meshvol.dask spreads a grid's blocks over workers this way); its origin is the
    /// block's first corner.
    ///
    /// check=True (the default) measures the checked solid, as `meshvol grid` does;
    /// check=False the surface as wound.
    ///
    /// units as the command's --units ('mm:mL': values in mL, origin and spacing in the
    /// report's length unit; bounds and pitch are given in the file's units); density
    /// makes the values masses (a mass per cell; not with fraction=True).
    ///
    /// timings=True adds `timings` to the Grid: the check's stages, then the kernel's, as
    /// in mass_properties.
    ///
    /// backend as the command's --backend: 'auto' (an OpenCL GPU with f64 when there is
    /// one, else the CPU), 'cpu', or 'opencl' (any OpenCL device; opencl_device=N picks
    /// one of `meshvol devices`): the same bits on each.
    #[pyo3(signature = (cells = None, bounds = None, fraction = false, pitch = None, check = true, region = None, units = None, density = None, timings = false, backend = "auto", opencl_device = None))]
    #[allow(clippy::too_many_arguments)]
    fn grid<'py>(
        &self,
        py: Python<'py>,
        cells: Option<&Bound<'py, PyAny>>,
        bounds: Option<&Bound<'py, PyAny>>,
        fraction: bool,
        pitch: Option<&Bound<'py, PyAny>>,
        check: bool,
        region: Option<&Bound<'py, PyAny>>,
        units: Option<&str>,
        density: Option<&Bound<'py, PyAny>>,
        timings: bool,
        backend: &str,
        opencl_device: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        properties::require_faces(&self.mesh)?;
        let on = grid::backend(backend, opencl_device)?;
        let options = crate::units::options(units, density)?;
        if fraction && options.density.is_some() {
            return Err(crate::errors::bad_argument("give density or fraction=True, not both"));
        }
        let (scale, warning) = meshvol_report::units::Scale::resolve(&options, self.source.unit)
            .map_err(crate::errors::bad_argument)?;
        let clock = timings.then(crate::timings::Clock::new);
        let grid = self.with_subject(py, check, clock.as_ref(), |subject| {
            let mut warnings = subject.warnings();
            warnings.extend(warning);
            self.warn(py, &warnings)?;
            let measured = subject.measured();
            let c = clock.as_ref();
            let place = (cells, bounds, fraction, pitch, region);
            grid::cell_volumes(py, &measured, place, &scale, &on, c)
        })?;
        if let Some(clock) = clock {
            grid.setattr("_timings", crate::timings::to_python(py, &clock.finish())?)?;
        }
        Ok(grid)
    }

    /// The cut-cell geometry of the solid on a grid (`meshvol grid --moments`): a
    /// meshvol.CutCells, a dict of float64 arrays: volume, fraction, centroid,
    /// boundary_area, boundary_vector, boundary_centroid (cells, vectors with a last axis
    /// of 3) and aperture_x, aperture_y, aperture_z (the cell faces along each axis);
    /// with origin, spacing and to_xarray(). cells, bounds and pitch as Mesh.grid takes
    /// them; check and units as every method (lengths, areas and volumes in the report's
    /// units; fractions and apertures are ratios). region=((i0, i1), (j0, j1), (k0, k1))
    /// gives the block of those cells (and the apertures of their faces), the same bits as
    /// the whole grid's (meshvol.dask.grid(moments=True) computes blocks this way).
    /// second_moments=True adds inertia (cells, 3, 3): each cell's solid's inertia tensor
    /// about its centroid, unit density, as mass_properties' inertia; face_centroids=True
    /// adds aperture_x_centroid, … (faces, 3): the centroid of each face's part inside the
    /// solid, NaN where the aperture is 0. docs/cells.md has the definitions.
    /// moments=True (the default) is what it computes, named as meshvol.dask.grid
    /// names it; moments=False is a ValueError pointing to Mesh.grid, the volumes alone.
    /// backend as Mesh.grid's: the cut cells run on the CPU ('opencl' is refused, 'auto'
    /// takes the CPU).
    #[pyo3(signature = (cells = None, bounds = None, pitch = None, check = true, region = None, units = None, second_moments = false, face_centroids = false, moments = true, backend = "auto", opencl_device = None))]
    #[allow(clippy::too_many_arguments)]
    fn cells<'py>(
        &self,
        py: Python<'py>,
        cells: Option<&Bound<'py, PyAny>>,
        bounds: Option<&Bound<'py, PyAny>>,
        pitch: Option<&Bound<'py, PyAny>>,
        check: bool,
        region: Option<&Bound<'py, PyAny>>,
        units: Option<&str>,
        second_moments: bool,
        face_centroids: bool,
        moments: bool,
        backend: &str,
        opencl_device: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        grid::backend(backend, opencl_device)?
            .cpu_only("the cut cells (Mesh.cells)", "leave backend='auto' or give 'cpu'")
            .map_err(crate::errors::bad_argument)?;
        if !moments {
            return Err(crate::errors::bad_argument(
                "Mesh.cells computes the cut cells (moments=True); for the cells' volumes alone use Mesh.grid",
            ));
        }
        properties::require_faces(&self.mesh)?;
        let options = crate::units::options(units, None)?;
        let (scale, warning) = meshvol_report::units::Scale::resolve(&options, self.source.unit)
            .map_err(crate::errors::bad_argument)?;
        let subject = self.subject(py, check)?;
        let mut warnings = subject.warnings();
        warnings.extend(warning);
        self.warn(py, &warnings)?;
        let measured = subject.measured();
        let extras = meshvol::grid::Extras { second_moments, face_centroids };
        let place = grid::Place { cells, bounds, pitch, region };
        grid::cut_cells(py, &measured, place, extras, &scale)
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

    /// The volume below each level along an axis (a strapping table): levels=N gives N
    /// slabs between the mesh's extremes, step=h a level every h. check=True (the
    /// default) measures the checked solid, as `meshvol profile` does; check=False the
    /// surface as wound.
    ///
    /// units and density as the command's --units and --density ('mm:L' for a strapping
    /// table in litres; step is in the file's units). timings=True adds `timings`, as in
    /// mass_properties.
    #[pyo3(signature = (axis = "z", levels = None, step = None, check = true, units = None, density = None, timings = false))]
    #[allow(clippy::too_many_arguments)]
    fn profile(
        &self,
        py: Python<'_>,
        axis: &str,
        levels: Option<i64>,
        step: Option<f64>,
        check: bool,
        units: Option<&str>,
        density: Option<&Bound<'_, PyAny>>,
        timings: bool,
    ) -> PyResult<PyProfile> {
        properties::require_faces(&self.mesh)?;
        let options = crate::units::options(units, density)?;
        let clock = timings.then(crate::timings::Clock::new);
        let profile = self.with_subject(py, check, clock.as_ref(), |subject| {
            grid::profile(py, &subject, axis, levels, step, &options)
        })?;
        let profile = profile.timed(clock.map(|c| c.finish()))?;
        self.warn(py, profile.warnings())?;
        Ok(profile)
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
