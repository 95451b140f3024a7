//! An upload: its body read into memory at a minimum rate and within the bytes all
//! requests may hold, then its file and options (the raw body named by `?name=` or
//! `X-File-Name`, or a `multipart/form-data` form's `file` field and option fields).

use crate::config::Config;
use crate::measure::{self, Options};
use crate::respond::error;
use crate::size::size_words;
use axum::body::Body;
use axum::extract::{FromRequest, Multipart, Request};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::Response;
use http_body_util::BodyExt;
use meshvol_report::units::{Density, UnitOptions, UnitsArg};
use serde::Deserialize;
use std::sync::Arc;
use tokio::sync::{OwnedSemaphorePermit, Semaphore};
use tokio::time::Instant;

/// The options' names, as query parameters and form fields.
const OPTIONS: &str = "name, units, density, weld_tolerance, no_intersections";

/// The request's options, as query parameters (or multipart fields of the same names):
/// the file's name (or the `X-File-Name` header), and the command's flags. Any other
/// name is refused: a misspelt option must not be measured without.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Params {
    name: Option<String>,
    units: Option<String>,
    density: Option<String>,
    weld_tolerance: Option<String>,
    no_intersections: Option<String>,
}

impl Params {
    /// A form field's value, or a message naming a field that is not an option.
    fn set(&mut self, field: &str, value: String) -> Result<(), String> {
        let slot = match field {
            "name" => &mut self.name,
            "units" => &mut self.units,
            "density" => &mut self.density,
            "weld_tolerance" => &mut self.weld_tolerance,
            "no_intersections" => &mut self.no_intersections,
            _ => {
                return Err(format!(
                    "unknown form field `{}`: the fields are file, {OPTIONS}",
                    field.escape_default()
                ))
            }
        };
        *slot = Some(value);
        Ok(())
    }

    /// The options, or a message saying which parameter is wrong. Empty values are
    /// absent (a form's empty field).
    pub(crate) fn options(&self) -> Result<Options, String> {
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

/// An upload read: its options, its file's name and bytes, and its share of the bytes
/// all requests may hold (given back when dropped).
pub(crate) struct Upload {
    pub params: Params,
    pub name: String,
    pub bytes: Vec<u8>,
    pub held: Option<OwnedSemaphorePermit>,
}

/// Reads the upload of `request` (begun at `start`): 408 when it comes slower than
/// `--min-rate`, 413 past `--max-upload`, 503 when the bytes held by all requests
/// would pass `--max-buffered`, 400 for a form without a file or with an unknown field.
pub(crate) async fn read(
    mut params: Params,
    request: Request,
    start: Instant,
    config: &Config,
    buffered: &Arc<Semaphore>,
) -> Result<Upload, Response> {
    let headers = request.headers().clone();
    let (bytes, held) = body(request.into_body(), &headers, start, config, buffered).await?;
    let kind = headers.get(header::CONTENT_TYPE).and_then(|v| v.to_str().ok());
    let Some(kind) = kind.filter(|v| v.starts_with("multipart/form-data")) else {
        let header_name = headers.get("x-file-name").and_then(|v| v.to_str().ok());
        let name =
            params.name.as_deref().or(header_name).map_or("upload".into(), measure::file_name);
        return Ok(Upload { params, name, bytes, held });
    };
    // The form is parsed from the bytes already held: its file is copied out once.
    let form = Request::builder()
        .header(header::CONTENT_TYPE, HeaderValue::from_str(kind).map_err(|_| bad_form())?)
        .body(Body::from(bytes))
        .map_err(|_| bad_form())?;
    let mut form =
        Multipart::from_request(form, &()).await.map_err(|e| unreadable(e.body_text()))?;
    let mut file = None;
    while let Some(field) = form.next_field().await.map_err(|e| unreadable(e.body_text()))? {
        let field_name = field.name().unwrap_or_default().to_string();
        if field_name == "file" {
            let name = field.file_name().map(measure::file_name);
            let bytes = field.bytes().await.map_err(|e| unreadable(e.body_text()))?;
            file = Some((name, Vec::from(bytes)));
        } else {
            let value = field.text().await.map_err(|e| unreadable(e.body_text()))?;
            params.set(&field_name, value).map_err(|e| error(StatusCode::BAD_REQUEST, None, &e))?;
        }
    }
    let Some((file_name, bytes)) = file else {
        return Err(error(StatusCode::BAD_REQUEST, None, "the form has no `file` field"));
    };
    let name = params.name.as_deref().map(measure::file_name).or(file_name);
    Ok(Upload { params, name: name.unwrap_or_else(|| "upload".to_string()), bytes, held })
}

fn unreadable(e: String) -> Response {
    error(StatusCode::BAD_REQUEST, None, &format!("cannot read the upload: {e}"))
}

fn bad_form() -> Response {
    unreadable("the form's content type is not one".to_string())
}

/// The body's bytes, each counted against `buffered` as it arrives.
async fn body(
    mut body: Body,
    headers: &HeaderMap,
    start: Instant,
    config: &Config,
    buffered: &Arc<Semaphore>,
) -> Result<(Vec<u8>, Option<OwnedSemaphorePermit>), Response> {
    let too_large = || {
        let limit = size_words(config.max_upload);
        let message = format!("the upload is larger than the limit of {limit} (--max-upload)");
        error(StatusCode::PAYLOAD_TOO_LARGE, None, &message)
    };
    let declared = headers
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok());
    if declared.is_some_and(|n| n > config.max_upload as u64) {
        return Err(too_large());
    }
    // Reserved, not touched: only the pages written are memory.
    let mut data = Vec::with_capacity(declared.unwrap_or(0) as usize);
    let mut held: Option<OwnedSemaphorePermit> = None;
    loop {
        // The body may take `client_timeout`, and then as long as `min_rate` allows
        // for what has come: a client that trickles is cut off, whatever its size.
        let allowed = data.len() as f64 / config.min_rate.max(1) as f64;
        let deadline = start + config.client_timeout + std::time::Duration::from_secs_f64(allowed);
        let frame = match tokio::time::timeout_at(deadline, body.frame()).await {
            Err(_) => return Err(too_slow(config)),
            Ok(None) => break,
            Ok(Some(Err(e))) => return Err(unreadable(e.to_string())),
            Ok(Some(Ok(frame))) => frame,
        };
        // Trailers carry nothing an upload needs.
        let Ok(chunk) = frame.into_data() else { continue };
        if data.len() + chunk.len() > config.max_upload {
            return Err(too_large());
        }
        let share = u32::try_from(chunk.len())
            .ok()
            .and_then(|n| Arc::clone(buffered).try_acquire_many_owned(n).ok());
        let Some(share) = share else {
            let message = format!(
                "busy: the uploads being read and checked hold {} (--max-buffered); try \
                 again shortly",
                size_words(config.max_buffered)
            );
            return Err(error(StatusCode::SERVICE_UNAVAILABLE, None, &message));
        };
        match &mut held {
            Some(held) => held.merge(share),
            None => held = Some(share),
        }
        data.extend_from_slice(&chunk);
    }
    Ok((data, held))
}

/// 408, closing the connection: the rest of a slow body is not waited for.
fn too_slow(config: &Config) -> Response {
    let message = format!(
        "the upload came slower than {}/s after the first {} s (--min-rate, --client-timeout)",
        size_words(config.min_rate),
        config.client_timeout.as_secs_f64()
    );
    let mut response = error(StatusCode::REQUEST_TIMEOUT, None, &message);
    response.headers_mut().insert(header::CONNECTION, HeaderValue::from_static("close"));
    response
}
