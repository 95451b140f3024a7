//! What the server is told ([`Config`], [`Budgets`]): a leaf the other files import.

use std::net::IpAddr;
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
