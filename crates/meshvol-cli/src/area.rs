//! `meshvol area`: area, perimeter, centroid and second moments of the polygons in WKT,
//! GeoJSON and text ring files, per feature and in total, with the checks that say
//! whether those numbers mean what they seem to.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use meshvol::polygon::{
    area_properties, polygon_issues, AreaProperties, Polygon, RingRole, SecondMoments,
};
use meshvol_io::{read_polygons, PolygonFile};
use serde::Serialize;

#[derive(Args)]
pub struct AreaArgs {
    /// Polygon files: WKT (.wkt), GeoJSON (.geojson, .json), or x y lines (.txt, .xy,
    /// .csv; blank lines separate the exterior from holes).
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
}

/// Second moments about the centroid, and the principal ones.
#[derive(Debug, Serialize)]
pub struct InertiaReport {
    /// ∫(y − cy)² dA.
    pub ix: f64,
    /// ∫(x − cx)² dA.
    pub iy: f64,
    /// ∫(x − cx)(y − cy) dA.
    pub ixy: f64,
    pub polar: f64,
    /// Larger first.
    pub principal: [f64; 2],
    /// Of the axis of the larger principal moment, counter-clockwise from x.
    pub principal_angle_degrees: f64,
}

impl From<SecondMoments> for InertiaReport {
    fn from(m: SecondMoments) -> Self {
        let (principal, angle) = m.principal();
        InertiaReport {
            ix: m.ix,
            iy: m.iy,
            ixy: m.ixy,
            polar: m.polar,
            principal,
            principal_angle_degrees: angle.to_degrees(),
        }
    }
}

#[derive(Debug, Serialize)]
pub struct RingReport {
    pub feature: usize,
    pub polygon: usize,
    pub ring: usize,
    /// `exterior` or `hole`.
    pub role: &'static str,
    pub vertices: usize,
    /// Positive counter-clockwise.
    pub signed_area: f64,
    /// `ccw`, `cw` or `none` (no area).
    pub orientation: &'static str,
    pub perimeter: f64,
}

#[derive(Debug, Serialize)]
pub struct FeatureReport {
    pub index: usize,
    pub name: Option<String>,
    pub polygons: usize,
    pub area: f64,
    pub perimeter: f64,
    pub centroid: Option<[f64; 2]>,
    pub inertia: Option<InertiaReport>,
    pub warnings: Vec<String>,
}

/// One file's report. Field names are the JSON keys.
#[derive(Debug, Serialize)]
pub struct AreaReport {
    pub file: String,
    pub format: &'static str,
    pub polygons: usize,
    pub area: f64,
    pub perimeter: f64,
    pub centroid: Option<[f64; 2]>,
    /// About the centroid; null when there is no area.
    pub inertia: Option<InertiaReport>,
    pub rings: Vec<RingReport>,
    /// Present when the file has more than one feature (a FeatureCollection, several WKT
    /// geometries); the totals above cover all of them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub features: Option<Vec<FeatureReport>>,
    pub warnings: Vec<String>,
}

fn inertia(p: &AreaProperties) -> Option<InertiaReport> {
    p.centroid.map(|_| p.inertia.into())
}

/// Measures a polygon file.
pub fn report(file: &str, polygons: &PolygonFile) -> AreaReport {
    let many = polygons.features.len() > 1;
    let mut warnings = polygons.warnings.clone();
    let mut rings = Vec::new();
    let mut features = Vec::new();
    for (index, feature) in polygons.features.iter().enumerate() {
        let measured = area_properties(&feature.polygons);
        let issues: Vec<String> =
            polygon_issues(&feature.polygons).iter().map(|i| i.to_string()).collect();
        let prefix = if many { format!("feature {index}: ") } else { String::new() };
        warnings.extend(issues.iter().map(|i| format!("{prefix}{i}")));
        rings.extend(measured.rings.iter().map(|r| RingReport {
            feature: index,
            polygon: r.polygon,
            ring: r.ring,
            role: match r.role {
                RingRole::Exterior => "exterior",
                RingRole::Hole => "hole",
            },
            vertices: r.vertices,
            signed_area: r.signed_area,
            orientation: if r.signed_area > 0.0 {
                "ccw"
            } else if r.signed_area < 0.0 {
                "cw"
            } else {
                "none"
            },
            perimeter: r.perimeter,
        }));
        features.push(FeatureReport {
            index,
            name: feature.name.clone(),
            polygons: feature.polygons.len(),
            area: measured.area,
            perimeter: measured.perimeter,
            centroid: measured.centroid,
            inertia: inertia(&measured),
            warnings: issues,
        });
    }
    let all: Vec<&Polygon> = polygons.features.iter().flat_map(|f| &f.polygons).collect();
    let total = area_properties(&all);
    if all.is_empty() {
        warnings.push("no polygons: nothing to measure".to_string());
    } else if total.centroid.is_none() {
        warnings.push("the area is zero: centroid and moments are undefined".to_string());
    }
    AreaReport {
        file: file.to_string(),
        format: polygons.format.name(),
        polygons: all.len(),
        area: total.area,
        perimeter: total.perimeter,
        centroid: total.centroid,
        inertia: inertia(&total),
        rings,
        features: many.then_some(features),
        warnings,
    }
}

fn point(p: [f64; 2]) -> String {
    format!("({}, {})", p[0], p[1])
}

fn write_measures(
    s: &mut String,
    indent: &str,
    area: f64,
    perimeter: f64,
    centroid: Option<[f64; 2]>,
    inertia: &Option<InertiaReport>,
) {
    let _ = writeln!(s, "{indent}area       {area}");
    let _ = writeln!(s, "{indent}perimeter  {perimeter}");
    match (centroid, inertia) {
        (Some(c), Some(m)) => {
            let _ = writeln!(s, "{indent}centroid   {}", point(c));
            let _ = writeln!(
                s,
                "{indent}inertia    ix {}  iy {}  ixy {}  polar {}  (about the centroid)",
                m.ix, m.iy, m.ixy, m.polar
            );
            let _ = writeln!(
                s,
                "{indent}principal  {}, {}  (axis of the first at {}° from x)",
                m.principal[0], m.principal[1], m.principal_angle_degrees
            );
        }
        _ => {
            let _ = writeln!(s, "{indent}centroid   undefined (no area)");
        }
    }
}

/// The human-readable report.
pub fn text(r: &AreaReport) -> String {
    let mut s = String::new();
    let features = r.features.as_ref().map_or(1, Vec::len);
    let _ = writeln!(
        s,
        "{}: {}, {} feature{}, {} polygon{}, {} ring{}",
        r.file,
        r.format,
        features,
        if features == 1 { "" } else { "s" },
        r.polygons,
        if r.polygons == 1 { "" } else { "s" },
        r.rings.len(),
        if r.rings.len() == 1 { "" } else { "s" },
    );
    write_measures(&mut s, "  ", r.area, r.perimeter, r.centroid, &r.inertia);
    if let Some(features) = &r.features {
        for f in features {
            let name = f.name.as_ref().map(|n| format!(" ({n})")).unwrap_or_default();
            let _ = writeln!(s, "  feature {}{name}: {} polygon(s)", f.index, f.polygons);
            write_measures(&mut s, "    ", f.area, f.perimeter, f.centroid, &f.inertia);
        }
    }
    let _ = writeln!(s, "  rings (signed area: positive counter-clockwise):");
    for ring in &r.rings {
        let feature =
            if r.features.is_some() { format!("feature {} ", ring.feature) } else { String::new() };
        let _ = writeln!(
            s,
            "    {feature}polygon {} ring {}: {}, {} vertices, signed area {}, perimeter {}",
            ring.polygon, ring.ring, ring.role, ring.vertices, ring.signed_area, ring.perimeter
        );
    }
    s
}

/// Runs `meshvol area`.
pub fn run(args: AreaArgs, quiet: bool) -> ExitCode {
    let mut failed = false;
    let mut stdout = std::io::stdout().lock();
    for path in &args.files {
        match measure(path) {
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

fn measure(path: &Path) -> Result<AreaReport, String> {
    let polygons = read_polygons(path).map_err(|e| e.to_string())?;
    let mut r = report(&path.display().to_string(), &polygons);
    overflow(&mut r, &polygons)?;
    Ok(r)
}

/// An area or perimeter that is not finite is an error (f64 cannot hold it; JSON would
/// print null); a centroid or second moments that overflow where the area does not are
/// left out with a warning.
fn overflow(r: &mut AreaReport, polygons: &PolygonFile) -> Result<(), String> {
    let largest = |f: &meshvol_io::PolygonFeature| {
        f.polygons
            .iter()
            .flat_map(|p| p.rings())
            .flatten()
            .fold(0.0f64, |m, q| m.max(q[0].abs()).max(q[1].abs()))
    };
    let all = polygons.features.iter().map(largest).fold(0.0f64, f64::max);
    let many = r.features.is_some();
    let mut measures = vec![(None, r.area, r.perimeter, &mut r.centroid, &mut r.inertia, all)];
    for (f, feature) in r.features.iter_mut().flatten().zip(&polygons.features) {
        let at = many.then_some(f.index);
        measures.push((at, f.area, f.perimeter, &mut f.centroid, &mut f.inertia, largest(feature)));
    }
    let mut warnings = Vec::new();
    // Features first, so the message names the one that overflows.
    for (at, area, perimeter, centroid, inertia, m) in measures.into_iter().rev() {
        let which = at.map(|i| format!("feature {i}: ")).unwrap_or_default();
        if !area.is_finite() || !perimeter.is_finite() {
            return Err(format!(
                "{}: {which}the area overflows f64: coordinates up to {m:e} give an area or \
                 perimeter beyond {:e}; rescale the coordinates (e.g. to larger units)",
                r.file,
                f64::MAX
            ));
        }
        let moments = inertia.as_ref().is_some_and(|i| {
            [i.ix, i.iy, i.ixy, i.polar, i.principal_angle_degrees]
                .iter()
                .chain(&i.principal)
                .any(|x| !x.is_finite())
        });
        if centroid.is_some_and(|c| !c[0].is_finite() || !c[1].is_finite()) || moments {
            *centroid = centroid.filter(|c| c[0].is_finite() && c[1].is_finite());
            *inertia = None;
            warnings.push(format!(
                "{which}the second moments overflow f64 (coordinates up to {m:e}): left out"
            ));
        }
    }
    r.warnings.extend(warnings);
    Ok(())
}
