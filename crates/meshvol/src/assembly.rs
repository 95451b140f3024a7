//! Surfaces assembled from placed copies of parts, as 3MF components and glTF nodes
//! build them: one part mesh placed by many affine transforms.
//!
//! A reader that expands such a file into one mesh also returns its [`Assembly`]: the
//! distinct part meshes and, in the order the copies were appended, which part each copy
//! is and the transform that placed it. The expanded mesh's faces are the copies' faces
//! in that order, each copy's corners `transform.apply(p)` of its part's (a mirroring
//! transform, determinant < 0, reverses each triangle's winding so outward stays
//! outward). [`crate::topology::check_assembled`] uses it to check each part once
//! instead of every copy.

use crate::{Bounds, Mesh, Point};

/// `p ↦ L·p + t`, stored as rows `[L₀ t₀], [L₁ t₁], [L₂ t₂]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine(pub [[f64; 4]; 3]);

impl Affine {
    pub const IDENTITY: Affine =
        Affine([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);

    /// The point moved.
    ///
    /// ```
    /// use meshvol::assembly::Affine;
    /// let shift = Affine([[1.0, 0.0, 0.0, 5.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 2.0, 0.0]]);
    /// assert_eq!(shift.apply([1.0, 1.0, 1.0]), [6.0, 1.0, 2.0]);
    /// ```
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

    /// A tensor (an inertia) turned by the linear part R: `R T Rᵀ`.
    pub fn turn_tensor(&self, t: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
        let r = |i: usize, k: usize| self.0[i][k];
        [0, 1, 2].map(|i| {
            [0, 1, 2].map(|j| {
                let mut sum = 0.0;
                for k in 0..3 {
                    for l in 0..3 {
                        sum += r(i, k) * t[k][l] * r(j, l);
                    }
                }
                sum
            })
        })
    }

    pub fn is_finite(&self) -> bool {
        self.0.iter().flatten().all(|x| x.is_finite())
    }

    /// A box holding the image of `b`: the box of its eight corners moved.
    pub fn bounds(&self, b: &Bounds) -> Bounds {
        let mut out = Bounds::EMPTY;
        for corner in 0..8 {
            let pick =
                |axis: usize| if corner >> axis & 1 == 0 { b.min[axis] } else { b.max[axis] };
            out.include(self.apply([pick(0), pick(1), pick(2)]));
        }
        out
    }
}

/// One copy: which part, placed how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub part: u32,
    pub transform: Affine,
}

/// How an expanded mesh was assembled: see the module docs.
#[derive(Clone, Debug, Default)]
pub struct Assembly {
    pub parts: Vec<Mesh>,
    /// The copies, in the order their faces follow one another in the expanded mesh.
    pub placements: Vec<Placement>,
}

impl Assembly {
    /// Whether some part is placed more than once: only then does checking parts
    /// instead of copies save anything.
    pub fn repeats_parts(&self) -> bool {
        self.placements.len() > self.parts.len()
    }

    /// The faces of all copies: the expanded mesh's face count.
    pub fn face_count(&self) -> usize {
        self.placements.iter().map(|p| self.parts[p.part as usize].face_count()).sum()
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

    #[test]
    fn moved_bounds_hold_every_moved_point() {
        // A quarter turn about z, then a shift: the unit box lands on [-1, 0]×[0, 1]+t.
        let turn = Affine([[0.0, -1.0, 0.0, 3.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, -1.0]]);
        let b = turn.bounds(&Bounds { min: [0.0; 3], max: [1.0; 3] });
        assert_eq!(b, Bounds { min: [2.0, 0.0, -1.0], max: [3.0, 1.0, 0.0] });
    }
}
