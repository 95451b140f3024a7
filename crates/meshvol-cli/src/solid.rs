//! The one solid behind every number: each measuring command (`volume`, `grid`,
//! `profile`, `union`, `section`, `repair`) reads its files through [`read`], which
//! checks each surface; the report layer then measures the solid it bounds (welded,
//! shells turned outward, cavities subtracted, degenerate and duplicate faces left out,
//! holes capped) and gives the reasons to doubt it as warnings. `--no-check` measures the
//! surface as wound instead.

use crate::input::{self, Progress};
use clap::Args;
use meshvol::topology::CheckOptions;
use meshvol_io::LoadedSurface;
use meshvol_report::checked::{refuse_empty, Checked};
use meshvol_report::subject::Subject;
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
    #[arg(long, value_name = "T", value_parser = crate::numbers::non_negative_finite, allow_hyphen_values = true)]
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

/// Reads `path` and, with `options`, checks it ([`Checked::of`], as the server and
/// Python do). A file without faces is an error: there is nothing to measure.
pub fn read(
    path: &Path,
    options: Option<CheckOptions>,
    progress: &Progress,
) -> Result<Checked, String> {
    progress.stage("reading", path);
    let name = path.display().to_string();
    let loaded = input::load(path, options.is_some())?;
    refuse_empty(&name, &loaded)?;
    if options.is_some() {
        progress.stage("checking", path);
    }
    let kernel = progress.kernel(format!("checking {name}"));
    let checked = Checked::of(&name, loaded, options.as_ref(), &kernel);
    // The check's arrays are gone: their pages need not stay beside the surface's.
    crate::allocator::trim();
    checked.map_err(|e| e.to_string())
}

/// The subjects of several inputs.
pub fn subjects(inputs: &[Checked]) -> Vec<Subject<'_, LoadedSurface>> {
    inputs.iter().map(Checked::subject).collect()
}
