//! `meshvol grid`: the volume of the solid in each cell of a regular grid, written as
//! `.npy`, `.vti` or `.csv`, with a summary as text or JSON (and a picture of a slice).

use crate::driver::{self, Output};
use crate::input::Progress;
use crate::solid::{self, SolidArgs};
use clap::Args;
use meshvol::grid::{
    cut_cells_extras, union_boundary_with, union_cell_volumes_with, CutCells, Extras, Grid,
    UnionBoundary,
};
use meshvol::surface::Joined;
use meshvol::{mass_properties, Point, Surface};
use meshvol_io::grid_out::{self, CellValues, Slice};
use meshvol_report::grid::{
    check_memory, choose, layer_holding, reported_summary, GridAsked, GridReport, GridRun, Spacing,
};
use meshvol_report::reported_cells;
use meshvol_report::subject::{union_bodies, Subject};
use meshvol_report::units::Scale;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

mod backend;
mod zarr;

#[derive(Args)]
#[command(group(clap::ArgGroup::new("spacing").required(true).args(["cells", "pitch"])))]
pub struct GridArgs {
    /// Mesh files; several are measured together (their cell volumes add up), or with
    /// --union as the union of their solids.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    #[command(flatten)]
    walk: crate::walk::WalkArgs,
    /// Cells along x, y and z.
    #[arg(long, value_name = "NX,NY,NZ", value_parser = parse_cells)]
    cells: Option<[usize; 3]>,
    /// Cell size: H for cubic cells, or HX,HY,HZ; enough cells to cover the bounds.
    #[arg(long, value_name = "H[,HY,HZ]", value_parser = parse_pitch)]
    pitch: Option<[f64; 3]>,
    /// The grid's box (default: the meshes' bounding box).
    #[arg(long, value_name = "X0,Y0,Z0,X1,Y1,Z1", value_parser = parse_bounds, allow_hyphen_values = true)]
    bounds: Option<(Point, Point)>,
    /// Where to write the cell values: .npy (float64, shape (NX, NY, NZ), C order), .npz
    /// (NumPy arrays `volume`, `fraction`, `origin`, `cell_size`; with --moments the
    /// cut-cell arrays too), .vti (VTK image data, cell arrays `volume` and `fraction`, and
    /// with --moments the rest), .csv (non-empty cells), or .zarr (a Zarr v3 group of the
    /// array and its cells' centres, for xarray.open_zarr; written chunk by chunk: for
    /// grids larger than memory; with --moments the cut-cell arrays). Values, origin and cell sizes in the reported units (--units);
    /// with --density, masses (alone in .npy and .zarr, a `mass` array or column beside
    /// `volume` in the others).
    #[arg(long, short, value_name = "OUT", value_parser = parse_out)]
    out: Option<PathBuf>,
    /// The chunk shape of a .zarr output (default 64 cells along each axis, at most the
    /// grid's): memory holds one slab of CX × NY × NZ cells at a time.
    #[arg(long, value_name = "CX,CY,CZ", value_parser = parse_cells)]
    chunks: Option<[usize; 3]>,
    /// Write the cut-cell geometry of every cell to --out (.npz, .vti or .zarr): the solid's
    /// `centroid` in the cell, the surface's `boundary_area`, `boundary_vector` (∫ n dA)
    /// and `boundary_centroid`, and the fraction of each cell face inside the solid,
    /// `aperture_x`, `aperture_y`, `aperture_z` (docs/cells.md).
    #[arg(long, requires = "out")]
    moments: bool,
    /// With --moments: each cell's `inertia` (NX, NY, NZ, 3, 3), the inertia tensor of the
    /// solid in the cell about its centroid, unit density, as `volume` reports a solid's.
    #[arg(long, requires = "moments")]
    second_moments: bool,
    /// With --moments: the centroid of the part of each cell face inside the solid,
    /// `aperture_x_centroid` (NX+1, NY, NZ, 3), `_y_` and `_z_` (NaN where the aperture is 0).
    #[arg(long, requires = "moments")]
    face_centroids: bool,
    /// Store volume / cell volume in .npy or .zarr instead of volumes.
    #[arg(long)]
    fraction: bool,
    /// Write a PNG picture of the fractions in one slice (with --slice).
    #[arg(long, value_name = "FILE", requires = "slice")]
    png: Option<PathBuf>,
    /// The slice for --png: a coordinate, x=X, y=Y or z=Z (the layer of cells that holds
    /// it; on a boundary between two layers, the one above it), or a cell index, i=I,
    /// j=J or k=K (from 0), as `section --plane z=H` takes a coordinate.
    #[arg(long, value_name = "AXIS=VALUE", value_parser = parse_slice, requires = "png", allow_hyphen_values = true)]
    slice: Option<SliceAt>,
    /// Print the summary as one JSON object.
    #[arg(long)]
    json: bool,
    /// Cell volumes of the union of the bodies (the files, or the shells of a single
    /// file): overlaps count once.
    #[arg(long)]
    union: bool,
    #[command(flatten)]
    backend: backend::BackendArgs,
    #[command(flatten)]
    units: crate::units::UnitArgs,
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
        Some("npy" | "npz" | "vti" | "csv" | "zarr") => Ok(path),
        _ => Err(format!("'{s}': the output must end in .npy, .npz, .vti, .csv or .zarr")),
    }
}

/// `--slice`: a coordinate along an axis, or a cell index along one.
#[derive(Clone, Copy, Debug, PartialEq)]
enum SliceAt {
    /// `x=X`, `y=Y`, `z=Z`: the layer of cells holding the coordinate.
    Coordinate { axis: usize, value: f64 },
    /// `i=I`, `j=J`, `k=K`: the layer with this index.
    Index { axis: usize, index: usize },
}

const SLICE_FORMS: &str = "x=X, y=Y or z=Z (a coordinate) or i=I, j=J or k=K (a cell index)";

fn parse_slice(s: &str) -> Result<SliceAt, String> {
    let (axis, value) =
        s.split_once('=').ok_or_else(|| format!("'{s}': expected {SLICE_FORMS}"))?;
    let value = value.trim();
    match axis.trim() {
        a @ ("x" | "y" | "z") => {
            let axis = usize::from(a.as_bytes()[0] - b'x');
            match value.parse::<f64>() {
                Ok(value) if value.is_finite() => Ok(SliceAt::Coordinate { axis, value }),
                _ => Err(format!("'{s}': the coordinate must be a number")),
            }
        }
        a @ ("i" | "j" | "k") => {
            let axis = usize::from(a.as_bytes()[0] - b'i');
            let index = value.parse().map_err(|_| {
                format!("'{s}': a cell index must be a whole number from 0 (for a coordinate use {}={value})", ["x", "y", "z"][axis])
            })?;
            Ok(SliceAt::Index { axis, index })
        }
        _ => Err(format!("'{s}': expected {SLICE_FORMS}")),
    }
}

/// The layer of cells `at` names in `grid`: a coordinate's is the one holding it
/// (`layer_holding`).
fn slice_of(at: SliceAt, grid: &meshvol::grid::Grid) -> Result<Slice, String> {
    let name = |axis: usize| ["x", "y", "z"][axis];
    match at {
        SliceAt::Index { axis, index } => {
            let n = grid.counts[axis];
            if index >= n {
                let letter = ["i", "j", "k"][axis];
                return Err(format!(
                    "--slice {letter}={index} is outside the grid ({letter} from 0 to {})",
                    n - 1
                ));
            }
            Ok(Slice { axis, index })
        }
        SliceAt::Coordinate { axis, value } => {
            let index = layer_holding(grid, axis, value).ok_or_else(|| {
                let plane = |k: usize| grid.origin[axis] + k as f64 * grid.cell[axis];
                format!(
                    "--slice {}={value} is outside the grid ({} from {} to {})",
                    name(axis),
                    name(axis),
                    plane(0),
                    plane(grid.counts[axis])
                )
            })?;
            Ok(Slice { axis, index })
        }
    }
}

fn extension(path: &Path) -> Option<String> {
    path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase)
}

/// Runs the command: one summary for all the files.
pub fn run(args: GridArgs, quiet: bool) -> ExitCode {
    // Usage errors, before any file is read: an OpenCL device asked for (--backend
    // opencl, --opencl-device) with what only the CPU computes (the cut cells' extra
    // arrays, the union, a .zarr written row by row); an OpenCL device asked for that
    // is not there (no OpenCL library, no such device, no f64).
    let zarr = args.out.as_deref().and_then(extension).as_deref() == Some("zarr");
    for (cpu_only, what) in [
        (args.second_moments, "--second-moments"),
        (args.face_centroids, "--face-centroids"),
        (args.union, "--union"),
        (zarr, "a .zarr output"),
    ] {
        if let (true, Err(e)) = (cpu_only, args.backend.cpu_only(what)) {
            eprintln!("meshvol: error: {e}");
            return ExitCode::from(2);
        }
    }
    if args.backend.forces_opencl() {
        if let Err(e) = args.backend.choice().device() {
            eprintln!("meshvol: error: --backend opencl: {e}");
            return ExitCode::from(2);
        }
    }
    let output = Output { json: args.json, quiet, csv: false };
    let files = args.walk.expand(&args.files, meshvol_io::InputKind::Mesh);
    driver::once(&files, output, |progress| measure(&args, &files.files, progress))
}

fn measure(args: &GridArgs, files: &[PathBuf], progress: &Progress) -> Result<GridReport, String> {
    let mut inputs = Vec::new();
    for path in files {
        let input = solid::read(path, args.solid.check(), progress)?;
        progress.done(path);
        inputs.push(input);
    }
    let subjects = solid::subjects(&inputs);
    let warnings = meshvol_report::subject::input_warnings(&subjects);
    let together = Joined::new(subjects.iter().map(Subject::measured).collect());
    let mp = mass_properties(&together);
    let bodies = if args.union { union_bodies(&subjects) } else { Vec::new() };
    let bodies: Vec<_> = bodies.into_iter().map(|b| b.surface).collect();
    let spacing = match (args.cells, args.pitch) {
        (Some(counts), _) => Spacing::Cells(counts),
        (None, Some(pitch)) => Spacing::Pitch(pitch),
        (None, None) => return Err("give --cells NX,NY,NZ or --pitch H".into()),
    };
    let (grid, bounds_from) = choose(args.bounds, mp.bounds, spacing, "--bounds")?;
    // The units, resolved before any work: the kernels run in the file's coordinates,
    // and every array is converted once (`reported_cells`) before a sink reads it.
    let files: Vec<_> = inputs.iter().map(|i| (i.source.name(), i.source.unit)).collect();
    let (scale, unit_warnings) = Scale::resolve_all(&args.units.options(), &files)?;
    let reported = reported_cells::grid(&scale, &grid)?;
    let density = scale.mass_per_volume();
    let mesh_volume = if args.union {
        bodies.iter().map(|b| mass_properties(b).signed_volume.abs()).sum()
    } else {
        mp.signed_volume
    };
    let asked = GridAsked {
        union: args.union.then_some(bodies.len()),
        out: args.out.as_ref().map(|p| p.display().to_string()),
        fraction: args.fraction,
        png: args.png.as_ref().map(|p| p.display().to_string()),
        moments: args.moments,
        second_moments: args.second_moments,
        face_centroids: args.face_centroids,
    };
    let names = files.iter().map(|(name, _)| name.to_string()).collect();
    let warnings = warnings.into_iter().chain(unit_warnings);
    let mut run = GridRun::new(names, bounds_from, mesh_volume, asked, &scale, warnings);
    let out_kind = args.out.as_deref().and_then(extension);
    if args.moments && !matches!(out_kind.as_deref(), Some("npz" | "vti" | "zarr")) {
        return Err("--moments writes several arrays: give --out cells.npz, cells.vti or \
                    cells.zarr"
            .into());
    }
    let extras =
        Extras { second_moments: args.second_moments, face_centroids: args.face_centroids };
    let zarr = args.out.as_deref().filter(|out| extension(out).as_deref() == Some("zarr"));
    if let Some(out) = zarr {
        if (args.union && !args.moments) || args.png.is_some() {
            return Err("--union (without --moments) and --png need the whole grid in memory: \
                        write .npy, .vti or .csv with them, not .zarr"
                .into());
        }
        let write = zarr::Write { grid: &grid, scale: &scale, out, chunks: args.chunks };
        let mut report = if args.union {
            // The union's boundary is measured as the solids' surface is, row by row;
            // the seconds computing include finding it.
            let start = Instant::now();
            let boundary = boundary_of(&bodies, progress)?;
            let finding = start.elapsed().as_secs_f64();
            let mut report = write.cut_cells(&boundary, extras, run, progress)?;
            report.run.seconds += finding;
            report
        } else if args.moments {
            write.cut_cells(&together, extras, run, progress)?
        } else {
            write.cells(&together, CellValues::asked(args.fraction, density), run, progress)?
        };
        report.run.mass = scale.mass(report.cells.total);
        return Ok(report);
    }
    if args.chunks.is_some() {
        return Err("--chunks is for a .zarr output (--out cells.zarr)".into());
    }
    // The cell array, with --union four more per-cell arrays, with --moments the cut cells.
    let arrays = if args.moments {
        CutCells::bytes_with(&grid, extras) / grid.array_bytes().max(1) + 1
    } else if args.union {
        5
    } else {
        1
    };
    check_memory(grid.counts, arrays, "grid")?;
    progress.stage_all("computing cell volumes");
    let start = Instant::now();
    let mut cut = None;
    let (mut volumes, columns_unresolved) = if args.union && args.moments {
        // The cut cells of the union: those of its boundary, the pieces of the solids'
        // surfaces outside the other solids.
        let boundary = boundary_of(&bodies, progress)?;
        cut = Some(cut_cells_of(&boundary, &grid, extras, progress)?);
        (Vec::new(), 0)
    } else if args.union {
        let hook = progress.kernel("computing the union's cell volumes".to_string());
        union_cell_volumes_with(&bodies, &grid, &hook).map_err(|e| e.to_string())?
    } else if args.moments {
        cut = Some(args.backend.cut_cells(&together, &grid, extras, progress)?);
        (Vec::new(), 0)
    } else {
        (args.backend.cell_volumes(&together, &grid, progress)?, 0)
    };
    run.seconds = start.elapsed().as_secs_f64();
    run.columns_unresolved = columns_unresolved;
    match &mut cut {
        Some(cells) => reported_cells::cut_cells(&scale, cells)?,
        None => reported_cells::volumes(&scale, &mut volumes),
    }
    // The cut cells hold the volumes (the same bits as cell_volumes'): not copied.
    let volumes: &[f64] = cut.as_ref().map_or(&volumes, |c| &c.volume);

    if let Some(out) = &args.out {
        progress.stage("writing", out);
        let file = std::fs::File::create(out)
            .map_err(|e| format!("{}: cannot create: {e}", out.display()))?;
        let mut w = BufWriter::new(file);
        let values = CellValues::asked(args.fraction, density);
        let written = match (out_kind.as_deref(), &cut) {
            (Some("npz"), Some(cells)) => grid_out::npz_cut_cells(&mut w, cells, density),
            (Some("npz"), None) => grid_out::npz(&mut w, &reported, volumes, density),
            (Some("vti"), Some(cells)) => grid_out::vti_cut_cells(&mut w, cells, density),
            (Some("npy"), _) => grid_out::npy(&mut w, &reported, volumes, values),
            (Some("vti"), None) => grid_out::vti(&mut w, &reported, volumes, density),
            _ => grid_out::csv(&mut w, &reported, volumes, density).map(|_| ()),
        };
        written.and_then(|()| w.flush()).map_err(|e| format!("{}: {e}", out.display()))?;
    }
    if let (Some(png), Some(at)) = (&args.png, args.slice) {
        progress.stage("drawing", png);
        // The slice is asked in the file's coordinates; drawn in the reported ones.
        let slice = slice_of(at, &grid)?;
        let mut bytes = Vec::new();
        grid_out::png(&mut bytes, &reported, volumes, slice).map_err(|e| e.to_string())?;
        std::fs::write(png, bytes).map_err(|e| format!("{}: cannot write: {e}", png.display()))?;
    }
    Ok(reported_summary(&scale, &reported, volumes, run))
}

/// The cut cells of `surface` on the whole of `grid`, on the CPU (the union's boundary).
fn cut_cells_of<S: Surface + ?Sized>(
    surface: &S,
    grid: &Grid,
    extras: Extras,
    progress: &Progress,
) -> Result<CutCells, String> {
    let hook = progress.kernel("computing the cut cells".to_string());
    let whole = grid.counts.map(|n| 0..n);
    cut_cells_extras(surface, grid, &whole, extras, &hook).map_err(|e| e.to_string())
}

/// The boundary of the union of `bodies` (`union_boundary`): what `--union --moments`
/// measures.
fn boundary_of<S: Surface>(bodies: &[S], progress: &Progress) -> Result<UnionBoundary, String> {
    let hook = progress.kernel("resolving the union's boundary".to_string());
    union_boundary_with(bodies, &hook).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slices_by_coordinate_pick_the_layer_holding_it() {
        let grid = meshvol::grid::Grid::new([0.0, 0.0, -1.0], [1.0, 1.0, 0.1], [2, 2, 30]).unwrap();
        let at = |s: &str| slice_of(parse_slice(s).unwrap(), &grid);
        assert_eq!(at("z=-1").unwrap(), Slice { axis: 2, index: 0 });
        assert_eq!(at("z=0.25").unwrap(), Slice { axis: 2, index: 12 });
        // On a boundary: the layer above it; on the far face: the last layer.
        assert_eq!(at("x=1").unwrap(), Slice { axis: 0, index: 1 });
        assert_eq!(at("z=2").unwrap(), Slice { axis: 2, index: 29 });
        // Each boundary c_k picks layer k, with c_k computed as the grid computes it.
        for k in 0..30 {
            let c = -1.0 + k as f64 * 0.1;
            assert_eq!(
                slice_of(SliceAt::Coordinate { axis: 2, value: c }, &grid).unwrap().index,
                k
            );
        }
        assert_eq!(at("k=29").unwrap(), Slice { axis: 2, index: 29 });
        assert!(at("k=30").unwrap_err().contains("k from 0 to 29"));
        assert!(at("z=2.01").unwrap_err().contains("outside the grid"));
        assert!(parse_slice("k=1.5").unwrap_err().contains("z=1.5"));
        assert!(parse_slice("w=1").is_err() && parse_slice("z=nan").is_err());
    }
}
