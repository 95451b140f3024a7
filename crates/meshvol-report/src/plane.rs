//! The one syntax of a plane, wherever one is given: `meshvol section --plane`,
//! `meshvol below --plane`, and the text form of Python's `plane=` arguments.
//!
//! | text | plane |
//! |---|---|
//! | `z=H` (`x=H`, `y=H`) | the coordinate equals H |
//! | `PX,PY,PZ,NX,NY,NZ` | through the point (PX, PY, PZ), normal (NX, NY, NZ) |
//! | `NX,NY,NZ,D` | the points x with n·x = D |
//!
//! Every form gives both what `section` cuts with (a [`Plane`] and its 2D frame) and
//! what `below` keeps (the half-space n·x ≤ D), so the two commands take the same text.
//! The normal is any non-zero length; its direction says which side is below.

use meshvol::section::{Plane, PlaneError};
use std::str::FromStr;

/// A plane as the user wrote it (see the module's table).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlaneArg {
    /// `z=H`, `x=H`, `y=H`: coordinate `axis` (0 = x, 1 = y, 2 = z) equals `value`.
    Axis { axis: usize, value: f64 },
    /// `PX,PY,PZ,NX,NY,NZ`: through `point`, with `normal`.
    PointNormal { point: [f64; 3], normal: [f64; 3] },
    /// `NX,NY,NZ,D`: the points x with `normal`·x = `d`.
    NormalOffset { normal: [f64; 3], d: f64 },
}

/// The forms, as error messages and help name them.
pub const PLANE_SYNTAX: &str =
    "z=H (or x=H, y=H), a point and a normal PX,PY,PZ,NX,NY,NZ, or a normal and an offset \
     NX,NY,NZ,D (the plane n·x = D)";

impl FromStr for PlaneArg {
    type Err = String;

    fn from_str(s: &str) -> Result<PlaneArg, String> {
        let number =
            |t: &str| -> Result<f64, String> {
                t.trim().parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| {
                    format!("'{}' is not a finite number: use {PLANE_SYNTAX}", t.trim())
                })
            };
        if let Some((axis, value)) = s.split_once('=') {
            let axis = match axis.trim().to_ascii_lowercase().as_str() {
                "x" => 0,
                "y" => 1,
                "z" => 2,
                other => return Err(format!("'{other}' is not an axis: use {PLANE_SYNTAX}")),
            };
            return Ok(PlaneArg::Axis { axis, value: number(value)? });
        }
        let values: Vec<f64> = s.split(',').map(number).collect::<Result<_, _>>()?;
        let plane = match values[..] {
            [px, py, pz, nx, ny, nz] => {
                PlaneArg::PointNormal { point: [px, py, pz], normal: [nx, ny, nz] }
            }
            [nx, ny, nz, d] => PlaneArg::NormalOffset { normal: [nx, ny, nz], d },
            _ => {
                return Err(format!(
                    "expected {PLANE_SYNTAX}; found {} number(s) in '{s}'",
                    values.len()
                ))
            }
        };
        plane.checked()
    }
}

impl PlaneArg {
    /// The plane, refused when its normal is zero or a number is not finite (as
    /// [`FromStr`] refuses it); for a `PlaneArg` built from numbers, not text.
    pub fn checked(self) -> Result<PlaneArg, String> {
        self.plane().map(|_| self).map_err(|e| format!("{e}: use {PLANE_SYNTAX}"))
    }

    /// The plane `section` cuts with. An axis plane keeps world coordinates in its 2D
    /// frame (`z=H`: (x, y)); the others get an orthonormal frame at a point of theirs.
    pub fn plane(&self) -> Result<Plane, PlaneError> {
        match *self {
            PlaneArg::Axis { axis, value } => Plane::axis(axis, value),
            PlaneArg::PointNormal { point, normal } => Plane::new(point, normal),
            PlaneArg::NormalOffset { normal, d } => {
                // The point of the plane nearest the origin: n·(d n / |n|²) = d.
                let squared: f64 = normal.iter().map(|x| x * x).sum();
                if squared == 0.0 {
                    return Err(PlaneError::ZeroNormal);
                }
                Plane::new(normal.map(|x| x * d / squared), normal)
            }
        }
    }

    /// The plane as (n, D), the half-space n·x ≤ D being below it: `z=H` is
    /// ((0, 0, 1), H); a point p and a normal n give (n, n·p).
    pub fn normal_offset(&self) -> ([f64; 3], f64) {
        match *self {
            PlaneArg::Axis { axis, value } => {
                let mut normal = [0.0; 3];
                normal[axis] = 1.0;
                (normal, value)
            }
            PlaneArg::PointNormal { point, normal } => {
                (normal, (0..3).map(|k| normal[k] * point[k]).sum())
            }
            PlaneArg::NormalOffset { normal, d } => (normal, d),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<PlaneArg, String> {
        s.parse()
    }

    #[test]
    fn every_form_parses_to_the_plane_it_names() {
        assert_eq!(parse("z=1.5"), Ok(PlaneArg::Axis { axis: 2, value: 1.5 }));
        assert_eq!(parse(" X = -2"), Ok(PlaneArg::Axis { axis: 0, value: -2.0 }));
        let six = parse("1,2,3, 0,0,2").unwrap();
        assert_eq!(six, PlaneArg::PointNormal { point: [1.0, 2.0, 3.0], normal: [0.0, 0.0, 2.0] });
        let four = parse("0,0,2,10").unwrap();
        assert_eq!(four, PlaneArg::NormalOffset { normal: [0.0, 0.0, 2.0], d: 10.0 });
    }

    /// The three ways of writing the plane z = 5 give the same half-space (up to the
    /// normal's length) and planes through the same points with the same normal.
    #[test]
    fn the_three_forms_of_one_plane_agree() {
        let forms = ["z=5", "7,-3,5,0,0,1", "0,0,2,10"];
        for text in forms {
            let arg = parse(text).unwrap();
            let (n, d) = arg.normal_offset();
            let length = n.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert_eq!((n.map(|x| x / length), d / length), ([0.0, 0.0, 1.0], 5.0), "{text}");
            let frame = arg.plane().unwrap().frame();
            assert_eq!(frame.normal, [0.0, 0.0, 1.0], "{text}");
            assert_eq!(frame.origin[2], 5.0, "{text}");
        }
        // A tilted plane: n = (1, 1, 0), D = 2 passes through (1, 1, 0) and (2, 0, 0).
        let frame = parse("1,1,0,2").unwrap().plane().unwrap().frame();
        let on = |p: [f64; 3]| (0..3).map(|k| (p[k] - frame.origin[k]) * frame.normal[k]).sum();
        for p in [[1.0, 1.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 7.0]] {
            let distance: f64 = on(p);
            assert!(distance.abs() < 1e-15, "{p:?}: {distance}");
        }
        // y=H is below where y ≤ H, whatever its 2D frame's normal (u × v = −y).
        assert_eq!(parse("y=4").unwrap().normal_offset(), ([0.0, 1.0, 0.0], 4.0));
    }

    #[test]
    fn malformed_planes_say_what_is_wrong_and_what_is_taken() {
        for (text, says) in [
            ("w=1", "'w' is not an axis"),
            ("z=abc", "'abc' is not a finite number"),
            ("z=inf", "'inf' is not a finite number"),
            ("1,2,3", "found 3 number(s)"),
            ("1,2,3,4,5", "found 5 number(s)"),
            ("0,0,0,0,0,0", "normal is zero"),
            ("0,0,0,5", "normal is zero"),
            ("", "'' is not a finite number"),
        ] {
            let e = parse(text).unwrap_err();
            assert!(e.contains(says), "{text}: {e}");
            assert!(e.contains("NX,NY,NZ,D") && e.contains("z=H"), "{text}: {e}");
        }
    }
}
