//! `meshvol grid --backend opencl` against `--backend cpu`: the same file, byte for
//! byte, where an OpenCL device with f64 is installed (PoCL in CI; otherwise the
//! comparisons say they skipped), the volumes and the cut cells (`--moments`);
//! `meshvol devices`; what only the CPU computes; a device that fails (a build or an
//! allocation the driver refuses, provoked through `MESHVOL_OPENCL_FAULT`).

mod common;
use common::{box_obj, p, write};
use serde_json::Value;
use std::process::{Command, Output};

/// The command cargo built for these tests, even where `MESHVOL_BIN` names another: CI
/// names its static release binary, which cannot load the OpenCL library (docs/gpu.md),
/// so every comparison here would skip there.
const BIN: &str = env!("CARGO_BIN_EXE_meshvol");

fn meshvol(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().expect("meshvol runs")
}

fn devices() -> Value {
    let out = meshvol(&["devices", "--json"]);
    assert!(out.status.success(), "stderr: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Whether a device with f64 is listed (said on stderr when not).
fn have_device() -> bool {
    let listed = devices();
    let found = listed["devices"].as_array().unwrap().iter().any(|d| d["fp64"] == true);
    if !found {
        eprintln!("skipped: no OpenCL device with f64 ({listed})");
    }
    found
}

#[test]
fn devices_lists_and_names_what_auto_takes() {
    let listed = devices();
    let list = listed["devices"].as_array().unwrap();
    assert_eq!(listed["opencl"].as_bool().unwrap(), listed["opencl"] == true);
    for (index, d) in list.iter().enumerate() {
        assert_eq!(d["index"], index);
        assert!(["GPU", "CPU", "accelerator", "other"].contains(&d["type"].as_str().unwrap()));
        assert!(d["memory_bytes"].as_u64().unwrap() >= d["max_alloc_bytes"].as_u64().unwrap());
    }
    // auto takes a GPU with f64, never a CPU device: the CPU path is meshvol's own.
    if let Some(auto) = listed["auto"].as_u64() {
        assert_eq!(list[auto as usize]["type"], "GPU");
        assert_eq!(list[auto as usize]["fp64"], true);
    }
    let text = meshvol(&["devices"]);
    assert!(text.status.success());
}

#[test]
fn opencl_files_are_the_cpu_files_byte_for_byte() {
    if !have_device() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let sample = concat!(env!("CARGO_MANIFEST_DIR"), "/../../samples/flanged-bushing.stl");
    let open =
        write(dir.path(), "open.obj", box_obj([0.1, 0.2, 0.3], [2.3, 1.9, 2.8], 1, true, true));
    let cases: [(&str, &[&str]); 5] = [
        (sample, &["--cells", "31,29,17"]),
        (sample, &["--cells", "20,21,22", "--fraction"]),
        // Bounds cutting through the part: the rest is beside, above and below.
        (sample, &["--cells", "13,9,11", "--bounds", "-10,-35,5,40,10,20"]),
        (sample, &["--pitch", "2.5", "--no-check"]),
        (p(&open), &["--cells", "7,6,5", "--no-check", "--bounds", "0,0,0,3,3,3"]),
    ];
    for (k, (file, extra)) in cases.iter().enumerate() {
        for ext in ["npy", "csv", "vti"] {
            let run = |backend: &str| {
                let out = dir.path().join(format!("{k}-{backend}.{ext}"));
                let mut args = vec!["grid", file, "--out", p(&out), "--backend", backend];
                args.extend_from_slice(extra);
                let run = meshvol(&args);
                assert!(run.status.success(), "{args:?}: {}", String::from_utf8_lossy(&run.stderr));
                std::fs::read(out).unwrap()
            };
            assert!(run("cpu") == run("opencl"), "case {k} {extra:?}, .{ext}: the files differ");
        }
    }
}

#[test]
fn opencl_moments_files_are_the_cpu_files_byte_for_byte() {
    if !have_device() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let sample = concat!(env!("CARGO_MANIFEST_DIR"), "/../../samples/flanged-bushing.stl");
    let open =
        write(dir.path(), "open.obj", box_obj([0.1, 0.2, 0.3], [2.3, 1.9, 2.8], 1, true, true));
    let cases: [(&str, &[&str]); 3] = [
        (sample, &["--cells", "23,19,11"]),
        // Bounds cutting through the part, in other units.
        (sample, &["--cells", "13,9,11", "--bounds", "-10,-35,5,40,10,20", "--units", "mm:cm"]),
        (p(&open), &["--cells", "7,6,5", "--no-check", "--bounds", "0,0,0,3,3,3"]),
    ];
    for (k, (file, extra)) in cases.iter().enumerate() {
        for ext in ["npz", "vti"] {
            let run = |backend: &str| {
                let out = dir.path().join(format!("{k}-{backend}.{ext}"));
                let mut args =
                    vec!["grid", file, "--moments", "--out", p(&out), "--backend", backend];
                args.extend_from_slice(extra);
                let run = meshvol(&args);
                assert!(run.status.success(), "{args:?}: {}", String::from_utf8_lossy(&run.stderr));
                std::fs::read(out).unwrap()
            };
            assert!(run("cpu") == run("opencl"), "case {k} {extra:?}, .{ext}: the files differ");
        }
    }
}

#[test]
fn what_only_the_cpu_computes_refuses_opencl() {
    let dir = tempfile::tempdir().unwrap();
    let cube = write(dir.path(), "cube.obj", box_obj([0.0; 3], [1.0; 3], 1, true, false));
    let npz = dir.path().join("cells.npz");
    let zarr = dir.path().join("cells.zarr");
    for (args, what) in [
        (vec!["--out", p(&npz), "--moments", "--second-moments"], "--second-moments"),
        (vec!["--out", p(&npz), "--moments", "--face-centroids"], "--face-centroids"),
        (vec!["--union"], "--union"),
        (vec!["--out", p(&zarr)], ".zarr"),
    ] {
        let mut all = vec!["grid", p(&cube), "--cells", "4,4,4", "--backend", "opencl"];
        all.extend(args.iter().copied());
        let out = meshvol(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        // A usage error, before any file is read: exit 2, saying it runs on the CPU.
        assert_eq!(out.status.code(), Some(2), "{all:?}: {stderr}");
        assert!(stderr.contains(what) && stderr.contains("CPU only"), "{all:?}: {stderr}");
        // auto computes them on the CPU.
        all[5] = "auto";
        let out = meshvol(&all);
        assert!(out.status.success(), "{all:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    let out = meshvol(&[
        "grid",
        p(&cube),
        "--cells",
        "4,4,4",
        "--backend",
        "opencl",
        "--opencl-device",
        "999",
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // A usage error, before any file is read: exit 2, naming OpenCL.
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("OpenCL"), "{stderr}");
}

#[test]
fn a_failing_device_is_an_error_naming_it_and_auto_falls_back_to_the_cpu_bits() {
    let listed = devices();
    let Some(index) = listed["devices"].as_array().unwrap().iter().position(|d| d["fp64"] == true)
    else {
        eprintln!("skipped: no OpenCL device with f64 ({listed})");
        return;
    };
    let name = listed["devices"][index]["name"].as_str().unwrap().to_string();
    let dir = tempfile::tempdir().unwrap();
    let sample = concat!(env!("CARGO_MANIFEST_DIR"), "/../../samples/flanged-bushing.stl");
    let device = index.to_string();
    let run = |backend: &str, fault: Option<&str>, moments: bool| {
        let ext = if moments { "npz" } else { "npy" };
        let out = dir.path().join(format!("{backend}-{}.{ext}", fault.unwrap_or("none")));
        let mut command = Command::new(BIN);
        command.args(["grid", sample, "--cells", "21,19,13", "--out", p(&out)]);
        if moments {
            command.arg("--moments");
        }
        command.args(["--backend", backend]);
        if backend != "cpu" {
            command.args(["--opencl-device", &device]);
        }
        if let Some(fault) = fault {
            command.env("MESHVOL_OPENCL_FAULT", fault);
        }
        let output = command.output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr).to_string();
        (output.status, stderr, std::fs::read(out).ok())
    };
    // The volumes, and the cut cells (--moments).
    for moments in [false, true] {
        let (status, _, cpu) = run("cpu", None, moments);
        assert!(status.success());
        for (fault, says) in [("build", "did not build"), ("alloc", "clCreateBuffer (cells)")] {
            let fault_of = format!("{fault}, moments: {moments}");
            // --backend opencl: an error naming the device and what OpenCL said, no file.
            let (status, stderr, file) = run("opencl", Some(fault), moments);
            assert_eq!(status.code(), Some(1), "{fault_of}: {stderr}");
            assert!(stderr.contains(&name) && stderr.contains(says), "{fault_of}: {stderr}");
            assert!(file.is_none(), "{fault_of}: a file was written");
            // --backend auto: a warning saying the same, and the CPU's file, byte for byte.
            let (status, stderr, file) = run("auto", Some(fault), moments);
            assert!(status.success(), "{fault_of}: {stderr}");
            assert!(stderr.contains("warning") && stderr.contains(&name), "{fault_of}: {stderr}");
            assert!(stderr.contains(says) && stderr.contains("on the CPU"), "{fault_of}: {stderr}");
            assert!(file == cpu, "{fault_of}: auto's file is not the CPU's");
        }
    }
}
