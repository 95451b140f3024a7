//! Who may ask: every request must name this server in its `Host` (else 421), and a
//! request a browser sends from another site's page must not get through (403).
//!
//! - `Host` is answered when it is the bound address, any IP address when bound to all
//!   of them (`0.0.0.0`), `localhost` when bound to loopback or all, or a name given
//!   with `--allow-host`. A page on another name that resolves to this machine (DNS
//!   rebinding) sends its own name, and is refused.
//! - `Origin`, when a request has one, must be this same server: its host and port
//!   those of `Host`, or its host a name given with `--allow-host` (a proxy in front
//!   may rewrite `Host`). A form or script on any other page (cross-site request
//!   forgery) is refused, and so is the `null` origin of sandboxed pages and files.

use crate::respond::error;
use axum::extract::{Request, State};
use axum::http::{header, StatusCode};
use axum::middleware::Next;
use axum::response::Response;
use std::net::IpAddr;
use std::sync::Arc;

/// The names a request may give for this server.
#[derive(Debug)]
pub(crate) struct Hosts {
    bind: IpAddr,
    /// `--allow-host` names, lowercase, without a trailing dot.
    names: Vec<String>,
}

impl Hosts {
    pub(crate) fn new(bind: IpAddr, names: &[String]) -> Hosts {
        Hosts { bind, names: names.iter().map(|n| normal(n)).collect() }
    }

    /// Whether `host` (a `Host` value, with or without a port) names this server.
    fn allows(&self, host: &str) -> bool {
        let name = without_port(host);
        if let Ok(ip) = name.trim_start_matches('[').trim_end_matches(']').parse::<IpAddr>() {
            return self.bind.is_unspecified()
                || ip == self.bind
                || (self.bind.is_loopback() && ip.is_loopback());
        }
        let name = normal(name);
        (name == "localhost" && (self.bind.is_loopback() || self.bind.is_unspecified()))
            || self.names.contains(&name)
    }

    /// Whether `origin` (`scheme://host[:port]`) is this server, asked as `host`.
    fn same_origin(&self, origin: &str, host: &str) -> bool {
        let Some((_, authority)) = origin.split_once("://") else { return false };
        authority.eq_ignore_ascii_case(host)
            || self.names.contains(&normal(without_port(authority)))
    }
}

/// A host name as compared: lowercase, without the trailing dot of a rooted name.
fn normal(name: &str) -> String {
    name.trim().trim_end_matches('.').to_ascii_lowercase()
}

/// The host of `host[:port]` (`[v6]:port` keeps its brackets).
fn without_port(authority: &str) -> &str {
    match authority.rfind(':') {
        Some(colon) if !authority[colon..].contains(']') && authority.matches(':').count() == 1 => {
            &authority[..colon]
        }
        Some(colon) if authority.starts_with('[') && authority[..colon].ends_with(']') => {
            &authority[..colon]
        }
        _ => authority,
    }
}

/// The middleware: refuses a request from elsewhere before any route sees it.
pub(crate) async fn guard(
    State(hosts): State<Arc<Hosts>>,
    request: Request,
    next: Next,
) -> Response {
    let headers = request.headers();
    let host = headers.get(header::HOST).and_then(|h| h.to_str().ok()).unwrap_or_default();
    if !hosts.allows(host) {
        let message = format!(
            "this server does not answer for the host '{}': ask for it by its address, or \
             start it with --allow-host NAME",
            host.escape_default()
        );
        return error(StatusCode::MISDIRECTED_REQUEST, None, &message);
    }
    if let Some(origin) = headers.get(header::ORIGIN) {
        let origin = String::from_utf8_lossy(origin.as_bytes());
        if !hosts.same_origin(&origin, host) {
            let message = format!(
                "a page from '{}' may not use this server (only its own page may)",
                origin.escape_default()
            );
            return error(StatusCode::FORBIDDEN, None, &message);
        }
    }
    next.run(request).await
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hosts_are_the_bound_address_localhost_or_allowed_names() {
        let loopback = Hosts::new("127.0.0.1".parse().unwrap(), &["Parts.Shop.".to_string()]);
        for ok in ["127.0.0.1:8765", "127.0.0.1", "localhost:8765", "LOCALHOST", "[::1]:80"] {
            assert!(loopback.allows(ok), "{ok}");
        }
        assert!(loopback.allows("parts.shop:8765") && loopback.allows("PARTS.SHOP."));
        for refused in ["evil.example", "evil.example:8765", "10.0.0.5:8765", "", "localhost.evil"]
        {
            assert!(!loopback.allows(refused), "{refused}");
        }
        let all = Hosts::new("0.0.0.0".parse().unwrap(), &[]);
        assert!(all.allows("192.168.1.20:8765") && all.allows("[fe80::1]:8765"));
        assert!(!all.allows("shop.example"));
        let one = Hosts::new("192.168.1.20".parse().unwrap(), &[]);
        assert!(one.allows("192.168.1.20:8765") && !one.allows("192.168.1.21:8765"));
        assert!(!one.allows("localhost:8765"));
    }

    #[test]
    fn origins_are_this_server_or_allowed_names() {
        let hosts = Hosts::new("127.0.0.1".parse().unwrap(), &["parts.shop".to_string()]);
        assert!(hosts.same_origin("http://127.0.0.1:8765", "127.0.0.1:8765"));
        assert!(hosts.same_origin("https://parts.shop", "127.0.0.1:8765"));
        assert!(!hosts.same_origin("http://127.0.0.1:9999", "127.0.0.1:8765"));
        assert!(!hosts.same_origin("http://evil.example", "127.0.0.1:8765"));
        assert!(!hosts.same_origin("null", "127.0.0.1:8765"));
    }
}
