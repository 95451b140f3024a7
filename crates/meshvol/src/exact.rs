//! The exact signed volume: the correctly rounded volume of the polyhedron the
//! coordinates describe.
//!
//! # Method
//! 6V = Σ a·(b×c) over the fan triangles. Each determinant is a sum of six products
//! ±aᵢbⱼcₖ. A product of three doubles is split exactly into four doubles with fused
//! multiply-add (TwoProduct: `p = a·b`, `e = fma(a, b, −p)` is exactly `a·b − p`; then
//! the same with c), every piece goes into an [`ExactSum`] (integer limbs: no rounding at
//! all), chunk accumulators merge exactly, and the total is divided by 6 and rounded
//! once.
//!
//! TwoProduct is exact unless a product underflows below 2⁻⁹⁶⁹ or overflows: that needs
//! coordinates beyond about 10⁻¹⁴⁵ or 10¹⁰², and is reported as an error rather than a
//! wrong "exact" answer.
//!
//! # Cost
//! About 24 exact additions per triangle: 3–5× the time of [`crate::mass_properties`]
//! (see the `exact` criterion bench), still well above the speed of reading the file.

use crate::accumulate::CHUNK_FACES;
use crate::accumulate::{ordered_reduce, ExactSum};
use crate::{Point, Surface};

/// Why an exact volume could not be computed.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ExactError {
    #[error("face {face}: coordinate products overflow or underflow f64 (coordinates beyond 1e102 or near 1e-145), so they cannot be summed exactly")]
    OutOfRange { face: usize },
}

/// Adds ±x·y·z exactly as four doubles; false when a piece over- or underflowed.
#[inline(always)]
fn add_triple_product(sum: &mut ExactSum, x: f64, y: f64, z: f64, negate: bool) -> bool {
    // 2⁻⁹⁶⁹: below it the FMA error term of a product may itself be rounded.
    const TINY: f64 = f64::from_bits(54 << 52);
    let p = x * y;
    let pe = x.mul_add(y, -p);
    let q = p * z;
    let qe = p.mul_add(z, -q);
    let w = pe * z;
    let we = pe.mul_add(z, -w);
    let lossy = |v: f64| !v.is_finite() || (v != 0.0 && v.abs() < TINY);
    if lossy(p) || lossy(q) || lossy(w) {
        return false;
    }
    for piece in [q, qe, w, we] {
        sum.add(if negate { -piece } else { piece });
    }
    true
}

/// Six times the exact signed volume of triangle (a, b, c) with the origin, added to `sum`.
#[inline(always)]
fn add_determinant(sum: &mut ExactSum, a: Point, b: Point, c: Point) -> bool {
    const TERMS: [(usize, usize, usize, bool); 6] = [
        (0, 1, 2, false),
        (1, 2, 0, false),
        (2, 0, 1, false),
        (0, 2, 1, true),
        (1, 0, 2, true),
        (2, 1, 0, true),
    ];
    TERMS.iter().all(|&(i, j, k, negate)| add_triple_product(sum, a[i], b[j], c[k], negate))
}

/// The signed volume of the polyhedron, correctly rounded to f64: Σ det(a, b, c)/6 over
/// the fan triangles about the world origin. For an open surface, the signed volume of
/// the cones from the origin to the faces, the same convention as
/// [`crate::MassProperties::signed_volume`].
///
/// ```
/// use meshvol::{Mesh, exact_signed_volume};
/// // A tetrahedron with volume 1/6 far from the origin: still exact.
/// let o = 1e7 + 0.1;
/// let p = vec![[o, o, o], [o + 1.0, o, o], [o, o + 1.0, o], [o, o, o + 1.0]];
/// let t = Mesh::from_triangles(p, vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]).unwrap();
/// assert_eq!(exact_signed_volume(&t).unwrap(), 1.0 / 6.0);
/// ```
pub fn exact_signed_volume<S: Surface + ?Sized>(surface: &S) -> Result<f64, ExactError> {
    let total = ordered_reduce(
        surface.face_count(),
        CHUNK_FACES,
        |range| {
            let mut sum = ExactSum::default();
            for face in range {
                let mut ok = true;
                surface.fan(face, |a, b, c| ok &= add_determinant(&mut sum, a, b, c));
                if !ok {
                    return Err(ExactError::OutOfRange { face });
                }
            }
            Ok(sum)
        },
        |total, part| {
            if let (Ok(t), Ok(p)) = (&mut *total, &part) {
                t.merge(p);
            } else if total.is_ok() {
                *total = part;
            }
        },
    );
    match total {
        None => Ok(0.0),
        Some(sum) => sum.map(|s| s.round_divided_by(6)),
    }
}
