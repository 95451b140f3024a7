//! The one loop every command runs: for each input, measure it and print its report.
//!
//! It owns what is the same for every command: the progress bar, warnings on stderr
//! (silenced by `--quiet`), the report as text or one JSON line on stdout, a failed input
//! as an error on stderr and, under `--json`, a `{"file": ..., "error": ...}` line on
//! stdout, a closed stdout (piped into `head`) ending the run quietly, and the exit
//! status: 0 when every input was measured and passed, 1 otherwise. With `--format csv`
//! the reports (and failed inputs, with an `error` column) are rows of one table, printed
//! when the run ends: its header is the union of the rows' columns.

use crate::input::Progress;
use crate::walk::Inputs;
use meshvol_report::table::Table;
use meshvol_report::timings::{self, StageTiming};
use meshvol_report::{error_line, json_line, Report};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// How reports are printed.
#[derive(Clone, Copy, Debug)]
pub struct Output {
    pub json: bool,
    pub quiet: bool,
    /// One CSV table for the run (`--format csv`), printed at its end.
    pub csv: bool,
}

/// `--format` of the commands that print text, JSON lines or one CSV table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    Text,
    Json,
    Csv,
}

/// `--json` and `--format`, for the commands that print text, JSON lines or one CSV
/// table.
#[derive(clap::Args, Clone, Copy, Debug)]
pub struct OutputArgs {
    /// Print one JSON object per file (`intersect`: per pair), one per line (`--format
    /// json`; the keys: docs/json.md).
    #[arg(long, conflicts_with = "format")]
    pub json: bool,
    /// What to print: `text` (the default), `json` (one object per file or pair), or
    /// `csv` (one table: a header, then a row per file or pair, the JSON keys as columns).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
}

/// The flags of the commands that measure each input's solid and print a report of it
/// (`below`, `intersect`), after their own: how to print, the units, the check.
#[derive(clap::Args)]
pub struct SolidReportArgs {
    #[command(flatten)]
    pub output: OutputArgs,
    #[command(flatten)]
    pub units: crate::units::UnitArgs,
    #[command(flatten)]
    pub solid: crate::solid::SolidArgs,
}

impl OutputArgs {
    /// The output these flags ask for.
    pub fn output(&self, quiet: bool) -> Output {
        Output::of(self.json, self.format, quiet)
    }
}

impl Output {
    /// The output `--json` or `--format` asks for.
    pub fn of(json: bool, format: Option<Format>, quiet: bool) -> Output {
        let json = json || format == Some(Format::Json);
        Output { json, quiet, csv: format == Some(Format::Csv) }
    }
}

/// Prints reports and errors, and remembers what decides the exit status.
pub struct Driver {
    pub progress: Progress,
    output: Output,
    failed: bool,
    /// stdout was closed: nothing more is printed.
    closed: bool,
    /// With `--format csv`: the rows so far.
    table: Option<Table>,
}

impl Driver {
    /// A driver for `inputs` (their sizes set the progress bar).
    pub fn new(inputs: &[PathBuf], output: Output) -> Driver {
        Driver {
            progress: Progress::new(inputs, output.quiet),
            output,
            failed: false,
            closed: false,
            table: output.csv.then(Table::new),
        }
    }

    /// Prints `report`: its warnings on stderr, then its text or JSON line (with
    /// `--timings`, the stages' timings as the JSON's `timings` list, or on stderr).
    pub fn report(&mut self, report: &impl Report) {
        let timings = self.progress.take_timings();
        let body = if self.output.json || self.output.csv {
            json_line(report).and_then(|line| match &timings {
                Some(t) => timings::with_timings(&line, t),
                None => Ok(line),
            })
        } else {
            self.print_timings(report.file(), timings.as_deref());
            Ok(report.text())
        };
        match body {
            Ok(body) if self.table.is_some() => self.row(report, &body),
            Ok(body) => self.show(report, &body),
            Err(e) => self.fail(report.file(), &e),
        }
    }

    /// With `--format csv`: `report`'s warnings, and its JSON line as a row.
    fn row(&mut self, report: &impl Report, line: &str) {
        for w in report.warnings() {
            self.progress.warn(report.file(), w);
        }
        self.failed |= !report.passed();
        match serde_json::from_str::<serde_json::Value>(line) {
            Ok(value) => self.table.get_or_insert_with(Table::new).push(&value),
            Err(e) => self.fail(report.file(), &format!("{}: {e}", report.file())),
        }
    }

    /// Prints `report`'s warnings, then `body` (the report in a form of the command's
    /// own: CSV, WKT, GeoJSON), and with `--timings` the stages' timings on stderr.
    pub fn print(&mut self, report: &impl Report, body: &str) {
        let timings = self.progress.take_timings();
        self.print_timings(report.file(), timings.as_deref());
        self.show(report, body);
    }

    fn print_timings(&self, file: &str, timings: Option<&[StageTiming]>) {
        if let Some(t) = timings {
            let text = timings::text(file, t);
            self.progress.suspend(|| eprint!("{text}"));
        }
    }

    fn show(&mut self, report: &impl Report, body: &str) {
        for w in report.warnings() {
            self.progress.warn(report.file(), w);
        }
        self.failed |= !report.passed();
        self.emit(body);
    }

    /// Reports that `file` failed with `error` (which names the file).
    pub fn fail(&mut self, file: &str, error: &str) {
        // The failed input's stages are not reported; the next input starts afresh.
        let _ = self.progress.take_timings();
        self.failed = true;
        self.progress.error(error);
        if let Some(table) = &mut self.table {
            if let Ok(value) = serde_json::from_str(&error_line(file, error)) {
                table.push(&value);
            }
        } else if self.output.json {
            self.emit(&error_line(file, error));
        }
    }

    fn emit(&mut self, text: &str) {
        if self.closed {
            return;
        }
        let written = self.progress.suspend(|| {
            let mut stdout = std::io::stdout().lock();
            stdout.write_all(text.as_bytes()).and_then(|()| stdout.flush())
        });
        self.closed = written.is_err();
    }

    /// Whether stdout was closed (the rest of the run can be skipped).
    pub fn closed(&self) -> bool {
        self.closed
    }

    /// Clears the progress bar and gives the exit status.
    pub fn finish(mut self) -> ExitCode {
        if let Some(table) = self.table.take() {
            self.emit(&table.to_csv());
        }
        self.progress.finish();
        if self.failed {
            ExitCode::FAILURE
        } else {
            ExitCode::SUCCESS
        }
    }
}

/// A driver for `inputs`, which has reported the folders that held no input.
pub fn start(inputs: &Inputs, output: Output) -> Driver {
    let mut driver = Driver::new(&inputs.files, output);
    for (name, error) in &inputs.problems {
        driver.fail(name, error);
    }
    driver
}

/// Runs `measure` on each input in turn and prints what it gives.
pub fn each<R: Report>(
    inputs: &Inputs,
    output: Output,
    mut measure: impl FnMut(&Path, &Progress) -> Result<R, String>,
) -> ExitCode {
    let mut driver = start(inputs, output);
    for path in &inputs.files {
        if driver.closed() {
            break;
        }
        let result = measure(path, &driver.progress);
        driver.progress.done(path);
        match result {
            Ok(report) => driver.report(&report),
            Err(e) => driver.fail(&path.display().to_string(), &e),
        }
    }
    driver.finish()
}

/// Runs `measure` once over all `inputs` (a grid, a union) and prints its report; not at
/// all when a folder given held no input (the result would leave it out).
pub fn once<R: Report>(
    inputs: &Inputs,
    output: Output,
    measure: impl FnOnce(&Progress) -> Result<R, String>,
) -> ExitCode {
    let mut driver = start(inputs, output);
    if !inputs.problems.is_empty() {
        return driver.finish();
    }
    let inputs = &inputs.files;
    match measure(&driver.progress) {
        Ok(report) => driver.report(&report),
        Err(e) => {
            let names: Vec<String> = inputs.iter().map(|p| p.display().to_string()).collect();
            // Every error names the input: a reader's does, a kernel's (a grid too
            // large, an overflow) is given the names here.
            let e = if names.iter().any(|n| e.starts_with(n.as_str())) {
                e
            } else {
                format!("{}: {e}", names.join(", "))
            };
            driver.fail(&names.join(", "), &e)
        }
    }
    driver.finish()
}
