//! `hull`: volume, area and centroid of the convex hull of a point cloud.

use crate::quantities::{Converter, Dimension::*, Quantities};
use std::fmt::Write as _;

use crate::number::{num, vector};
use crate::units::{Mass, UnitNames};
use crate::written::WrittenReport;
use crate::Report;
use meshvol::hull::Hull;
use meshvol::Mesh;
use serde::Serialize;

/// One file's report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct HullReport {
    pub file: Option<String>,
    pub format: Option<&'static str>,
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
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
    /// The hull as written by `--out`, read back and measured (absent without `--out`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub written: Option<WrittenReport>,
}

impl HullReport {
    /// The report with the hull's mesh `written` to a file (and its warning when the file
    /// is not the hull).
    pub fn with_written(mut self, written: WrittenReport) -> HullReport {
        self.warnings.extend(written.warning());
        self.written = Some(written);
        self
    }
}

/// The report of `hull`, the hull of `points` points of the file named `file` in the
/// format `format` (both `None` for arrays), with the reader's `warnings`.
pub fn hull(
    file: Option<String>,
    format: Option<&'static str>,
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
        file,
        format,
        points,
        hull_vertices: mesh.map_or(0, Mesh::vertex_count),
        hull_faces: mesh.map_or(0, Mesh::face_count),
        volume: hull.volume(),
        volume_error_bound: hull.properties.volume_error_bound,
        area: hull.properties.area,
        centroid: hull.properties.centroid,
        degenerate,
        units: None,
        mass: None,
        warnings,
        written: None,
    }
}

impl Report for HullReport {
    crate::file_and_warnings!("points");

    fn text(&self) -> String {
        let r = self;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}: {}, {}",
            self.file(),
            r.format.unwrap_or("arrays"),
            crate::number::count(r.points, "point", "points")
        );
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
                let _ = writeln!(
                    s,
                    "  volume     {}  (± {})",
                    num(r.volume, 15),
                    num(r.volume_error_bound, 2)
                );
                let _ = writeln!(s, "  area       {}", num(r.area, 15));
                if let Some(c) = r.centroid {
                    let _ = writeln!(s, "  centroid   {}", vector(c, 15));
                }
                if let Some(w) = &r.written {
                    let _ = writeln!(s, "  written    {}", w.text());
                }
            }
        }
        s.push_str(&crate::units::units_text(&self.units, &self.mass));
        s
    }
}

impl Quantities for HullReport {
    fn convert(&mut self, to: &Converter) {
        to.one(Volume, &mut self.volume);
        to.one(Volume, &mut self.volume_error_bound);
        to.one(Area, &mut self.area);
        to.point(&mut self.centroid);
    }

    fn mass_basis(&self) -> f64 {
        self.volume
    }

    crate::unit_slots!();
}
