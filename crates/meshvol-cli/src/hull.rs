//! `meshvol hull`: volume, area and centroid of the convex hull of each file's points.

use crate::driver::{self, Output};
use clap::Args;
use meshvol::hull::convex_hull_with;
use meshvol_io::write::MeshFormat;
use meshvol_report::hull::hull;
use meshvol_report::quantities::Quantities;
use meshvol_report::written::write_mesh;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct HullArgs {
    /// Point files (.xyz, .txt, .csv, .pts: x y z per line, header allowed) or any mesh
    /// file (its vertices; a PLY of vertices only is a point cloud); `-` reads standard
    /// input (format from the content).
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
    /// Write the hull (of a single FILE) as .stl (binary), .obj or .ply (binary). The file
    /// is read back and must be the hull reported: STL stores float32 coordinates, which
    /// can change a hull far from the origin; such a write is refused (exit 1).
    #[arg(long, short, value_name = "OUT", value_parser = parse_out)]
    out: Option<PathBuf>,
    /// Write --out even when its format changes the hull (float32 rounding): warn, and
    /// report the volume written beside the hull's.
    #[arg(long, requires = "out")]
    allow_lossy: bool,
    #[command(flatten)]
    units: crate::units::UnitArgs,
}

fn parse_out(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match MeshFormat::of_path(&path) {
        Some(MeshFormat::Stl | MeshFormat::Obj | MeshFormat::Ply) => Ok(path),
        _ => Err(format!("'{s}': cannot write this format: use .stl, .obj or .ply")),
    }
}

/// Runs the command.
pub fn run(args: HullArgs, quiet: bool) -> ExitCode {
    let inputs = args.walk.expand(&args.files, meshvol_io::InputKind::Points);
    if args.out.is_some() && inputs.files.len() + inputs.problems.len() != 1 {
        eprintln!("meshvol: error: --out writes one hull: give one FILE");
        return ExitCode::from(2);
    }
    driver::each(&inputs, Output { json: args.json, quiet, csv: false }, |path, progress| {
        let name = path.display().to_string();
        progress.stage("reading", path);
        let cloud = crate::input::load_points(path)?;
        let hook = progress.kernel(format!("computing the hull of {name}"));
        let h = convex_hull_with(&cloud.points, &hook).map_err(|e| format!("{name}: {e}"))?;
        drop(hook);
        let written = match &args.out {
            Some(out) => {
                let mesh = h.mesh.as_ref().ok_or_else(|| {
                    let why = h.degeneracy.map(|d| d.to_string()).unwrap_or_default();
                    format!("{name}: no hull to write to {}: {why}", out.display())
                })?;
                progress.stage("writing and reading back", out);
                let w = write_mesh(mesh, out, args.allow_lossy)
                    .map_err(|e| e.message("--allow-lossy"))?;
                Some(w)
            }
            None => None,
        };
        let format = Some(cloud.source.name());
        let report = hull(Some(name), format, cloud.points.len(), &h, cloud.warnings);
        match written {
            Some(w) => report.with_written(w),
            None => report,
        }
        .in_units(&args.units.options(), None)
    })
}
