//! The connections under the routes: hyper's HTTP/1 server with tokio's timer, so that
//! no client can hold a connection by being slow.
//!
//! - A request's header must arrive within `client_timeout` (hyper's header-read
//!   timeout). Hyper starts the same timer whenever a connection waits for its next
//!   request, so it is also the keep-alive idle timeout.
//! - A write to a client that stopped reading fails after `client_timeout`
//!   (`tokio-io-timeout` on the socket), which drops the connection and the answer it
//!   held.
//! - At most `max_connections` are open; the next waits in the listen queue until one
//!   closes (the timeouts above close the idle ones).
//! - SIGINT or SIGTERM stops accepting and lets the connections finish (hyper-util's
//!   graceful shutdown) for at most `client_timeout`: the checks running are cancelled,
//!   so their requests end at their check's next stage with 503.

use crate::config::Config;
use axum::Router;
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::server::graceful::GracefulShutdown;
use hyper_util::service::TowerToHyperService;
use std::future::Future;
use std::pin::Pin;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::net::TcpListener;
use tokio::sync::Semaphore;
use tokio_io_timeout::TimeoutStream;

/// The most bytes hyper buffers of one connection's reads (its header included): a
/// header larger than this is refused, and open connections cost at most this each.
const MAX_BUFFER: usize = 64 * 1024;

/// The signals that stop the server, registered before it says it listens (so a
/// signal sent as soon as it is ready is not lost).
pub(crate) struct Stop(Pin<Box<dyn Future<Output = ()> + Send>>);

impl Stop {
    /// SIGINT (Ctrl-C) or, on Unix, SIGTERM.
    pub(crate) fn on_signals() -> Result<Stop, String> {
        let cannot = |e: std::io::Error| format!("cannot watch for Ctrl-C: {e}");
        #[cfg(unix)]
        {
            use tokio::signal::unix::{signal, SignalKind};
            let mut interrupt = signal(SignalKind::interrupt()).map_err(cannot)?;
            let mut terminate = signal(SignalKind::terminate()).map_err(cannot)?;
            Ok(Stop(Box::pin(async move {
                tokio::select! {
                    _ = interrupt.recv() => {}
                    _ = terminate.recv() => {}
                }
            })))
        }
        #[cfg(not(unix))]
        {
            let _ = cannot;
            Ok(Stop(Box::pin(async {
                // An error here means no Ctrl-C can be seen: serve until killed.
                if tokio::signal::ctrl_c().await.is_err() {
                    std::future::pending::<()>().await;
                }
            })))
        }
    }
}

/// Accepts connections on `listener` and serves `app` on each until `stop`; then sets
/// `stopping` (which cancels the checks running) and waits for the connections.
pub(crate) async fn run(
    listener: TcpListener,
    app: Router,
    config: &Config,
    stop: Stop,
    stopping: &AtomicBool,
) {
    let mut http = http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(config.client_timeout)
        .max_buf_size(MAX_BUFFER);
    let open = Arc::new(Semaphore::new(config.max_connections.max(1)));
    let graceful = GracefulShutdown::new();
    let mut stop = stop.0;
    loop {
        let place = tokio::select! {
            place = Arc::clone(&open).acquire_owned() => place,
            () = &mut stop => break,
        };
        // The semaphore is never closed.
        let Ok(place) = place else { break };
        let accepted = tokio::select! {
            accepted = listener.accept() => accepted,
            () = &mut stop => break,
        };
        let stream = match accepted {
            Ok((stream, _)) => stream,
            // Out of file descriptors, or a connection reset before it was accepted:
            // pause a moment rather than spin, and go on.
            Err(_) => {
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        let mut io = TimeoutStream::new(stream);
        io.set_write_timeout(Some(config.client_timeout));
        let connection = http
            .serve_connection(TokioIo::new(Box::pin(io)), TowerToHyperService::new(app.clone()));
        let connection = graceful.watch(connection);
        tokio::spawn(async move {
            // A connection's errors (a timeout, a reset) end that connection only.
            let _ = connection.await;
            drop(place);
        });
    }
    stopping.store(true, Ordering::SeqCst);
    drop(listener);
    // Cancelled checks end at their next stage; what is left after `client_timeout`
    // (a slow upload, an answer not read) is dropped with the runtime.
    let _ = tokio::time::timeout(config.client_timeout, graceful.shutdown()).await;
}
