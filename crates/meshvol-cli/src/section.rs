//! `meshvol section`: the cross-section of a mesh by a plane, its area and moments, and
//! its outline as WKT or GeoJSON.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::driver::{Driver, Output};
use crate::input::Progress;
use clap::Args;
use meshvol::polygon::Polygon;
use meshvol::section::Plane;
use meshvol_report::quantities::Quantities;
use meshvol_report::section::{section, SectionReport};
use meshvol_report::units::Scale;

#[derive(Args)]
pub struct SectionArgs {
    /// The mesh to cut: STL, OBJ, OFF, PLY, 3MF, glTF/GLB.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// The plane: `z=H`, `x=H`, `y=H` (2D coordinates (x, y), (y, z), (x, z)), or a
    /// point and a normal `PX,PY,PZ,NX,NY,NZ`.
    #[arg(long, value_name = "PLANE", value_parser = parse_plane, allow_hyphen_values = true)]
    plane: Plane,
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

/// Parses `z=H`, `x=H`, `y=H` or `PX,PY,PZ,NX,NY,NZ`.
fn parse_plane(s: &str) -> Result<Plane, String> {
    let number = |t: &str| -> Result<f64, String> {
        t.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("'{t}' is not a finite number"))
    };
    if let Some((axis, value)) = s.split_once('=') {
        let axis = match axis.trim().to_ascii_lowercase().as_str() {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            other => return Err(format!("'{other}' is not an axis: use x=H, y=H or z=H")),
        };
        return Plane::axis(axis, number(value)?).map_err(|e| e.to_string());
    }
    let values: Vec<f64> = s.split(',').map(number).collect::<Result<_, _>>()?;
    let [px, py, pz, nx, ny, nz] = values[..] else {
        return Err(format!(
            "expected z=H, x=H, y=H or six numbers PX,PY,PZ,NX,NY,NZ; found {} number(s)",
            values.len()
        ));
    };
    Plane::new([px, py, pz], [nx, ny, nz]).map_err(|e| e.to_string())
}

/// The section as WKT or GeoJSON, by `geojson`.
fn geometry(r: &SectionReport, polygons: &[Polygon], geojson: bool) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::new();
    if geojson {
        let mut properties = serde_json::Map::new();
        properties.insert("file".into(), r.file.clone().into());
        properties.insert("area".into(), r.area.into());
        if let Ok(plane) = serde_json::to_value(&r.plane) {
            properties.insert("plane".into(), plane);
        }
        meshvol_io::geojson::write_feature(&mut out, polygons, properties)?;
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
    let (report, mut polygons) = section(&input.subject(), &args.plane);
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

#[cfg(test)]
mod tests {
    use super::parse_plane;

    #[test]
    fn planes_parse() {
        assert_eq!(parse_plane("z=1.5").unwrap().frame().origin, [0.0, 0.0, 1.5]);
        assert_eq!(parse_plane("X = -2").unwrap().frame().normal, [1.0, 0.0, 0.0]);
        let p = parse_plane("1,2,3,0,0,2").unwrap().frame();
        assert_eq!((p.origin, p.normal), ([1.0, 2.0, 3.0], [0.0, 0.0, 1.0]));
        assert!(parse_plane("w=1").unwrap_err().contains("not an axis"));
        assert!(parse_plane("z=abc").unwrap_err().contains("'abc'"));
        assert!(parse_plane("1,2,3").unwrap_err().contains("found 3"));
        assert!(parse_plane("0,0,0,0,0,0").unwrap_err().contains("zero"));
    }
}
