//! `meshvol section`: the cross-section of a mesh by a plane, its area and moments, and
//! its outline as WKT or GeoJSON.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use meshvol::polygon::{area_properties, Polygon};
use meshvol::section::{section, Plane, PlaneFrame};
use serde::Serialize;

use crate::area::InertiaReport;

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

#[derive(Debug, Serialize)]
pub struct PlaneReport {
    /// A point of the plane: the 2D origin.
    pub origin: [f64; 3],
    pub normal: [f64; 3],
    /// The 3D directions of the 2D coordinates' axes: (s, t) is origin + s·u + t·v.
    pub u: [f64; 3],
    pub v: [f64; 3],
}

/// The report. Field names are the JSON keys.
#[derive(Debug, Serialize)]
pub struct SectionReport {
    pub file: String,
    pub format: String,
    pub plane: PlaneReport,
    /// Exteriors minus holes, in the plane's 2D coordinates.
    pub area: f64,
    /// Σ of the loops' areas as the mesh winds them (negative for inward winding).
    pub signed_area: f64,
    pub perimeter: f64,
    /// In the plane's 2D coordinates.
    pub centroid: Option<[f64; 2]>,
    pub centroid_3d: Option<[f64; 3]>,
    /// About the centroid, in the plane's 2D axes.
    pub inertia: Option<InertiaReport>,
    pub polygons: usize,
    pub holes: usize,
    pub loops: usize,
    /// Triangles crossing the plane.
    pub segments: usize,
    pub open_chains: usize,
    pub warnings: Vec<String>,
}

fn plane_report(f: &PlaneFrame) -> PlaneReport {
    PlaneReport { origin: f.origin, normal: f.normal, u: f.u, v: f.v }
}

/// Cuts a loaded mesh.
fn measure(input: &crate::solid::Input, plane: &Plane) -> (SectionReport, Vec<Polygon>) {
    let (file, loaded) = (&input.name, &input.loaded);
    let cut = section(&input.surface(), plane);
    let props = area_properties(&cut.polygons);
    let frame = plane.frame();
    let mut warnings = input.warnings.clone();
    if cut.segments == 0 {
        warnings.push("the plane does not cut the surface: the section is empty".into());
    }
    if cut.open_chains > 0 {
        warnings.push(format!(
            "{} chain(s) of the section do not close: the surface is open along the plane; \
             they are left out of the area",
            cut.open_chains
        ));
    }
    if cut.ambiguous_edges > 0 {
        warnings.push(format!(
            "{} edge(s) crossed twice in one direction: edges shared by more than two \
             triangles, or inconsistent winding; loops through them are chained arbitrarily",
            cut.ambiguous_edges
        ));
    }
    if cut.misoriented_loops > 0 {
        warnings.push(format!(
            "{} loop(s) wound against their nesting: an inward-wound shell inside another, or \
             intersecting shells; the area follows the nesting",
            cut.misoriented_loops
        ));
    }
    if cut.signed_area < 0.0 {
        warnings.push(
            "the loops wind clockwise: the mesh is wound inward (the area is still reported \
             positive)"
                .into(),
        );
    }
    let centroid_3d = props
        .centroid
        .map(|[s, t]| [0, 1, 2].map(|k| frame.origin[k] + s * frame.u[k] + t * frame.v[k]));
    let report = SectionReport {
        file: file.to_string(),
        format: loaded.format.name().to_string(),
        plane: plane_report(&frame),
        area: props.area,
        signed_area: cut.signed_area,
        perimeter: props.perimeter,
        centroid: props.centroid,
        centroid_3d,
        inertia: props.centroid.map(|_| props.inertia.into()),
        polygons: cut.polygons.len(),
        holes: cut.polygons.iter().map(|p| p.holes.len()).sum(),
        loops: cut.loops,
        segments: cut.segments,
        open_chains: cut.open_chains,
        warnings,
    };
    (report, cut.polygons)
}

fn text(r: &SectionReport) -> String {
    let mut s = String::new();
    let p = &r.plane;
    let _ = writeln!(
        s,
        "{}: {}, section by the plane through {:?} with normal {:?}",
        r.file, r.format, p.origin, p.normal
    );
    let _ = writeln!(s, "  2D axes    u {:?}, v {:?}", p.u, p.v);
    let _ = writeln!(
        s,
        "  outline    {} polygon(s), {} hole(s), from {} loop(s) of {} segment(s)",
        r.polygons, r.holes, r.loops, r.segments
    );
    let _ = writeln!(s, "  area       {}", r.area);
    let _ = writeln!(s, "  perimeter  {}", r.perimeter);
    match (&r.centroid, &r.centroid_3d, &r.inertia) {
        (Some(c), Some(c3), Some(m)) => {
            let _ =
                writeln!(s, "  centroid   ({}, {}) in the plane, {:?} in space", c[0], c[1], c3);
            let _ = writeln!(
                s,
                "  inertia    iu {}  iv {}  iuv {}  polar {}  (about the centroid)",
                m.ix, m.iy, m.ixy, m.polar
            );
        }
        _ => {
            let _ = writeln!(s, "  centroid   undefined (no area)");
        }
    }
    s
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
    match run_inner(&args, quiet) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run_inner(args: &SectionArgs, quiet: bool) -> Result<(), String> {
    let out_geojson = args.out.as_deref().map(out_is_geojson).transpose()?;
    let progress = crate::input::Progress::new(std::slice::from_ref(&args.file), quiet);
    let input = crate::solid::read(&args.file, args.solid.check(), &progress)?;
    progress.finish();
    let (report, polygons) = measure(&input, &args.plane);
    for w in &report.warnings {
        progress.warn(&input.name, w);
    }
    if let (Some(out), Some(geojson)) = (&args.out, out_geojson) {
        let bytes = geometry(&report, &polygons, geojson).map_err(|e| e.to_string())?;
        std::fs::write(out, bytes).map_err(|e| format!("{}: {e}", out.display()))?;
    }
    let printed = if args.wkt || args.geojson {
        geometry(&report, &polygons, args.geojson).map_err(|e| e.to_string())?
    } else if args.json {
        serde_json::to_string(&report).map(|s| s + "\n").map_err(|e| e.to_string())?.into_bytes()
    } else {
        text(&report).into_bytes()
    };
    // A closed stdout (piped into `head`) is not an error worth a message.
    let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), &printed);
    Ok(())
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
