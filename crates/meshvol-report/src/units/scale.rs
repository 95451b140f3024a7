//! [`Scale`]: the factors of one report, from the file's numbers to the units asked for
//! and from volumes to masses, and the text lines naming them.

use super::{resolve, Density, UnitNames, UnitOptions, Units};
use meshvol_io::LengthUnit;
use serde::Serialize;

/// A mass and how it was found: flattened into reports as `density`, `density_unit`,
/// `mass`, `mass_unit` (present when `--density` was given).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mass {
    /// The density as given.
    pub density: f64,
    /// Its unit as given (`g/cm^3`), or null: mass per reported volume unit.
    pub density_unit: Option<String>,
    pub mass: f64,
    /// The mass's unit (`g`), or null for a density without one.
    pub mass_unit: Option<String>,
}

/// The conversion one report makes: from the file's numbers to the units asked for, and
/// from volumes to masses. The identity when no unit is known or asked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    pub units: Option<Units>,
    length: f64,
    area: f64,
    volume: f64,
    /// Mass per reported volume unit, in the density's mass unit.
    rho: Option<f64>,
    density: Option<Density>,
}

impl Default for Scale {
    fn default() -> Self {
        Scale { units: None, length: 1.0, area: 1.0, volume: 1.0, rho: None, density: None }
    }
}

impl Scale {
    /// [`Scale::resolve`] for the report of one file: its warning added to `warnings`,
    /// an error prefixed by the file's name.
    pub fn for_report(
        options: &UnitOptions,
        declared: Option<LengthUnit>,
        file: &str,
        warnings: &mut Vec<String>,
    ) -> Result<Scale, String> {
        let (scale, warning) =
            Scale::resolve(options, declared).map_err(|e| format!("{file}: {e}"))?;
        warnings.extend(warning);
        Ok(scale)
    }

    /// The scale for a file declaring `declared`, and a warning when `--units` overrides
    /// the declaration. Errors: `:REPORT` with nothing declared, a density with a unit
    /// and no length unit to convert from, a density that is not positive.
    pub fn resolve(
        options: &UnitOptions,
        declared: Option<LengthUnit>,
    ) -> Result<(Scale, Option<String>), String> {
        let (units, warning) = resolve(options.units, declared)?;
        let mut scale = match units {
            None => Scale::default(),
            Some(u) => Scale {
                units: Some(u),
                length: u.length_factor(),
                area: u.area_factor(),
                volume: u.volume_factor(),
                rho: None,
                density: None,
            },
        };
        if let Some(d) = options.density {
            d.validate()?;
            scale.rho = Some(match (d.unit, units) {
                (None, _) => d.value,
                (Some((_, per)), Some(u)) if d.per_area => {
                    d.value * u.report.square_metres / per.square_metres
                }
                (Some((_, per)), Some(u)) => d.value * u.report.cubic_metres / per.cubic_metres,
                (Some(_), None) => {
                    return Err(format!(
                        "--density {}{} has a unit, but the file's length unit is not known: \
                         give it with --units (e.g. --units mm)",
                        d.value,
                        d.unit_name().unwrap_or_default()
                    ))
                }
            });
            scale.density = Some(d);
        }
        Ok((scale, warning))
    }

    /// The one scale of several files measured together (a grid, a union): each file's
    /// units must agree.
    pub fn resolve_all(
        options: &UnitOptions,
        files: &[(&str, Option<LengthUnit>)],
    ) -> Result<(Scale, Vec<String>), String> {
        let mut first: Option<(Scale, &str)> = None;
        let mut warnings = Vec::new();
        for &(name, declared) in files {
            let (scale, warning) =
                Scale::resolve(options, declared).map_err(|e| format!("{name}: {e}"))?;
            warnings.extend(warning.map(|w| format!("{name}: {w}")));
            match first {
                None => first = Some((scale, name)),
                Some((s, other)) if s.units.map(|u| u.file) != scale.units.map(|u| u.file) => {
                    let unit = |s: Scale| s.units.map_or("none".into(), |u| u.file.to_string());
                    return Err(format!(
                        "{name} is in {}, {other} in {}: measure them in one unit (give --units)",
                        unit(scale),
                        unit(s)
                    ));
                }
                Some(_) => {}
            }
        }
        Ok((first.map_or_else(Scale::default, |(s, _)| s), warnings))
    }

    pub fn length(&self, x: f64) -> f64 {
        x * self.length
    }
    pub fn area(&self, x: f64) -> f64 {
        x * self.area
    }
    pub fn volume(&self, x: f64) -> f64 {
        x * self.volume
    }
    pub fn point<const N: usize>(&self, p: [f64; N]) -> [f64; N] {
        p.map(|x| x * self.length)
    }
    /// A second moment of area (length⁴): area × length².
    pub fn area_moment(&self, x: f64) -> f64 {
        x * self.area * self.length * self.length
    }
    /// A second moment of volume (length⁵): volume × length².
    pub fn volume_moment(&self, x: f64) -> f64 {
        x * self.volume * self.length * self.length
    }
    /// Whether anything changes.
    pub fn converts(&self) -> bool {
        self.volume != 1.0 || self.length != 1.0 || self.area != 1.0
    }

    /// The names of the reported units, when known.
    pub fn names(&self) -> Option<UnitNames> {
        self.units.map(|u| u.names())
    }

    /// Mass per reported volume (or area) unit, with `--density`: what a sink that
    /// writes masses multiplies reported volumes by.
    pub fn mass_per_volume(&self) -> Option<f64> {
        self.rho
    }

    /// Mass per reported volume unit (1 without `--density`).
    pub fn density(&self) -> f64 {
        self.rho.unwrap_or(1.0)
    }

    /// The mass of `volume` (in reported units), with `--density`; for a density per
    /// area, the mass of a sheet of `volume`'s area.
    pub fn mass(&self, volume: f64) -> Option<Mass> {
        let (rho, d) = (self.rho?, self.density?);
        Some(Mass {
            density: d.value,
            density_unit: d.unit_name(),
            mass: rho * volume,
            mass_unit: d.unit.map(|(m, _)| m.symbol.to_string()),
        })
    }

    /// The suffixes text puts after a length, an area and a volume: ` mm`, or nothing.
    pub fn suffixes(names: &Option<UnitNames>) -> (String, String, String) {
        match names {
            Some(u) => (format!(" {}", u.length), format!(" {}", u.area), format!(" {}", u.volume)),
            None => Default::default(),
        }
    }
}

/// The text line of a mass: `  mass               12.5 kg  (density 7.85 g/cm^3)`.
pub fn mass_line(mass: &Option<Mass>) -> String {
    use crate::number::num;
    match mass {
        None => String::new(),
        Some(m) => {
            let mu = m.mass_unit.as_ref().map(|u| format!(" {u}")).unwrap_or_default();
            let du = m.density_unit.as_ref().map(|u| format!(" {u}")).unwrap_or_default();
            format!(
                "  mass               {}{mu}  (density {}{du})\n",
                num(m.mass, 12),
                num(m.density, 15)
            )
        }
    }
}

/// The text line naming the units (and the mass line with `--density`); empty when
/// neither is known.
pub fn units_text(names: &Option<UnitNames>, mass: &Option<Mass>) -> String {
    let mut s = String::new();
    if let Some(u) = names {
        s += &format!(
            "  units              lengths in {}, areas in {}, volumes in {} (the file in {})\n",
            u.length, u.area, u.volume, u.file
        );
    }
    s + &mass_line(mass)
}
