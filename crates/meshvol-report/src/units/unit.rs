//! A unit to report in ([`Unit`]): the lengths, areas and volumes `--units` knows by
//! name, below the files that convert with them (`mod.rs`, `density.rs`, `scale.rs`).

use meshvol_io::LengthUnit;
use std::str::FromStr;

/// The units `--units` and `--density` know, for error messages.
pub const KNOWN_UNITS: &str = "lengths um, mm, cm, dm, m, km, in, ft, yd; volumes (to \
    report in) mL, L, m3, cm3, mm3, in3, ft3, yd3, gal, acre-ft";

/// The units `--density` knows for its mass.
pub const KNOWN_MASSES: &str = "mg, g, kg, t, oz, lb";

/// A unit to report in: the symbols and sizes (in SI) of its length, area and volume.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unit {
    pub(super) length: &'static str,
    pub(super) metres: f64,
    pub(super) area: &'static str,
    pub(super) square_metres: f64,
    pub(super) volume: &'static str,
    pub(super) cubic_metres: f64,
}

impl Unit {
    /// The unit of lengths `l`, areas l² and volumes l³.
    const fn cube(length: &'static str, area: &'static str, volume: &'static str, m: f64) -> Unit {
        Unit { length, metres: m, area, square_metres: m * m, volume, cubic_metres: m * m * m }
    }

    /// The unit a file unit reports in unconverted.
    pub fn of(l: LengthUnit) -> Unit {
        match l {
            LengthUnit::Micrometre => UM,
            LengthUnit::Millimetre => MM,
            LengthUnit::Centimetre => CM,
            LengthUnit::Metre => M,
            LengthUnit::Inch => IN,
            LengthUnit::Foot => FT,
        }
    }

    /// The volume unit's symbol (`mm^3`, `L`, `acre-ft`).
    pub fn volume_symbol(&self) -> &'static str {
        self.volume
    }

    /// The length unit's symbol (`mm`; `cm` for mL).
    pub fn length_symbol(&self) -> &'static str {
        self.length
    }

    /// Cubic metres per volume unit.
    pub fn cubic_metres(&self) -> f64 {
        self.cubic_metres
    }
}

const UM: Unit = Unit::cube("um", "um^2", "um^3", 1e-6);
const MM: Unit = Unit::cube("mm", "mm^2", "mm^3", 1e-3);
const CM: Unit = Unit::cube("cm", "cm^2", "cm^3", 1e-2);
const DM: Unit = Unit::cube("dm", "dm^2", "dm^3", 0.1);
const M: Unit = Unit::cube("m", "m^2", "m^3", 1.0);
const KM: Unit = Unit::cube("km", "km^2", "km^3", 1e3);
const IN: Unit = Unit::cube("in", "in^2", "in^3", 0.0254);
const FT: Unit = Unit::cube("ft", "ft^2", "ft^3", 0.3048);
const YD: Unit = Unit::cube("yd", "yd^2", "yd^3", 0.9144);
/// A US survey-independent international acre: 43,560 ft².
const ACRE_M2: f64 = 43_560.0 * 0.3048 * 0.3048;

/// Metres in one unit of the length a report names (`mm`, `in`, `yd`): how a sink that
/// needs SI (the robot formats) converts a report made in any unit.
pub fn metres_per(length: &str) -> Option<f64> {
    report_length(length).map(|u| u.metres)
}

/// Parses a length unit's name: um (or µm, micron), mm, cm, m, in (inch), ft (foot).
pub(super) fn length_unit(s: &str) -> Option<LengthUnit> {
    Some(match s.to_ascii_lowercase().as_str() {
        "um" | "µm" | "micron" => LengthUnit::Micrometre,
        "mm" => LengthUnit::Millimetre,
        "cm" => LengthUnit::Centimetre,
        "m" => LengthUnit::Metre,
        "in" | "inch" => LengthUnit::Inch,
        "ft" | "foot" => LengthUnit::Foot,
        _ => return None,
    })
}

/// A length unit to report in (one a file's unit may not be: dm, km, yd).
pub(super) fn report_length(s: &str) -> Option<Unit> {
    if let Some(l) = length_unit(s) {
        return Some(Unit::of(l));
    }
    match s.to_ascii_lowercase().as_str() {
        "dm" => Some(DM),
        "km" => Some(KM),
        "yd" | "yard" => Some(YD),
        _ => None,
    }
}

impl FromStr for Unit {
    type Err = String;
    fn from_str(s: &str) -> Result<Unit, String> {
        if let Some(u) = report_length(s) {
            return Ok(u);
        }
        // A length cubed: cm3, m^3, in³.
        let cubed = ["^3", "³", "3"].iter().find_map(|suffix| s.strip_suffix(suffix));
        if let Some(u) = cubed.and_then(report_length) {
            return Ok(u);
        }
        let mut u = match s.to_ascii_lowercase().as_str() {
            "ml" | "cc" => CM,
            "l" => DM,
            "gal" => IN,
            "acre-ft" | "acre-foot" | "acreft" | "af" => FT,
            _ => return Err(format!("unknown unit '{s}': known units are {KNOWN_UNITS}")),
        };
        match s.to_ascii_lowercase().as_str() {
            "ml" | "cc" => u.volume = "mL",
            "l" => u.volume = "L",
            "gal" => {
                u.volume = "gal";
                u.cubic_metres = 231.0 * 0.0254 * 0.0254 * 0.0254;
            }
            _ => {
                u.area = "acre";
                u.square_metres = ACRE_M2;
                u.volume = "acre-ft";
                u.cubic_metres = ACRE_M2 * 0.3048;
            }
        }
        Ok(u)
    }
}
