//! The cross-section of a closed surface by a plane: closed loops, nested into polygons
//! with holes, in the plane's own 2D coordinates.
//!
//! # Method
//! Every vertex gets the side of the plane it is on, from its signed distance
//! d = (x − p)·n (for `x = h`, `y = h`, `z = h`: the coordinate minus h). A vertex exactly
//! on the plane (d = 0) counts as above it (d > 0): the section
//! is that of the surface moved down by an infinitesimal amount, so the section at a
//! level where the surface has a horizontal face is the limit of the sections just
//! below it, and every triangle crosses the plane along exactly two of its edges or
//! not at all.
//!
//! A triangle that crosses yields one segment, from the crossing on its edge that goes
//! from above to below (in the triangle's vertex order) to the crossing on the edge that
//! goes from below to above. For outward-wound triangles this winds the loops
//! counter-clockwise seen from above, around the solid; they are reported
//! counter-clockwise in the plane's 2D frame (see [`Plane::frame`]).
//!
//! Segments are chained through the edges they cross: an edge is named by its two end
//! points (below end first, the exact coordinate bits), and its crossing point is
//! computed from those two points in that order, t = d₋ / (d₋ − d₊),
//! x = x₋ + t (x₊ − x₋), or x = x₊ exactly when d₊ = 0. The two triangles that share an
//! edge therefore name it identically and compute the identical point, and chaining is
//! exact: no tolerance, no welding of nearby points. Chaining by edge and not by point
//! keeps loops that touch at an on-plane vertex apart, as the perturbation says they are.
//!
//! Loops are nested by exact point-in-polygon tests: a loop inside an even number of
//! others is an exterior, inside an odd number a hole of the smallest loop around it.
//! Areas and moments then come from [`crate::polygon::area_properties`].
//!
//! # Coordinates
//! An axis plane keeps world coordinates: `z = h` gives (x, y), `x = h` gives (y, z),
//! `y = h` gives (x, z) (so its frame's normal u × v is −y), each to the last bit. A general plane gets an orthonormal frame
//! (u, v) at its point p with u × v = n/|n|; coordinates are ((x − p)·u, (x − p)·v).
//!
//! # What is reported
//! A surface that is open along the plane leaves chains that do not close; a surface
//! whose edges are shared by more than two triangles, or wound inconsistently, leaves
//! edges crossed twice in one direction. Both are counted in [`Section`] and left out of
//! the polygons: the area of an open outline is not defined.

use std::collections::HashMap;

use crate::accumulate::ordered_reduce;
use crate::accumulate::CHUNK_FACES;
use crate::polygon::{point_in_ring, signed_area, Point2, Polygon};
use crate::vector::{cross, dot, norm, scale, sub};
use crate::{Point, Surface};

/// A plane and the 2D frame its sections are given in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    kind: PlaneKind,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum PlaneKind {
    /// Coordinate `axis` equals `value`; 2D coordinates are the other two axes, in the
    /// order of `AXIS_FRAMES`.
    Axis { axis: usize, value: f64 },
    /// Through `point`, unit `normal`, with unit `u` and `v = normal × u`.
    General { point: Point, normal: Point, u: Point, v: Point },
}

/// For a plane normal to axis k: the 2D coordinates' axes.
const AXIS_FRAMES: [[usize; 2]; 3] = [[1, 2], [0, 2], [0, 1]];

/// Why a plane could not be made.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum PlaneError {
    #[error("the plane's normal is zero")]
    ZeroNormal,
    #[error("the plane has a non-finite coordinate ({0})")]
    NonFinite(f64),
    #[error("axis {0} does not exist: use 0 (x), 1 (y) or 2 (z)")]
    NoSuchAxis(usize),
}

impl Plane {
    /// The plane where coordinate `axis` (0 = x, 1 = y, 2 = z) equals `value`.
    pub fn axis(axis: usize, value: f64) -> Result<Plane, PlaneError> {
        if axis > 2 {
            return Err(PlaneError::NoSuchAxis(axis));
        }
        if !value.is_finite() {
            return Err(PlaneError::NonFinite(value));
        }
        Ok(Plane { kind: PlaneKind::Axis { axis, value } })
    }

    /// The plane through `point` with normal `normal` (any length).
    pub fn new(point: Point, normal: Point) -> Result<Plane, PlaneError> {
        if let Some(&bad) = point.iter().chain(&normal).find(|x| !x.is_finite()) {
            return Err(PlaneError::NonFinite(bad));
        }
        let length = norm(normal);
        if length == 0.0 || !length.is_finite() {
            return Err(PlaneError::ZeroNormal);
        }
        let n = scale(normal, 1.0 / length);
        // u: the axis least aligned with n, made orthogonal to it.
        let smallest = (0..3).min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs())).unwrap_or(0);
        let mut e = [0.0; 3];
        e[smallest] = 1.0;
        let u = cross(e, n);
        let u = scale(u, 1.0 / norm(u));
        let v = cross(n, u);
        Ok(Plane { kind: PlaneKind::General { point, normal: n, u, v } })
    }

    /// A point of the plane, its unit normal, and the unit axes (u, v) of the 2D
    /// coordinates: a 2D point (s, t) is the 3D point `origin + s·u + t·v`.
    pub fn frame(&self) -> PlaneFrame {
        match self.kind {
            PlaneKind::Axis { axis, value } => {
                let unit = |k: usize| {
                    let mut e = [0.0; 3];
                    e[k] = 1.0;
                    e
                };
                let [a, b] = AXIS_FRAMES[axis];
                let mut origin = [0.0; 3];
                origin[axis] = value;
                PlaneFrame { origin, normal: cross(unit(a), unit(b)), u: unit(a), v: unit(b) }
            }
            PlaneKind::General { point, normal, u, v } => {
                PlaneFrame { origin: point, normal, u, v }
            }
        }
    }

    /// Signed distance (times |n| for axis planes, which have unit normals anyway).
    #[inline(always)]
    fn distance(&self, x: Point) -> f64 {
        match self.kind {
            PlaneKind::Axis { axis, value } => x[axis] - value,
            PlaneKind::General { point, normal, .. } => dot(sub(x, point), normal),
        }
    }

    /// Whether the 2D frame's normal u × v points against the side the distance calls
    /// above (the `y = h` plane: (x, z) coordinates, normal −y), so that chained loops
    /// must be reversed to wind counter-clockwise in the frame.
    fn frame_is_flipped(&self) -> bool {
        matches!(self.kind, PlaneKind::Axis { axis: 1, .. })
    }

    /// The 2D coordinates of a point of the plane.
    #[inline(always)]
    fn project(&self, x: Point) -> Point2 {
        match self.kind {
            PlaneKind::Axis { axis, .. } => {
                let [a, b] = AXIS_FRAMES[axis];
                [x[a], x[b]]
            }
            PlaneKind::General { point, u, v, .. } => {
                let r = sub(x, point);
                [dot(r, u), dot(r, v)]
            }
        }
    }
}

/// A plane's frame: see [`Plane::frame`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneFrame {
    pub origin: Point,
    pub normal: Point,
    pub u: Point,
    pub v: Point,
}

/// What [`section`] finds.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// Exteriors wound counter-clockwise and holes clockwise (in the plane's 2D frame),
    /// as GeoJSON wants; measure them with [`crate::polygon::area_properties`].
    pub polygons: Vec<Polygon>,
    /// Σ of the closed loops' signed areas as the surface winds them: the section's
    /// area for an outward-wound surface, its negative for an inward-wound one.
    pub signed_area: f64,
    /// Closed loops found (exteriors and holes).
    pub loops: usize,
    /// Triangles that cross the plane.
    pub segments: usize,
    /// Chains that did not close: the surface is open along the plane.
    pub open_chains: usize,
    /// Edges crossed more than once in the same direction: edges shared by more than two
    /// triangles, or inconsistent winding. Such crossings are chained turning most to the
    /// left (see [`section`]).
    pub ambiguous_edges: usize,
    /// Loops whose winding disagrees with their nesting (a counter-clockwise hole or a
    /// clockwise exterior, relative to the majority): an inward-wound shell inside
    /// another, or surfaces that intersect each other.
    pub misoriented_loops: usize,
}

/// An edge named by its end points' coordinate bits, below end first.
type EdgeKey = [u64; 6];

/// One triangle's piece of the section: from the crossing of edge `from` (`start`) to
/// that of edge `to` (`end`).
#[derive(Clone, Copy)]
struct Segment {
    from: EdgeKey,
    to: EdgeKey,
    start: Point,
    end: Point,
}

#[inline(always)]
fn key(below: Point, above: Point) -> EdgeKey {
    // +0.0 for −0.0, so both zeros name the same point.
    let bits = |x: f64| (x + 0.0).to_bits();
    [bits(below[0]), bits(below[1]), bits(below[2]), bits(above[0]), bits(above[1]), bits(above[2])]
}

/// Where the edge from `below` (distance `d_below` < 0) to `above` (`d_above` ≥ 0)
/// crosses the plane: a function of the ordered pair only.
#[inline(always)]
fn crossing(below: Point, d_below: f64, above: Point, d_above: f64) -> Point {
    if d_above == 0.0 {
        return above;
    }
    let t = d_below / (d_below - d_above);
    [0, 1, 2].map(|k| below[k] + t * (above[k] - below[k]))
}

/// The segment of triangle (a, b, c), if it crosses the plane.
#[inline(always)]
fn triangle_segment(plane: &Plane, corners: [Point; 3]) -> Option<Segment> {
    let d = corners.map(|p| plane.distance(p));
    let below = d.map(|x| x < 0.0);
    if below == [true; 3] || below == [false; 3] {
        return None;
    }
    let mut from = None;
    let mut to = None;
    for i in 0..3 {
        let j = (i + 1) % 3;
        match (below[i], below[j]) {
            (false, true) => {
                let point = crossing(corners[j], d[j], corners[i], d[i]);
                from = Some((key(corners[j], corners[i]), point));
            }
            (true, false) => {
                let point = crossing(corners[i], d[i], corners[j], d[j]);
                to = Some((key(corners[i], corners[j]), point));
            }
            _ => {}
        }
    }
    let ((from, start), (to, end)) = (from?, to?);
    Some(Segment { from, to, start, end })
}

/// Moves the pieces of one face's fan (`pieces`, emptied) into `found`, as the face
/// itself crosses the plane.
///
/// A fan's pieces chain through the crossings of its diagonals, from a crossing of the
/// face's own edges (where the chain enters) to another (where it leaves). Where the
/// fan's first corner does not see all of a non-convex face, some of its triangles fold
/// back over others, and a chain may join the entry of one piece of the face's section
/// to the exit of another, across a gap outside the face: the sums are unchanged, but
/// the loops are not the section's (they run over the gap and back, and split into loops
/// of both windings). The face's section lies on one line; along it entries and exits
/// alternate, so the k-th entry pairs with the k-th exit, and each pair is one segment
/// between the face's own edges (the same keys and points: chaining with the
/// neighbouring faces is untouched). A fan that does not fold (every piece runs forward
/// along the line) is kept as it is, bit for bit.
fn face_segments(pieces: &mut Vec<Segment>, found: &mut Vec<Segment>) {
    if pieces.len() < 2 {
        found.append(pieces);
        return;
    }
    // The direction of the section along the line: the chains' net run, Σ (end − start).
    let mut along = [0.0; 3];
    for s in pieces.iter() {
        along = [0, 1, 2].map(|k| along[k] + (s.end[k] - s.start[k]));
    }
    let run = |s: &Segment| dot(sub(s.end, s.start), along);
    if pieces.iter().all(|s| run(s) >= 0.0) || along == [0.0; 3] {
        found.append(pieces);
        return;
    }
    // The face's own edges: keys not both ended and started by its pieces.
    let mut tos: Vec<EdgeKey> = pieces.iter().map(|s| s.to).collect();
    let mut froms: Vec<EdgeKey> = pieces.iter().map(|s| s.from).collect();
    tos.sort_unstable();
    froms.sort_unstable();
    let mut entries: Vec<(EdgeKey, Point)> = pieces
        .iter()
        .filter(|s| tos.binary_search(&s.from).is_err())
        .map(|s| (s.from, s.start))
        .collect();
    let mut exits: Vec<(EdgeKey, Point)> = pieces
        .iter()
        .filter(|s| froms.binary_search(&s.to).is_err())
        .map(|s| (s.to, s.end))
        .collect();
    let at = |p: &Point| dot(*p, along);
    entries.sort_by(|a, b| at(&a.1).total_cmp(&at(&b.1)));
    exits.sort_by(|a, b| at(&a.1).total_cmp(&at(&b.1)));
    let pairs = entries.iter().zip(&exits);
    // A face that is not a consistently wound planar polygon: left as its fan says.
    if entries.is_empty()
        || entries.len() != exits.len()
        || pairs.clone().any(|(entry, exit)| at(&exit.1) < at(&entry.1))
    {
        found.append(pieces);
        return;
    }
    found.extend(pairs.map(|(&(from, start), &(to, end))| Segment { from, to, start, end }));
    pieces.clear();
}

/// The cross-section of `surface` by `plane`.
///
/// ```
/// use meshvol::section::{section, Plane};
/// use meshvol::polygon::area_properties;
/// use meshvol::Mesh;
/// // The unit cube, cut at half height and through its top face.
/// let p = vec![
///     [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0],
///     [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0],
/// ];
/// let quads: [&[u32]; 6] = [
///     &[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7],
/// ];
/// let cube = Mesh::from_polygons(p, quads).unwrap();
/// let half = section(&cube, &Plane::axis(2, 0.5).unwrap());
/// assert_eq!((half.loops, half.signed_area), (1, 1.0));
/// assert_eq!(area_properties(&half.polygons).centroid, Some([0.5, 0.5]));
/// // On-plane vertices count as above: the top face's level gives the section just
/// // below it, the bottom face's level gives nothing.
/// assert_eq!(section(&cube, &Plane::axis(2, 1.0).unwrap()).signed_area, 1.0);
/// assert_eq!(section(&cube, &Plane::axis(2, 0.0).unwrap()).loops, 0);
/// ```
pub fn section<S: Surface + ?Sized>(surface: &S, plane: &Plane) -> Section {
    let segments: Vec<Segment> = ordered_reduce(
        surface.face_count(),
        CHUNK_FACES,
        |range| {
            let (mut found, mut pieces) = (Vec::new(), Vec::new());
            for face in range {
                surface.fan(face, |a, b, c| {
                    if let Some(s) = triangle_segment(plane, [a, b, c]) {
                        pieces.push(s);
                    }
                });
                face_segments(&mut pieces, &mut found);
            }
            found
        },
        |all, part| all.extend(part),
    )
    .unwrap_or_default();

    // Each edge's crossing is the start of one segment and the end of another; an edge
    // shared by more than two triangles (a non-manifold edge, or a fan's diagonal lying
    // on an edge of its face through a corner between) starts several. The segments
    // starting at each edge form one run of `order`, and a chain arriving at an edge
    // goes on with one of the run's unused segments, so where as many segments end at
    // an edge as start there every one is chained. Where there is a choice, the chain
    // turns most to the left: the solid lies to the left of its section's segments, so
    // this traces the boundary of one piece of it around the point, and sections that
    // touch there (two bodies sharing an edge) stay apart, whatever the face order.
    let mut order: Vec<u32> = (0..segments.len() as u32).collect();
    order.sort_unstable_by(|&a, &b| {
        segments[a as usize].from.cmp(&segments[b as usize].from).then(a.cmp(&b))
    });
    let mut runs: HashMap<EdgeKey, (usize, usize)> = HashMap::with_capacity(segments.len());
    let mut ambiguous_edges = 0;
    let mut start = 0;
    while start < order.len() {
        let edge = segments[order[start] as usize].from;
        let mut end = start + 1;
        while end < order.len() && segments[order[end] as usize].from == edge {
            end += 1;
        }
        if end - start > 1 {
            ambiguous_edges += 1;
        }
        runs.insert(edge, (start, end));
        start = end;
    }
    // Open chains first, from the edges where more segments start than end, so that
    // each is counted once; whatever is left is made of loops.
    let mut ending: HashMap<EdgeKey, usize> = HashMap::with_capacity(segments.len());
    for s in &segments {
        *ending.entry(s.to).or_default() += 1;
    }
    let mut sources: Vec<(usize, usize)> = Vec::new();
    for (&edge, &(start, end)) in &runs {
        let ends = ending.get(&edge).copied().unwrap_or(0);
        if end - start > ends {
            sources.push((start, end - start - ends));
        }
    }
    sources.sort_unstable();
    let mut used = vec![false; segments.len()];
    let direction = |i: usize| {
        let (a, b) = (plane.project(segments[i].start), plane.project(segments[i].end));
        [b[0] - a[0], b[1] - a[1]]
    };
    // How far segment `next` turns left from segment `at` seen from the side the normal
    // points to (an angle in (−π, π]; the `y = h` frame sees the plane from below).
    let left = if plane.frame_is_flipped() { -1.0 } else { 1.0 };
    let turn = |at: usize, next: usize| {
        let (u, v) = (direction(at), direction(next));
        (left * (u[0] * v[1] - u[1] * v[0])).atan2(u[0] * v[0] + u[1] * v[1])
    };
    // The segment the chain goes on with after `at` (`None`: the chain ends), marked
    // used; `first`, the chain's first segment, is a candidate too (a loop closes).
    let next = |used: &mut [bool], at: usize, first: Option<usize>| -> Option<usize> {
        let &(start, end) = runs.get(&segments[at].to)?;
        let candidates = order[start..end].iter().map(|&i| i as usize);
        let mut free = candidates.filter(|&i| !used[i] || Some(i) == first);
        let best = if end - start > 1 {
            free.max_by(|&a, &b| turn(at, a).total_cmp(&turn(at, b)).then(b.cmp(&a)))
        } else {
            free.next()
        }?;
        used[best] = true;
        Some(best)
    };
    let mut open_chains = 0;
    for (start, count) in sources {
        let (_, end) = runs[&segments[order[start] as usize].from];
        for _ in 0..count {
            let Some(mut at) = order[start..end].iter().map(|&i| i as usize).find(|&i| !used[i])
            else {
                break;
            };
            used[at] = true;
            open_chains += 1;
            while let Some(following) = next(&mut used, at, None) {
                at = following;
            }
        }
    }
    let mut loops: Vec<Vec<Point2>> = Vec::new();
    let mut chain: Vec<Point2> = Vec::new();
    for first in 0..segments.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        chain.clear();
        let mut at = first;
        // With the open chains gone, every edge starts as many unused segments as end
        // there, so the walk can only stop where it began.
        let closed = loop {
            let point = plane.project(segments[at].start);
            if chain.last() != Some(&point) {
                chain.push(point);
            }
            match next(&mut used, at, Some(first)) {
                Some(following) if following == first => break true,
                Some(following) => at = following,
                None => break false,
            }
        };
        if !closed {
            open_chains += 1;
            continue;
        }
        if chain.len() > 1 && chain.first() == chain.last() {
            chain.pop();
        }
        if chain.len() >= 3 {
            if plane.frame_is_flipped() {
                chain.reverse();
            }
            loops.push(chain.clone());
        }
    }
    let signed_area = loops.iter().map(|l| signed_area(l)).sum();
    let loop_count = loops.len();
    let (polygons, misoriented_loops) = nest(loops);
    Section {
        polygons,
        signed_area,
        loops: loop_count,
        segments: segments.len(),
        open_chains,
        ambiguous_edges,
        misoriented_loops,
    }
}

/// Groups loops into polygons by nesting depth, orients exteriors counter-clockwise and
/// holes clockwise, and counts loops whose winding disagrees with their depth.
fn nest(loops: Vec<Vec<Point2>>) -> (Vec<Polygon>, usize) {
    let areas: Vec<f64> = loops.iter().map(|l| signed_area(l)).collect();
    let boxes: Vec<[f64; 4]> = loops
        .iter()
        .map(|l| {
            l.iter().fold([f64::MAX, f64::MAX, f64::MIN, f64::MIN], |b, p| {
                [b[0].min(p[0]), b[1].min(p[1]), b[2].max(p[0]), b[3].max(p[1])]
            })
        })
        .collect();
    // Larger loops first: a loop's containers come before it.
    let mut order: Vec<usize> = (0..loops.len()).collect();
    order.sort_by(|&a, &b| areas[b].abs().total_cmp(&areas[a].abs()));
    let mut depth = vec![0usize; loops.len()];
    let mut parent = vec![None; loops.len()];
    for (position, &i) in order.iter().enumerate() {
        let b = boxes[i];
        for &j in order[..position].iter().rev() {
            let c = boxes[j];
            if b[0] < c[0] || b[1] < c[1] || b[2] > c[2] || b[3] > c[3] {
                continue;
            }
            let verdict = loops[i].iter().find_map(|&p| point_in_ring(&loops[j], p));
            if verdict == Some(true) {
                // The smallest container is the parent; its depth is already known.
                parent[i] = Some(j);
                depth[i] = depth[j] + 1;
                break;
            }
        }
    }
    // The majority's sign says how the surface is wound; loops against it are counted.
    let outward: f64 =
        order.iter().map(|&i| if depth[i].is_multiple_of(2) { areas[i] } else { -areas[i] }).sum();
    let sign = if outward < 0.0 { -1.0 } else { 1.0 };
    let mut misoriented = 0;
    let mut polygon_of = vec![usize::MAX; loops.len()];
    let mut polygons: Vec<Polygon> = Vec::new();
    let mut loops: Vec<Option<Vec<Point2>>> = loops.into_iter().map(Some).collect();
    for &i in &order {
        let exterior = depth[i].is_multiple_of(2);
        let expected = if exterior { sign } else { -sign };
        if areas[i] * expected < 0.0 {
            misoriented += 1;
        }
        let Some(mut ring) = loops[i].take() else { continue };
        // Exteriors counter-clockwise, holes clockwise.
        if (areas[i] < 0.0) == exterior {
            ring.reverse();
        }
        if exterior {
            polygon_of[i] = polygons.len();
            polygons.push(Polygon::new(ring, Vec::new()));
        } else if let Some(p) = parent[i].map(|j| polygon_of[j]).filter(|&p| p != usize::MAX) {
            polygons[p].holes.push(ring);
        }
    }
    (polygons, misoriented)
}
