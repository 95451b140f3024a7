//! Area, perimeter, centroid and second moments of polygons with holes, by Green's
//! theorem on each ring's edges, summed about the ring's first vertex with fused
//! multiply-adds and compensation (the math and accuracy are in [`super`]'s docs).

use std::borrow::Borrow;

use super::{Point2, Polygon};
use crate::accumulate::{CompensatedSum, UNIT_ROUNDOFF};

/// The second moments of an area about its centroid (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SecondMoments {
    /// ∫(y − c_y)² dA: about the axis through the centroid parallel to x.
    pub ix: f64,
    /// ∫(x − c_x)² dA: about the axis through the centroid parallel to y.
    pub iy: f64,
    /// ∫(x − c_x)(y − c_y) dA.
    pub ixy: f64,
    /// ix + iy: about the axis through the centroid normal to the plane.
    pub polar: f64,
}

impl SecondMoments {
    /// The principal moments (larger first) and the angle, in radians counter-clockwise
    /// from the x axis, of the axis about which the first one is taken.
    ///
    /// ```
    /// use meshvol::polygon::SecondMoments;
    /// // A 2 × 1 rectangle turned by 30°: principal moments 2/3 and 1/6.
    /// let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    /// let (a, b) = (1.0 / 6.0, 2.0 / 3.0); // about its own x and y axes
    /// let m = SecondMoments {
    ///     ix: a * c * c + b * s * s,
    ///     iy: a * s * s + b * c * c,
    ///     ixy: (b - a) * s * c,
    ///     polar: a + b,
    /// };
    /// let ([big, small], angle) = m.principal();
    /// assert!((big - 2.0 / 3.0).abs() < 1e-15 && (small - 1.0 / 6.0).abs() < 1e-15);
    /// assert!((angle - 120f64.to_radians()).abs() < 1e-12);
    /// ```
    pub fn principal(&self) -> ([f64; 2], f64) {
        let mean = (self.ix + self.iy) / 2.0;
        let half_difference = (self.ix - self.iy) / 2.0;
        let radius = half_difference.hypot(self.ixy);
        // The moment about the axis at angle θ is mean + half_difference·cos 2θ
        // − ixy·sin 2θ, largest where (cos 2θ, sin 2θ) points along
        // (half_difference, −ixy).
        // (+ 0.0 turns an angle of −0 into 0.)
        let angle = 0.5 * (-self.ixy).atan2(half_difference) + 0.0;
        // Axes are directions modulo π: report the angle in [0, π).
        let pi = std::f64::consts::PI;
        let angle = if angle < 0.0 { angle + pi } else { angle };
        let angle = if angle >= pi { angle - pi } else { angle };
        ([mean + radius, mean - radius], angle)
    }
}

/// Whether a ring bounds its polygon from outside or is a hole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RingRole {
    Exterior,
    Hole,
}

/// One ring as it was given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RingProperties {
    /// The polygon's index in the set.
    pub polygon: usize,
    /// The ring's index in its polygon: 0 for the exterior, 1, 2, … for the holes.
    pub ring: usize,
    pub role: RingRole,
    pub vertices: usize,
    /// Area as wound: positive counter-clockwise.
    pub signed_area: f64,
    pub perimeter: f64,
}

/// What [`area_properties`] measures.
#[derive(Clone, Debug, PartialEq)]
pub struct AreaProperties {
    /// Σ |exteriors| − Σ |holes|.
    pub area: f64,
    /// The length of every ring, holes included.
    pub perimeter: f64,
    /// `None` when the area is zero within rounding.
    pub centroid: Option<Point2>,
    /// About the centroid; zero when the centroid is `None`.
    pub inertia: SecondMoments,
    /// Every ring, polygon by polygon.
    pub rings: Vec<RingProperties>,
}

/// Ring sums about a reference point: twice the area, six times the first moments,
/// Σ|k| and the perimeter.
#[derive(Clone, Copy, Default)]
struct FirstSums {
    double_area: CompensatedSum,
    six_first: [CompensatedSum; 2],
    abs_double_area: f64,
    perimeter: CompensatedSum,
}

/// x₀y₁ − x₁y₀ to within 1.5 ulp of the result (Kahan's algorithm with FMA).
#[inline(always)]
pub(crate) fn cross(a: Point2, b: Point2) -> f64 {
    let w = b[0] * a[1];
    let error = b[0].mul_add(a[1], -w);
    a[0].mul_add(b[1], -w) - error
}

/// Calls `edge(a, b)` for each edge of `ring` with both ends taken as
/// (p − `origin`) − `offset`.
#[inline(always)]
fn for_each_edge(
    ring: &[Point2],
    origin: Point2,
    offset: Point2,
    mut edge: impl FnMut(Point2, Point2),
) {
    let relative = |p: Point2| [(p[0] - origin[0]) - offset[0], (p[1] - origin[1]) - offset[1]];
    let Some(&last) = ring.last() else { return };
    let mut a = relative(last);
    for &p in ring {
        let b = relative(p);
        edge(a, b);
        a = b;
    }
}

fn first_sums(ring: &[Point2]) -> FirstSums {
    let mut s = FirstSums::default();
    let Some(&origin) = ring.first() else { return s };
    for_each_edge(ring, origin, [0.0; 2], |a, b| {
        let k = cross(a, b);
        s.double_area.add(k);
        s.abs_double_area += k.abs();
        s.six_first[0].add((a[0] + b[0]) * k);
        s.six_first[1].add((a[1] + b[1]) * k);
        s.perimeter.add((b[0] - a[0]).hypot(b[1] - a[1]));
    });
    s
}

/// 12 ∫x² dA, 12 ∫y² dA and 24 ∫xy dA of a ring about `origin + offset`, as wound.
fn second_sums(ring: &[Point2], origin: Point2, offset: Point2) -> [f64; 3] {
    let mut sums = [CompensatedSum::default(); 3];
    for_each_edge(ring, origin, offset, |a, b| {
        let k = cross(a, b);
        sums[0].add((a[0] * a[0] + a[0] * b[0] + b[0] * b[0]) * k);
        sums[1].add((a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) * k);
        sums[2].add((a[0] * (2.0 * a[1] + b[1]) + b[0] * (a[1] + 2.0 * b[1])) * k);
    });
    sums.map(|s| s.value())
}

/// The signed area of a ring: positive when it winds counter-clockwise.
///
/// ```
/// use meshvol::polygon::signed_area;
/// assert_eq!(signed_area(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]), 2.0);
/// assert_eq!(signed_area(&[[0.0, 0.0], [0.0, 1.0], [2.0, 1.0], [2.0, 0.0]]), -2.0);
/// ```
pub fn signed_area(ring: &[Point2]) -> f64 {
    first_sums(ring).double_area.value() / 2.0
}

/// Area, perimeter, centroid and second moments of a set of polygons (a multipolygon,
/// or one polygon as a one-element slice).
///
/// ```
/// use meshvol::polygon::{area_properties, Polygon};
/// // A 4 × 2 rectangle with a 1 × 1 hole, far from the origin; the hole is wound the same
/// // way as the exterior and still subtracts.
/// let o = [5.0e6, 1.0e7];
/// let at = |x: f64, y: f64| [o[0] + x, o[1] + y];
/// let square = Polygon::new(
///     vec![at(0.0, 0.0), at(4.0, 0.0), at(4.0, 2.0), at(0.0, 2.0)],
///     vec![vec![at(1.0, 0.5), at(2.0, 0.5), at(2.0, 1.5), at(1.0, 1.5)]],
/// );
/// let p = area_properties(&[square]);
/// assert_eq!(p.area, 7.0);
/// assert_eq!(p.perimeter, 16.0);
/// // The centroid is exact to the last digit of its world coordinates (1e-9 at 5e6).
/// let c = p.centroid.unwrap();
/// assert!((c[0] - (o[0] + 14.5 / 7.0)).abs() < 1e-9 && c[1] == o[1] + 1.0);
/// // ix: the rectangle's 4·2³/12 minus the hole's 1/12 (both centred on y = 1).
/// assert!((p.inertia.ix - (32.0 / 12.0 - 1.0 / 12.0)).abs() < 1e-13);
/// assert_eq!(p.rings[1].signed_area, 1.0);
/// ```
pub fn area_properties<P: Borrow<Polygon>>(polygons: &[P]) -> AreaProperties {
    let reference = polygons.iter().find_map(|p| p.borrow().exterior.first().copied());
    let mut rings = Vec::new();
    let mut double_area = CompensatedSum::default();
    let mut abs_double_area = 0.0;
    let mut six_first = [CompensatedSum::default(); 2];
    let mut perimeter = CompensatedSum::default();
    // Per ring: the weight (±1 or 0) that turns its sums into the region's, and its
    // first vertex.
    let mut weights: Vec<(f64, Point2)> = Vec::new();
    let origin = reference.unwrap_or_default();
    for (index, polygon) in polygons.iter().enumerate() {
        for (ring_index, ring) in polygon.borrow().rings().enumerate() {
            let sums = first_sums(ring);
            let signed = sums.double_area.value();
            let (role, role_sign) =
                if ring_index == 0 { (RingRole::Exterior, 1.0) } else { (RingRole::Hole, -1.0) };
            let weight = if signed > 0.0 {
                role_sign
            } else if signed < 0.0 {
                -role_sign
            } else {
                0.0
            };
            let ring_origin = ring.first().copied().unwrap_or(origin);
            // The ring's own origin relative to the common one; its area times this
            // moves the ring's first moment to the common origin.
            let shift = [ring_origin[0] - origin[0], ring_origin[1] - origin[1]];
            double_area.add(weight * signed);
            abs_double_area += sums.abs_double_area;
            for axis in 0..2 {
                six_first[axis].add(weight * sums.six_first[axis].value());
                six_first[axis].add(weight * 3.0 * signed * shift[axis]);
            }
            perimeter.add(sums.perimeter.value());
            weights.push((weight, ring_origin));
            rings.push(RingProperties {
                polygon: index,
                ring: ring_index,
                role,
                vertices: ring.len(),
                signed_area: signed / 2.0,
                perimeter: sums.perimeter.value(),
            });
        }
    }
    let double = double_area.value();
    let mut centroid = None;
    let mut inertia = SecondMoments::default();
    // Below this the rings cancel to rounding: no centroid.
    if double.abs() > 8.0 * UNIT_ROUNDOFF * abs_double_area {
        // The centroid relative to the common origin.
        let c = six_first.map(|s| s.value() / (3.0 * double));
        let mut sums = [CompensatedSum::default(); 3];
        let mut weights = weights.iter();
        for polygon in polygons {
            for ring in polygon.borrow().rings() {
                let Some(&(weight, ring_origin)) = weights.next() else { break };
                if weight == 0.0 {
                    continue;
                }
                // Coordinates about the centroid as (p − ring origin) − (c − shift): both
                // differences are small, so the second pass keeps full precision.
                let shift = [ring_origin[0] - origin[0], ring_origin[1] - origin[1]];
                let offset = [c[0] - shift[0], c[1] - shift[1]];
                let [xx, yy, xy] = second_sums(ring, ring_origin, offset);
                sums[0].add(weight * xx);
                sums[1].add(weight * yy);
                sums[2].add(weight * xy);
            }
        }
        let [xx, yy, xy] = sums.map(|s| s.value());
        let (iy, ix, ixy) = (xx / 12.0, yy / 12.0, xy / 24.0);
        inertia = SecondMoments { ix, iy, ixy, polar: ix + iy };
        centroid = Some([origin[0] + c[0], origin[1] + c[1]]);
    }
    AreaProperties { area: double / 2.0, perimeter: perimeter.value(), centroid, inertia, rings }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::{polygon_issues, PolygonIssue};
    use crate::test_rng::XorShift;

    /// A star-shaped ring around (cx, cy) with integer vertices, counter-clockwise.
    fn star(rng: &mut XorShift, n: usize, centre: [i64; 2], radius: i64) -> Vec<[i64; 2]> {
        (0..n)
            .map(|i| {
                let angle = std::f64::consts::TAU * i as f64 / n as f64;
                let r = (radius / 2 + rng.below(radius as u64 / 2) as i64) as f64;
                [centre[0] + (r * angle.cos()) as i64, centre[1] + (r * angle.sin()) as i64]
            })
            .collect()
    }

    /// Exact sums of a ring with integer vertices, as wound: 2A, 6∫x, 6∫y, 12∫x², 12∫y²,
    /// 24∫xy.
    fn exact_sums(ring: &[[i64; 2]]) -> [i128; 6] {
        let mut s = [0i128; 6];
        for (j, a) in ring.iter().enumerate() {
            let b = ring[(j + 1) % ring.len()];
            let (x0, y0, x1, y1) = (a[0] as i128, a[1] as i128, b[0] as i128, b[1] as i128);
            let k = x0 * y1 - x1 * y0;
            s[0] += k;
            s[1] += (x0 + x1) * k;
            s[2] += (y0 + y1) * k;
            s[3] += (x0 * x0 + x0 * x1 + x1 * x1) * k;
            s[4] += (y0 * y0 + y0 * y1 + y1 * y1) * k;
            s[5] += (2 * x0 * y0 + x0 * y1 + x1 * y0 + 2 * x1 * y1) * k;
        }
        s
    }

    /// Area, centroid and (ix, iy, ixy) of a polygon with integer vertices, from exact
    /// integer sums (holes subtract), each rounded once or twice at the end.
    fn exact_properties(rings: &[Vec<[i64; 2]>]) -> (f64, [f64; 2], [f64; 3]) {
        let mut total = [0i128; 6];
        for (i, ring) in rings.iter().enumerate() {
            let s = exact_sums(ring);
            let sign = s[0].signum() * if i == 0 { 1 } else { -1 };
            for (t, x) in total.iter_mut().zip(s) {
                *t += sign * x;
            }
        }
        let [k, sx, sy, sxx, syy, sxy] = total;
        // A = k/2, c = s/(3k), ∫x² about c = sxx/12 − sx²/(18k), ∫xy = sxy/24 − sx·sy/(18k).
        let about = |s2: i128, s2_div: i128, a: i128, b: i128| {
            (s2 * 18 * k - s2_div * a * b) as f64 / (s2_div * 18 * k) as f64
        };
        (
            k as f64 / 2.0,
            [sx as f64 / (3 * k) as f64, sy as f64 / (3 * k) as f64],
            [about(syy, 12, sy, sy), about(sxx, 12, sx, sx), about(sxy, 24, sx, sy)],
        )
    }

    #[test]
    fn parcel_at_utm_coordinates_keeps_every_digit() {
        // A parcel of about 300 m with vertices on a 1/1024 m grid at (5e6, 1e7): every
        // coordinate is exact in f64, so the exact area is known.
        const SCALE: f64 = 1.0 / 1024.0;
        let offset = [5.0e6, 1.0e7];
        let mut rng = XorShift::new(0x9e3779b97f4a7c15);
        let outer = star(&mut rng, 60, [160_000, 160_000], 150_000);
        let hole = star(&mut rng, 20, [150_000, 150_000], 30_000);
        let world = |ring: &[[i64; 2]]| -> Vec<Point2> {
            ring.iter()
                .map(|p| [offset[0] + p[0] as f64 * SCALE, offset[1] + p[1] as f64 * SCALE])
                .collect()
        };
        let polygon = Polygon::new(world(&outer), vec![world(&hole)]);
        let (exact_area, exact_centroid, exact_moments) =
            exact_properties(&[outer.clone(), hole.clone()]);
        let exact_area = exact_area * SCALE * SCALE;

        let p = area_properties(&[&polygon]);
        assert_eq!(p.area, exact_area);

        // The textbook shoelace on world coordinates.
        let naive = |ring: &[Point2]| {
            let mut s = 0.0;
            for (j, a) in ring.iter().enumerate() {
                let b = ring[(j + 1) % ring.len()];
                s += a[0] * b[1] - b[0] * a[1];
            }
            s / 2.0
        };
        let naive_area = naive(&polygon.exterior) - naive(&polygon.holes[0]);
        let naive_error = (naive_area - exact_area).abs() / exact_area;
        assert!(naive_error > 1e-9, "naive shoelace error only {naive_error:e}");

        let c = p.centroid.unwrap();
        for axis in 0..2 {
            let exact = offset[axis] + exact_centroid[axis] * SCALE;
            // Within one ulp of the world coordinate (1.9e-9 at 1e7).
            assert!((c[axis] - exact).abs() <= 2e-9, "centroid {axis}: {} vs {exact}", c[axis]);
        }
        let scale4 = SCALE.powi(4);
        let got = [p.inertia.ix, p.inertia.iy, p.inertia.ixy];
        for (g, e) in got.iter().zip(exact_moments) {
            let e = e * scale4;
            assert!((g - e).abs() <= 1e-13 * p.inertia.polar, "moment {g} vs {e}");
        }
        assert_eq!(p.inertia.polar, p.inertia.ix + p.inertia.iy);
    }

    #[test]
    fn holes_subtract_whatever_their_winding() {
        let outer = vec![[0.0, 0.0], [0.0, 3.0], [3.0, 3.0], [3.0, 0.0]]; // clockwise
        let ccw_hole = vec![[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]];
        let cw_hole: Vec<Point2> = ccw_hole.iter().rev().copied().collect();
        for hole in [ccw_hole, cw_hole] {
            let p = area_properties(&[Polygon::new(outer.clone(), vec![hole.clone()])]);
            assert_eq!(p.area, 8.0);
            assert_eq!(p.centroid, Some([1.5, 1.5]));
            // Square frame: (3⁴ − 1⁴)/12 about each axis.
            assert_eq!(p.inertia.ix, 80.0 / 12.0);
            assert_eq!(p.inertia.ixy, 0.0);
            assert_eq!(p.rings[0].signed_area, -9.0);
            assert_eq!(p.rings[1].role, RingRole::Hole);
            assert_eq!(p.perimeter, 16.0);
        }
    }

    #[test]
    fn moments_of_an_l_shape_match_its_rectangles() {
        // L = [0,4]×[0,1] ∪ [0,1]×[1,3]; the rectangles' moments by the parallel-axis
        // theorem are the independent value.
        let l = Polygon::new(
            vec![[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]],
            vec![],
        );
        let rects = [(4.0, 1.0, [2.0, 0.5]), (1.0, 2.0, [0.5, 2.0])];
        let area: f64 = rects.iter().map(|r| r.0 * r.1).sum();
        let c = [0, 1].map(|k| rects.iter().map(|r| r.0 * r.1 * r.2[k]).sum::<f64>() / area);
        let (mut ix, mut iy, mut ixy) = (0.0, 0.0, 0.0);
        for (w, h, rc) in rects {
            let (dx, dy) = (rc[0] - c[0], rc[1] - c[1]);
            ix += w * h * h * h / 12.0 + w * h * dy * dy;
            iy += h * w * w * w / 12.0 + w * h * dx * dx;
            ixy += w * h * dx * dy;
        }
        let p = area_properties(&[l]);
        assert_eq!(p.area, area);
        let got = p.centroid.unwrap();
        assert!((got[0] - c[0]).abs() < 1e-15 && (got[1] - c[1]).abs() < 1e-15);
        for (g, e) in [(p.inertia.ix, ix), (p.inertia.iy, iy), (p.inertia.ixy, ixy)] {
            assert!((g - e).abs() < 1e-14, "{g} vs {e}");
        }
    }

    #[test]
    fn random_integer_polygons_match_exact_arithmetic() {
        let mut rng = XorShift::new(0x853c49e6748fea9b);
        for trial in 0..50 {
            let n = 3 + rng.below(40) as usize;
            let ring = star(&mut rng, n, [2000, 2000], 2000);
            let polygon = Polygon::new(ring.iter().map(|p| p.map(|x| x as f64)).collect(), vec![]);
            let (area, centroid, moments) = exact_properties(&[ring]);
            let p = area_properties(&[polygon]);
            assert_eq!(p.area, area, "trial {trial}");
            let c = p.centroid.unwrap();
            for k in 0..2 {
                assert!((c[k] - centroid[k]).abs() <= 1e-12 * centroid[k].abs());
            }
            for (g, e) in [p.inertia.ix, p.inertia.iy, p.inertia.ixy].iter().zip(moments) {
                assert!((g - e).abs() <= 1e-12 * p.inertia.polar, "trial {trial}: {g} vs {e}");
            }
        }
    }

    #[test]
    fn multipolygons_add_and_empty_input_has_no_centroid() {
        let unit =
            |x: f64| Polygon::new(vec![[x, 0.0], [x + 1.0, 0.0], [x + 1.0, 1.0], [x, 1.0]], vec![]);
        let p = area_properties(&[unit(0.0), unit(2.0)]);
        assert_eq!(p.area, 2.0);
        assert_eq!(p.centroid, Some([1.5, 0.5]));
        // Two unit squares 2 apart: iy = 2·(1/12 + 1²).
        assert_eq!(p.inertia.iy, 2.0 * (1.0 / 12.0 + 1.0));
        assert_eq!(p.rings.len(), 2);
        assert!(polygon_issues(&[unit(0.0), unit(2.0)]).is_empty());

        let empty = area_properties::<Polygon>(&[]);
        assert_eq!((empty.area, empty.centroid), (0.0, None));
        let line = Polygon::new(vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]], vec![]);
        assert_eq!(area_properties(&[&line]).centroid, None);
        assert!(matches!(polygon_issues(&[&line])[..], [PolygonIssue::Degenerate { ring: 0, .. }]));
    }
}
