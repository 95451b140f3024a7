//! The server's answers as JSON: a body, an error (the command's error line when a file
//! is named), 404 and 413 naming the budget. Every route and check answers through
//! these.

use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};

/// A JSON answer.
pub(crate) fn json(status: StatusCode, body: String) -> Response {
    (status, [(header::CONTENT_TYPE, HeaderValue::from_static("application/json"))], body)
        .into_response()
}

/// A JSON error: `{"file": ..., "error": ...}` (the command's error line) when a file is
/// named, `{"error": ...}` otherwise.
pub(crate) fn error(status: StatusCode, file: Option<&str>, message: &str) -> Response {
    let body = match file {
        Some(file) => meshvol_report::error_line(file, message),
        None => serde_json::json!({ "error": message }).to_string(),
    };
    json(status, body)
}

/// 404 for a path that is neither the page's nor the API's.
pub(crate) fn not_found() -> Response {
    error(
        StatusCode::NOT_FOUND,
        None,
        "no such page: the page is /, the API /api/check, /api/view and /api/limits",
    )
}

/// 413 naming the budget (its flag) that `file` went past.
pub(crate) fn over_budget(file: &str, budget: &str, message: &str) -> Response {
    let body = serde_json::json!({
        "file": file,
        "error": format!("{message} (the budget {budget}: raise it to allow more)"),
        "budget": budget,
    });
    json(StatusCode::PAYLOAD_TOO_LARGE, body.to_string())
}

/// A JSON answer already written.
pub(crate) fn json_bytes(body: Vec<u8>) -> Response {
    (StatusCode::OK, [(header::CONTENT_TYPE, HeaderValue::from_static("application/json"))], body)
        .into_response()
}
