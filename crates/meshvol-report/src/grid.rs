//! `grid`: the summary of a grid of cell volumes, the grid's choice from the arguments,
//! and the memory estimate that refuses a grid before it is allocated.

use crate::number::{count, num, vector};
use crate::units::{Mass, Scale, UnitNames};
use crate::Report;
use meshvol::accumulate::CompensatedSum;
use meshvol::grid::{bytes_text, occupancy, Grid, GridError, Occupancy};
use meshvol::{Bounds, Point};
use meshvol_io::memory::available_memory;
use rayon::prelude::*;
use serde::Serialize;
use std::fmt::Write;
use std::path::Path;

/// How the cells are given.
#[derive(Clone, Copy, Debug)]
pub enum Spacing {
    /// NX, NY, NZ cells across the bounds.
    Cells([usize; 3]),
    /// Cells of this size from the lower bound, enough to cover the upper one.
    Pitch([f64; 3]),
}

/// The grid the arguments describe: over `given` bounds, or else the meshes' bounding
/// box (`mesh`). Returns it and where its bounds came from (`given` or `mesh`).
/// `bounds_argument` names the argument that gives bounds, for the message about a flat
/// mesh.
pub fn choose(
    given: Option<(Point, Point)>,
    mesh: Option<Bounds>,
    spacing: Spacing,
    bounds_argument: &str,
) -> Result<(Grid, &'static str), String> {
    let (min, max, from) = match given {
        Some((min, max)) => (min, max, "given"),
        None => {
            let b = mesh.ok_or("no vertices: there is no surface to measure")?;
            (b.min, b.max, "mesh")
        }
    };
    let grid = match spacing {
        Spacing::Cells(counts) => Grid::from_bounds(min, max, counts),
        Spacing::Pitch(pitch) => Grid::with_pitch(min, max, pitch),
    }
    .map_err(|e| match e {
        GridError::EmptyBounds { .. } if from == "mesh" => {
            format!("{e}; the mesh is flat: give {bounds_argument}")
        }
        e => e.to_string(),
    })?;
    Ok((grid, from))
}

/// The layer of cells of `grid` along `axis` holding the coordinate `value` (`grid
/// --slice z=Z`, and the page's grid slice): the cell [c_k, c_(k+1)) holding it, where
/// c_k = origin + k · cell as the grid computes it (so a coordinate on the boundary of
/// two layers picks the upper one), and the grid's far face the last layer. `None`
/// outside the grid.
pub fn layer_holding(grid: &Grid, axis: usize, value: f64) -> Option<usize> {
    let n = grid.counts[axis];
    let plane = |k: usize| grid.origin[axis] + k as f64 * grid.cell[axis];
    if !(value >= plane(0) && value <= plane(n)) {
        return None;
    }
    let guess = ((value - plane(0)) / grid.cell[axis]).floor();
    let mut k = if guess > 0.0 { (guess as usize).min(n - 1) } else { 0 };
    while k > 0 && value < plane(k) {
        k -= 1;
    }
    while k + 1 < n && value >= plane(k + 1) {
        k += 1;
    }
    Some(k)
}

/// Refuses `counts` cells held in memory at once (`arrays` f64 values per cell) where
/// they would not fit in the memory available, naming what they would need: an
/// allocation the system overcommits would kill the process later instead. The memory
/// available is the readers' ([`available_memory`]: `MESHVOL_MEMORY_LIMIT`, else the
/// system's), so a grid and a file are held to the same figure. `what` names
/// the cells: `grid`, `block`, or a `chunk row` of a grid written chunk by chunk.
pub fn check_memory(counts: [usize; 3], arrays: u128, what: &str) -> Result<(), String> {
    let cells = counts.iter().map(|&n| n as u128).product::<u128>();
    let need = cells * 8 * arrays;
    match available_memory() {
        Some(available) if need > available => {
            let [nx, ny, nz] = counts;
            let advice = if what == "grid" { "use fewer cells" } else { "use smaller chunks" };
            Err(format!(
                "a {nx}×{ny}×{nz} {what} has {cells} cells and would need {} of memory; {} is \
                 available: {advice}",
                bytes_text(need),
                bytes_text(available)
            ))
        }
        _ => Ok(()),
    }
}

#[derive(Clone, Debug, Serialize)]
pub struct GridBounds {
    pub min: Point,
    pub max: Point,
}

/// The grid and what its cells hold.
#[derive(Clone, Debug, Serialize)]
pub struct CellSummary {
    /// The grid's box.
    pub bounds: GridBounds,
    pub cells: [usize; 3],
    pub cell_size: [f64; 3],
    /// Σ of the cells.
    pub total: f64,
    pub cells_full: usize,
    pub cells_partial: usize,
    pub cells_empty: usize,
}

/// How the cells were computed and where they went: what the caller knows.
#[derive(Clone, Debug, Serialize)]
pub struct GridRun {
    pub files: Vec<String>,
    /// `mesh` (the bounding box of the meshes, grown to whole cells with a pitch) or
    /// `given`.
    pub bounds_from: &'static str,
    /// The meshes' volume: Σ of signed volumes (for a union, of each body's |volume|,
    /// which counts overlaps more than once).
    pub mesh_volume: f64,
    /// Whether the cells are the union's, and of how many bodies.
    pub union: bool,
    pub bodies: usize,
    /// Columns of the union left at their lower bound (could not be resolved exactly).
    pub columns_unresolved: usize,
    /// Seconds spent computing the cell volumes.
    pub seconds: f64,
    pub out: Option<String>,
    /// The chunk shape of a `.zarr` output (written chunk row by chunk row), else `None`.
    pub chunks: Option<[usize; 3]>,
    /// Whether `out` holds fractions (volume / cell volume) instead of volumes.
    pub fraction: bool,
    pub png: Option<String>,
    /// Whether `out` holds the cut-cell geometry (`--moments`) beside the volumes.
    pub moments: bool,
    /// Whether it holds each cell's `inertia` too (`--second-moments`).
    pub second_moments: bool,
    /// Whether it holds the faces' wetted centroids too (`--face-centroids`).
    pub face_centroids: bool,
    /// The units the numbers are in (`--units`, or the unit the file declares); null:
    /// the file's own numbers, unit unknown.
    pub units: Option<UnitNames>,
    /// With `--density`: `density`, `density_unit`, `mass`, `mass_unit`.
    #[serde(flatten)]
    pub mass: Option<Mass>,
    /// The readers' warnings and the reasons to doubt each file's solid, as
    /// `FILE: warning`.
    pub warnings: Vec<String>,
}

/// What a grid run was asked to write: the command's output flags (Python's and the
/// page's arguments).
#[derive(Clone, Debug, Default)]
pub struct GridAsked {
    /// The union's cells, of this many bodies (`--union`).
    pub union: Option<usize>,
    pub out: Option<String>,
    pub fraction: bool,
    pub png: Option<String>,
    pub moments: bool,
    pub second_moments: bool,
    pub face_centroids: bool,
}

impl GridRun {
    /// A run over `files` (each file's name), its grid's bounds from `bounds_from`, of
    /// meshes whose volume is `mesh_volume` in the files' units: that volume converted
    /// and its units named by `scale`, the inputs' `warnings` followed by the units'
    /// own. The time, the mass and the unresolved columns are the run's to fill in.
    pub fn new(
        files: Vec<String>,
        bounds_from: &'static str,
        mesh_volume: f64,
        asked: GridAsked,
        scale: &Scale,
        warnings: impl IntoIterator<Item = String>,
    ) -> GridRun {
        GridRun {
            files,
            bounds_from,
            mesh_volume: scale.volume(mesh_volume),
            union: asked.union.is_some(),
            bodies: asked.union.unwrap_or(0),
            columns_unresolved: 0,
            seconds: 0.0,
            out: asked.out,
            chunks: None,
            fraction: asked.fraction,
            units: scale.names(),
            mass: None,
            png: asked.png,
            moments: asked.moments,
            second_moments: asked.second_moments,
            face_centroids: asked.face_centroids,
            warnings: warnings.into_iter().collect(),
        }
    }
}

/// The summary of a grid. Field names are the JSON keys.
#[derive(Clone, Debug, Serialize)]
pub struct GridReport {
    /// The files, joined by `, `.
    pub file: String,
    #[serde(flatten)]
    pub cells: CellSummary,
    #[serde(flatten)]
    pub run: GridRun,
}

/// The total and occupancy of a grid's cells, taken in runs of whole x planes in C order
/// (a grid written chunk row by chunk row never holds all of them): the same total as of
/// the whole array at once.
///
/// Each plane is tallied in fixed blocks of [`TALLY_BLOCK`] cells, in parallel, and the
/// blocks' compensated sums are merged in cell order: the blocks depend on the grid's
/// shape alone, so the total is the same bits at any thread count and for any split of
/// the grid into runs of planes. (A serial pass over a 512³ grid took longer than the
/// kernel on 16 threads.)
#[derive(Clone, Debug, Default)]
pub struct CellTally {
    total: CompensatedSum,
    occupied: Occupancy,
}

/// Cells per block of a plane in [`CellTally`].
pub const TALLY_BLOCK: usize = 1 << 14;

impl CellTally {
    /// Adds the next run of cells of `grid`: whole x planes (`ny·nz` cells each).
    pub fn add(&mut self, grid: &Grid, volumes: &[f64]) {
        let plane = (grid.counts[1] * grid.counts[2]).max(1);
        debug_assert_eq!(volumes.len() % plane, 0, "a tally takes whole x planes");
        let cell_volume = grid.cell_volume();
        let blocks: Vec<(CompensatedSum, Occupancy)> = volumes
            .par_chunks(plane)
            .flat_map(|plane| {
                plane.par_chunks(TALLY_BLOCK).map(|block| {
                    let mut total = CompensatedSum::default();
                    block.iter().for_each(|&v| total.add(v));
                    (total, occupancy(block, cell_volume))
                })
            })
            .collect();
        for (total, o) in &blocks {
            self.total.merge(total);
            self.occupied.empty += o.empty;
            self.occupied.partial += o.partial;
            self.occupied.full += o.full;
        }
    }
}

/// The summary of `volumes`, the cells of `grid`.
pub fn summary(grid: &Grid, volumes: &[f64], run: GridRun) -> GridReport {
    let mut tally = CellTally::default();
    tally.add(grid, volumes);
    tallied_summary(grid, &tally, run)
}

/// The summary of the cells of `grid` tallied in `tally`.
pub fn tallied_summary(grid: &Grid, tally: &CellTally, run: GridRun) -> GridReport {
    let (total, occupied) = (&tally.total, tally.occupied);
    GridReport {
        file: run.files.join(", "),
        cells: CellSummary {
            bounds: GridBounds { min: grid.origin, max: grid.max() },
            cells: grid.counts,
            cell_size: grid.cell,
            total: total.value(),
            cells_full: occupied.full,
            cells_partial: occupied.partial,
            cells_empty: occupied.empty,
        },
        run,
    }
}

impl Report for GridReport {
    fn file(&self) -> &str {
        &self.file
    }

    fn warnings(&self) -> &[String] {
        &self.run.warnings
    }

    fn text(&self) -> String {
        let (r, c) = (&self.run, &self.cells);
        let mut s = String::new();
        let [nx, ny, nz] = c.cells;
        let from = if r.bounds_from == "mesh" { "the meshes' bounding box" } else { "--bounds" };
        let _ = writeln!(s, "{}: grid of {nx}×{ny}×{nz} cells", self.file);
        let _ = writeln!(
            s,
            "  bounds         {} to {} (from {from})",
            vector(c.bounds.min, 15),
            vector(c.bounds.max, 15)
        );
        let _ = writeln!(s, "  cell size      {}", vector(c.cell_size, 15));
        if r.union {
            let _ = writeln!(
                s,
                "  union of       {} (Σ of their volumes {})",
                count(r.bodies, "body", "bodies"),
                num(r.mesh_volume, 15)
            );
            let _ = writeln!(s, "  total          {}", num(c.total, 15));
            if r.columns_unresolved > 0 {
                let _ = writeln!(
                    s,
                    "  unresolved     {} hold lower bounds in their open cells",
                    count(r.columns_unresolved, "column", "columns")
                );
            }
        } else {
            let _ = writeln!(
                s,
                "  total          {}  (mesh volume {})",
                num(c.total, 15),
                num(r.mesh_volume, 15)
            );
        }
        let _ = writeln!(
            s,
            "  cells          {} full, {} partial, {} empty",
            c.cells_full, c.cells_partial, c.cells_empty
        );
        if let Some(out) = &r.out {
            // With a density the files hold masses too: alone in a one-array file, beside
            // the volumes in the others.
            let one = if r.fraction {
                "fractions"
            } else if r.mass.is_some() {
                "masses"
            } else {
                "volumes"
            };
            let mass = if r.mass.is_some() { ", mass" } else { "" };
            let what = match Path::new(out).extension().and_then(|e| e.to_str()) {
                Some(e) if e.eq_ignore_ascii_case("npy") => {
                    format!("float64 {one}, shape ({nx}, {ny}, {nz}), C order")
                }
                Some(e) if e.eq_ignore_ascii_case("vti") && r.moments => format!(
                    "VTK image data: cell arrays volume, fraction{mass}, centroid, boundary_area, \
                     boundary_vector, boundary_centroid{}; field arrays aperture_x, _y, _z{}",
                    if r.second_moments { ", inertia" } else { "" },
                    if r.face_centroids { ", aperture_x_centroid, _y_, _z_" } else { "" }
                ),
                Some(e) if e.eq_ignore_ascii_case("vti") => {
                    let arrays = if r.mass.is_some() {
                        "volume, fraction and mass"
                    } else {
                        "volume and fraction"
                    };
                    format!("VTK image data, cell arrays {arrays}")
                }
                Some(e) if e.eq_ignore_ascii_case("npz") && r.moments => format!(
                    "NumPy arrays volume, fraction{mass}, centroid, boundary_area, \
                     boundary_vector, boundary_centroid, aperture_x, _y, _z{}{}, origin, cell_size",
                    if r.second_moments { ", inertia" } else { "" },
                    if r.face_centroids { ", aperture_x_centroid, _y_, _z_" } else { "" }
                ),
                Some(e) if e.eq_ignore_ascii_case("npz") => {
                    format!("NumPy arrays volume, fraction{mass}, origin, cell_size")
                }
                Some(e) if e.eq_ignore_ascii_case("zarr") && r.moments => {
                    let [cx, cy, cz] = r.chunks.unwrap_or(c.cells);
                    format!(
                        "Zarr v3 group of float64 arrays volume, fraction{mass}, centroid, \
                         boundary_area, boundary_vector, boundary_centroid, aperture_x, _y, _z{}{}, \
                         chunks ({cx}, {cy}, {cz}), coordinates x, y, z, x_face, y_face, z_face",
                        if r.second_moments { ", inertia" } else { "" },
                        if r.face_centroids { ", aperture_x_centroid, _y_, _z_" } else { "" }
                    )
                }
                Some(e) if e.eq_ignore_ascii_case("zarr") => {
                    let [cx, cy, cz] = r.chunks.unwrap_or(c.cells);
                    let name = match one {
                        "fractions" => "fraction",
                        "masses" => "mass",
                        _ => "volume",
                    };
                    format!(
                        "Zarr v3 group: float64 {one} `{name}`, shape ({nx}, {ny}, {nz}), chunks \
                         ({cx}, {cy}, {cz}), coordinates x, y, z"
                    )
                }
                _ => {
                    format!("i,j,k,volume,fraction{} of the non-empty cells", mass.replace(' ', ""))
                }
            };
            let _ = writeln!(s, "  wrote          {out} ({what})");
        }
        if let Some(png) = &r.png {
            let _ = writeln!(s, "  picture        {png}");
        }
        let _ = writeln!(s, "  time           {:.3} s", r.seconds);
        s.push_str(&crate::units::units_text(&self.run.units, &self.run.mass));
        s
    }
}

/// The summary of `volumes`, cells already converted to the units of `scale`
/// (`reported_cells`) on the `reported` grid: its total is the sum of what the sinks
/// write. Names the units and, with a density, gives the mass of the total.
pub fn reported_summary(
    scale: &Scale,
    reported: &Grid,
    volumes: &[f64],
    run: GridRun,
) -> GridReport {
    let mut report = summary(reported, volumes, run);
    report.run.units = scale.names();
    report.run.mass = scale.mass(report.cells.total);
    report
}

#[cfg(test)]
mod tests {
    use super::{CellTally, TALLY_BLOCK};
    use meshvol::grid::{Grid, OCCUPANCY_TOLERANCE};

    /// Cells of very different sizes (mantissas of 30 bits, exponents from −60 to 30,
    /// either sign, some within the occupancy tolerances): a plain sum would lose most
    /// of the small ones. Each is an integer multiple of 2⁻⁶⁰, so the exact total is an
    /// integer sum in i128.
    fn cells(n: usize, seed: u64) -> (Vec<f64>, i128) {
        let mut state = seed;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let (mut volumes, mut exact) = (Vec::with_capacity(n), 0i128);
        for _ in 0..n {
            let r = next();
            let mantissa = (r >> 34) as i128; // 30 bits
            let exponent = (r % 91) as i32 - 60;
            let sign = if r & (1 << 20) == 0 { 1 } else { -1 };
            let v = sign as f64 * mantissa as f64 * 2f64.powi(exponent);
            exact += sign * (mantissa << (exponent + 60));
            volumes.push(v);
        }
        (volumes, exact)
    }

    fn tally(grid: &Grid, volumes: &[f64], planes_per_run: usize) -> CellTally {
        let plane = grid.counts[1] * grid.counts[2];
        let mut tally = CellTally::default();
        for run in volumes.chunks(plane * planes_per_run) {
            tally.add(grid, run);
        }
        tally
    }

    #[test]
    fn the_total_is_within_the_compensated_bound_of_the_exact_sum_and_the_same_bits_at_any_split() {
        // Planes of 150·130 cells: more than one block each, the last one short.
        let grid = Grid::from_bounds([0.0; 3], [1.0; 3], [7, 150, 130]).unwrap();
        const { assert!(150 * 130 > TALLY_BLOCK) };
        let (volumes, exact) = cells(7 * 150 * 130, 0x9e37_79b9_7f4a_7c15);
        let whole = tally(&grid, &volumes, 7);
        let exact = exact as f64 * 2f64.powi(-60);
        let magnitude: f64 = volumes.iter().map(|v| v.abs()).sum();
        let (e, n) = (f64::EPSILON / 2.0, volumes.len() as f64);
        // Ogita, Rump and Oishi's bound for a compensated sum (Sum2), doubled for the
        // merging of the blocks: a plain sum's error, about n·e·magnitude, is far beyond.
        let bound = 2.0 * e * exact.abs() + 2.0 * (n * e).powi(2) * magnitude;
        let total = whole.total.value();
        assert!((total - exact).abs() <= bound, "{total} vs exact {exact}, bound {bound}");
        for planes in [1, 2, 3] {
            let split = tally(&grid, &volumes, planes);
            assert_eq!(split.total.value().to_bits(), total.to_bits(), "runs of {planes} planes");
            assert_eq!(split.occupied, whole.occupied);
        }
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let again = pool.install(|| tally(&grid, &volumes, 7));
            assert_eq!(again.total.value().to_bits(), total.to_bits(), "{threads} threads");
        }
    }

    #[test]
    fn occupancy_counts_each_cell_once() {
        let grid = Grid::from_bounds([0.0; 3], [2.0; 3], [3, 128, 130]).unwrap();
        let cell = grid.cell_volume();
        let t = OCCUPANCY_TOLERANCE * cell;
        let kinds = [0.0, t / 2.0, -t, cell, -cell + t / 2.0, cell / 3.0, -cell / 2.0];
        let volumes: Vec<f64> = (0..3 * 128 * 130).map(|i| kinds[(i * 7 + i / 5) % 7]).collect();
        let (mut empty, mut full) = (0, 0);
        for v in &volumes {
            empty += usize::from(v.abs() <= t);
            full += usize::from(v.abs() >= cell - t);
        }
        let tally = tally(&grid, &volumes, 1);
        assert_eq!(tally.occupied.empty, empty);
        assert_eq!(tally.occupied.full, full);
        assert_eq!(tally.occupied.partial, volumes.len() - empty - full);
    }
}
