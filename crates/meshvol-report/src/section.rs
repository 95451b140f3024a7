//! `section`: the cross-section of an input's solid by a plane, its area and moments.

use crate::quantities::{Converter, Dimension::*, Quantities};
use std::fmt::Write as _;

use crate::area::InertiaReport;
use crate::number::{count, num, vector};
use crate::subject::Subject;
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::polygon::{area_properties, Polygon};
use meshvol::section::{section as kernel, Plane, PlaneFrame};
use meshvol::Surface;
use serde::Serialize;

#[derive(Clone, Debug, Serialize)]
pub struct PlaneReport {
    /// A point of the plane: the 2D origin.
    pub origin: [f64; 3],
    pub normal: [f64; 3],
    /// The 3D directions of the 2D coordinates' axes: (s, t) is origin + s·u + t·v.
    pub u: [f64; 3],
    pub v: [f64; 3],
}

/// The report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct SectionReport {
    pub file: Option<String>,
    pub format: Option<&'static str>,
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
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

impl SectionReport {
    /// The properties of the section's GeoJSON Feature (`--geojson`, `--out *.geojson`):
    /// the file, the area in the report's units, and the plane.
    pub fn geojson_properties(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut properties = serde_json::Map::new();
        properties.insert("file".into(), self.file.clone().into());
        properties.insert("area".into(), self.area.into());
        if let Ok(plane) = serde_json::to_value(&self.plane) {
            properties.insert("plane".into(), plane);
        }
        properties
    }
}

fn plane_report(f: &PlaneFrame) -> PlaneReport {
    PlaneReport { origin: f.origin, normal: f.normal, u: f.u, v: f.v }
}

/// Cuts an input's solid by `plane`: the report and the section's polygons (in the
/// plane's 2D coordinates).
pub fn section<S: Surface>(
    subject: &Subject<'_, S>,
    plane: &Plane,
) -> (SectionReport, Vec<Polygon>) {
    let cut = kernel(&subject.measured(), plane);
    let props = area_properties(&cut.polygons);
    let frame = plane.frame();
    let mut warnings = subject.warnings();
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
        file: subject.source.file.clone(),
        format: subject.source.format,
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
        units: None,
        mass: None,
        warnings,
    };
    (report, cut.polygons)
}

impl Report for SectionReport {
    crate::file_and_warnings!("mesh");

    fn text(&self) -> String {
        let r = self;
        let mut s = String::new();
        let p = &r.plane;
        let _ = writeln!(
            s,
            "{}: {}, section by the plane through {} with normal {}",
            self.file(),
            r.format.unwrap_or("arrays"),
            vector(p.origin, 15),
            vector(p.normal, 15)
        );
        let _ = writeln!(s, "  2D axes    u {}, v {}", vector(p.u, 15), vector(p.v, 15));
        let _ = writeln!(
            s,
            "  outline    {}, {}, from {} of {}",
            count(r.polygons, "polygon", "polygons"),
            count(r.holes, "hole", "holes"),
            count(r.loops, "loop", "loops"),
            count(r.segments, "segment", "segments")
        );
        let _ = writeln!(s, "  area       {}", num(r.area, 15));
        let _ = writeln!(s, "  perimeter  {}", num(r.perimeter, 15));
        match (&r.centroid, &r.centroid_3d, &r.inertia) {
            (Some(c), Some(c3), Some(m)) => {
                let _ = writeln!(
                    s,
                    "  centroid   ({}, {}) in the plane, {} in space",
                    num(c[0], 15),
                    num(c[1], 15),
                    vector(*c3, 15)
                );
                let _ = writeln!(
                    s,
                    "  inertia    iu {}  iv {}  iuv {}  polar {}  (about the centroid)",
                    num(m.ix, 15),
                    num(m.iy, 15),
                    num(m.ixy, 15),
                    num(m.polar, 15)
                );
            }
            _ => {
                let _ = writeln!(s, "  centroid   undefined (no area)");
            }
        }
        s.push_str(&crate::units::units_text(&self.units, &self.mass));
        s
    }
}

impl Quantities for SectionReport {
    fn convert(&mut self, to: &Converter) {
        to.all(Length, &mut self.plane.origin);
        to.one(Area, &mut self.area);
        to.one(Area, &mut self.signed_area);
        to.one(Length, &mut self.perimeter);
        to.point(&mut self.centroid);
        to.point(&mut self.centroid_3d);
        if let Some(i) = &mut self.inertia {
            i.convert(to);
        }
    }

    /// With a density per area, the mass of a sheet of the section's outline.
    fn mass_basis(&self) -> f64 {
        self.area
    }

    crate::unit_slots!();
}
