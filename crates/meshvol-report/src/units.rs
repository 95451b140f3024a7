//! `--units FILE[:REPORT]` or `--units :REPORT`: the length unit the file uses and the
//! unit to report in.
//!
//! A file that declares its unit (3MF's `unit` attribute; glTF, which is in metres) gives
//! the file unit when `--units` does not: no `--units` reports in the declared unit,
//! `--units :cm` converts from it. An explicit FILE unit wins over the declaration, with
//! a warning when they differ. `:REPORT` for a file that declares nothing is an error.

use meshvol_io::LengthUnit;
use serde::Serialize;
use std::str::FromStr;

/// A unit to report in: a length (areas and volumes follow it), or a volume unit that
/// implies one (mL = cm³, L = dm³). Lengths are [`LengthUnit`]s, the type the readers use
/// for what a file declares: there is one length unit type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Unit {
    Length(LengthUnit),
    Millilitre,
    Litre,
}

impl Unit {
    /// The length unit lengths are reported in.
    fn length(self) -> Length {
        match self {
            Unit::Length(l) => Length::Unit(l),
            Unit::Millilitre => Length::Unit(LengthUnit::Centimetre),
            Unit::Litre => Length::Decimetre,
        }
    }
}

/// A reported length unit: a [`LengthUnit`], or the decimetre that litres imply.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Length {
    Unit(LengthUnit),
    Decimetre,
}

impl Length {
    fn metres(self) -> f64 {
        match self {
            Length::Unit(l) => l.metres(),
            Length::Decimetre => 0.1,
        }
    }

    fn symbol(self) -> &'static str {
        match self {
            Length::Unit(l) => l.symbol(),
            Length::Decimetre => "dm",
        }
    }
}

/// Parses a length unit's name: um (or µm, micron), mm, cm, m, in (inch), ft (foot).
fn length_unit(s: &str) -> Option<LengthUnit> {
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

impl FromStr for Unit {
    type Err = String;
    fn from_str(s: &str) -> Result<Unit, String> {
        if let Some(l) = length_unit(s) {
            return Ok(Unit::Length(l));
        }
        match s.to_ascii_lowercase().as_str() {
            "ml" => Ok(Unit::Millilitre),
            "l" => Ok(Unit::Litre),
            _ => Err(format!("unknown unit '{s}' (use um, mm, cm, m, in, ft, or mL/L to report)")),
        }
    }
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
                Ok(_) => format!("'{s}': the file's unit must be a length (um, mm, cm, m, in, ft)"),
                Err(e) => e,
            })?),
        };
        let report = match (report, file) {
            ("", Some(file)) => Unit::Length(file),
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
        (None, Some(d)) => (units(d, Unit::Length(d)), None),
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
        self.file.metres() / self.report.length().metres()
    }

    pub fn names(&self) -> UnitNames {
        let length = self.report.length().symbol();
        let volume = match self.report {
            Unit::Millilitre => "mL".to_string(),
            Unit::Litre => "L".to_string(),
            _ => format!("{length}^3"),
        };
        UnitNames {
            length: length.to_string(),
            area: format!("{length}^2"),
            volume,
            file: self.file.symbol().to_string(),
            file_declared: self.declared.map(|d| d.symbol().to_string()),
        }
    }
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
    fn declared_units() {
        use LengthUnit as L;
        // Nothing given: the declaration, reported as is.
        let (u, w) = resolve(None, Some(L::Inch)).unwrap();
        let u = u.unwrap();
        assert_eq!(
            (u.file, u.report, u.length_factor(), w),
            (L::Inch, Unit::Length(L::Inch), 1.0, None)
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
