//! `--units FILE[:REPORT]`: the length unit the file uses and the unit to report in.

use serde::Serialize;
use std::str::FromStr;

/// A length unit, or a volume unit that implies one (mL = cm³, L = dm³).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Unit {
    Mm,
    Cm,
    M,
    In,
    Ft,
    Ml,
    L,
}

impl Unit {
    /// Metres per length unit.
    fn metres(self) -> f64 {
        match self {
            Unit::Mm => 1e-3,
            Unit::Cm | Unit::Ml => 1e-2,
            Unit::M => 1.0,
            Unit::In => 0.0254,
            Unit::Ft => 0.3048,
            Unit::L => 0.1,
        }
    }

    fn length_name(self) -> &'static str {
        match self {
            Unit::Mm => "mm",
            Unit::Cm | Unit::Ml => "cm",
            Unit::M => "m",
            Unit::In => "in",
            Unit::Ft => "ft",
            Unit::L => "dm",
        }
    }
}

impl FromStr for Unit {
    type Err = String;
    fn from_str(s: &str) -> Result<Unit, String> {
        Ok(match s.to_ascii_lowercase().as_str() {
            "mm" => Unit::Mm,
            "cm" => Unit::Cm,
            "m" => Unit::M,
            "in" | "inch" => Unit::In,
            "ft" | "foot" => Unit::Ft,
            "ml" => Unit::Ml,
            "l" => Unit::L,
            _ => {
                return Err(format!(
                    "unknown unit '{s}' (use mm, cm, m, in, ft, or mL/L to report)"
                ))
            }
        })
    }
}

/// How file lengths map to reported quantities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    /// The file's length unit.
    pub file: Unit,
    /// The unit results are reported in.
    pub report: Unit,
}

impl FromStr for Units {
    type Err = String;
    fn from_str(s: &str) -> Result<Units, String> {
        let (file, report) = s.split_once(':').unwrap_or((s, s));
        let file: Unit = file.parse()?;
        if matches!(file, Unit::Ml | Unit::L) {
            return Err(format!("'{s}': the file's unit must be a length (mm, cm, m, in, ft)"));
        }
        Ok(Units { file, report: report.parse()? })
    }
}

/// Names of the reported units, as printed and in JSON.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UnitNames {
    pub length: String,
    pub area: String,
    pub volume: String,
}

impl Units {
    /// Reported length per file length.
    pub fn length_factor(&self) -> f64 {
        self.file.metres() / self.report.metres()
    }

    pub fn names(&self) -> UnitNames {
        let length = self.report.length_name();
        let volume = match self.report {
            Unit::Ml => "mL".to_string(),
            Unit::L => "L".to_string(),
            _ => format!("{length}^3"),
        };
        UnitNames { length: length.to_string(), area: format!("{length}^2"), volume }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_converts() {
        let u: Units = "mm:cm".parse().unwrap();
        assert_eq!(u.length_factor(), 0.1);
        let u: Units = "in:mL".parse().unwrap();
        // 1 in = 2.54 cm, so 1 in³ = 16.387064 mL.
        assert!((u.length_factor().powi(3) - 16.387064).abs() < 1e-12);
        assert_eq!(u.names().volume, "mL");
        assert_eq!("ft".parse::<Units>().unwrap().length_factor(), 1.0);
        assert!("mL".parse::<Units>().is_err());
        assert!("mm:furlong".parse::<Units>().unwrap_err().contains("furlong"));
    }
}
