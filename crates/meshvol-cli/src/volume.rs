//! `meshvol volume`: mass properties of each file, as text or one JSON object per line.

use crate::check::CheckReport;
use crate::solid::Input;
use crate::units::{UnitNames, UnitsArg};
use meshvol::accumulate::UNIT_ROUNDOFF;
use meshvol::{exact_signed_volume, mass_properties, FaceRange, MassProperties, Surface};
use meshvol_io::Loaded;
use serde::Serialize;
use std::fmt::Write;

/// Options of `meshvol volume` that shape a report.
#[derive(Clone, Copy, Debug)]
pub struct VolumeOptions {
    pub density: f64,
    /// `--units`, resolved per file against the unit the file declares.
    pub units: Option<UnitsArg>,
    pub exact: bool,
}

#[derive(Debug, Serialize)]
pub struct BoundsReport {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

/// One file's report. Field names are the JSON keys: a public contract.
#[derive(Debug, Serialize)]
pub struct VolumeReport {
    pub file: String,
    pub format: String,
    /// What decided the format: `extension` or `content`.
    pub format_source: &'static str,
    pub vertices: usize,
    pub faces: usize,
    pub triangles: usize,
    pub volume: f64,
    pub signed_volume: f64,
    pub volume_error_bound: f64,
    /// True when `signed_volume` is the correctly rounded exact value (`--exact`).
    pub exact: bool,
    pub area: f64,
    pub centroid: Option<[f64; 3]>,
    pub inertia: [[f64; 3]; 3],
    pub principal_moments: [f64; 3],
    pub principal_axes: [[f64; 3]; 3],
    pub density: f64,
    pub mass: f64,
    pub bounds: Option<BoundsReport>,
    pub units: Option<UnitNames>,
    pub warnings: Vec<String>,
    /// The file's objects (solids, groups, 3MF items, glTF nodes), when it has two or
    /// more; the other keys hold the total.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub objects: Option<Vec<ObjectReport>>,
    /// Topology facts (absent with `--no-check`).
    #[serde(flatten)]
    pub check: Option<CheckReport>,
}

/// One object of a file, measured as wound (no topology check), in the report's units.
#[derive(Debug, Serialize)]
pub struct ObjectReport {
    pub name: String,
    /// Its faces in the file: `[first, end)`.
    pub faces: [usize; 2],
    pub triangles: usize,
    pub volume: f64,
    pub signed_volume: f64,
    pub area: f64,
    pub centroid: Option<[f64; 3]>,
}

/// Each object's properties, scaled by the length factor `f`.
fn objects(loaded: &Loaded, f: f64) -> Option<Vec<ObjectReport>> {
    if loaded.objects.is_empty() {
        return None;
    }
    let reports = loaded
        .objects
        .iter()
        .map(|o| {
            let mp = mass_properties(&FaceRange::new(&loaded.surface, o.faces.clone()));
            ObjectReport {
                name: o.name.clone(),
                faces: [o.faces.start, o.faces.end],
                triangles: mp.triangles,
                volume: mp.signed_volume.abs() * f * f * f,
                signed_volume: mp.signed_volume * f * f * f,
                area: mp.area * f * f,
                centroid: mp.centroid.map(|c| c.map(|x| x * f)),
            }
        })
        .collect();
    Some(reports)
}

fn measure<S: Surface + ?Sized>(surface: &S, exact: bool) -> Result<MassProperties, String> {
    let mut mp = mass_properties(surface);
    if exact {
        mp.signed_volume = exact_signed_volume(surface).map_err(|e| e.to_string())?;
        // Correctly rounded: within half an ulp.
        mp.volume_error_bound = UNIT_ROUNDOFF * mp.signed_volume.abs();
    }
    Ok(mp)
}

/// Measures a file's solid (or, unchecked, its surface as wound) and builds its report.
pub fn report(input: &Input, options: &VolumeOptions) -> Result<VolumeReport, String> {
    let (file, loaded) = (&input.name, &input.loaded);
    let exact = options.exact;
    let as_wound = measure(&loaded.surface, exact).map_err(|e| format!("{file}: {e}"))?;
    let mut warnings = input.warnings.clone();
    let (units, unit_warning) =
        crate::units::resolve(options.units, loaded.unit).map_err(|e| format!("{file}: {e}"))?;
    warnings.extend(unit_warning);
    // With a check, the properties are the solid's: shells turned outward, cavities
    // subtracted, degenerate and duplicate faces dropped, holes capped.
    let (mp, check) = match &input.check {
        None => (as_wound, None),
        Some(checked) => {
            let mp = if checked.repairs() == (0, 0, 0) {
                as_wound
            } else {
                measure(&input.surface(), exact).map_err(|e| format!("{file}: {e}"))?
            };
            (mp, Some(crate::check::report(checked)))
        }
    };
    warnings.extend(meshvol::topology::volume_warnings(input.check.as_ref(), &as_wound, &mp));

    let f = units.map_or(1.0, |u| u.length_factor());
    let (f2, f3) = (f * f, f * f * f);
    let rho = options.density;
    let signed_volume = as_wound.signed_volume * f3;
    let volume = mp.signed_volume.abs() * f3;
    // Converting rounds a few more times: widen the bound by that.
    let conversion = if f == 1.0 { 0.0 } else { 4.0 * UNIT_ROUNDOFF * volume };
    let inertia = mp.inertia.map(|row| row.map(|x| x * rho * f3 * f2));
    // Density times volume or second moments beyond f64 would print as null: refuse.
    let principal = mp.principal().moments.map(|x| x * rho * f3 * f2);
    let mut moments = inertia.iter().flatten().chain(&principal);
    if !(rho * volume).is_finite() || moments.any(|x| !x.is_finite()) {
        return Err(format!(
            "{file}: mass or inertia overflows f64 with density {rho:e} (volume {volume:e}): \
             use a smaller density or other units"
        ));
    }
    let check = check.map(|mut c| {
        c.solid_volume *= f3;
        c.volume_uncertainty *= f3;
        c.shell_details.iter_mut().for_each(|s| s.volume *= f3);
        c
    });
    let principal = mp.principal();
    Ok(VolumeReport {
        file: file.clone(),
        format: loaded.format.name().to_string(),
        format_source: loaded.format_source.name(),
        vertices: loaded.vertex_count(),
        faces: as_wound.faces,
        triangles: as_wound.triangles,
        volume,
        signed_volume,
        volume_error_bound: mp.volume_error_bound * f3 + conversion,
        exact,
        area: mp.area * f2,
        centroid: mp.centroid.map(|c| c.map(|x| x * f)),
        inertia,
        principal_moments: principal.moments.map(|x| x * rho * f3 * f2),
        principal_axes: principal.axes,
        density: rho,
        mass: rho * volume,
        bounds: mp
            .bounds
            .map(|b| BoundsReport { min: b.min.map(|x| x * f), max: b.max.map(|x| x * f) }),
        units: units.map(|u| u.names()),
        warnings,
        objects: objects(loaded, f),
        check,
    })
}

/// A number with `digits` significant digits, in plain notation where that is readable.
pub fn num(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let magnitude = x.abs().log10().floor() as i32;
    if (-4..12).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{x:.*e}", digits - 1)
    }
}

fn vector(v: [f64; 3]) -> String {
    format!("({}, {}, {})", num(v[0], 10), num(v[1], 10), num(v[2], 10))
}

/// The human-readable report.
pub fn text(r: &VolumeReport) -> String {
    let (len, area, vol) = match &r.units {
        Some(u) => (format!(" {}", u.length), format!(" {}", u.area), format!(" {}", u.volume)),
        None => Default::default(),
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{}: {}, {} faces ({} triangles), {} vertices",
        r.file, r.format, r.faces, r.triangles, r.vertices
    );
    let uncertain = r.check.as_ref().is_some_and(|c| c.volume_uncertainty > 0.0);
    let how = match (r.exact, uncertain) {
        (true, false) => "exact, correctly rounded".to_string(),
        // Exact arithmetic on a guessed surface: the caps' uncertainty dominates.
        (true, true) => "exact for the capped solid".to_string(),
        (false, _) => format!("± {}", num(r.volume_error_bound, 2)),
    };
    let _ = writeln!(s, "  volume             {}{vol}  ({how})", num(r.volume, 15));
    if r.signed_volume < 0.0 {
        let _ = writeln!(s, "  signed volume      {}{vol}", num(r.signed_volume, 15));
    }
    if let Some(c) = &r.check {
        let _ = writeln!(s, "  check              {}", c.verdict);
        if c.volume_uncertainty > 0.0 {
            let _ = writeln!(
                s,
                "  uncertainty        ± {}{vol} (from capping holes)",
                num(c.volume_uncertainty, 3)
            );
        }
    }
    let _ = writeln!(s, "  area               {}{area}", num(r.area, 15));
    if r.density != 1.0 {
        let _ = writeln!(s, "  mass               {}  (density {})", num(r.mass, 12), r.density);
    }
    match r.centroid {
        Some(c) => {
            let _ = writeln!(s, "  centroid           {}{len}", vector(c));
            let _ = writeln!(s, "  inertia about the centroid (density {}):", r.density);
            for row in r.inertia {
                let _ = writeln!(
                    s,
                    "    [{:>18} {:>18} {:>18}]",
                    num(row[0], 10),
                    num(row[1], 10),
                    num(row[2], 10)
                );
            }
            let m = r.principal_moments;
            let _ = writeln!(
                s,
                "  principal moments  {}, {}, {}",
                num(m[0], 10),
                num(m[1], 10),
                num(m[2], 10)
            );
            for (k, axis) in r.principal_axes.iter().enumerate() {
                let _ = writeln!(s, "  principal axis {}   {}", k + 1, vector(*axis));
            }
        }
        None => {
            let _ = writeln!(s, "  centroid           undefined");
        }
    }
    if let Some(b) = &r.bounds {
        let size = [0, 1, 2].map(|k| b.max[k] - b.min[k]);
        let _ = writeln!(s, "  bounds             {} to {}{len}", vector(b.min), vector(b.max));
        let _ = writeln!(s, "  size               {}{len}", vector(size));
    }
    if let Some(objects) = &r.objects {
        let width = objects.iter().map(|o| o.name.chars().count()).max().unwrap_or(0).max(4);
        let _ = writeln!(s, "  objects ({}, measured as wound):", objects.len());
        let _ = writeln!(
            s,
            "    {:<width$}  {:>9}  {:>18}  {:>18}  centroid{len}",
            "name",
            "triangles",
            format!("volume{vol}"),
            format!("area{area}")
        );
        for o in objects {
            let centroid = o.centroid.map_or("undefined".to_string(), vector);
            let _ = writeln!(
                s,
                "    {:<width$}  {:>9}  {:>18}  {:>18}  {centroid}",
                o.name,
                o.triangles,
                num(o.signed_volume, 10),
                num(o.area, 10)
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::num;

    #[test]
    fn numbers_read_well() {
        assert_eq!(num(1.0, 15), "1");
        assert_eq!(num(12345.678901234567, 10), "12345.6789"); // trailing zeros trimmed
        assert_eq!(num(-0.5, 10), "-0.5");
        assert_eq!(num(1.5e-9, 2), "1.5e-9");
        assert_eq!(num(2.5e13, 3), "2.50e13");
    }
}
