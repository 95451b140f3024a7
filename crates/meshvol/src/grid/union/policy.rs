//! Whether refinement pays: a sample of the open base columns is refined one level
//! first. Refinement helps where it can meet the tolerance without exact resolution,
//! or where it closes whole columns (every open cell's children settled), so that they
//! need no resolution. Where two surfaces cross or lie on each other in most open cells
//! (one shape meshed twice, bodies glued), every refined column stays open: each level
//! then costs about a quarter of the exact resolution and saves none of it.

use super::bounds::{Bodies, Cell};
use super::refine::{refine, Refined, MAX_DEPTH};
use crate::grid::GridError;
use crate::Surface;
use rayon::prelude::*;

/// One open base column in this many is refined as the sample.
pub(super) const SAMPLE_EVERY: usize = 8;

/// Refinement is worth it when at least this fraction of the sampled columns closes.
const CLOSES: f64 = 0.25;

/// The sample: every [`SAMPLE_EVERY`]-th column of `open_columns` refined one level
/// (`None` for the others, to be refined when refinement goes on), and whether
/// refinement pays: the whole open gap `gap`, shrunk [`MAX_DEPTH`] times by the
/// sample's ratio of children's gap to parents' (an optimistic guess: a cell's gap
/// shrinks less once its surfaces are settled to a curve), meets `target`, or the sample
/// closes at least [`CLOSES`] of its columns.
#[allow(clippy::type_complexity)]
pub(super) fn sample<S: Surface + ?Sized>(
    model: &Bodies<'_, S>,
    open_columns: &[usize],
    gap: f64,
    target: f64,
) -> Result<(Vec<Option<Vec<Refined>>>, bool), GridError> {
    let refined: Vec<Option<Result<Vec<Refined>, GridError>>> = open_columns
        .par_iter()
        .enumerate()
        .map(|(n, &c)| {
            (n % SAMPLE_EVERY == 0).then(|| {
                let cells = model.open_cells(c);
                cells
                    .iter()
                    .map(|cell| refine(&model.bodies, model.rule, &model.grid, cell))
                    .collect()
            })
        })
        .collect();
    let refined: Vec<Option<Vec<Refined>>> =
        refined.into_iter().map(Option::transpose).collect::<Result<_, _>>()?;
    // Fixed order sums over the sample: the same bits at any thread count.
    let (mut before, mut after, mut columns, mut closed) = (0.0, 0.0, 0usize, 0usize);
    for (n, column) in refined.iter().enumerate() {
        let Some(column) = column else { continue };
        let nz = model.grid.counts[2];
        for k in 0..nz {
            if let Cell::Open { lower, upper } = model.cell(open_columns[n] * nz + k) {
                before += upper - lower;
            }
        }
        let mut open = false;
        for r in column {
            for child in &r.open {
                after += child.upper - child.lower;
                open = true;
            }
        }
        columns += 1;
        closed += usize::from(!open);
    }
    let ratio = if before > 0.0 { after / before } else { 0.0 };
    let pays =
        gap * ratio.powi(MAX_DEPTH as i32) <= target || closed as f64 >= CLOSES * columns as f64;
    Ok((refined, pays))
}
