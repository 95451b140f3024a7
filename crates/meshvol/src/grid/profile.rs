//! Profiles along an axis: the volume below each level, the volume of each slab between
//! levels, and the area of the solid's cross-section at each level (a tank strapping
//! table, a displacement curve, a fill-level curve).
//!
//! # Math
//! A profile is the column–clamp method ([module docs](super)) with one column over the
//! whole footprint and the levels as layer planes: slab k's volume is
//! `∫ over S of g_k(z) n_z dA` with `g_k(z) = clamp(z, t_k, t_{k+1}) − t_k`, and the volume
//! below t_k is the sum of the slabs under it. The axis is rotated to z by a cyclic
//! permutation of the coordinates (which keeps the winding's sign).
//!
//! The section area is the derivative of the volume below: with
//! `V(t) = ∫ over S of (min(z, t) − t_0) n_z dA`, `V′(t) = ∫ over S ∩ {z > t} of n_z dA`, the
//! signed projected area of the surface above the plane (the part above and the section
//! close up, so the two have the same projected area). Where a face lies flat on the
//! plane the derivative jumps; the reported `section_area` is then the area just above the
//! level (the right derivative, which leaves out such faces), except at the last level,
//! where it is the area just below (the left derivative, which counts them). A box from
//! z = 0 to 1 thus reports its footprint at 0 and at 1.

use super::cells::{sweep_layers, ColumnSink, Piece};
use crate::accumulate::CHUNK_FACES;
use crate::accumulate::{ordered_reduce, two_sum};
use crate::{Point, Surface};

/// A coordinate axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    X,
    Y,
    Z,
}

impl Axis {
    /// 0, 1 or 2.
    pub fn index(self) -> usize {
        self as usize
    }

    /// `x`, `y` or `z`.
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self as usize]
    }

    /// The cyclic permutation that brings this axis to the third place: (y, z, x) for x,
    /// (z, x, y) for y.
    fn permute(self, p: Point) -> Point {
        match self {
            Axis::X => [p[1], p[2], p[0]],
            Axis::Y => [p[2], p[0], p[1]],
            Axis::Z => p,
        }
    }
}

/// Where the levels of a profile lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Levels {
    /// `n + 1` equally spaced levels from the surface's minimum to its maximum.
    Count(usize),
    /// Levels every `h` from the minimum, up to the first at or above the maximum.
    Step(f64),
}

/// At most this many levels (2²⁴).
pub const MAX_LEVELS: usize = 1 << 24;

/// Why a profile cannot be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProfileError {
    #[error("the surface has no faces")]
    NoFaces,
    #[error("the surface is flat along {axis} (all of it at {axis} = {at}): there is no volume to profile")]
    Flat { axis: &'static str, at: f64 },
    #[error("the number of slabs must be at least 1")]
    NoSlabs,
    #[error("the step must be positive and finite; got {0}")]
    BadStep(f64),
    #[error("{levels} levels are too many (at most {MAX_LEVELS})")]
    TooManyLevels { levels: f64 },
}

/// A profile: `levels[k]`, and at each level the volume below it and the section area;
/// `slab_volume[k]` lies between `levels[k]` and `levels[k + 1]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    pub axis: Axis,
    pub levels: Vec<f64>,
    pub volume_below: Vec<f64>,
    pub slab_volume: Vec<f64>,
    pub section_area: Vec<f64>,
}

/// Per-slab sums in slab units: `direct[k] = ∫ (u − k) dA` of parts in slab k,
/// `area[k]` their projected area (`area[n]`: parts above the last level), and
/// `flat[m]` the area of parts lying flat on level m.
#[derive(Clone)]
struct Sums {
    direct: Vec<f64>,
    area: Vec<f64>,
    flat: Vec<f64>,
}

impl Sums {
    fn merge(&mut self, other: Sums) {
        for (a, b) in [
            (&mut self.direct, other.direct),
            (&mut self.area, other.area),
            (&mut self.flat, other.flat),
        ] {
            for (x, y) in a.iter_mut().zip(b) {
                *x += y;
            }
        }
    }
}

/// The least and greatest coordinate of the surface's vertices along `axis`.
fn extent<S: Surface + ?Sized>(surface: &S, axis: usize) -> Option<(f64, f64)> {
    ordered_reduce(
        surface.face_count(),
        CHUNK_FACES,
        |range| {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for f in range {
                surface.fan(f, |a, b, c| {
                    for p in [a, b, c] {
                        lo = lo.min(p[axis]);
                        hi = hi.max(p[axis]);
                    }
                });
            }
            (lo, hi)
        },
        |a, b| *a = (a.0.min(b.0), a.1.max(b.1)),
    )
    .filter(|(lo, hi)| lo <= hi)
}

/// The profile of the solid bounded by `surface` along `axis`.
///
/// ```
/// use meshvol::grid::{profile, Axis, Levels};
/// use meshvol::shapes::cuboid;
/// let p = profile(&cuboid([0.0; 3], [2.0, 3.0, 4.0]), Axis::Z, Levels::Count(4)).unwrap();
/// assert_eq!(p.levels, vec![0.0, 1.0, 2.0, 3.0, 4.0]);
/// assert_eq!(p.volume_below, vec![0.0, 6.0, 12.0, 18.0, 24.0]);
/// assert_eq!(p.slab_volume, vec![6.0; 4]);
/// assert_eq!(p.section_area, vec![6.0; 5]);
/// ```
pub fn profile<S: Surface + ?Sized>(
    surface: &S,
    axis: Axis,
    levels: Levels,
) -> Result<Profile, ProfileError> {
    let (min, max) = extent(surface, axis.index()).ok_or(ProfileError::NoFaces)?;
    if min == max {
        return Err(ProfileError::Flat { axis: axis.name(), at: min });
    }
    let (slabs, step) = match levels {
        Levels::Count(0) => return Err(ProfileError::NoSlabs),
        Levels::Count(n) => (n as f64, (max - min) / n as f64),
        Levels::Step(h) if !(h.is_finite() && h > 0.0) => return Err(ProfileError::BadStep(h)),
        Levels::Step(h) => (((max - min) / h).ceil().max(1.0), h),
    };
    let within = slabs < MAX_LEVELS as f64;
    if !within || step == 0.0 {
        return Err(ProfileError::TooManyLevels { levels: slabs + 1.0 });
    }
    let n = slabs as usize;
    let mut level_values: Vec<f64> = (0..=n).map(|k| min + k as f64 * step).collect();
    if matches!(levels, Levels::Count(_)) {
        level_values[n] = max;
    }

    let faces = surface.face_count();
    let r = crate::mesh::first_corner(surface).map_or([0.0; 3], |a| axis.permute(a));
    let to_units = |p: Point| {
        let q = axis.permute(p);
        [q[0] - r[0], q[1] - r[1], (q[2] - min) / step]
    };
    // Enough faces per chunk that the chunks' sums (3·(n + 1) doubles each) stay within
    // about 2²² doubles together; the chunking depends on the input only.
    let chunk = CHUNK_FACES.max(faces.div_ceil(((1usize << 22) / (3 * (n + 1))).max(1)));
    let empty = Sums { direct: vec![0.0; n], area: vec![0.0; n + 1], flat: vec![0.0; n + 1] };
    let sums = ordered_reduce(
        faces,
        chunk,
        |range| {
            let mut sums = empty.clone();
            for f in range {
                surface.fan(f, |a, b, c| {
                    let t = Piece::triangle(to_units(a), to_units(b), to_units(c));
                    let (z0, z1) = t.range(2);
                    if z0 == z1 && z0.fract() == 0.0 && (0.0..=n as f64).contains(&z0) {
                        sums.flat[z0 as usize] += t.area();
                    }
                    let mut sink =
                        ColumnSink { direct: &mut sums.direct, area: &mut sums.area, first: 0 };
                    sweep_layers(&t, (z0, z1), n, &mut sink);
                });
            }
            sums
        },
        Sums::merge,
    )
    .unwrap_or(empty);

    // Suffix sums: area above each level, and the slabs.
    let mut slab_volume = vec![0.0; n];
    let mut section_area = vec![0.0; n + 1];
    let (mut above, mut compensation) = (sums.area[n], 0.0);
    section_area[n] = above;
    for k in (0..n).rev() {
        slab_volume[k] = (sums.direct[k] + (above + compensation)) * step;
        let (s, e) = two_sum(above, sums.area[k]);
        above = s;
        compensation += e;
        section_area[k] = (above + compensation) - sums.flat[k];
    }
    let mut volume_below = Vec::with_capacity(n + 1);
    let (mut below, mut compensation) = (0.0, 0.0);
    volume_below.push(0.0);
    for &v in &slab_volume {
        let (s, e) = two_sum(below, v);
        below = s;
        compensation += e;
        volume_below.push(below + compensation);
    }
    Ok(Profile { axis, levels: level_values, volume_below, slab_volume, section_area })
}
