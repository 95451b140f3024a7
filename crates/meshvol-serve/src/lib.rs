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
//! | `config.rs`, `size.rs` | the settings and budgets; sizes read and written as words |

mod api;
mod config;
mod conn;
mod guard;
mod measure;
mod page;
mod respond;
mod size;
mod upload;

pub use config::{Budgets, Config};
pub use measure::{page as page_content, Page};
pub use page::standalone;
pub use size::{parse_size, size_words};

use std::net::SocketAddr;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

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
