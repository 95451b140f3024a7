//! `cutfill`: the earthwork between an existing surface and a design (a second surface,
//! or a level): cut, fill and net volumes and their areas over the common footprint,
//! and optionally the same per cell of a plan grid.

use crate::number::num;
use crate::quantities::{Converter, Dimension::*, Quantities};
use crate::subject::Source;
use crate::units::{Mass, UnitNames};
use crate::Report;
use meshvol::cutfill::{cell_cut_fill_with, cut_fill_with, CellCutFill, Design, PlanGrid, Terrain};
use meshvol::progress::Progress;
use meshvol::Surface;
use serde::Serialize;
use std::fmt::Write;

/// What the existing surface is compared with.
pub enum Against<'a, S> {
    /// A design surface and where it came from.
    Surface { source: &'a Source, surface: &'a S },
    /// The plane z = level.
    Level(f64),
}

/// How the plan grid of per-cell values is spaced over the common footprint's box.
#[derive(Clone, Copy, Debug)]
pub enum Spacing {
    /// NX × NY cells.
    Cells([usize; 2]),
    /// Square cells of this size, as many as cover the box.
    Pitch(f64),
}

/// The plan grid of per-cell values: cell (i, j) spans `origin + (i, j)·cell` to
/// `origin + (i+1, j+1)·cell`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct GridInfo {
    pub counts: [usize; 2],
    pub origin: [f64; 2],
    pub cell: [f64; 2],
}

/// The report. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct CutFillReport {
    /// The existing surface's file.
    pub file: Option<String>,
    /// The design's file (`mesh` for arrays), or `z = LEVEL`.
    pub design: String,
    /// The design level; null with a design surface.
    pub level: Option<f64>,
    /// ∫ max(existing − design, 0) dA over the common footprint.
    pub cut: f64,
    /// ∫ max(design − existing, 0) dA.
    pub fill: f64,
    /// cut − fill.
    pub net: f64,
    pub area_cut: f64,
    pub area_fill: f64,
    /// The area where both surfaces are defined.
    pub footprint_area: f64,
    /// The common footprint's box, [[x0, y0], [x1, y1]]; null when there is none.
    pub footprint_bounds: Option<[[f64; 2]; 2]>,
    /// The plan areas of the existing surface and of the design (null for a level).
    pub existing_area: f64,
    pub design_area: Option<f64>,
    /// The plan grid of the per-cell values; null without one.
    pub grid: Option<GridInfo>,
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    pub warnings: Vec<String>,
}

/// Per-cell cut and fill volumes, in C order over the report's grid (`i·ny + j`).
pub type Cells = CellCutFill;

/// At most this many vertical faces are named in the warning.
const NAMED_FACES: usize = 5;

/// A surface as a height field; the error names its file.
fn terrain<S: Surface>(source: &Source, surface: &S) -> Result<Terrain, String> {
    Terrain::new(surface).map_err(|e| format!("{}: {e}", source.name()))
}

/// The warning about a surface's vertical faces, if it has any.
fn vertical_warning(terrain: &Terrain) -> Option<String> {
    let faces = terrain.vertical_faces();
    if faces.is_empty() {
        return None;
    }
    let named: Vec<String> = faces.iter().take(NAMED_FACES).map(|f| f.to_string()).collect();
    let more = if faces.len() > NAMED_FACES { ", ..." } else { "" };
    Some(format!(
        "{} vertical face{} (no area in plan) left out: face{} {}{more}",
        faces.len(),
        if faces.len() == 1 { "" } else { "s" },
        if faces.len() == 1 { "" } else { "s" },
        named.join(", ")
    ))
}

/// The plan grid `spacing` asks for over `bounds`.
fn plan_grid(bounds: [[f64; 2]; 2], spacing: Spacing) -> Result<PlanGrid, String> {
    let extent = [0, 1].map(|a| bounds[1][a] - bounds[0][a]);
    if let Some(a) = (0..2).find(|&a| !(extent[a] > 0.0 && extent[a].is_finite())) {
        return Err(format!(
            "the common footprint has no extent along {} to divide into cells",
            ["x", "y"][a]
        ));
    }
    let (counts, cell) = match spacing {
        Spacing::Cells(counts) => (counts, [0, 1].map(|a| extent[a] / counts[a] as f64)),
        Spacing::Pitch(pitch) => {
            let n = extent.map(|e| (e / pitch).ceil().max(1.0));
            if n.iter().any(|&k| k > meshvol::cutfill::MAX_CELLS as f64) {
                return Err(format!(
                    "a pitch of {pitch:e} across {:e} × {:e} gives too many cells: use a larger \
                     pitch",
                    extent[0], extent[1]
                ));
            }
            (n.map(|k| k as usize), [pitch; 2])
        }
    };
    PlanGrid::new(bounds[0], cell, counts).map_err(|e| e.to_string())
}

/// Cut and fill of the existing surface (`source`, `surface`) against `against`, and
/// with `spacing` per cell of a plan grid over the common footprint's box.
pub fn cutfill<S: Surface, T: Surface>(
    source: &Source,
    surface: &S,
    against: Against<'_, T>,
    spacing: Option<Spacing>,
) -> Result<(CutFillReport, Option<Cells>), String> {
    cutfill_with(source, surface, against, spacing, &())
}

/// [`cutfill`], telling `progress` the kernels' stages and how far through them.
pub fn cutfill_with<S: Surface, T: Surface>(
    source: &Source,
    surface: &S,
    against: Against<'_, T>,
    spacing: Option<Spacing>,
    progress: &dyn Progress,
) -> Result<(CutFillReport, Option<Cells>), String> {
    let name = source.name();
    progress.stage("checking the existing surface is a height field");
    let existing = terrain(source, surface)?;
    let mut warnings = source.warnings.clone();
    warnings.extend(vertical_warning(&existing));
    let design_terrain;
    let (design, level, design_area, kernel_design) = match against {
        Against::Level(z) => {
            if !z.is_finite() {
                return Err(format!("the level must be a finite number; got {z}"));
            }
            (format!("z = {z}"), Some(z), None, Design::Level(z))
        }
        Against::Surface { source: design_source, surface } => {
            progress.stage("checking the design is a height field");
            design_terrain = terrain(design_source, surface)?;
            let design_name = design_source.name();
            warnings.extend(design_source.warnings.iter().map(|w| format!("{design_name}: {w}")));
            warnings
                .extend(vertical_warning(&design_terrain).map(|w| format!("{design_name}: {w}")));
            let area = design_terrain.plan_area();
            (design_name.to_string(), None, Some(area), Design::Surface(&design_terrain))
        }
    };
    let totals = cut_fill_with(&existing, kernel_design, progress);
    let sums = [totals.cut, totals.fill, totals.area_cut, totals.area_fill, totals.footprint_area];
    if !sums.iter().all(|x| x.is_finite()) {
        return Err(format!(
            "{name}: the cut and fill overflow f64: the coordinates are too large to measure"
        ));
    }
    let existing_area = existing.plan_area();
    if totals.footprint_area == 0.0 {
        warnings.push("the surfaces have no footprint in common: nothing to compare".to_string());
    } else if totals.footprint_area < existing_area * (1.0 - 1e-9) {
        warnings.push(format!(
            "the design covers {} of the existing surface's {} in plan: cut and fill are over \
             the common footprint only",
            num(totals.footprint_area, 6),
            num(existing_area, 6)
        ));
    }
    let cells = match spacing {
        None => None,
        Some(spacing) => {
            let bounds = totals
                .footprint_bounds
                .ok_or_else(|| format!("{name}: no common footprint to divide into cells"))?;
            let grid = plan_grid(bounds, spacing).map_err(|e| format!("{name}: {e}"))?;
            Some((grid, cell_cut_fill_with(&existing, kernel_design, &grid, progress)))
        }
    };
    let report = CutFillReport {
        file: source.file.clone(),
        design,
        level,
        cut: totals.cut,
        fill: totals.fill,
        net: totals.cut - totals.fill,
        area_cut: totals.area_cut,
        area_fill: totals.area_fill,
        footprint_area: totals.footprint_area,
        footprint_bounds: totals.footprint_bounds,
        existing_area,
        design_area,
        grid: cells.as_ref().map(|(g, _)| GridInfo {
            counts: g.counts(),
            origin: g.origin(),
            cell: g.cell(),
        }),
        units: None,
        mass: None,
        warnings,
    };
    Ok((report, cells.map(|(_, c)| c)))
}

impl Report for CutFillReport {
    crate::file_and_warnings!("mesh");

    fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}: cut and fill against {}", self.file(), self.design);
        let _ = writeln!(
            s,
            "  cut              {}  over an area of {}",
            num(self.cut, 15),
            num(self.area_cut, 15)
        );
        let _ = writeln!(
            s,
            "  fill             {}  over an area of {}",
            num(self.fill, 15),
            num(self.area_fill, 15)
        );
        let _ = writeln!(s, "  net (cut − fill) {}", num(self.net, 15));
        let _ = writeln!(s, "  footprint area   {}", num(self.footprint_area, 15));
        if let Some(g) = &self.grid {
            let _ = writeln!(
                s,
                "  cells            {} × {} of {} × {} from ({}, {})",
                g.counts[0],
                g.counts[1],
                num(g.cell[0], 10),
                num(g.cell[1], 10),
                num(g.origin[0], 12),
                num(g.origin[1], 12)
            );
        }
        s.push_str(&crate::units::units_text(&self.units, &self.mass));
        s
    }
}

impl Quantities for CutFillReport {
    fn convert(&mut self, to: &Converter) {
        to.some(Length, &mut self.level);
        to.all(Volume, [&mut self.cut, &mut self.fill, &mut self.net]);
        let areas = [&mut self.area_cut, &mut self.area_fill, &mut self.footprint_area];
        to.all(Area, areas.into_iter().chain([&mut self.existing_area]));
        to.some(Area, &mut self.design_area);
        to.all(Length, self.footprint_bounds.iter_mut().flatten().flatten());
        if let Some(g) = &mut self.grid {
            to.all(Length, g.origin.iter_mut().chain(&mut g.cell));
        }
    }

    /// The fill's: the material brought in.
    fn mass_basis(&self) -> f64 {
        self.fill
    }

    crate::unit_slots!();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_from_cells_or_a_pitch() {
        let b = [[1.0, 2.0], [3.0, 3.0]];
        let g = plan_grid(b, Spacing::Cells([4, 2])).unwrap();
        assert_eq!((g.counts(), g.cell(), g.origin()), ([4, 2], [0.5, 0.5], [1.0, 2.0]));
        let g = plan_grid(b, Spacing::Pitch(0.3)).unwrap();
        assert_eq!((g.counts(), g.cell()), ([7, 4], [0.3, 0.3]));
        assert!(plan_grid(b, Spacing::Pitch(1e-300)).unwrap_err().contains("larger pitch"));
        let thin = [[1.0, 2.0], [3.0, 2.0]];
        assert!(plan_grid(thin, Spacing::Cells([2, 2])).unwrap_err().contains("along y"));
    }
}
