//! `--units` and `--density`, the same on every measuring command (a mass per volume, or
//! per area for the commands that measure areas); what they mean lives in the report
//! layer (`meshvol_report::units`).

use clap::Args;
use meshvol_report::units::{Density, UnitOptions, UnitsArg};

/// The units to report in and the density that turns volumes into masses.
#[derive(Args, Clone, Copy, Debug)]
pub struct UnitArgs {
    /// The file's length unit and the unit to report in: FILE[:REPORT], e.g. `mm`,
    /// `mm:cm`, `mm:L`, `ft:yd3`, or `:REPORT` to convert from the unit the file declares
    /// (3MF, glTF). File units: um, mm, cm, m, in, ft; REPORT may also be dm, km, yd, or a
    /// volume: mL, L, m3 (any length with 3: cm3, in3), yd3, gal, acre-ft. Arguments that
    /// are places or sizes (--plane, --step, --pitch, --bounds, --level) stay in the
    /// file's units.
    #[arg(long, value_name = "FILE[:REPORT]")]
    pub units: Option<UnitsArg>,
    /// Density: VALUE (mass per reported volume unit) or VALUE with a unit, e.g.
    /// `7.85g/cm3`, `7850kg/m3`, `62.4lb/ft3` (mass units: mg, g, kg, t, oz, lb); a unit
    /// needs the file's length unit (--units). Adds the mass, with its unit.
    #[arg(long, value_name = "RHO[UNIT]", allow_hyphen_values = true, value_parser = volume_density)]
    pub density: Option<Density>,
}

/// A density in mass per volume (or a bare number).
fn volume_density(s: &str) -> Result<Density, String> {
    s.parse::<Density>()?.of_volume()
}

/// A density in mass per area (or a bare number).
fn area_density(s: &str) -> Result<Density, String> {
    s.parse::<Density>()?.of_area()
}

impl UnitArgs {
    /// The options the report layer takes.
    pub fn options(&self) -> UnitOptions {
        UnitOptions { units: self.units, density: self.density }
    }
}

/// `--units` and a density per area: for the commands that measure areas (`section`,
/// `area`), whose mass is that of a sheet with the outline measured.
#[derive(Args, Clone, Copy, Debug)]
pub struct AreaUnitArgs {
    /// The file's length unit and the unit to report in: FILE[:REPORT], e.g. `mm`,
    /// `mm:cm`, `ft:yd`, or `:REPORT` to convert from the unit the file declares. File
    /// units: um, mm, cm, m, in, ft; REPORT may also be dm, km, yd (or acre-ft: areas in
    /// acres).
    #[arg(long, value_name = "FILE[:REPORT]")]
    pub units: Option<UnitsArg>,
    /// Mass per area: VALUE (per reported area unit) or VALUE with a unit, e.g.
    /// `62.8kg/m2` (an 8 mm steel plate), `0.27g/cm2`, `2lb/ft2`; a unit needs the
    /// file's length unit (--units). Adds the mass of a sheet with this outline.
    #[arg(long, value_name = "RHO[UNIT]", allow_hyphen_values = true, value_parser = area_density)]
    pub density: Option<Density>,
}

impl AreaUnitArgs {
    pub fn options(&self) -> UnitOptions {
        UnitOptions { units: self.units, density: self.density }
    }
}
