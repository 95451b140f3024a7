//! `meshvol check`: can the volume be trusted? Exits 1 when a file does not bound a
//! volume.

use crate::driver;
use crate::input;
use clap::Args;
use meshvol_report::check::{check, CheckReport};
use meshvol_report::checked::check_loaded;
use meshvol_report::quantities::Quantities;
use meshvol_report::subject::Source;
use meshvol_report::units::UnitOptions;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args)]
pub struct CheckArgs {
    /// Mesh files (or those compressed: .gz, .bz2, .zst, a .zip of one), or folders of
    /// them.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    #[command(flatten)]
    output: driver::OutputArgs,
    /// Skip the search for crossing triangles (self-intersections; overlapping shells
    /// are then found only by the ray tests).
    #[arg(long)]
    no_intersections: bool,
    /// Weld vertices whose coordinates differ by at most T; 0 welds exactly equal
    /// positions only. Default: exactly, and when that leaves holes, again within 1e-9 of
    /// the bounding box diagonal (reported as `weld_tolerance`).
    #[arg(long, value_name = "T", value_parser = crate::numbers::non_negative_finite, allow_hyphen_values = true)]
    weld_tolerance: Option<f64>,
    #[command(flatten)]
    units: crate::units::UnitArgs,
    /// Also write the report as one self-contained web page (report, 3D view with the
    /// problems drawn, geometry inlined) to HTML, for one FILE: to attach to an email
    /// or a ticket.
    #[arg(long, value_name = "HTML")]
    html: Option<PathBuf>,
}

/// Runs the command. A file without faces is checked too: it bounds nothing.
pub fn run(args: CheckArgs, quiet: bool) -> ExitCode {
    let options = crate::solid::check_options(args.weld_tolerance, !args.no_intersections);
    let inputs = args.walk.expand(&args.files, meshvol_io::InputKind::Mesh);
    let output = args.output.output(quiet);
    if args.html.is_some() && (inputs.files.len() != 1 || !inputs.problems.is_empty()) {
        eprintln!(
            "meshvol: error: --html writes the page of one file; {} given",
            inputs.files.len() + inputs.problems.len()
        );
        return ExitCode::from(2);
    }
    driver::each(&inputs, output, |path, progress| {
        let name = path.display().to_string();
        progress.stage("reading", path);
        let loaded = input::load(path, true)?;
        progress.stage("checking", path);
        let kernel = progress.kernel(format!("checking {name}"));
        let c = check_loaded(&name, &loaded, &options, &kernel).map_err(|e| e.to_string())?;
        let source = Source::of(&name, &loaded);
        let report = check(&source, &c).in_units(&args.units.options(), loaded.unit)?;
        if let Some(html) = &args.html {
            progress.stage("writing the page", path);
            write_page(html, &source, &loaded.surface, &c, &report, &args.units.options())?;
        }
        Ok(report)
    })
}

/// Writes the self-contained page of one checked file to `html`.
fn write_page<S: meshvol::Surface>(
    html: &Path,
    source: &Source,
    surface: &S,
    c: &meshvol::topology::Check,
    report: &CheckReport,
    units: &UnitOptions,
) -> Result<(), String> {
    let page = meshvol_serve::page_content(source, surface, c, report.clone(), units)?;
    let content = serde_json::to_string(&page).map_err(|e| e.to_string())?;
    std::fs::write(html, meshvol_serve::standalone(&content))
        .map_err(|e| format!("{}: cannot write the page: {e}", html.display()))
}
