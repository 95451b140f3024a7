//! What `meshvol.Mesh` measures: its mass properties, check, grid, cut cells and
//! profile, each the command's report through the report layer. A second `#[pymethods]`
//! block of `Mesh`, so that `mesh.rs` (the class, its arrays and its checked solid)
//! imports none of the result classes that hold a Mesh.

use crate::check::{self, PyCheck};
use crate::grid::{self, PyProfile};
use crate::mesh::PyMesh;
use crate::properties::{self, PyMassProperties};
use pyo3::prelude::*;

#[pymethods]
impl PyMesh {
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
    /// backend as Mesh.grid's: on an OpenCL device the sweeps and each column's sums run
    /// there and the x and y apertures on the CPU, the same bits; second_moments and
    /// face_centroids run on the CPU only ('opencl' is refused for them, 'auto' takes
    /// the CPU).
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
        let on = grid::backend(backend, opencl_device)?;
        if second_moments || face_centroids {
            on.cpu_only(
                "second_moments=True and face_centroids=True",
                "leave backend='auto' or give 'cpu'",
            )
            .map_err(crate::errors::bad_argument)?;
        }
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
        grid::cut_cells(py, &measured, place, extras, &scale, &on)
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
}
