//! How many cells are empty, partial or full ([`occupancy`]): a leaf below mod.rs.

/// How many cells are empty, partial or full.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Occupancy {
    pub empty: usize,
    pub partial: usize,
    pub full: usize,
}

/// Cells whose volume is within this fraction of 0 or of the cell's volume count as
/// empty or full: far above the rounding of the column sums (about 10⁻¹³ of a cell on
/// a 512³ grid), far below any solid a user would model.
pub const OCCUPANCY_TOLERANCE: f64 = 1e-9;

/// Counts empty, partial and full cells of a cell array (by |volume|, so that inward
/// surfaces count the same), with [`OCCUPANCY_TOLERANCE`].
pub fn occupancy(volumes: &[f64], cell_volume: f64) -> Occupancy {
    let tolerance = OCCUPANCY_TOLERANCE * cell_volume;
    let mut o = Occupancy::default();
    for v in volumes {
        let v = v.abs();
        if v <= tolerance {
            o.empty += 1;
        } else if v >= cell_volume - tolerance {
            o.full += 1;
        } else {
            o.partial += 1;
        }
    }
    o
}
