//! A report's quantities in the units asked for: the one mechanism every report converts
//! through.
//!
//! A report lists each of its quantities once with its [`Dimension`]
//! ([`Quantities::convert`]); [`Scale::convert`] scales it (lengths and points by f,
//! areas by f², volumes by f³, second moments of area by f⁴ and of volume by f⁵); and
//! [`Quantities::in_units`] does what is the same for every report: resolving `--units`
//! against the unit each file declares (with the warning when they differ), the names
//! of the units, and with `--density` the mass of the report's [`Quantities::mass_basis`].
//! A report never scales its own fields, so a quantity added to a report is converted
//! where it is listed or not at all, and every sink (text, JSON, CSV, Python, the page)
//! writes the one converted value.

use crate::units::{Mass, Scale, UnitNames, UnitOptions};
use crate::Report;
use meshvol::accumulate::UNIT_ROUNDOFF;
use meshvol_io::LengthUnit;

/// `Quantities::unit_slots` of a report with the fields `warnings`, `units` and `mass`.
macro_rules! unit_slots {
    () => {
        fn unit_slots(&mut self) -> crate::quantities::UnitSlots<'_> {
            crate::quantities::UnitSlots {
                warnings: &mut self.warnings,
                units: &mut self.units,
                mass: &mut self.mass,
            }
        }
    };
}
pub(crate) use unit_slots;

/// What a quantity measures, and so how a change of units scales it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    /// A length, a coordinate or a point: × f.
    Length,
    /// An area, or ∫ n dA: × f².
    Area,
    /// A volume: × f³.
    Volume,
    /// A second moment of area, ∫ x² dA: × f⁴.
    AreaMoment,
    /// A second moment of volume, ∫ x² dV: × f⁵.
    VolumeMoment,
}

impl Scale {
    /// `x` of dimension `d` in the reported units.
    pub fn convert(&self, d: Dimension, x: f64) -> f64 {
        match d {
            Dimension::Length => self.length(x),
            Dimension::Area => self.area(x),
            Dimension::Volume => self.volume(x),
            Dimension::AreaMoment => self.area_moment(x),
            Dimension::VolumeMoment => self.volume_moment(x),
        }
    }
}

/// What [`Quantities::convert`] is given: converts quantities where they are.
pub struct Converter<'a> {
    scale: &'a Scale,
}

impl<'a> Converter<'a> {
    /// The converter of `scale`: for a report built in reported units, as `volume`'s.
    pub fn new(scale: &'a Scale) -> Converter<'a> {
        Converter { scale }
    }

    /// One number of dimension `d`.
    pub fn one(&self, d: Dimension, x: &mut f64) {
        *x = self.scale.convert(d, *x);
    }

    /// Numbers of dimension `d`: a list, an array, a point's coordinates.
    pub fn all<'x>(&self, d: Dimension, xs: impl IntoIterator<Item = &'x mut f64>) {
        xs.into_iter().for_each(|x| self.one(d, x));
    }

    /// A number that may be absent.
    pub fn some(&self, d: Dimension, x: &mut Option<f64>) {
        self.all(d, x.iter_mut());
    }

    /// A certified interval of volumes, `[lower, upper]`: converted and widened by the
    /// conversion's rounding (the factor's and the product's, a few units of roundoff),
    /// so that it still holds the converted value. Nothing changes without a conversion.
    pub fn interval(&self, lower: &mut f64, upper: &mut f64) {
        if !self.scale.converts() {
            return;
        }
        let slack = |x: f64| 4.0 * UNIT_ROUNDOFF * x.abs();
        let (l, u) = (self.scale.volume(*lower), self.scale.volume(*upper));
        *lower = (l - slack(l)).next_down();
        *upper = (u + slack(u)).next_up();
    }

    /// A point (or a vector of lengths) that may be absent.
    pub fn point<const N: usize>(&self, p: &mut Option<[f64; N]>) {
        self.all(Dimension::Length, p.iter_mut().flatten());
    }
}

/// Where [`Quantities::in_units`] puts what is the same for every report.
pub struct UnitSlots<'a> {
    pub warnings: &'a mut Vec<String>,
    pub units: &'a mut Option<UnitNames>,
    pub mass: &'a mut Option<Mass>,
}

/// The files a report measured, with the unit each declares: one (the report's own
/// file) or several, which must agree on their unit.
pub trait Declared {
    /// The files, named; `file` names a report's own.
    fn files<'a>(&'a self, file: &'a str) -> Vec<(&'a str, Option<LengthUnit>)>;
}

impl Declared for Option<LengthUnit> {
    fn files<'a>(&'a self, file: &'a str) -> Vec<(&'a str, Option<LengthUnit>)> {
        vec![(file, *self)]
    }
}

impl Declared for &[(&str, Option<LengthUnit>)] {
    fn files<'a>(&'a self, _: &'a str) -> Vec<(&'a str, Option<LengthUnit>)> {
        self.to_vec()
    }
}

impl<const N: usize> Declared for &[(&str, Option<LengthUnit>); N] {
    fn files<'a>(&'a self, _: &'a str) -> Vec<(&'a str, Option<LengthUnit>)> {
        self.to_vec()
    }
}

impl Declared for &Vec<(&str, Option<LengthUnit>)> {
    fn files<'a>(&'a self, _: &'a str) -> Vec<(&'a str, Option<LengthUnit>)> {
        self.to_vec()
    }
}

/// A report made in the file's units that [`Quantities::in_units`] converts.
pub trait Quantities: Report + Sized {
    /// Lists every quantity of the report with its dimension.
    fn convert(&mut self, to: &Converter);

    /// What the mass is of, in reported units (a volume; for the commands that measure
    /// areas, the area of a sheet), after [`Quantities::convert`].
    fn mass_basis(&self) -> f64;

    /// Where the warnings, the units' names and the mass go.
    fn unit_slots(&mut self) -> UnitSlots<'_>;

    /// The report in the units `options` ask for, for the files it measured (`declared`:
    /// the unit its own file declares, or several files with theirs). Errors name the
    /// file; a single file's unit warning is the report's own, several files' name
    /// theirs.
    fn in_units(mut self, options: &UnitOptions, declared: impl Declared) -> Result<Self, String> {
        let file = self.file().to_string();
        let files = declared.files(&file);
        let (scale, warnings) = match files[..] {
            [(name, unit)] => {
                let (scale, warning) =
                    Scale::resolve(options, unit).map_err(|e| format!("{name}: {e}"))?;
                (scale, warning.into_iter().collect())
            }
            _ => Scale::resolve_all(options, &files)?,
        };
        self.convert(&Converter::new(&scale));
        let basis = self.mass_basis();
        let slots = self.unit_slots();
        slots.warnings.extend(warnings);
        *slots.units = scale.names();
        *slots.mass = scale.mass(basis);
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_dimension_scales_by_its_power_of_the_length() {
        // 1 ft = 12 in, written out: lengths ×12, areas ×144, volumes ×1728, second
        // moments of area ×20736 and of volume ×248832.
        let options = UnitOptions { units: Some("ft:in".parse().unwrap()), density: None };
        let (scale, _) = Scale::resolve(&options, None).unwrap();
        let by = |d| scale.convert(d, 1.0);
        assert!((by(Dimension::Length) - 12.0).abs() < 1e-12);
        assert!((by(Dimension::Area) - 144.0).abs() < 1e-10);
        assert!((by(Dimension::Volume) - 1728.0).abs() < 1e-9);
        assert!((by(Dimension::AreaMoment) - 20736.0).abs() < 1e-8);
        assert!((by(Dimension::VolumeMoment) - 248832.0).abs() < 1e-7);
    }
}
