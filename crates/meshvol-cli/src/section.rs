//! `meshvol section`: the cross-section of a mesh by a plane, its area and moments, and
//! its outline as WKT or GeoJSON.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::driver::{Driver, Output};
use crate::input::Progress;
use clap::Args;
use meshvol::polygon::Polygon;
use meshvol_report::plane::PlaneArg;
use meshvol_report::quantities::Quantities;
use meshvol_report::section::{section, SectionReport};
use meshvol_report::units::Scale;

#[derive(Args)]
pub struct SectionArgs {
    /// The mesh to cut: STL, OBJ, OFF, PLY, 3MF, glTF/GLB.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// The plane: `z=H`, `x=H`, `y=H` (2D coordinates (x, y), (y, z), (x, z)), a point
    /// and a normal `PX,PY,PZ,NX,NY,NZ`, or a normal and an offset `NX,NY,NZ,D` (n·x = D).
    #[arg(long, value_name = "PLANE", allow_hyphen_values = true)]
    plane: PlaneArg,
    /// Print the report as one JSON object.
    #[arg(long, conflicts_with_all = ["wkt", "geojson"])]
    json: bool,
    /// Print the section as a WKT MULTIPOLYGON instead of the report.
    #[arg(long, conflicts_with = "geojson")]
    wkt: bool,
    /// Print the section as a GeoJSON Feature instead of the report.
    #[arg(long)]
    geojson: bool,
    /// Write the section to OUT (.wkt, .geojson or .json) and print the report.
    #[arg(long, short, value_name = "OUT")]
    out: Option<PathBuf>,
    #[command(flatten)]
    units: crate::units::AreaUnitArgs,
    #[command(flatten)]
    solid: crate::solid::SolidArgs,
}

/// The section as WKT or GeoJSON, by `geojson`.
fn geometry(r: &SectionReport, polygons: &[Polygon], geojson: bool) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::new();
    if geojson {
        meshvol_io::geojson::write_feature(&mut out, polygons, r.geojson_properties())?;
    } else {
        meshvol_io::wkt::write_multipolygon(&mut out, polygons)?;
    }
    Ok(out)
}

/// Whether OUT names GeoJSON (true) or WKT (false).
fn out_is_geojson(out: &Path) -> Result<bool, String> {
    match out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("geojson" | "json") => Ok(true),
        Some("wkt") => Ok(false),
        _ => Err(format!("{}: cannot tell the format: use .wkt, .geojson or .json", out.display())),
    }
}

/// Runs `meshvol section`.
pub fn run(args: SectionArgs, quiet: bool) -> ExitCode {
    let files = std::slice::from_ref(&args.file);
    let mut driver = Driver::new(files, Output { json: args.json, quiet, csv: false });
    match measure(&args, &driver.progress) {
        Ok((report, Some(geometry))) => driver.print(&report, &geometry),
        Ok((report, None)) => driver.report(&report),
        Err(e) => driver.fail(&args.file.display().to_string(), &e),
    }
    driver.finish()
}

/// The report, and the section's outline when it is what is printed.
fn measure(
    args: &SectionArgs,
    progress: &Progress,
) -> Result<(SectionReport, Option<String>), String> {
    let out_geojson = args.out.as_deref().map(out_is_geojson).transpose()?;
    let input = crate::solid::read(&args.file, args.solid.check(), progress)?;
    progress.stage("cutting", &args.file);
    // The parser has refused a plane that cannot be made.
    let plane = args.plane.plane().map_err(|e| e.to_string())?;
    let (report, mut polygons) = section(&input.subject(), &plane);
    // The report and the outline (WKT, GeoJSON) in the units asked for: the outline's
    // coordinates in the plane scale as lengths, so its area is the report's.
    let options = args.units.options();
    let report = report.in_units(&options, input.source.unit)?;
    let (scale, _) = Scale::resolve(&options, input.source.unit)?;
    for polygon in &mut polygons {
        for ring in std::iter::once(&mut polygon.exterior).chain(&mut polygon.holes) {
            ring.iter_mut().for_each(|p| *p = scale.point(*p));
        }
    }
    if let (Some(out), Some(geojson)) = (&args.out, out_geojson) {
        let bytes = geometry(&report, &polygons, geojson).map_err(|e| e.to_string())?;
        std::fs::write(out, bytes).map_err(|e| format!("{}: {e}", out.display()))?;
    }
    let printed = if args.wkt || args.geojson {
        let bytes = geometry(&report, &polygons, args.geojson).map_err(|e| e.to_string())?;
        Some(String::from_utf8_lossy(&bytes).into_owned())
    } else {
        None
    };
    Ok((report, printed))
}
