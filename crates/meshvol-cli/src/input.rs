//! Reading the inputs: files, or `-` for standard input, with a progress bar on stderr
//! for large inputs.
//!
//! The bar shows only when stderr is a terminal, `--quiet` is not given, and the run
//! takes more than a moment: it appears once the command has run for [`DELAY`] (or
//! `MESHVOL_PROGRESS_DELAY_MS` milliseconds), whatever the size of its inputs, so a
//! quick run prints only its results and a long kernel on a small file still shows how
//! far it is. It counts the input bytes done and names the current file and stage;
//! warnings and results are printed around it. `--quiet` also silences warnings (errors
//! are always printed).
//!
//! While a kernel runs ([`Progress::kernel`]: the hull, the cell volumes, cut and fill,
//! the union, the check), its stages name the message and the bar shows how far through
//! the current stage it is (the kernel's own `advance`, per chunk of its work); the bytes
//! come back when it ends.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use meshvol_io::{Loaded, PointCloud, PolygonFile};
use meshvol_report::timings::{Running, StageTiming};

/// How long a run goes before its bar appears, unless `MESHVOL_PROGRESS_DELAY_MS` says.
const DELAY: Duration = Duration::from_secs(1);

/// The path that means standard input.
pub fn is_stdin(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// All of standard input, up to the stream limit (`MESHVOL_MAX_STREAM_BYTES`): an
/// endless input is an error, not a process that fills memory.
fn stdin_bytes() -> Result<Vec<u8>, String> {
    meshvol_io::read_stream(std::io::stdin().lock())
        .map_err(|e| format!("-: cannot read standard input: {e}"))
}

/// Reads a mesh from a file, or from standard input for `-` (all of it, then the format
/// from its content). A file whose reading (and, if `checked`, checking) would not fit
/// in the memory available is refused before it is parsed ([`meshvol_io::memory`]).
pub fn load(path: &Path, checked: bool) -> Result<Loaded, String> {
    let limits = meshvol_io::Limits { checked, ..meshvol_io::Limits::from_env() };
    let read = if is_stdin(path) {
        meshvol_io::read_bytes_within(path, stdin_bytes()?, &limits)
    } else {
        meshvol_io::read_file_within(path, &limits)
    };
    read.map_err(|e| e.to_string())
}

/// Reads polygons from a file, or from standard input for `-`.
pub fn load_polygons(path: &Path) -> Result<PolygonFile, String> {
    if is_stdin(path) {
        return meshvol_io::read_polygons_bytes(path, &stdin_bytes()?).map_err(|e| e.to_string());
    }
    meshvol_io::read_polygons(path).map_err(|e| e.to_string())
}

/// Reads points from a file, or from standard input for `-`.
pub fn load_points(path: &Path) -> Result<PointCloud, String> {
    if is_stdin(path) {
        return meshvol_io::read_points_bytes(path, stdin_bytes()?).map_err(|e| e.to_string());
    }
    meshvol_io::read_points(path).map_err(|e| e.to_string())
}

/// Whether stage timings are recorded (`--timings`): set once by `main`.
pub static TIMINGS: AtomicBool = AtomicBool::new(false);

/// Progress on stderr, and the warnings printed around it.
pub struct Progress {
    /// The bar, drawn to nothing until [`DELAY`] has passed.
    bar: Option<ProgressBar>,
    /// Whether the bar is finished: held while the bar is shown, so a bar finished
    /// just as its delay ends is never drawn again.
    finished: Arc<Mutex<bool>>,
    quiet: bool,
    /// With `--timings`: the stages of the current input.
    clock: Option<Mutex<Clock>>,
}

/// The stages of one input as they pass: every stage a command or kernel names ends
/// the one before it.
struct Clock {
    done: Vec<StageTiming>,
    current: Option<Running>,
}

impl Clock {
    fn close(&mut self) {
        if let Some(stage) = self.current.take() {
            self.done.push(stage.finish());
        }
    }

    fn start(&mut self, stage: &str) {
        self.close();
        self.current = Some(Running::start(stage));
    }
}

impl Progress {
    pub fn new(paths: &[PathBuf], quiet: bool) -> Progress {
        let total: u64 =
            paths.iter().filter_map(|p| std::fs::metadata(p).ok()).map(|m| m.len()).sum();
        let finished = Arc::new(Mutex::new(false));
        let show = !quiet && std::io::stderr().is_terminal();
        let bar = show.then(|| {
            let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
            bar.set_style(style(BYTES));
            show_after(delay(), bar.clone(), Arc::clone(&finished));
            bar
        });
        let clock = TIMINGS
            .load(Ordering::Relaxed)
            .then(|| Mutex::new(Clock { done: Vec::new(), current: None }));
        Progress { bar, finished, quiet, clock }
    }

    /// Says what is being done to which file.
    pub fn stage(&self, what: &str, path: &Path) {
        self.time(what);
        if let Some(bar) = &self.bar {
            bar.set_message(format!("{what} {}", path.display()));
        }
    }

    /// Says what is being done to all the inputs together.
    pub fn stage_all(&self, what: &str) {
        self.time(what);
        if let Some(bar) = &self.bar {
            bar.set_message(what.to_string());
        }
    }

    /// With `--timings`, ends the current stage and starts `stage`.
    fn time(&self, stage: &str) {
        if let Some(clock) = &self.clock {
            clock.lock().unwrap_or_else(|e| e.into_inner()).start(stage);
        }
    }

    /// With `--timings`, the stages of the input just measured (the last ending now),
    /// and a fresh start for the next; `None` without.
    pub fn take_timings(&self) -> Option<Vec<StageTiming>> {
        let clock = self.clock.as_ref()?;
        let mut clock = clock.lock().unwrap_or_else(|e| e.into_inner());
        clock.close();
        Some(std::mem::take(&mut clock.done))
    }

    /// Counts a file as done.
    pub fn done(&self, path: &Path) {
        if let Some(bar) = &self.bar {
            bar.inc(std::fs::metadata(path).map_or(0, |m| m.len()));
        }
    }

    /// Runs `f` (which prints) with the bar hidden.
    pub fn suspend<T>(&self, f: impl FnOnce() -> T) -> T {
        match &self.bar {
            Some(bar) => bar.suspend(f),
            None => f(),
        }
    }

    /// Prints a warning about `name`, unless quiet.
    pub fn warn(&self, name: &str, warning: &str) {
        if !self.quiet {
            self.suspend(|| eprintln!("meshvol: warning: {name}: {warning}"));
        }
    }

    /// Prints an error.
    pub fn error(&self, error: &str) {
        self.suspend(|| eprintln!("meshvol: error: {error}"));
    }

    /// The core's progress hook for a kernel doing `what` (`"computing the hull of
    /// x.ply"`): its stages follow `what` in the message, and its advances fill the bar.
    pub fn kernel(&self, what: String) -> Kernel<'_> {
        let saved = self.bar.as_ref().map_or((0, None), |bar| (bar.position(), bar.length()));
        if let Some(bar) = &self.bar {
            bar.set_message(what.clone());
        }
        Kernel { progress: self, what, saved, counting: AtomicBool::new(false) }
    }

    /// Clears the bar; warnings still print after it.
    pub fn finish(&self) {
        if let Some(bar) = &self.bar {
            // A poisoned lock (a panic while showing the bar) still finishes it.
            let mut finished = self.finished.lock().unwrap_or_else(|e| e.into_inner());
            *finished = true;
            bar.finish_and_clear();
        }
    }
}

/// The delay before the bar appears: `MESHVOL_PROGRESS_DELAY_MS` when it is a number of
/// milliseconds, [`DELAY`] otherwise.
fn delay() -> Duration {
    std::env::var("MESHVOL_PROGRESS_DELAY_MS")
        .ok()
        .and_then(|ms| ms.trim().parse().ok())
        .map_or(DELAY, Duration::from_millis)
}

/// Draws `bar` on stderr after `delay`, unless it is finished by then. The waiting
/// thread is not joined: a run that ends first simply ends. A system that cannot start
/// the thread gets no bar, not a failed run.
fn show_after(delay: Duration, bar: ProgressBar, finished: Arc<Mutex<bool>>) {
    let _ = std::thread::Builder::new().name("progress".into()).spawn(move || {
        std::thread::sleep(delay);
        let finished = finished.lock().unwrap_or_else(|e| e.into_inner());
        if !*finished {
            bar.set_draw_target(ProgressDrawTarget::stderr());
            bar.enable_steady_tick(Duration::from_millis(120));
        }
    });
}

/// The bar's template while reading (bytes) and while a kernel runs (its fraction).
const BYTES: &str = "{spinner} [{elapsed_precise}] {bar:30} {bytes}/{total_bytes} {wide_msg}";
const FRACTION: &str = "{spinner} [{elapsed_precise}] {bar:30} {percent:>3}% {wide_msg}";

fn style(template: &str) -> ProgressStyle {
    ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar())
}

/// A kernel's progress on the bar ([`Progress::kernel`]).
pub struct Kernel<'a> {
    progress: &'a Progress,
    what: String,
    /// The bar's byte count and total before the kernel, put back after it.
    saved: (u64, Option<u64>),
    /// Whether the bar counts the kernel's units (since its first advance).
    counting: AtomicBool,
}

impl meshvol::progress::Progress for Kernel<'_> {
    fn stage(&self, name: &'static str) {
        self.progress.time(name);
        if let Some(bar) = &self.progress.bar {
            bar.set_message(format!("{}: {name}", self.what));
        }
    }

    fn advance(&self, done: u64, total: u64) {
        if let Some(bar) = &self.progress.bar {
            if !self.counting.swap(true, Ordering::Relaxed) {
                bar.set_style(style(FRACTION));
            }
            bar.set_length(total.max(1));
            bar.set_position(done);
        }
    }
}

impl Drop for Kernel<'_> {
    fn drop(&mut self) {
        if let (Some(bar), true) = (&self.progress.bar, *self.counting.get_mut()) {
            bar.set_style(style(BYTES));
            if let Some(total) = self.saved.1 {
                bar.set_length(total);
            }
            bar.set_position(self.saved.0);
        }
    }
}
