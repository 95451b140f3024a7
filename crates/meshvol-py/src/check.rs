//! `meshvol.Check`: the facts `meshvol check` reports.

use crate::dict::Fields;
use crate::errors::{bad_argument, mesh_error};
use crate::mesh::PyMesh;
use crate::properties::{self, PyMassProperties};
use crate::shell::PyShell;
use meshvol::topology::{Check, CheckOptions, Weld};
use meshvol_report::check::CheckReport;
use meshvol_report::quantities::Quantities;
use pyo3::prelude::*;

/// Can the volume be trusted? The report of `meshvol check`, whose keys are its
/// attributes and the keys of to_dict(): closed, manifold, winding, shells and
/// cavities, overlaps, self-intersections, and the volume of the solid the surface most
/// plausibly bounds.
///
/// bounds_a_volume is True when the surface is closed, manifold, orientable and free of
/// crossings; verdict says the most important fact in one line. orientation is
/// 'outward', 'inward' or 'mixed' (None without shells) and winding 'ccw' or 'cw' (None
/// when mixed). solid_volume is the solid's volume: shells turned outward, cavities
/// subtracted, degenerate and duplicate faces dropped, holes capped (volume_uncertainty
/// says how far the caps could be off).
#[pyclass(module = "meshvol", name = "Check", frozen)]
pub struct PyCheck {
    report: CheckReport,
    fields: Fields,
    check: Check,
    mesh: Py<PyMesh>,
}

/// Checks `mesh` with the GIL released.
pub fn check(
    mesh: &Bound<'_, PyMesh>,
    weld_tolerance: Option<f64>,
    intersections: bool,
    units: &meshvol_report::units::UnitOptions,
    timings: bool,
) -> PyResult<PyCheck> {
    let weld = match weld_tolerance {
        None => Weld::Auto,
        Some(t) if !(t.is_finite() && t >= 0.0) => {
            return Err(bad_argument(format!(
                "weld_tolerance must be a non-negative number or None; got {t}"
            )));
        }
        Some(0.0) => Weld::Exact,
        Some(t) => Weld::Tolerance(t),
    };
    let options = CheckOptions { weld, intersections, ..CheckOptions::default() };
    let m = mesh.get();
    let clock = timings.then(crate::timings::Clock::new);
    crate::timings::stage(clock.as_ref(), "checking");
    let c = mesh
        .py()
        .detach(|| match &clock {
            Some(clock) => {
                let (assembly, bodies) = (m.assembly.as_deref(), m.source.body_faces());
                meshvol::topology::check_assembled(&m.mesh, assembly, &bodies, &options, clock)
            }
            None => m.check_with(&options),
        })
        .map_err(mesh_error)?;
    crate::timings::stage(clock.as_ref(), "reporting");
    let report = meshvol_report::check::check(&m.source, &c)
        .in_units(units, m.source.unit)
        .map_err(mesh_error)?;
    let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
    Ok(PyCheck { fields, report, check: c, mesh: mesh.clone().unbind() })
}

#[pymethods]
impl PyCheck {
    /// Each shell's facts, as Shell objects.
    #[getter]
    fn shell_details(&self) -> PyResult<Vec<PyShell>> {
        self.report.facts.shell_details.iter().map(PyShell::new).collect()
    }

    /// Pairs of shells whose surfaces cross, as (i, j) tuples with i < j.
    #[getter]
    fn overlapping_shells(&self) -> Vec<(usize, usize)> {
        self.report.facts.overlapping_shells.iter().map(|&[a, b]| (a, b)).collect()
    }

    /// A few crossing face pairs, as (face, face) tuples.
    #[getter]
    fn intersection_examples(&self) -> Vec<(usize, usize)> {
        self.report.facts.intersection_examples.iter().map(|&[a, b]| (a, b)).collect()
    }

    /// Mass properties of the solid this check found, as Mesh.mass_properties() gives
    /// them by default (`meshvol volume` with this check's options): shells turned
    /// outward, cavities subtracted, degenerate and duplicate faces dropped, holes capped;
    /// signed_volume, faces and triangles are the surface's as wound, and warnings say
    /// why the solid may not be the one meant. timings=True adds `timings`: one stage,
    /// `measuring` (the check is this one, not run again).
    #[pyo3(signature = (density = None, exact = false, units = None, timings = false), text_signature = "(self, density=1.0, exact=False, units=None, timings=False)")]
    fn mass_properties(
        &self,
        py: Python<'_>,
        density: Option<&Bound<'_, PyAny>>,
        exact: bool,
        units: Option<&str>,
        timings: bool,
    ) -> PyResult<PyMassProperties> {
        let clock = timings.then(crate::timings::Clock::new);
        crate::timings::stage(clock.as_ref(), "measuring");
        let measured =
            properties::measure(py, self.mesh.get(), Some(&self.check), density, exact, units)?;
        measured.timed(clock.map(|c| c.finish()))
    }

    /// The repaired solid as a new welded Mesh (what `meshvol repair` writes): shells
    /// turned outward (cavities inward), degenerate and duplicate faces dropped, and
    /// with caps=True, holes capped with fans of triangles.
    #[pyo3(signature = (caps = false))]
    fn solid_mesh(&self, py: Python<'_>, caps: bool) -> PyMesh {
        PyMesh::from(py.detach(|| self.check.solid_mesh(caps)))
    }

    /// (faces flipped, faces dropped, cap triangles added) by the repair.
    #[getter]
    fn repairs(&self) -> (usize, usize, usize) {
        self.check.repairs()
    }

    fn __repr__(&self) -> String {
        format!("Check('{}')", self.report.facts.verdict)
    }
}

crate::dict::report_methods!(PyCheck, "Check");
