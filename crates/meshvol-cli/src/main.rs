//! The `meshvol` command: a thin layer of arguments and output over the meshvol
//! libraries. Results go to stdout, errors and warnings to stderr; the exit status is 0
//! when every file was measured, 1 when any failed, 2 on a usage error.

mod units;
mod volume;

use clap::{Args, CommandFactory, Parser, Subcommand};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use units::Units;
use volume::VolumeOptions;

#[derive(Parser)]
#[command(
    name = "meshvol",
    version,
    about = "Measure solids: volume, area, centroid and inertia of mesh files, exactly and fast.",
    after_help = "`meshvol FILE...` is short for `meshvol volume FILE...`."
)]
struct Cli {
    /// Worker threads (default: one per core). Results are identical for any count.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Volume, area, centroid, inertia, principal axes, mass and bounds of each file.
    Volume(VolumeArgs),
}

#[derive(Args)]
struct VolumeArgs {
    /// Mesh files: STL (binary or ASCII), OBJ, OFF.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
    /// Density, in mass per reported volume unit; scales `mass` and `inertia`.
    #[arg(long, default_value_t = 1.0, value_parser = positive_finite)]
    density: f64,
    /// The file's length unit and the unit to report in: FILE[:REPORT], e.g. `mm`,
    /// `mm:cm`, `in:mL`. Units: mm, cm, m, in, ft; REPORT may also be mL (lengths in cm) or
    /// L (lengths in dm).
    #[arg(long, value_name = "FILE[:REPORT]")]
    units: Option<Units>,
    /// Report the correctly rounded exact signed volume (exact arithmetic; a few times
    /// slower than the default, which is already within `volume_error_bound`).
    #[arg(long)]
    exact: bool,
}

fn positive_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("'{s}' is not a positive number")),
    }
}

/// Inserts `volume` when the first argument is not a subcommand or a top-level flag, so
/// `meshvol part.stl` means `meshvol volume part.stl`.
fn with_default_command(mut args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let command = Cli::command();
    let known = |a: &str| {
        command.get_subcommands().any(|c| c.get_name() == a)
            || matches!(a, "help" | "-h" | "--help" | "-V" | "--version")
    };
    // Skip global options (and their values) to find the first real argument.
    let mut i = 1;
    while i < args.len() {
        let a = args[i].to_string_lossy();
        if a == "--threads" {
            i += 2;
        } else if a.starts_with("--threads=") {
            i += 1;
        } else {
            break;
        }
    }
    if i < args.len() && !known(&args[i].to_string_lossy()) {
        args.insert(i, "volume".into());
    }
    args
}

fn main() -> ExitCode {
    let cli = Cli::parse_from(with_default_command(std::env::args_os().collect()));
    if let Some(n) = cli.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(n).build_global() {
            eprintln!("meshvol: cannot start {n} threads: {e}");
            return ExitCode::from(2);
        }
    }
    match cli.command {
        Command::Volume(args) => run_volume(args),
    }
}

fn run_volume(args: VolumeArgs) -> ExitCode {
    let options = VolumeOptions { density: args.density, units: args.units, exact: args.exact };
    let mut failed = false;
    let mut stdout = std::io::stdout().lock();
    for path in &args.files {
        let name = path.display().to_string();
        let report = meshvol_io::read(path)
            .map_err(|e| e.to_string())
            .and_then(|loaded| volume::report(&name, &loaded, &options));
        match report {
            Ok(r) => {
                let out = if args.json {
                    serde_json::to_string(&r).map(|s| s + "\n").unwrap_or_else(|e| e.to_string())
                } else {
                    volume::text(&r)
                };
                for w in &r.warnings {
                    eprintln!("meshvol: warning: {name}: {w}");
                }
                if stdout.write_all(out.as_bytes()).is_err() {
                    return ExitCode::FAILURE; // stdout closed (e.g. piped into `head`)
                }
            }
            Err(e) => {
                eprintln!("meshvol: error: {e}");
                failed = true;
            }
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
