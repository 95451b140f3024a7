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
//! | `api.rs` | the HTTP routes, the request's options, the limits |
//! | `page.rs` | the page's embedded files, and the self-contained page |

mod api;
mod measure;
mod page;

pub use measure::{page as page_content, Page};
pub use page::standalone;

use std::net::{IpAddr, SocketAddr};
use std::time::Duration;

/// How the server listens and what it allows per request.
#[derive(Clone, Copy, Debug)]
pub struct Config {
    /// The address to listen on: loopback unless told otherwise.
    pub bind: IpAddr,
    /// 0 picks a free port (the address is passed to `serve`'s `ready`).
    pub port: u16,
    /// The largest upload, in bytes (larger: 413).
    pub max_upload: usize,
    /// Checks run at once; more wait in the queue.
    pub max_concurrent: usize,
    /// Requests that may wait for a check; more get 503 at once.
    pub queue: usize,
    /// The longest a request may take, waiting included (longer: 503).
    pub timeout: Duration,
}

/// Serves until the process ends: calls `ready` with the address once it listens.
/// Errors: the address cannot be bound, the runtime cannot start.
pub fn serve(config: Config, ready: impl FnOnce(SocketAddr)) -> Result<(), String> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        // Checks run on blocking threads, at most `max_concurrent` at once (api.rs); a
        // check that ran past its time limit still holds its thread until it ends.
        .max_blocking_threads(config.max_concurrent.max(1) * 2)
        .enable_all()
        .build()
        .map_err(|e| format!("cannot start the server's threads: {e}"))?;
    runtime.block_on(async move {
        let address = SocketAddr::new(config.bind, config.port);
        let listener = tokio::net::TcpListener::bind(address)
            .await
            .map_err(|e| format!("cannot listen on {address}: {e}"))?;
        let bound =
            listener.local_addr().map_err(|e| format!("cannot listen on {address}: {e}"))?;
        let app = api::router(config)?;
        ready(bound);
        axum::serve(listener, app).await.map_err(|e| format!("the server stopped: {e}"))
    })
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
