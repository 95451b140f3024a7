//! `--density VALUE[UNIT]`: a mass per volume (or, for the commands that measure areas,
//! per area), with the mass units it knows.

use super::unit::{report_length, Unit, KNOWN_MASSES};
use std::str::FromStr;

/// A mass unit: its symbol and kilograms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassUnit {
    pub symbol: &'static str,
    pub kilograms: f64,
}

pub(super) fn mass_unit(s: &str) -> Option<MassUnit> {
    let (symbol, kilograms) = match s {
        "mg" => ("mg", 1e-6),
        "g" => ("g", 1e-3),
        "kg" => ("kg", 1.0),
        "t" | "tonne" => ("t", 1e3),
        "oz" => ("oz", 0.028349523125),
        "lb" | "lbs" => ("lb", 0.45359237),
        _ => return None,
    };
    Some(MassUnit { symbol, kilograms })
}

/// `--density VALUE[MASS/VOLUME]`: `2.5` (mass per reported volume unit), `7.85g/cm3`,
/// `7850kg/m3`, `62.4lb/ft3`, `1kg/L`. The commands that measure areas (`section`,
/// `area`) take a mass per area instead, `VALUE[MASS/AREA]` (`62.8kg/m2`: an 8 mm steel
/// plate; a bare number is per reported area unit), and report the mass of a sheet
/// with that outline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Density {
    pub value: f64,
    /// The mass and volume (or area) units, when given.
    pub unit: Option<(MassUnit, Unit)>,
    /// Whether the unit is a mass per area (`kg/m2`).
    pub per_area: bool,
}

impl Density {
    /// A density without a unit: mass per reported volume (or area) unit.
    pub fn plain(value: f64) -> Density {
        Density { value, unit: None, per_area: false }
    }

    /// The unit as written: `g/cm^3`, `kg/m^2`.
    pub fn unit_name(&self) -> Option<String> {
        self.unit
            .map(|(m, v)| format!("{}/{}", m.symbol, if self.per_area { v.area } else { v.volume }))
    }

    /// The density of a command that measures volumes: not a mass per area.
    pub fn of_volume(self) -> Result<Density, String> {
        if self.per_area {
            return Err(format!(
                "density {}{} is a mass per area; this command measures volumes: give a mass \
                 per volume, e.g. 7.85g/cm3 or 7850kg/m3",
                self.value,
                self.unit_name().unwrap_or_default()
            ));
        }
        Ok(self)
    }

    /// The density of a command that measures areas (`section`, `area`): a mass per area.
    pub fn of_area(self) -> Result<Density, String> {
        if self.unit.is_some() && !self.per_area {
            return Err(format!(
                "density {}{} is a mass per volume; this command measures areas: give a mass \
                 per area (a sheet's), e.g. 62.8kg/m2 or 0.785g/cm2",
                self.value,
                self.unit_name().unwrap_or_default()
            ));
        }
        Ok(Density { per_area: true, ..self })
    }

    /// Checks the value: positive and finite.
    pub fn validate(&self) -> Result<(), String> {
        if self.value.is_finite() && self.value > 0.0 {
            Ok(())
        } else {
            Err(format!("density must be a positive number; got {}", self.value))
        }
    }
}

impl FromStr for Density {
    type Err = String;
    fn from_str(s: &str) -> Result<Density, String> {
        let t = s.trim();
        // The longest prefix that is a number; the rest is the unit.
        let split = (1..=t.len())
            .rev()
            .filter(|&i| t.is_char_boundary(i))
            .find(|&i| t[..i].parse::<f64>().is_ok())
            .ok_or_else(|| format!("'{s}': expected a number, e.g. 2.5, 7.85g/cm3 or 7850kg/m3"))?;
        let value: f64 = t[..split].parse().map_err(|_| format!("'{s}': not a number"))?;
        let rest = t[split..].trim();
        let mut per_area = false;
        let unit = if rest.is_empty() {
            None
        } else {
            let (mass, volume) = rest.split_once('/').ok_or_else(|| {
                format!(
                    "'{s}': a density's unit is MASS/VOLUME, e.g. g/cm3 or kg/m3 (MASS/AREA, \
                     e.g. kg/m2, for section and area)"
                )
            })?;
            let mass = mass_unit(mass.trim()).ok_or_else(|| {
                format!("'{s}': unknown mass unit '{mass}': known units are {KNOWN_MASSES}")
            })?;
            let per = volume.trim();
            // A length squared is an area: kg/m2, g/cm^2, lb/ft².
            let squared = ["^2", "²", "2"].iter().find_map(|suffix| per.strip_suffix(suffix));
            match squared.and_then(report_length) {
                Some(area) => {
                    per_area = true;
                    Some((mass, area))
                }
                None => {
                    let volume: Unit = per.parse().map_err(|e| format!("'{s}': {e}"))?;
                    Some((mass, volume))
                }
            }
        };
        let density = Density { value, unit, per_area };
        density.validate().map_err(|e| format!("'{s}': {e}"))?;
        Ok(density)
    }
}
