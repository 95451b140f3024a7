//! Untrusted input: devices and endless streams stop at once with a clear error, in
//! bounded memory; absurd settings are refused or capped with a message.

mod common;
use common::meshvol;
use std::io::Write;
use std::process::{Command, Stdio};

#[test]
fn devices_are_refused() {
    for args in [["volume", "/dev/zero"], ["hull", "/dev/zero"], ["area", "/dev/zero"]] {
        let out = meshvol(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("/dev/zero") && stderr.contains("device"), "{args:?}: {stderr}");
    }
}

#[test]
fn an_endless_stream_stops_at_the_limit() {
    for command in ["volume", "hull", "area"] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_meshvol"))
            .args([command, "-"])
            .env("MESHVOL_MAX_STREAM_BYTES", "1000000")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let mut stdin = child.stdin.take().unwrap();
        // 4 MB of a stream that would go on: the command stops reading after 1 MB, so
        // the write fails once it has closed the pipe.
        let feeder = std::thread::spawn(move || {
            let chunk = vec![b'1'; 1 << 16];
            for _ in 0..64 {
                if stdin.write_all(&chunk).is_err() {
                    break;
                }
            }
        });
        let out = child.wait_with_output().unwrap();
        feeder.join().unwrap();
        assert_eq!(out.status.code(), Some(1), "{command}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains("past 1000000 bytes"), "{command}: {stderr}");
    }
}

#[test]
fn negative_settings_say_what_they_must_be() {
    let out = meshvol(&["volume", "x.stl", "--density", "-1"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("--density") && stderr.contains("must be a positive number"));
    let out = meshvol(&["union", "x.stl", "--tolerance", "-1e-6"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("must be a positive number"));
}
