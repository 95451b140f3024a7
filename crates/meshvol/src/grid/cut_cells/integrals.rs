//! The integrals over one part (the surface inside one cell, a convex planar polygon in
//! grid units) that the cut-cell sums need.
//!
//! Coordinates are local to the part's cell, `x' = x − i`, `y' = y − j`, `z' = z − k`,
//! so every value is in [0, 1] and no digits are spent on the cell's position. A part is
//! taken as a fan from vertex 0; for fan triangle `(o, a, b)`:
//!
//! - `c = (a − o) × (b − o)`, twice its area vector; `c_z` twice its signed projected area;
//! - for linear `f`, `g` on a triangle of signed projected area `A`:
//!   `∫ f dA = A (f_o + f_a + f_b) / 3` and
//!   `∫ f g dA = A (Σ f g + Σ f · Σ g) / 12` (the sums over its three corners).
//!
//! `∫ z' dA` and the signed projected area are taken by [`Polygon::area_and_moment`], the
//! volume kernel's own function, so the volumes are the same bits as `grid`'s.

use super::super::clip::Polygon;

/// A part's volume terms (about its layer's floor) and its column terms (handed down).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Projected {
    /// Signed projected area `∫ n_z dA`.
    pub(super) area: f64,
    /// `∫ x' n_z dA`, `∫ y' n_z dA`: the first moments of the projected area.
    pub(super) area_x: f64,
    pub(super) area_y: f64,
    /// `∫ z' n_z dA`, `∫ x' z' n_z dA`, `∫ y' z' n_z dA`, `∫ ½ z'² n_z dA`.
    pub(super) z: f64,
    pub(super) xz: f64,
    pub(super) yz: f64,
    pub(super) zz_half: f64,
}

/// The integrals of a part in layer `k` of column `(i, j)` over its xy projection.
#[inline(always)]
pub(super) fn projected<const N: usize>(part: &Polygon<N>, [i, j, k]: [f64; 3]) -> Projected {
    let (area, z) = part.area_and_moment(k);
    let v = part.vertices();
    if v.len() < 3 {
        return Projected::default();
    }
    let local = |p: &[f64; 3]| [p[0] - i, p[1] - j, p[2] - k];
    let o = local(&v[0]);
    let (mut area_x, mut area_y, mut xz, mut yz, mut zz) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for w in v[1..].windows(2) {
        let (a, b) = (local(&w[0]), local(&w[1]));
        let cross = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        let (sx, sy, sz) = (o[0] + a[0] + b[0], o[1] + a[1] + b[1], o[2] + a[2] + b[2]);
        area_x += cross * sx;
        area_y += cross * sy;
        xz += cross * (o[0] * o[2] + a[0] * a[2] + b[0] * b[2] + sx * sz);
        yz += cross * (o[1] * o[2] + a[1] * a[2] + b[1] * b[2] + sy * sz);
        zz += cross * (o[2] * o[2] + a[2] * a[2] + b[2] * b[2] + sz * sz);
    }
    // cross = 2A per triangle: ∫ f = cross·Σf/6, ∫ f g = cross·(…)/24, ½∫ z² = cross·(…)/48.
    Projected {
        area,
        area_x: area_x / 6.0,
        area_y: area_y / 6.0,
        z,
        xz: xz / 24.0,
        yz: yz / 24.0,
        zz_half: zz / 48.0,
    }
}

/// The signed projected area and its first moments, for a part above the cells that are
/// computed: all a layer below it needs. The same operations, so the same bits, as
/// [`projected`]'s `area`, `area_x` and `area_y`.
#[inline(always)]
pub(super) fn handed_down<const N: usize>(part: &Polygon<N>, [i, j]: [f64; 2]) -> [f64; 3] {
    let v = part.vertices();
    if v.len() < 3 {
        return [0.0; 3];
    }
    let local = |p: &[f64; 3]| [p[0] - i, p[1] - j];
    let o = local(&v[0]);
    let (mut area_x, mut area_y) = (0.0, 0.0);
    for w in v[1..].windows(2) {
        let (a, b) = (local(&w[0]), local(&w[1]));
        let cross = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        area_x += cross * (o[0] + a[0] + b[0]);
        area_y += cross * (o[1] + a[1] + b[1]);
    }
    [part.area(), area_x / 6.0, area_y / 6.0]
}

/// A part as a piece of surface: its area vector `∫ n dA` (grid units, half the fan's
/// summed cross products) and its centroid in local coordinates, or `None` when it has no
/// area.
#[inline(always)]
pub(super) fn surface_part<const N: usize>(
    part: &Polygon<N>,
    [i, j, k]: [f64; 3],
) -> Option<([f64; 3], [f64; 3])> {
    let v = part.vertices();
    if v.len() < 3 {
        return None;
    }
    let local = |p: &[f64; 3]| [p[0] - i, p[1] - j, p[2] - k];
    let o = local(&v[0]);
    let mut crosses = [[0.0; 3]; N];
    let mut centres = [[0.0; 3]; N];
    let mut total = [0.0; 3];
    for (t, w) in v[1..].windows(2).enumerate() {
        let (a, b) = (local(&w[0]), local(&w[1]));
        let (e, f) =
            ([a[0] - o[0], a[1] - o[1], a[2] - o[2]], [b[0] - o[0], b[1] - o[1], b[2] - o[2]]);
        let c = [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]];
        crosses[t] = c;
        centres[t] = [0, 1, 2].map(|d| (o[d] + a[d] + b[d]) / 3.0);
        for d in 0..3 {
            total[d] += c[d];
        }
    }
    let norm2 = total[0] * total[0] + total[1] * total[1] + total[2] * total[2];
    if norm2 == 0.0 {
        return None;
    }
    // The fan triangles' areas are in the ratios of their crosses along the total (they
    // are coplanar); ratios of areas in a plane survive the grid's affine scaling, so the
    // centroid in grid units maps to the centroid in the world.
    let mut centroid = [0.0; 3];
    for t in 0..v.len() - 2 {
        let c = crosses[t];
        let weight = (c[0] * total[0] + c[1] * total[1] + c[2] * total[2]) / norm2;
        for d in 0..3 {
            centroid[d] += weight * centres[t][d];
        }
    }
    Some((total.map(|c| 0.5 * c), centroid))
}

#[cfg(test)]
mod tests {
    use super::*;

    type P = Polygon<9>;

    #[test]
    fn a_tilted_square_by_hand() {
        // z = x over the unit square of column (2, 3), layer 5: z' = x'.
        let mut sq = P::EMPTY;
        for v in [[2.0, 3.0, 5.0], [3.0, 3.0, 6.0], [3.0, 4.0, 6.0], [2.0, 4.0, 5.0]] {
            sq.push(v);
        }
        let p = projected(&sq, [2.0, 3.0, 5.0]);
        // ∫ x' = ½, ∫ y' = ½, ∫ z' = ½, ∫ x'z' = ∫ x'² = ⅓, ∫ y'z' = ¼, ½∫ z'² = ⅙.
        assert_eq!((p.area, p.area_x, p.area_y, p.z), (1.0, 0.5, 0.5, 0.5));
        assert!((p.xz - 1.0 / 3.0).abs() < 1e-15 && (p.yz - 0.25).abs() < 1e-15);
        assert!((p.zz_half - 1.0 / 6.0).abs() < 1e-15);
        // The surface: normal (−1, 0, 1)·√2/2, area √2, centroid at the middle.
        let (vector, centroid) = surface_part(&sq, [2.0, 3.0, 5.0]).unwrap();
        assert_eq!(vector, [-1.0, 0.0, 1.0]);
        assert_eq!(centroid, [0.5, 0.5, 0.5]);
    }

    #[test]
    fn a_wall_has_no_projection_but_a_surface() {
        let t = P::triangle([0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(projected(&t, [0.0; 3]), Projected::default());
        let (vector, centroid) = surface_part(&t, [0.0; 3]).unwrap();
        assert_eq!(vector, [0.5, 0.0, 0.0]);
        let third = 1.0 / 3.0;
        assert_eq!(centroid, [0.0, third, third]);
        assert!(surface_part(&P::triangle([0.0; 3], [1.0; 3], [2.0; 3]), [0.0; 3]).is_none());
    }
}
