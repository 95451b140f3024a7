//! The HTTP routes: the page's files, `POST /api/check` (the command's JSON),
//! `POST /api/view` (the page's reports and geometry) and `GET /api/limits`.
//!
//! Limits, so that no request can take the server down: a request waits in a queue of
//! at most `queue` for one of `max_concurrent` checks, or gets 503 at once; its body is
//! read only once it holds a check's place (so memory is bounded by `max_concurrent`
//! uploads), up to `max_upload` bytes (more: 413); and it is answered within `timeout`
//! (or 503). A check that panics is a 500 with a message, not a stopped server.

use crate::measure::{self, Options};
use crate::{page, size_words, Config};
use axum::body::Bytes;
use axum::extract::rejection::QueryRejection;
use axum::extract::{DefaultBodyLimit, FromRequest, Multipart, Query, Request, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use meshvol_report::units::{Density, UnitOptions, UnitsArg};
use serde::Deserialize;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use tokio::sync::Semaphore;

/// What every request shares.
struct Shared {
    config: Config,
    /// An empty folder, the server's own: uploads are read as if they were in it (and
    /// never written anywhere).
    folder: tempfile::TempDir,
    checks: Arc<Semaphore>,
    waiting: AtomicUsize,
}

/// The server's routes over `config`.
pub fn router(config: Config) -> Result<Router, String> {
    let folder = tempfile::Builder::new()
        .prefix("meshvol-serve-")
        .tempdir()
        .map_err(|e| format!("cannot make the server's empty folder: {e}"))?;
    let shared = Arc::new(Shared {
        config,
        folder,
        checks: Arc::new(Semaphore::new(config.max_concurrent.max(1))),
        waiting: AtomicUsize::new(0),
    });
    Ok(Router::new()
        .route("/", get(|| async { page::asset("index.html") }))
        .route(
            "/{*file}",
            get(|axum::extract::Path(file): axum::extract::Path<String>| async move {
                page::asset(&file)
            }),
        )
        .route("/api/limits", get(limits))
        .route("/api/check", post(|s, q, h, r| handle(s, q, h, r, false)))
        .route("/api/view", post(|s, q, h, r| handle(s, q, h, r, true)))
        .layer(DefaultBodyLimit::max(config.max_upload))
        .with_state(shared))
}

/// The limits, for the page to say them (and refuse a file too large before sending it).
async fn limits(State(shared): State<Arc<Shared>>) -> Response {
    let c = &shared.config;
    let body = serde_json::json!({
        "max_upload": c.max_upload,
        "max_concurrent": c.max_concurrent,
        "queue": c.queue,
        "timeout_s": c.timeout.as_secs_f64(),
    });
    json(StatusCode::OK, body.to_string())
}

/// The request's options, as query parameters (or multipart fields of the same names):
/// the file's name (or the `X-File-Name` header), and the command's flags.
#[derive(Clone, Debug, Default, Deserialize)]
struct Params {
    name: Option<String>,
    units: Option<String>,
    density: Option<String>,
    weld_tolerance: Option<String>,
    no_intersections: Option<String>,
}

impl Params {
    fn set(&mut self, field: &str, value: String) {
        match field {
            "name" => self.name = Some(value),
            "units" => self.units = Some(value),
            "density" => self.density = Some(value),
            "weld_tolerance" => self.weld_tolerance = Some(value),
            "no_intersections" => self.no_intersections = Some(value),
            _ => {}
        }
    }

    /// The options, or a message saying which parameter is wrong. Empty values are
    /// absent (a form's empty field).
    fn options(&self) -> Result<Options, String> {
        fn given(v: &Option<String>) -> Option<&str> {
            v.as_deref().map(str::trim).filter(|v| !v.is_empty())
        }
        let units = given(&self.units)
            .map(|u| u.parse::<UnitsArg>().map_err(|e| format!("units: {e}")))
            .transpose()?;
        let density = given(&self.density)
            .map(|d| d.parse::<Density>().map_err(|e| format!("density: {e}")))
            .transpose()?;
        let weld = given(&self.weld_tolerance)
            .map(|t| match t.parse::<f64>() {
                Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
                _ => Err(format!("weld_tolerance: must be zero or a positive number; got {t}")),
            })
            .transpose()?;
        let no_intersections = match given(&self.no_intersections) {
            None | Some("0" | "false" | "no" | "off") => false,
            Some("1" | "true" | "yes" | "on") => true,
            Some(v) => return Err(format!("no_intersections: true or false; got {v}")),
        };
        Ok(Options {
            units: UnitOptions { units, density },
            check: meshvol_report::subject::check_options(weld, !no_intersections),
        })
    }
}

/// A JSON answer.
fn json(status: StatusCode, body: String) -> Response {
    (status, [(header::CONTENT_TYPE, HeaderValue::from_static("application/json"))], body)
        .into_response()
}

/// A JSON error: `{"file": ..., "error": ...}` (the command's error line) when a file is
/// named, `{"error": ...}` otherwise.
fn error(status: StatusCode, file: Option<&str>, message: &str) -> Response {
    let body = match file {
        Some(file) => meshvol_report::error_line(file, message),
        None => serde_json::json!({ "error": message }).to_string(),
    };
    json(status, body)
}

/// Counts a request in the queue while it lives.
struct Waiting<'a>(&'a AtomicUsize);

impl Drop for Waiting<'_> {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::SeqCst);
    }
}

/// `POST /api/check` (`view` false) and `POST /api/view` (true).
async fn handle(
    State(shared): State<Arc<Shared>>,
    query: Result<Query<Params>, QueryRejection>,
    headers: HeaderMap,
    request: Request,
    view: bool,
) -> Response {
    let params = match query {
        Ok(Query(params)) => params,
        Err(e) => {
            return error(StatusCode::BAD_REQUEST, None, &format!("the query: {}", e.body_text()))
        }
    };
    let config = shared.config;
    // A free place is taken at once; otherwise the request waits, if the queue has room.
    let free = Arc::clone(&shared.checks).try_acquire_owned().ok();
    let queued = free.is_none().then(|| Waiting(&shared.waiting));
    if free.is_none() && shared.waiting.fetch_add(1, Ordering::SeqCst) >= config.queue {
        drop(queued);
        let message = format!(
            "busy: {} checks running and {} waiting; try again shortly",
            config.max_concurrent, config.queue
        );
        return error(StatusCode::SERVICE_UNAVAILABLE, None, &message);
    }
    let answer = async {
        let permit = match free {
            Some(permit) => permit,
            None => match Arc::clone(&shared.checks).acquire_owned().await {
                Ok(permit) => permit,
                Err(_) => {
                    return error(StatusCode::SERVICE_UNAVAILABLE, None, "the server is stopping")
                }
            },
        };
        drop(queued);
        let (params, name, bytes) = match upload(params, &headers, request, config.max_upload).await
        {
            Ok(upload) => upload,
            Err(response) => return response,
        };
        let options = match params.options() {
            Ok(options) => options,
            Err(e) => return error(StatusCode::BAD_REQUEST, Some(&name), &e),
        };
        let folder = shared.folder.path().to_path_buf();
        let shown = name.clone();
        // The permit goes with the check: one that outlives the time limit still counts.
        // The answer is written there too (a view can be megabytes of JSON), off the
        // threads that serve connections.
        let checked = tokio::task::spawn_blocking(move || {
            let _permit = permit;
            let (report, page) = measure::measure(&folder, &name, bytes, &options, view)
                .map_err(|e| (StatusCode::UNPROCESSABLE_ENTITY, e))?;
            let body = match page {
                None => meshvol_report::json_line(&report),
                Some(page) => serde_json::to_string(&page).map_err(|e| e.to_string()),
            };
            body.map_err(|e| (StatusCode::INTERNAL_SERVER_ERROR, format!("{name}: {e}")))
        })
        .await;
        match checked {
            Ok(Ok(body)) => json(StatusCode::OK, body),
            Ok(Err((status, e))) => error(status, Some(&shown), &e),
            Err(_) => error(
                StatusCode::INTERNAL_SERVER_ERROR,
                Some(&shown),
                &format!("{shown}: the check failed unexpectedly (a bug: please report it)"),
            ),
        }
    };
    match tokio::time::timeout(config.timeout, answer).await {
        Ok(response) => response,
        Err(_) => error(
            StatusCode::SERVICE_UNAVAILABLE,
            None,
            &format!(
                "the request took longer than the limit of {} s (waiting included); try a \
                 smaller file, or ask for a longer --timeout",
                config.timeout.as_secs_f64()
            ),
        ),
    }
}

/// The upload: the raw body (named by `?name=` or `X-File-Name`), or a multipart form's
/// `file` field (named by its filename) with the options as other fields.
async fn upload(
    mut params: Params,
    headers: &HeaderMap,
    request: Request,
    max_upload: usize,
) -> Result<(Params, String, Vec<u8>), Response> {
    let too_large = |status: StatusCode, e: String| {
        if status == StatusCode::PAYLOAD_TOO_LARGE {
            let limit = size_words(max_upload);
            error(
                status,
                None,
                &format!("the upload is larger than the limit of {limit} (--max-upload)"),
            )
        } else {
            error(status, None, &format!("cannot read the upload: {e}"))
        }
    };
    let multipart = headers
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.starts_with("multipart/form-data"));
    if !multipart {
        let header_name = headers.get("x-file-name").and_then(|v| v.to_str().ok());
        let name = params.name.as_deref().or(header_name).map(measure::file_name);
        let bytes = Bytes::from_request(request, &())
            .await
            .map_err(|e| too_large(e.status(), e.body_text()))?;
        let name = name.unwrap_or_else(|| "upload".to_string());
        return Ok((params, name, Vec::from(bytes)));
    }
    let mut form = Multipart::from_request(request, &())
        .await
        .map_err(|e| too_large(e.status(), e.body_text()))?;
    let mut file = None;
    while let Some(field) =
        form.next_field().await.map_err(|e| too_large(e.status(), e.body_text()))?
    {
        let field_name = field.name().unwrap_or_default().to_string();
        if field_name == "file" {
            let name = field.file_name().map(measure::file_name);
            let bytes = field.bytes().await.map_err(|e| too_large(e.status(), e.body_text()))?;
            file = Some((name, Vec::from(bytes)));
        } else {
            let value = field.text().await.map_err(|e| too_large(e.status(), e.body_text()))?;
            params.set(&field_name, value);
        }
    }
    let Some((file_name, bytes)) = file else {
        return Err(error(StatusCode::BAD_REQUEST, None, "the form has no `file` field"));
    };
    let name = params.name.as_deref().map(measure::file_name).or(file_name);
    Ok((params.clone(), name.unwrap_or_else(|| "upload".to_string()), bytes))
}
