//! Affine transforms of points, as 3MF components and glTF nodes place their meshes, and
//! the triangle mesh that the placed copies are gathered into.

use meshvol::{Mesh, Point};
use rayon::prelude::*;

use crate::Object;

/// `p ↦ L·p + t`, stored as rows `[L₀ t₀], [L₁ t₁], [L₂ t₂]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Affine(pub [[f64; 4]; 3]);

impl Affine {
    pub const IDENTITY: Affine =
        Affine([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);

    #[inline]
    pub fn apply(&self, p: Point) -> Point {
        let m = &self.0;
        [0, 1, 2].map(|r| m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3])
    }

    /// `outer ∘ self`: this transform first, then `outer`.
    pub fn then(&self, outer: &Affine) -> Affine {
        let (a, b) = (&outer.0, &self.0);
        let mut out = [[0.0; 4]; 3];
        for r in 0..3 {
            for c in 0..4 {
                out[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
            }
            out[r][3] += a[r][3];
        }
        Affine(out)
    }

    /// The determinant of the linear part: negative for a mirroring transform, which
    /// turns outward-wound faces inward.
    pub fn determinant(&self) -> f64 {
        let m = &self.0;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    pub fn is_finite(&self) -> bool {
        self.0.iter().flatten().all(|x| x.is_finite())
    }
}

/// Triangle meshes placed by transforms, gathered into one mesh, with one [`Object`] per
/// placed part.
pub(crate) struct Placed {
    positions: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    objects: Vec<Object>,
}

/// Parts with fewer vertices and triangles than this are placed in one thread.
const PARALLEL_PART: usize = 1 << 14;

impl Placed {
    /// Reserves room for the totals, which the caller computes from what the file holds
    /// (never from unchecked counts): an error when they exceed 32-bit indices or memory.
    pub fn with_capacity(vertices: u64, triangles: u64) -> Result<Placed, String> {
        if vertices > u64::from(u32::MAX) {
            return Err(format!(
                "the placed parts have {vertices} vertices in all, more than 32-bit indices hold"
            ));
        }
        let mut placed =
            Placed { positions: Vec::new(), triangles: Vec::new(), objects: Vec::new() };
        let cannot = |what: &str, n: u64| format!("cannot allocate memory for {n} {what}");
        placed
            .positions
            .try_reserve_exact(vertices as usize)
            .map_err(|_| cannot("vertices", vertices))?;
        let t = usize::try_from(triangles).map_err(|_| cannot("triangles", triangles))?;
        placed.triangles.try_reserve_exact(t).map_err(|_| cannot("triangles", triangles))?;
        Ok(placed)
    }

    /// Adds a part: `positions` moved by `placement`, and `triangles` indexing them
    /// (checked by the caller), wound the other way when `placement` mirrors, so that
    /// outward faces stay outward.
    pub fn add(&mut self, positions: &[Point], triangles: &[[u32; 3]], placement: &Affine) {
        let base = self.positions.len() as u32;
        let mirrored = placement.determinant() < 0.0;
        let corners = |&[a, b, c]: &[u32; 3]| {
            if mirrored {
                [base + a, base + c, base + b]
            } else {
                [base + a, base + b, base + c]
            }
        };
        // Small parts in this thread: a file placing a tetrahedron 10⁶ times made 2·10⁶
        // parallel jobs of four items each, and the idle workers' spinning took 33 s.
        if positions.len() + triangles.len() < PARALLEL_PART {
            self.positions.extend(positions.iter().map(|&p| placement.apply(p)));
            self.triangles.extend(triangles.iter().map(corners));
            return;
        }
        if *placement == Affine::IDENTITY {
            self.positions.extend_from_slice(positions);
        } else {
            self.positions.par_extend(positions.par_iter().map(|&p| placement.apply(p)));
        }
        self.triangles.par_extend(triangles.par_iter().map(corners));
    }

    /// [`Placed::add`] for arrays the caller no longer needs: the first part, when it
    /// is not moved, is taken without a copy.
    pub fn add_owned(
        &mut self,
        positions: Vec<Point>,
        triangles: Vec<[u32; 3]>,
        placement: &Affine,
    ) {
        if self.positions.is_empty() && self.triangles.is_empty() && *placement == Affine::IDENTITY
        {
            self.positions = positions;
            self.triangles = triangles;
        } else {
            self.add(&positions, &triangles, placement);
        }
    }

    /// The number of triangles added so far.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Names the triangles added since `first` as one object (nothing when there are
    /// none).
    pub fn close_object(&mut self, name: String, first: usize) {
        if self.triangles.len() > first {
            self.objects.push(Object { name, faces: first..self.triangles.len() });
        }
    }

    /// The mesh and its objects.
    pub fn finish(self) -> Result<(Mesh, Vec<Object>), meshvol::MeshError> {
        Ok((Mesh::from_triangles(self.positions, self.triangles)?, self.objects))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compose_apply_and_mirror() {
        let scale = Affine([[2.0, 0.0, 0.0, 0.0], [0.0, 2.0, 0.0, 0.0], [0.0, 0.0, 2.0, 0.0]]);
        let shift = Affine([[1.0, 0.0, 0.0, 5.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
        // Scale first, then shift.
        assert_eq!(scale.then(&shift).apply([1.0, 1.0, 1.0]), [7.0, 2.0, 2.0]);
        assert_eq!(shift.then(&scale).apply([1.0, 1.0, 1.0]), [12.0, 2.0, 2.0]);
        assert_eq!(scale.determinant(), 8.0);
        let mirror = Affine([[-1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
        assert_eq!(mirror.determinant(), -1.0);
        assert_eq!(Affine::IDENTITY.then(&shift), shift);
    }
}
