//! A `meshvol serve` started for a test, and plain HTTP requests to it.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

/// A running `meshvol serve --port 0`, stopped when dropped.
pub struct Server {
    child: Child,
    /// `http://127.0.0.1:PORT`
    pub url: String,
}

impl Server {
    /// Starts the server with `args` after `serve --port 0`; waits until it listens.
    pub fn start(args: &[&str]) -> Server {
        Server::start_in_env(args, &[])
    }

    /// [`Server::start`] with the variables `env` set.
    pub fn start_in_env(args: &[&str], env: &[(&str, &str)]) -> Server {
        let mut child = Command::new(super::bin())
            .args(["serve", "--port", "0"])
            .args(args)
            .envs(env.iter().copied())
            .stderr(Stdio::piped())
            .stdout(Stdio::null())
            .spawn()
            .expect("meshvol serve starts");
        let mut stderr = BufReader::new(child.stderr.take().unwrap());
        let mut line = String::new();
        stderr.read_line(&mut line).unwrap();
        let url = line
            .split("serving on ")
            .nth(1)
            .and_then(|rest| rest.split('/').nth(2))
            .map(|host| format!("http://{host}"))
            .unwrap_or_else(|| panic!("no address in the server's first line: {line}"));
        // Keep reading its stderr so the server never blocks on a full pipe.
        std::thread::spawn(move || {
            let mut sink = String::new();
            while stderr.read_line(&mut sink).is_ok_and(|n| n > 0) {
                sink.clear();
            }
        });
        Server { child, url }
    }

    /// Sends the server the signal `name` (`TERM`, `INT`) and waits for it to exit.
    pub fn stop(mut self, name: &str) -> std::process::ExitStatus {
        let pid = self.child.id().to_string();
        let sent = Command::new("kill").args([&format!("-{name}"), &pid]).status();
        assert!(sent.is_ok_and(|s| s.success()), "kill -{name} {pid}");
        self.child.wait().expect("the server exits")
    }

    /// The server's process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// POSTs `body` to `path` (with its query); the status and the body as text.
    pub fn post(&self, path: &str, body: &[u8]) -> (u16, String) {
        self.post_typed(path, body, "application/octet-stream")
    }

    /// POSTs `body` with the content type `kind`.
    pub fn post_typed(&self, path: &str, body: &[u8], kind: &str) -> (u16, String) {
        let agent = agent();
        let mut response = agent
            .post(format!("{}{path}", self.url))
            .header("content-type", kind)
            .send(body)
            .expect("the server answers");
        (response.status().as_u16(), response.body_mut().read_to_string().unwrap())
    }

    /// GETs `path`: the status and the body.
    pub fn get(&self, path: &str) -> (u16, String) {
        let mut response = agent().get(format!("{}{path}", self.url)).call().expect("answers");
        (response.status().as_u16(), response.body_mut().read_to_string().unwrap())
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// An HTTP client that returns 4xx and 5xx answers instead of failing on them.
pub fn agent() -> ureq::Agent {
    ureq::Agent::config_builder().http_status_as_error(false).build().into()
}

/// The peak resident memory of process `pid` in KiB (Linux: VmHWM), if known.
pub fn peak_memory_kib(pid: u32) -> Option<u64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}
