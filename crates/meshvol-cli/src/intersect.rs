//! `meshvol intersect`: the volume of the intersection of two closed bodies (two files,
//! each one body) as a certified interval, with its moments, IoU, Dice and the
//! differences, without a boolean mesh; with `--pairs`, of every pair of several files
//! whose boxes overlap.

use crate::driver::{self, Output};
use crate::solid;
use clap::Args;
use meshvol::overlap::Body;
use meshvol::topology::CheckOptions;
use meshvol_report::intersect::{intersect_prepared, overlapping_pairs, prepare, prepare_pair};
use meshvol_report::quantities::Quantities;
use rayon::prelude::*;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct IntersectArgs {
    /// Two mesh files A and B, each one body (every shell of the file); with --pairs,
    /// any number.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// Every pair of the files whose boxes overlap, each once (one report per pair, in
    /// the files' order); pairs whose boxes are apart hold no volume and are not
    /// printed.
    #[arg(long)]
    pairs: bool,
    /// With --pairs: refuse to measure more pairs than this.
    #[arg(long, value_name = "N", default_value_t = 10_000)]
    max_pairs: usize,
    /// Stop refining once (upper − lower) ≤ REL · lower.
    #[arg(long, value_name = "REL", default_value_t = 1e-9, value_parser = crate::numbers::positive_finite, allow_hyphen_values = true)]
    tolerance: f64,
    #[command(flatten)]
    report: driver::SolidReportArgs,
}

/// Runs the command: one report for the pair, or one per overlapping pair.
pub fn run(args: IntersectArgs, quiet: bool) -> ExitCode {
    let output = args.report.output.output(quiet);
    let files = args.walk.expand(&args.files, meshvol_io::InputKind::Mesh);
    if args.pairs {
        return pairs(&args, &files, output);
    }
    if files.files.len() + files.problems.len() != 2 {
        let found = if args.files.iter().any(|f| f.is_dir()) {
            format!(" (the arguments give {})", files.files.len())
        } else {
            String::new()
        };
        eprintln!("meshvol: error: intersect takes two files A B{found} (several with --pairs)");
        return ExitCode::from(2);
    }
    driver::once(&files, output, |progress| {
        let mut inputs = Vec::new();
        for path in &files.files {
            inputs.push(solid::read(path, check_options(&args), progress)?);
            progress.done(path);
        }
        let subjects = solid::subjects(&inputs);
        progress.stage_all("preparing the bodies");
        let bodies = prepare_pair(&subjects[0], &subjects[1]);
        progress.stage_all("measuring");
        let hook = progress.kernel("measuring the intersection".to_string());
        let files: Vec<_> = inputs.iter().map(|i| (i.source.name(), i.source.unit)).collect();
        let bodies = [bodies[0].as_ref(), bodies[1].as_ref()];
        intersect_prepared(&subjects[0], &subjects[1], bodies, [None, None], args.tolerance, &hook)?
            .in_units(&args.report.units.options(), &files)
    })
}

/// `--pairs`: each file read and checked once; a file that fails is reported and left
/// out of the pairs.
fn pairs(args: &IntersectArgs, files: &crate::walk::Inputs, output: Output) -> ExitCode {
    let mut driver = driver::start(files, output);
    let mut inputs = Vec::new();
    for path in &files.files {
        match solid::read(path, check_options(args), &driver.progress) {
            Ok(input) => inputs.push(input),
            Err(e) => driver.fail(&path.display().to_string(), &e),
        }
        driver.progress.done(path);
    }
    let subjects = solid::subjects(&inputs);
    let pairs = overlapping_pairs(&subjects);
    if pairs.len() > args.max_pairs {
        let names: Vec<String> = files.files.iter().map(|p| p.display().to_string()).collect();
        let error = format!(
            "{}: {} pairs of boxes overlap, more than --max-pairs {}; raise it to measure them",
            names.join(", "),
            pairs.len(),
            args.max_pairs
        );
        driver.fail(&names.join(", "), &error);
        return driver.finish();
    }
    // Each body prepared for the boundary method once, and only if it is in a pair, in
    // parallel (each body the same whichever thread prepares it).
    driver.progress.stage_all("preparing the bodies");
    let mut in_pair = vec![false; subjects.len()];
    pairs.iter().for_each(|&(i, j)| (in_pair[i], in_pair[j]) = (true, true));
    let bodies: Vec<Option<Body>> = subjects
        .par_iter()
        .zip(&in_pair)
        .map(|(s, &needed)| if needed { prepare(s) } else { None })
        .collect();
    let body = |k: usize| bodies[k].as_ref();
    driver.progress.stage_all("measuring");
    for (i, j) in pairs {
        if driver.closed() {
            break;
        }
        let (a, b) = (&subjects[i], &subjects[j]);
        let what = format!("intersecting {} and {}", a.source.name(), b.source.name());
        let result = {
            let hook = driver.progress.kernel(what);
            let files = [(a.source.name(), a.source.unit), (b.source.name(), b.source.unit)];
            intersect_prepared(a, b, [body(i), body(j)], [None, None], args.tolerance, &hook)
                .and_then(|r| r.in_units(&args.report.units.options(), &files))
        };
        match result {
            Ok(report) => driver.report(&report),
            Err(e) => {
                let file = format!("{}, {}", a.source.name(), b.source.name());
                driver.fail(&file, &format!("{file}: {e}"));
            }
        }
    }
    driver.finish()
}

/// The check each input gets: the command's, keeping the crossing search's spatial index
/// for the input's body to take ([`CheckOptions::keep_spatial_index`]).
fn check_options(args: &IntersectArgs) -> Option<CheckOptions> {
    args.report.solid.check().map(|options| CheckOptions { keep_spatial_index: true, ..options })
}
