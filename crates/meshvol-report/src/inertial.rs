//! Mass and inertia as robot descriptions want them: the `<inertial>` element of URDF,
//! of SDF, and MuJoCo's MJCF, from a volume report in SI units.
//!
//! All three take the mass in kilograms, the centre of mass in metres (the element's
//! origin, axes parallel to the link frame: the file's axes) and the inertia tensor about
//! it in kg·m², whose off-diagonal entries are I_xy = −∫ x y dm (the tensor, not the
//! products of inertia): exactly the report's `inertia`. URDF and SDF list ixx ixy ixz
//! iyy iyz izz; MJCF's `fullinertia` lists ixx iyy izz ixy ixz iyz.

use crate::units::{kilograms_per, metres_per, UnitOptions};
use crate::volume::VolumeReport;

/// A robot description format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RobotFormat {
    Urdf,
    Sdf,
    Mjcf,
}

impl std::str::FromStr for RobotFormat {
    type Err = String;
    fn from_str(s: &str) -> Result<RobotFormat, String> {
        match s.to_ascii_lowercase().as_str() {
            "urdf" => Ok(RobotFormat::Urdf),
            "sdf" => Ok(RobotFormat::Sdf),
            "mjcf" => Ok(RobotFormat::Mjcf),
            _ => Err(format!("'{s}' is not a robot description format (urdf, sdf, mjcf)")),
        }
    }
}

/// A number as XML attribute text: the shortest digits that read back the same,
/// in exponent form when plain notation would be long.
fn number(x: f64) -> String {
    let x = if x == 0.0 { 0.0 } else { x }; // no "-0"
    if x != 0.0 && !(1e-4..1e12).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The SI factors of a report: metres per reported length and kilograms per reported
/// mass. Robot formats are SI whatever the report's units: a report made in mm and g
/// (`--units mm --density 2.7g/cm3`) is converted here, once, from the units it names.
/// A density without a unit is a mass per reported volume unit; its mass unit is known
/// only as kilograms per cubic metre, in a report in metres. Errors name the unit the
/// formats need.
fn si_factors(report: &VolumeReport) -> Result<(f64, f64), String> {
    let file = report.file.as_deref().unwrap_or("mesh");
    let length = report.units.as_ref().map(|u| u.length.as_str());
    let Some(metres) = length.and_then(metres_per) else {
        return Err(format!(
            "{file}: robot descriptions are in metres and kilograms, and the file's length \
             unit is not known: give it (--units mm, or --units mm:m; in Python units=\"mm\")"
        ));
    };
    let kilograms = match report.mass_unit.as_deref() {
        Some(mass) => kilograms_per(mass)
            .ok_or_else(|| format!("{file}: unknown mass unit '{mass}' for a robot description"))?,
        None if length == Some("m") => 1.0,
        None => {
            return Err(format!(
                "{file}: robot descriptions need the mass in kilograms: give the density with \
                 its unit (--density 2700kg/m3 or 2.7g/cm3; in Python density=\"2700kg/m3\"), \
                 or report in metres (--units FILE:m) with the density in kg/m³"
            ))
        }
    };
    Ok((metres, kilograms))
}

/// Refuses, before any file is read, the unit options no report can be turned into SI
/// by: a density without a unit (a mass per reported volume unit, of no known mass unit)
/// reported in a length other than metres. A format's name for the message.
pub fn refuse_units(options: &UnitOptions, format: &str) -> Result<(), String> {
    let plain = options.density.is_none_or(|d| d.unit.is_none());
    match options.units {
        Some(u) if plain && u.report.length_symbol() != "m" => Err(format!(
            "--format {format} writes kilograms: give the density with its unit (--density \
             2700kg/m3 or 2.7g/cm3), or report in metres (--units FILE:m) with the density in \
             kg/m³"
        )),
        _ => Ok(()),
    }
}

/// The `<inertial>` element of `report` in `format`: mass in kg, centre of mass in m and
/// inertia in kg·m², converted from the report's units ([`si_factors`]); its solid must
/// have a volume.
pub fn inertial(report: &VolumeReport, format: RobotFormat) -> Result<String, String> {
    let file = report.file.as_deref().unwrap_or("mesh");
    let (metres, kilograms) = si_factors(report)?;
    let c = report.centroid.ok_or_else(|| {
        format!("{file}: the solid has no volume, so no centre of mass or inertia")
    })?;
    let c = c.map(|x| x * metres);
    let mass = report.mass * kilograms;
    let inertia = report.inertia.map(|row| row.map(|x| x * kilograms * metres * metres));
    let [x, y, z] = c.map(number);
    let m = number(mass);
    let i = inertia.map(|row| row.map(number));
    let (ixx, iyy, izz, ixy, ixz, iyz) =
        (&i[0][0], &i[1][1], &i[2][2], &i[0][1], &i[0][2], &i[1][2]);
    Ok(match format {
        RobotFormat::Urdf => format!(
            "<inertial>\n  <origin xyz=\"{x} {y} {z}\" rpy=\"0 0 0\"/>\n  <mass value=\"{m}\"/>\n  \
             <inertia ixx=\"{ixx}\" ixy=\"{ixy}\" ixz=\"{ixz}\" iyy=\"{iyy}\" iyz=\"{iyz}\" \
             izz=\"{izz}\"/>\n</inertial>\n"
        ),
        RobotFormat::Sdf => format!(
            "<inertial>\n  <pose>{x} {y} {z} 0 0 0</pose>\n  <mass>{m}</mass>\n  <inertia>\n    \
             <ixx>{ixx}</ixx>\n    <ixy>{ixy}</ixy>\n    <ixz>{ixz}</ixz>\n    <iyy>{iyy}</iyy>\n    \
             <iyz>{iyz}</iyz>\n    <izz>{izz}</izz>\n  </inertia>\n</inertial>\n"
        ),
        RobotFormat::Mjcf => format!(
            "<inertial pos=\"{x} {y} {z}\" mass=\"{m}\" \
             fullinertia=\"{ixx} {iyy} {izz} {ixy} {ixz} {iyz}\"/>\n"
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::number;

    #[test]
    fn numbers_read_back() {
        for x in [0.00785, 1.308333333333333e-7, -2.5e-17, 12.5, 1e15, 0.0] {
            assert_eq!(number(x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(1.25e-7), "1.25e-7");
    }
}
