//! `meshvol grid`: the volume of the solid in each cell of a regular grid, written as
//! `.npy`, `.vti` or `.csv`, with a summary as text or JSON (and a picture of a slice).

use crate::input;
use crate::solid::{self, SolidArgs};
use clap::Args;
use meshvol::grid::{bytes_text, cell_volumes, occupancy, union_cell_volumes, Grid};
use meshvol::{mass_properties, Point, Surface};
use meshvol_io::grid_out::{self, Slice};
use serde::Serialize;
use std::fmt::Write as _;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

#[derive(Args)]
pub struct GridArgs {
    /// Mesh files; several are measured together (their cell volumes add up), or with
    /// --union as the union of their solids.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Cells along x, y and z.
    #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_cells, required_unless_present = "pitch", conflicts_with = "pitch")]
    cells: Option<[usize; 3]>,
    /// Cell size: H for cubic cells, or HX,HY,HZ; enough cells to cover the bounds.
    #[arg(long, value_name = "H[,HY,HZ]", value_parser = parse_pitch)]
    pitch: Option<[f64; 3]>,
    /// The grid's box (default: the meshes' bounding box).
    #[arg(long, value_name = "X0,Y0,Z0,X1,Y1,Z1", value_parser = parse_bounds, allow_hyphen_values = true)]
    bounds: Option<(Point, Point)>,
    /// Where to write the cell values: .npy (float64, shape (NX, NY, NZ), C order), .vti
    /// (VTK image data, cell arrays `volume` and `fraction`) or .csv (non-empty cells).
    #[arg(long, short, value_name = "OUT", value_parser = parse_out)]
    out: Option<PathBuf>,
    /// Store volume / cell volume in .npy instead of volumes.
    #[arg(long)]
    fraction: bool,
    /// Write a PNG picture of the fractions in one slice (with --slice).
    #[arg(long, value_name = "FILE", requires = "slice")]
    png: Option<PathBuf>,
    /// The slice for --png: x=I, y=J or z=K (a cell index).
    #[arg(long, value_name = "AXIS=INDEX", value_parser = parse_slice, requires = "png")]
    slice: Option<Slice>,
    /// Print the summary as one JSON object.
    #[arg(long)]
    json: bool,
    /// Cell volumes of the union of the bodies (the files, or the shells of a single
    /// file): overlaps count once.
    #[arg(long)]
    union: bool,
    #[command(flatten)]
    solid: SolidArgs,
}

fn numbers<T: std::str::FromStr>(s: &str, n: &[usize], what: &str) -> Result<Vec<T>, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if !n.contains(&parts.len()) {
        let counts: Vec<String> = n.iter().map(|k| k.to_string()).collect();
        return Err(format!("'{s}': expected {} comma-separated {what}", counts.join(" or ")));
    }
    parts.iter().map(|p| p.parse::<T>().map_err(|_| format!("'{p}' is not {what}"))).collect()
}

fn parse_cells(s: &str) -> Result<[usize; 3], String> {
    let v: Vec<usize> = numbers(s, &[3], "whole numbers of cells")?;
    if v.contains(&0) {
        return Err(format!("'{s}': every axis needs at least one cell"));
    }
    Ok([v[0], v[1], v[2]])
}

fn parse_pitch(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = numbers(s, &[1, 3], "numbers")?;
    if v.iter().any(|h| !(h.is_finite() && *h > 0.0)) {
        return Err(format!("'{s}': cell sizes must be positive"));
    }
    Ok(if v.len() == 1 { [v[0]; 3] } else { [v[0], v[1], v[2]] })
}

fn parse_bounds(s: &str) -> Result<(Point, Point), String> {
    let v: Vec<f64> = numbers(s, &[6], "numbers")?;
    if v.iter().any(|x| !x.is_finite()) {
        return Err(format!("'{s}': bounds must be finite"));
    }
    let (min, max) = ([v[0], v[1], v[2]], [v[3], v[4], v[5]]);
    if let Some(a) = (0..3).find(|&a| max[a] <= min[a]) {
        let axis = ["x", "y", "z"][a];
        return Err(format!("'{s}': {axis}1 must be greater than {axis}0"));
    }
    Ok((min, max))
}

fn parse_out(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match extension(&path).as_deref() {
        Some("npy" | "vti" | "csv") => Ok(path),
        _ => Err(format!("'{s}': the output must end in .npy, .vti or .csv")),
    }
}

fn parse_slice(s: &str) -> Result<Slice, String> {
    let (axis, index) =
        s.split_once('=').ok_or_else(|| format!("'{s}': expected x=I, y=J or z=K"))?;
    let axis = match axis.trim() {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        _ => return Err(format!("'{s}': the axis must be x, y or z")),
    };
    let index =
        index.trim().parse().map_err(|_| format!("'{s}': the index must be a whole number"))?;
    Ok(Slice { axis, index })
}

fn extension(path: &Path) -> Option<String> {
    path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase)
}

/// Memory the machine has available, from /proc/meminfo where there is one.
pub fn available_memory() -> Option<u128> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses a grid whose arrays (`arrays` f64 values per cell) would not fit in the
/// memory available, naming what it would need.
pub fn check_memory(grid: &Grid, arrays: u128) -> Result<(), String> {
    let need = grid.array_bytes() * arrays;
    if let Some(available) = available_memory() {
        if need > available {
            let [nx, ny, nz] = grid.counts;
            let cells = nx as u128 * ny as u128 * nz as u128;
            return Err(format!(
                "a {nx}×{ny}×{nz} grid has {cells} cells and would need {} of memory; {} is available: use fewer cells",
                bytes_text(need),
                bytes_text(available)
            ));
        }
    }
    Ok(())
}

#[derive(Serialize)]
struct BoundsReport {
    min: Point,
    max: Point,
}

/// The summary. Field names are the JSON keys.
#[derive(Serialize)]
struct GridReport {
    files: Vec<String>,
    /// The grid's box.
    bounds: BoundsReport,
    /// `mesh` (the bounding box of the meshes, grown to whole cells with --pitch) or
    /// `given` (--bounds).
    bounds_from: &'static str,
    cells: [usize; 3],
    cell_size: [f64; 3],
    /// Σ of the cells.
    total: f64,
    /// The meshes' volume: Σ of signed volumes (with --union, of each body's |volume|,
    /// which counts overlaps more than once).
    mesh_volume: f64,
    union: bool,
    /// Bodies (with --union).
    bodies: usize,
    cells_full: usize,
    cells_partial: usize,
    cells_empty: usize,
    /// Columns of the union left at their lower bound (could not be resolved exactly).
    columns_unresolved: usize,
    /// Seconds spent computing the cell volumes.
    seconds: f64,
    out: Option<String>,
    png: Option<String>,
    /// The readers' warnings and the reasons to doubt each file's solid, as
    /// `FILE: warning`.
    warnings: Vec<String>,
}

/// Several surfaces read as one (their faces one after another).
struct Together<S> {
    surfaces: Vec<S>,
    starts: Vec<usize>,
}

impl<S: Surface> Together<S> {
    fn new(surfaces: Vec<S>) -> Self {
        let mut starts = vec![0];
        for s in &surfaces {
            starts.push(starts.last().copied().unwrap_or(0) + s.face_count());
        }
        Together { surfaces, starts }
    }
}

impl<S: Surface> Surface for Together<S> {
    fn face_count(&self) -> usize {
        self.starts.last().copied().unwrap_or(0)
    }

    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        let s = self.starts.partition_point(|&start| start <= face) - 1;
        self.surfaces[s].fan(face - self.starts[s], triangle)
    }
}

/// Runs the command: the report on stdout, an error on stderr with exit status 1.
pub fn run(args: GridArgs, quiet: bool) -> ExitCode {
    match measure(args, quiet) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn measure(args: GridArgs, quiet: bool) -> Result<(), String> {
    let progress = input::Progress::new(&args.files, quiet);
    let mut inputs = Vec::new();
    let mut warnings = Vec::new();
    for path in &args.files {
        let input = solid::read(path, args.solid.check(), &progress)?;
        for w in &input.warnings {
            progress.warn(&input.name, w);
            warnings.push(format!("{}: {w}", input.name));
        }
        progress.done(path);
        inputs.push(input);
    }
    progress.finish();
    let together = Together::new(inputs.iter().map(solid::Input::surface).collect());
    let mp = mass_properties(&together);
    let bodies = if args.union { solid::union_bodies(&inputs) } else { Vec::new() };
    let bodies: Vec<_> = bodies.into_iter().map(|b| b.surface).collect();
    let (min, max, bounds_from) = match args.bounds {
        Some((min, max)) => (min, max, "given"),
        None => {
            let b = mp.bounds.ok_or("no vertices: there is no surface to measure")?;
            (b.min, b.max, "mesh")
        }
    };
    let grid = match (args.cells, args.pitch) {
        (Some(counts), _) => Grid::from_bounds(min, max, counts),
        (None, Some(pitch)) => Grid::with_pitch(min, max, pitch),
        (None, None) => return Err("give --cells NX,NY,NZ or --pitch H".into()),
    }
    .map_err(|e| match e {
        meshvol::grid::GridError::EmptyBounds { .. } if bounds_from == "mesh" => {
            format!("{e}; the meshes are flat: give --bounds")
        }
        e => e.to_string(),
    })?;
    // The cell array, and with --union four more per-cell arrays.
    check_memory(&grid, if args.union { 5 } else { 1 })?;
    let start = Instant::now();
    let (volumes, columns_unresolved) = if args.union {
        union_cell_volumes(&bodies, &grid).map_err(|e| e.to_string())?
    } else {
        (cell_volumes(&together, &grid).map_err(|e| e.to_string())?, 0)
    };
    let seconds = start.elapsed().as_secs_f64();
    let mesh_volume = if args.union {
        bodies.iter().map(|b| mass_properties(b).signed_volume.abs()).sum()
    } else {
        mp.signed_volume
    };

    if let Some(out) = &args.out {
        let file = std::fs::File::create(out)
            .map_err(|e| format!("{}: cannot create: {e}", out.display()))?;
        let mut w = BufWriter::new(file);
        let written = match extension(out).as_deref() {
            Some("npy") => grid_out::npy(&mut w, &grid, &volumes, args.fraction),
            Some("vti") => grid_out::vti(&mut w, &grid, &volumes),
            _ => grid_out::csv(&mut w, &grid, &volumes).map(|_| ()),
        };
        written.and_then(|()| w.flush()).map_err(|e| format!("{}: {e}", out.display()))?;
    }
    if let (Some(png), Some(slice)) = (&args.png, args.slice) {
        let mut bytes = Vec::new();
        grid_out::png(&mut bytes, &grid, &volumes, slice).map_err(|e| e.to_string())?;
        std::fs::write(png, bytes).map_err(|e| format!("{}: cannot write: {e}", png.display()))?;
    }
    let occupied = occupancy(&volumes, grid.cell_volume());
    let mut total = meshvol::accumulate::CompensatedSum::default();
    volumes.iter().for_each(|&v| total.add(v));
    let report = GridReport {
        files: args.files.iter().map(|p| p.display().to_string()).collect(),
        bounds: BoundsReport { min: grid.origin, max: grid.max() },
        bounds_from,
        cells: grid.counts,
        cell_size: grid.cell,
        total: total.value(),
        mesh_volume,
        union: args.union,
        bodies: bodies.len(),
        cells_full: occupied.full,
        cells_partial: occupied.partial,
        cells_empty: occupied.empty,
        columns_unresolved,
        seconds,
        out: args.out.as_ref().map(|p| p.display().to_string()),
        png: args.png.as_ref().map(|p| p.display().to_string()),
        warnings,
    };
    let text = if args.json {
        serde_json::to_string(&report).map_err(|e| e.to_string())? + "\n"
    } else {
        text(&report, args.fraction)
    };
    if std::io::stdout().lock().write_all(text.as_bytes()).is_err() {
        return Ok(()); // stdout closed
    }
    Ok(())
}

fn vector(v: [f64; 3]) -> String {
    format!("({}, {}, {})", v[0], v[1], v[2])
}

fn text(r: &GridReport, fraction: bool) -> String {
    let mut s = String::new();
    let [nx, ny, nz] = r.cells;
    let from = if r.bounds_from == "mesh" { "the meshes' bounding box" } else { "--bounds" };
    let _ = writeln!(s, "{}: grid of {nx}×{ny}×{nz} cells", r.files.join(", "));
    let _ = writeln!(
        s,
        "  bounds         {} to {} (from {from})",
        vector(r.bounds.min),
        vector(r.bounds.max)
    );
    let _ = writeln!(s, "  cell size      {}", vector(r.cell_size));
    if r.union {
        let _ = writeln!(
            s,
            "  union of       {} bodies (Σ of their volumes {})",
            r.bodies, r.mesh_volume
        );
        let _ = writeln!(s, "  total          {}", r.total);
        if r.columns_unresolved > 0 {
            let _ = writeln!(
                s,
                "  unresolved     {} columns hold lower bounds in their open cells",
                r.columns_unresolved
            );
        }
    } else {
        let _ = writeln!(s, "  total          {}  (mesh volume {})", r.total, r.mesh_volume);
    }
    let _ = writeln!(
        s,
        "  cells          {} full, {} partial, {} empty",
        r.cells_full, r.cells_partial, r.cells_empty
    );
    if let Some(out) = &r.out {
        let what = match Path::new(out).extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("npy") => format!(
                "float64 {}, shape ({nx}, {ny}, {nz}), C order",
                if fraction { "fractions" } else { "volumes" }
            ),
            Some(e) if e.eq_ignore_ascii_case("vti") => {
                "VTK image data, cell arrays volume and fraction".to_string()
            }
            _ => "i,j,k,volume,fraction of the non-empty cells".to_string(),
        };
        let _ = writeln!(s, "  wrote          {out} ({what})");
    }
    if let Some(png) = &r.png {
        let _ = writeln!(s, "  picture        {png}");
    }
    let _ = writeln!(s, "  time           {:.3} s", r.seconds);
    s
}
