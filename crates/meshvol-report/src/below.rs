//! `below`: the part of an input's solid under a plane (hydrostatics: displaced volume,
//! centre of buoyancy, waterplane, wetted area), the plane given, or found from the
//! volume it must hold; turned by heel and trim.

use crate::number::{num, vector};
use crate::quantities::{Converter, Dimension::*, Quantities};
use crate::subject::Subject;
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::below::{below as kernel, level_for_volume};
use meshvol::section::Plane;
use meshvol::Surface;
use serde::Serialize;
use std::fmt::Write;

/// Where the plane is.
#[derive(Clone, Copy, Debug)]
pub enum Waterline {
    /// n·x ≤ d.
    Plane { normal: [f64; 3], d: f64 },
    /// The level along `direction` that leaves `volume` below.
    Volume { direction: [f64; 3], volume: f64 },
}

/// The plane, and how it is turned: the normal (or direction) is turned by `heel`
/// degrees about x, then by `trim` degrees about y.
#[derive(Clone, Copy, Debug)]
pub struct BelowOptions {
    pub waterline: Waterline,
    pub heel: f64,
    pub trim: f64,
}

/// The report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct BelowReport {
    pub file: Option<String>,
    /// The plane's unit normal (after heel and trim); the part is where normal·x ≤ level.
    pub normal: [f64; 3],
    pub level: f64,
    pub volume: f64,
    /// The part's centroid (centre of buoyancy); null when it has no volume.
    pub centroid: Option<[f64; 3]>,
    /// The area of the solid's surface below the plane.
    pub wetted_area: f64,
    /// The area of the solid's section by the plane (waterplane area), and its centroid.
    pub section_area: f64,
    pub section_centroid: Option<[f64; 3]>,
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

/// `v` turned by `heel` degrees about x, then `trim` degrees about y.
fn turned(v: [f64; 3], heel: f64, trim: f64) -> [f64; 3] {
    let (sh, ch) = heel.to_radians().sin_cos();
    let (st, ct) = trim.to_radians().sin_cos();
    let x = [v[0], ch * v[1] - sh * v[2], sh * v[1] + ch * v[2]];
    [ct * x[0] + st * x[2], x[1], -st * x[0] + ct * x[2]]
}

/// The part of an input's solid below the plane `options` describe.
pub fn below<S: Surface>(
    subject: &Subject<'_, S>,
    options: &BelowOptions,
) -> Result<BelowReport, String> {
    let name = subject.source.name();
    let solid = subject.measured();
    let unit = |v: [f64; 3]| {
        let length = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if length.is_finite() && length > 0.0 {
            Ok((v.map(|x| x / length), length))
        } else {
            Err(format!("the plane's normal must be a finite, non-zero vector; got {v:?}"))
        }
    };
    let (normal, level) = match options.waterline {
        Waterline::Plane { normal, d } => {
            let (n, length) = unit(turned(normal, options.heel, options.trim))?;
            (n, d / length)
        }
        Waterline::Volume { direction, volume } => {
            let (n, _) = unit(turned(direction, options.heel, options.trim))?;
            (n, level_for_volume(&solid, n, volume).map_err(|e| format!("{name}: {e}"))?)
        }
    };
    let plane =
        Plane::new(normal.map(|x| x * level), normal).map_err(|e| format!("{name}: {e}"))?;
    let part = kernel(&solid, &plane);
    let mut warnings = subject.warnings();
    if part.part.signed_volume < 0.0 {
        warnings.push(
            "the volume below is negative: the faces are wound inward (clockwise seen from \
             outside)"
                .to_string(),
        );
    }
    Ok(BelowReport {
        file: subject.source.file.clone(),
        normal,
        level,
        volume: part.part.signed_volume,
        centroid: part.part.centroid,
        wetted_area: part.part.area,
        section_area: part.section_area,
        section_centroid: part.section_centroid,
        units: None,
        mass: None,
        warnings,
    })
}

impl Report for BelowReport {
    crate::file_and_warnings!("mesh");

    fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}: below the plane {}·x = {}",
            self.file(),
            vector(self.normal, 10),
            num(self.level, 15)
        );
        let _ = writeln!(s, "  volume             {}", num(self.volume, 15));
        let centroid = self.centroid.map_or("undefined".to_string(), |c| vector(c, 12));
        let _ = writeln!(s, "  centroid           {centroid}  (centre of buoyancy)");
        let _ = writeln!(s, "  wetted area        {}", num(self.wetted_area, 15));
        let _ = writeln!(s, "  section area       {}  (waterplane)", num(self.section_area, 15));
        if let Some(c) = self.section_centroid {
            let _ = writeln!(s, "  section centroid   {}", vector(c, 12));
        }
        s.push_str(&crate::units::units_text(&self.units, &self.mass));
        s
    }
}

impl Quantities for BelowReport {
    fn convert(&mut self, to: &Converter) {
        to.one(Length, &mut self.level);
        to.one(Volume, &mut self.volume);
        to.point(&mut self.centroid);
        to.one(Area, &mut self.wetted_area);
        to.one(Area, &mut self.section_area);
        to.point(&mut self.section_centroid);
    }

    fn mass_basis(&self) -> f64 {
        self.volume
    }

    crate::unit_slots!();
}

#[cfg(test)]
mod tests {
    use super::turned;

    #[test]
    fn heel_and_trim_turn_the_normal() {
        let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15);
        let s = 30f64.to_radians().sin();
        let c = 30f64.to_radians().cos();
        assert!(close(turned([0.0, 0.0, 1.0], 30.0, 0.0), [0.0, -s, c]));
        assert!(close(turned([0.0, 0.0, 1.0], 0.0, 30.0), [s, 0.0, c]));
    }
}
