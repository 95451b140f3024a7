//! Principal moments and axes of a 3×3 symmetric tensor by cyclic Jacobi rotations.
//!
//! Jacobi converges quadratically and keeps small eigenvalues to full relative accuracy
//! for these well-conditioned tensors. It is written here (about 40 lines) rather than
//! taken from nalgebra's `SymmetricEigen` because nalgebra would be the largest
//! dependency of the library by far (compile time) for this one 3×3 use.

use crate::vector::{cross, norm, scale};
use crate::Point;

/// The principal moments of inertia (ascending) and their axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principal {
    pub moments: [f64; 3],
    /// `axes[k]` is the unit axis of `moments[k]`; the three form a right-handed frame.
    pub axes: [Point; 3],
}

/// Eigen-decomposition of the symmetric `m`: eigenvalues ascending, unit eigenvectors.
///
/// Each axis's sign is chosen so its largest-magnitude component is positive, and the
/// third axis is the cross product of the first two (a right-handed frame).
/// A tensor with a non-finite entry (moments that overflowed f64) has no principal frame:
/// every moment and axis component is then NaN.
pub fn principal(m: [[f64; 3]; 3]) -> Principal {
    if m.iter().flatten().any(|x| !x.is_finite()) {
        return Principal { moments: [f64::NAN; 3], axes: [[f64::NAN; 3]; 3] };
    }
    let mut a = m;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let scale_sq: f64 = a.iter().flatten().map(|x| x * x).sum();
    for _sweep in 0..64 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        if off <= scale_sq * 1e-34 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            // The rotation in the (p, q) plane that zeroes a[p][q].
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            let mut j = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            j[p][p] = c;
            j[q][q] = c;
            j[p][q] = s;
            j[q][p] = -s;
            a = mul(transpose(j), mul(a, j));
            v = mul(v, j);
        }
    }
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &k| a[i][i].total_cmp(&a[k][k]));
    let column = |k: usize| -> Point {
        let axis = [v[0][k], v[1][k], v[2][k]];
        let largest = axis.iter().fold(0.0f64, |m, &x| if x.abs() > m.abs() { x } else { m });
        scale(axis, if largest < 0.0 { -1.0 } else { 1.0 } / norm(axis))
    };
    let (x, y) = (column(order[0]), column(order[1]));
    let z = cross(x, y);
    Principal { moments: order.map(|i| a[i][i]), axes: [x, y, z] }
}

fn mul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn transpose(a: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [[a[0][0], a[1][0], a[2][0]], [a[0][1], a[1][1], a[2][1]], [a[0][2], a[1][2], a[2][2]]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vector::dot;

    #[test]
    fn recovers_a_rotated_diagonal_tensor() {
        // R diag(1, 2, 3) Rᵀ with R a rotation about (1, 1, 1) by 0.7 rad (Rodrigues).
        let (ang, k) = (0.7f64, scale([1.0, 1.0, 1.0], 1.0 / 3f64.sqrt()));
        let kx = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
        let mut r = mul(kx, kx);
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = r[i][j] * (1.0 - ang.cos())
                    + kx[i][j] * ang.sin()
                    + if i == j { 1.0 } else { 0.0 };
            }
        }
        let d = [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 3.0]];
        let m = mul(r, mul(d, transpose(r)));
        let p = principal(m);
        for k in 0..3 {
            assert!((p.moments[k] - (k + 1) as f64).abs() < 1e-14);
            // Axis k is ± column k of R.
            let col = [r[0][k], r[1][k], r[2][k]];
            assert!((dot(p.axes[k], col).abs() - 1.0).abs() < 1e-14);
        }
        assert!((dot(cross(p.axes[0], p.axes[1]), p.axes[2]) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn diagonal_and_degenerate_tensors() {
        let p = principal([[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.0]]);
        assert_eq!(p.moments, [1.0, 2.0, 2.0]);
        assert_eq!(p.axes[0], [0.0, 0.0, 1.0]);
        let z = principal([[0.0; 3]; 3]);
        assert_eq!(z.moments, [0.0; 3]);
        let overflowed = principal([[f64::INFINITY, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        assert!(overflowed
            .moments
            .iter()
            .chain(overflowed.axes.iter().flatten())
            .all(|x| x.is_nan()));
    }
}
