//! Whether a set of polygons means what its numbers seem to: rings that are not simple,
//! rings that cross each other, holes outside their exterior, rings with no area.
//!
//! Edges of positive length are swept in order of their smallest x; each is tested
//! against the active edges whose x range it overlaps (and whose y range meets its own)
//! with exact orientation predicates, so touching and collinear contacts are decided
//! exactly. Each pair of rings is reported once, with a count of its contacts.

use std::borrow::Borrow;
use std::fmt;

use super::{Point2, Polygon};

/// Something that makes a polygon's numbers mean other than they seem.
#[derive(Clone, Debug, PartialEq)]
pub enum PolygonIssue {
    /// Edges of one ring that are not neighbours meet (cross, touch or overlap): the
    /// ring is not simple, and its signed area counts each lobe by its winding.
    SelfIntersection {
        polygon: usize,
        ring: usize,
        /// The first pair of edges found to meet (edge j runs from vertex j to j + 1).
        edges: [usize; 2],
        near: Point2,
        /// How many edge pairs of the ring meet.
        contacts: u64,
    },
    /// Edges of two rings (of one polygon or of two) cross or overlap along a stretch:
    /// a hole that leaves its exterior, or polygons of a set that overlap (and so count
    /// twice). Rings that only touch at a point are allowed.
    RingsCross {
        /// (polygon, ring) of each.
        rings: [(usize, usize); 2],
        edges: [usize; 2],
        near: Point2,
        contacts: u64,
    },
    /// A hole that lies outside its polygon's exterior: it subtracts area that is not
    /// there.
    HoleOutside { polygon: usize, ring: usize },
    /// A ring that encloses no area: fewer than three distinct vertices, or all on one
    /// line.
    Degenerate { polygon: usize, ring: usize, vertices: usize },
    /// The intersection check stopped after `pairs` edge pairs (see
    /// [`MAX_EDGE_PAIR_TESTS`]); rings may intersect unreported.
    CheckIncomplete { pairs: u64 },
}

impl fmt::Display for PolygonIssue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let count = |n: u64| if n > 1 { format!(" ({n} edge pairs meet)") } else { String::new() };
        match self {
            PolygonIssue::SelfIntersection { polygon, ring, edges, near, contacts } => write!(
                f,
                "polygon {polygon} ring {ring} intersects itself: edges {} and {} meet near \
                 ({}, {}){}; its signed area counts each lobe by its winding",
                edges[0],
                edges[1],
                near[0],
                near[1],
                count(*contacts)
            ),
            PolygonIssue::RingsCross { rings, edges, near, contacts } => {
                let [(p0, r0), (p1, r1)] = *rings;
                let what = if p0 == p1 {
                    "a hole crosses its polygon's boundary or another hole"
                } else {
                    "the polygons overlap, and overlapping area counts twice"
                };
                write!(
                    f,
                    "polygon {p0} ring {r0} and polygon {p1} ring {r1} cross: edges {} and {} \
                     meet near ({}, {}){}; {what}",
                    edges[0],
                    edges[1],
                    near[0],
                    near[1],
                    count(*contacts)
                )
            }
            PolygonIssue::HoleOutside { polygon, ring } => write!(
                f,
                "polygon {polygon} ring {ring} is a hole outside its exterior ring: it \
                 subtracts area that is not there"
            ),
            PolygonIssue::Degenerate { polygon, ring, vertices } => write!(
                f,
                "polygon {polygon} ring {ring} ({vertices} vertices) encloses no area: its \
                 vertices are repeated or on one line"
            ),
            PolygonIssue::CheckIncomplete { pairs } => write!(
                f,
                "the intersection check stopped after {pairs} edge pairs: rings may intersect \
                 unreported"
            ),
        }
    }
}

/// The most edge pairs [`polygon_issues`] tests (about a quarter of a second). Rings
/// with n edges need about n·w tests, where w is the number of edges that overlap a
/// typical edge's x range: a few for ordinary outlines (a million-vertex coastline is
/// far below the limit), up to n for combs of thin vertical spikes.
pub const MAX_EDGE_PAIR_TESTS: u64 = 1 << 25;

/// How two segments meet.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Contact {
    /// They cross at a point inside both.
    Cross(Point2),
    /// An end of one lies on the other.
    Touch(Point2),
    /// They are collinear and share a stretch of positive length.
    Overlap(Point2),
}

fn orient(a: Point2, b: Point2, c: Point2) -> f64 {
    let coord = |p: Point2| robust::Coord { x: p[0], y: p[1] };
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Whether and how segments a and b meet, decided with exact orientation signs.
fn contact(a: [Point2; 2], b: [Point2; 2]) -> Option<Contact> {
    let o = [orient(a[0], a[1], b[0]), orient(a[0], a[1], b[1])];
    if o[0] * o[1] > 0.0 {
        return None;
    }
    let p = [orient(b[0], b[1], a[0]), orient(b[0], b[1], a[1])];
    if p[0] * p[1] > 0.0 {
        return None;
    }
    if o == [0.0; 2] {
        // Collinear: compare the extents along a's longer axis.
        let axis = usize::from((a[1][1] - a[0][1]).abs() > (a[1][0] - a[0][0]).abs());
        let (a0, a1) = (a[0][axis].min(a[1][axis]), a[0][axis].max(a[1][axis]));
        let (b0, b1) = (b[0][axis].min(b[1][axis]), b[0][axis].max(b[1][axis]));
        let (lo, hi) = (a0.max(b0), a1.min(b1));
        let point_at = |v: f64| {
            if a[0][axis] == v {
                a[0]
            } else if a[1][axis] == v {
                a[1]
            } else if b[0][axis] == v {
                b[0]
            } else {
                b[1]
            }
        };
        return match lo.partial_cmp(&hi)? {
            std::cmp::Ordering::Less => Some(Contact::Overlap(point_at(lo))),
            std::cmp::Ordering::Equal => Some(Contact::Touch(point_at(lo))),
            std::cmp::Ordering::Greater => None,
        };
    }
    if o[0] == 0.0 {
        Some(Contact::Touch(b[0]))
    } else if o[1] == 0.0 {
        Some(Contact::Touch(b[1]))
    } else if p[0] == 0.0 {
        Some(Contact::Touch(a[0]))
    } else if p[1] == 0.0 {
        Some(Contact::Touch(a[1]))
    } else {
        // A proper crossing; o[0] and o[1] have opposite signs, so t is in (0, 1).
        let t = o[0] / (o[0] - o[1]);
        Some(Contact::Cross([b[0][0] + t * (b[1][0] - b[0][0]), b[0][1] + t * (b[1][1] - b[0][1])]))
    }
}

/// An edge of positive length, for the sweep.
#[derive(Clone, Copy)]
struct SweepEdge {
    /// [min, max] of its ends' x, then of their y.
    range: [[f64; 2]; 2],
    ends: [Point2; 2],
    /// Its polygon, its ring, and its index in the ring (edge j runs from vertex j):
    /// compared in this order, they order the edges of a set.
    place: [u32; 3],
    /// Its position among the ring's edges of positive length, and their number:
    /// neighbours in this order share a vertex.
    rank: u32,
    ring_edges: u32,
}

/// Whether every vertex of `ring` lies on one line (exactly).
fn collinear(ring: &[Point2]) -> bool {
    let Some(&a) = ring.first() else { return true };
    let Some(&b) = ring.iter().find(|&&p| p != a) else { return true };
    ring.iter().all(|&p| orient(a, b, p) == 0.0)
}

/// Whether `point` is inside `ring` (`Some(true)`), outside (`Some(false)`), or on its
/// boundary (`None`), by the winding number with exact orientation signs.
pub(crate) fn point_in_ring(ring: &[Point2], point: Point2) -> Option<bool> {
    let mut winding = 0i64;
    let Some(&last) = ring.last() else { return Some(false) };
    let mut a = last;
    for &b in ring {
        let side = orient(a, b, point);
        let within_box = point[0] >= a[0].min(b[0])
            && point[0] <= a[0].max(b[0])
            && point[1] >= a[1].min(b[1])
            && point[1] <= a[1].max(b[1]);
        if side == 0.0 && within_box {
            return None;
        }
        if a[1] <= point[1] {
            if b[1] > point[1] && side > 0.0 {
                winding += 1;
            }
        } else if b[1] <= point[1] && side < 0.0 {
            winding -= 1;
        }
        a = b;
    }
    Some(winding != 0)
}

/// Checks a set of polygons: rings that intersect themselves, rings that cross each
/// other (holes leaving their exterior, overlapping polygons), holes outside their
/// exterior, and rings with no area.
///
/// Edges are swept in order of their smallest x; each is tested against the edges whose
/// x range it overlaps, with exact orientation predicates (Shewchuk's, from the `robust`
/// crate), so touching and collinear cases are decided exactly. The work is bounded by
/// [`MAX_EDGE_PAIR_TESTS`].
///
/// ```
/// use meshvol::polygon::{polygon_issues, Polygon, PolygonIssue};
/// // A bow tie: its signed area is 0, not 2.
/// let bow_tie = Polygon::new(vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]], vec![]);
/// let issues = polygon_issues(&[bow_tie]);
/// assert!(matches!(
///     issues[..],
///     [PolygonIssue::SelfIntersection { polygon: 0, ring: 0, edges: [0, 2], near: [1.0, 1.0], .. }]
/// ));
/// ```
pub fn polygon_issues<P: Borrow<Polygon>>(polygons: &[P]) -> Vec<PolygonIssue> {
    let mut issues = Vec::new();
    let mut edges: Vec<SweepEdge> = Vec::new();
    for (polygon_index, polygon) in polygons.iter().enumerate() {
        let polygon = polygon.borrow();
        for (ring_index, ring) in polygon.rings().enumerate() {
            let start = edges.len();
            let n = ring.len();
            for j in 0..n {
                let ends = [ring[j], ring[(j + 1) % n]];
                if ends[0] == ends[1] {
                    continue;
                }
                edges.push(SweepEdge {
                    range: [0, 1].map(|a| [ends[0][a].min(ends[1][a]), ends[0][a].max(ends[1][a])]),
                    ends,
                    place: [polygon_index as u32, ring_index as u32, j as u32],
                    rank: (edges.len() - start) as u32,
                    ring_edges: 0,
                });
            }
            let count = edges.len() - start;
            for e in &mut edges[start..] {
                e.ring_edges = count as u32;
            }
            if count < 3 || collinear(ring) {
                issues.push(PolygonIssue::Degenerate {
                    polygon: polygon_index,
                    ring: ring_index,
                    vertices: n,
                });
            }
        }
        for (hole_index, hole) in polygon.holes.iter().enumerate() {
            if polygon.exterior.len() < 3 {
                break;
            }
            let verdict = hole.iter().find_map(|&p| point_in_ring(&polygon.exterior, p));
            if verdict == Some(false) {
                issues.push(PolygonIssue::HoleOutside {
                    polygon: polygon_index,
                    ring: hole_index + 1,
                });
            }
        }
    }
    sweep(&mut edges, &mut issues);
    issues
}

/// Tests every pair of edges whose x ranges overlap; reports each pair of rings once.
fn sweep(edges: &mut [SweepEdge], issues: &mut Vec<PolygonIssue>) {
    edges.sort_unstable_by(|a, b| a.range[0][0].total_cmp(&b.range[0][0]));
    // Issues already reported, by ring pair: index into `issues`.
    let mut reported: std::collections::BTreeMap<[u32; 4], usize> = Default::default();
    let mut active: Vec<u32> = Vec::new();
    let mut pairs = 0u64;
    for (i, edge) in edges.iter().enumerate() {
        active.retain(|&k| edges[k as usize].range[0][1] >= edge.range[0][0]);
        for &k in &active {
            let other = &edges[k as usize];
            pairs += 1;
            if other.range[1][1] < edge.range[1][0] || other.range[1][0] > edge.range[1][1] {
                continue;
            }
            let same_ring = other.place[..2] == edge.place[..2];
            if same_ring {
                let gap = other.rank.abs_diff(edge.rank);
                if gap == 1 || gap + 1 == edge.ring_edges {
                    continue; // neighbours share a vertex
                }
            }
            let Some(found) = contact(other.ends, edge.ends) else { continue };
            let near = match found {
                Contact::Cross(p) | Contact::Overlap(p) => p,
                Contact::Touch(p) if same_ring => p,
                Contact::Touch(_) => continue,
            };
            let (first, second) =
                if other.place <= edge.place { (other, edge) } else { (edge, other) };
            let key = [first.place[0], first.place[1], second.place[0], second.place[1]];
            if let Some(&at) = reported.get(&key) {
                if let PolygonIssue::SelfIntersection { contacts, .. }
                | PolygonIssue::RingsCross { contacts, .. } = &mut issues[at]
                {
                    *contacts += 1;
                }
                continue;
            }
            reported.insert(key, issues.len());
            let edges = [first.place[2] as usize, second.place[2] as usize];
            issues.push(if same_ring {
                PolygonIssue::SelfIntersection {
                    polygon: first.place[0] as usize,
                    ring: first.place[1] as usize,
                    edges,
                    near,
                    contacts: 1,
                }
            } else {
                PolygonIssue::RingsCross {
                    rings: [
                        (first.place[0] as usize, first.place[1] as usize),
                        (second.place[0] as usize, second.place[1] as usize),
                    ],
                    edges,
                    near,
                    contacts: 1,
                }
            });
        }
        if pairs > MAX_EDGE_PAIR_TESTS {
            issues.push(PolygonIssue::CheckIncomplete { pairs });
            return;
        }
        active.push(i as u32);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::Polygon;

    #[test]
    fn issues_name_the_rings_and_the_place() {
        let square = |o: f64, s: f64| vec![[o, o], [o + s, o], [o + s, o + s], [o, o + s]];
        // A hole that sticks out of its exterior.
        let p = Polygon::new(square(0.0, 2.0), vec![square(1.0, 2.0)]);
        let issues = polygon_issues(&[p]);
        assert!(
            matches!(
                issues[..],
                [PolygonIssue::RingsCross { rings: [(0, 0), (0, 1)], contacts: 2, .. }]
            ),
            "{issues:?}"
        );
        // A hole entirely outside.
        let p = Polygon::new(square(0.0, 2.0), vec![square(5.0, 1.0)]);
        assert_eq!(polygon_issues(&[p]), vec![PolygonIssue::HoleOutside { polygon: 0, ring: 1 }]);
        // A hole touching the exterior at one corner is allowed; overlapping polygons are not.
        let p = Polygon::new(square(0.0, 2.0), vec![vec![[0.0, 0.0], [1.0, 0.5], [0.5, 1.0]]]);
        assert!(polygon_issues(&[p]).is_empty());
        let issues = polygon_issues(&[
            Polygon::new(square(0.0, 2.0), vec![]),
            Polygon::new(square(1.0, 2.0), vec![]),
        ]);
        assert!(matches!(issues[..], [PolygonIssue::RingsCross { rings: [(0, 0), (1, 0)], .. }]));
        assert!(issues[0].to_string().contains("overlap"));
        // A ring that touches itself at a vertex (two triangles joined at (1, 1)).
        let pinched = vec![[0.0, 0.0], [1.0, 1.0], [2.0, 0.0], [2.0, 2.0], [1.0, 1.0], [0.0, 2.0]];
        let issues = polygon_issues(&[Polygon::new(pinched, vec![])]);
        assert!(matches!(issues[..], [PolygonIssue::SelfIntersection { near: [1.0, 1.0], .. }]));
        // Repeated vertices and a closing copy of the first vertex are not intersections.
        let repeated = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]];
        assert!(polygon_issues(&[Polygon::new(repeated, vec![])]).is_empty());
    }

    #[test]
    fn the_sweep_finds_a_crossing_in_a_large_ring() {
        // A 100 000-gon whose last vertex is pulled across the first edges.
        let n = 100_000;
        let mut ring: Vec<Point2> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [a.cos(), a.sin()]
            })
            .collect();
        assert!(polygon_issues(&[Polygon::new(ring.clone(), vec![])]).is_empty());
        ring[n - 1] = [1.0, 0.5];
        let issues = polygon_issues(&[Polygon::new(ring, vec![])]);
        assert!(
            matches!(issues[..], [PolygonIssue::SelfIntersection { polygon: 0, ring: 0, .. }]),
            "{issues:?}"
        );
    }
}
