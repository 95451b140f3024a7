//! A uniform bin index over one column's footprint in plan (xy, base-grid units), for
//! the exact resolution: which triangles a vertical ray may cross, and which cutters a
//! piece's box may meet, without scanning the whole column.
//!
//! An item is filed in every bin its closed xy box meets. The bin of a coordinate is
//! `clamp(⌊(v − origin) · side⌋, 0, side − 1)`, a monotone function of `v` (rounded
//! subtraction and product are monotone), so an item whose closed box holds a point is
//! filed in that point's bin, and one whose box meets a query box in a bin of the query's
//! range: lookups never miss an item, points and boxes slightly outside the footprint
//! included (they fall in the border bins).

use crate::Point;

/// Bins to a side at most.
const MAX_SIDE: usize = 128;

/// Bins of one column's plan; item `t` of bin `b` is `items[offsets[b] + t]`.
pub(super) struct PlanIndex {
    origin: [f64; 2],
    side: usize,
    offsets: Vec<u32>,
    items: Vec<u32>,
    /// Each item's first bin along x and y.
    first: Vec<[u16; 2]>,
}

/// An item's closed box in plan: `[x_lo, x_hi, y_lo, y_hi]`.
pub(super) type PlanBox = [f64; 4];

/// The plan box of a triangle.
pub(super) fn plan_box(t: &[Point; 3]) -> PlanBox {
    let (mut b, mut c) = ([t[0][0], t[0][0]], [t[0][1], t[0][1]]);
    for v in &t[1..] {
        b = [b[0].min(v[0]), b[1].max(v[0])];
        c = [c[0].min(v[1]), c[1].max(v[1])];
    }
    [b[0], b[1], c[0], c[1]]
}

impl PlanIndex {
    /// Files `boxes` (item i = `boxes[i]`) over the unit square at `origin`, about
    /// `per_bin` items to a bin and at most [`MAX_SIDE`]² bins.
    pub fn new(origin: [f64; 2], boxes: &[PlanBox], per_bin: usize) -> PlanIndex {
        let bins = (boxes.len() / per_bin.max(1)) as f64;
        let side = bins.sqrt().ceil().clamp(1.0, MAX_SIDE as f64) as usize;
        let mut offsets = vec![0u32; side * side + 1];
        let mut shape =
            PlanIndex { origin, side, offsets: Vec::new(), items: Vec::new(), first: Vec::new() };
        shape.first =
            boxes.iter().map(|b| [0, 2].map(|a| shape.slot(b[a], a / 2) as u16)).collect();
        for b in boxes {
            shape.each_bin(b, |bin| offsets[bin + 1] += 1);
        }
        for k in 0..side * side {
            offsets[k + 1] += offsets[k];
        }
        let mut fill = offsets.clone();
        let mut items = vec![0u32; offsets[side * side] as usize];
        for (i, b) in boxes.iter().enumerate() {
            shape.each_bin(b, |bin| {
                items[fill[bin] as usize] = i as u32;
                fill[bin] += 1;
            });
        }
        PlanIndex { offsets, items, ..shape }
    }

    /// The bin of coordinate `v` along axis `a` (module docs; NaN goes to bin 0).
    fn slot(&self, v: f64, a: usize) -> usize {
        let t = ((v - self.origin[a]) * self.side as f64).floor();
        t.max(0.0).min((self.side - 1) as f64) as usize
    }

    /// Calls `f(bin)` for every bin the closed box `b` meets, row by row.
    fn each_bin(&self, b: &PlanBox, mut f: impl FnMut(usize)) {
        let (x0, x1) = (self.slot(b[0], 0), self.slot(b[1], 0));
        let (y0, y1) = (self.slot(b[2], 1), self.slot(b[3], 1));
        for x in x0..=x1 {
            for y in y0..=y1 {
                f(x * self.side + y);
            }
        }
    }

    fn bin(&self, bin: usize) -> &[u32] {
        &self.items[self.offsets[bin] as usize..self.offsets[bin + 1] as usize]
    }

    /// The items whose box may hold the point `(x, y)`: one bin, in item order.
    pub fn at(&self, x: f64, y: f64) -> &[u32] {
        self.bin(self.slot(x, 0) * self.side + self.slot(y, 1))
    }

    /// Replaces `out` with the items whose box may meet the closed box `b`, each once
    /// (from the first bin that both boxes meet), bin by bin.
    pub fn meeting(&self, b: &PlanBox, out: &mut Vec<u32>) {
        out.clear();
        let (x0, y0) = (self.slot(b[0], 0), self.slot(b[2], 1));
        self.each_bin(b, |bin| {
            let (x, y) = (bin / self.side, bin % self.side);
            for &item in self.bin(bin) {
                let [fx, fy] = self.first[item as usize];
                if x == x0.max(fx as usize) && y == y0.max(fy as usize) {
                    out.push(item);
                }
            }
        });
    }
}
