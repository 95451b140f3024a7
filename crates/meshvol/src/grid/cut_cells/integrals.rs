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
//!   `∫ f g dA = A (Σ f g + Σ f · Σ g) / 12` (the sums over its three corners) and
//!   `∫ f g h dA = A (Σf Σg Σh + Σfg Σh + Σgh Σf + Σfh Σg + 2 Σfgh) / 60` (from
//!   `∫ λ₁^a λ₂^b λ₃^c dA = 2A a! b! c! / (a + b + c + 2)!` in barycentric coordinates).
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

/// The second-moment terms of a part (only with `second_moments`): in its layer, the
/// degree-3 integrals `(∫ x'²z', ∫ y'²z', ∫ x'y'z', ½∫ x'z'², ½∫ y'z'², ⅓∫ z'³) n_z dA`
/// (fields `G` with `∂G/∂z` = x'², y'², x'y', x'z', y'z', z'², clamped: the module docs
/// of [`super`]), and the degree-2 terms handed down, `(∫ x'², ∫ y'², ∫ x'y') n_z dA`.
#[inline(always)]
pub(super) fn second<const N: usize>(part: &Polygon<N>, [i, j, k]: [f64; 3]) -> [f64; 9] {
    let v = part.vertices();
    if v.len() < 3 {
        return [0.0; 9];
    }
    let local = |p: &[f64; 3]| [p[0] - i, p[1] - j, p[2] - k];
    let o = local(&v[0]);
    let mut sums = [0.0; 9];
    for w in v[1..].windows(2) {
        let (a, b) = (local(&w[0]), local(&w[1]));
        let cross = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        let corner = |d: usize| [o[d], a[d], b[d]];
        let (x, y, z) = (corner(0), corner(1), corner(2));
        // cross = 2A: ∫ f g h = cross·triple/120, ∫ f g = cross·pair/24.
        let terms = [
            triple(x, x, z) / 120.0,
            triple(y, y, z) / 120.0,
            triple(x, y, z) / 120.0,
            triple(x, z, z) / 240.0,
            triple(y, z, z) / 240.0,
            triple(z, z, z) / 360.0,
            pair(x, x) / 24.0,
            pair(y, y) / 24.0,
            pair(x, y) / 24.0,
        ];
        for (s, t) in sums.iter_mut().zip(terms) {
            *s += cross * t;
        }
    }
    sums
}

/// `Σ f g + Σ f · Σ g` over a triangle's corners.
#[inline(always)]
fn pair(f: [f64; 3], g: [f64; 3]) -> f64 {
    let sum = |v: [f64; 3]| v[0] + v[1] + v[2];
    f[0] * g[0] + f[1] * g[1] + f[2] * g[2] + sum(f) * sum(g)
}

/// `Σf Σg Σh + Σfg Σh + Σgh Σf + Σfh Σg + 2 Σfgh` over a triangle's corners.
#[inline(always)]
fn triple(f: [f64; 3], g: [f64; 3], h: [f64; 3]) -> f64 {
    let sum = |v: [f64; 3]| v[0] + v[1] + v[2];
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let fgh = f[0] * g[0] * h[0] + f[1] * g[1] * h[1] + f[2] * g[2] * h[2];
    sum(f) * sum(g) * sum(h)
        + dot(f, g) * sum(h)
        + dot(g, h) * sum(f)
        + dot(f, h) * sum(g)
        + 2.0 * fgh
}

/// The first moments over a part of the x and y components of its area vector (only
/// with `face_centroids`): `(∫ y' n_x, ∫ z' n_x, ∫ x' n_y, ∫ z' n_y) dA`, grid units,
/// local to corner `[i, j, k]`. Summed over a tube they give the moments of the solid's
/// section in a cell face (the linear fields `(y', 0, 0)`, … of [`super::apertures`]).
#[inline(always)]
pub(super) fn face_moments<const N: usize>(part: &Polygon<N>, [i, j, k]: [f64; 3]) -> [f64; 4] {
    let v = part.vertices();
    if v.len() < 3 {
        return [0.0; 4];
    }
    let local = |p: &[f64; 3]| [p[0] - i, p[1] - j, p[2] - k];
    let o = local(&v[0]);
    let mut sums = [0.0; 4];
    for w in v[1..].windows(2) {
        let (a, b) = (local(&w[0]), local(&w[1]));
        let (e, f) =
            ([a[0] - o[0], a[1] - o[1], a[2] - o[2]], [b[0] - o[0], b[1] - o[1], b[2] - o[2]]);
        let (cx, cy) = (e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2]);
        let s = [0, 1, 2].map(|d| o[d] + a[d] + b[d]);
        // cross = 2 × the area vector: ∫ f n dA = cross·Σf/6.
        sums[0] += cx * s[1];
        sums[1] += cx * s[2];
        sums[2] += cy * s[0];
        sums[3] += cy * s[2];
    }
    sums.map(|s| s / 6.0)
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
    fn second_and_face_moments_of_a_tilted_square_by_hand() {
        // z' = x' over the unit square: ∫ x'²z' = ∫ x³ = ¼, ∫ y'²z' = ∫ x'y'z' = ⅙,
        // ½∫ x'z'² = ⅛, ½∫ y'z'² = ⅓∫ z'³ = 1/12; ∫ x'² = ∫ y'² = ⅓, ∫ x'y' = ¼.
        let mut sq = P::EMPTY;
        for v in [[2.0, 3.0, 5.0], [3.0, 3.0, 6.0], [3.0, 4.0, 6.0], [2.0, 4.0, 5.0]] {
            sq.push(v);
        }
        let got = second(&sq, [2.0, 3.0, 5.0]);
        let want =
            [0.25, 1.0 / 6.0, 1.0 / 6.0, 0.125, 1.0 / 12.0, 1.0 / 12.0, 1.0 / 3.0, 1.0 / 3.0, 0.25];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-15, "{got:?}");
        }
        // n dA = (−1, 0, 1) dx'dy': ∫ y' n_x = −½, ∫ z' n_x = −½, n_y = 0.
        assert_eq!(face_moments(&sq, [2.0, 3.0, 5.0]), [-0.5, -0.5, 0.0, 0.0]);
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
