//! A surface read as a height field z = f(x, y): its triangles in plan, and the check
//! that no two of them overlap there.
//!
//! Each fan triangle is projected on the xy plane and turned counter-clockwise there if
//! it was not (a surface may face up or down, or be wound either way in places: only
//! the plan matters). A triangle with no area in plan (exactly, by `orient2d`) carries
//! none of the integrals: vertical ones (some area in space) are left out and listed,
//! degenerate ones left out silently.
//!
//! The surface is a height field when the interiors of its triangles' projections are
//! disjoint. A fold or an overhang makes two triangles overlap in plan, however they
//! are wound: [`super::overlaps`] finds the first such pair, exactly and in
//! n log n time.

use super::plan::{box_union, facet_box, Facet, PlanBox};
use crate::accumulate::CompensatedSum;
use crate::vector::{cross, norm, orient2d, sub};
use crate::{Point, Surface};
use rayon::prelude::*;

/// Why a surface is not a height field.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum TerrainError {
    #[error(
        "faces {first} and {second} overlap in plan: the surface is not a height field \
         z = f(x, y) (it folds over, or has an overhang or a second layer there)"
    )]
    Overlap { first: usize, second: usize },
    #[error("face {face} has a coordinate that is not a finite number")]
    NotFinite { face: usize },
    #[error("the surface has {triangles} triangles; at most 2^32 − 1 can be compared")]
    TooManyTriangles { triangles: usize },
}

/// A surface prepared as a height field: its triangles in plan, checked not to overlap.
#[derive(Clone, Debug)]
pub struct Terrain {
    pub(crate) facets: Vec<Facet>,
    bounds: Option<PlanBox>,
    area: f64,
    vertical: Vec<usize>,
}

/// Faces per parallel task when reading a surface's triangles.
const FACE_CHUNK: usize = 4096;

/// The triangles of faces `faces`, and the vertical faces among them.
fn read_faces<S: Surface + ?Sized>(
    surface: &S,
    faces: std::ops::Range<usize>,
) -> Result<(Vec<Facet>, Vec<usize>), TerrainError> {
    let mut facets = Vec::new();
    let mut vertical = Vec::new();
    for face in faces {
        let mut error = None;
        let mut upright = false;
        surface.fan(face, |a: Point, b: Point, c: Point| {
            if ![a, b, c].iter().flatten().all(|x| x.is_finite()) {
                error = Some(TerrainError::NotFinite { face });
                return;
            }
            let xy = [a, b, c].map(|p| [p[0], p[1]]);
            let z = [a[2], b[2], c[2]];
            let turn = orient2d(xy[0], xy[1], xy[2]);
            if turn == 0.0 {
                upright |= norm(cross(sub(b, a), sub(c, a))) > 0.0;
            } else if turn > 0.0 {
                facets.push(Facet { xy, z, face });
            } else {
                facets.push(Facet { xy: [xy[0], xy[2], xy[1]], z: [z[0], z[2], z[1]], face });
            }
        });
        if let Some(e) = error {
            return Err(e);
        }
        if upright {
            vertical.push(face);
        }
    }
    Ok((facets, vertical))
}

impl Terrain {
    /// Reads `surface` as a height field; an error names the first face (in face
    /// order) that is not finite, or the first pair of faces that overlap in plan.
    pub fn new<S: Surface + ?Sized>(surface: &S) -> Result<Terrain, TerrainError> {
        let parts: Vec<_> = (0..surface.face_count().div_ceil(FACE_CHUNK))
            .into_par_iter()
            .map(|i| {
                let end = ((i + 1) * FACE_CHUNK).min(surface.face_count());
                read_faces(surface, i * FACE_CHUNK..end)
            })
            .collect();
        let mut facets = Vec::new();
        let mut vertical = Vec::new();
        for part in parts {
            let (f, v) = part?;
            facets.extend(f);
            vertical.extend(v);
        }
        if u32::try_from(facets.len()).is_err() {
            return Err(TerrainError::TooManyTriangles { triangles: facets.len() });
        }
        let bounds = facets.iter().map(facet_box).reduce(|a, b| box_union(&a, &b));
        let mut area = CompensatedSum::default();
        for f in &facets {
            let [a, b, c] = f.xy;
            area.add(0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])));
        }
        let terrain = Terrain { facets, bounds, area: area.value(), vertical };
        match super::overlaps::first_overlap(&terrain.facets) {
            Some((first, second)) => Err(TerrainError::Overlap { first, second }),
            None => Ok(terrain),
        }
    }

    /// The box of the surface's plan: [min, max] of x and y; `None` without area.
    pub fn plan_bounds(&self) -> Option<[[f64; 2]; 2]> {
        self.bounds
    }

    /// The area of the surface's plan.
    pub fn plan_area(&self) -> f64 {
        self.area
    }

    /// The faces left out because they stand vertical (no area in plan), in order.
    pub fn vertical_faces(&self) -> &[usize] {
        &self.vertical
    }

    /// The number of triangles with area in plan.
    pub fn triangle_count(&self) -> usize {
        self.facets.len()
    }
}
