//! `meshvol volume`: mass properties of each file's solid.

use crate::driver::{self, Output};
use crate::input::Progress;
use crate::solid::{self, SolidArgs};
use clap::{Args, ValueEnum};
use meshvol_report::inertial::{inertial, refuse_units, RobotFormat};
use meshvol_report::units::Density;
use meshvol_report::volume::{volume, VolumeOptions};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args)]
pub struct VolumeArgs {
    /// Mesh files: STL (binary or ASCII), OBJ, OFF, PLY, 3MF, glTF/GLB, or those
    /// compressed (.gz, .bz2, .zst, a .zip of one); folders (the mesh files in them,
    /// sorted by path); `-` reads standard input (format from the content).
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// Print one JSON object per file, one per line (`--format json`).
    #[arg(long, conflicts_with = "format")]
    json: bool,
    /// What to print: `text` (the default), `json`, `csv` (one table: a header, then a
    /// row per file, the JSON keys as columns, nested ones as `parent.child`), or the
    /// `<inertial>` element of a robot description, `urdf`, `sdf` or `mjcf` (mass, centre
    /// of mass and inertia in kg, m and kg·m², converted from any --units and a --density
    /// with its unit, e.g. `--units mm --density 2.7g/cm3`).
    #[arg(long, value_enum)]
    format: Option<Format>,
    #[command(flatten)]
    units: crate::units::UnitArgs,
    /// Report the correctly rounded exact signed volume (exact arithmetic; a few times
    /// slower than the default, which is already within `volume_error_bound`).
    #[arg(long)]
    exact: bool,
    /// Accepted for scripts written when the crossing search was optional: it is now
    /// part of the default check (`--no-intersections` skips it).
    #[arg(long, hide = true, conflicts_with_all = ["no_check", "no_intersections"])]
    intersections: bool,
    #[command(flatten)]
    solid: SolidArgs,
}

/// What `volume` prints.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Format {
    Text,
    Json,
    Csv,
    Urdf,
    Sdf,
    Mjcf,
}

/// Runs the command.
pub fn run(args: VolumeArgs, quiet: bool) -> ExitCode {
    let options = VolumeOptions {
        density: args.units.density.unwrap_or(Density::plain(1.0)),
        units: args.units.units,
        exact: args.exact,
    };
    let check = args.solid.check();
    let inputs = args.walk.expand(&args.files, meshvol_io::InputKind::Mesh);
    let measure = |path: &Path, progress: &Progress| {
        let input = solid::read(path, check, progress)?;
        progress.stage("measuring", path);
        volume(&input.subject(), &options)
    };
    let robot = match args.format {
        Some(Format::Urdf) => RobotFormat::Urdf,
        Some(Format::Sdf) => RobotFormat::Sdf,
        Some(Format::Mjcf) => RobotFormat::Mjcf,
        format => {
            let json = args.json || format == Some(Format::Json);
            let output = Output { json, quiet, csv: format == Some(Format::Csv) };
            return driver::each(&inputs, output, measure);
        }
    };
    let format = format!("{robot:?}").to_ascii_lowercase();
    if let Err(e) = refuse_units(&args.units.options(), &format) {
        eprintln!("meshvol: error: {e}");
        return ExitCode::from(2);
    }
    // One element per file, after a comment naming it.
    let mut driver = driver::start(&inputs, Output { json: false, quiet, csv: false });
    for path in &inputs.files {
        let name = path.display().to_string();
        let printed = measure(path, &driver.progress).and_then(|report| {
            let element = inertial(&report, robot)?;
            Ok((report, format!("<!-- {} -->\n{element}", name.replace("--", "- -"))))
        });
        driver.progress.done(path);
        match printed {
            Ok((report, element)) => driver.print(&report, &element),
            Err(e) => driver.fail(&name, &e),
        }
    }
    driver.finish()
}
