//! `meshvol below`: the part of each file's solid under a plane: displaced volume,
//! centre of buoyancy, wetted area, waterplane; or the level that holds a volume.

use crate::driver;
use crate::solid;
use clap::Args;
use meshvol_report::below::{below, BelowOptions, Waterline};
use meshvol_report::plane::PlaneArg;
use meshvol_report::quantities::Quantities;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
#[command(group(clap::ArgGroup::new("waterline").required(true).args(["plane", "volume"])))]
pub struct BelowArgs {
    /// Mesh files (or those compressed: .gz, .bz2, .zst, a .zip of one), or folders of
    /// them.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// The plane: `NX,NY,NZ,D` (n·x = D), `z=H` (`x=H`, `y=H`: the normal along the
    /// axis), or a point and a normal `PX,PY,PZ,NX,NY,NZ`. The part where n·x ≤ D (on
    /// the side the normal points away from) is measured.
    #[arg(long, value_name = "PLANE", allow_hyphen_values = true)]
    plane: Option<PlaneArg>,
    /// The volume to hold below: finds the level D along --direction (a draft).
    #[arg(long, value_name = "V", value_parser = crate::numbers::positive_finite, allow_hyphen_values = true)]
    volume: Option<f64>,
    /// The direction the level is taken along, with --volume (default: z).
    #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_numbers::<3>, allow_hyphen_values = true, requires = "volume")]
    direction: Option<[f64; 3]>,
    /// Heel: the plane's normal turned by DEG degrees about x.
    #[arg(long, value_name = "DEG", default_value_t = 0.0, allow_hyphen_values = true)]
    heel: f64,
    /// Trim: the plane's normal turned by DEG degrees about y (after the heel).
    #[arg(long, value_name = "DEG", default_value_t = 0.0, allow_hyphen_values = true)]
    trim: f64,
    #[command(flatten)]
    report: driver::SolidReportArgs,
}

fn parse_numbers<const N: usize>(s: &str) -> Result<[f64; N], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("'{s}': expected {N} comma-separated numbers"))?;
    v.try_into().map_err(|_| format!("'{s}': expected {N} comma-separated numbers"))
}

/// Runs the command.
pub fn run(args: BelowArgs, quiet: bool) -> ExitCode {
    let waterline = match (args.plane, args.volume) {
        (Some(plane), _) => {
            let (normal, d) = plane.normal_offset();
            Waterline::Plane { normal, d }
        }
        (None, Some(volume)) => {
            Waterline::Volume { direction: args.direction.unwrap_or([0.0, 0.0, 1.0]), volume }
        }
        (None, None) => {
            eprintln!("meshvol: error: give --plane PLANE or --volume V");
            return ExitCode::from(2);
        }
    };
    let options = BelowOptions { waterline, heel: args.heel, trim: args.trim };
    let check = args.report.solid.check();
    let units = args.report.units.options();
    let inputs = args.walk.expand(&args.files, meshvol_io::InputKind::Mesh);
    driver::each(&inputs, args.report.output.output(quiet), |path, progress| {
        let input = solid::read(path, check, progress)?;
        progress.stage("measuring", path);
        below(&input.subject(), &options)?.in_units(&units, input.source.unit)
    })
}
