//! The convex hull of a point set, as a closed outward triangle mesh, and its volume,
//! area and centroid.
//!
//! # Method
//! | stage | what | where |
//! |---|---|---|
//! | 1 | degenerate sets: no points, all equal, all on a line, all in a plane | `degeneracy` |
//! | 1½ | chunks of 16 384 points hulled alone, their corners kept, where that pays | `candidates` |
//! | 2 | a fixed-seed biased random insertion order; the first tetrahedron in it | `incremental` |
//! | 3 | every point on the conflict list of one tetrahedron face it sees (parallel) | `incremental` |
//! | 4 | insert each point still outside, in order; move the conflicts of removed faces | `incremental` |
//! | 5 | vertices that are not corners (coplanar input): hull the corners again | `incremental` |
//! | 6 | measure with [`crate::mass_properties`] about a hull vertex | [`convex_hull`] |
//!
//! 1. Degenerate sets are recognised exactly before any hull is attempted. Each is
//!    decided with exact predicates (Shewchuk's orientation tests, `robust` crate): a
//!    point set is flat when every point has orientation exactly 0 against three points
//!    that span the plane. Such sets have volume 0, and say why.
//!
//!    1½. A point inside the hull of some of the points is no corner of the hull, so
//!    when the first chunk of 16 384 points keeps under an eighth of them as corners
//!    (points in a ball: a few percent), every chunk is hulled on its own, in parallel, and
//!    only the chunks' corners go on. Points mostly on the hull (a sphere) skip this.
//!    A chunk is every m-th point (m chunks), not a run of consecutive points: a run
//!    of an ordered cloud (a lattice in file order) is a flat slab whose points are
//!    nearly all on its own hull, so every one would be kept, after an exact test.
//! 2. The hull is built by randomized incremental construction (Clarkson and Shor
//!    1989; de Berg et al., *Computational Geometry*, ch. 11). Points go in in a random
//!    order, fixed by a seed, so the hull is the same on every run and thread count; the
//!    order is a biased randomized one (Amenta, Choi and Rote 2003): rounds of doubling
//!    size, each a random sample, each sorted along a Morton curve, which keeps the
//!    expected bound and lets consecutive insertions work on faces still in cache.
//! 3. Each point not yet inserted is on the conflict list of one hull face that it
//!    sees, i.e. whose plane it is strictly outside; a point that sees no face is inside
//!    and is dropped for good.
//! 4. Inserting p: the faces p sees are found by a walk from its conflict face over
//!    neighbours; they form a disc whose boundary (the horizon) is one cycle of edges,
//!    and each horizon edge (u, w) gets the new face (u, w, p). A point that saw a
//!    removed face either sees one of the new faces or is inside the new hull (the
//!    segment from it into a removed face leaves the new hull through the new part), so
//!    the removed faces' conflicts are tested against the new faces only.
//! 5. Coplanar points: a point exactly on a face's plane does not see that face, so a
//!    point on the boundary of the hull built so far is never inserted. But a point
//!    inserted early can end up inside a flat face or on an edge once later points
//!    flatten its neighbourhood; such a vertex has all its triangles in one or two
//!    planes (a corner's span three or more). When there are any, the hull's corners are
//!    hulled again, and then every input point is a corner. So the result's vertices are
//!    exactly the hull's corners (its extreme points); a flat face with more than three
//!    corners is split into triangles, coplanar with their neighbours.
//! 6. The mesh is measured with [`crate::mass_properties`] (compensated sums) in
//!    coordinates relative to a hull vertex, and translated back.
//!
//! # Predicates
//! Every decision is the sign of an orientation determinant, exact. For face (a, b, c)
//! and point q, the rounded `((b − a) × (c − a)) · (q − a)` is trusted when it exceeds
//! 10⁻¹⁵ · max(mₖ) · Σ|qₖ − aₖ|, mₖ being the absolute values of the normal component
//! k's two terms summed: that bounds the same expression over absolute values, and each
//! of its terms passes through at most 8 roundings (γ₈ < 8.9·10⁻¹⁶). Otherwise (nearly or
//! exactly coplanar points, or products near underflow) Shewchuk's adaptive orient3d
//! decides. So the hull is the exact convex hull of the input for every input,
//! cospherical, coplanar, duplicated or gridded alike. Points exactly on a face's plane
//! do not see it (the hull never grows by a flat step), which is also why duplicates need
//! no special case.
//!
//! # Cost
//! Expected O(n log n) time for every input (the expectation is over the insertion
//! order, not over the points), and O(n) memory: 36 bytes a hull face, about 40 a
//! point, and 32 a point on a conflict list. Points all on the hull (a sphere), where
//! quickhull's n·h cost shows, are no special case.
//!
//! `meshvol hull FILE` (release build, whole process, reading the `.xyz` included;
//! 2-core machine shared with other builds, load 0.7–3.5) against the parry3d-f64
//! quickhull this replaced (with its chunk pass) and against qhull (scipy 1.17
//! `ConvexHull`, the hull alone, after `numpy.loadtxt`), on the same points:
//!
//! | points | meshvol | parry (before) | qhull, hull alone |
//! |---|---|---|---|
//! | 100 000 on a sphere | 0.14–0.25 s | 1.6 s | 0.56–0.97 s |
//! | 1 000 000 on a sphere | 1.8–2.6 s | 234 s | 9.0–14.4 s |
//! | 5 000 000 on a sphere | 11.8–13.2 s | over 11 min | 48.6 s |
//! | 100 000 in a ball | 0.05–0.14 s | 0.06 s | 0.03 s |
//! | 1 000 000 in a ball | 0.39 s | 0.29–0.40 s | 0.29 s |
//! | 5 000 000 in a ball | 1.9 s | 1.5–1.9 s | 1.8 s |
//!
//! In-process (criterion, `cargo bench -p meshvol-bench --bench hull`, the hull and its
//! measurement alone, quiet machine; generated clouds of the same kinds, and the 5M
//! file): 100 000 / 1 000 000 / 5 000 000 points on a sphere 0.15 / 1.74 / 10.1 s (qhull's hull alone 0.56 / 9.0 / 48.6 s: 3.7–5.2×
//! ahead; parry 0.94 s at 100 000); 100 000 / 1 000 000 in a ball 0.024 / 0.18 s
//! (qhull 0.03 / 0.29 s). Whole processes in a ball stay up to 1.3× behind parry with
//! its chunks, which hulled a chunk with few corners faster.

mod incremental;

use incremental::collinear;

use crate::progress::{Counter, Progress};
use crate::vector::{add, orient3d, sub};
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

/// Points per chunk of [`candidates`].
const CHUNK_POINTS: usize = 1 << 14;

/// Above this share of its points kept as corners, the first chunk says the points
/// are mostly on the hull (as on a sphere), and chunks would not pay.
const KEPT_SHARE_TO_SKIP_CHUNKS: f64 = 0.125;

/// The indices of the points that can be corners of the hull (in increasing order),
/// when chunks cut them down: each fixed chunk of about [`CHUNK_POINTS`] is hulled on
/// its own (in parallel, the same on any number of threads) and only its corners are
/// kept, since a point in the hull of other points is no corner of the whole. A chunk
/// that is flat keeps all its points. A million points in a ball keep about 2%, and the
/// hull of the rest is then mostly the hull of points near its surface. `None` when
/// that would not pay: few points, or a first chunk that keeps more than
/// [`KEPT_SHARE_TO_SKIP_CHUNKS`] of its points.
///
/// Chunk j of m holds the points j, j + m, j + 2m, …: every chunk is spread over the
/// whole cloud. Runs of consecutive points would make an ordered cloud (a lattice in
/// file order, a scan line by line) into slabs with nearly every point on their own
/// hull's faces, each one kept and each one decided by exact arithmetic.
fn candidates(points: &[Point], progress: &dyn Progress) -> Option<Vec<u32>> {
    if points.len() < 4 * CHUNK_POINTS {
        return None;
    }
    let chunks = points.len().div_ceil(CHUNK_POINTS);
    let size = |j: usize| (points.len() - j).div_ceil(chunks);
    let corners_of = |j: usize| -> Vec<u32> {
        let indices: Vec<u32> = (j..points.len()).step_by(chunks).map(|i| i as u32).collect();
        let chunk: Vec<Point> = indices.iter().map(|&i| points[i as usize]).collect();
        if degeneracy(&chunk).is_some() {
            return indices;
        }
        let mut corner = vec![false; chunk.len()];
        incremental::hull_triangles(&chunk, &())
            .iter()
            .flatten()
            .for_each(|&v| corner[v as usize] = true);
        indices.into_iter().zip(corner).filter(|&(_, c)| c).map(|(i, _)| i).collect()
    };
    progress.stage("hulling chunks of points");
    let first = corners_of(0);
    if first.len() as f64 > KEPT_SHARE_TO_SKIP_CHUNKS * size(0) as f64 {
        return None;
    }
    let done = Counter::new(progress, points.len() - size(0));
    let rest = crate::accumulate::ordered_reduce(
        chunks - 1,
        1,
        |range| {
            let corners = corners_of(range.start + 1);
            done.add(size(range.start + 1));
            corners
        },
        |all, part| all.extend(part),
    );
    let mut kept: Vec<u32> = first.into_iter().chain(rest.into_iter().flatten()).collect();
    kept.sort_unstable();
    Some(kept)
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
    convex_hull_with(points, &())
}

/// [`convex_hull`], telling `progress` its stages (`hulling chunks of points`,
/// `inserting points`, ...) and the points hulled or inserted so far in each.
pub fn convex_hull_with(points: &[Point], progress: &dyn Progress) -> Result<Hull, HullError> {
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
    let triangles = match candidates(points, progress) {
        None => incremental::hull_triangles(points, progress),
        Some(kept) => {
            let subset: Vec<Point> = kept.iter().map(|&i| points[i as usize]).collect();
            let triangles = incremental::hull_triangles(&subset, progress);
            triangles.into_iter().map(|t| t.map(|v| kept[v as usize])).collect()
        }
    };
    let (vertices, triangles) = compact(points, &triangles);
    // Measured about a hull vertex: x − r is exact for points within a factor of two of
    // r, as a cloud far from the origin is, so the sums keep their precision.
    let reference = points[vertices[0] as usize];
    let local = vertices.iter().map(|&v| sub(points[v as usize], reference)).collect();
    let invalid = |e: crate::MeshError| HullError::InvalidResult(e.to_string());
    let mut properties =
        mass_properties(&Mesh::from_triangles(local, triangles.clone()).map_err(invalid)?);
    properties.centroid = properties.centroid.map(|c| add(c, reference));
    properties.bounds = properties
        .bounds
        .map(|b| crate::Bounds { min: add(b.min, reference), max: add(b.max, reference) });
    let world = vertices.iter().map(|&v| points[v as usize]).collect();
    let mesh = Mesh::from_triangles(world, triangles).map_err(invalid)?;
    Ok(Hull { mesh: Some(mesh), properties, degeneracy: None })
}

/// The hull's vertices in order of first use (indices into `points`), and its
/// triangles over them.
fn compact(points: &[Point], triangles: &[[u32; 3]]) -> (Vec<u32>, Vec<[u32; 3]>) {
    let mut index = vec![u32::MAX; points.len()];
    let mut vertices = Vec::new();
    let compacted = triangles
        .iter()
        .map(|t| {
            t.map(|v| {
                if index[v as usize] == u32::MAX {
                    index[v as usize] = vertices.len() as u32;
                    vertices.push(v);
                }
                index[v as usize]
            })
        })
        .collect();
    (vertices, compacted)
}

#[cfg(test)]
mod tests;
