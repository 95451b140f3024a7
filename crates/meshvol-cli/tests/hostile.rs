//! Untrusted input: devices and endless streams stop at once with a clear error, in
//! bounded memory; absurd settings are refused or capped with a message.

mod common;
use common::{meshvol, three_mf, write};
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
        let mut child = Command::new(common::bin())
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

/// A 3MF placing a tetrahedron of volume 1/8 `n`×`n` times (two levels of components,
/// copies 2 apart along x and y), the second level mirrored in x every other row when
/// `mirror`: about 2 KB for 10⁶ copies.
fn placed_tetrahedra(n: usize, mirror: bool) -> String {
    let mut model = String::from(
        r#"<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>
        <object id="1" type="model"><mesh><vertices>
        <vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="0.75"/>
        </vertices><triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/>
        <triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles></mesh></object>
        <object id="2" type="model"><components>"#,
    );
    for i in 0..n {
        model +=
            &format!(r#"<component objectid="1" transform="1 0 0 0 1 0 0 0 1 {} 0 0"/>"#, 2 * i);
    }
    model += r#"</components></object><object id="3" type="model"><components>"#;
    for j in 0..n {
        let sx = if mirror && j % 2 == 1 { -1 } else { 1 };
        let x = if sx < 0 { 2 * n } else { 0 };
        model += &format!(
            r#"<component objectid="2" transform="{sx} 0 0 0 1 0 0 0 1 {x} {} 0"/>"#,
            2 * j
        );
    }
    model + r#"</components></object></resources><build><item objectid="3"/></build></model>"#
}

/// The keys of `volume --json` and `check --json` that the test of a million placements
/// reads. Deserialized into this, the million entries of `shell_details` are skipped
/// unbuilt: building them as a `serde_json::Value` took this test 30 s in a debug build.
#[derive(serde::Deserialize)]
struct Facts {
    volume: Option<f64>,
    shells: Option<u64>,
    closed: Option<bool>,
    bounds_a_volume: Option<bool>,
    solid_volume: Option<f64>,
    orientation: Option<String>,
    edges: Option<u64>,
    euler_characteristic: Option<i64>,
}

/// 10⁶ placed copies are checked from their one part: the checked volume is exactly
/// 10⁶ × 1/8, every copy a closed shell, and `check` agrees.
#[test]
fn a_million_placements_are_measured_from_their_part() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "tets.3mf", three_mf(&placed_tetrahedra(1000, true)));
    let out = meshvol(&["volume", "--json", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: Facts = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r.volume, Some(125000.0));
    assert_eq!(r.shells, Some(1_000_000));
    assert_eq!((r.closed, r.bounds_a_volume), (Some(true), Some(true)));
    let out = meshvol(&["check", "--json", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let c: Facts = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!((c.solid_volume, c.orientation.as_deref()), (Some(125000.0), Some("outward")));
    assert_eq!((c.edges, c.euler_characteristic), (Some(6_000_000), Some(2_000_000)));
}
