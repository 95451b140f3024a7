//! `meshvol hull`: volume, area and centroid of the convex hull of each file's points.

use crate::driver::{self, Output};
use clap::Args;
use meshvol::hull::convex_hull_with;
use meshvol::Mesh;
use meshvol_io::write::{self, PlyEncoding};
use meshvol_report::hull::hull;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args)]
pub struct HullArgs {
    /// Point files (.xyz, .txt, .csv, .pts: x y z per line, header allowed) or any mesh
    /// file (its vertices; a PLY of vertices only is a point cloud); `-` reads standard
    /// input (format from the content).
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
    /// Write the hull (of a single FILE) as .stl (binary), .obj or .ply (binary).
    #[arg(long, short, value_name = "OUT", value_parser = parse_out)]
    out: Option<PathBuf>,
}

fn parse_out(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("stl" | "obj" | "ply") => Ok(path),
        _ => Err(format!("'{s}': cannot write this format: use .stl, .obj or .ply")),
    }
}

fn write_mesh(out: &Path, mesh: &Mesh) -> Result<(), String> {
    let file = std::fs::File::create(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut w = std::io::BufWriter::new(file);
    let extension = out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => write::obj(&mut w, mesh),
        Some("ply") => write::ply(&mut w, mesh, PlyEncoding::BinaryLittleEndian),
        _ => write::stl_binary(&mut w, mesh),
    }
    .and_then(|()| std::io::Write::flush(&mut w))
    .map_err(|e| format!("{}: {e}", out.display()))
}

/// Runs the command.
pub fn run(args: HullArgs, quiet: bool) -> ExitCode {
    if args.out.is_some() && args.files.len() != 1 {
        eprintln!("meshvol: error: --out writes one hull: give one FILE");
        return ExitCode::from(2);
    }
    driver::each(&args.files, Output { json: args.json, quiet }, |path, progress| {
        let name = path.display().to_string();
        progress.stage("reading", path);
        let cloud = crate::input::load_points(path)?;
        let hook = progress.kernel(format!("computing the hull of {name}"));
        let h = convex_hull_with(&cloud.points, &hook).map_err(|e| format!("{name}: {e}"))?;
        drop(hook);
        if let Some(out) = &args.out {
            let mesh = h.mesh.as_ref().ok_or_else(|| {
                let why = h.degeneracy.map(|d| d.to_string()).unwrap_or_default();
                format!("{name}: no hull to write to {}: {why}", out.display())
            })?;
            write_mesh(out, mesh)?;
        }
        let format = Some(cloud.source.name());
        Ok(hull(Some(name), format, cloud.points.len(), &h, cloud.warnings))
    })
}
