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
    /// The largest upload: bytes, or with KiB, MiB, GiB (or KB, MB, GB). Larger: 413.
    #[arg(long, default_value = "256MiB", value_parser = meshvol_serve::parse_size)]
    max_upload: usize,
    /// Checks run at once (default: one per core); further uploads wait.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    max_concurrent: Option<u32>,
    /// Uploads that may wait for a check; more are answered 503 at once.
    #[arg(long, value_name = "N", default_value_t = 64)]
    queue: usize,
    /// The longest a request may take, waiting included, in seconds. Longer: 503.
    #[arg(long, value_name = "SECONDS", default_value_t = 120.0, value_parser = crate::positive_finite)]
    timeout: f64,
}

/// Serves until interrupted.
pub fn run(args: ServeArgs, quiet: bool) -> ExitCode {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let config = meshvol_serve::Config {
        bind: args.bind,
        port: args.port,
        max_upload: args.max_upload,
        max_concurrent: args.max_concurrent.map_or(cores, |n| n as usize),
        queue: args.queue,
        timeout: Duration::from_secs_f64(args.timeout.min(1e9)),
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
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            ExitCode::FAILURE
        }
    }
}
