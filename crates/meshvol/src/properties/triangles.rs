//! One chunk of [`crate::mass_properties`] over a surface whose every face is one
//! triangle, four triangles a SIMD step, with the bits of the scalar loop.

use super::bounds::Bounds;
use super::partial::{moment_terms, Partial, BLOCK_FACES};
use crate::accumulate::CompensatedSum;
use crate::lanes::{dispatch, Lanes, OnLanes};
use crate::vector::norm;
use crate::volume::Corners;
use crate::Point;

/// Where [`triangles_partial`] reads a surface whose every face is one triangle.
pub(super) trait Triangles {
    /// Every coordinate is a number (not NaN): the bounds' minima and maxima can skip
    /// their NaN tests.
    const NUMBERS: bool;

    /// Face `face`'s corners.
    fn corners(&self, face: usize) -> [Point; 3];

    /// Whether faces `range` name their corners scattered through memory, so that the
    /// loop should prefetch them ([`crate::volume::scattered`]).
    #[inline(always)]
    fn scattered(&self, _range: std::ops::Range<usize>) -> bool {
        false
    }

    /// Asks the processor to start loading the corners of faces `ahead..ahead + 4`
    /// (those that exist; a hint).
    #[inline(always)]
    fn prefetch(&self, _ahead: usize) {}

    /// Faces `face..face + 4`'s corners as lanes, lane j face `face + j`'s.
    #[inline(always)]
    fn four<L: Lanes>(&self, face: usize) -> Corners<L> {
        let mut p = [[[0.0; 4]; 3]; 3];
        for lane in 0..4 {
            for (corner, q) in self.corners(face + lane).into_iter().enumerate() {
                for k in 0..3 {
                    p[corner][k][lane] = q[k];
                }
            }
        }
        crate::volume::corners::<L>(&p)
    }
}

/// An indexed triangle mesh (a surface's [`crate::Surface::indexed_triangles`], such as a
/// [`crate::Mesh`] of triangles): four triangles' corners are gathered into lanes from
/// the positions ([`Lanes::gather`]).
pub(super) struct Indexed<'a> {
    pub(super) positions: &'a [Point],
    pub(super) triangles: &'a [[u32; 3]],
}

impl Triangles for Indexed<'_> {
    // Arrays behind a `Surface` hold finite coordinates (its contract; a `Mesh`
    // validates them when built).
    const NUMBERS: bool = true;

    #[inline(always)]
    fn corners(&self, face: usize) -> [Point; 3] {
        self.triangles[face].map(|i| self.positions[i as usize])
    }

    #[inline(always)]
    fn scattered(&self, range: std::ops::Range<usize>) -> bool {
        crate::volume::scattered(&self.triangles[range])
    }

    #[inline(always)]
    fn prefetch(&self, ahead: usize) {
        let at = |i: u32| &self.positions[i as usize];
        crate::volume::prefetch_corners(self.triangles.get(ahead..ahead + 4), at);
    }

    #[inline(always)]
    fn four<L: Lanes>(&self, face: usize) -> Corners<L> {
        let t = &self.triangles[face..face + 4];
        let at = |i: u32| &self.positions[i as usize];
        [
            L::gather([at(t[0][0]), at(t[1][0]), at(t[2][0]), at(t[3][0])]),
            L::gather([at(t[0][1]), at(t[1][1]), at(t[2][1]), at(t[3][1])]),
            L::gather([at(t[0][2]), at(t[1][2]), at(t[2][2]), at(t[3][2])]),
        ]
    }
}

/// Any other surface of triangles (a binary STL read in place), face by face.
pub(super) struct EachTriangle<F>(pub(super) F);

impl<F: Fn(usize) -> [Point; 3]> Triangles for EachTriangle<F> {
    const NUMBERS: bool = false;

    #[inline(always)]
    fn corners(&self, face: usize) -> [Point; 3] {
        (self.0)(face)
    }
}

/// One chunk of [`crate::mass_properties`] over a surface whose every face is one triangle
/// (an indexed triangle mesh, a validated [`crate::Mesh`]; a binary STL read in
/// place), four triangles a SIMD step: every per-triangle
/// quantity of the scalar loop (the same IEEE operations, lane by lane), and every sum
/// too, lane j holding the chunk's j-th interleaved sum (`volume_sums::LaneSums`): the same
/// bits as the scalar loop, which the tests compare (`tests/volume.rs`). The bounds are
/// lane-wise minima and maxima, their zeros (whose sign depends on the order) redone
/// in order.
pub(super) fn triangles_partial<T: Triangles>(
    corners: &T,
    range: std::ops::Range<usize>,
    r: Point,
) -> Partial {
    dispatch(TrianglesPartial { corners, range, r })
}

/// [`triangles_partial_in`]'s arguments, for the lanes [`dispatch`] picks.
struct TrianglesPartial<'a, T> {
    corners: &'a T,
    range: std::ops::Range<usize>,
    r: Point,
}

// Not derived: `T` need not be Clone for its reference to be.
impl<T> Clone for TrianglesPartial<'_, T> {
    fn clone(&self) -> Self {
        TrianglesPartial { corners: self.corners, range: self.range.clone(), r: self.r }
    }
}

impl<T: Triangles> OnLanes for TrianglesPartial<'_, T> {
    type Output = Partial;
    #[inline(always)]
    fn run<L: Lanes>(self) -> Partial {
        triangles_partial_in::<L, T>(self.corners, self.range, self.r)
    }
}

#[inline(always)]
fn triangles_partial_in<L: Lanes, T: Triangles>(
    triangles: &T,
    range: std::ops::Range<usize>,
    r: Point,
) -> Partial {
    use crate::volume::{add_compensated, VolumeLanes};
    let zero = L::ZERO;
    let first = range.start;
    let mut bounds = Bounds::of(r);
    // The volume's sums in `VolumeLanes`; the block's ten plain sums (first and second
    // moments, double area) and their compensated sums, one triangle a lane likewise.
    let mut lanes = VolumeLanes::<L>::new(r);
    let mut block = [zero; 10];
    let (mut sum, mut compensation) = ([zero; 10], [zero; 10]);
    // The bounds lane by lane; see below for their signed zeros.
    let rl = [L::splat(r[0]), L::splat(r[1]), L::splat(r[2])];
    let (mut low, mut high) = (rl, rl);
    let groups_end = first + range.len() / 4 * 4;
    let mut face = first;
    // Block by block: the inner loop holds the running sums in registers, the outer one
    // the compensated sums, which it touches once a block.
    let ends_block = |next: usize| (next - 1) % BLOCK_FACES == BLOCK_FACES - 1;
    let prefetch = triangles.scattered(range.clone());
    while face < groups_end {
        loop {
            if prefetch {
                triangles.prefetch(face + crate::volume::PREFETCH_TRIANGLES);
            }
            let corners = triangles.four::<L>(face);
            let [[ax, ay, az], [bx, by, bz], [cx, cy, cz]] = corners;
            for (k, [x, y, z]) in [[ax, bx, cx], [ay, by, cy], [az, bz, cz]].into_iter().enumerate()
            {
                if T::NUMBERS {
                    low[k] = low[k].min_of_numbers(x).min_of_numbers(y).min_of_numbers(z);
                    high[k] = high[k].max_of_numbers(x).max_of_numbers(y).max_of_numbers(z);
                } else {
                    low[k] = low[k].min(x).min(y).min(z);
                    high[k] = high[k].max(x).max(y).max(z);
                }
            }
            let (area, d, a) = lanes.add(corners);
            let (b, c) =
                ([bx - rl[0], by - rl[1], bz - rl[2]], [cx - rl[0], cy - rl[1], cz - rl[2]]);
            // The moments' terms and the double area, as `Partial::add_triangle`.
            for (sum, t) in block.iter_mut().zip(moment_terms(a, b, c)) {
                *sum += d * t;
            }
            block[9] += (area[0] * area[0] + area[1] * area[1] + area[2] * area[2]).sqrt();
            face += 4;
            if face == groups_end || ends_block(face) {
                break;
            }
        }
        // The group's last face ended a block: `Partial::flush_block`, lane by lane.
        if ends_block(face) {
            for k in 0..10 {
                add_compensated(&mut sum[k], &mut compensation[k], block[k]);
            }
            block = [zero; 10];
        }
    }
    let volume = lanes.lanes();
    let (sum, compensation, block) = (
        sum.map(|x| x.to_array()),
        compensation.map(|x| x.to_array()),
        block.map(|x| x.to_array()),
    );
    let mut parts: [Partial; 4] = std::array::from_fn(|j| {
        let compensated = |k: usize| CompensatedSum::from_parts(sum[k][j], compensation[k][j]);
        Partial {
            volume: volume.0[j],
            first: [0, 1, 2].map(compensated),
            second: [3, 4, 5, 6, 7, 8].map(compensated),
            double_area: compensated(9),
            block: block.map(|b| b[j]),
            bounds: None,
        }
    });
    for k in 0..3 {
        let pick = |lanes: L, better: fn(f64, f64) -> bool| {
            lanes.to_array().into_iter().fold(r[k], |m, x| if better(x, m) { x } else { m })
        };
        bounds.min[k] = pick(low[k], |x, m| x < m);
        bounds.max[k] = pick(high[k], |x, m| x > m);
    }
    // The last few triangles as the scalar loop reads them; the remainder starts at a
    // multiple of 4 from the chunk's start, so at lane 0.
    for lane in 0..range.len() % 4 {
        let [a, b, c] = triangles.corners(face);
        bounds.include(a);
        bounds.include(b);
        bounds.include(c);
        let part = &mut parts[lane];
        let (cross, magnitude) = part.add_triangle(r, a, b, c);
        // A face's fan sum starts at 0.0 (`0.0 + x` turns −0 into +0).
        let vector_area = cross.map(|x| 0.0 + x);
        part.block[9] += norm(vector_area);
        part.volume.add_vector_area(vector_area, magnitude, 1);
        if face % BLOCK_FACES == BLOCK_FACES - 1 {
            parts.iter_mut().for_each(Partial::flush_block);
        }
        face += 1;
    }
    // `Bounds::include` keeps the first of equal extremes, so its result has the same
    // bits in any order except for a zero extreme (−0.0 or +0.0, whichever came
    // first). r comes first: a zero extreme is r's when r is at zero on that axis (a
    // part standing on z = 0 whose first vertex is there); otherwise recompute it in
    // the scalar loop's order (r, then each triangle's corners).
    for k in 0..3 {
        let unsure = |extreme: f64| extreme == 0.0 && r[k] != 0.0;
        if bounds.min[k] == 0.0 && r[k] == 0.0 {
            bounds.min[k] = r[k];
        }
        if bounds.max[k] == 0.0 && r[k] == 0.0 {
            bounds.max[k] = r[k];
        }
        if unsure(bounds.min[k]) || unsure(bounds.max[k]) {
            let (mut low, mut high) = (r[k], r[k]);
            for x in range.clone().flat_map(|f| triangles.corners(f).map(|p| p[k])) {
                low = if x < low { x } else { low };
                high = if x > high { x } else { high };
            }
            if bounds.min[k] == 0.0 {
                bounds.min[k] = low;
            }
            if bounds.max[k] == 0.0 {
                bounds.max[k] = high;
            }
        }
    }
    Partial::merged(parts, bounds)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::every_copy;
    use crate::test_rng::XorShift;

    /// The baseline lanes (`wide`, what a CPU without AVX2 runs) give the bits of the
    /// AVX2 and AVX-512 copies (those this CPU has) and of the dispatched one, blocks,
    /// bounds' signed zeros and remainders included.
    #[test]
    fn baseline_and_dispatched_lanes_agree() {
        let mut rng = XorShift::new(0x9e37_79b9_7f4a_7c15);
        // Some coordinates exactly ±0, for the bounds' zeros.
        let positions: Vec<Point> = (0..20_000)
            .map(|_| {
                [0; 3].map(|_| match rng.below(5) {
                    0 => 0.0,
                    1 => -0.0,
                    _ => (rng.unit() - 0.5) * 2f64.powi(rng.below(30) as i32 - 15),
                })
            })
            .collect();
        // Ids among the first 300 vertices, and last among all 20,000: scattered, so
        // that the indexed loop prefetches.
        let sizes = [1, 5, 8, 67, BLOCK_FACES + 3, 3 * BLOCK_FACES + 9, 3 * BLOCK_FACES + 9];
        for (n, ids) in sizes.into_iter().zip([300, 300, 300, 300, 300, 300, 20_000]) {
            let triangles: Vec<[u32; 3]> =
                (0..n).map(|_| [0; 3].map(|_| rng.below(ids) as u32)).collect();
            let r = positions[triangles[0][0] as usize];
            let corners = EachTriangle(|f: usize| triangles[f].map(|i: u32| positions[i as usize]));
            let indexed = Indexed { positions: &positions, triangles: &triangles };
            if n >= 64 {
                assert_eq!(indexed.scattered(0..n), ids > 300, "{n} triangles");
            }
            let mut copies = every_copy(TrianglesPartial { corners: &corners, range: 0..n, r });
            let baseline = copies.remove(0);
            copies.extend(every_copy(TrianglesPartial { corners: &indexed, range: 0..n, r }));
            copies.push(triangles_partial(&corners, 0..n, r));
            copies.push(triangles_partial(&indexed, 0..n, r));
            for copy in copies {
                assert_eq!(format!("{baseline:?}"), format!("{copy:?}"), "{n} triangles");
            }
        }
    }
}
