//! The `meshvol` command: a thin layer of arguments over the meshvol libraries. Each
//! command module parses its arguments, reads its inputs (`input`, `solid`), asks the
//! report layer (`meshvol_report`) for reports and hands them to the one driver
//! (`driver`), which prints them and decides the exit status: 0 when every file was
//! measured (and, for `check`, bounds a volume), 1 when any failed, 2 on a usage error.

mod allocator;
mod area;
mod below;
mod check;
mod cutfill;
mod devices;
mod driver;
mod grid;
mod hull;
mod input;
mod intersect;
mod manual;
mod nearest;
mod numbers;
mod profile;
mod repair;
mod section;
mod serve;
mod solid;
mod union;
mod units;
mod volume;
mod walk;

use clap::{CommandFactory, Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "meshvol",
    version,
    about = "Measure solids: volume, area, centroid and inertia of mesh files, exactly and fast.",
    after_help = "`meshvol FILE...` is short for `meshvol volume FILE...`; a folder stands for the \
                  mesh files in it (--recursive: in its subfolders too).\n\nExamples:\n  \
                  meshvol samples/flanged-bushing.stl\n  meshvol check samples/ --format csv\n  \
                  meshvol help grid"
)]
struct Cli {
    /// Worker threads (default: one per core). Results are identical for any count.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    /// No progress bar and no warnings on stderr (errors are still printed).
    #[arg(long, short, global = true)]
    quiet: bool,
    /// Time each stage (reading, each stage of the check, measuring): wall and CPU
    /// seconds, as a `timings` list in the JSON (with --json) or on stderr.
    #[arg(long, global = true)]
    timings: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Volume, area, centroid, inertia, principal axes, mass and bounds of each file.
    #[command(after_help = EXAMPLES_VOLUME)]
    Volume(volume::VolumeArgs),
    /// Can the volume be trusted? Closed, manifold, wound which way, shells, cavities,
    /// overlaps, self-intersections. Exits 1 when a file does not bound a volume.
    #[command(after_help = EXAMPLES_CHECK)]
    Check(check::CheckArgs),
    /// Write the mesh with shells turned outward (cavities inward), degenerate and
    /// duplicate faces removed, vertices welded, and with --cap, holes capped. Says what
    /// changed.
    #[command(after_help = EXAMPLES_REPAIR)]
    Repair(repair::RepairArgs),
    /// Area, perimeter, centroid and second moments of polygons (WKT, GeoJSON, x y
    /// lines), per feature and in total; reports self-intersecting and crossing rings.
    #[command(after_help = EXAMPLES_AREA)]
    Area(area::AreaArgs),
    /// The cross-section of a mesh by a plane: its outline (as WKT or GeoJSON on
    /// request), area, centroid and second moments.
    #[command(after_help = EXAMPLES_SECTION)]
    Section(section::SectionArgs),
    /// Volume, area and centroid of the convex hull of a point cloud (.xyz, .csv, PLY,
    /// or any mesh's vertices); --out writes the hull.
    #[command(after_help = EXAMPLES_HULL)]
    Hull(hull::HullArgs),
    /// The volume of the solid in each cell of a regular grid (exact, not voxels): .npy,
    /// .npz, .vti, .csv or .zarr (with --moments, the cut cells), a summary, and a PNG of
    /// a slice.
    #[command(after_help = EXAMPLES_GRID)]
    Grid(grid::GridArgs),
    /// Volume below each level along an axis, slab volumes and section areas (a
    /// strapping table).
    #[command(after_help = EXAMPLES_PROFILE)]
    Profile(profile::ProfileArgs),
    /// The volume of the union of overlapping bodies (files, or one file's shells) as a
    /// certified interval, without a boolean mesh.
    #[command(after_help = EXAMPLES_UNION)]
    Union(union::UnionArgs),
    /// The volume of the intersection of two bodies as a certified interval, with IoU,
    /// Dice and the differences A − B, B − A, without a boolean mesh.
    #[command(after_help = EXAMPLES_INTERSECT)]
    Intersect(intersect::IntersectArgs),
    /// The part of the solid below a plane: volume, centroid (centre of buoyancy),
    /// wetted area, section (waterplane); or the level that holds a given volume.
    #[command(after_help = EXAMPLES_BELOW)]
    Below(below::BelowArgs),
    /// Cut and fill between an existing surface and a design surface or level
    /// (earthwork volumes), exactly; per plan cell with --cells or --pitch.
    #[command(after_help = EXAMPLES_CUTFILL)]
    Cutfill(cutfill::CutFillArgs),
    /// A page to drop mesh files on (volume, mass, verdict and a 3D view of the
    /// problems), and its HTTP API: `POST /api/check` answers `check --json`'s object.
    #[command(after_help = EXAMPLES_SERVE)]
    Serve(serve::ServeArgs),
    /// The OpenCL devices `grid --backend` can use (name, type, f64, memory), and the one
    /// `--backend auto` takes.
    #[command(after_help = EXAMPLES_DEVICES)]
    Devices(devices::DevicesArgs),
    /// Print a completion script for a shell to stdout (`meshvol completions bash >
    /// ~/.local/share/bash-completion/completions/meshvol`).
    #[command(after_help = EXAMPLES_COMPLETIONS)]
    Completions {
        /// The shell.
        #[arg(value_enum)]
        shell: clap_complete::Shell,
    },
    /// Print the manual page (roff) to stdout: the command's, or with COMMAND that
    /// subcommand's (`meshvol man > meshvol.1 && man ./meshvol.1`); with --all DIR, write
    /// every page into DIR.
    #[command(after_help = EXAMPLES_MAN)]
    Man {
        /// A subcommand: its own page (`meshvol-volume(1)`).
        #[arg(value_name = "COMMAND", conflicts_with = "all")]
        command: Option<String>,
        /// Write every page into DIR (made if missing): meshvol.1 and meshvol-COMMAND.1
        /// for each subcommand; prints the paths written.
        #[arg(long, value_name = "DIR", value_hint = clap::ValueHint::DirPath)]
        all: Option<std::path::PathBuf>,
    },
}

/// `--help`'s examples, per command.
const EXAMPLES_VOLUME: &str = "Examples:\n  meshvol volume samples/flanged-bushing.stl\n  meshvol volume samples/ --recursive --glob '*.stl' --format csv > volumes.csv\n  meshvol volume samples/flanged-bushing.stl --units mm:cm --density 7.85g/cm3 --json";
const EXAMPLES_CHECK: &str = "Examples:\n  meshvol check samples/flanged-bushing.stl\n  meshvol check samples/ -r --format csv\n  meshvol check part.stl.gz --no-intersections --json\n  meshvol check samples/flanged-bushing.stl --html report.html";
const EXAMPLES_REPAIR: &str = "Examples:\n  meshvol repair samples/flanged-bushing.stl -o bushing.ply\n  meshvol repair scan.obj --cap -o closed.obj --json";
const EXAMPLES_AREA: &str = "Examples:\n  meshvol area parcel.wkt lots.geojson\n  meshvol area parcels/ --glob '*.wkt' --json\n  cat lots.wkt | meshvol area -";
const EXAMPLES_SECTION: &str = "Examples:\n  meshvol section samples/flanged-bushing.stl --plane z=10\n  meshvol section samples/flanged-bushing.stl --plane z=12.5 --wkt\n  meshvol section samples/flanged-bushing.stl --plane 0,1,1,10 --json";
const EXAMPLES_HULL: &str = "Examples:\n  meshvol hull samples/flanged-bushing.stl\n  meshvol hull scan.xyz --out hull.stl --json";
const EXAMPLES_GRID: &str = "Examples:\n  meshvol grid samples/flanged-bushing.stl --cells 60,60,30 --out cells.npy\n  meshvol grid samples/flanged-bushing.stl --pitch 1 --png z.png --slice z=12.5\n  meshvol grid samples/flanged-bushing.stl --pitch 1 --png mid.png --slice k=15 --json\n  meshvol grid samples/flanged-bushing.stl --pitch 0.5 --backend auto --out cells.npy";
const EXAMPLES_DEVICES: &str = "Examples:\n  meshvol devices\n  meshvol devices --json";
const EXAMPLES_PROFILE: &str = "Examples:\n  meshvol profile samples/flanged-bushing.stl --levels 10\n  meshvol profile samples/flanged-bushing.stl --step 0.5 --units mm:mL --csv";
const EXAMPLES_UNION: &str = "Examples:\n  meshvol union a.stl b.stl c.stl --json\n  meshvol union samples/flanged-bushing.stl       # one file: its shells are the bodies";
const EXAMPLES_INTERSECT: &str =
    "Examples:\n  meshvol intersect a.stl b.stl --json\n  meshvol intersect parts/ --pairs --format csv > overlaps.csv";
const EXAMPLES_BELOW: &str = "Examples:\n  meshvol below samples/flanged-bushing.stl --plane z=10\n  meshvol below samples/flanged-bushing.stl --plane 0,0,1,10\n  meshvol below samples/flanged-bushing.stl --volume 10000 --units mm:mL\n  meshvol below hulls/ --volume 4 --heel 10 --format csv";
const EXAMPLES_CUTFILL: &str = "Examples:\n  meshvol cutfill terrain.obj --level 5\n  meshvol cutfill existing.stl --design design.stl --pitch 10 --out cells.npy";
const EXAMPLES_SERVE: &str = "Examples:\n  meshvol serve                       # http://127.0.0.1:8765/\n  meshvol serve --port 8080 --max-upload 1GiB\n  meshvol serve --bind 0.0.0.0 --max-concurrent 4   # answers the network: put it behind a proxy";
const EXAMPLES_COMPLETIONS: &str = "Examples:\n  meshvol completions bash > ~/.local/share/bash-completion/completions/meshvol\n  meshvol completions zsh > ~/.zfunc/_meshvol\n  meshvol completions fish > ~/.config/fish/completions/meshvol.fish\n  meshvol completions elvish > ~/.config/elvish/lib/meshvol.elv\n  meshvol completions powershell >> $PROFILE";
const EXAMPLES_MAN: &str = "Examples:\n  meshvol man > meshvol.1 && man ./meshvol.1\n  meshvol man volume > meshvol-volume.1\n  meshvol man --all ~/.local/share/man/man1";

/// Inserts `volume` when the first argument after the global options is not a
/// subcommand, so `meshvol part.stl` means `meshvol volume part.stl` and
/// `meshvol -q part.stl` means `meshvol -q volume part.stl`.
fn with_default_command(mut args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let command = Cli::command();
    let known = |a: &str| {
        command.get_subcommands().any(|c| c.get_name() == a)
            || matches!(a, "help" | "-h" | "--help" | "-V" | "--version")
    };
    let i = first_argument(&args);
    if i < args.len() && !known(&args[i].to_string_lossy()) {
        args.insert(i, "volume".into());
    }
    args
}

/// Where the first argument after the global options (and their values) is.
fn first_argument(args: &[std::ffi::OsString]) -> usize {
    let mut i = 1;
    while i < args.len() {
        let a = args[i].to_string_lossy();
        if a == "--threads" {
            i += 2;
        } else if a.starts_with("--threads=") || matches!(&*a, "-q" | "--quiet" | "--timings") {
            i += 1;
        } else {
            break;
        }
    }
    i
}

/// The subcommand `arg` was probably meant to be, when it is not a file ([`nearest`](nearest::nearest)).
fn misspelt_command(arg: &std::ffi::OsStr) -> Option<String> {
    let a = arg.to_str()?;
    if a.len() < 2
        || a.starts_with('-')
        || std::path::Path::new(a).exists()
        || a.contains(['.', '/'])
    {
        return None;
    }
    let command = Cli::command();
    if a == "help" || command.get_subcommands().any(|c| c.get_name() == a) {
        return None;
    }
    nearest::nearest(a, command.get_subcommands().map(|c| c.get_name()))
}

/// More worker threads than this many per core only cost memory and time.
const THREADS_PER_CORE: usize = 4;

fn main() -> ExitCode {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    // `meshvol chek part.obj`: a typo of a subcommand, not a file to measure.
    if let Some(first) = args.get(first_argument(&args)) {
        if let Some(name) = misspelt_command(first) {
            eprintln!(
                "meshvol: error: '{}' is not a subcommand or a file: did you mean `{name}`?",
                first.to_string_lossy()
            );
            return ExitCode::from(2);
        }
    }
    let cli = match Cli::try_parse_from(with_default_command(args)) {
        Ok(cli) => cli,
        // Usage errors with the prefix of every other error of the command (clap's own
        // is `error:`), exit status 2.
        Err(e) if e.use_stderr() => {
            eprint!("meshvol: {}", e.render());
            return ExitCode::from(2);
        }
        Err(e) => e.exit(),
    };
    allocator::configure(matches!(cli.command, Command::Serve(_)));
    input::TIMINGS.store(cli.timings, std::sync::atomic::Ordering::Relaxed);
    if let Some(n) = cli.threads {
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        let cap = THREADS_PER_CORE * cores;
        let n = if n > cap {
            if !cli.quiet {
                eprintln!(
                    "meshvol: warning: --threads {n} is more than {THREADS_PER_CORE} per core \
                     ({cores} cores): using {cap}"
                );
            }
            cap
        } else {
            n
        };
        if let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(n).build_global() {
            eprintln!("meshvol: error: cannot start {n} threads: {e}");
            return ExitCode::from(2);
        }
    }
    match cli.command {
        Command::Volume(args) => volume::run(args, cli.quiet),
        Command::Check(args) => check::run(args, cli.quiet),
        Command::Repair(args) => repair::run(args, cli.quiet),
        Command::Area(args) => area::run(args, cli.quiet),
        Command::Section(args) => section::run(args, cli.quiet),
        Command::Hull(args) => hull::run(args, cli.quiet),
        Command::Grid(args) => grid::run(args, cli.quiet),
        Command::Profile(args) => profile::run(args, cli.quiet),
        Command::Union(args) => union::run(args, cli.quiet),
        Command::Intersect(args) => intersect::run(args, cli.quiet),
        Command::Below(args) => below::run(args, cli.quiet),
        Command::Cutfill(args) => cutfill::run(args, cli.quiet),
        Command::Serve(args) => serve::run(args, cli.quiet),
        Command::Devices(args) => devices::run(args),
        Command::Completions { shell } => manual::completions(shell, Cli::command()),
        Command::Man { all: Some(dir), .. } => manual::man_all(Cli::command(), &dir),
        Command::Man { command, all: None } => manual::man(Cli::command(), command.as_deref()),
    }
}
