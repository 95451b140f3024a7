//! `meshvol serve`: the page to drop mesh files on, and its HTTP API (the
//! `meshvol-serve` crate); loopback only unless `--bind` says otherwise.

use clap::Args;
use std::net::IpAddr;
use std::process::ExitCode;
use std::time::Duration;

#[derive(Args)]
pub struct ServeArgs {
    /// The port to listen on (0: any free port, printed when listening).
    #[arg(long, default_value_t = 8765)]
    port: u16,
    /// The address to listen on. The default answers this machine only; `0.0.0.0`
    /// answers the network (put it behind your intranet's proxy and access rules).
    #[arg(long, default_value = "127.0.0.1")]
    bind: IpAddr,
    /// A host name the server answers to besides its address (the name users type, or
    /// the proxy's); repeat for several. Other names are refused (421).
    #[arg(long, value_name = "NAME")]
    allow_host: Vec<String>,
    /// The largest upload: bytes, or with KiB, MiB, GiB (or KB, MB, GB). Larger: 413.
    #[arg(long, default_value = "256MiB", value_parser = meshvol_serve::parse_size)]
    max_upload: usize,
    /// Checks run at once (default: one per core); further uploads wait.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    max_concurrent: Option<u32>,
    /// Requests that may wait, reading their upload or for a check; more are answered
    /// 503 at once.
    #[arg(long, value_name = "N", default_value_t = 64)]
    queue: usize,
    /// The longest a request may wait for a check and be checked, in seconds. Longer:
    /// 503, and its check is stopped.
    #[arg(long, value_name = "SECONDS", default_value_t = 120.0, value_parser = crate::numbers::positive_finite)]
    timeout: f64,
    /// The longest a client may keep a connection waiting, in seconds: for a request's
    /// header, between requests, for reading an answer; and before its upload must
    /// keep to --min-rate.
    #[arg(long, value_name = "SECONDS", default_value_t = 10.0, value_parser = crate::numbers::positive_finite)]
    client_timeout: f64,
    /// The slowest an upload may arrive, per second (on average, after
    /// --client-timeout). Slower: 408.
    #[arg(long, value_name = "SIZE", default_value = "16KiB", value_parser = meshvol_serve::parse_size)]
    min_rate: usize,
    /// Connections open at once; more wait to be accepted.
    #[arg(long, value_name = "N", default_value_t = 512, value_parser = clap::value_parser!(u32).range(1..=65536))]
    max_connections: u32,
    /// Upload bytes held at once, all requests together (default: 4 × --max-upload).
    /// More: 503.
    #[arg(long, value_name = "SIZE", value_parser = meshvol_serve::parse_size)]
    max_buffered: Option<usize>,
    /// The bytes one upload may inflate to: a compressed file, a zip's member, a 3MF
    /// part (default: MESHVOL_MAX_STREAM_BYTES if set, else 4 × --max-upload). More: 413.
    #[arg(long, value_name = "SIZE", value_parser = meshvol_serve::parse_size)]
    max_inflated: Option<usize>,
    /// The faces one upload may hold, copies placed by a 3MF or glTF counted (default:
    /// one per 16 bytes of --max-upload). More: 413.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    max_faces: Option<u64>,
    /// The copies a 3MF build or glTF scene may place (default: one per 256 bytes of
    /// --max-upload). More: 413.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    max_placements: Option<u64>,
    /// The largest answer (default: 4 × --max-upload). Larger: 413.
    #[arg(long, value_name = "SIZE", value_parser = meshvol_serve::parse_size)]
    max_answer: Option<usize>,
}

/// Serves until interrupted (Ctrl-C or SIGTERM).
pub fn run(args: ServeArgs, quiet: bool) -> ExitCode {
    // A setting the server would silently ignore is refused before it starts.
    let stream_limit = match meshvol_io::stream_limit_setting() {
        Ok(limit) => limit,
        Err(e) => {
            eprintln!("meshvol: error: {e}: give a number of bytes, or unset it");
            return ExitCode::FAILURE;
        }
    };
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let from_upload = meshvol_serve::Budgets::from_upload(args.max_upload);
    let budgets = meshvol_serve::Budgets {
        inflated_bytes: args
            .max_inflated
            .map(|n| n as u64)
            .or(stream_limit)
            .unwrap_or(from_upload.inflated_bytes),
        faces: args.max_faces.unwrap_or(from_upload.faces),
        placements: args.max_placements.unwrap_or(from_upload.placements),
        answer_bytes: args.max_answer.unwrap_or(from_upload.answer_bytes),
    };
    let config = meshvol_serve::Config {
        bind: args.bind,
        port: args.port,
        allow_hosts: args.allow_host,
        max_upload: args.max_upload,
        max_concurrent: args.max_concurrent.map_or(cores, |n| n as usize),
        queue: args.queue,
        timeout: Duration::from_secs_f64(args.timeout.min(1e9)),
        client_timeout: Duration::from_secs_f64(args.client_timeout.min(1e9)),
        min_rate: args.min_rate,
        max_connections: args.max_connections as usize,
        max_buffered: args.max_buffered.unwrap_or(args.max_upload.saturating_mul(4)),
        budgets,
    };
    let served = meshvol_serve::serve(config, |address| {
        // Printed even with --quiet: it is how a script learns the port of `--port 0`.
        eprintln!("meshvol: serving on http://{address}/ (Ctrl-C stops it)");
        if !quiet && !address.ip().is_loopback() {
            eprintln!(
                "meshvol: warning: listening on {} answers other machines: anyone who can \
                 reach it can upload files to measure",
                address.ip()
            );
        }
    });
    match served {
        Ok(()) => {
            if !quiet {
                eprintln!("meshvol: stopped");
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            ExitCode::FAILURE
        }
    }
}
