//! The one solid behind every number: each measuring command (`volume`, `grid`,
//! `profile`, `union`, `section`, `repair`) reads its files through [`read`], which
//! checks each surface; the report layer then measures the solid it bounds (welded,
//! shells turned outward, cavities subtracted, degenerate and duplicate faces left out,
//! holes capped) and gives the reasons to doubt it as warnings. `--no-check` measures the
//! surface as wound instead.

use crate::input::{self, Progress};
use clap::Args;
use meshvol::topology::{self, Check, CheckOptions};
use meshvol_io::LoadedSurface;
use meshvol_report::subject::{Source, Subject};
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
    #[arg(long, value_name = "T", value_parser = crate::non_negative_finite, allow_hyphen_values = true)]
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
pub use meshvol_report::subject::check_options;

/// One input, read and (unless `--no-check`) checked.
pub struct Input {
    pub source: Source,
    pub surface: LoadedSurface,
    /// The check the solid comes from; `None` with `--no-check`.
    pub check: Option<Check>,
}

impl Input {
    /// The input as the report layer takes it.
    pub fn subject(&self) -> Subject<'_, LoadedSurface> {
        Subject { source: &self.source, surface: &self.surface, check: self.check.as_ref() }
    }
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
        return Err(format!("{name}: {}", meshvol_report::volume::NO_FACES));
    }
    let source = Source::of(&name, &loaded);
    let check = match options {
        None => None,
        Some(options) => {
            progress.stage("checking", path);
            let check = topology::check_assembled(
                &loaded.surface,
                loaded.assembly.as_ref(),
                &loaded.body_faces(),
                &options,
                &progress.kernel(format!("checking {}", path.display())),
            )
            .map_err(|e| format!("{name}: {e}"))?;
            Some(check)
        }
    };
    Ok(Input { source, surface: loaded.surface, check })
}

/// The subjects of several inputs.
pub fn subjects(inputs: &[Input]) -> Vec<Subject<'_, LoadedSurface>> {
    inputs.iter().map(Input::subject).collect()
}
