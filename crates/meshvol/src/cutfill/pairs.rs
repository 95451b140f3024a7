//! Which triangles overlap in plan: a uniform grid of buckets over a box, each triangle
//! listed in every bucket its bounding box touches (a counting sort, [`Buckets`]). Two
//! triangles whose boxes overlap share the buckets of the boxes' intersection; the pair
//! is taken in one of them only, the bucket of the intersection's lower-left corner
//! (the larger of the two boxes' first bucket along each axis), so no pair is seen twice
//! and no set of pairs is kept. About one bucket per triangle keeps the lists short:
//! the work is linear in the triangles, the buckets they touch, and the pairs found.

use super::terrain::Facet;
use crate::buckets::Buckets;
use std::ops::Range;

/// Most buckets: keys are u32, and a bucket per triangle is plenty.
const MAX_BUCKETS: usize = 1 << 26;

/// A box in plan: [min, max].
pub(crate) type PlanBox = [[f64; 2]; 2];

/// The box of a triangle.
pub(crate) fn facet_box(f: &Facet) -> PlanBox {
    let [a, b, c] = f.xy;
    [
        [a[0].min(b[0]).min(c[0]), a[1].min(b[1]).min(c[1])],
        [a[0].max(b[0]).max(c[0]), a[1].max(b[1]).max(c[1])],
    ]
}

/// The box holding both.
pub(crate) fn box_union(a: &PlanBox, b: &PlanBox) -> PlanBox {
    [[a[0][0].min(b[0][0]), a[0][1].min(b[0][1])], [a[1][0].max(b[1][0]), a[1][1].max(b[1][1])]]
}

/// Whether two boxes overlap (touching counts).
pub(crate) fn boxes_overlap(a: &PlanBox, b: &PlanBox) -> bool {
    a[0][0] <= b[1][0] && b[0][0] <= a[1][0] && a[0][1] <= b[1][1] && b[0][1] <= a[1][1]
}

/// A grid of buckets over a box. Coordinates are halved before they are compared, so
/// that a box wider than f64 (from −1e308 to 1e308) still has a width.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BucketGrid {
    half_origin: [f64; 2],
    half_size: [f64; 2],
    counts: [usize; 2],
}

impl BucketGrid {
    /// About `items` square-ish buckets over `bounds` (which must have a positive
    /// extent along both axes).
    pub fn new(bounds: PlanBox, items: usize) -> BucketGrid {
        let half_origin = bounds[0].map(|x| 0.5 * x);
        let [w, h] = [0, 1].map(|a| 0.5 * bounds[1][a] - half_origin[a]);
        let target = items.clamp(1, MAX_BUCKETS) as f64;
        let nx = (target * (w / h)).sqrt().round().clamp(1.0, target);
        let ny = (target / nx).ceil().clamp(1.0, target);
        let half_size = [w / nx, h / ny];
        // A box too thin for its buckets' sizes to be numbers is one bucket.
        if !(half_size.iter().all(|s| s.is_finite() && *s > 0.0)) {
            return BucketGrid { half_origin, half_size: [f64::INFINITY; 2], counts: [1, 1] };
        }
        BucketGrid { half_origin, half_size, counts: [nx as usize, ny as usize] }
    }

    pub fn len(&self) -> usize {
        self.counts[0] * self.counts[1]
    }

    /// The bucket column or row of coordinate `x` along `axis`, clamped to the grid.
    fn index(&self, axis: usize, x: f64) -> usize {
        let i = ((0.5 * x - self.half_origin[axis]) / self.half_size[axis]).floor();
        if i.is_nan() {
            return 0;
        }
        (i.max(0.0) as usize).min(self.counts[axis] - 1)
    }

    /// The first and last bucket (column, row) a box touches.
    fn span(&self, b: &PlanBox) -> [[usize; 2]; 2] {
        [0, 1].map(|corner| [0, 1].map(|axis| self.index(axis, b[corner][axis])))
    }

    /// The facets of `facets[range]` inside `within` listed by bucket (as indices into
    /// `facets`).
    pub fn buckets(&self, facets: &[Facet], within: &PlanBox) -> Buckets<u32> {
        let pairs = |range: Range<usize>| {
            range.flat_map(move |f| {
                let b = facet_box(&facets[f]);
                let span = boxes_overlap(&b, within).then(|| self.span(&b));
                span.into_iter().flat_map(move |[lo, hi]| {
                    (lo[0]..=hi[0]).flat_map(move |i| {
                        (lo[1]..=hi[1]).map(move |j| ((i * self.counts[1] + j) as u32, f as u32))
                    })
                })
            })
        };
        Buckets::new(self.len(), facets.len(), pairs)
    }

    /// Whether bucket `bucket` is the one where the pair of boxes `a` and `b` is taken.
    pub fn owns(&self, bucket: usize, a: &PlanBox, b: &PlanBox) -> bool {
        let first =
            [0, 1].map(|axis| self.index(axis, a[0][axis]).max(self.index(axis, b[0][axis])));
        bucket == first[0] * self.counts[1] + first[1]
    }
}
