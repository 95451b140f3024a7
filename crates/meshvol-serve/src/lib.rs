//! `meshvol serve`: a page to drop mesh files on, and the HTTP API behind it; and the
//! same page as one self-contained file (`meshvol check --html`).
//!
//! The numbers come from the report layer (`meshvol_report`), as the command's JSON does:
//! `POST /api/check` answers exactly `meshvol check --json`'s object, and the page shows
//! `check`'s and `volume`'s reports with the view of the checked solid
//! (`meshvol_report::view`). See docs/serve.md for the API, the limits and what the
//! server promises about uploads.
//!
//! | file | what |
//! | --- | --- |
//! | `measure.rs` | one upload: bytes → reader → check → reports and view |
//! | `api.rs` | the HTTP routes, a request's places and time limit, errors as JSON |
//! | `upload.rs` | an upload's body (its rate, size and bytes held) and options |
//! | `guard.rs` | who may ask: the `Host` and `Origin` checks |
//! | `conn.rs` | the connections: timeouts, their cap, graceful shutdown |
//! | `page.rs` | the page's embedded files, and the self-contained page |

mod api;
mod conn;
mod guard;
mod measure;
mod page;
mod respond;
mod upload;

pub use measure::{page as page_content, Page};
pub use page::standalone;

use std::net::{IpAddr, SocketAddr};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

/// How the server listens and what it allows per connection and per request.
#[derive(Clone, Debug)]
pub struct Config {
    /// The address to listen on: loopback unless told otherwise.
    pub bind: IpAddr,
    /// 0 picks a free port (the address is passed to `serve`'s `ready`).
    pub port: u16,
    /// Host names answered besides the bound address (lowercase; `--allow-host`).
    pub allow_hosts: Vec<String>,
    /// The largest upload, in bytes (larger: 413).
    pub max_upload: usize,
    /// Checks run at once; more wait in the queue.
    pub max_concurrent: usize,
    /// Requests that may wait (reading their upload, or for a check); more get 503.
    pub queue: usize,
    /// The longest a request may wait for a check and be checked (longer: 503, and
    /// the check is stopped).
    pub timeout: Duration,
    /// The longest a client may keep a connection waiting: for a request's header,
    /// between requests on a kept-alive connection, for reading an answer; and the
    /// grace before an upload must keep to `min_rate`.
    pub client_timeout: Duration,
    /// The slowest an upload may arrive, in bytes a second (on average since its
    /// request began, after `client_timeout`).
    pub min_rate: usize,
    /// Connections open at once; more wait to be accepted.
    pub max_connections: usize,
    /// Upload bytes held in memory at once, all requests together (more: 503).
    pub max_buffered: usize,
    /// What one request's work may cost.
    pub budgets: Budgets,
}

/// The limits of one request's work, each checked before the work it bounds; past one,
/// 413 naming it.
#[derive(Clone, Copy, Debug)]
pub struct Budgets {
    /// The bytes a compressed upload, a zip's member or a 3MF part inflates to.
    pub inflated_bytes: u64,
    /// The faces read (3MF and glTF copies expanded: counted before expanding).
    pub faces: u64,
    /// The placed copies of a 3MF build or a glTF scene.
    pub placements: u64,
    /// The bytes of one answer's JSON.
    pub answer_bytes: usize,
}

impl Budgets {
    /// The budgets that follow from the upload limit: 4× its bytes inflated and in an
    /// answer, a face per 16 bytes, a placement per 256.
    pub fn from_upload(max_upload: usize) -> Budgets {
        let bytes = max_upload as u64;
        Budgets {
            inflated_bytes: bytes.saturating_mul(4),
            faces: (bytes / 16).max(1),
            placements: (bytes / 256).max(1),
            answer_bytes: max_upload.saturating_mul(4),
        }
    }
}

/// Serves until SIGINT or SIGTERM: calls `ready` with the address once it listens.
/// Then stops accepting, lets the requests in flight finish (a check still running is
/// cancelled), removes its temporary folder and returns.
/// Errors: a setting is out of range, the address cannot be bound, the runtime cannot
/// start.
pub fn serve(config: Config, ready: impl FnOnce(SocketAddr)) -> Result<(), String> {
    if config.max_buffered < config.max_upload {
        return Err(format!(
            "--max-buffered ({}) is less than --max-upload ({}): no upload of the largest \
             size could be held",
            size_words(config.max_buffered),
            size_words(config.max_upload)
        ));
    }
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        // Checks run on blocking threads, at most `max_concurrent` at once (api.rs); a
        // cancelled check holds its thread until its current stage ends.
        .max_blocking_threads(config.max_concurrent.max(1) * 2)
        .enable_all()
        .build()
        .map_err(|e| format!("cannot start the server's threads: {e}"))?;
    // The empty folder uploads are read "in": made here so that it is removed here,
    // once no request can use it.
    let folder = tempfile::Builder::new()
        .prefix("meshvol-serve-")
        .tempdir()
        .map_err(|e| format!("cannot make the server's empty folder: {e}"))?;
    let stopping = Arc::new(AtomicBool::new(false));
    let served = runtime.block_on(async {
        let address = SocketAddr::new(config.bind, config.port);
        let listener = tokio::net::TcpListener::bind(address)
            .await
            .map_err(|e| format!("cannot listen on {address}: {e}"))?;
        let bound =
            listener.local_addr().map_err(|e| format!("cannot listen on {address}: {e}"))?;
        let app = api::router(&config, folder.path(), Arc::clone(&stopping));
        let stop = conn::Stop::on_signals()?;
        ready(bound);
        conn::run(listener, app, &config, stop, &stopping).await;
        Ok(())
    });
    // Checks still running were cancelled: each ends at its next stage.
    runtime.shutdown_timeout(Duration::from_secs(5));
    let removed = folder.close().map_err(|e| format!("cannot remove the server's folder: {e}"));
    served.and(removed)
}

/// Parses a size: bytes, or a number with `KiB`, `MiB`, `GiB` (powers of 1024) or `KB`,
/// `MB`, `GB` (powers of 1000); `256MiB`, `1.5GB`, `1000000`.
pub fn parse_size(s: &str) -> Result<usize, String> {
    let t = s.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let factor: f64 = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" => 1e3,
        "m" | "mb" => 1e6,
        "g" | "gb" => 1e9,
        "kib" => 1024.0,
        "mib" => 1024.0 * 1024.0,
        "gib" => 1024.0 * 1024.0 * 1024.0,
        _ => return Err(format!("'{s}' is not a size: use bytes, or KiB, MiB, GiB, KB, MB, GB")),
    };
    match number.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 1.0 && x * factor <= usize::MAX as f64 => {
            Ok((x * factor) as usize)
        }
        _ => Err(format!("'{s}' is not a size of at least one byte")),
    }
}

/// A size in words for messages: `256 MiB`, `1000 bytes`.
pub fn size_words(bytes: usize) -> String {
    const MIB: usize = 1024 * 1024;
    match bytes {
        b if b >= MIB && b % MIB == 0 => format!("{} MiB", b / MIB),
        b if b >= 1024 && b % 1024 == 0 => format!("{} KiB", b / 1024),
        b => format!("{b} bytes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_read_in_binary_and_decimal_units() {
        assert_eq!(parse_size("256MiB"), Ok(256 * 1024 * 1024));
        assert_eq!(parse_size("1.5 GB"), Ok(1_500_000_000));
        assert_eq!(parse_size("1000"), Ok(1000));
        assert_eq!(parse_size("2kib"), Ok(2048));
        assert!(parse_size("0").is_err());
        assert!(parse_size("-5MB").is_err());
        assert!(parse_size("5 parsecs").is_err());
        assert!(parse_size("nan").is_err());
        assert_eq!(size_words(256 * 1024 * 1024), "256 MiB");
        assert_eq!(size_words(1000), "1000 bytes");
    }
}
