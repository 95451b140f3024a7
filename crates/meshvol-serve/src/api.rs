//! The HTTP routes: the page's files, `POST /api/check` (the command's JSON),
//! `POST /api/view` (the page's reports and geometry) and `GET /api/limits`; every
//! error as JSON.
//!
//! So that no request can take the server down: a request takes one of
//! `max_concurrent + queue` places or gets 503 at once; holding it, it reads its upload
//! (`upload.rs`: rate, size and the bytes all requests hold are bounded) and only then
//! waits for one of `max_concurrent` checks, so a slow client holds no check. Its check
//! runs within its budgets (`measure.rs`) and `timeout`: past it, the request is
//! answered 503 and the check is cancelled at its next stage, which frees its place.
//! A check that panics is a 500 with a message, not a stopped server.

use crate::config::Config;
use crate::guard::{self, Hosts};
use crate::measure::{self, Failure};
use crate::page;
use crate::respond::{error, json, json_bytes, not_found, over_budget};
use crate::size::size_words;
use crate::upload::{self, Params};
use axum::extract::rejection::QueryRejection;
use axum::extract::{Query, Request, State};
use axum::http::{header, StatusCode};
use axum::response::Response;
use axum::routing::{get, post};
use axum::Router;
use meshvol::progress::Progress;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use tokio::sync::Semaphore;
use tokio::time::Instant;

/// What every request shares.
struct Shared {
    config: Config,
    /// An empty folder, the server's own: uploads are read as if they were in it (and
    /// never written anywhere).
    folder: PathBuf,
    /// Places of requests reading their upload, waiting for a check or checked.
    places: Arc<Semaphore>,
    checks: Arc<Semaphore>,
    /// Bytes of the uploads held, all requests together.
    buffered: Arc<Semaphore>,
    /// Set when the server stops: every check running is cancelled.
    stopping: Arc<AtomicBool>,
}

/// The server's routes over `config`, reading uploads in `folder`.
pub fn router(config: &Config, folder: &Path, stopping: Arc<AtomicBool>) -> Router {
    let hosts = Arc::new(Hosts::new(config.bind, &config.allow_hosts));
    let checks = config.max_concurrent.max(1);
    let shared = Arc::new(Shared {
        config: config.clone(),
        folder: folder.to_path_buf(),
        places: Arc::new(Semaphore::new(checks + config.queue)),
        checks: Arc::new(Semaphore::new(checks)),
        buffered: Arc::new(Semaphore::new(config.max_buffered.min(Semaphore::MAX_PERMITS))),
        stopping,
    });
    Router::new()
        .route("/", get(|| async { page::asset("index.html") }))
        .route(
            "/{*file}",
            get(|axum::extract::Path(file): axum::extract::Path<String>| async move {
                page::asset(&file)
            }),
        )
        .route("/api/limits", get(limits))
        .route("/api/check", post(|s, q, r| handle(s, q, r, false)))
        .route("/api/view", post(|s, q, r| handle(s, q, r, true)))
        .fallback(|| async { not_found() })
        .method_not_allowed_fallback(|request: Request| async move {
            let message =
                format!("{} is not a method of {}", request.method(), request.uri().path());
            error(StatusCode::METHOD_NOT_ALLOWED, None, &message)
        })
        .with_state(shared)
        .layer(axum::middleware::from_fn_with_state(hosts, guard::guard))
}

/// The limits, for the page to say them (and refuse a file too large before sending it).
async fn limits(State(shared): State<Arc<Shared>>) -> Response {
    let c = &shared.config;
    let body = serde_json::json!({
        "max_upload": c.max_upload,
        "max_concurrent": c.max_concurrent,
        "queue": c.queue,
        "timeout_s": c.timeout.as_secs_f64(),
        "client_timeout_s": c.client_timeout.as_secs_f64(),
        "min_rate": c.min_rate,
        "max_connections": c.max_connections,
        "max_buffered": c.max_buffered,
        "max_inflated": c.budgets.inflated_bytes,
        "max_faces": c.budgets.faces,
        "max_placements": c.budgets.placements,
        "max_answer": c.budgets.answer_bytes,
    });
    json(StatusCode::OK, body.to_string())
}

/// The cancellation hook a check is run with: its request's deadline passed, or the
/// server is stopping.
struct Cancel {
    late: Arc<AtomicBool>,
    stopping: Arc<AtomicBool>,
}

impl Progress for Cancel {
    fn cancelled(&self) -> bool {
        self.late.load(Ordering::Relaxed) || self.stopping.load(Ordering::Relaxed)
    }
}

/// `POST /api/check` (`view` false) and `POST /api/view` (true).
async fn handle(
    State(shared): State<Arc<Shared>>,
    query: Result<Query<Params>, QueryRejection>,
    request: Request,
    view: bool,
) -> Response {
    let start = Instant::now();
    let params = match query {
        Ok(Query(params)) => params,
        Err(e) => {
            return error(StatusCode::BAD_REQUEST, None, &format!("the query: {}", e.body_text()))
        }
    };
    let encoding = request.headers().get(header::CONTENT_ENCODING);
    if let Some(encoding) = encoding.filter(|e| e.as_bytes() != b"identity") {
        let message = format!(
            "the upload is sent with Content-Encoding {}: send the file's own bytes (a \
             compressed file named .gz, .bz2, .zst or .zip is read as one)",
            String::from_utf8_lossy(encoding.as_bytes())
        );
        return error(StatusCode::UNSUPPORTED_MEDIA_TYPE, None, &message);
    }
    let config = &shared.config;
    let Ok(place) = Arc::clone(&shared.places).try_acquire_owned() else {
        let message = format!(
            "busy: {} checks running and {} requests waiting; try again shortly",
            config.max_concurrent, config.queue
        );
        return error(StatusCode::SERVICE_UNAVAILABLE, None, &message);
    };
    let upload = match upload::read(params, request, start, config, &shared.buffered).await {
        Ok(upload) => upload,
        Err(response) => return response,
    };
    let options = match upload.params.options() {
        Ok(options) => options,
        Err(e) => return error(StatusCode::BAD_REQUEST, Some(&upload.name), &e),
    };
    let late = Arc::new(AtomicBool::new(false));
    let hook = Cancel { late: Arc::clone(&late), stopping: Arc::clone(&shared.stopping) };
    let shown = upload.name.clone();
    let answer = async {
        let Ok(check) = Arc::clone(&shared.checks).acquire_owned().await else {
            return error(StatusCode::SERVICE_UNAVAILABLE, None, "the server is stopping");
        };
        let (folder, budgets) = (shared.folder.clone(), config.budgets);
        // The places go with the check: one that runs on after its request was
        // answered still counts until its next stage stops it. The answer is written
        // there too (a view can be megabytes of JSON), off the threads that serve
        // connections.
        let checked = tokio::task::spawn_blocking(move || {
            let _held = (place, check, upload.held);
            let name = upload.name;
            let measured =
                measure::measure(&folder, &name, upload.bytes, &options, view, &budgets, &hook);
            let (report, page) = measured?;
            let mut body = Bounded { bytes: Vec::new(), limit: budgets.answer_bytes, over: false };
            let written = match page {
                None => serde_json::to_writer(&mut body, &report),
                Some(page) => serde_json::to_writer(&mut body, &page),
            };
            match written {
                Ok(()) => Ok(body.bytes),
                Err(_) if body.over => {
                    let message = format!(
                        "{name}: the answer is larger than {}",
                        size_words(budgets.answer_bytes)
                    );
                    Err(Failure::Over { budget: "--max-answer", message })
                }
                Err(e) => Err(Failure::Unreadable(format!("{name}: {e}"))),
            }
        })
        .await;
        match checked {
            Ok(Ok(body)) => json_bytes(body),
            Ok(Err(Failure::Unreadable(e))) => {
                error(StatusCode::UNPROCESSABLE_ENTITY, Some(&shown), &e)
            }
            Ok(Err(Failure::Over { budget, message })) => over_budget(&shown, budget, &message),
            Ok(Err(Failure::NoMemory(message))) => {
                error(StatusCode::SERVICE_UNAVAILABLE, Some(&shown), &message)
            }
            Ok(Err(Failure::Cancelled)) => {
                error(StatusCode::SERVICE_UNAVAILABLE, Some(&shown), "the server is stopping")
            }
            Err(_) => error(
                StatusCode::INTERNAL_SERVER_ERROR,
                Some(&shown),
                &format!("{shown}: the check failed unexpectedly (a bug: please report it)"),
            ),
        }
    };
    match tokio::time::timeout(config.timeout, answer).await {
        Ok(response) => response,
        Err(_) => {
            // The check stops at its next stage and gives its places back.
            late.store(true, Ordering::Relaxed);
            let message = format!(
                "the request took longer than the limit of {} s (--timeout, waiting for a \
                 check included): its check was stopped; try a smaller file",
                config.timeout.as_secs_f64()
            );
            error(StatusCode::SERVICE_UNAVAILABLE, Some(&shown), &message)
        }
    }
}

/// An answer written up to `limit` bytes: past it, the write fails (and serializing
/// stops there, holding no more).
struct Bounded {
    bytes: Vec<u8>,
    limit: usize,
    over: bool,
}

impl Write for Bounded {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.bytes.len() + buf.len() > self.limit {
            self.over = true;
            self.bytes = Vec::new();
            return Err(std::io::Error::other("past the answer's budget"));
        }
        self.bytes.extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}
