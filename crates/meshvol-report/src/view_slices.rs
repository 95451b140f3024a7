//! What the page shows under its section slider (`meshvol serve`, `check --html`): the
//! checked solid cut at [`SLICE_LEVELS`] heights, each cut as `meshvol section --plane
//! z=H` reports it, with its outline to draw; and a grid of cell volume fractions over
//! the solid, as `meshvol grid --cells NX,NY,NZ` computes it, whose z layers hold the
//! levels one each.
//!
//! The levels are the mid-planes of the grid's layers: with z0, z1 the solid's bounds
//! and h = (z1 − z0) / 64, level k is z0 + (k + ½)·h, so no level lies on a flat face at
//! the bottom or top, and level k lies in layer k (found, not assumed, by the rule of
//! `grid --slice z=Z`: [`crate::grid::layer_holding`]). The grid has 64 layers along z
//! and at most 64 cells along x and y, the longer of the two with 64, the other as many
//! as keep the cells nearest square in plan.
//!
//! The payload is bounded whatever the mesh: 64 section reports, outlines of at most
//! [`MAX_OUTLINE_POINTS`] points a level, and at most 64³ = 262,144 cells, each an
//! integer round(255 × fraction) (a few bytes of JSON each; about 1 MiB at most).

use crate::grid::{layer_holding, reported_summary, GridAsked, GridReport, GridRun};
use crate::quantities::Quantities;
use crate::reported_cells;
use crate::section::{section, SectionReport};
use crate::subject::{input_warnings, Subject};
use crate::units::{Scale, UnitOptions};
use meshvol::grid::{cell_volumes, Grid};
use meshvol::polygon::{Point2, Polygon};
use meshvol::section::Plane;
use meshvol::{mass_properties, Surface};
use serde::Serialize;
use std::time::Instant;

/// Section levels, and grid layers along z.
pub const SLICE_LEVELS: usize = 64;

/// The most cells along x or y.
pub const MAX_PLAN_CELLS: usize = 64;

/// The most outline points kept for one level (the outline is for drawing only; the
/// numbers are the section report's, from the whole outline).
pub const MAX_OUTLINE_POINTS: usize = 1024;

/// The sections and the grid under the page's slider. Levels and outlines are in the
/// file's coordinates (as the view's positions); the reports are in the units asked for.
#[derive(Clone, Debug, Serialize)]
pub struct Slices {
    /// The section levels along z, bottom to top.
    pub levels: Vec<f64>,
    /// At each level, `meshvol section --plane z=LEVEL --json`'s report (with `--units`).
    pub sections: Vec<SectionReport>,
    /// At each level, the section's rings (exteriors and holes) as flat `x, y, x, y, ...`
    /// (float32), every s-th point kept where a level has more than
    /// [`MAX_OUTLINE_POINTS`]; rings left with fewer than 3 points are dropped.
    pub outlines: Vec<Vec<Vec<f32>>>,
    /// `meshvol grid --cells NX,NY,NZ --json`'s report for the grid (with `--units` and
    /// `--density`).
    pub grid: GridReport,
    /// The grid's origin and cell size in the file's coordinates (the report's `bounds`
    /// and `cell_size` are in the units asked for): where the outlines lie on it.
    pub origin: [f64; 3],
    pub cell: [f64; 3],
    /// At each level, the grid layer (k, from 0) that holds it.
    pub layers: Vec<usize>,
    /// Each cell's round(255 × volume / cell volume), in C order (i, j, k: k fastest) as
    /// `grid --out cells.npy` writes the cells: 0 empty, 255 full; above 255 where
    /// overlapping shells count twice, below 0 where the surface winds inward.
    pub fractions: Vec<i32>,
}

/// The slices of `subject`'s solid, or `None` where no grid spans it (the solid is flat
/// along an axis, or its cells' volume would overflow). `units` are the page's options: the grid's report takes them all,
/// the sections their `--units` only (the page's density is per volume).
pub fn slices<S: Surface>(
    subject: &Subject<'_, S>,
    units: &UnitOptions,
) -> Result<Option<Slices>, String> {
    let measured = subject.measured();
    let mp = mass_properties(&measured);
    let Some(bounds) = mp.bounds else { return Ok(None) };
    let Some(counts) = grid_counts(bounds.min, bounds.max) else { return Ok(None) };
    let Ok(grid) = Grid::from_bounds(bounds.min, bounds.max, counts) else { return Ok(None) };
    let start = Instant::now();
    let volumes = cell_volumes(&measured, &grid).map_err(|e| e.to_string())?;
    let name = subject.source.name().to_string();
    let (scale, unit_warnings) = Scale::resolve_all(units, &[(&name, subject.source.unit)])?;
    let warnings = input_warnings(std::slice::from_ref(subject)).into_iter().chain(unit_warnings);
    let mut run = GridRun::new(
        vec![name.clone()],
        "mesh",
        mp.signed_volume,
        GridAsked::default(),
        &scale,
        warnings,
    );
    run.seconds = start.elapsed().as_secs_f64();
    let full = grid.cell_volume();
    let fractions = volumes.iter().map(|v| (255.0 * (v / full)).round() as i32).collect();
    // The cells converted as the command's grid converts them: the same total.
    let mut reported_volumes = volumes.clone();
    reported_cells::volumes(&scale, &mut reported_volumes);
    let reported = reported_cells::grid(&scale, &grid)?;
    let report = reported_summary(&scale, &reported, &reported_volumes, run);
    let (z0, h) = (grid.origin[2], grid.cell[2]);
    let levels: Vec<f64> = (0..SLICE_LEVELS).map(|k| z0 + (k as f64 + 0.5) * h).collect();
    let layers = levels.iter().map(|&z| layer_holding(&grid, 2, z).unwrap_or(0)).collect();
    let lengths = UnitOptions { units: units.units, density: None };
    let mut sections = Vec::with_capacity(SLICE_LEVELS);
    let mut outlines = Vec::with_capacity(SLICE_LEVELS);
    for &z in &levels {
        let plane = Plane::axis(2, z).map_err(|e| e.to_string())?;
        let (report, polygons) = section(subject, &plane);
        sections.push(report.in_units(&lengths, subject.source.unit)?);
        outlines.push(outline(&polygons));
    }
    let (origin, cell) = (grid.origin, grid.cell);
    Ok(Some(Slices { levels, sections, outlines, grid: report, origin, cell, layers, fractions }))
}

/// The grid's cells over the box `min`–`max`: [`SLICE_LEVELS`] along z; along x and y,
/// [`MAX_PLAN_CELLS`] on the longer side and the other in proportion (at least 1).
/// `None` where the box is flat along an axis.
fn grid_counts(min: [f64; 3], max: [f64; 3]) -> Option<[usize; 3]> {
    let extent = [0, 1, 2].map(|a| max[a] - min[a]);
    if extent.iter().any(|&e| !(e > 0.0 && e.is_finite())) {
        return None;
    }
    let side = extent[0].max(extent[1]) / MAX_PLAN_CELLS as f64;
    let plan = |e: f64| ((e / side).round() as usize).clamp(1, MAX_PLAN_CELLS);
    Some([plan(extent[0]), plan(extent[1]), SLICE_LEVELS])
}

/// The rings of `polygons`, thinned to at most [`MAX_OUTLINE_POINTS`] points: every
/// s-th point of each ring, the smallest s that keeps the bound.
fn outline(polygons: &[Polygon]) -> Vec<Vec<f32>> {
    let rings: Vec<&Vec<Point2>> =
        polygons.iter().flat_map(|p| std::iter::once(&p.exterior).chain(&p.holes)).collect();
    let kept = |ring: &[Point2], s: usize| match ring.len().div_ceil(s) {
        n if n >= 3 => n,
        _ => 0,
    };
    let total: usize = rings.iter().map(|r| r.len()).sum();
    let mut s = total.div_ceil(MAX_OUTLINE_POINTS).max(1);
    while rings.iter().map(|r| kept(r, s)).sum::<usize>() > MAX_OUTLINE_POINTS {
        s += 1;
    }
    rings
        .iter()
        .filter(|r| kept(r, s) > 0)
        .map(|r| r.iter().step_by(s).flat_map(|p| [p[0] as f32, p[1] as f32]).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::subject::Source;
    use meshvol::shapes::cuboid;
    use meshvol::topology::{check, CheckOptions};

    /// A 4 × 2 × 8 box on a 64 × 32 × 64 grid: cells of 1/16 × 1/16 × 1/8, all inside.
    /// Every fraction is 1 (255), each section a 4 × 2 rectangle (area 8, perimeter 12),
    /// and level k the middle of layer k.
    #[test]
    fn a_box_is_full_cells_and_rectangles_at_every_level() {
        let cube = cuboid([1.0, -1.0, 0.0], [5.0, 1.0, 8.0]);
        let c = check(&cube, &CheckOptions::default()).unwrap();
        let source = Source::arrays(8);
        let subject = Subject { source: &source, surface: &cube, check: Some(&c) };
        let s = slices(&subject, &UnitOptions::default()).unwrap().unwrap();
        assert_eq!(s.grid.cells.cells, [64, 32, 64]);
        assert_eq!(s.grid.cells.cell_size, [1.0 / 16.0, 1.0 / 16.0, 0.125]);
        assert_eq!(s.fractions.len(), 64 * 32 * 64);
        assert!(s.fractions.iter().all(|&f| f == 255));
        assert_eq!(s.grid.cells.total, 64.0);
        for k in 0..SLICE_LEVELS {
            assert_eq!(s.levels[k], 0.125 * (k as f64 + 0.5));
            assert_eq!(s.layers[k], k);
            assert_eq!((s.sections[k].area, s.sections[k].perimeter), (8.0, 12.0));
            assert_eq!(s.sections[k].plane.origin, [0.0, 0.0, s.levels[k]]);
            assert_eq!(s.outlines[k].len(), 1, "one ring");
            assert_eq!(s.outlines[k][0].len() % 2, 0);
        }
    }

    /// A torus of 40,000 faces (many chunks of the kernels) gives the same slices, bit
    /// for bit, on 1, 2 and 5 threads; its cells add up to its volume.
    #[test]
    fn slices_are_the_same_at_any_thread_count() {
        let torus = meshvol::shapes::torus(3.0, 1.0, 200, 100);
        let c = check(&torus, &CheckOptions::default()).unwrap();
        let source = Source::arrays(torus.vertex_count());
        let subject = Subject { source: &source, surface: &torus, check: Some(&c) };
        let on = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut s =
                pool.install(|| slices(&subject, &UnitOptions::default())).unwrap().unwrap();
            s.grid.run.seconds = 0.0;
            serde_json::to_string(&s).unwrap()
        };
        let one = on(1);
        assert_eq!(one, on(2));
        assert_eq!(one, on(5));
        let s = slices(&subject, &UnitOptions::default()).unwrap().unwrap();
        let volume = meshvol::shapes::torus_volume(3.0, 1.0, 200, 100);
        assert!((s.grid.cells.total - volume).abs() < 1e-9 * volume);
    }

    /// Outlines keep at most the bound, from rings of any sizes.
    #[test]
    fn outlines_are_thinned_to_the_bound() {
        let ring = |n: usize| -> Vec<Point2> {
            (0..n).map(|i| (i as f64 / n as f64 * std::f64::consts::TAU).sin_cos().into()).collect()
        };
        let many: Vec<Polygon> = (0..700).map(|_| Polygon::new(ring(7), vec![ring(5)])).collect();
        let points = |o: &[Vec<f32>]| o.iter().map(|r| r.len() / 2).sum::<usize>();
        assert!(points(&outline(&many)) <= MAX_OUTLINE_POINTS);
        let one = [Polygon::new(ring(100_000), vec![])];
        let thin = outline(&one);
        assert!(points(&thin) <= MAX_OUTLINE_POINTS && points(&thin) > MAX_OUTLINE_POINTS / 2);
        let small = [Polygon::new(ring(10), vec![ring(4)])];
        assert_eq!(points(&outline(&small)), 14, "kept whole");
    }
}
