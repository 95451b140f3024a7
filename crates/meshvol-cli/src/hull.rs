//! `meshvol hull`: volume, area and centroid of the convex hull of each file's points.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use meshvol::hull::{convex_hull, Hull};
use meshvol::Mesh;
use meshvol_io::write::{self, PlyEncoding};
use serde::Serialize;

#[derive(Args)]
pub struct HullArgs {
    /// Point files (.xyz, .txt, .csv, .pts: x y z per line, header allowed) or any mesh
    /// file (its vertices; a PLY of vertices only is a point cloud).
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
    /// Write the hull (of a single FILE) as .stl (binary), .obj or .ply (binary).
    #[arg(long, short, value_name = "OUT")]
    out: Option<PathBuf>,
}

/// One file's report. Field names are the JSON keys.
#[derive(Debug, Serialize)]
pub struct HullReport {
    pub file: String,
    pub format: &'static str,
    /// Points read.
    pub points: usize,
    pub hull_vertices: usize,
    /// Triangles of the hull.
    pub hull_faces: usize,
    pub volume: f64,
    /// A bound on the volume's rounding error (the hull's vertices taken as exact).
    pub volume_error_bound: f64,
    pub area: f64,
    pub centroid: Option<[f64; 3]>,
    /// Why the hull has no volume, when it has none: `no points`, `coincident`,
    /// `collinear` or `coplanar`.
    pub degenerate: Option<&'static str>,
    pub warnings: Vec<String>,
}

fn report(
    file: &str,
    format: &'static str,
    points: usize,
    hull: &Hull,
    mut warnings: Vec<String>,
) -> HullReport {
    use meshvol::hull::Degeneracy;
    let degenerate = hull.degeneracy.map(|d| match d {
        Degeneracy::NoPoints => "no points",
        Degeneracy::AllCoincide => "coincident",
        Degeneracy::Collinear => "collinear",
        Degeneracy::Coplanar => "coplanar",
    });
    if let Some(d) = hull.degeneracy {
        warnings.push(format!("{d}: the hull encloses no volume, so the volume is 0"));
    }
    let mesh = hull.mesh.as_ref();
    HullReport {
        file: file.to_string(),
        format,
        points,
        hull_vertices: mesh.map_or(0, Mesh::vertex_count),
        hull_faces: mesh.map_or(0, Mesh::face_count),
        volume: hull.volume(),
        volume_error_bound: hull.properties.volume_error_bound,
        area: hull.properties.area,
        centroid: hull.properties.centroid,
        degenerate,
        warnings,
    }
}

fn text(r: &HullReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{}: {}, {} points", r.file, r.format, r.points);
    match r.degenerate {
        Some(why) => {
            let _ = writeln!(s, "  hull       none ({why})");
            let _ = writeln!(s, "  volume     0");
        }
        None => {
            let _ = writeln!(
                s,
                "  hull       {} vertices, {} triangles",
                r.hull_vertices, r.hull_faces
            );
            let _ = writeln!(s, "  volume     {}  (± {:.1e})", r.volume, r.volume_error_bound);
            let _ = writeln!(s, "  area       {}", r.area);
            if let Some(c) = r.centroid {
                let _ = writeln!(s, "  centroid   ({}, {}, {})", c[0], c[1], c[2]);
            }
        }
    }
    s
}

/// The formats `--out` writes.
#[derive(Clone, Copy)]
enum OutFormat {
    Stl,
    Obj,
    Ply,
}

/// The format OUT's extension names, checked before any work is done.
fn out_format(out: &Path) -> Result<OutFormat, String> {
    match out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("stl") => Ok(OutFormat::Stl),
        Some("obj") => Ok(OutFormat::Obj),
        Some("ply") => Ok(OutFormat::Ply),
        _ => Err(format!("{}: cannot write this format: use .stl, .obj or .ply", out.display())),
    }
}

fn write_mesh(out: &Path, format: OutFormat, mesh: &Mesh) -> Result<(), String> {
    let file = std::fs::File::create(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut w = std::io::BufWriter::new(file);
    match format {
        OutFormat::Stl => write::stl_binary(&mut w, mesh),
        OutFormat::Obj => write::obj(&mut w, mesh),
        OutFormat::Ply => write::ply(&mut w, mesh, PlyEncoding::BinaryLittleEndian),
    }
    .and_then(|()| std::io::Write::flush(&mut w))
    .map_err(|e| format!("{}: {e}", out.display()))
}

fn measure(path: &Path, out: Option<(&Path, OutFormat)>) -> Result<HullReport, String> {
    let cloud = meshvol_io::read_points(path).map_err(|e| e.to_string())?;
    let name = path.display().to_string();
    let hull = convex_hull(&cloud.points).map_err(|e| format!("{name}: {e}"))?;
    let r = report(&name, cloud.source.name(), cloud.points.len(), &hull, cloud.warnings);
    if let Some((out, format)) = out {
        match &hull.mesh {
            Some(mesh) => write_mesh(out, format, mesh)?,
            None => {
                return Err(format!(
                    "{name}: no hull to write to {}: {}",
                    out.display(),
                    hull.degeneracy.map(|d| d.to_string()).unwrap_or_default()
                ))
            }
        }
    }
    Ok(r)
}

/// Runs `meshvol hull`.
pub fn run(args: HullArgs, quiet: bool) -> ExitCode {
    let out = match args.out.as_deref().map(|out| out_format(out).map(|f| (out, f))).transpose() {
        Ok(out) => out,
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            return ExitCode::from(2);
        }
    };
    if out.is_some() && args.files.len() != 1 {
        eprintln!("meshvol: error: --out writes one hull: give one FILE");
        return ExitCode::from(2);
    }
    let mut failed = false;
    let mut stdout = std::io::stdout().lock();
    for path in &args.files {
        match measure(path, out) {
            Ok(r) => {
                if !quiet {
                    for w in &r.warnings {
                        eprintln!("meshvol: warning: {}: {w}", r.file);
                    }
                }
                let out = if args.json {
                    serde_json::to_string(&r).map(|s| s + "\n").unwrap_or_else(|e| e.to_string())
                } else {
                    text(&r)
                };
                if std::io::Write::write_all(&mut stdout, out.as_bytes()).is_err() {
                    return ExitCode::FAILURE;
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
