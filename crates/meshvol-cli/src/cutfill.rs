//! `meshvol cutfill`: cut and fill between an existing surface and a design surface or
//! level (earthwork volumes), in total and per plan cell (.npy, and a PNG map of net).

use crate::driver::{self, Output};
use crate::input::{self, Progress};
use clap::{ArgGroup, Args};
use meshvol::grid::Grid;
use meshvol_io::grid_out::{self, Legend, Slice};
use meshvol_report::cutfill::{cutfill_with, Against, CutFillReport, Spacing};
use meshvol_report::quantities::Quantities;
use meshvol_report::reported_cells;
use meshvol_report::subject::Source;
use meshvol_report::units::Scale;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Args)]
#[command(group(ArgGroup::new("against").required(true).args(["design", "level"])))]
#[command(group(ArgGroup::new("spacing").args(["cells", "pitch"])))]
pub struct CutFillArgs {
    /// The existing surface: a height field z = f(x, y) (a terrain TIN), any mesh format.
    #[arg(value_name = "EXISTING")]
    existing: PathBuf,
    /// The design surface, another height field.
    #[arg(long, value_name = "SURFACE")]
    design: Option<PathBuf>,
    /// The design level: the plane z = Z.
    #[arg(long, value_name = "Z", value_parser = finite, allow_hyphen_values = true)]
    level: Option<f64>,
    /// Cut and fill per cell: NX × NY cells over the common footprint's box.
    #[arg(long, value_name = "NX,NY", value_parser = parse_cells)]
    cells: Option<[usize; 2]>,
    /// Cut and fill per cell: square cells of size P over the common footprint's box.
    #[arg(long, value_name = "P", value_parser = crate::numbers::positive_finite)]
    pitch: Option<f64>,
    /// Write the per-cell volumes as .npy: float64, shape (2, NX, NY), [0] cut, [1] fill.
    #[arg(long, short, value_name = "OUT", value_parser = parse_out, requires = "spacing")]
    out: Option<PathBuf>,
    /// Write a PNG map of the net depth per cell (cut positive, fill negative).
    #[arg(long, value_name = "FILE", requires = "spacing")]
    png: Option<PathBuf>,
    /// Print the report as one JSON object.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    units: crate::units::UnitArgs,
}

fn finite(s: &str) -> Result<f64, String> {
    s.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| format!("must be a finite number; got {s}"))
}

fn parse_cells(s: &str) -> Result<[usize; 2], String> {
    let v: Vec<usize> = s
        .split(',')
        .map(|t| t.trim().parse::<usize>().ok())
        .collect::<Option<_>>()
        .filter(|v: &Vec<usize>| v.len() == 2)
        .ok_or_else(|| format!("'{s}': expected 2 comma-separated whole numbers of cells"))?;
    if v.contains(&0) {
        return Err(format!("'{s}': each axis needs at least one cell"));
    }
    Ok([v[0], v[1]])
}

fn parse_out(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("npy") => Ok(path),
        _ => Err(format!("'{s}': the output must end in .npy")),
    }
}

/// Runs the command: one report for the pair.
pub fn run(args: CutFillArgs, quiet: bool) -> ExitCode {
    let inputs: Vec<PathBuf> =
        std::iter::once(args.existing.clone()).chain(args.design.clone()).collect();
    driver::once(
        &crate::walk::Inputs::plain(inputs),
        Output { json: args.json, quiet, csv: false },
        |progress| measure(&args, progress),
    )
}

fn read(path: &Path, progress: &Progress) -> Result<(Source, meshvol_io::LoadedSurface), String> {
    progress.stage("reading", path);
    let loaded = input::load(path, false)?;
    let name = path.display().to_string();
    if loaded.face_count() == 0 {
        return Err(format!("{name}: {}", meshvol_report::volume::NO_FACES));
    }
    let source = Source::of(&name, &loaded);
    progress.done(path);
    Ok((source, loaded.surface))
}

fn measure(args: &CutFillArgs, progress: &Progress) -> Result<CutFillReport, String> {
    let (source, surface) = read(&args.existing, progress)?;
    let design = args.design.as_deref().map(|p| read(p, progress)).transpose()?;
    let against = match (&design, args.level) {
        (Some((source, surface)), _) => Against::Surface { source, surface },
        (None, Some(level)) => Against::Level(level),
        (None, None) => return Err("give --design SURFACE or --level Z".into()),
    };
    let spacing = match (args.cells, args.pitch) {
        (Some(cells), _) => Some(Spacing::Cells(cells)),
        (None, Some(pitch)) => Some(Spacing::Pitch(pitch)),
        (None, None) => None,
    };
    let hook = progress.kernel("measuring cut and fill".to_string());
    let (report, mut cells) = cutfill_with(&source, &surface, against, spacing, &hook)?;
    drop(hook);
    // The report and the per-cell values (--out, --png) in the units asked for, each
    // converted once by the report layer.
    let mut files = vec![(source.name(), source.unit)];
    files.extend(design.as_ref().map(|(s, _)| (s.name(), s.unit)));
    let options = args.units.options();
    let report = report.in_units(&options, &files)?;
    let (scale, _) = Scale::resolve_all(&options, &files)?;
    if let (Some(cells), Some(info)) = (cells.as_mut(), &report.grid) {
        reported_cells::volumes(&scale, &mut cells.cut);
        reported_cells::volumes(&scale, &mut cells.fill);
        let [nx, ny] = info.counts;
        if let Some(out) = &args.out {
            progress.stage("writing", out);
            let file = std::fs::File::create(out)
                .map_err(|e| format!("{}: cannot create: {e}", out.display()))?;
            let mut w = BufWriter::new(file);
            let values: Vec<f64> = cells.cut.iter().chain(&cells.fill).copied().collect();
            grid_out::npy_array(&mut w, &[2, nx, ny], values.into_iter())
                .and_then(|()| w.flush())
                .map_err(|e| format!("{}: {e}", out.display()))?;
        }
        if let Some(png) = &args.png {
            progress.stage("drawing", png);
            // The net depth: the net volume of a cell over its area.
            let area = info.cell[0] * info.cell[1];
            let depth: Vec<f64> =
                cells.cut.iter().zip(&cells.fill).map(|(c, f)| (c - f) / area).collect();
            let full = depth.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            let legend = Legend {
                title: "cut (+) and fill (-)".to_string(),
                name: "depth".to_string(),
                full: if full > 0.0 { full } else { 1.0 },
            };
            let origin = [info.origin[0], info.origin[1], 0.0];
            let plan = Grid::new(origin, [info.cell[0], info.cell[1], 1.0], [nx, ny, 1])
                .map_err(|e| e.to_string())?;
            let mut bytes = Vec::new();
            grid_out::png_map(&mut bytes, &plan, &depth, Slice { axis: 2, index: 0 }, &legend)
                .map_err(|e| format!("{}: {e}", png.display()))?;
            std::fs::write(png, bytes)
                .map_err(|e| format!("{}: cannot write: {e}", png.display()))?;
        }
    }
    Ok(report)
}
