//! `meshvol intersect`: the volume of the intersection of two closed bodies (two files,
//! each one body) as a certified interval, with IoU, Dice and the differences, without
//! a boolean mesh.

use crate::driver::{self, Output};
use crate::solid::{self, SolidArgs};
use clap::Args;
use meshvol_report::intersect::intersect_with;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct IntersectArgs {
    /// The first body (every shell of the file).
    #[arg(value_name = "A")]
    a: PathBuf,
    /// The second body.
    #[arg(value_name = "B")]
    b: PathBuf,
    /// Stop refining once (upper − lower) ≤ REL · lower.
    #[arg(long, value_name = "REL", default_value_t = 1e-9, value_parser = crate::positive_finite, allow_hyphen_values = true)]
    tolerance: f64,
    /// Print one JSON object: lower, upper, volume, iou, dice, a_minus_b, b_minus_a,
    /// volume_a, volume_b, union, warnings (docs/json.md).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    solid: SolidArgs,
}

/// Runs the command: one report for the pair.
pub fn run(args: IntersectArgs, quiet: bool) -> ExitCode {
    let files = [args.a.clone(), args.b.clone()];
    driver::once(&files, Output { json: args.json, quiet }, |progress| {
        let mut inputs = Vec::new();
        for path in &files {
            inputs.push(solid::read(path, args.solid.check(), progress)?);
            progress.done(path);
        }
        let hook = progress.kernel("measuring the intersection".to_string());
        let subjects = solid::subjects(&inputs);
        intersect_with(&subjects[0], &subjects[1], args.tolerance, &hook)
    })
}
