//! The progress bar: it appears on a terminal once a run has lasted its delay, whatever
//! the input's size; never under `--quiet` or when stderr is not a terminal; and a run
//! quicker than the delay prints only its results.
//!
//! A terminal is `script` (util-linux, part of every Debian) running the command on a
//! pseudo-terminal. A run that lasts as long as the test wants reads a named pipe (as
//! its file, or as its standard input) that the test fills only once it has seen (or
//! waited for) the bar: the pipe is an input of 0 bytes, as small as inputs come.

mod common;
use common::{meshvol, p, write};

use serde_json::Value;
use std::io::{Read, Write};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The unit cube as OBJ triangles (volume 1).
fn cube() -> String {
    let mut s = String::new();
    for k in 0..8 {
        s += &format!("v {} {} {}\n", k & 1, (k >> 1) & 1, (k >> 2) & 1);
    }
    for q in [[0, 2, 3, 1], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5], [4, 5, 7, 6]] {
        let [a, b, c, d] = q.map(|i| i + 1);
        s += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
    }
    s
}

/// Starts `meshvol ARGS` on a pseudo-terminal (stdout and stderr both go to it), with
/// the bar's delay set to `delay_ms`; `stdin` redirects its standard input from a file.
fn on_terminal(args: &str, delay_ms: u64, stdin: Option<&Path>) -> Child {
    let mut command = format!("'{}' {args}", common::bin().display());
    if let Some(path) = stdin {
        command += &format!(" < '{}'", p(path));
    }
    Command::new("script")
        .args(["-qfec", &command, "/dev/null"])
        .env("MESHVOL_PROGRESS_DELAY_MS", delay_ms.to_string())
        .env("COLUMNS", "200")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .spawn()
        .expect("script (util-linux) runs")
}

/// Collects what `child` writes to stdout as it comes.
fn collect(child: &mut Child) -> (Arc<Mutex<Vec<u8>>>, std::thread::JoinHandle<()>) {
    let seen = Arc::new(Mutex::new(Vec::new()));
    let mut stdout = child.stdout.take().unwrap();
    let sink = Arc::clone(&seen);
    let reader = std::thread::spawn(move || {
        let mut chunk = [0u8; 4096];
        while let Ok(n @ 1..) = stdout.read(&mut chunk) {
            sink.lock().unwrap().extend_from_slice(&chunk[..n]);
        }
    });
    (seen, reader)
}

fn text(bytes: &Mutex<Vec<u8>>) -> String {
    String::from_utf8_lossy(&bytes.lock().unwrap()).into_owned()
}

/// A named pipe in `dir`.
fn fifo(dir: &Path) -> std::path::PathBuf {
    let path = dir.join("in.obj");
    let made = Command::new("mkfifo").arg(&path).status().expect("mkfifo runs");
    assert!(made.success());
    path
}

/// The JSON report in a terminal's output (after the bar's last clearing).
fn report(output: &str) -> Value {
    let start = output.find("{\"file\"").unwrap_or_else(|| panic!("no report in {output:?}"));
    let line = output[start..].lines().next().unwrap();
    serde_json::from_str(line).unwrap_or_else(|e| panic!("{e}: {line:?}"))
}

#[test]
fn a_run_longer_than_the_delay_shows_the_bar_then_its_result() {
    let dir = tempfile::tempdir().unwrap();
    let pipe = fifo(dir.path());
    let mut child = on_terminal(&format!("volume --json '{}'", p(&pipe)), 0, None);
    let (seen, reader) = collect(&mut child);
    // Opening the pipe waits for meshvol to open it.
    let mut input = std::fs::OpenOptions::new().write(true).open(&pipe).unwrap();
    let until = Instant::now() + Duration::from_secs(60);
    while !text(&seen).contains("reading ") {
        assert!(Instant::now() < until, "no bar within 60 s: {:?}", text(&seen));
        std::thread::sleep(Duration::from_millis(20));
    }
    input.write_all(cube().as_bytes()).unwrap();
    drop(input);
    assert!(child.wait().unwrap().success());
    reader.join().unwrap();
    let output = text(&seen);
    // The bar: elapsed time, and the stage it names; cleared before the report.
    assert!(output.contains("[00:00:0"), "{output:?}");
    assert_eq!(report(&output)["volume"].as_f64(), Some(1.0));
}

#[test]
fn a_run_quicker_than_the_delay_prints_only_its_result() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "cube.obj", cube());
    let mut child = on_terminal(&format!("volume --json '{}'", p(&path)), 60_000, None);
    let (seen, reader) = collect(&mut child);
    assert!(child.wait().unwrap().success());
    reader.join().unwrap();
    let output = text(&seen);
    assert!(!output.contains('\x1b') && !output.contains("[00:"), "{output:?}");
    assert_eq!(report(&output)["volume"].as_f64(), Some(1.0));
}

/// Feeds the cube to `child`'s standard input (the named pipe `pipe`, or its own stdin)
/// only after the bar has had time to appear.
fn feed_late(pipe: Option<&Path>, child: &mut Child) {
    std::thread::sleep(Duration::from_millis(500));
    let bytes = cube();
    match pipe {
        Some(pipe) => {
            std::fs::OpenOptions::new().write(true).open(pipe).unwrap().write_all(bytes.as_bytes())
        }
        None => child.stdin.take().unwrap().write_all(bytes.as_bytes()),
    }
    .unwrap();
}

#[test]
fn quiet_shows_no_bar_even_on_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let pipe = fifo(dir.path());
    let mut child = on_terminal("volume -q --json -", 0, Some(&pipe));
    let (seen, reader) = collect(&mut child);
    feed_late(Some(&pipe), &mut child);
    assert!(child.wait().unwrap().success());
    reader.join().unwrap();
    let output = text(&seen);
    assert!(!output.contains('\x1b') && !output.contains("[00:"), "{output:?}");
    assert_eq!(report(&output)["volume"].as_f64(), Some(1.0));
}

#[test]
fn no_bar_when_stderr_is_not_a_terminal() {
    let mut child = Command::new(common::bin())
        .args(["volume", "--json", "-"])
        .env("MESHVOL_PROGRESS_DELAY_MS", "0")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    feed_late(None, &mut child);
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    assert!(out.stderr.is_empty(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["volume"].as_f64(), Some(1.0));
    // And the same file read from a path agrees.
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "cube.obj", cube());
    let again: Value = serde_json::from_slice(&meshvol(&["volume", "--json", p(&path)]).stdout)
        .expect("one JSON line");
    assert_eq!(again["volume"], report["volume"]);
}
