//! `meshvol area`: area, perimeter, centroid and second moments of the polygons in WKT,
//! GeoJSON and text ring files, per feature and in total.

use crate::driver::{self, Output};
use clap::Args;
use meshvol_report::area::area;
use meshvol_report::quantities::Quantities;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args)]
pub struct AreaArgs {
    /// Polygon files: WKT (.wkt), GeoJSON (.geojson, .json), or x y lines (.txt, .xy,
    /// .csv; blank lines separate the exterior from holes); `-` reads standard input
    /// (format from the content).
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    units: crate::units::AreaUnitArgs,
}

/// Runs the command.
pub fn run(args: AreaArgs, quiet: bool) -> ExitCode {
    let inputs = args.walk.expand(&args.files, meshvol_io::InputKind::Polygons);
    driver::each(&inputs, Output { json: args.json, quiet, csv: false }, |path, _| {
        let file = crate::input::load_polygons(path)?;
        let name = path.display().to_string();
        area(Some(name), Some(file.format.name()), &file.features, file.warnings)?
            .in_units(&args.units.options(), None)
    })
}
