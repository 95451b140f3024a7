//! A body prepared once for many overlap queries: its triangles welded by exact
//! equality of coordinates, its edges with the triangle that tests each, its vertex
//! graph for the inside/outside walk, and a hierarchy of its triangles, whose shape
//! every pose reuses (its boxes refitted to the placed triangles).

use crate::accumulate::UNIT_ROUNDOFF;
use crate::assembly::Affine;
use crate::bvh::{Box32, Bvh};
use crate::properties::Bounds;
use crate::topology::weld;
use crate::vector::{cross, norm, orient2d, sub};
use crate::{mass_properties, MassProperties, Point, Surface};
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// A closed body ready for [`super::overlap`].
#[derive(Clone, Debug)]
pub struct Body {
    /// Distinct points, own frame.
    pub(super) points: Vec<Point>,
    /// Triangles as point ids, wound as the surface winds them, in the spatial order
    /// of the hierarchy (triangle k is the hierarchy's item k).
    pub(super) triangles: Vec<[u32; 3]>,
    /// Triangles whose corners are exactly collinear: no area, no plane; only their
    /// edges take part.
    pub(super) flat: Vec<bool>,
    /// Per triangle, its edges: edge i runs from corner i to corner i + 1.
    pub(super) face_edges: Vec<[u32; 3]>,
    /// Per edge, its ends, the lower id first.
    pub(super) edges: Vec<[u32; 2]>,
    /// Per edge, the triangle that tests it against the other body (the first one with
    /// area that has it): each crossing of an edge is found once.
    pub(super) owner: Vec<u32>,
    /// The vertex graph: the edges at vertex v are `adjacent[start[v]..start[v + 1]]`,
    /// as (neighbour, edge).
    pub(super) start: Vec<u32>,
    pub(super) adjacent: Vec<(u32, u32)>,
    pub(super) bvh: Bvh,
    /// Own frame; `None` without triangles.
    pub(super) bounds: Option<Bounds>,
    /// The sums of the triangles' areas and of their perimeters (for the bound on how
    /// much volume a small move of the body sweeps).
    pub(super) area: f64,
    pub(super) perimeter: f64,
    /// Why the body cannot take the boundary method (`None`: it can).
    pub(super) unfit: Option<&'static str>,
    /// Its mass properties, own frame.
    properties: MassProperties,
}

impl Body {
    /// Prepares `surface` (its fan triangles). The body is fit for the boundary method
    /// when it is closed: every edge is used as often in one direction as in the other.
    /// Whether it is free of self-crossings is the caller's to know (the check says).
    pub fn new<S: Surface>(surface: &S) -> Body {
        let mut corners: Vec<Point> = Vec::with_capacity(3 * surface.face_count());
        for f in 0..surface.face_count() {
            // `+ 0.0` turns −0 into +0: the same point, which welding compares by bits.
            surface.fan(f, |a, b, c| corners.extend([a, b, c].map(|p| p.map(|x| x + 0.0))));
        }
        let welded = weld::exact(&corners);
        drop(corners);
        let points = welded.positions;
        let raw: Vec<[u32; 3]> =
            welded.corner_vertex.par_chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let corners_of = |t: &[u32; 3]| t.map(|i| points[i as usize]);
        let centres: Vec<Point> = raw
            .par_iter()
            .map(|t| {
                let [a, b, c] = corners_of(t);
                [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0)
            })
            .collect();
        let order = Bvh::spatial_order(&centres);
        drop(centres);
        let triangles: Vec<[u32; 3]> = order.par_iter().map(|&i| raw[i as usize]).collect();
        drop(raw);
        let flat: Vec<bool> = triangles.par_iter().map(|t| collinear(corners_of(t))).collect();
        let bvh = Bvh::new(triangles.len(), |k| Box32::around(&box_of(corners_of(&triangles[k]))));
        let bounds = bounds_of(&points);
        // Fixed chunks summed in order: the same bits at any thread count.
        let sums: Vec<(f64, f64)> = triangles
            .par_chunks(4096)
            .map(|chunk| {
                let (mut area, mut perimeter) = (0.0, 0.0);
                for t in chunk {
                    let [a, b, c] = corners_of(t);
                    area += 0.5 * norm(cross(sub(b, a), sub(c, a)));
                    perimeter += norm(sub(b, a)) + norm(sub(c, b)) + norm(sub(a, c));
                }
                (area, perimeter)
            })
            .collect();
        let (area, perimeter) = sums.iter().fold((0.0, 0.0), |s, x| (s.0 + x.0, s.1 + x.1));
        let EdgeTable { edges, face_edges, owner, closed } = edge_table(&triangles, &flat);
        let (start, adjacent) = vertex_graph(points.len(), &edges);
        let unfit = if triangles.is_empty() {
            Some("it has no triangle")
        } else if !closed {
            Some("it is not closed with exactly equal vertices")
        } else {
            None
        };
        Body {
            points,
            triangles,
            flat,
            face_edges,
            edges,
            owner,
            start,
            adjacent,
            bvh,
            bounds,
            area,
            perimeter,
            unfit,
            properties: mass_properties(surface),
        }
    }

    /// The mass properties of the body moved by `pose` (`None`: where it is), with the
    /// box `bounds` of its moved points, without measuring it again: the volume scaled
    /// by the pose's determinant (a rigid pose may be off orthonormal by rounding), its
    /// bound widened by what rounding the moved coordinates (by up to `8u·reach`, see
    /// [`Body::swept`]) can change; centroid and inertia turned.
    pub(super) fn placed_properties(
        &self,
        pose: Option<Affine>,
        bounds: Option<Bounds>,
        reach: f64,
    ) -> MassProperties {
        let p = &self.properties;
        let Some(m) = pose else { return MassProperties { bounds, ..*p } };
        let det = m.determinant();
        MassProperties {
            signed_volume: det * p.signed_volume,
            volume_error_bound: det.abs() * p.volume_error_bound
                + self.swept(8.0 * UNIT_ROUNDOFF * reach),
            centroid: p.centroid.map(|c| m.apply(c)),
            inertia: m.turn_tensor(&p.inertia),
            bounds,
            ..*p
        }
    }

    /// A bound on the volume the surface sweeps when each of its points moves by at
    /// most `d`: it stays within the Minkowski sum of each triangle with a ball of
    /// radius d, whose volume is 2d·area + (π/2)d²·perimeter + (4π/3)d³ (Steiner), with
    /// 1 % room for the rounding of the sums.
    pub(super) fn swept(&self, d: f64) -> f64 {
        let n = self.triangles.len() as f64;
        1.01 * (2.0 * d * self.area
            + FRAC_PI_2 * d * d * self.perimeter
            + 4.0 * PI / 3.0 * d * d * d * n)
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Why the boundary method cannot measure this body (`None`: it can).
    pub fn unfit(&self) -> Option<&'static str> {
        self.unfit
    }
}

/// The box of a triangle.
pub(super) fn box_of(t: [Point; 3]) -> Bounds {
    let mut b = Bounds::of(t[0]);
    b.include(t[1]);
    b.include(t[2]);
    b
}

/// The box of `points`; `None` for none.
pub(super) fn bounds_of(points: &[Point]) -> Option<Bounds> {
    let (first, rest) = points.split_first()?;
    let mut b = Bounds::of(*first);
    rest.iter().for_each(|p| b.include(*p));
    Some(b)
}

/// Whether the three points lie on one line, exactly: every projection onto a
/// coordinate plane has zero orientation.
fn collinear([a, b, c]: [Point; 3]) -> bool {
    [(0, 1), (1, 2), (2, 0)]
        .iter()
        .all(|&(i, j)| orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]) == 0.0)
}

/// The edges (ends, lower id first), each triangle's edges, each edge's owner, and
/// whether every edge is used as often in one direction as in the other.
///
/// Each corner's edge is filed under its lower end (a counting sort by vertex), and the
/// few edges at a vertex grouped by their other end: linear time, no sort of all
/// corners. Edges are numbered by lower end, then upper end.
fn edge_table(triangles: &[[u32; 3]], flat: &[bool]) -> EdgeTable {
    let vertices = triangles.iter().flatten().map(|&v| v as usize + 1).max().unwrap_or(0);
    let mut start = vec![0u32; vertices + 1];
    for t in triangles {
        for i in 0..3 {
            start[t[i].min(t[(i + 1) % 3]) as usize + 1] += 1;
        }
    }
    for v in 0..vertices {
        start[v + 1] += start[v];
    }
    // (upper end, corner 3t + i); the corner's direction is read back from the triangle.
    let mut filed = vec![(0u32, 0u32); 3 * triangles.len()];
    let mut fill = start.clone();
    for (t, tri) in triangles.iter().enumerate() {
        for i in 0..3 {
            let (u, v) = (tri[i], tri[(i + 1) % 3]);
            let slot = &mut fill[u.min(v) as usize];
            filed[*slot as usize] = (u.max(v), 3 * t as u32 + i as u32);
            *slot += 1;
        }
    }
    let mut edges = Vec::new();
    let mut owner = Vec::new();
    let mut face_edges = vec![[0u32; 3]; triangles.len()];
    let mut closed = true;
    for low in 0..vertices {
        let group = &mut filed[start[low] as usize..start[low + 1] as usize];
        group.sort_unstable();
        let mut k = 0;
        while k < group.len() {
            let mut end = k + 1;
            while end < group.len() && group[end].0 == group[k].0 {
                end += 1;
            }
            let id = edges.len() as u32;
            edges.push([low as u32, group[k].0]);
            let mut balance = 0i32;
            let mut with_area = None;
            for &(_, corner) in &group[k..end] {
                let (t, i) = ((corner / 3) as usize, (corner % 3) as usize);
                balance += if triangles[t][i] as usize == low { 1 } else { -1 };
                if with_area.is_none() && !flat[t] {
                    with_area = Some(t as u32);
                }
                face_edges[t][i] = id;
            }
            closed &= balance == 0;
            owner.push(with_area.unwrap_or(group[k].1 / 3));
            k = end;
        }
    }
    EdgeTable { edges, face_edges, owner, closed }
}

/// What [`edge_table`] finds.
struct EdgeTable {
    edges: Vec<[u32; 2]>,
    face_edges: Vec<[u32; 3]>,
    owner: Vec<u32>,
    closed: bool,
}

/// The vertex graph as adjacency lists (neighbour, edge), by vertex.
fn vertex_graph(points: usize, edges: &[[u32; 2]]) -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut start = vec![0u32; points + 1];
    for e in edges {
        start[e[0] as usize + 1] += 1;
        start[e[1] as usize + 1] += 1;
    }
    for v in 0..points {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut adjacent = vec![(0u32, 0u32); 2 * edges.len()];
    for (id, e) in edges.iter().enumerate() {
        for (from, to) in [(e[0], e[1]), (e[1], e[0])] {
            adjacent[fill[from as usize] as usize] = (to, id as u32);
            fill[from as usize] += 1;
        }
    }
    (start, adjacent)
}
