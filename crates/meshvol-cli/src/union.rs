//! `meshvol union`: the volume of the union of several closed bodies (files, or the
//! shells of one file) as a certified interval, without a boolean mesh.

use crate::driver::{self, Output};
use crate::solid::{self, SolidArgs};
use clap::Args;
use meshvol_report::quantities::Quantities;
use meshvol_report::union::union_with;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct UnionArgs {
    /// Mesh files: each is one body; a single file's shells are the bodies.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// Stop refining once (upper − lower) ≤ REL · lower.
    #[arg(long, value_name = "REL", default_value_t = 1e-6, value_parser = crate::numbers::positive_finite, allow_hyphen_values = true)]
    tolerance: f64,
    /// Print one JSON object: lower, upper, volume, bodies, sum_of_volumes, cells_refined,
    /// cells_resolved_exactly, volume_uncertainty, warnings.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    units: crate::units::UnitArgs,
    #[command(flatten)]
    solid: SolidArgs,
}

/// Runs the command: one report for all the bodies.
pub fn run(args: UnionArgs, quiet: bool) -> ExitCode {
    let files = args.walk.expand(&args.files, meshvol_io::InputKind::Mesh);
    driver::once(&files, Output { json: args.json, quiet, csv: false }, |progress| {
        let mut inputs = Vec::new();
        for path in &files.files {
            inputs.push(solid::read(path, args.solid.check(), progress)?);
            progress.done(path);
        }
        let hook = progress.kernel("measuring the union".to_string());
        let files: Vec<_> = inputs.iter().map(|i| (i.source.name(), i.source.unit)).collect();
        union_with(&solid::subjects(&inputs), args.tolerance, &hook)?
            .in_units(&args.units.options(), &files)
    })
}
