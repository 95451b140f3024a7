//! The `meshvol` command: a thin layer of arguments and output over the meshvol
//! libraries. Results go to stdout, errors and warnings to stderr; the exit status is 0
//! when every file was measured, 1 when any failed, 2 on a usage error.

mod area;
mod check;
mod grid;
mod hull;
mod input;
mod profile;
mod repair;
mod section;
mod solid;
mod union;
mod units;
mod volume;

use clap::{Args, CommandFactory, Parser, Subcommand};
use meshvol::topology::CheckOptions;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use units::UnitsArg;
use volume::VolumeOptions;

#[derive(Parser)]
#[command(
    name = "meshvol",
    version,
    about = "Measure solids: volume, area, centroid and inertia of mesh files, exactly and fast.",
    after_help = "`meshvol FILE...` is short for `meshvol volume FILE...`."
)]
struct Cli {
    /// Worker threads (default: one per core). Results are identical for any count.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    /// No progress bar and no warnings on stderr (errors are still printed).
    #[arg(long, short, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Volume, area, centroid, inertia, principal axes, mass and bounds of each file.
    Volume(VolumeArgs),
    /// Can the volume be trusted? Closed, manifold, wound which way, shells, cavities,
    /// overlaps, self-intersections. Exits 1 when a file does not bound a volume.
    Check(CheckArgs),
    /// Write the mesh with shells turned outward (cavities inward), degenerate and
    /// duplicate faces removed, vertices welded, and with --cap, holes capped. Says what
    /// changed.
    Repair(RepairArgs),
    /// Area, perimeter, centroid and second moments of polygons (WKT, GeoJSON, x y
    /// lines), per feature and in total; reports self-intersecting and crossing rings.
    Area(area::AreaArgs),
    /// The cross-section of a mesh by a plane: its outline (as WKT or GeoJSON on
    /// request), area, centroid and second moments.
    Section(section::SectionArgs),
    /// Volume, area and centroid of the convex hull of a point cloud (.xyz, .csv, PLY,
    /// or any mesh's vertices); --out writes the hull.
    Hull(hull::HullArgs),
    /// The volume of the solid in each cell of a regular grid (exact, not voxels): .npy,
    /// .vti or .csv, a summary, and a PNG of a slice.
    Grid(grid::GridArgs),
    /// Volume below each level along an axis, slab volumes and section areas (a
    /// strapping table).
    Profile(profile::ProfileArgs),
    /// The volume of the union of overlapping bodies (files, or one file's shells) as a
    /// certified interval, without a boolean mesh.
    Union(union::UnionArgs),
}

#[derive(Args)]
struct RepairArgs {
    /// The mesh to repair.
    #[arg(value_name = "FILE")]
    file: PathBuf,
    /// Where to write the result: .stl (binary), .obj, .ply (binary) or .glb.
    #[arg(short, long, value_name = "OUT")]
    out: PathBuf,
    /// Cap each hole with a fan of triangles from its centroid.
    #[arg(long)]
    cap: bool,
    /// Print what changed as one JSON object.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    topology: TopologyArgs,
}

/// How surfaces are welded (shared by `volume`, `check` and `repair`).
#[derive(Args)]
struct TopologyArgs {
    /// Weld vertices whose coordinates differ by at most T; 0 welds exactly equal
    /// positions only. Default: exactly, and when that leaves holes, again within 1e-9 of
    /// the bounding box diagonal (reported as `weld_tolerance`).
    #[arg(long, value_name = "T", value_parser = non_negative_finite)]
    weld_tolerance: Option<f64>,
}

impl TopologyArgs {
    /// Check options; `intersections` turns on the search for crossing triangles.
    fn options(&self, intersections: bool) -> CheckOptions {
        solid::check_options(self.weld_tolerance, intersections)
    }
}

#[derive(Args)]
struct CheckArgs {
    /// Mesh files.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
    /// Skip the search for crossing triangles (self-intersections; overlapping shells
    /// are then found only by the ray tests).
    #[arg(long)]
    no_intersections: bool,
    #[command(flatten)]
    topology: TopologyArgs,
}

#[derive(Args)]
struct VolumeArgs {
    /// Mesh files: STL (binary or ASCII), OBJ, OFF, PLY, 3MF, glTF/GLB; `-` reads
    /// standard input (format from the content).
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
    /// Print one JSON object per file, one per line.
    #[arg(long)]
    json: bool,
    /// Density, in mass per reported volume unit; scales `mass` and `inertia`.
    #[arg(long, default_value_t = 1.0, value_parser = positive_finite)]
    density: f64,
    /// The file's length unit and the unit to report in: FILE[:REPORT], e.g. `mm`,
    /// `mm:cm`, `in:mL`, or `:REPORT` to convert from the unit the file declares (3MF,
    /// glTF). Units: um, mm, cm, m, in, ft; REPORT may also be mL (lengths in cm) or L
    /// (lengths in dm). Files that declare a unit are reported in it by default.
    #[arg(long, value_name = "FILE[:REPORT]")]
    units: Option<UnitsArg>,
    /// Report the correctly rounded exact signed volume (exact arithmetic; a few times
    /// slower than the default, which is already within `volume_error_bound`).
    #[arg(long)]
    exact: bool,
    /// Accepted for scripts written when the crossing search was optional: it is now
    /// part of the default check (`--no-intersections` skips it).
    #[arg(long, hide = true, conflicts_with_all = ["no_check", "no_intersections"])]
    intersections: bool,
    #[command(flatten)]
    solid: solid::SolidArgs,
}

fn non_negative_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("'{s}' is not a non-negative number")),
    }
}

fn positive_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("'{s}' is not a positive number")),
    }
}

/// Inserts `volume` when the first argument is not a subcommand or a top-level flag, so
/// `meshvol part.stl` means `meshvol volume part.stl`.
fn with_default_command(mut args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let command = Cli::command();
    let known = |a: &str| {
        command.get_subcommands().any(|c| c.get_name() == a)
            || matches!(a, "help" | "-h" | "--help" | "-V" | "--version")
    };
    // Skip global options (and their values) to find the first real argument.
    let mut i = 1;
    while i < args.len() {
        let a = args[i].to_string_lossy();
        if a == "--threads" {
            i += 2;
        } else if a.starts_with("--threads=") {
            i += 1;
        } else {
            break;
        }
    }
    if i < args.len() && !known(&args[i].to_string_lossy()) {
        args.insert(i, "volume".into());
    }
    args
}

/// mimalloc reuses the large short-lived arrays of a check instead of returning them to
/// the kernel (see Cargo.toml).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    let cli = Cli::parse_from(with_default_command(std::env::args_os().collect()));
    if let Some(n) = cli.threads {
        if let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(n).build_global() {
            eprintln!("meshvol: cannot start {n} threads: {e}");
            return ExitCode::from(2);
        }
    }
    match cli.command {
        Command::Volume(args) => run_volume(args, cli.quiet),
        Command::Check(args) => run_check(args, cli.quiet),
        Command::Area(args) => area::run(args, cli.quiet),
        Command::Section(args) => section::run(args, cli.quiet),
        Command::Hull(args) => hull::run(args, cli.quiet),
        Command::Grid(args) => grid::run(args, cli.quiet),
        Command::Profile(args) => profile::run(args, cli.quiet),
        Command::Union(args) => union::run(args, cli.quiet),
        Command::Repair(args) => {
            match repair::run(
                &args.file,
                &args.out,
                args.cap,
                args.json,
                &args.topology.options(false),
            ) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("meshvol: error: {e}");
                    ExitCode::FAILURE
                }
            }
        }
    }
}

/// Writes to stdout; false when stdout is closed (e.g. piped into `head`).
fn emit(out: &mut impl Write, text: &str) -> bool {
    out.write_all(text.as_bytes()).is_ok()
}

fn run_check(args: CheckArgs, quiet: bool) -> ExitCode {
    let options = args.topology.options(!args.no_intersections);
    let mut all_bound = true;
    let mut stdout = std::io::stdout().lock();
    let progress = input::Progress::new(&args.files, quiet);
    for path in &args.files {
        let name = path.display().to_string();
        progress.stage("reading", path);
        let checked = input::load(path).and_then(|loaded| {
            progress.stage("checking", path);
            let c = meshvol::topology::check(&loaded.surface, &options)
                .map_err(|e| format!("{name}: {e}"))?;
            Ok((check::report(&c), loaded))
        });
        progress.done(path);
        match checked {
            Ok((report, loaded)) => {
                all_bound &= report.bounds_a_volume;
                let text = if args.json {
                    let line = check::JsonLine {
                        file: &name,
                        format: loaded.format.name(),
                        report: &report,
                        warnings: &loaded.warnings,
                    };
                    serde_json::to_string(&line).map(|s| s + "\n").unwrap_or_else(|e| e.to_string())
                } else {
                    check::text(&name, loaded.format.name(), &report)
                };
                for w in &loaded.warnings {
                    progress.warn(&name, w);
                }
                if !progress.suspend(|| emit(&mut stdout, &text)) {
                    return ExitCode::FAILURE;
                }
            }
            Err(e) => {
                progress.error(&e);
                all_bound = false;
            }
        }
    }
    progress.finish();
    if all_bound {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn run_volume(args: VolumeArgs, quiet: bool) -> ExitCode {
    let options = VolumeOptions { density: args.density, units: args.units, exact: args.exact };
    let check = args.solid.check();
    let mut failed = false;
    let mut stdout = std::io::stdout().lock();
    let progress = input::Progress::new(&args.files, quiet);
    for path in &args.files {
        let report = solid::read(path, check, &progress).and_then(|input| {
            progress.stage("measuring", path);
            volume::report(&input, &options)
        });
        progress.done(path);
        match report {
            Ok(r) => {
                let out = if args.json {
                    serde_json::to_string(&r).map(|s| s + "\n").unwrap_or_else(|e| e.to_string())
                } else {
                    volume::text(&r)
                };
                for w in &r.warnings {
                    progress.warn(&r.file, w);
                }
                if !progress.suspend(|| emit(&mut stdout, &out)) {
                    return ExitCode::FAILURE;
                }
            }
            Err(e) => {
                progress.error(&e);
                failed = true;
            }
        }
    }
    progress.finish();
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
