//! `meshvol.intersection`: the overlap of two bodies, each placed by an optional rigid
//! pose (what `meshvol intersect` reports).

use crate::dict::Fields;
use crate::errors::{bad_argument, mesh_error};
use crate::load::{warn_for, MeshArg};
use meshvol::assembly::Affine;
use meshvol::overlap::Body;
use meshvol::Mesh;
use meshvol_report::intersect::{intersect_poses, intersect_prepared, rigid_pose, IntersectReport};
use meshvol_report::quantities::Quantities;
use meshvol_report::subject::Subject;
use meshvol_report::units::UnitOptions;
use numpy::ndarray::arr2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::prelude::*;

/// The intersection of two bodies A and B: the report of `meshvol intersect --json`,
/// whose keys are its attributes and the keys of to_dict(): lower <= |A∩B| <= upper
/// (volume the midpoint), volume_a, volume_b, union (with union_lower, union_upper),
/// a_minus_b, b_minus_a, iou (with iou_lower, iou_upper), dice, centroid and inertia of
/// A∩B (None without volume), the interface (contact_area, contact_vector,
/// contact_normal), disjoint, the grid's facts, warnings.
#[pyclass(module = "meshvol", name = "Intersection", frozen)]
pub struct PyIntersection {
    report: IntersectReport,
    fields: Fields,
}

#[pymethods]
impl PyIntersection {
    /// The centroid of A∩B, a float64 array of 3, or None.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    /// The inertia tensor of A∩B about its centroid for unit density, a float64 (3, 3)
    /// array, or None.
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.report.inertia.map(|m| arr2(&m).into_pyarray(py))
    }

    /// ∫ n dA over the part of B's surface inside A (n: B's outward normal): the rate of
    /// change of the overlap volume as B moves, a float64 array of 3, or None.
    #[getter]
    fn contact_vector<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.contact_vector.map(|c| PyArray1::from_slice(py, &c))
    }

    /// contact_vector scaled to length 1, or None where it is 0 or not known.
    #[getter]
    fn contact_normal<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.contact_normal.map(|c| PyArray1::from_slice(py, &c))
    }

    fn __repr__(&self) -> String {
        let r = &self.report;
        format!(
            "Intersection(lower={:?}, upper={:?}, iou={:?}, disjoint={})",
            r.interval.lower,
            r.interval.upper,
            r.iou,
            if r.disjoint { "True" } else { "False" }
        )
    }
}

/// `pose` (a 4×4 array-like, or None) as a rigid motion; ValueError naming `what` (the
/// argument) and why it is not one.
fn pose_of(pose: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Affine>> {
    let Some(pose) = pose.filter(|p| !p.is_none()) else { return Ok(None) };
    let (matrices, many) = matrices_of(pose, what)?;
    if many {
        return Err(bad_argument(format!(
            "{what} must be a 4×4 rigid transform; got {} of them (meshvol.intersections \
             takes many)",
            matrices.len()
        )));
    }
    rigid(&matrices[0], what).map(Some)
}

/// `poses` (None, one 4×4 array-like, or an (N, 4, 4) one) as rigid motions: `None`
/// for none, else one per pose; ValueError naming `what[k]` for a pose that is not one.
fn poses_of(poses: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<Vec<Affine>>> {
    let Some(poses) = poses.filter(|p| !p.is_none()) else { return Ok(None) };
    let (matrices, many) = matrices_of(poses, what)?;
    let name = |k: usize| if many { format!("{what}[{k}]") } else { what.to_string() };
    matrices.iter().enumerate().map(|(k, m)| rigid(m, &name(k))).collect::<PyResult<_>>().map(Some)
}

/// The 4×4 matrices in `value`, a (4, 4) or (N, 4, 4) array-like of numbers, and
/// whether it was the latter; ValueError naming `what` otherwise.
fn matrices_of(value: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<[[f64; 4]; 4]>, bool)> {
    let numpy = value.py().import("numpy")?;
    let array = numpy.call_method1("asarray", (value, "float64")).map_err(|e| {
        bad_argument(format!("{what} cannot be read as a 4×4 array of numbers: {e}"))
    })?;
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    let matrix = |rows: &[Vec<f64>]| -> [[f64; 4]; 4] {
        std::array::from_fn(|r| std::array::from_fn(|c| rows[r][c]))
    };
    match shape[..] {
        [4, 4] => {
            let rows: Vec<Vec<f64>> = array.call_method0("tolist")?.extract()?;
            Ok((vec![matrix(&rows)], false))
        }
        [_, 4, 4] => {
            let all: Vec<Vec<Vec<f64>>> = array.call_method0("tolist")?.extract()?;
            Ok((all.iter().map(|rows| matrix(rows)).collect(), true))
        }
        _ => {
            let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
            Err(bad_argument(format!(
                "{what} must be a 4×4 rigid transform (or, for many, an (N, 4, 4) array); got \
                 an array of shape ({})",
                dims.join(", ") + if shape.len() == 1 { "," } else { "" }
            )))
        }
    }
}

fn rigid(m: &[[f64; 4]; 4], what: &str) -> PyResult<Affine> {
    rigid_pose(m).map_err(|why| bad_argument(format!("{what} is not rigid: {why}")))
}

/// What intersection and intersections share once their own arguments are read: the
/// two bodies as given (read here from a path, or taken), their subjects and prepared
/// solids, `measure` run on them without the GIL, and its reports in `options`' units.
/// With `timings`, each check is run again and timed, then `measuring` starts.
fn measure_pair<'py, F>(
    py: Python<'py>,
    [a, b]: [&Bound<'py, PyAny>; 2],
    check: bool,
    timings: bool,
    options: &UnitOptions,
    measure: F,
) -> PyResult<Measured<'py>>
where
    F: Send + FnOnce(&Subject<'_, Mesh>, &Subject<'_, Mesh>, [Option<&Body>; 2]) -> Reports,
{
    let given = [MeshArg::of(a)?, MeshArg::of(b)?];
    let (a, b) = (&given[0].mesh, &given[1].mesh);
    let (mut sa, mut sb) = (a.get().subject(py, check)?, b.get().subject(py, check)?);
    let clock = timings.then(crate::timings::Clock::new);
    let timed = match (&clock, check) {
        (Some(c), true) => Some((a.get().timed_check(py, c)?, b.get().timed_check(py, c)?)),
        _ => None,
    };
    crate::timings::stage(clock.as_ref(), "measuring");
    if let Some((ca, cb)) = &timed {
        (sa.check, sb.check) = (Some(ca), Some(cb));
    }
    let bodies = [a.get().prepared(py, check)?, b.get().prepared(py, check)?];
    let reports = py.detach(|| measure(&sa, &sb, bodies)).map_err(mesh_error)?;
    let files = [(sa.source.name(), sa.source.unit), (sb.source.name(), sb.source.unit)];
    let reports = reports
        .into_iter()
        .map(|r| r.in_units(options, &files))
        .collect::<Result<Vec<_>, _>>()
        .map_err(mesh_error)?;
    Ok(Measured { reports, given, clock })
}

/// What `measure` gives [`measure_pair`]: one report a pose.
type Reports = Result<Vec<IntersectReport>, String>;

/// [`measure_pair`]'s answer: the reports, the meshes as given (whose warnings the caller
/// issues with the reports'), and the clock still running.
struct Measured<'py> {
    reports: Vec<IntersectReport>,
    given: [MeshArg<'py>; 2],
    clock: Option<crate::timings::Clock>,
}

/// The volume of the intersection of two bodies as a certified interval, with IoU,
/// Dice, the differences, and the centroid and inertia of the overlap, without a boolean
/// mesh (the report of `meshvol intersect`).
///
/// a and b are meshes (meshvol.Mesh, objects with .vertices and .faces such as
/// trimesh.Trimesh, or paths read as meshvol.load reads them), each one body (every
/// shell). pose_a and pose_b, when given, are
/// 4×4 rigid transforms (rotation and translation, last row 0 0 0 1) that place each
/// body: its checked solid, checked once and kept by the Mesh, is moved, so a loop over
/// poses checks nothing again. A pose that is not rigid (a scale, a shear, a mirror, a
/// non-finite entry, another shape) raises ValueError naming it. Refinement stops once
/// upper - lower <= tolerance * lower. timings=True adds `timings` (each check, run
/// again, then measuring). check=True (the default) measures each mesh's
/// checked solid; check=False the surfaces as wound. units and density as the command's
/// --units and --density.
#[pyfunction]
#[pyo3(signature = (a, b, pose_a = None, pose_b = None, tolerance = 1e-9, check = true, units = None, density = None, timings = false))]
#[allow(clippy::too_many_arguments)]
pub fn intersection(
    py: Python<'_>,
    a: &Bound<'_, PyAny>,
    b: &Bound<'_, PyAny>,
    pose_a: Option<&Bound<'_, PyAny>>,
    pose_b: Option<&Bound<'_, PyAny>>,
    tolerance: f64,
    check: bool,
    units: Option<&str>,
    density: Option<&Bound<'_, PyAny>>,
    timings: bool,
) -> PyResult<PyIntersection> {
    let options = crate::units::options(units, density)?;
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(bad_argument(format!("tolerance must be a positive number; got {tolerance}")));
    }
    let poses = [pose_of(pose_a, "pose_a")?, pose_of(pose_b, "pose_b")?];
    let Measured { mut reports, given, clock } =
        measure_pair(py, [a, b], check, timings, &options, |sa, sb, bodies| {
            intersect_prepared(sa, sb, bodies, poses, tolerance, &()).map(|r| vec![r])
        })?;
    let report = reports.remove(0); // one pose, one report
    warn_for(py, &given, &report.warnings)?;
    let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
    Ok(PyIntersection { fields, report })
}

/// The intersection of a and b for many poses at once, in parallel: a list of
/// Intersection, one per pose, each the one meshvol.intersection gives for that pose
/// alone (the same bits at any thread count).
///
/// poses_a and poses_b are each None (the body where it is), one 4×4 rigid transform
/// (used for every pose), or an (N, 4, 4) array of them; two arrays must have the same
/// N. Each mesh is checked once (the check the Mesh keeps) and its checked solid moved
/// by each pose; units and density as for intersection. A pose that is not rigid raises
/// ValueError naming it (poses_b[3]). The
/// check's warnings, and the intervals' (each once), are issued as MeshWarning.
/// timings=True gives each result the call's `timings`: each check (run again), then
/// measuring every pose (the same list on each).
#[pyfunction]
#[pyo3(signature = (a, b, poses_a = None, poses_b = None, tolerance = 1e-9, check = true, units = None, density = None, timings = false))]
#[allow(clippy::too_many_arguments)]
pub fn intersections(
    py: Python<'_>,
    a: &Bound<'_, PyAny>,
    b: &Bound<'_, PyAny>,
    poses_a: Option<&Bound<'_, PyAny>>,
    poses_b: Option<&Bound<'_, PyAny>>,
    tolerance: f64,
    check: bool,
    units: Option<&str>,
    density: Option<&Bound<'_, PyAny>>,
    timings: bool,
) -> PyResult<Vec<PyIntersection>> {
    let options = crate::units::options(units, density)?;
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(bad_argument(format!("tolerance must be a positive number; got {tolerance}")));
    }
    let (pa, pb) = (poses_of(poses_a, "poses_a")?, poses_of(poses_b, "poses_b")?);
    let count = |p: &Option<Vec<Affine>>| p.as_ref().map_or(1, Vec::len);
    let n = count(&pa).max(count(&pb));
    for (p, what) in [(&pa, "poses_a"), (&pb, "poses_b")] {
        if !matches!(count(p), 1) && count(p) != n {
            return Err(bad_argument(format!(
                "{what} holds {} poses and the other {n}: give one pose or the same number",
                count(p)
            )));
        }
    }
    let pick = |p: &Option<Vec<Affine>>, k: usize| p.as_ref().map(|v| v[k.min(v.len() - 1)]);
    let pairs: Vec<[Option<Affine>; 2]> = (0..n).map(|k| [pick(&pa, k), pick(&pb, k)]).collect();
    let Measured { reports, given, clock } =
        measure_pair(py, [a, b], check, timings, &options, |sa, sb, bodies| {
            intersect_poses(sa, sb, bodies, &pairs, tolerance)
        })?;
    let mut warnings: Vec<String> = Vec::new();
    for w in reports.iter().flat_map(|r| &r.warnings) {
        if !warnings.contains(w) {
            warnings.push(w.clone());
        }
    }
    warn_for(py, &given, &warnings)?;
    let stages = clock.map(|c| c.finish());
    reports
        .into_iter()
        .map(|report| {
            let fields = Fields::new(&report)?.with_timings(stages.clone())?;
            Ok(PyIntersection { fields, report })
        })
        .collect()
}

crate::dict::report_methods!(PyIntersection, "Intersection");
