//! Units, in one place for every command: `--units FILE[:REPORT]` (or `--units :REPORT`),
//! the length unit the file uses and the unit to report in, and `--density VALUE[UNIT]`,
//! which turns volumes into masses.
//!
//! A file that declares its unit (3MF's `unit` attribute; glTF, which is in metres) gives
//! the file unit when `--units` does not: no `--units` reports in the declared unit,
//! `--units :cm` converts from it. An explicit FILE unit wins over the declaration, with
//! a warning when they differ. `:REPORT` for a file that declares nothing is an error.
//!
//! A report unit is a length (areas and volumes follow it) or a volume unit that implies
//! a length and an area: mL (cm), L (dm), m3 (m), yd3 (yd), gal (US gallon; in),
//! acre-ft (ft, areas in acres). Every report converts through [`Scale`]: lengths by f,
//! areas by the area factor, volumes by the volume factor, second moments by volume ×
//! length², masses by the density.
//!
//! Arguments that are places or sizes (`--plane`, `--step`, `--pitch`, `--bounds`,
//! `--level`, `below --volume`) stay in the file's own coordinates: `--units` changes what
//! is reported, not what is asked.

use meshvol_io::LengthUnit;
use serde::Serialize;
use std::str::FromStr;

mod density;
mod scale;
mod unit;

use density::mass_unit;
pub use density::{Density, MassUnit};
pub use scale::{mass_line, units_text, Mass, Scale};
use unit::length_unit;
pub use unit::{metres_per, Unit, KNOWN_MASSES, KNOWN_UNITS};

/// Kilograms in one unit of the mass a report names (`g`, `lb`).
pub fn kilograms_per(mass: &str) -> Option<f64> {
    mass_unit(mass).map(|m| m.kilograms)
}

/// How file lengths map to reported quantities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    /// The file's length unit.
    pub file: LengthUnit,
    /// The unit results are reported in.
    pub report: Unit,
    /// The unit the file declares, if it declares one.
    pub declared: Option<LengthUnit>,
}

/// What `--units` says: `FILE`, `FILE:REPORT`, or `:REPORT` (the file unit from the
/// file's declaration).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitsArg {
    pub file: Option<LengthUnit>,
    pub report: Unit,
}

impl FromStr for UnitsArg {
    type Err = String;
    fn from_str(s: &str) -> Result<UnitsArg, String> {
        let (file, report) = s.split_once(':').unwrap_or((s, s));
        let file = match file {
            "" => None,
            f => Some(length_unit(f).ok_or_else(|| match f.parse::<Unit>() {
                Ok(_) => format!(
                    "'{s}': the file's unit must be one a file can be in: um, mm, cm, m, in, ft"
                ),
                Err(e) => e,
            })?),
        };
        let report = match (report, file) {
            ("", Some(file)) => Unit::of(file),
            ("", None) => return Err(format!("'{s}': no unit given")),
            (report, _) => report.parse()?,
        };
        Ok(UnitsArg { file, report })
    }
}

/// The units for one file: from `--units` and what the file declares. Returns them (none
/// when neither says anything) and a warning when `--units` overrides the declaration.
pub fn resolve(
    arg: Option<UnitsArg>,
    declared: Option<LengthUnit>,
) -> Result<(Option<Units>, Option<String>), String> {
    let units = |file, report| Some(Units { file, report, declared });
    Ok(match (arg, declared) {
        (None, None) => (None, None),
        (None, Some(d)) => (units(d, Unit::of(d)), None),
        (Some(UnitsArg { file: Some(f), report }), d) => {
            let warning = d.filter(|&d| d != f).map(|d| {
                format!(
                    "the file declares its lengths in {}; --units says {}: using {}",
                    d.symbol(),
                    f.symbol(),
                    f.symbol()
                )
            });
            (units(f, report), warning)
        }
        (Some(UnitsArg { file: None, report }), Some(d)) => (units(d, report), None),
        (Some(UnitsArg { file: None, .. }), None) => {
            return Err("the file declares no length unit: give it, as in --units mm:cm".into())
        }
    })
}

/// Names of the reported units, as printed and in JSON.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UnitNames {
    pub length: String,
    pub area: String,
    pub volume: String,
    /// The length unit the file's numbers were taken to be in.
    pub file: String,
    /// The length unit the file declares (3MF, glTF), or null.
    pub file_declared: Option<String>,
}

impl Units {
    /// Reported length per file length.
    pub fn length_factor(&self) -> f64 {
        self.file.metres() / self.report.metres
    }

    /// Reported area per file area.
    pub fn area_factor(&self) -> f64 {
        let m = self.file.metres();
        m * m / self.report.square_metres
    }

    /// Reported volume per file volume.
    pub fn volume_factor(&self) -> f64 {
        let m = self.file.metres();
        m * m * m / self.report.cubic_metres
    }

    pub fn names(&self) -> UnitNames {
        UnitNames {
            length: self.report.length.to_string(),
            area: self.report.area.to_string(),
            volume: self.report.volume.to_string(),
            file: self.file.symbol().to_string(),
            file_declared: self.declared.map(|d| d.symbol().to_string()),
        }
    }
}

/// What a command was asked about units: `--units` and `--density`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UnitOptions {
    pub units: Option<UnitsArg>,
    pub density: Option<Density>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn units(s: &str, declared: Option<LengthUnit>) -> Units {
        resolve(Some(s.parse().unwrap()), declared).unwrap().0.unwrap()
    }

    #[test]
    fn parses_and_converts() {
        let u = units("mm:cm", None);
        assert_eq!(u.length_factor(), 0.1);
        let u = units("in:mL", None);
        // 1 in = 2.54 cm, so 1 in³ = 16.387064 mL.
        assert!((u.length_factor().powi(3) - 16.387064).abs() < 1e-12);
        assert_eq!(u.names().volume, "mL");
        assert_eq!(units("ft", None).length_factor(), 1.0);
        assert_eq!(units("um:mm", None).length_factor(), 1e-3);
        assert!("mL".parse::<UnitsArg>().is_err());
        assert!(":".parse::<UnitsArg>().is_err());
        assert!("mm:furlong".parse::<UnitsArg>().unwrap_err().contains("furlong"));
    }

    #[test]
    fn volume_units_and_densities() {
        // 1000 mm cube = 1 m³ = 1000 L = 1.307950619 yd³ = 1/1233.48183754752 acre-ft.
        let v = |s: &str| units(s, None).volume_factor() * 1e9;
        assert!((v("mm:L") - 1000.0).abs() < 1e-9);
        assert!((v("mm:m3") - 1.0).abs() < 1e-15);
        assert!((v("mm:yd3") - 1.0 / 0.9144f64.powi(3)).abs() < 1e-12);
        assert!((v("mm:acre-ft") - 1.0 / 1233.48183754752).abs() < 1e-15);
        assert!((v("mm:gal") - 1.0 / 0.003785411784).abs() < 1e-9);
        assert_eq!(units("mm:acre-ft", None).names().area, "acre");
        assert_eq!(units("mm:cm3", None).names().volume, "cm^3");
        let e = "mm:furlong".parse::<UnitsArg>().unwrap_err();
        assert!(e.contains("mL") && e.contains("acre-ft"), "{e}");
        let d: Density = "7.85g/cm3".parse().unwrap();
        assert_eq!((d.value, d.unit_name().as_deref()), (7.85, Some("g/cm^3")));
        let d: Density = "7850kg/m3".parse().unwrap();
        assert_eq!(d.unit_name().as_deref(), Some("kg/m^3"));
        assert_eq!("2.5".parse::<Density>().unwrap(), Density::plain(2.5));
        assert_eq!("1e3kg/L".parse::<Density>().unwrap().value, 1000.0);
        for bad in ["0", "-1g/cm3", "inf", "NaN", "abc", "2furlong/cm3", "2g/parsec"] {
            assert!(bad.parse::<Density>().is_err(), "{bad}");
        }
        // 7.85 g/cm³ over 1 m³ reported in L: 7.85e6 g.
        let options = UnitOptions {
            units: Some("mm:L".parse().unwrap()),
            density: Some("7.85g/cm3".parse().unwrap()),
        };
        let (scale, _) = Scale::resolve(&options, None).unwrap();
        let m = scale.mass(scale.volume(1e9)).unwrap();
        assert!((m.mass - 7.85e6).abs() < 1e-6, "{m:?}");
        assert_eq!(m.mass_unit.as_deref(), Some("g"));
        // A mass per area (section, area): 62.8 kg/m² over 1 m² reported in cm².
        let d: Density = "62.8kg/m2".parse().unwrap();
        assert_eq!((d.per_area, d.unit_name().as_deref()), (true, Some("kg/m^2")));
        assert!(d.of_volume().unwrap_err().contains("mass per area"));
        let options = UnitOptions {
            units: Some("mm:cm".parse().unwrap()),
            density: Some(d.of_area().unwrap()),
        };
        let (scale, _) = Scale::resolve(&options, None).unwrap();
        let m = scale.mass(scale.area(1e6)).unwrap();
        assert!((m.mass - 62.8).abs() < 1e-12, "{m:?}");
        assert_eq!(m.mass_unit.as_deref(), Some("kg"));
        assert!("7.85g/cm3"
            .parse::<Density>()
            .unwrap()
            .of_area()
            .unwrap_err()
            .contains("per area"));
        assert!("2.5".parse::<Density>().unwrap().of_area().unwrap().per_area);
        // A density with a unit needs a length unit.
        let options = UnitOptions { units: None, density: Some("7.85g/cm3".parse().unwrap()) };
        assert!(Scale::resolve(&options, None).unwrap_err().contains("--units"));
    }

    #[test]
    fn declared_units() {
        use LengthUnit as L;
        // Nothing given: the declaration, reported as is.
        let (u, w) = resolve(None, Some(L::Inch)).unwrap();
        let u = u.unwrap();
        assert_eq!(
            (u.file, u.report, u.length_factor(), w),
            (L::Inch, Unit::of(L::Inch), 1.0, None)
        );
        assert_eq!(u.names().file_declared.as_deref(), Some("in"));
        // A report unit only: converted from the declaration.
        let u = units(":cm", Some(L::Inch));
        assert!((u.length_factor() - 2.54).abs() < 1e-15);
        assert_eq!(u.names().file, "in");
        // An explicit file unit wins, with a warning when it differs.
        let (u, w) = resolve(Some("mm:cm".parse().unwrap()), Some(L::Inch)).unwrap();
        assert_eq!(u.unwrap().file, L::Millimetre);
        assert!(w.unwrap().contains("declares its lengths in in"));
        assert_eq!(resolve(Some("mm".parse().unwrap()), Some(L::Millimetre)).unwrap().1, None);
        // Nothing declared and no file unit.
        assert!(resolve(Some(":cm".parse().unwrap()), None).unwrap_err().contains("declares no"));
        assert_eq!(resolve(None, None).unwrap(), (None, None));
    }
}
