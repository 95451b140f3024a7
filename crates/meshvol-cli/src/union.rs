//! `meshvol union`: the volume of the union of several closed bodies (files, or the
//! shells of one file) as a certified interval, without a boolean mesh.

use crate::input;
use clap::Args;
use meshvol::grid::{shells, union, FaceSubset};
use meshvol_io::LoadedSurface;
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
    /// cells_resolved_exactly.
    #[arg(long)]
    json: bool,
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
    let mut loaded = Vec::new();
    for path in &args.files {
        let file = input::load(path)?;
        if !quiet {
            for w in &file.warnings {
                eprintln!("meshvol: warning: {}: {w}", path.display());
            }
        }
        loaded.push(file);
    }
    let surfaces: Vec<&LoadedSurface> = loaded.iter().map(|l| &l.surface).collect();
    let (bodies, names): (Vec<FaceSubset<'_, LoadedSurface>>, Vec<String>) = if surfaces.len() == 1
    {
        let name = args.files[0].display().to_string();
        shells(surfaces[0])
            .into_iter()
            .enumerate()
            .map(|(k, faces)| {
                (FaceSubset::new(surfaces[0], faces), format!("{name}, shell {}", k + 1))
            })
            .unzip()
    } else {
        surfaces
            .iter()
            .zip(&args.files)
            .map(|(s, p)| (FaceSubset::all(*s), p.display().to_string()))
            .unzip()
    };
    if bodies.is_empty() {
        return Err("no faces: there is no body to measure".into());
    }
    let start = Instant::now();
    let u = union(&bodies, args.tolerance).map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    if !quiet {
        for &b in &u.flipped {
            eprintln!(
                "meshvol: warning: {}: wound inward (negative volume); measured as a solid \
                 turned outward (if it is a cavity, the union of shells is not what you want)",
                names[b]
            );
        }
        if u.columns_unresolved > 0 {
            eprintln!(
                "meshvol: warning: {} columns of the grid could not be resolved exactly; \
                 the interval keeps their bounds",
                u.columns_unresolved
            );
        }
        let within = u.upper - u.lower <= args.tolerance * u.lower.abs();
        if !within {
            eprintln!(
                "meshvol: warning: the interval is wider than the tolerance {}: refinement and \
                 exact resolution could not close it",
                args.tolerance
            );
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
