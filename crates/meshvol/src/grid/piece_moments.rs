//! The moments of a solid from pieces of its boundary, by the divergence theorem with
//! vertical fields: for a polynomial f and G with ∂G/∂z = f,
//!
//! ```text
//! ∫_V f dV = ∮_∂V G n_z dA = Σ_pieces ∫ G(x, y, z(x, y)) dA_xy (signed plan area)
//! ```
//!
//! so vertical pieces add nothing and each planar piece is a polynomial integral over
//! its plan projection (z linear on it). The ten moments up to degree 2 need G of degree
//! at most 3 (`z`, `xz`, `yz`, `z²/2`, `x²z`, `y²z`, `z³/3`, `xyz`, `yz²/2`, `xz²/2`),
//! integrated exactly over each triangle of a piece's fan by the degree-3 rule (weights
//! 3/60 at the corners, 8/60 at the edge midpoints, 27/60 at the centroid).
//!
//! Coordinates are the grid's units scaled by the cell (relative to the grid's origin),
//! so sums stay small near the pieces; [`finish`] moves them to the world.

use crate::vector::{add, scale};
use crate::Point;

/// ∫ over the solid of 1, x, y, z, x², y², z², xy, yz, zx (relative coordinates).
pub(crate) type Sums = [f64; 10];

/// The integrands G at `p`, in the order of [`Sums`].
fn integrands([x, y, z]: Point) -> Sums {
    let (z2, z3) = (z * z, z * z * z);
    [
        z,
        x * z,
        y * z,
        0.5 * z2,
        x * x * z,
        y * y * z,
        z3 / 3.0,
        x * y * z,
        0.5 * y * z2,
        0.5 * x * z2,
    ]
}

/// Adds the integrals of the planar piece with `vertices` (grid units) to `sums`; `cell`
/// is the grid's cell size.
pub(crate) fn add_piece(vertices: &[Point], cell: [f64; 3], sums: &mut Sums) {
    if vertices.len() < 3 {
        return;
    }
    let world = |u: Point| [u[0] * cell[0], u[1] * cell[1], u[2] * cell[2]];
    let o = world(vertices[0]);
    for k in 1..vertices.len() - 1 {
        let (b, c) = (world(vertices[k]), world(vertices[k + 1]));
        let area = 0.5 * ((b[0] - o[0]) * (c[1] - o[1]) - (b[1] - o[1]) * (c[0] - o[0]));
        if area == 0.0 {
            continue;
        }
        let mid = |p: Point, q: Point| scale(add(p, q), 0.5);
        let centre = scale(add(add(o, b), c), 1.0 / 3.0);
        let mut s = [0.0; 10];
        for (points, weight) in
            [([o, b, c], 3.0 / 60.0), ([mid(o, b), mid(b, c), mid(c, o)], 8.0 / 60.0)]
        {
            for p in points {
                let g = integrands(p);
                for n in 0..10 {
                    s[n] += weight * g[n];
                }
            }
        }
        let g = integrands(centre);
        for n in 0..10 {
            sums[n] += area * (s[n] + 27.0 / 60.0 * g[n]);
        }
    }
}

/// Volume, centroid (world) and inertia about the centroid (unit density) from `sums`
/// about `origin`; `None` without volume.
pub(crate) fn finish(sums: &Sums, origin: Point) -> Option<(f64, Point, [[f64; 3]; 3])> {
    let v = sums[0];
    if !(v > 0.0 && v.is_finite()) {
        return None;
    }
    let c = [sums[1] / v, sums[2] / v, sums[3] / v];
    let xx = sums[4] - v * c[0] * c[0];
    let yy = sums[5] - v * c[1] * c[1];
    let zz = sums[6] - v * c[2] * c[2];
    let xy = sums[7] - v * c[0] * c[1];
    let yz = sums[8] - v * c[1] * c[2];
    let zx = sums[9] - v * c[2] * c[0];
    let inertia = [[yy + zz, -xy, -zx], [-xy, xx + zz, -yz], [-zx, -yz, xx + yy]];
    Some((v, add(origin, c), inertia))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_cube_from_its_top_and_bottom() {
        // Top up (counter-clockwise in plan) at z = 1, bottom down at z = 0.
        let top = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]];
        let bottom = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
        let mut sums = [0.0; 10];
        add_piece(&top, [2.0, 1.0, 1.0], &mut sums);
        add_piece(&bottom, [2.0, 1.0, 1.0], &mut sums);
        let (v, c, i) = finish(&sums, [1.0, 0.0, 0.0]).unwrap();
        assert!((v - 2.0).abs() < 1e-15);
        assert!((c[0] - 2.0).abs() < 1e-15 && (c[1] - 0.5).abs() < 1e-15);
        // A 2×1×1 box: I_xx = m(1 + 1)/12, I_zz = m(4 + 1)/12.
        assert!((i[0][0] - 2.0 * 2.0 / 12.0).abs() < 1e-14, "{i:?}");
        assert!((i[2][2] - 2.0 * 5.0 / 12.0).abs() < 1e-14, "{i:?}");
        assert!(i[0][1].abs() < 1e-15);
    }
}
