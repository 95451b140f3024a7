//! The part of a solid on one side of a plane: its volume and centroid (displaced volume
//! and centre of buoyancy), the area of the surface there (wetted area), and the
//! section in the plane (waterplane area and centroid); and the plane's level that
//! leaves a given volume below it (a draft).
//!
//! Math: cut each fan triangle by the half-space n·(x − o) ≤ 0 (o on the plane), and
//! close the cut surface with a cap in the plane: a fan of triangles from o over the
//! rim (each cut triangle's edges that lie in the plane, joined to o). The part is then
//! a closed solid, measured by [`crate::mass_properties`] like any other (volume,
//! centroid, inertia); the wetted area is the cut surface's own. The section comes from
//! [`crate::section::section`].
//!
//! ```
//! use meshvol::below::below;
//! use meshvol::section::Plane;
//! use meshvol::shapes::cuboid;
//! // The unit cube below x + z = 1: half of it.
//! let plane = Plane::new([0.5, 0.0, 0.5], [1.0, 0.0, 1.0]).unwrap();
//! let part = below(&cuboid([0.0; 3], [1.0; 3]), &plane);
//! assert!((part.part.signed_volume - 0.5).abs() < 1e-15);
//! ```

use crate::polygon::area_properties;
use crate::section::{section, Plane};
use crate::vector::{add, dot, scale, sub};
use crate::{mass_properties, MassProperties, Point, Surface};

/// The part of a solid below a plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Below {
    /// The part's mass properties (volume, centroid, inertia about its centroid);
    /// `area` is the wetted area: the solid's surface below the plane.
    pub part: MassProperties,
    /// The area of the solid's section by the plane.
    pub section_area: f64,
    /// The section's centroid, in space; `None` without a section.
    pub section_centroid: Option<Point>,
}

/// A surface's triangles cut by the half-space n·(x − o) ≤ 0, moved by −o; with `caps`,
/// each cut triangle's edges in the plane are joined to o (the cap as a fan from o over
/// the rim: each rim edge is in one kept triangle, an edge in the plane between two kept
/// triangles gets two caps that cancel), so the cut surface is closed. Triangles wholly
/// in the plane are the cap's own and are left out.
struct Cut<'a, S: ?Sized> {
    surface: &'a S,
    origin: Point,
    normal: Point,
    caps: bool,
}

impl<S: Surface + ?Sized> Surface for Cut<'_, S> {
    fn face_count(&self) -> usize {
        self.surface.face_count()
    }

    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        self.surface.fan(face, |a, b, c| {
            let p = [a, b, c].map(|x| sub(x, self.origin));
            let s = p.map(|x| dot(self.normal, x));
            // Sutherland–Hodgman against one plane: at most four corners, each marked
            // when it is in the plane (a crossing, or a corner on it).
            let mut kept = [([0.0; 3], false); 4];
            let mut n = 0;
            for i in 0..3 {
                let j = (i + 1) % 3;
                if s[i] <= 0.0 {
                    kept[n] = (p[i], s[i] == 0.0);
                    n += 1;
                }
                if (s[i] < 0.0 && s[j] > 0.0) || (s[i] > 0.0 && s[j] < 0.0) {
                    let t = s[i] / (s[i] - s[j]);
                    kept[n] = (add(p[i], scale(sub(p[j], p[i]), t)), true);
                    n += 1;
                }
            }
            if n < 3 || kept[..n].iter().all(|k| k.1) {
                return;
            }
            for k in 1..n - 1 {
                triangle(kept[0].0, kept[k].0, kept[k + 1].0);
            }
            if self.caps {
                for k in 0..n {
                    let (x, y) = (kept[k], kept[(k + 1) % n]);
                    if x.1 && y.1 {
                        triangle([0.0; 3], y.0, x.0);
                    }
                }
            }
        });
    }
}

/// The part of the solid `surface` bounds where n·x ≤ n·o, for the plane's point o and
/// normal n (its frame's).
pub fn below<S: Surface + ?Sized>(surface: &S, plane: &Plane) -> Below {
    let frame = plane.frame();
    let cut = |caps| Cut { surface, origin: frame.origin, normal: frame.normal, caps };
    // Closed by its cap, the part's sums do not depend on the point they are taken
    // about; its wetted area is that of the cut surface alone.
    let mut part = mass_properties(&cut(true));
    let wetted = mass_properties(&cut(false));
    part.area = wetted.area;
    part.centroid = part.centroid.map(|c| add(c, frame.origin));
    part.bounds = wetted.bounds.map(|mut b| {
        b.min = add(b.min, frame.origin);
        b.max = add(b.max, frame.origin);
        b
    });
    let props = area_properties(&section(surface, plane).polygons);
    let section_centroid =
        props.centroid.map(|[s, t]| add(frame.origin, add(scale(frame.u, s), scale(frame.v, t))));
    Below { part, section_area: props.area, section_centroid }
}

/// Why no level holds a volume.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum LevelError {
    #[error("the direction must be a finite, non-zero vector")]
    BadDirection,
    #[error("the volume {volume} is not between 0 and the solid's volume {total}")]
    OutOfRange { volume: f64, total: f64 },
    #[error("the surface has no vertices")]
    Empty,
    /// The volume below is not monotone in the level (a surface that is not closed):
    /// the adjacent levels `level` and the next float hold `low` and `high`, which do not
    /// bracket the volume asked for, even allowing for their rounding bounds.
    #[error(
        "no level holds the volume {volume}: the volume below jumps from {low} to {high} at \
         the level {level} (the surface is not a closed solid)"
    )]
    NotReached { volume: f64, level: f64, low: f64, high: f64 },
}

/// The level d such that the part of the solid where n̂·x ≤ d (n̂ = `direction`
/// normalized) has volume `volume`: bisection on the part's volume, which grows with d,
/// to the last bit of d (about 64 steps, each one pass over the triangles).
///
/// The answer is checked, never assumed: the volumes at the final bracket's two levels
/// (adjacent floats), widened by their rounding bounds, must hold `volume` between
/// them, or the search did not converge ([`LevelError::NotReached`]); of the two, the
/// level whose volume is nearer is returned.
pub fn level_for_volume<S: Surface + ?Sized>(
    surface: &S,
    direction: Point,
    volume: f64,
) -> Result<f64, LevelError> {
    let length = dot(direction, direction).sqrt();
    if !(length.is_finite() && length > 0.0) {
        return Err(LevelError::BadDirection);
    }
    let n = scale(direction, 1.0 / length);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for f in 0..surface.face_count() {
        surface.fan(f, |a, b, c| {
            for x in [a, b, c] {
                let d = dot(n, x);
                lo = lo.min(d);
                hi = hi.max(d);
            }
        });
    }
    if lo > hi {
        return Err(LevelError::Empty);
    }
    let total = mass_properties(surface).signed_volume;
    if !(volume >= 0.0 && volume <= total) {
        return Err(LevelError::OutOfRange { volume, total });
    }
    let at = |d: f64| {
        let plane = Plane::new(scale(n, d), n).map_err(|_| LevelError::BadDirection)?;
        let part = below(surface, &plane).part;
        Ok((part.signed_volume, part.volume_error_bound))
    };
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if at(mid)?.0 < volume {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let ((low, low_bound), (high, high_bound)) = (at(lo)?, at(hi)?);
    if !(low - low_bound <= volume && volume <= high + high_bound) {
        return Err(LevelError::NotReached { volume, level: lo, low, high });
    }
    Ok(if volume - low <= high - volume { lo } else { hi })
}
