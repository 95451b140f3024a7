//! `meshvol repair FILE -o OUT`: write the solid the mesh most plausibly bounds, and say
//! exactly what was changed. Never silent.

use crate::driver::{Driver, Output};
use clap::Args;
use meshvol_io::write::{self, PlyEncoding};
use meshvol_report::repair::repair;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args)]
pub struct RepairArgs {
    /// The mesh to repair.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// Where to write the result: .stl (binary), .obj, .ply (binary) or .glb.
    #[arg(short, long, value_name = "OUT", value_parser = parse_out)]
    out: PathBuf,
    /// Cap each hole with a fan of triangles from its centroid.
    #[arg(long)]
    cap: bool,
    /// Print what changed as one JSON object.
    #[arg(long)]
    json: bool,
    /// Weld vertices whose coordinates differ by at most T; 0 welds exactly equal
    /// positions only. Default: exactly, and when that leaves holes, again within 1e-9 of
    /// the bounding box diagonal (reported as `weld_tolerance`).
    #[arg(long, value_name = "T", value_parser = crate::non_negative_finite, allow_hyphen_values = true)]
    weld_tolerance: Option<f64>,
}

fn extension(path: &Path) -> Option<String> {
    path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase)
}

fn parse_out(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match extension(&path).as_deref() {
        Some("stl" | "obj" | "ply" | "glb") => Ok(path),
        _ => Err(format!("'{s}': the output must end in .stl, .obj, .ply or .glb")),
    }
}

/// Runs the command: a file without faces is an error (and nothing is written).
pub fn run(args: RepairArgs, quiet: bool) -> ExitCode {
    let options = crate::solid::check_options(args.weld_tolerance, false);
    let files = std::slice::from_ref(&args.file);
    let mut driver = Driver::new(files, Output { json: args.json, quiet });
    let repaired =
        crate::solid::read(&args.file, Some(options), &driver.progress).and_then(|input| {
            let check = input.check.as_ref().ok_or("no check")?;
            let mesh = check.solid_mesh(args.cap);
            let out = &args.out;
            let written = std::fs::File::create(out).and_then(|f| {
                let mut w = BufWriter::new(f);
                match extension(out).as_deref() {
                    Some("obj") => write::obj(&mut w, &mesh),
                    Some("ply") => write::ply(&mut w, &mesh, PlyEncoding::BinaryLittleEndian),
                    Some("glb") => write::glb(&mut w, &mesh),
                    _ => write::stl_binary(&mut w, &mesh),
                }?;
                std::io::Write::flush(&mut w)
            });
            written.map_err(|e| format!("{}: {e}", out.display()))?;
            let out = out.display().to_string();
            Ok(repair(&input.source, &input.surface, check, &mesh, args.cap, &out))
        });
    match repaired {
        Ok(report) => driver.report(&report),
        Err(e) => driver.fail(&args.file.display().to_string(), &e),
    }
    driver.finish()
}
