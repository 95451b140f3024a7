//! `meshvol profile`: the volume below each level along an axis, the volume of each slab
//! between levels and the cross-section area at each level (a strapping table).

use crate::driver::{Driver, Output};
use crate::input::Progress;
use crate::solid::{self, SolidArgs};
use clap::{Args, ValueEnum};
use meshvol::grid::{Axis, Levels};
use meshvol_report::profile::{profile, ProfileReport};
use meshvol_report::quantities::Quantities;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Clone, Copy, ValueEnum)]
pub enum AxisArg {
    X,
    Y,
    Z,
}

#[derive(Args)]
#[command(group(clap::ArgGroup::new("spacing").required(true).args(["levels", "step"])))]
pub struct ProfileArgs {
    /// The mesh file.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// The axis the levels are taken along.
    #[arg(long, value_enum, default_value = "z")]
    axis: AxisArg,
    /// N slabs: N + 1 equally spaced levels from the mesh's minimum to its maximum.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=(meshvol::grid::MAX_LEVELS as u64 - 1)))]
    levels: Option<u64>,
    /// A level every H from the minimum, up to the first at or above the maximum.
    #[arg(long, value_name = "H", value_parser = crate::numbers::positive_finite, allow_hyphen_values = true)]
    step: Option<f64>,
    /// Print one JSON object: axis, levels, volume_below, slab_volume, section_area.
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// Print CSV: level,volume_below,slab_volume,section_area.
    #[arg(long)]
    csv: bool,
    #[command(flatten)]
    units: crate::units::UnitArgs,
    #[command(flatten)]
    solid: SolidArgs,
}

/// Runs the command: the table, CSV or JSON on stdout.
pub fn run(args: ProfileArgs, quiet: bool) -> ExitCode {
    let files = std::slice::from_ref(&args.file);
    let mut driver = Driver::new(files, Output { json: args.json, quiet, csv: false });
    match measure(&args, &driver.progress) {
        Ok(report) if args.csv => driver.print(&report, &report.csv()),
        Ok(report) => driver.report(&report),
        Err(e) => driver.fail(&args.file.display().to_string(), &e),
    }
    driver.finish()
}

fn measure(args: &ProfileArgs, progress: &Progress) -> Result<ProfileReport, String> {
    let input = solid::read(&args.file, args.solid.check(), progress)?;
    let axis = match args.axis {
        AxisArg::X => Axis::X,
        AxisArg::Y => Axis::Y,
        AxisArg::Z => Axis::Z,
    };
    let levels = match (args.levels, args.step) {
        (Some(n), _) => Levels::Count(n as usize),
        (None, Some(h)) => Levels::Step(h),
        (None, None) => return Err("give --levels N or --step H".into()),
    };
    progress.stage("measuring", &args.file);
    profile(&input.subject(), axis, levels)?.in_units(&args.units.options(), input.source.unit)
}
