//! `units=` and `density=` as every measuring method takes them: the command's
//! `--units FILE[:REPORT]` and `--density VALUE[UNIT]` (a mass per volume; per area for
//! the methods that measure areas), converted by the report layer
//! (`meshvol_report::units`), so that Python reports what the command reports.

use crate::errors::bad_argument;
use meshvol_report::units::{Density, UnitOptions, UnitsArg};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

/// A density: a positive number (mass per reported volume unit), or text with a unit
/// as the command's --density takes it ('7.85g/cm3', '7850kg/m3').
pub fn density(d: &Bound<'_, PyAny>) -> PyResult<Density> {
    any_density(d)?.of_volume().map_err(bad_argument)
}

/// A number, or a mass per volume or per area.
fn any_density(d: &Bound<'_, PyAny>) -> PyResult<Density> {
    if let Ok(text) = d.extract::<String>() {
        return text.parse::<Density>().map_err(bad_argument);
    }
    let value: f64 = d.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "density must be a number or a string such as '7.85g/cm3'; got {}",
            d.get_type().name().map(|n| n.to_string()).unwrap_or_default()
        ))
    })?;
    check_density(value)?;
    Ok(Density::plain(value))
}

/// The unit options of `units` ('mm', 'mm:cm', ':in') and `density` (None: no mass).
pub fn options(units: Option<&str>, density: Option<&Bound<'_, PyAny>>) -> PyResult<UnitOptions> {
    let units = units.map(str::parse::<UnitsArg>).transpose().map_err(bad_argument)?;
    let density = density.filter(|d| !d.is_none()).map(self::density).transpose()?;
    Ok(UnitOptions { units, density })
}

/// The unit options of the methods that measure areas (`Mesh.section`,
/// `meshvol.polygon_area`): `density` is a mass per area ('62.8kg/m2', or a number per
/// reported area unit), the mass that of a sheet with the outline measured.
pub fn area_options(
    units: Option<&str>,
    density: Option<&Bound<'_, PyAny>>,
) -> PyResult<UnitOptions> {
    let units = units.map(str::parse::<UnitsArg>).transpose().map_err(bad_argument)?;
    let density = density
        .filter(|d| !d.is_none())
        .map(|d| any_density(d)?.of_area().map_err(bad_argument))
        .transpose()?;
    Ok(UnitOptions { units, density })
}

/// A density argument whose default (None) is 1.
pub fn density_or_one(d: Option<&Bound<'_, PyAny>>) -> PyResult<Density> {
    match d.filter(|d| !d.is_none()) {
        Some(d) => density(d),
        None => Ok(Density::plain(1.0)),
    }
}

/// Checks a density as the command does: positive and finite.
pub fn check_density(density: f64) -> PyResult<()> {
    if density.is_finite() && density > 0.0 {
        Ok(())
    } else {
        Err(bad_argument(format!("density must be a positive number; got {density}")))
    }
}
