//! The convex hull of a point set, as a closed outward triangle mesh, and its volume,
//! area and centroid.
//!
//! # Method
//! 1. Degenerate sets are recognised exactly before any hull is attempted: no points,
//!    all points equal, all on one line, all in one plane. Each is decided with exact
//!    predicates (Shewchuk's orientation tests, `robust` crate): a point set is flat
//!    when every point has orientation exactly 0 against three points that span the
//!    plane. Such sets have volume 0, and say why.
//! 2. The points are translated by the first point r (`x − r` is exact for points
//!    within a factor of two of r, as a cloud far from the origin is), and hulled with
//!    parry3d-f64's quickhull (`try_convex_hull`), which works in coordinates
//!    normalised to the cloud's box.
//! 3. The hull mesh is measured with [`crate::mass_properties`] (compensated sums about
//!    a vertex), and translated back.
//!
//! # Why parry, and why behind a feature
//! parry3d-f64 is maintained, pure Rust, and its quickhull is the one the Rust geometry
//! ecosystem tests most; the qhull crate needs libclang at build time. But parry and its
//! math stack take about 90 s to compile against a few seconds for the rest of this
//! crate, so the hull is behind the `hull` cargo feature (off by default; the `meshvol`
//! command turns it on). Its floating-point quickhull can fail on sets that are flat to
//! within its tolerance without being exactly flat; that is reported as
//! [`HullError::NearlyFlat`], never a panic.
//!
//! # Cost
//! parry clears a workspace the size of its input for every point it adds to the hull,
//! so it costs about n·h. Hulling fixed chunks of 16 384 points first (in parallel) and
//! keeping only their hull vertices makes that n·(a chunk's h) + (candidates)·h: a
//! million points in a ball take 0.7 s of CPU time, text parsing included (release
//! build). Sets whose points are nearly all hull vertices (points on a sphere) stay
//! n·h: 100 000 of them take 1.7 s, a million would take minutes.

use parry3d_f64::math::Vector3;
use parry3d_f64::transformation::try_convex_hull;

use crate::vector::{add, sub};
use crate::{mass_properties, MassProperties, Mesh, Point};

/// Why a point set has no solid hull.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degeneracy {
    /// No points at all.
    NoPoints,
    /// Every point is the same point.
    AllCoincide,
    /// Every point lies on one line.
    Collinear,
    /// Every point lies in one plane.
    Coplanar,
}

impl std::fmt::Display for Degeneracy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Degeneracy::NoPoints => "there are no points",
            Degeneracy::AllCoincide => "all points are the same point",
            Degeneracy::Collinear => "all points lie on one line",
            Degeneracy::Coplanar => "all points lie in one plane",
        })
    }
}

/// Why a hull could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HullError {
    #[error("point {index} has a non-finite coordinate ({value})")]
    NonFinite { index: usize, value: f64 },
    #[error(
        "the points are not exactly flat, but too close to a plane or line for the hull \
         algorithm ({0}); their volume is negligible next to their extent"
    )]
    NearlyFlat(String),
    #[error("{0} points do not fit 32-bit indices")]
    TooManyPoints(usize),
    #[error("the hull algorithm returned an invalid mesh: {0}")]
    InvalidResult(String),
}

/// A convex hull and its measurements.
#[derive(Clone, Debug)]
pub struct Hull {
    /// The hull as outward-wound triangles over its vertices (a subset of the input
    /// points); `None` for a degenerate set.
    pub mesh: Option<Mesh>,
    /// Volume, area, centroid and inertia of the hull's solid; zero with no centroid for
    /// a degenerate set.
    pub properties: MassProperties,
    /// Why the set has no solid hull, when it has none.
    pub degeneracy: Option<Degeneracy>,
}

impl Hull {
    /// The hull's volume (0 for a degenerate set).
    pub fn volume(&self) -> f64 {
        self.properties.volume()
    }
}

fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let coord = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
    robust::orient2d(coord(a), coord(b), coord(c))
}

fn orient3d(a: Point, b: Point, c: Point, d: Point) -> f64 {
    let coord = |p: Point| robust::Coord3D { x: p[0], y: p[1], z: p[2] };
    robust::orient3d(coord(a), coord(b), coord(c), coord(d))
}

/// Whether a, b, c lie on one line, exactly: all three coordinate-plane projections are
/// collinear.
fn collinear(a: Point, b: Point, c: Point) -> bool {
    [[0, 1], [1, 2], [2, 0]]
        .iter()
        .all(|&[i, j]| orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]) == 0.0)
}

/// The exact degeneracy of a point set, if it has one.
fn degeneracy(points: &[Point]) -> Option<Degeneracy> {
    let Some(&a) = points.first() else { return Some(Degeneracy::NoPoints) };
    let Some(&b) = points.iter().find(|&&p| p != a) else {
        return Some(Degeneracy::AllCoincide);
    };
    let Some(&c) = points.iter().find(|&&p| !collinear(a, b, p)) else {
        return Some(Degeneracy::Collinear);
    };
    if points.iter().all(|&p| orient3d(a, b, c, p) == 0.0) {
        return Some(Degeneracy::Coplanar);
    }
    None
}

/// Points per chunk of the first pass of [`candidates`].
const CHUNK_POINTS: usize = 1 << 14;

/// parry's hull, with a panic inside it (an internal assertion on some input nobody has
/// tried) turned into an error rather than taking the caller down.
fn hull_of(points: &[Vector3]) -> Result<(Vec<Vector3>, Vec<[u32; 3]>), HullError> {
    std::panic::catch_unwind(|| try_convex_hull(points))
        .map_err(|_| HullError::InvalidResult("the hull algorithm failed on this input".into()))?
        .map_err(|e| HullError::NearlyFlat(e.to_string()))
}

/// The points that can be vertices of the hull. parry's quickhull clears a workspace the
/// size of its input for every point it adds, so its cost grows as n·h; hulling fixed
/// chunks first (in parallel, deterministically) and keeping only each chunk's hull
/// vertices (a point inside its chunk's hull is inside the whole hull) cuts a million
/// points in a ball to about 20 000 candidates. A chunk parry cannot hull keeps all its
/// points.
fn candidates(points: &[Vector3]) -> Vec<Vector3> {
    if points.len() <= 2 * CHUNK_POINTS {
        return points.to_vec();
    }
    crate::accumulate::ordered_reduce(
        points.len(),
        CHUNK_POINTS,
        |range| match hull_of(&points[range.clone()]) {
            Ok((vertices, _)) => vertices,
            Err(_) => points[range].to_vec(),
        },
        |all, part| all.extend(part),
    )
    .unwrap_or_default()
}

/// The convex hull of `points`.
///
/// ```
/// use meshvol::hull::{convex_hull, Degeneracy};
/// // The corners of a box far from the origin, with an inside point and a duplicate.
/// let o = 1.0e7;
/// let mut points: Vec<[f64; 3]> = (0..8)
///     .map(|i| [o + (i & 1) as f64 * 3.0, o + (i >> 1 & 1) as f64 * 2.0, o + (i >> 2) as f64])
///     .collect();
/// points.push([o + 1.0, o + 1.0, o + 0.5]);
/// points.push(points[0]);
/// let hull = convex_hull(&points).unwrap();
/// assert_eq!(hull.volume(), 6.0);
/// assert_eq!(hull.properties.area, 2.0 * (6.0 + 3.0 + 2.0));
/// assert_eq!(hull.properties.centroid, Some([o + 1.5, o + 1.0, o + 0.5]));
/// assert_eq!(hull.mesh.unwrap().vertex_count(), 8);
///
/// // Flat sets have volume 0 and say why.
/// let flat = convex_hull(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]).unwrap();
/// assert_eq!((flat.volume(), flat.degeneracy), (0.0, Some(Degeneracy::Coplanar)));
/// ```
pub fn convex_hull(points: &[Point]) -> Result<Hull, HullError> {
    for (index, p) in points.iter().enumerate() {
        if let Some(&value) = p.iter().find(|x| !x.is_finite()) {
            return Err(HullError::NonFinite { index, value });
        }
    }
    if u32::try_from(points.len()).is_err() {
        return Err(HullError::TooManyPoints(points.len()));
    }
    if let Some(d) = degeneracy(points) {
        return Ok(Hull { mesh: None, properties: MassProperties::empty(0), degeneracy: Some(d) });
    }
    let reference = points[0];
    let local: Vec<Vector3> = points
        .iter()
        .map(|&p| {
            let [x, y, z] = sub(p, reference);
            Vector3::new(x, y, z)
        })
        .collect();
    let candidates = candidates(&local);
    drop(local);
    let (vertices, mut triangles) = hull_of(&candidates)?;
    let positions: Vec<Point> = vertices.iter().map(|v| [v.x, v.y, v.z]).collect();
    let invalid = |e: crate::MeshError| HullError::InvalidResult(e.to_string());
    let local_mesh = Mesh::from_triangles(positions, triangles.clone()).map_err(invalid)?;
    let mut properties = mass_properties(&local_mesh);
    if properties.centroid.is_none() {
        return Err(HullError::NearlyFlat("the hull it built encloses no volume".into()));
    }
    if properties.signed_volume < 0.0 {
        triangles.iter_mut().for_each(|t| t.swap(1, 2));
        properties = mass_properties(&local_mesh.flipped());
    }
    properties.centroid = properties.centroid.map(|c| add(c, reference));
    properties.bounds = properties
        .bounds
        .map(|b| crate::Bounds { min: add(b.min, reference), max: add(b.max, reference) });
    let world = local_mesh.positions().iter().map(|&p| add(p, reference)).collect();
    let mesh = Mesh::from_triangles(world, triangles).map_err(invalid)?;
    Ok(Hull { mesh: Some(mesh), properties, degeneracy: None })
}
