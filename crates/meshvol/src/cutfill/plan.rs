//! The plan view every stage of cut and fill reads: a terrain's triangle in plan
//! ([`Facet`]) and boxes in plan.

/// One triangle of a terrain: its corners in plan, counter-clockwise, their heights,
/// and the face it comes from.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Facet {
    pub xy: [[f64; 2]; 3],
    pub z: [f64; 3],
    pub face: usize,
}

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
