//! `area`: area, perimeter, centroid and second moments of polygons, per feature and in
//! total, with the checks that say whether those numbers mean what they seem to. The 2D
//! second moments ([`InertiaReport`]) have this one shape wherever they are reported
//! (`area`, `section`).

use crate::quantities::{Converter, Dimension::*, Quantities};
use std::fmt::Write as _;

use crate::number::{count, num};
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::polygon::{
    area_properties, polygon_issues, AreaProperties, Polygon, RingRole, SecondMoments,
};
use meshvol_io::PolygonFeature;
use serde::Serialize;

/// Second moments about the centroid, and the principal ones.
#[derive(Clone, Copy, Debug, Default, Serialize)]
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

#[derive(Clone, Debug, Serialize)]
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

#[derive(Clone, Debug, Serialize)]
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
#[derive(Clone, Debug, Serialize)]
pub struct AreaReport {
    pub file: Option<String>,
    pub format: Option<&'static str>,
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
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

fn inertia(p: &AreaProperties) -> Option<InertiaReport> {
    p.centroid.map(|_| p.inertia.into())
}

/// Measures polygons: `features` of the file named `file` in the format `format` (both
/// `None` for arrays), with the reader's `warnings`. An area or perimeter beyond f64 is
/// an error naming the file.
pub fn area(
    file: Option<String>,
    format: Option<&'static str>,
    features: &[PolygonFeature],
    warnings: Vec<String>,
) -> Result<AreaReport, String> {
    let mut r = measure(file, format, features, warnings);
    overflow(&mut r, features)?;
    Ok(r)
}

fn measure(
    file: Option<String>,
    format: Option<&'static str>,
    features_in: &[PolygonFeature],
    mut warnings: Vec<String>,
) -> AreaReport {
    let many = features_in.len() > 1;
    let mut rings = Vec::new();
    let mut features = Vec::new();
    for (index, feature) in features_in.iter().enumerate() {
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
    let all: Vec<&Polygon> = features_in.iter().flat_map(|f| &f.polygons).collect();
    let total = area_properties(&all);
    if all.is_empty() {
        warnings.push("no polygons: nothing to measure".to_string());
    } else if total.centroid.is_none() {
        warnings.push("the area is zero: centroid and moments are undefined".to_string());
    }
    AreaReport {
        file,
        format,
        polygons: all.len(),
        area: total.area,
        perimeter: total.perimeter,
        centroid: total.centroid,
        inertia: inertia(&total),
        rings,
        features: many.then_some(features),
        units: None,
        mass: None,
        warnings,
    }
}

fn point(p: [f64; 2]) -> String {
    format!("({}, {})", num(p[0], 15), num(p[1], 15))
}

fn write_measures(
    s: &mut String,
    indent: &str,
    area: f64,
    perimeter: f64,
    centroid: Option<[f64; 2]>,
    inertia: &Option<InertiaReport>,
) {
    let _ = writeln!(s, "{indent}area       {}", num(area, 15));
    let _ = writeln!(s, "{indent}perimeter  {}", num(perimeter, 15));
    match (centroid, inertia) {
        (Some(c), Some(m)) => {
            let _ = writeln!(s, "{indent}centroid   {}", point(c));
            let _ = writeln!(
                s,
                "{indent}inertia    ix {}  iy {}  ixy {}  polar {}  (about the centroid)",
                num(m.ix, 15),
                num(m.iy, 15),
                num(m.ixy, 15),
                num(m.polar, 15)
            );
            let _ = writeln!(
                s,
                "{indent}principal  {}, {}  (axis of the first at {}° from x)",
                num(m.principal[0], 15),
                num(m.principal[1], 15),
                num(m.principal_angle_degrees, 15)
            );
        }
        _ => {
            let _ = writeln!(s, "{indent}centroid   undefined (no area)");
        }
    }
}

impl Report for AreaReport {
    crate::file_and_warnings!("polygons");

    fn text(&self) -> String {
        let r = self;
        let mut s = String::new();
        let features = r.features.as_ref().map_or(1, Vec::len);
        let _ = writeln!(
            s,
            "{}: {}, {}, {}, {}",
            self.file(),
            r.format.unwrap_or("arrays"),
            count(features, "feature", "features"),
            count(r.polygons, "polygon", "polygons"),
            count(r.rings.len(), "ring", "rings"),
        );
        write_measures(&mut s, "  ", r.area, r.perimeter, r.centroid, &r.inertia);
        if let Some(features) = &r.features {
            for f in features {
                let name = f.name.as_ref().map(|n| format!(" ({n})")).unwrap_or_default();
                let _ = writeln!(
                    s,
                    "  feature {}{name}: {}",
                    f.index,
                    count(f.polygons, "polygon", "polygons")
                );
                write_measures(&mut s, "    ", f.area, f.perimeter, f.centroid, &f.inertia);
            }
        }
        let _ = writeln!(s, "  rings (signed area: positive counter-clockwise):");
        for ring in &r.rings {
            let feature = if r.features.is_some() {
                format!("feature {} ", ring.feature)
            } else {
                String::new()
            };
            let _ = writeln!(
                s,
                "    {feature}polygon {} ring {}: {}, {}, signed area {}, perimeter {}",
                ring.polygon,
                ring.ring,
                ring.role,
                count(ring.vertices, "vertex", "vertices"),
                num(ring.signed_area, 15),
                num(ring.perimeter, 15)
            );
        }
        s.push_str(&crate::units::units_text(&self.units, &self.mass));
        s
    }
}

/// An area or perimeter that is not finite is an error (f64 cannot hold it; JSON would
/// print null); a centroid or second moments that overflow where the area does not are
/// left out with a warning.
fn overflow(r: &mut AreaReport, features: &[PolygonFeature]) -> Result<(), String> {
    let largest = |f: &PolygonFeature| {
        f.polygons
            .iter()
            .flat_map(|p| p.rings())
            .flatten()
            .fold(0.0f64, |m, q| m.max(q[0].abs()).max(q[1].abs()))
    };
    let all = features.iter().map(largest).fold(0.0f64, f64::max);
    let many = r.features.is_some();
    let mut measures = vec![(None, r.area, r.perimeter, &mut r.centroid, &mut r.inertia, all)];
    for (f, feature) in r.features.iter_mut().flatten().zip(features) {
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
                r.file.as_deref().unwrap_or("polygons"),
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

impl InertiaReport {
    /// The moments in reported units (area × length²).
    pub fn convert(&mut self, to: &Converter) {
        to.all(AreaMoment, [&mut self.ix, &mut self.iy, &mut self.ixy, &mut self.polar]);
        to.all(AreaMoment, &mut self.principal);
    }
}

impl Quantities for AreaReport {
    fn convert(&mut self, to: &Converter) {
        to.one(Area, &mut self.area);
        to.one(Length, &mut self.perimeter);
        to.point(&mut self.centroid);
        self.inertia.iter_mut().for_each(|i| i.convert(to));
        for r in &mut self.rings {
            to.one(Area, &mut r.signed_area);
            to.one(Length, &mut r.perimeter);
        }
        for f in self.features.iter_mut().flatten() {
            to.one(Area, &mut f.area);
            to.one(Length, &mut f.perimeter);
            to.point(&mut f.centroid);
            f.inertia.iter_mut().for_each(|i| i.convert(to));
        }
    }

    /// With a density per area, the mass of a sheet of the polygons' outline.
    fn mass_basis(&self) -> f64 {
        self.area
    }

    crate::unit_slots!();
}
