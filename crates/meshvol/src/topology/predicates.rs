//! Exact geometric predicates on triangles, from Shewchuk's adaptive orientation tests
//! (the `robust` crate): signs are exact, so the answers do not depend on rounding.

use crate::vector::{cross, dot, sign, sub};
use crate::Point;
use robust::{orient2d, orient3d, Coord, Coord3D};
use std::ops::{Add, Mul, Sub};

fn c3(p: Point) -> Coord3D<f64> {
    Coord3D { x: p[0], y: p[1], z: p[2] }
}

/// Sign of det[a − d; b − d; c − d]: positive when d lies behind the triangle (a, b, c),
/// i.e. on the side its normal (b − a) × (c − a) points away from.
pub(crate) fn orient(a: Point, b: Point, c: Point, d: Point) -> f64 {
    Plane::of([a, b, c]).orient(d)
}

/// [`orient`] where the floating-point filter cannot decide: nearly or exactly coplanar
/// points, which touching faces make common. (Out of line: the filter's fast path is
/// inlined into the pair search, and this rarer path would crowd it.)
#[cold]
#[inline(never)]
fn orient_exactly([a, b, c]: [Point; 3], d: Point) -> f64 {
    // a, b, c in a plane x_k = h (faces of CAD parts often are): expanding the
    // determinant along column k leaves (−1)^k (h − d_k) times the 2D orientation of
    // a, b, c without axis k, each factor's sign exact. This skips orient3d's slow
    // exact path, which every touching pair of such faces would otherwise take.
    for k in 0..3 {
        if a[k] == b[k] && b[k] == c[k] {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let (i, j) = (i.min(j), i.max(j));
            let flat = |p: Point| Coord { x: p[i], y: p[j] };
            let parity = if k == 1 { -1.0 } else { 1.0 };
            return parity * sign(a[k] - d[k]) * sign(orient2d(flat(a), flat(b), flat(c)));
        }
    }
    orient_on_grid([a, b, c], d).unwrap_or_else(|| sign(orient3d(c3(a), c3(b), c3(c), c3(d))))
}

/// The sign of det[a − d; b − d; c − d] in integer arithmetic, when the nine
/// differences are exact in f64 and are multiples of one power of two spanning at most
/// [`GRID_BITS`] bits (points read from a float32 file of one part are); `None`
/// otherwise. Each product of three then fits in 3 × 40 bits and their sum in an i128;
/// within [`NARROW_BITS`] (nearby points of one grid, the common case), in an i64.
/// Exactly coplanar points (flat regions of CAD parts, touching faces) are common, and
/// for them orient3d's adaptive path computes the whole exact expansion, several times
/// slower.
fn orient_on_grid(rows: [Point; 3], d: Point) -> Option<f64> {
    let mut x = [0.0; 9];
    let (mut low, mut high) = (i32::MAX, i32::MIN);
    for (i, p) in rows.iter().enumerate() {
        for k in 0..3 {
            let difference = p[k] - d[k];
            // Knuth's two-difference: the rounding error of p[k] − d[k], zero when exact.
            let virtual_d = p[k] - difference;
            let tail = (p[k] - (difference + virtual_d)) + (virtual_d - d[k]);
            if tail != 0.0 || !difference.is_finite() {
                return None;
            }
            if difference != 0.0 {
                let bits = difference.to_bits();
                let exponent = ((bits >> 52) & 0x7ff) as i32;
                if exponent == 0 {
                    return None; // subnormal: left to orient3d
                }
                // The lowest set bit's place, and the place above the highest.
                let significand = bits & ((1 << 52) - 1) | 1 << 52;
                low = low.min(exponent - 1075 + significand.trailing_zeros() as i32);
                high = high.max(exponent - 1022);
            }
            x[3 * i + k] = difference;
        }
    }
    if low == i32::MAX {
        return Some(0.0); // every difference is zero: d is a, b and c
    }
    if high - low > GRID_BITS || !(-1022..=1000).contains(&low) {
        return None;
    }
    // In units of 2^low (a power of two, so the scaling is exact): integers below
    // 2^(high − low).
    let unit = f64::from_bits(((1023 - low) as u64) << 52);
    let m = x.map(|v| (v * unit) as i64);
    let sign = if high - low <= NARROW_BITS {
        // |m| < 2^20: products of three below 2^60, the sum of six below 2^63.
        determinant(m).signum()
    } else {
        determinant(m.map(i128::from)).signum() as i64
    };
    Some(sign as f64)
}

/// The determinant of the 3 × 3 matrix `m` (rows in order), expanded along its first row.
fn determinant<T: Copy + Add<Output = T> + Sub<Output = T> + Mul<Output = T>>(m: [T; 9]) -> T {
    m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6])
        + m[2] * (m[3] * m[7] - m[4] * m[6])
}

/// The widest span of bits [`orient_on_grid`] takes.
const GRID_BITS: i32 = 40;

/// The widest span of bits [`orient_on_grid`] computes in an i64.
const NARROW_BITS: i32 = 20;

/// A triangle with its plane, for exact orientation tests against it.
///
/// The edge vectors' cross product is computed once, with the magnitudes Shewchuk's
/// static error bound needs (the same expression shape as his orient3d: a coordinate
/// times a difference of two products, three times, on differences of input
/// coordinates), so most tests are a dot product and a comparison, and the rest go to
/// [`orient_exactly`].
pub(crate) struct Plane {
    t: [Point; 3],
    /// (t₁ − t₀) × (t₂ − t₀), rounded.
    normal: Point,
    /// Per component of `normal`, the sum of its two products' magnitudes.
    magnitude: Point,
}

/// Shewchuk's orient3d error bound coefficient, (7 + 56ε)ε with ε = 2⁻⁵³.
const ORIENT3D_BOUND: f64 = (7.0 + 56.0 * HALF_ULP) * HALF_ULP;
const HALF_ULP: f64 = f64::EPSILON / 2.0;

impl Plane {
    pub(crate) fn of(t: [Point; 3]) -> Plane {
        let (v, w) = (sub(t[1], t[0]), sub(t[2], t[0]));
        let m = |i: usize, j: usize| (v[i] * w[j]).abs() + (v[j] * w[i]).abs();
        Plane { t, normal: cross(v, w), magnitude: [m(1, 2), m(2, 0), m(0, 1)] }
    }

    /// `orient(t[0], t[1], t[2], p)`, exactly.
    #[inline(always)]
    pub(crate) fn orient(&self, p: Point) -> f64 {
        let u = sub(p, self.t[0]);
        // orient is the sign of det[a − p; b − p; c − p] = −(p − a)·((b − a) × (c − a)).
        let det = -dot(u, self.normal);
        let permanent = dot(u.map(f64::abs), self.magnitude);
        if det.abs() > ORIENT3D_BOUND * permanent {
            sign(det)
        } else {
            orient_exactly(self.t, p)
        }
    }

    /// Whether segment pq, whose ends are on opposite sides of the plane (their
    /// [`Plane::orient`]s already known), crosses this triangle properly: the
    /// segment's line strictly inside the triangle.
    fn crossed_inside(&self, p: Point, q: Point) -> bool {
        self.crossing(p, q) == Some(true)
    }

    /// How segment pq, whose ends are strictly on opposite sides of the plane, meets
    /// this triangle: `Some(true)` through its interior, `Some(false)` missing it,
    /// `None` through its boundary (an edge or a corner).
    pub(crate) fn crossing(&self, p: Point, q: Point) -> Option<bool> {
        let [a, b, c] = self.t;
        let s = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)];
        if s[0] != 0.0 && s[0] == s[1] && s[1] == s[2] {
            Some(true)
        } else if s.contains(&1.0) && s.contains(&-1.0) {
            Some(false)
        } else {
            None
        }
    }

    /// (t₁ − t₀) × (t₂ − t₀), rounded.
    pub(crate) fn normal(&self) -> Point {
        self.normal
    }

    /// det[t₀ − p; t₁ − p; t₂ − p] (whose sign [`Plane::orient`] gives) in floating
    /// point, and a bound on its error (Shewchuk's static bound for orient3d).
    pub(crate) fn height(&self, p: Point) -> (f64, f64) {
        let u = sub(p, self.t[0]);
        let permanent = dot(u.map(f64::abs), self.magnitude);
        (-dot(u, self.normal), ORIENT3D_BOUND * permanent)
    }
}

/// Whether orientations `s` are all on one closed side, not all zero.
fn apart(s: [f64; 3]) -> bool {
    let straddle = s[0] * s[1] < 0.0 || s[1] * s[2] < 0.0 || s[2] * s[0] < 0.0;
    !straddle && s != [0.0; 3]
}

impl Plane {
    /// Whether this triangle and `u` cross properly: an edge of one passes strictly
    /// through the interior of the other. Touching (shared or coplanar parts, an edge
    /// lying on a face) does not count: it neither double-counts volume nor breaks a
    /// surface. (A method of the first triangle's plane, made once for all its partners:
    /// a pair search tests each triangle against several.)
    pub(crate) fn crossed_by(&self, u: [Point; 3]) -> bool {
        // The corners of u on one closed side of t's plane, not all in it: they cannot
        // cross. (No edge of u crosses the plane strictly, and u's interior is strictly
        // off it, where t's edges are not. A corner off the plane makes t a true
        // triangle, with a plane: a segment-like t has every point in its "plane".)
        // Three orientation tests settle most pairs before the edge tests; a corner in
        // the plane, which neighbours across a flat quad have, settles them too, where
        // the strict test went on to the second plane: on a 5M-triangle sphere snapped
        // to a grid, half the exact tests were those.
        let t = self.t;
        let side_u = u.map(|p| self.orient(p));
        if apart(side_u) {
            return false;
        }
        let plane_u = Plane::of(u);
        let side_t = t.map(|p| plane_u.orient(p));
        if apart(side_t) {
            return false;
        }
        // An edge crosses the other triangle only with its ends strictly on opposite
        // sides of that plane: the sides just found, not computed again (on a 5M sphere
        // snapped to a 2⁻¹⁰ grid, where neighbouring chords are exactly parallel, two
        // thirds of 10M exact tests were such repeats).
        let crossing = |side: [f64; 3], plane: &Plane, points: [Point; 3]| {
            (0..3).any(|i| {
                let j = (i + 1) % 3;
                side[i] * side[j] < 0.0 && plane.crossed_inside(points[i], points[j])
            })
        };
        crossing(side_t, &plane_u, t) || crossing(side_u, self, u)
    }
}

/// The six axis directions a ray can take, as rotations of coordinates that carry the
/// direction to +x: (x, y, z), (y, z, x), (z, x, y), (−x, −y, z), (−y, −z, x), (−z, −x, y).
/// Rotations keep orientation, so winding signs mean the same in every frame.
pub(crate) const RAY_FRAMES: [fn(Point) -> Point; 6] = [
    |p| p,
    |p| [p[1], p[2], p[0]],
    |p| [p[2], p[0], p[1]],
    |p| [-p[0], -p[1], p[2]],
    |p| [-p[1], -p[2], p[0]],
    |p| [-p[2], -p[0], p[1]],
];

/// The box, in original coordinates, swept by the ray from `p` along the direction
/// `RAY_FRAMES[frame]` carries to +x.
pub(crate) fn ray_box(p: Point, frame: usize) -> (Point, Point) {
    let (mut min, mut max) = (p, p);
    match frame {
        0 => max[0] = f64::INFINITY,
        1 => max[1] = f64::INFINITY,
        2 => max[2] = f64::INFINITY,
        3 => min[0] = f64::NEG_INFINITY,
        4 => min[1] = f64::NEG_INFINITY,
        _ => min[2] = f64::NEG_INFINITY,
    }
    (min, max)
}

/// A direction no axis-aligned or diagonal feature of a mesh lines up with, for the
/// last-resort oblique ray.
pub(crate) const OBLIQUE: Point = [0.8017837257372732, 0.5345224838248488, 0.2672612419124244];

/// How segment pq, from `p` to a point `q` beyond all geometry, meets triangle
/// (a, b, c): `Some(±1)` when it passes strictly through the interior (+1 where it
/// leaves through the triangle's back, i.e. exits an outward-wound solid), `Some(0)`
/// when it misses, `None` when it grazes an edge or starts on the triangle.
pub(crate) fn segment_crossing(p: Point, q: Point, a: Point, b: Point, c: Point) -> Option<i32> {
    let (sp, sq) = (orient(a, b, c, p), orient(a, b, c, q));
    if sp * sq > 0.0 || (sp == 0.0 && sq == 0.0) {
        return Some(0);
    }
    let s = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)];
    if s.contains(&1.0) && s.contains(&-1.0) {
        return Some(0);
    }
    if s.contains(&0.0) || sp == 0.0 {
        return None;
    }
    Some(sp as i32)
}

/// How the ray from `p` in +x meets triangle (a, b, c): `Some(±1)` when it passes
/// strictly through the interior, the sign being that of the triangle's normal's x
/// component (+1 where the ray leaves an outward-wound solid); `Some(0)` when it misses;
/// `None` when it grazes an edge or vertex, or p lies on the triangle's plane inside it
/// (the caller then tries another ray).
pub(crate) fn ray_crossing(p: Point, a: Point, b: Point, c: Point) -> Option<i32> {
    let yz = |v: Point| Coord { x: v[1], y: v[2] };
    let normal_x = sign(orient2d(yz(a), yz(b), yz(c)));
    if normal_x == 0.0 {
        return Some(0); // edge-on to the ray: parallel, no crossing
    }
    let e = [
        orient2d(yz(a), yz(b), yz(p)),
        orient2d(yz(b), yz(c), yz(p)),
        orient2d(yz(c), yz(a), yz(p)),
    ]
    .map(sign);
    if e.iter().any(|&s| s == -normal_x) {
        return Some(0); // p's projection is outside the triangle's
    }
    if e.contains(&0.0) {
        return None;
    }
    // The plane is ahead of p along +x iff (p − a)·n and n_x have opposite signs, i.e.
    // orient (which is −sign((p − a)·n)) has the sign of n_x.
    match orient(a, b, c, p) {
        s if s == normal_x => Some(normal_x as i32),
        0.0 => None,
        _ => Some(0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangles_cross(t: [Point; 3], u: [Point; 3]) -> bool {
        Plane::of(t).crossed_by(u)
    }

    #[test]
    fn axis_plane_shortcut_agrees_with_orient3d() {
        // Small integer coordinates: many triples share a coordinate, many quadruples
        // are coplanar.
        let mut rng = crate::test_rng::XorShift::new(0x9e3779b97f4a7c15u64);
        let mut next = || (rng.next_u64() % 4) as f64 - 1.5;
        for _ in 0..20000 {
            let mut p = [[0.0; 3]; 4];
            p.iter_mut().for_each(|q| q.iter_mut().for_each(|x| *x = next()));
            let k = (next() + 1.5) as usize % 3;
            (p[1][k], p[2][k]) = (p[0][k], p[0][k]);
            let exact = sign(orient3d(c3(p[0]), c3(p[1]), c3(p[2]), c3(p[3])));
            assert_eq!(orient_exactly([p[0], p[1], p[2]], p[3]), exact, "{p:?}");
            assert_eq!(orient(p[0], p[1], p[2], p[3]), exact, "{p:?}");
        }
    }

    /// Nearby points of one grid, as a fine mesh has (differences of a few grid steps,
    /// far from the origin): the spans on both sides of [`NARROW_BITS`], where the
    /// determinant goes from an i64 to an i128; exactly coplanar, one step off and
    /// anywhere near (a determinant that overflows an i64 when the span is too wide:
    /// wrapped, a small one still comes out right), each sign checked against orient3d.
    #[test]
    fn narrow_grid_orientation_agrees_with_orient3d() {
        let mut rng = crate::test_rng::XorShift::new(0x6a09e667f3bcc909);
        let (mut narrow, mut wide) = (0, 0);
        for i in 0..40_000 {
            let step = [1.0 / 1024.0, 1.0, 0.5f64.powi(30)][i % 3];
            // Differences below 2^bits steps: 2^20 steps is the widest i64 span.
            let bits = [3, 12, 19, 20, 21, 30][(i / 3) % 6];
            let origin = [1e5, -3e4, 7e3].map(|x: f64| (x / step).round() * step);
            let mut offset = || (rng.below(1 << bits) as f64 - (1u64 << (bits - 1)) as f64) * step;
            let t = [0; 3].map(|_| [0, 1, 2].map(|k| origin[k] + offset()));
            let near = [0, 1, 2].map(|k| origin[k] + offset());
            let (s, r) = ((rng.below(3)) as f64 - 1.0, (rng.below(3)) as f64 - 1.0);
            let mut d =
                [0, 1, 2].map(|k| t[0][k] + s * (t[1][k] - t[0][k]) + r * (t[2][k] - t[0][k]));
            match i % 4 {
                0 | 1 => d[i % 3] += step, // one grid step off the plane
                2 => d = near,             // anywhere near
                _ => {}                    // on the plane
            }
            let exact = sign(orient3d(c3(t[0]), c3(t[1]), c3(t[2]), c3(d)));
            let Some(grid) = orient_on_grid(t, d) else { continue };
            assert_eq!(grid, exact, "{t:?} {d:?}");
            if bits < 20 {
                narrow += 1;
            } else if bits > 20 {
                wide += 1;
            }
        }
        // Both paths were taken, many times.
        assert!(narrow > 10_000 && wide > 5_000, "{narrow} {wide}");
    }

    #[test]
    fn grid_orientation_agrees_with_orient3d() {
        // Points on grids of 2^-10 (float32-like, up to ±2^17), many exactly coplanar
        // (the fourth point an integer combination of the first three), some near; and
        // spans too wide or differences not exact, where it must decline.
        let mut rng = crate::test_rng::XorShift::new(0x853c49e6748fea9bu64);
        let mut next = || rng.next_u64();
        let mut decided = 0;
        for i in 0..50_000 {
            let mut coordinate = || ((next() % (1 << 27)) as f64 - (1 << 26) as f64) / 1024.0;
            let t = [0; 3].map(|_| [0; 3].map(|_| coordinate()));
            let (s, r) = ((next() % 5) as f64 - 2.0, (next() % 5) as f64 - 2.0);
            let mut d =
                [0, 1, 2].map(|k| t[0][k] + s * (t[1][k] - t[0][k]) + r * (t[2][k] - t[0][k]));
            match i % 4 {
                0 => d[(i / 4) % 3] += 1.0 / 1024.0, // one grid step off the plane
                1 => d = d.map(|x| x * (1.0 + f64::EPSILON)), // not on the grid
                2 => d[0] = 1e30,                    // too wide a span
                _ => {}                              // exactly on the plane
            }
            let exact = sign(orient3d(c3(t[0]), c3(t[1]), c3(t[2]), c3(d)));
            if let Some(s) = orient_on_grid(t, d) {
                assert_eq!(s, exact, "{t:?} {d:?}");
                decided += 1;
            }
            assert_eq!(orient(t[0], t[1], t[2], d), exact, "{t:?} {d:?}");
        }
        // It decides the grid cases (exactly and one step off the plane), not the rest.
        assert!(decided >= 25_000, "{decided}");
        assert_eq!(orient_on_grid([[0.0; 3]; 3], [0.0; 3]), Some(0.0));
        assert_eq!(
            orient_on_grid([[1e-300, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [0.0; 3]),
            None
        );
    }

    #[test]
    fn plane_filter_agrees_with_orient3d() {
        // Random triangles and points, some exactly or nearly on the plane (a point of
        // the triangle nudged by an ulp or so), some far: the filter may only answer
        // when it is right.
        let mut rng = crate::test_rng::XorShift::new(0x2545f4914f6cdd1du64);
        let mut next = || rng.unit() - 0.5;
        for i in 0..20000 {
            let t = [[next(), next(), next()], [next(), next(), next()], [next(), next(), next()]];
            let (w, z) = (next() + 0.5, next() + 0.5);
            let on = [0, 1, 2].map(|k| t[0][k] + w * (t[1][k] - t[0][k]) + z * (t[2][k] - t[0][k]));
            let p = match i % 3 {
                0 => [next(), next(), next()],
                1 => on,
                _ => on.map(|x| x + next() * 1e-15),
            };
            let scale = [1.0, 1e-8, 1e8][i % 3];
            let (t, p) = (t.map(|q| q.map(|x| x * scale)), p.map(|x| x * scale));
            let exact = sign(orient3d(c3(t[0]), c3(t[1]), c3(t[2]), c3(p)));
            assert_eq!(Plane::of(t).orient(p), exact, "{t:?} {p:?}");
        }
    }

    /// Whether orientations `s` are all strictly on one side: the textbook's test.
    fn one_side(s: [f64; 3]) -> bool {
        s[0] != 0.0 && s[0] == s[1] && s[1] == s[2]
    }

    /// [`Plane::crossed_by`] (each orientation computed once, through the filter) against
    /// the textbook form with every orientation exact and computed where it is used, on
    /// pairs made to defeat the filter: on a coarse grid (many exactly coplanar), nearly
    /// coplanar off any grid, touching at a corner or along an edge, slivers, and
    /// crossing.
    #[test]
    fn reused_sides_give_the_textbook_answer() {
        let exact = |t: [Point; 3], p: Point| orient(t[0], t[1], t[2], p);
        let crossed_by = |t: [Point; 3], p: Point, q: Point| {
            let [a, b, c] = t;
            let (s1, s2, s3) = (orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a));
            exact(t, p) * exact(t, q) < 0.0 && s1 != 0.0 && s1 == s2 && s2 == s3
        };
        let textbook = |t: [Point; 3], u: [Point; 3]| {
            let edges = |t: [Point; 3]| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])];
            !one_side(u.map(|p| exact(t, p)))
                && !one_side(t.map(|p| exact(u, p)))
                && (edges(t).iter().any(|&(p, q)| crossed_by(u, p, q))
                    || edges(u).iter().any(|&(p, q)| crossed_by(t, p, q)))
        };
        let mut rng = crate::test_rng::XorShift::new(0x3c6ef372fe94f82b);
        let (mut crossing, mut touching) = (0, 0);
        for case in 0..100_000 {
            let mut r = |n: u64| rng.below(2 * n + 1) as f64 - n as f64;
            let grid = [4.0, 64.0, 1024.0][case % 3];
            let base = [r(50), r(50), r(50)];
            let (s1, s2) = ([r(9), r(9), r(9)], [r(9), r(9), r(9)]);
            // Points of one plane (base + i s1 + j s2), a few off it by a grid step.
            let mut point = |off: bool| -> Point {
                let (i, j) = (r(4), r(4));
                let lift = if off { r(1) } else { 0.0 };
                [0, 1, 2].map(|k| (base[k] + i * s1[k] + j * s2[k] + lift) / grid)
            };
            let off = case % 4 == 0;
            let t = [point(false), point(false), point(false)];
            let mut u = [point(off), point(off), point(off)];
            match case % 5 {
                0 => u[0] = t[0],                                           // a corner
                1 => u[0] = [0, 1, 2].map(|k| (t[0][k] + t[1][k]) / 2.0),   // on an edge
                2 => u[2] = u[1].map(|c| c * (1.0 + f64::EPSILON)),         // a sliver
                3 => u = u.map(|p| p.map(|c| c + c * f64::EPSILON * r(3))), // off the grid
                _ => {}
            }
            let expected = textbook(t, u);
            assert_eq!(triangles_cross(t, u), expected, "{t:?} {u:?}");
            assert_eq!(triangles_cross(u, t), expected, "{u:?} {t:?}");
            crossing += expected as usize;
            touching += (!expected && !one_side(u.map(|p| exact(t, p)))) as usize;
        }
        assert!(crossing > 1000 && touching > 1000, "{crossing} crossing, {touching} touching");
    }

    #[test]
    fn crossing_and_touching_triangles() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        // Pierces t through its interior.
        assert!(triangles_cross(t, [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 3.0, 0.5]]));
        // Stands on t (touches along a segment, does not cross).
        assert!(!triangles_cross(t, [[0.2, 0.2, 0.0], [1.0, 0.2, 0.0], [0.5, 0.5, 1.0]]));
        // Shares an edge.
        assert!(!triangles_cross(t, [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, -1.0, 1.0]]));
        // Far away.
        assert!(!triangles_cross(t, [[5.0, 5.0, -1.0], [5.0, 5.0, 1.0], [6.0, 6.0, 0.0]]));
    }

    #[test]
    fn coplanar_edge_on_a_wall_is_not_a_crossing() {
        // A floor triangle whose edge lies in a vertical wall that dips 3e-16 below it
        // (corpus featuretype.STL): they touch along the edge and do not cross.
        let (a, b) = ([-0.128, -0.977, 0.0], [-0.13, -1.0, 0.0]);
        let floor = [a, b, [-0.56, -1.19, 0.0]];
        let wall = [[a[0], a[1], -2.7e-16], [a[0], a[1], 0.75], [b[0], b[1], 0.75]];
        assert!(!triangles_cross(floor, wall));
    }

    #[test]
    fn ray_frames_are_rotations_that_carry_each_axis_to_x() {
        let det = |f: fn(Point) -> Point| {
            let (x, y, z) = (f([1.0, 0.0, 0.0]), f([0.0, 1.0, 0.0]), f([0.0, 0.0, 1.0]));
            x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0])
                + x[2] * (y[0] * z[1] - y[1] * z[0])
        };
        let directions = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, -1.0],
        ];
        for (k, f) in RAY_FRAMES.iter().enumerate() {
            assert_eq!(det(*f), 1.0);
            assert_eq!(f(directions[k]), [1.0, 0.0, 0.0]);
            let (min, max) = ray_box([0.0; 3], k);
            let far = directions[k].map(|d| d * f64::INFINITY);
            assert!((0..3).all(|i| d_in(far[i], min[i], max[i])));
        }
        fn d_in(x: f64, lo: f64, hi: f64) -> bool {
            x.is_nan() || (lo <= x && x <= hi)
        }
    }

    #[test]
    fn segment_crossings_agree_with_the_axis_ray() {
        let (a, b, c) = ([1.0, -1.0, -1.0], [1.0, 1.0, -1.0], [1.0, -1.0, 1.0]);
        let p = [0.0, -0.5, -0.5];
        let q = [10.0, -0.4, -0.45];
        assert_eq!(segment_crossing(p, q, a, b, c), ray_crossing(p, a, b, c));
        assert_eq!(segment_crossing(p, q, a, c, b), Some(-1));
        assert_eq!(segment_crossing(p, [-10.0, -0.4, -0.45], a, b, c), Some(0));
        assert_eq!(segment_crossing(p, [10.0, 30.0, 30.0], a, b, c), Some(0)); // passes at y = z = 2.55
    }

    #[test]
    fn ray_crossings_follow_the_normal() {
        // Triangle in the plane x = 1, normal +x (counter-clockwise seen from +x).
        let (a, b, c) = ([1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 1.0]);
        assert_eq!(ray_crossing([0.0, 0.2, 0.2], a, b, c), Some(1));
        assert_eq!(ray_crossing([0.0, 0.2, 0.2], a, c, b), Some(-1));
        assert_eq!(ray_crossing([2.0, 0.2, 0.2], a, b, c), Some(0)); // behind the ray
        assert_eq!(ray_crossing([0.0, 0.9, 0.9], a, b, c), Some(0)); // outside
        assert_eq!(ray_crossing([0.0, 0.5, 0.5], a, b, c), None); // through an edge
        assert_eq!(ray_crossing([1.0, 0.2, 0.2], a, b, c), None); // on the triangle
    }
}
