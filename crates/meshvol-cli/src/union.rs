//! `meshvol union`: the volume of the union of several closed bodies (files, or the
//! shells of one file) as a certified interval, without a boolean mesh.

use crate::input;
use crate::solid::{self, SolidArgs};
use clap::Args;
use meshvol::grid::union;
use serde::Serialize;
use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args)]
pub struct UnionArgs {
    /// Mesh files: each is one body; a single file's shells are the bodies.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Stop refining once (upper − lower) ≤ REL · lower.
    #[arg(long, value_name = "REL", default_value_t = 1e-6, value_parser = crate::positive_finite)]
    tolerance: f64,
    /// Print one JSON object: lower, upper, volume, bodies, sum_of_volumes, cells_refined,
    /// cells_resolved_exactly, volume_uncertainty, warnings.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    solid: SolidArgs,
}

/// The JSON report: exactly these keys.
#[derive(Serialize)]
struct UnionReport {
    lower: f64,
    upper: f64,
    volume: f64,
    bodies: usize,
    sum_of_volumes: f64,
    cells_refined: usize,
    cells_resolved_exactly: usize,
    /// How far the caps on the bodies' holes could put the volume off; the interval is
    /// widened by it (0 for closed bodies).
    volume_uncertainty: f64,
    warnings: Vec<String>,
}

/// Runs the command: the report on stdout, an error on stderr with exit status 1.
pub fn run(args: UnionArgs, quiet: bool) -> ExitCode {
    match measure(args, quiet) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn measure(args: UnionArgs, quiet: bool) -> Result<(), String> {
    let progress = input::Progress::new(&args.files, quiet);
    let mut inputs = Vec::new();
    let mut warnings = Vec::new();
    for path in &args.files {
        let input = solid::read(path, args.solid.check(), &progress)?;
        warnings.extend(input.warnings.iter().map(|w| format!("{}: {w}", input.name)));
        progress.done(path);
        inputs.push(input);
    }
    progress.finish();
    let (bodies, names): (Vec<_>, Vec<String>) =
        solid::union_bodies(&inputs).into_iter().map(|b| (b.surface, b.name)).unzip();
    if bodies.is_empty() {
        return Err("no faces: there is no body to measure".into());
    }
    let start = Instant::now();
    let mut u = union(&bodies, args.tolerance).map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    // Caps on holes are guesses: the interval must hold whatever the missing faces were.
    let uncertainty: f64 = inputs.iter().map(solid::Input::volume_uncertainty).sum();
    u.lower = (u.lower - uncertainty).max(0.0);
    u.upper += uncertainty;
    for &b in &u.flipped {
        warnings.push(format!(
            "{}: wound inward (negative volume); measured as a solid turned outward (if it is \
             a cavity, the union of shells is not what you want)",
            names[b]
        ));
    }
    for &b in &u.bodies_not_solid {
        warnings.push(format!(
            "{}: not a closed solid (its volume in some cells leaves [0, cell volume]): the \
             interval is ordered but not certified",
            names[b]
        ));
    }
    if u.columns_unresolved > 0 {
        warnings.push(format!(
            "{} columns of the grid could not be resolved exactly; the interval keeps their \
             bounds",
            u.columns_unresolved
        ));
    }
    if u.upper - u.lower > args.tolerance * u.lower.abs() {
        let why = if uncertainty > 0.0 {
            "the caps on holes leave it uncertain"
        } else {
            "refinement and exact resolution could not close it"
        };
        warnings
            .push(format!("the interval is wider than the tolerance {}: {why}", args.tolerance));
    }
    if !quiet {
        for w in &warnings {
            eprintln!("meshvol: warning: {w}");
        }
    }
    let report = UnionReport {
        lower: u.lower,
        upper: u.upper,
        volume: u.volume(),
        bodies: u.bodies,
        sum_of_volumes: u.sum_of_volumes,
        cells_refined: u.cells_refined,
        cells_resolved_exactly: u.cells_resolved_exactly,
        volume_uncertainty: uncertainty,
        warnings,
    };
    let text = if args.json {
        serde_json::to_string(&report).map_err(|e| e.to_string())? + "\n"
    } else {
        let mut s = String::new();
        let [nx, ny, nz] = u.grid.counts;
        let _ = writeln!(s, "union of {} bodies: {}", u.bodies, names.join("; "));
        let _ = writeln!(s, "  volume           {}  (midpoint)", u.volume());
        let _ = writeln!(
            s,
            "  certified        [{}, {}]  (width {:.2e})",
            u.lower,
            u.upper,
            u.upper - u.lower
        );
        if uncertainty > 0.0 {
            let _ = writeln!(s, "  caps on holes    ± {uncertainty:.3e} (in the interval)");
        }
        let _ = writeln!(s, "  sum of volumes   {}", u.sum_of_volumes);
        let _ = writeln!(
            s,
            "  grid             {nx}×{ny}×{nz}, {} cells refined, {} resolved exactly",
            u.cells_refined, u.cells_resolved_exactly
        );
        let _ = writeln!(s, "  time             {seconds:.3} s");
        s
    };
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
    Ok(())
}
