//! `volume`: mass properties of an input's solid, in the units asked for.
//!
//! Unit conversion scales lengths by f, areas by f², volumes by f³ and second moments by
//! f⁵ (and density); each scaling rounds once more, so the volume's error bound widens by
//! 4 units of roundoff of the volume.

use crate::check::CheckFacts;
use crate::number::{num, vector};
use crate::quantities::Converter;
use crate::subject::Subject;
use crate::units::{Density, Scale, UnitNames, UnitOptions, UnitsArg};
use crate::Report;
use meshvol::accumulate::UNIT_ROUNDOFF;
use meshvol::surface::FaceRange;
use meshvol::{exact_signed_volume, mass_properties, MassProperties, Surface};
use serde::Serialize;
use std::fmt::Write;

/// What shapes a volume report besides the input.
#[derive(Clone, Copy, Debug)]
pub struct VolumeOptions {
    /// Mass per reported volume unit, or with a unit (`7.85g/cm3`); must be positive and
    /// finite.
    pub density: Density,
    /// `--units`, resolved per input against the unit its file declares.
    pub units: Option<UnitsArg>,
    /// The correctly rounded exact signed volume (exact arithmetic).
    pub exact: bool,
}

impl Default for VolumeOptions {
    fn default() -> Self {
        VolumeOptions { density: Density::plain(1.0), units: None, exact: false }
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct BoundsReport {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

/// One input's report. Field names are the JSON keys: a public contract.
#[derive(Clone, Debug, Serialize)]
pub struct VolumeReport {
    pub file: Option<String>,
    pub format: Option<&'static str>,
    /// What decided the format: `extension` or `content`.
    pub format_source: Option<&'static str>,
    pub vertices: usize,
    pub faces: usize,
    pub triangles: usize,
    pub volume: f64,
    pub signed_volume: f64,
    pub volume_error_bound: f64,
    /// True when `signed_volume` is the correctly rounded exact value.
    pub exact: bool,
    /// The surface's own area (caps over holes left out).
    pub area: f64,
    /// The area of the caps the check put over holes (0 without): with `area`, the
    /// area of the solid's boundary, which `volume`, the centroid and the grid measure.
    pub cap_area: f64,
    pub centroid: Option<[f64; 3]>,
    pub inertia: [[f64; 3]; 3],
    pub principal_moments: [f64; 3],
    pub principal_axes: [[f64; 3]; 3],
    pub density: f64,
    /// The density's unit as given (`g/cm^3`), or null: mass per reported volume unit.
    pub density_unit: Option<String>,
    pub mass: f64,
    /// The mass's unit (the density's: `g`), or null.
    pub mass_unit: Option<String>,
    pub bounds: Option<BoundsReport>,
    pub units: Option<UnitNames>,
    pub warnings: Vec<String>,
    /// The file's objects (solids, groups, 3MF items, glTF nodes), when it has two or
    /// more; the other keys hold the total.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub objects: Option<Vec<ObjectReport>>,
    /// Topology facts (absent unchecked).
    #[serde(flatten)]
    pub check: Option<CheckFacts>,
}

/// One object of a file, measured as wound (no topology check), in the report's units.
#[derive(Clone, Debug, Serialize)]
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
fn objects<S: Surface>(subject: &Subject<'_, S>, scale: &Scale) -> Option<Vec<ObjectReport>> {
    let objects = &subject.source.objects;
    if objects.is_empty() {
        return None;
    }
    let reports = objects
        .iter()
        .map(|o| {
            let mp = mass_properties(&FaceRange::new(subject.surface, o.faces.clone()));
            ObjectReport {
                name: o.name.clone(),
                faces: [o.faces.start, o.faces.end],
                triangles: mp.triangles,
                volume: scale.volume(mp.signed_volume.abs()),
                signed_volume: scale.volume(mp.signed_volume),
                area: scale.area(mp.area),
                centroid: mp.centroid.map(|c| scale.point(c)),
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

/// The message for a surface without faces.
pub const NO_FACES: &str = "no faces: there is no surface to measure";

/// Measures an input's solid (or, unchecked, its surface as wound) and builds its report.
/// Errors name the input.
pub fn volume<S: Surface>(
    subject: &Subject<'_, S>,
    options: &VolumeOptions,
) -> Result<VolumeReport, String> {
    let name = subject.source.name();
    options.density.validate()?;
    if subject.surface.face_count() == 0 {
        return Err(format!("{name}: {NO_FACES}"));
    }
    let exact = options.exact;
    // Checked, as wound with what the check proved: a closed, consistently oriented,
    // exactly welded surface skips the move to the origin (its vector area is zero).
    let as_wound = match subject.check {
        Some(checked) => measure(&checked.as_wound(subject.surface), exact),
        None => measure(subject.surface, exact),
    }
    .map_err(|e| format!("{name}: {e}"))?;
    let mut warnings = subject.warnings();
    let unit_options = UnitOptions { units: options.units, density: Some(options.density) };
    let (scale, unit_warning) =
        Scale::resolve(&unit_options, subject.source.unit).map_err(|e| format!("{name}: {e}"))?;
    // Mass per reported volume unit, in the density's mass unit.
    let rho = scale.density();
    warnings.extend(unit_warning);
    // Checked, the properties are the solid's: shells turned outward, cavities
    // subtracted, degenerate and duplicate faces dropped, holes capped.
    let mp = match subject.check {
        Some(checked) if checked.repairs() != (0, 0, 0) => {
            measure(&subject.measured(), exact).map_err(|e| format!("{name}: {e}"))?
        }
        _ => as_wound,
    };
    warnings.extend(meshvol::topology::volume_warnings(subject.check, &as_wound, &mp));
    // The area is the surface's own: caps close its holes for the volume, but are no
    // part of it (a flat open sheet has its own area, not twice it). Their area is
    // reported beside it: the solid's boundary, which the grid's cut cells integrate,
    // is both.
    let (area, cap_area) = match subject.check {
        Some(checked) if checked.repairs().2 > 0 => {
            let solid = checked.solid(subject.surface);
            let kept = solid.surface_faces();
            let part = |faces| mass_properties(&FaceRange::new(&solid, faces)).area;
            (part(0..kept), part(kept..solid.face_count()))
        }
        _ => (mp.area, 0.0),
    };

    let f = scale.length(1.0);
    let volume = scale.volume(mp.signed_volume.abs());
    // Converting rounds a few more times: widen the bound by that.
    let conversion = if scale.converts() { 4.0 * UNIT_ROUNDOFF * volume } else { 0.0 };
    let inertia = mp.inertia.map(|row| row.map(|x| scale.volume_moment(x) * rho));
    // Density times volume or second moments beyond f64 would print as null: refuse
    // (before the eigen-solver, which wants a finite tensor).
    if !(rho * volume).is_finite() || inertia.iter().flatten().any(|x| !x.is_finite()) {
        return Err(format!(
            "{name}: mass or inertia overflows f64 with density {rho:e} (volume {volume:e}): \
             use a smaller density or other units"
        ));
    }
    let principal = mp.principal();
    let principal_moments = principal.moments.map(|x| scale.volume_moment(x) * rho);
    if principal_moments.iter().any(|x| !x.is_finite()) {
        return Err(format!(
            "{name}: the principal moments overflow f64 with density {rho:e}: use a smaller \
             density or other units"
        ));
    }
    let check = subject.check.map(|c| {
        let mut facts = CheckFacts::of(c, subject.source);
        facts.convert(&Converter::new(&scale));
        facts
    });
    Ok(VolumeReport {
        file: subject.source.file.clone(),
        format: subject.source.format,
        format_source: subject.source.format_source,
        vertices: subject.source.vertices,
        faces: as_wound.faces,
        triangles: as_wound.triangles,
        volume,
        signed_volume: scale.volume(as_wound.signed_volume),
        volume_error_bound: scale.volume(mp.volume_error_bound) + conversion,
        exact,
        area: scale.area(area),
        cap_area: scale.area(cap_area),
        centroid: mp.centroid.map(|c| c.map(|x| x * f)),
        inertia,
        principal_moments,
        principal_axes: principal.axes,
        density: options.density.value,
        density_unit: options.density.unit_name(),
        mass: rho * volume,
        mass_unit: options.density.unit.map(|(m, _)| m.symbol.to_string()),
        bounds: mp
            .bounds
            .map(|b| BoundsReport { min: b.min.map(|x| x * f), max: b.max.map(|x| x * f) }),
        units: scale.names(),
        warnings,
        objects: objects(subject, &scale),
        check,
    })
}

impl Report for VolumeReport {
    crate::file_and_warnings!("mesh");

    fn text(&self) -> String {
        let r = self;
        let (len, area, vol) = match &r.units {
            Some(u) => (format!(" {}", u.length), format!(" {}", u.area), format!(" {}", u.volume)),
            None => Default::default(),
        };
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}: {}, {} ({}), {}",
            self.file(),
            r.format.unwrap_or("arrays"),
            crate::number::count(r.faces, "face", "faces"),
            crate::number::count(r.triangles, "triangle", "triangles"),
            crate::number::count(r.vertices, "vertex", "vertices")
        );
        let uncertain = r.check.as_ref().is_some_and(|c| c.volume_uncertainty > 0.0);
        let how = match (r.exact, uncertain) {
            (true, false) => "exact, correctly rounded".to_string(),
            // Exact arithmetic on a guessed surface: the caps' uncertainty dominates.
            (true, true) => "exact for the capped solid".to_string(),
            (false, _) => format!("± {} rounding", num(r.volume_error_bound, 2)),
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
        if r.density != 1.0 || r.density_unit.is_some() {
            let mu = r.mass_unit.as_ref().map(|u| format!(" {u}")).unwrap_or_default();
            let du = r.density_unit.as_ref().map(|u| format!(" {u}")).unwrap_or_default();
            let _ = writeln!(
                s,
                "  mass               {}{mu}  (density {}{du})",
                num(r.mass, 12),
                num(r.density, 15)
            );
        }
        match r.centroid {
            Some(c) => {
                let _ = writeln!(s, "  centroid           {}{len}", vector(c, 10));
                let _ =
                    writeln!(s, "  inertia about the centroid (density {}):", num(r.density, 15));
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
                    let _ = writeln!(s, "  principal axis {}   {}", k + 1, vector(*axis, 10));
                }
            }
            None => {
                let _ = writeln!(s, "  centroid           undefined");
            }
        }
        if let Some(b) = &r.bounds {
            let size = [0, 1, 2].map(|k| b.max[k] - b.min[k]);
            let _ = writeln!(
                s,
                "  bounds             {} to {}{len}",
                vector(b.min, 10),
                vector(b.max, 10)
            );
            let _ = writeln!(s, "  size               {}{len}", vector(size, 10));
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
                let centroid = o.centroid.map_or("undefined".to_string(), |c| vector(c, 10));
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
}
