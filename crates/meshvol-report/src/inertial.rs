//! Mass and inertia as robot descriptions want them: the `<inertial>` element of URDF,
//! of SDF, and MuJoCo's MJCF, from a volume report in SI units.
//!
//! All three take the mass in kilograms, the centre of mass in metres (the element's
//! origin, axes parallel to the link frame: the file's axes) and the inertia tensor about
//! it in kg·m², whose off-diagonal entries are I_xy = −∫ x y dm (the tensor, not the
//! products of inertia): exactly the report's `inertia`. URDF and SDF list ixx ixy ixz
//! iyy iyz izz; MJCF's `fullinertia` lists ixx iyy izz ixy ixz iyz.

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

/// The `<inertial>` element of `report` in `format`. The report must be in metres (a
/// unit conversion to m, or a file declaring metres), so that with a density in kg/m³
/// the mass is in kg; and its solid must have a volume.
pub fn inertial(report: &VolumeReport, format: RobotFormat) -> Result<String, String> {
    let file = report.file.as_deref().unwrap_or("mesh");
    if report.units.as_ref().is_none_or(|u| u.length != "m") {
        return Err(format!(
            "{file}: robot descriptions are in metres and kilograms: report in metres \
             (--units FILE:m, e.g. mm:m; in Python units=\"mm:m\") with the density in kg/m³"
        ));
    }
    let c = report.centroid.ok_or_else(|| {
        format!("{file}: the solid has no volume, so no centre of mass or inertia")
    })?;
    let [x, y, z] = c.map(number);
    let m = number(report.mass);
    let i = report.inertia.map(|row| row.map(number));
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
