//! `meshvol.measure`'s native part: the paths expanded into files by the command's own
//! walk (`meshvol_io::walk`: folders, patterns, `--glob`), then many files measured at
//! once, the files spread over a rayon pool with the GIL released, each file's
//! `meshvol volume --json` line (or `{"file", "error"}`) returned in the input's order.

use crate::errors::bad_argument;
use crate::timings::Clock;
use meshvol::topology::CheckOptions;
use meshvol_io::walk::{Filter, Walk};
use meshvol_io::InputKind;
use meshvol_report::checked::{refuse_empty, Checked};
use meshvol_report::timings::with_timings;
use meshvol_report::units::UnitsArg;
use meshvol_report::volume::{volume, VolumeOptions};
use meshvol_report::{error_line, json_line};
use pyo3::prelude::*;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// One file's line, as `meshvol volume --json FILE` prints it (the same reading, check
/// and report: the CLI's `solid::read` then `volume`); with `timings`, as `--timings`
/// adds them: the stages reading, checking (and the check's own), measuring.
fn measure_one(path: &Path, check: bool, options: &VolumeOptions, timings: bool) -> String {
    let name = path.display().to_string();
    let clock = timings.then(Clock::new);
    let report = (|| -> Result<String, String> {
        crate::timings::stage(clock.as_ref(), "reading");
        // Within the memory of the reading, and of the check only where one follows.
        let limits = meshvol_io::Limits { checked: check, ..meshvol_io::Limits::from_env() };
        let loaded = meshvol_io::read_file_within(path, &limits).map_err(|e| e.to_string())?;
        refuse_empty(&name, &loaded)?;
        let check_with = check.then(CheckOptions::default);
        if check {
            crate::timings::stage(clock.as_ref(), "checking");
        }
        let stages: &dyn meshvol::progress::Progress = match &clock {
            Some(clock) => clock,
            None => &(),
        };
        let checked =
            Checked::of(&name, loaded, check_with.as_ref(), stages).map_err(|e| e.to_string())?;
        crate::timings::stage(clock.as_ref(), "measuring");
        let subject = checked.subject();
        let line = json_line(&volume(&subject, options)?)?;
        match &clock {
            Some(clock) => with_timings(&line, &clock.finish()),
            None => Ok(line),
        }
    })();
    match report {
        Ok(line) => line,
        Err(e) => error_line(&name, &e),
    }
}

/// Each file's JSON line, in order: files measured `workers` at a time (None: one per
/// core; at most one a file and 8 a core), on the threads of a rayon pool, the GIL
/// released throughout. With `timings`, each line has the command's `timings` list (an
/// error line has none, as the command's).
#[pyfunction]
#[pyo3(signature = (paths, workers = None, check = true, density = None, units = None, exact = false, timings = false), text_signature = "(paths, workers=None, check=True, density=1.0, units=None, exact=False, timings=False)")]
#[allow(clippy::too_many_arguments)]
pub fn _measure_files(
    py: Python<'_>,
    paths: Vec<PathBuf>,
    workers: Option<usize>,
    check: bool,
    density: Option<&Bound<'_, PyAny>>,
    units: Option<&str>,
    exact: bool,
    timings: bool,
) -> PyResult<Vec<String>> {
    let density = crate::units::density_or_one(density)?;
    let units = units.map(str::parse::<UnitsArg>).transpose().map_err(bad_argument)?;
    let options = VolumeOptions { density, units, exact };
    if workers == Some(0) {
        return Err(bad_argument("workers must be at least 1 (or None: one per core)"));
    }
    let run = || -> Vec<String> {
        paths.par_iter().map(|p| measure_one(p, check, &options, timings)).collect()
    };
    // Threads are OS threads: at most one a file and 8 a core (workers=10**6 must not
    // start a million).
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let workers = workers.map(|n| n.min(paths.len().max(1)).min(8 * cores));
    py.detach(|| match workers {
        None => Ok(run()),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(|pool| pool.install(run))
            .map_err(|e| e.to_string()),
    })
    .map_err(crate::errors::mesh_error)
}

/// The files to measure, and each folder or pattern that gave none with its error.
type Expanded = (Vec<PathBuf>, Vec<(String, String)>);

/// The files `paths` stands for, as `meshvol volume` reads its arguments (with
/// `--recursive` when `recursive`, and a `--glob` for each of `globs`), and the folders
/// and patterns that gave none, with the command's error for each. A path that names
/// nothing but holds `*`, `?` or `[` is a pattern, as Python's `glob` expands it (the
/// shell does for the command). A malformed glob is a `ValueError`.
#[pyfunction]
#[pyo3(signature = (paths, recursive = true, globs = Vec::new()))]
pub fn _expand(
    py: Python<'_>,
    paths: Vec<PathBuf>,
    recursive: bool,
    globs: Vec<String>,
) -> PyResult<Expanded> {
    let filters = globs
        .iter()
        .map(|g| Filter::parse(g).map_err(|e| bad_argument(format!("glob {e}"))))
        .collect::<PyResult<Vec<_>>>()?;
    let walk = Walk { recursive, filters, patterns: true };
    let inputs = py.detach(|| walk.expand(&paths, InputKind::Mesh));
    Ok((inputs.files, inputs.problems))
}

/// The endings of the file names a folder is searched for (`.stl`, ..., `.stl.gz`, ...,
/// `.zip`), lower case: `meshvol_io`'s one rule, for Python's `MESH_EXTENSIONS`.
#[pyfunction]
pub fn _mesh_name_endings() -> Vec<String> {
    InputKind::Mesh.name_endings()
}
