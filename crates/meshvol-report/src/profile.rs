//! `profile`: the volume below each level along an axis, each slab's volume and the
//! section area at each level (a strapping table).

use crate::number::num;
use crate::quantities::{Converter, Dimension::*, Quantities};
use crate::subject::Subject;
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::grid::{profile as kernel, Axis, Levels};
use meshvol::Surface;
use serde::Serialize;
use std::fmt::Write;

/// The report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct ProfileReport {
    pub file: Option<String>,
    /// `x`, `y` or `z`.
    pub axis: &'static str,
    pub levels: Vec<f64>,
    pub volume_below: Vec<f64>,
    /// The volume between each level and the next (one fewer than the levels).
    pub slab_volume: Vec<f64>,
    pub section_area: Vec<f64>,
    /// The reader's warnings and the reasons to doubt the solid.
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

/// The profile of an input's solid along `axis`.
pub fn profile<S: Surface>(
    subject: &Subject<'_, S>,
    axis: Axis,
    levels: Levels,
) -> Result<ProfileReport, String> {
    let name = subject.source.name();
    if subject.surface.face_count() == 0 {
        return Err(format!("{name}: {}", crate::volume::NO_FACES));
    }
    let p = kernel(&subject.measured(), axis, levels).map_err(|e| format!("{name}: {e}"))?;
    let mut warnings = subject.warnings();
    if p.volume_below.last().is_some_and(|&v| v < 0.0) {
        warnings.push(
            "volumes are negative: the faces are wound inward (clockwise seen from outside)"
                .to_string(),
        );
    }
    Ok(ProfileReport {
        file: subject.source.file.clone(),
        axis: p.axis.name(),
        levels: p.levels,
        volume_below: p.volume_below,
        slab_volume: p.slab_volume,
        section_area: p.section_area,
        units: None,
        mass: None,
        warnings,
    })
}

impl ProfileReport {
    /// `level,volume_below,slab_volume,section_area`, every digit; the last level has no
    /// slab above it.
    pub fn csv(&self) -> String {
        let mut s = String::from("level,volume_below,slab_volume,section_area\n");
        for (k, level) in self.levels.iter().enumerate() {
            let slab = self.slab_volume.get(k).map(|v| format!("{v:?}")).unwrap_or_default();
            let _ = writeln!(
                s,
                "{level:?},{:?},{slab},{:?}",
                self.volume_below[k], self.section_area[k]
            );
        }
        s
    }
}

impl Report for ProfileReport {
    crate::file_and_warnings!("mesh");

    fn text(&self) -> String {
        let mut s = String::new();
        let axis = self.axis;
        let _ = writeln!(
            s,
            "{}: profile along {axis}, {}",
            self.file(),
            crate::number::count(self.levels.len(), "level", "levels")
        );
        let _ = writeln!(
            s,
            "  {:>22}  {:>22}  {:>22}  {:>22}",
            axis, "volume below", "slab volume (to next)", "section area"
        );
        for (k, level) in self.levels.iter().enumerate() {
            let slab = self.slab_volume.get(k).map(|&v| num(v, 15)).unwrap_or_default();
            let _ = writeln!(
                s,
                "  {:>22}  {:>22}  {:>22}  {:>22}",
                num(*level, 15),
                num(self.volume_below[k], 15),
                slab,
                num(self.section_area[k], 15)
            );
        }
        s.push_str(&crate::units::units_text(&self.units, &self.mass));
        s
    }
}

impl Quantities for ProfileReport {
    fn convert(&mut self, to: &Converter) {
        to.all(Length, &mut self.levels);
        to.all(Volume, &mut self.volume_below);
        to.all(Volume, &mut self.slab_volume);
        to.all(Area, &mut self.section_area);
    }

    /// The whole solid's.
    fn mass_basis(&self) -> f64 {
        self.volume_below.last().copied().unwrap_or(0.0)
    }

    crate::unit_slots!();
}
