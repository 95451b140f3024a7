//! The sums the signed volume and its bound are made of, and the bound: what
//! [`crate::mass_properties`] and [`crate::volume`] share, summed in the same order by
//! both, so that both give the same bits. The math is in the module docs of
//! [`crate::properties`].

use crate::accumulate::{gamma, CompensatedSum, UNIT_ROUNDOFF};
use crate::vector::{dot, sub};
use crate::{Point, Surface};

/// The sums the signed volume and its bound are made of: what [`crate::mass_properties`] and
/// [`crate::volume`] share, summed in the same order by both, so that both give the same
/// bits.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct VolumeSums {
    pub(crate) six_volume: CompensatedSum,
    /// Σ over faces of twice the vector area (each face's fan summed plainly), for the
    /// move from the reference point to the origin.
    pub(crate) vector_area: [CompensatedSum; 3],
    /// Per component, Σ of the magnitudes M of the two products in each fan triangle's
    /// cross product, and Σ (m − 1)·M over faces of m > 1 fan triangles (none in a
    /// triangle mesh): the bound weighs each face's M by m + 4, 5·ΣM plus this.
    pub(crate) vector_area_magnitude: [f64; 3],
    pub(crate) vector_area_fan_excess: [f64; 3],
    /// Σ P, for the error bound.
    pub(crate) determinant_magnitude: f64,
    /// Σ |D|, for the error bound.
    pub(crate) abs_six_volume: f64,
    pub(crate) triangles: usize,
}

impl VolumeSums {
    pub(crate) fn merge(&mut self, o: &VolumeSums) {
        self.six_volume.merge(&o.six_volume);
        for k in 0..3 {
            self.vector_area[k].merge(&o.vector_area[k]);
            self.vector_area_magnitude[k] += o.vector_area_magnitude[k];
            self.vector_area_fan_excess[k] += o.vector_area_fan_excess[k];
        }
        self.determinant_magnitude += o.determinant_magnitude;
        self.abs_six_volume += o.abs_six_volume;
        self.triangles += o.triangles;
    }

    /// Adds triangle (a, b, c) by its first corner relative to the reference point r,
    /// `a_r` = a − r, and its cross product (b − a)×(c − a) as [`cross_products`] gives
    /// it (`cross` = plus − minus, `magnitude` = |plus| + |minus|): D = a_r·cross and
    /// its magnitude P = |a_r|·magnitude (see the module docs).
    #[inline(always)]
    pub(crate) fn add_determinant(&mut self, a_r: Point, cross: Point, magnitude: Point) -> f64 {
        let d = dot(a_r, cross);
        let permanent =
            a_r[0].abs() * magnitude[0] + a_r[1].abs() * magnitude[1] + a_r[2].abs() * magnitude[2];
        self.six_volume.add(d);
        self.abs_six_volume += d.abs();
        self.determinant_magnitude += permanent;
        self.triangles += 1;
        d
    }

    /// Adds fan triangle (a, b, c) of a face: D (see [`Self::add_determinant`]); returns
    /// its cross product and magnitudes for the face's vector area, and D (which the
    /// moments weigh their terms by).
    #[inline(always)]
    pub(crate) fn add_fan_triangle(
        &mut self,
        r: Point,
        a: Point,
        b: Point,
        c: Point,
    ) -> (Point, Point, f64) {
        let (cross, magnitude) = cross_products(a, b, c);
        let d = self.add_determinant(sub(a, r), cross, magnitude);
        (cross, magnitude, d)
    }

    /// Adds a face's vector area (its fan's cross products summed plainly), their
    /// products' magnitudes, and its fan's length.
    #[inline(always)]
    pub(crate) fn add_vector_area(&mut self, vector_area: Point, magnitude: Point, fan: usize) {
        for k in 0..3 {
            self.vector_area[k].add(vector_area[k]);
            self.vector_area_magnitude[k] += magnitude[k];
            if fan > 1 {
                self.vector_area_fan_excess[k] += (fan - 1) as f64 * magnitude[k];
            }
        }
    }
}

/// Adds face `face` of `surface` triangle by triangle of its fan, each by `add` (which
/// returns its cross product and magnitudes), and returns what the face's vector area is
/// made of: the cross products summed plainly, their magnitudes, and the fan's length
/// (for [`VolumeSums::add_vector_area`]). The one loop over a polygon's fan, so that
/// [`crate::mass_properties`] and [`crate::volume`] sum it in the same order.
#[inline(always)]
pub(crate) fn add_face_fan<S: Surface + ?Sized>(
    surface: &S,
    face: usize,
    mut add: impl FnMut(Point, Point, Point) -> (Point, Point),
) -> (Point, Point, usize) {
    let mut vector_area = [0.0; 3];
    let mut magnitude = [0.0; 3];
    let mut fan = 0usize;
    surface.fan(face, |a, b, c| {
        let (cross, m) = add(a, b, c);
        for k in 0..3 {
            vector_area[k] += cross[k];
            magnitude[k] += m[k];
        }
        fan += 1;
    });
    (vector_area, magnitude, fan)
}

/// The cross product (b − a)×(c − a) as plus − minus of its components' two products,
/// and the products' magnitudes |plus| + |minus|: the same operations as the SIMD lanes
/// (`volume::VolumeLanes::add`).
#[inline(always)]
pub(crate) fn cross_products(a: Point, b: Point, c: Point) -> (Point, Point) {
    let (u, v) = (sub(b, a), sub(c, a));
    let plus = [u[1] * v[2], u[2] * v[0], u[0] * v[1]];
    let minus = [u[2] * v[1], u[0] * v[2], u[1] * v[0]];
    (
        [plus[0] - minus[0], plus[1] - minus[1], plus[2] - minus[2]],
        [
            plus[0].abs() + minus[0].abs(),
            plus[1].abs() + minus[1].abs(),
            plus[2].abs() + minus[2].abs(),
        ],
    )
}

/// How much wider than the bound of the sum about r the correction to the origin may
/// make the volume's bound, relative to the volume, before the exact sum is taken.
const LOOSE_BOUND: f64 = 1.0 / (1u64 << 42) as f64;

/// The signed volume and its bound from [`VolumeSums`] (see the module docs).
pub(crate) struct VolumeFinish {
    pub(crate) signed_volume: f64,
    pub(crate) volume_error_bound: f64,
    /// The signed volume about r, and its bound.
    pub(crate) about_r: f64,
    pub(crate) bound_about_r: f64,
    /// The bound is loose (see [`LOOSE_BOUND`]): the exact sum should replace it.
    pub(crate) loose: bool,
}

impl VolumeSums {
    /// `zero_vector_area`: the surface's vector area is known to be exactly zero
    /// ([`crate::Surface::vector_area_is_zero`]), so the volume about r is the volume about the
    /// origin and its bound the whole bound.
    pub(crate) fn finish(&self, faces: usize, r: Point, zero_vector_area: bool) -> VolumeFinish {
        let sums = self;
        let n = sums.triangles as f64;
        let six_volume = sums.six_volume.value();
        // About r: what the centroid and inertia are taken about.
        let about_r = six_volume / 6.0;
        let six_bound = gamma(8.0) * sums.determinant_magnitude
            + UNIT_ROUNDOFF * six_volume.abs()
            + gamma(n).powi(2) * sums.abs_six_volume;
        // (1 + γ(n + 8)) covers the rounding of the bound's own sums.
        let headroom = 1.0 + gamma(n + 8.0);
        let bound_about_r = six_bound * headroom / 6.0 + UNIT_ROUNDOFF * about_r.abs();
        if zero_vector_area {
            let (signed_volume, volume_error_bound) = (about_r, bound_about_r);
            return VolumeFinish {
                signed_volume,
                volume_error_bound,
                about_r,
                bound_about_r,
                loose: false,
            };
        }

        // To the origin: V_O = V_r + r·S/6, S = Σ (b − a) × (c − a) over the fan triangles.
        // Each cross product component is off by at most γ(4) of its two products'
        // magnitudes (two subtractions, a product, a difference); a face's fan of m
        // triangles, summed plainly, by γ(m − 1) more; the compensated sum over faces adds
        // u·|S| + γ(F)²·Σ|terms|. 2u·(m + 4) covers γ(m + 4) with room.
        let s = sums.vector_area.map(|x| x.value());
        let faces_f = faces as f64;
        let mut correction_bound = 0.0;
        for k in 0..3 {
            let weighted = 5.0 * sums.vector_area_magnitude[k] + sums.vector_area_fan_excess[k];
            let s_bound = 2.0 * UNIT_ROUNDOFF * weighted
                + UNIT_ROUNDOFF * s[k].abs()
                + 2.0 * gamma(faces_f).powi(2) * sums.vector_area_magnitude[k];
            // The dot product and division by 6 round by γ(4) of Σ|r_k S_k|.
            correction_bound += r[k].abs() * (s_bound + gamma(4.0) * s[k].abs());
        }
        let correction_bound = correction_bound * headroom / 6.0;
        let correction = dot(r, s) / 6.0;
        let (signed_volume, volume_error_bound) = if correction.abs() <= correction_bound {
            // Not distinguishable from 0 (a closed surface's S is 0): adding it would only
            // add its rounding. The value stays V_r; the bound covers the true correction.
            (about_r, bound_about_r + correction.abs() + correction_bound)
        } else {
            let v = about_r + correction;
            (v, bound_about_r + correction_bound + UNIT_ROUNDOFF * v.abs())
        };
        let loose = volume_error_bound - bound_about_r
            > bound_about_r.max(LOOSE_BOUND * signed_volume.abs());
        VolumeFinish { signed_volume, volume_error_bound, about_r, bound_about_r, loose }
    }
}

/// A chunk's volume sums as four interleaved sums: the chunk's `k`-th triangle (and for
/// the per-face sums its `k`-th face) goes to sum `k mod 4`, and the four are merged in
/// order at the chunk's end. This is the summation order of every path, scalar or SIMD
/// ([`crate::volume::VolumeLanes`]), so all give the same bits; the error bound is that of a
/// compensated sum cut into parts merged in order, as the chunks already are.
#[derive(Clone, Copy, Default)]
pub(crate) struct LaneSums(pub(crate) [VolumeSums; 4]);

impl LaneSums {
    /// The four sums merged in order.
    pub(crate) fn merged(&self) -> VolumeSums {
        let mut total = self.0[0];
        for lane in &self.0[1..] {
            total.merge(lane);
        }
        total
    }
}
