//! `meshvol check`: can the volume be trusted? Exits 1 when a file does not bound a
//! volume.

use crate::driver::{self, Output};
use crate::input;
use clap::Args;
use meshvol_report::check::check;
use meshvol_report::subject::Source;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct CheckArgs {
    /// Mesh files (or those compressed: .gz, .bz2, .zst, a .zip of one), or folders of
    /// them.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// Print one JSON object per file, one per line (`--format json`).
    #[arg(long, conflicts_with = "format")]
    json: bool,
    /// What to print: `text` (the default), `json` (one object per file), or `csv` (one
    /// table: a header, then a row per file, the JSON keys as columns).
    #[arg(long, value_enum)]
    format: Option<driver::Format>,
    /// Skip the search for crossing triangles (self-intersections; overlapping shells
    /// are then found only by the ray tests).
    #[arg(long)]
    no_intersections: bool,
    /// Weld vertices whose coordinates differ by at most T; 0 welds exactly equal
    /// positions only. Default: exactly, and when that leaves holes, again within 1e-9 of
    /// the bounding box diagonal (reported as `weld_tolerance`).
    #[arg(long, value_name = "T", value_parser = crate::non_negative_finite, allow_hyphen_values = true)]
    weld_tolerance: Option<f64>,
    #[command(flatten)]
    units: crate::units::UnitArgs,
}

/// Runs the command. A file without faces is checked too: it bounds nothing.
pub fn run(args: CheckArgs, quiet: bool) -> ExitCode {
    let options = crate::solid::check_options(args.weld_tolerance, !args.no_intersections);
    let inputs = args.walk.expand(&args.files, meshvol_io::InputKind::Mesh);
    let output = Output::of(args.json, args.format, quiet);
    driver::each(&inputs, output, |path, progress| {
        let name = path.display().to_string();
        progress.stage("reading", path);
        let loaded = input::load(path)?;
        progress.stage("checking", path);
        let c = meshvol::topology::check_assembled(
            &loaded.surface,
            loaded.assembly.as_ref(),
            &options,
            &progress.kernel(format!("checking {}", path.display())),
        )
        .map_err(|e| format!("{name}: {e}"))?;
        check(&Source::of(&name, &loaded), &c).in_units(&args.units.options(), loaded.unit)
    })
}
