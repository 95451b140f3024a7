//! The one solid behind every number: each measuring command (`volume`, `grid`,
//! `profile`, `union`, `section`) reads its files through [`read`], which checks each
//! surface and hands out the solid it bounds (welded, shells turned outward, cavities
//! subtracted, degenerate and duplicate faces left out, holes capped) with the reasons
//! to doubt it as warnings. `--no-check` hands out the surface as wound instead.

use crate::input::{self, Progress};
use clap::Args;
use meshvol::grid::{shells, FaceSubset};
use meshvol::topology::{self, Check, CheckOptions, Measured, Weld};
use meshvol_io::{Loaded, LoadedSurface};
use std::path::Path;

/// How a measuring command forms its solid; shared by every command that measures one.
#[derive(Args, Clone, Copy, Debug)]
pub struct SolidArgs {
    /// Measure the surface as the file winds it, without checking it: no welding, no
    /// cavity or shell correction, no caps. Fastest; volumes then carry the file's sign
    /// (negative for inward winding) and overlaps count twice.
    #[arg(long, conflicts_with_all = ["weld_tolerance", "no_intersections"])]
    pub no_check: bool,
    /// Weld vertices whose coordinates differ by at most T; 0 welds exactly equal
    /// positions only. Default: exactly, and when that leaves holes, again within 1e-9 of
    /// the bounding box diagonal (reported as `weld_tolerance`).
    #[arg(long, value_name = "T", value_parser = crate::non_negative_finite)]
    pub weld_tolerance: Option<f64>,
    /// Skip the search for crossing triangles (self-intersections; overlapping shells
    /// are then found only by the nesting ray tests). Faster, and trusts the file more.
    #[arg(long)]
    pub no_intersections: bool,
}

impl SolidArgs {
    /// The check to run, or `None` with `--no-check`.
    pub fn check(&self) -> Option<CheckOptions> {
        (!self.no_check).then(|| check_options(self.weld_tolerance, !self.no_intersections))
    }
}

/// Check options from the weld tolerance flag and whether to search for crossings.
pub fn check_options(weld_tolerance: Option<f64>, intersections: bool) -> CheckOptions {
    CheckOptions {
        weld: match weld_tolerance {
            None => Weld::Auto,
            Some(0.0) => Weld::Exact,
            Some(t) => Weld::Tolerance(t),
        },
        intersections,
        ..CheckOptions::default()
    }
}

/// One input, read and (unless `--no-check`) checked.
pub struct Input {
    /// The path as given.
    pub name: String,
    pub loaded: Loaded,
    /// The check the solid comes from; `None` with `--no-check`.
    pub check: Option<Check>,
    /// The reader's warnings, then the reasons to doubt the solid.
    pub warnings: Vec<String>,
}

/// Reads `path` and, with `options`, checks it. A file without faces is an error: there
/// is nothing to measure.
pub fn read(
    path: &Path,
    options: Option<CheckOptions>,
    progress: &Progress,
) -> Result<Input, String> {
    let name = path.display().to_string();
    progress.stage("reading", path);
    let loaded = input::load(path)?;
    if loaded.face_count() == 0 {
        return Err(format!("{name}: no faces: there is no surface to measure"));
    }
    let mut warnings = loaded.warnings.clone();
    let check = match options {
        None => None,
        Some(options) => {
            progress.stage("checking", path);
            let check =
                topology::check(&loaded.surface, &options).map_err(|e| format!("{name}: {e}"))?;
            warnings.extend(check.doubts());
            Some(check)
        }
    };
    Ok(Input { name, loaded, check, warnings })
}

/// One body of a union: a file's whole solid, or one outermost shell of a single file
/// with what is nested in it.
pub struct Body<'a> {
    pub name: String,
    pub surface: FaceSubset<Measured<'a, LoadedSurface>>,
}

impl Input {
    /// What is measured: the checked solid, or the surface as wound.
    pub fn surface(&self) -> Measured<'_, LoadedSurface> {
        match &self.check {
            Some(check) => Measured::Solid(check.solid(&self.loaded.surface)),
            None => Measured::AsWound(&self.loaded.surface),
        }
    }

    /// How far the caps on holes could put the volume off (0 when closed or unchecked).
    pub fn volume_uncertainty(&self) -> f64 {
        self.check.as_ref().map_or(0.0, |c| c.volume_uncertainty)
    }

    /// The file's bodies: the checked solid's outermost shells, each with its cavities
    /// (numbered as `meshvol check` numbers shells); unchecked, the surface's
    /// connected parts.
    pub fn bodies(&self) -> Vec<Body<'_>> {
        let surface = self.surface();
        let parts: Vec<(usize, Vec<usize>)> = match &self.check {
            Some(check) => check.bodies().into_iter().map(|b| (b.shell, b.faces)).collect(),
            None => shells(&self.loaded.surface).into_iter().enumerate().collect(),
        };
        parts
            .into_iter()
            .map(|(shell, faces)| Body {
                name: format!("{}, shell {shell}", self.name),
                surface: FaceSubset::new(surface, faces),
            })
            .collect()
    }

    /// The whole file as one body.
    pub fn whole(&self) -> Body<'_> {
        let surface = self.surface();
        Body { name: self.name.clone(), surface: FaceSubset::all(surface) }
    }
}

/// Bodies of a union: the bodies of a single file, or each file whole.
pub fn union_bodies(inputs: &[Input]) -> Vec<Body<'_>> {
    match inputs {
        [one] => one.bodies(),
        many => many.iter().map(Input::whole).collect(),
    }
}
