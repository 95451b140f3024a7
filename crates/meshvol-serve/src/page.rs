//! The page's files, embedded in the binary, and the self-contained page of
//! `meshvol check --html` (the same page with its scripts and one file's content
//! inlined).

use axum::http::{header, HeaderValue};
use axum::response::{IntoResponse, Response};

const INDEX: &str = include_str!("page/index.html");
const APP: &str = include_str!("page/app.js");
const STYLE: &str = include_str!("page/style.css");
const THREE: &str = include_str!("page/vendor/three.min.js");
const ORBIT: &str = include_str!("page/vendor/OrbitControls.js");
const THREE_LICENSE: &str = include_str!("page/vendor/LICENSE-three.txt");

/// What the page may load and run: its own files only (no inline script, nothing from
/// elsewhere), the 3D view's drawings, requests to this server; and no other page may
/// frame it.
const POLICY: &str = "default-src 'none'; script-src 'self'; style-src 'self'; \
                      img-src 'self' data: blob:; connect-src 'self'; base-uri 'none'; \
                      form-action 'none'; frame-ancestors 'none'";

/// The embedded file at `path` (as the page names it), or 404.
pub fn asset(path: &str) -> Response {
    let (body, kind) = match path {
        "index.html" => (INDEX, "text/html; charset=utf-8"),
        "app.js" => (APP, "text/javascript; charset=utf-8"),
        "style.css" => (STYLE, "text/css; charset=utf-8"),
        "vendor/three.min.js" => (THREE, "text/javascript; charset=utf-8"),
        "vendor/OrbitControls.js" => (ORBIT, "text/javascript; charset=utf-8"),
        "vendor/LICENSE-three.txt" => (THREE_LICENSE, "text/plain; charset=utf-8"),
        _ => return crate::respond::not_found(),
    };
    (
        [
            (header::CONTENT_TYPE, HeaderValue::from_static(kind)),
            (header::X_CONTENT_TYPE_OPTIONS, HeaderValue::from_static("nosniff")),
            (header::X_FRAME_OPTIONS, HeaderValue::from_static("DENY")),
            (header::CONTENT_SECURITY_POLICY, HeaderValue::from_static(POLICY)),
        ],
        body,
    )
        .into_response()
}

/// A script made safe inside a `<script>` element: no `</script` can close it (the
/// vendored files have none, scripts/update-three.sh checks; in the page's own strings
/// `<\/` means the same).
fn in_script(code: &str) -> String {
    code.replace("</script", "<\\/script")
}

/// JSON made safe inside a `<script>` element: every `<` as `\u003c`, so no file name
/// can close the element or open a comment.
fn json_in_script(json: &str) -> String {
    json.replace('<', "\\u003c")
}

/// The page as one file: the scripts and the stylesheet inlined, and `content` (the
/// page's JSON for one file: `Page`) given to it, so it shows that file without a server.
pub fn standalone(content_json: &str) -> String {
    // The inlined three.js goes with its licence.
    let licence = format!(
        "<!-- three.js, vendored from Debian's libjs-three:\n{}-->",
        THREE_LICENSE.replace("--", "- -")
    );
    let scripts = format!(
        "<style>\n{STYLE}</style>\n{licence}\n<script>\n{}\n</script>\n<script>\n{}\n</script>\n\
         <script>window.MESHVOL_PAGE = {};</script>\n<script>\n{}\n</script>",
        in_script(THREE),
        in_script(ORBIT),
        json_in_script(content_json),
        in_script(APP)
    );
    let start = INDEX.find("<!-- assets -->").unwrap_or(0);
    let end = INDEX.find("<!-- /assets -->").map_or(start, |e| e + "<!-- /assets -->".len());
    format!("{}{scripts}{}", &INDEX[..start], &INDEX[end..])
}
