//! `grid`: Σ of the cells over any grid that encloses the solid is its volume; cells of
//! a grid moved with the solid hold what they held (times s³), the cell (i, j, k) going
//! where the axis permutation and sign flips send it.

use crate::solids::catalogue;
use crate::transform::{transforms, Transform};
use crate::{assert_near, bounds, checked};
use meshvol::grid::{cell_volumes, Grid};
use meshvol::mass_properties;
use proptest::prelude::*;

/// A dyadic grid of `counts` cells enclosing [min, max] with a margin of at least
/// `margin` (so that its cell walls move exactly with the solid).
fn enclosing(
    min: [f64; 3],
    max: [f64; 3],
    counts: [usize; 3],
    margin: f64,
) -> ([f64; 3], [f64; 3]) {
    let origin = min.map(|x| (x * 4.0).floor() / 4.0 - margin);
    let cell = [0, 1, 2].map(|a| {
        let needed = (max[a] + margin - origin[a]) / counts[a] as f64;
        2f64.powi(needed.log2().ceil() as i32)
    });
    (origin, cell)
}

fn cells_follow(t: &Transform, counts: [usize; 3], margin: f64) {
    let s3 = t.scale.powi(3);
    for solid in catalogue() {
        let name = solid.name;
        let (before, after) = (solid.shape.mesh(), t.apply(&solid.shape).mesh());
        let (c0, c1) = (checked(&before), checked(&after));
        let (min, max) = bounds(&solid.shape.positions);
        let (origin, cell) = enclosing(min, max, counts, margin);
        let grid0 = Grid::new(origin, cell, counts).unwrap();
        let (o1, h1, n1) = t.grid(origin, cell, counts);
        let grid1 = Grid::new(o1, h1, n1).unwrap();
        let v0 = cell_volumes(&c0.solid(&before), &grid0).unwrap();
        let v1 = cell_volumes(&c1.solid(&after), &grid1).unwrap();
        let volume = solid.volume.unwrap_or(mass_properties(&c0.solid(&before)).signed_volume);
        if solid.solid {
            assert_near(&format!("{name}: Σ grid"), v0.iter().sum(), volume, volume);
            let total: f64 = v1.iter().sum();
            assert_near(&format!("{name}: Σ grid under {t:?}"), total, s3 * volume, s3 * volume);
        }
        for i in 0..counts[0] {
            for j in 0..counts[1] {
                for k in 0..counts[2] {
                    let (a, b) = (
                        v0[grid0.index([i, j, k])],
                        v1[grid1.index(t.cell_index([i, j, k], counts))],
                    );
                    let what = format!("{name}: cell ({i}, {j}, {k}) of {counts:?} under {t:?}");
                    assert_near(&what, b, s3 * a, s3 * volume);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(crate::cases(16))]

    #[test]
    fn cells_move_with_the_solid(
        t in transforms(),
        counts in prop::array::uniform3(1usize..=5),
        margin in prop::sample::select(vec![0.25, 0.5, 3.0]),
    ) {
        cells_follow(&t, counts, margin);
    }
}
