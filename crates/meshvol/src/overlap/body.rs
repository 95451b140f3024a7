//! A body prepared once for many overlap queries: its triangles welded by exact
//! equality of coordinates, its edges with the triangle that tests each, its vertex
//! graph for the inside/outside walk, and a hierarchy of its triangles, whose shape
//! every pose reuses (its boxes refitted to the placed triangles).
//!
//! A checked solid that is exactly welded triangles (no tolerance, no caps, every face
//! a triangle) already holds the weld: [`Body::of_solid`] renumbers the check's vertices
//! in order of first use, which is the numbering welding the corners again would give,
//! so the body is the same bit for bit without a second weld. Its mass properties are
//! summed over the welded triangles through the indexed path, four triangles a SIMD
//! step, the same bits as the scalar loop over those triangles. (On two 1M-triangle spheres,
//! the weld, the serial edge table and the scalar mass properties were each about a
//! third of the preparation.)

use super::edges::{edge_table, vertex_graph, EdgeTable};
use crate::accumulate::UNIT_ROUNDOFF;
use crate::assembly::Affine;
use crate::bvh::{triangle_centre, Box32, Bvh};
use crate::properties::Bounds;
use crate::topology::{weld, Check, SpatialIndex};
use crate::vector::{cross, norm, orient2d, sub};
use crate::{mass_properties, MassProperties, Point, Surface};
use rayon::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::{Arc, OnceLock};

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
    /// Shared with the check it came from, when taken from it ([`Body::of_solid`]).
    pub(super) bvh: Arc<Bvh>,
    /// Own frame; `None` without triangles.
    pub(super) bounds: Option<Bounds>,
    /// The sums of the triangles' areas and of their perimeters (for the bound on how
    /// much volume a small move of the body sweeps), found the first time a bound needs
    /// them: bodies measured where they are, off any touch, never do (four square
    /// roots a triangle, a tenth of the preparation).
    sizes: OnceLock<(f64, f64)>,
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
        let mut one_triangle_each = true;
        for f in 0..surface.face_count() {
            let before = corners.len();
            // `+ 0.0` turns −0 into +0: the same point, which welding compares by bits.
            surface.fan(f, |a, b, c| corners.extend([a, b, c].map(|p| p.map(|x| x + 0.0))));
            one_triangle_each &= corners.len() == before + 3;
        }
        let welded = weld::exact(&corners);
        drop(corners);
        let triangles =
            welded.corner_vertex.par_chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        // A face of several triangles has its own area and rounding bound: measured as
        // the surface's face.
        let properties = (!one_triangle_each).then(|| mass_properties(surface));
        Body::welded(welded.positions, triangles, properties, None)
    }

    /// Prepares the solid `check` found in `surface` ([`Check::solid`]), as [`Body::new`]
    /// of it does, bit for bit, from what the check already holds when the solid is
    /// exactly welded triangles ([`Check::solid_triangles`]): the vertices and each
    /// corner's vertex, so nothing is welded again.
    ///
    /// When the check kept its spatial index ([`crate::topology::CheckOptions::keep_spatial_index`])
    /// and that index holds every triangle of the solid, numbered as the solid numbers
    /// them (no face dropped), the body takes its order and hierarchy instead of
    /// building them: both order triangles by the centres of their boxes and build the
    /// same tree over the same boxes, so the body is the same bit for bit. (On two
    /// 1M-triangle spheres that saved 0.05 s of ordering and 0.02 s of building a body.)
    pub fn of_solid<S: Surface + ?Sized>(check: &Check, surface: &S) -> Body {
        match check.solid_triangles() {
            Some((vertices, triangles)) => {
                let (points, triangles) = numbered_by_first_use(vertices, &triangles);
                let index = check
                    .spatial_index()
                    .filter(|i| i.faces.len() == triangles.len() && check.repairs().1 == 0);
                Body::welded(points, triangles, None, index)
            }
            None => Body::new(&check.solid(surface)),
        }
    }

    /// The body of welded triangles (`points` numbered in order of first use, at +0
    /// rather than −0), whose faces are those triangles in order; `properties`, when
    /// given, are those of the faces (otherwise measured here from the triangles).
    /// `index`: the check's spatial order of these triangles and hierarchy over them,
    /// taken instead of built (see [`Body::of_solid`]).
    fn welded(
        points: Vec<Point>,
        raw: Vec<[u32; 3]>,
        properties: Option<MassProperties>,
        index: Option<&SpatialIndex>,
    ) -> Body {
        let properties = properties
            .unwrap_or_else(|| mass_properties(&Triangles { points: &points, triangles: &raw }));
        let corners_of = |t: &[u32; 3]| t.map(|i| points[i as usize]);
        let built;
        let order: &[u32] = match index {
            Some(index) => &index.faces,
            None => {
                built = Bvh::spatial_order_of(raw.len(), |i| triangle_centre(corners_of(&raw[i])));
                &built
            }
        };
        let triangles: Vec<[u32; 3]> = order.par_iter().map(|&i| raw[i as usize]).collect();
        drop(raw);
        let flat: Vec<bool> = triangles.par_iter().map(|t| collinear(corners_of(t))).collect();
        let bvh = match index {
            Some(index) => Arc::clone(&index.bvh),
            None => Arc::new(Bvh::new(triangles.len(), |k| {
                Box32::around(&box_of(corners_of(&triangles[k])))
            })),
        };
        let bounds = Bounds::of_points(&points);
        let EdgeTable { edges, face_edges, owner, first_edge, closed } =
            edge_table(&triangles, &flat, points.len());
        let (start, adjacent) = vertex_graph(&edges, &first_edge);
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
            sizes: OnceLock::new(),
            unfit,
            properties,
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
        let (area, perimeter) = *self.sizes.get_or_init(|| self.sizes());
        1.01 * (2.0 * d * area + FRAC_PI_2 * d * d * perimeter + 4.0 * PI / 3.0 * d * d * d * n)
    }

    /// The sums of the triangles' areas and perimeters, in fixed chunks summed in
    /// order: the same bits at any thread count.
    fn sizes(&self) -> (f64, f64) {
        let corners_of = |t: &[u32; 3]| t.map(|i| self.points[i as usize]);
        let sums: Vec<(f64, f64)> = self
            .triangles
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
        sums.iter().fold((0.0, 0.0), |s, x| (s.0 + x.0, s.1 + x.1))
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

/// Whether the three points lie on one line, exactly: every projection onto a
/// coordinate plane has zero orientation.
fn collinear([a, b, c]: [Point; 3]) -> bool {
    [(0, 1), (1, 2), (2, 0)]
        .iter()
        .all(|&(i, j)| orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]) == 0.0)
}

/// `triangles` (ids into `vertices`) with their vertices renumbered in order of first
/// use, at +0 rather than −0: what welding their corners exactly gives
/// ([`weld::exact`] numbers vertices by their first corner), when distinct ids are
/// distinct positions. One pass in corner order (the order is the numbering), then the
/// triangles renamed in parallel.
fn numbered_by_first_use(
    vertices: &[Point],
    triangles: &[[u32; 3]],
) -> (Vec<Point>, Vec<[u32; 3]>) {
    let mut new_id = vec![u32::MAX; vertices.len()];
    // At most every vertex: one allocation, not a growing list copied as it grows.
    let mut points = Vec::with_capacity(vertices.len());
    for &v in triangles.as_flattened() {
        let id = &mut new_id[v as usize];
        if *id == u32::MAX {
            *id = points.len() as u32;
            points.push(vertices[v as usize].map(|x| x + 0.0));
        }
    }
    let triangles = triangles.par_iter().map(|t| t.map(|v| new_id[v as usize])).collect();
    (points, triangles)
}

/// Welded triangles as a surface, face f being triangle f: measured through the mass
/// properties' indexed path, the same bits as through their fans.
struct Triangles<'a> {
    points: &'a [Point],
    triangles: &'a [[u32; 3]],
}

impl Surface for Triangles<'_> {
    fn face_count(&self) -> usize {
        self.triangles.len()
    }

    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        let [a, b, c] = self.triangles[face].map(|i| self.points[i as usize]);
        triangle(a, b, c);
    }

    fn indexed_triangles(&self) -> Option<(&[Point], &[[u32; 3]])> {
        Some((self.points, self.triangles))
    }
}
