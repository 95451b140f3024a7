//! `meshvol repair FILE -o OUT`: write the solid the mesh most plausibly bounds, and say
//! exactly what was changed. Never silent; and what is written is read back and must be
//! the solid reported (`meshvol_report::written`), unless `--allow-lossy`.

use crate::driver::{Driver, Output};
use clap::Args;
use meshvol_io::write::MeshFormat;
use meshvol_report::repair::repair;
use meshvol_report::written::write_mesh;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct RepairArgs {
    /// The mesh to repair.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// Where to write the result: .stl (binary), .obj, .ply (binary) or .glb. The file is
    /// read back and must be the solid reported: STL and GLB store float32 coordinates,
    /// which can change a solid far from the origin; such a write is refused (exit 1).
    #[arg(short, long, value_name = "OUT", value_parser = parse_out)]
    out: PathBuf,
    /// Write OUT even when its format changes the solid (float32 rounding): warn, and
    /// report the volume written beside the volume intended.
    #[arg(long)]
    allow_lossy: bool,
    /// Cap each hole with a fan of triangles from its centroid.
    #[arg(long)]
    cap: bool,
    /// Print what changed as one JSON object.
    #[arg(long)]
    json: bool,
    /// Weld vertices whose coordinates differ by at most T; 0 welds exactly equal
    /// positions only. Default: exactly, and when that leaves holes, again within 1e-9 of
    /// the bounding box diagonal (reported as `weld_tolerance`).
    #[arg(long, value_name = "T", value_parser = crate::numbers::non_negative_finite, allow_hyphen_values = true)]
    weld_tolerance: Option<f64>,
}

fn parse_out(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match MeshFormat::of_path(&path) {
        Some(_) => Ok(path),
        None => Err(format!("'{s}': the output must end in .stl, .obj, .ply or .glb")),
    }
}

/// Runs the command: a file without faces is an error, and so is a file written that is
/// not the solid reported (without `--allow-lossy`); nothing is written then.
pub fn run(args: RepairArgs, quiet: bool) -> ExitCode {
    let options = crate::solid::check_options(args.weld_tolerance, false);
    let files = std::slice::from_ref(&args.file);
    let mut driver = Driver::new(files, Output { json: args.json, quiet, csv: false });
    let repaired =
        crate::solid::read(&args.file, Some(options), &driver.progress).and_then(|input| {
            let check = input.check.as_ref().ok_or("no check")?;
            let mesh = check.solid_mesh(args.cap);
            driver.progress.stage("writing and reading back", &args.out);
            let written = write_mesh(&mesh, &args.out, args.allow_lossy)
                .map_err(|e| e.message("--allow-lossy"))?;
            Ok(repair(&input.source, &input.surface, check, &mesh, args.cap, written))
        });
    match repaired {
        Ok(report) => driver.report(&report),
        Err(e) => driver.fail(&args.file.display().to_string(), &e),
    }
    driver.finish()
}
