//! `meshvol profile`: the volume below each level along an axis, the volume of each slab
//! between levels and the cross-section area at each level (a strapping table).

use crate::input;
use crate::solid::{self, SolidArgs};
use clap::{Args, ValueEnum};
use meshvol::grid::{profile, Axis, Levels, Profile};
use serde::Serialize;
use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Clone, Copy, ValueEnum)]
pub enum AxisArg {
    X,
    Y,
    Z,
}

#[derive(Args)]
pub struct ProfileArgs {
    /// The mesh file.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// The axis the levels are taken along.
    #[arg(long, value_enum, default_value = "z")]
    axis: AxisArg,
    /// N slabs: N + 1 equally spaced levels from the mesh's minimum to its maximum.
    #[arg(long, value_name = "N", required_unless_present = "step", conflicts_with = "step", value_parser = clap::value_parser!(u64).range(1..=(meshvol::grid::MAX_LEVELS as u64 - 1)))]
    levels: Option<u64>,
    /// A level every H from the minimum, up to the first at or above the maximum.
    #[arg(long, value_name = "H", value_parser = crate::positive_finite)]
    step: Option<f64>,
    /// Print one JSON object: axis, levels, volume_below, slab_volume, section_area.
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// Print CSV: level,volume_below,slab_volume,section_area.
    #[arg(long)]
    csv: bool,
    #[command(flatten)]
    solid: SolidArgs,
}

/// The JSON report: exactly these keys.
#[derive(Serialize)]
struct ProfileReport<'a> {
    file: &'a str,
    axis: &'static str,
    levels: &'a [f64],
    volume_below: &'a [f64],
    slab_volume: &'a [f64],
    section_area: &'a [f64],
    /// The reader's warnings and the reasons to doubt the solid.
    warnings: &'a [String],
}

/// Runs the command: the report on stdout, an error on stderr with exit status 1.
pub fn run(args: ProfileArgs, quiet: bool) -> ExitCode {
    match measure(args, quiet) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn measure(args: ProfileArgs, quiet: bool) -> Result<(), String> {
    let progress = input::Progress::new(std::slice::from_ref(&args.file), quiet);
    let input = solid::read(&args.file, args.solid.check(), &progress)?;
    progress.finish();
    let name = &input.name;
    let mut warnings = input.warnings.clone();
    let axis = match args.axis {
        AxisArg::X => Axis::X,
        AxisArg::Y => Axis::Y,
        AxisArg::Z => Axis::Z,
    };
    let levels = match (args.levels, args.step) {
        (Some(n), _) => Levels::Count(n as usize),
        (None, Some(h)) => Levels::Step(h),
        (None, None) => return Err("give --levels N or --step H".into()),
    };
    let p = profile(&input.surface(), axis, levels).map_err(|e| format!("{name}: {e}"))?;
    if p.volume_below.last().is_some_and(|&v| v < 0.0) {
        warnings.push(
            "volumes are negative: the faces are wound inward (clockwise seen from outside)"
                .to_string(),
        );
    }
    for w in &warnings {
        progress.warn(name, w);
    }
    let text = if args.json {
        let report = ProfileReport {
            file: name,
            axis: p.axis.name(),
            levels: &p.levels,
            volume_below: &p.volume_below,
            slab_volume: &p.slab_volume,
            section_area: &p.section_area,
            warnings: &warnings,
        };
        serde_json::to_string(&report).map_err(|e| e.to_string())? + "\n"
    } else if args.csv {
        csv(&p)
    } else {
        table(name, &p)
    };
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
    Ok(())
}

/// `level,volume_below,slab_volume,section_area`; the last level has no slab above it.
fn csv(p: &Profile) -> String {
    let mut s = String::from("level,volume_below,slab_volume,section_area\n");
    for (k, level) in p.levels.iter().enumerate() {
        let slab = p.slab_volume.get(k).map(|v| format!("{v:?}")).unwrap_or_default();
        let _ = writeln!(s, "{level:?},{:?},{slab},{:?}", p.volume_below[k], p.section_area[k]);
    }
    s
}

fn table(name: &str, p: &Profile) -> String {
    let mut s = String::new();
    let axis = p.axis.name();
    let _ = writeln!(s, "{name}: profile along {axis}, {} levels", p.levels.len());
    let _ = writeln!(
        s,
        "  {:>22}  {:>22}  {:>22}  {:>22}",
        axis, "volume below", "slab volume (to next)", "section area"
    );
    for (k, level) in p.levels.iter().enumerate() {
        let slab = p.slab_volume.get(k).map(|v| v.to_string()).unwrap_or_default();
        let _ = writeln!(
            s,
            "  {:>22}  {:>22}  {:>22}  {:>22}",
            level, p.volume_below[k], slab, p.section_area[k]
        );
    }
    s
}
