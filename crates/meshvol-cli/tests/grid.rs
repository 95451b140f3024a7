//! `meshvol grid`, `profile` and `union` end to end: the built binary on files written
//! here, checked against closed forms (boxes) and by reading the outputs back.

mod common;
use common::{f, meshvol, p, read_npy, read_npz, read_vti, write};

use serde_json::Value;
use std::path::Path;
use std::process::Output;

fn json(out: &Output) -> Value {
    assert!(out.status.success(), "stderr: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

fn keys(v: &Value) -> Vec<String> {
    let mut k: Vec<String> = v.as_object().expect("an object").keys().cloned().collect();
    k.sort();
    k
}

/// OBJ text of the box `lo..hi` (quads wound outward), its vertices numbered from
/// `first`.
fn box_obj(lo: [f64; 3], hi: [f64; 3], first: usize) -> String {
    let mut s = String::new();
    for k in 0..8 {
        let p =
            [0, 1, 2]
                .map(|a| if [k & 1, (k >> 1) & 1, (k >> 2) & 1][a] == 1 { hi[a] } else { lo[a] });
        s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    // Corners: bit 0 = x, bit 1 = y, bit 2 = z.
    for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [1, 3, 7, 5], [3, 2, 6, 7], [2, 0, 4, 6]] {
        s += &format!("f {} {} {} {}\n", q[0] + first, q[1] + first, q[2] + first, q[3] + first);
    }
    s
}

/// Length of [a0, a1] ∩ [b0, b1].
fn overlap(a0: f64, a1: f64, b0: f64, b1: f64) -> f64 {
    (a1.min(b1) - a0.max(b0)).max(0.0)
}

#[test]
fn grid_writes_npy_vti_and_csv_that_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let (lo, hi) = ([0.25, 0.5, -0.3], [1.5, 1.25, 0.9]);
    let mesh = write(dir.path(), "box.obj", box_obj(lo, hi, 1));
    // A negative first number must not read as a flag.
    let bounds = "-0,0,-0.5,2,1.5,1";
    let (npy, vti, csv) =
        (dir.path().join("c.npy"), dir.path().join("c.vti"), dir.path().join("c.csv"));
    for out in [&npy, &vti, &csv] {
        let summary = json(&meshvol(&[
            "grid",
            p(&mesh),
            "--cells",
            "4,3,5",
            "--bounds",
            bounds,
            "--out",
            p(out),
            "--json",
        ]));
        assert_eq!(summary["cells"], serde_json::json!([4, 3, 5]));
        assert_eq!(summary["bounds_from"], "given");
        assert_eq!(summary["bounds"]["min"], serde_json::json!([0.0, 0.0, -0.5]));
        let volume = 1.25 * 0.75 * 1.2;
        assert!((f(&summary["total"]) - volume).abs() < 1e-14);
        assert!((f(&summary["mesh_volume"]) - volume).abs() < 1e-14);
        let counted = ["cells_full", "cells_partial", "cells_empty"]
            .iter()
            .map(|k| summary[k].as_u64().unwrap())
            .sum::<u64>();
        assert_eq!(counted, 60);
    }
    // The box against every cell: the product of the overlaps of the intervals.
    let (cell, origin) = ([0.5, 0.5, 0.3], [0.0, 0.0, -0.5]);
    let expected = |i: usize, j: usize, k: usize| -> f64 {
        (0..3)
            .map(|a| {
                let c0 = origin[a] + [i, j, k][a] as f64 * cell[a];
                overlap(c0, c0 + cell[a], lo[a], hi[a])
            })
            .product()
    };
    let (shape, values) = read_npy(&npy);
    assert_eq!(shape, vec![4, 3, 5]);
    for i in 0..4 {
        for j in 0..3 {
            for k in 0..5 {
                let v = values[(i * 3 + j) * 5 + k];
                assert!((v - expected(i, j, k)).abs() < 1e-15, "npy {i},{j},{k}: {v}");
            }
        }
    }
    let v = read_vti(&vti);
    assert_eq!(v.extent, vec![0, 4, 0, 3, 0, 5]);
    assert_eq!(v.origin, origin.to_vec());
    assert_eq!(v.spacing, vec![0.5, 0.5, 0.3]);
    for k in 0..5 {
        for j in 0..3 {
            for i in 0..4 {
                let at = (k * 3 + j) * 4 + i;
                assert_eq!(v.array("volume")[at], values[(i * 3 + j) * 5 + k]);
                let cell_volume = 0.5 * 0.5 * 0.3;
                assert!(
                    (v.array("fraction")[at] - values[(i * 3 + j) * 5 + k] / cell_volume).abs()
                        < 1e-15
                );
            }
        }
    }
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("i,j,k,volume,fraction"));
    let rows: Vec<Vec<f64>> =
        lines.map(|l| l.split(',').map(|x| x.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), values.iter().filter(|&&x| x != 0.0).count());
    for r in rows {
        let (i, j, k) = (r[0] as usize, r[1] as usize, r[2] as usize);
        assert_eq!(r[3], values[(i * 3 + j) * 5 + k]);
    }
    // --fraction: volumes over the cell volume.
    let fractions = dir.path().join("f.npy");
    json(&meshvol(&[
        "grid",
        p(&mesh),
        "--cells",
        "4,3,5",
        "--bounds",
        bounds,
        "--out",
        p(&fractions),
        "--fraction",
        "--json",
    ]));
    let (_, fr) = read_npy(&fractions);
    let cell_volume = 0.5 * 0.5 * 0.3;
    assert!(fr.iter().zip(&values).all(|(a, b)| (a - b / cell_volume).abs() < 1e-15));
}

#[test]
fn grid_defaults_to_the_bounding_box_and_draws_a_slice() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write(dir.path(), "box.obj", box_obj([0.0; 3], [1.0, 2.0, 3.0], 1));
    let png = dir.path().join("s.png");
    let summary = json(&meshvol(&[
        "grid",
        p(&mesh),
        "--pitch",
        "0.4",
        "--json",
        "--png",
        p(&png),
        "--slice",
        "y=2",
    ]));
    // 1/0.4 → 3 cells, 2/0.4 → 5, 3/0.4 → 8: the box grows to whole cells.
    assert_eq!(summary["cells"], serde_json::json!([3, 5, 8]));
    assert_eq!(summary["bounds_from"], "mesh");
    assert_eq!(summary["bounds"]["min"], serde_json::json!([0.0, 0.0, 0.0]));
    assert!((f(&summary["total"]) - 6.0).abs() < 1e-14);
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // Text: says which bounds were used.
    let out = meshvol(&["grid", p(&mesh), "--cells", "2,2,2"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("(from the meshes' bounding box)") && text.contains("total          6"),
        "{text}"
    );
}

#[test]
fn grid_refuses_bad_grids_with_clear_messages() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write(dir.path(), "box.obj", box_obj([0.0; 3], [1.0; 3], 1));
    let usage = [
        vec!["--cells", "0,4,4"],
        vec!["--cells", "4,4"],
        vec!["--cells", "a,b,c"],
        vec!["--pitch", "-1"],
        vec!["--cells", "2,2,2", "--bounds", "0,0,0,1,1"],
        vec!["--cells", "2,2,2", "--bounds", "1,0,0,0,1,1"],
        vec!["--cells", "2,2,2", "--out", "x.txt"],
        vec!["--cells", "2,2,2", "--png", "x.png", "--slice", "w=1"],
    ];
    for extra in usage {
        let mut args = vec!["grid", p(&mesh)];
        args.extend(extra.iter().copied());
        let out = meshvol(&args);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{extra:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let out = meshvol(&["grid", p(&mesh), "--cells", "1000000,1000000,1000000"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.starts_with("meshvol: error:") && err.contains("6.9 EiB"), "{err}");
    // A slice outside the grid.
    let png = dir.path().join("s.png");
    let out = meshvol(&["grid", p(&mesh), "--cells", "2,2,2", "--png", p(&png), "--slice", "z=5"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("outside the grid"));
    // A flat mesh has no box of its own.
    let flat = write(dir.path(), "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let out = meshvol(&["grid", p(&flat), "--cells", "2,2,2"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("give --bounds"));
}

#[test]
fn profile_json_and_csv() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write(dir.path(), "box.obj", box_obj([0.0; 3], [2.0, 3.0, 4.0], 1));
    let v = json(&meshvol(&["profile", p(&mesh), "--levels", "4", "--json"]));
    assert_eq!(
        keys(&v),
        [
            "axis",
            "file",
            "levels",
            "section_area",
            "slab_volume",
            "units",
            "volume_below",
            "warnings"
        ]
    );
    assert_eq!(v["axis"], "z");
    assert_eq!(v["levels"], serde_json::json!([0.0, 1.0, 2.0, 3.0, 4.0]));
    assert_eq!(v["volume_below"], serde_json::json!([0.0, 6.0, 12.0, 18.0, 24.0]));
    assert_eq!(v["slab_volume"], serde_json::json!([6.0, 6.0, 6.0, 6.0]));
    assert_eq!(v["section_area"], serde_json::json!([6.0, 6.0, 6.0, 6.0, 6.0]));
    let v = json(&meshvol(&["profile", p(&mesh), "--axis", "y", "--step", "2", "--json"]));
    assert_eq!(v["levels"], serde_json::json!([0.0, 2.0, 4.0]));
    assert_eq!(v["volume_below"], serde_json::json!([0.0, 16.0, 24.0]));
    let out = meshvol(&["profile", p(&mesh), "--axis", "x", "--levels", "2", "--csv"]);
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "level,volume_below,slab_volume,section_area\n0.0,0.0,12.0,12.0\n1.0,12.0,12.0,12.0\n2.0,24.0,,12.0\n"
    );
    assert_eq!(meshvol(&["profile", p(&mesh), "--levels", "0"]).status.code(), Some(2));
    assert_eq!(meshvol(&["profile", p(&mesh)]).status.code(), Some(2));
}

#[test]
fn union_of_files_and_of_shells() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (([0.0; 3], [2.0; 3]), ([1.0, 0.5, 1.5], [3.0, 1.75, 2.5]));
    let exact = 8.0 + 2.0 * 1.25 * 1.0 - 1.0 * 1.25 * 0.5;
    let fa = write(dir.path(), "a.obj", box_obj(a.0, a.1, 1));
    let fb = write(dir.path(), "b.obj", box_obj(b.0, b.1, 1));
    let both = write(dir.path(), "ab.obj", &(box_obj(a.0, a.1, 1) + &box_obj(b.0, b.1, 9)));
    for files in [vec![p(&fa), p(&fb)], vec![p(&both)]] {
        let mut args = vec!["union"];
        args.extend(files);
        args.push("--json");
        let v = json(&meshvol(&args));
        assert_eq!(
            keys(&v),
            [
                "bodies",
                "body_names",
                "cells_refined",
                "cells_resolved_exactly",
                "certified",
                "columns_unresolved",
                "file",
                "files",
                "flipped",
                "grid",
                "lower",
                "seconds",
                "sum_of_volumes",
                "uncertified_reason",
                "units",
                "upper",
                "volume",
                "volume_uncertainty",
                "warnings"
            ]
        );
        assert_eq!(v["bodies"], 2);
        assert_eq!(f(&v["sum_of_volumes"]), 10.5);
        assert!(f(&v["lower"]) <= exact && exact <= f(&v["upper"]), "{v}");
        assert!(f(&v["upper"]) - f(&v["lower"]) <= 1e-6 * exact);
        // (serde_json's default parser may be an ulp off.)
        assert!((f(&v["volume"]) - 0.5 * (f(&v["lower"]) + f(&v["upper"]))).abs() < 1e-14);
    }
    // The grid of the union sums to the union's volume.
    let v = json(&meshvol(&["grid", p(&both), "--union", "--cells", "7,5,6", "--json"]));
    assert_eq!(v["bodies"], 2);
    assert!((f(&v["total"]) - exact).abs() < 1e-13, "{v}");
    let v = json(&meshvol(&["grid", p(&both), "--cells", "7,5,6", "--json"]));
    assert!((f(&v["total"]) - 10.5).abs() < 1e-13, "{v}");
}

#[test]
fn grid_moments_write_the_cut_cells_of_a_box() {
    let dir = tempfile::tempdir().unwrap();
    let (lo, hi) = ([0.25, 0.5, -0.3], [1.5, 1.25, 0.9]);
    let mesh = write(dir.path(), "box.obj", box_obj(lo, hi, 1));
    let (origin, cell) = ([0.0, 0.0, -0.5], [0.5, 0.5, 0.3]);
    let moments_to = |out: &Path| {
        let args = ["grid", p(&mesh), "--cells", "4,3,5", "--bounds", "0,0,-0.5,2,1.5,1"];
        json(&meshvol(&[&args[..], &["--moments", "--out", p(out), "--json"]].concat()))
    };
    let npz = dir.path().join("c.npz");
    let summary = moments_to(&npz);
    assert_eq!(summary["moments"], true);
    let arrays = read_npz(&npz);
    let names: Vec<&str> = arrays.keys().map(String::as_str).collect();
    assert_eq!(
        names,
        [
            "aperture_x",
            "aperture_y",
            "aperture_z",
            "boundary_area",
            "boundary_centroid",
            "boundary_vector",
            "cell_size",
            "centroid",
            "fraction",
            "origin",
            "volume"
        ]
    );
    assert_eq!(arrays["centroid"].0, [4, 3, 5, 3]);
    assert_eq!(arrays["aperture_x"].0, [5, 3, 5]);
    assert_eq!(arrays["aperture_z"].0, [4, 3, 6]);
    assert_eq!(arrays["origin"].1, origin);
    // Every cell against the box: the overlap's volume and middle, the box's faces in it.
    let range = |a: usize, n: usize| {
        let c0 = origin[a] + n as f64 * cell[a];
        (c0.max(lo[a]), (c0 + cell[a]).min(hi[a]), c0)
    };
    for n in 0..60 {
        let at = [n / 15, n / 5 % 3, n % 5];
        let o = [0, 1, 2].map(|a| range(a, at[a]));
        let len = o.map(|(a, b, _)| (b - a).max(0.0));
        let volume: f64 = len.iter().product();
        assert!((arrays["volume"].1[n] - volume).abs() < 1e-14, "{at:?}");
        if volume > 1e-9 {
            for a in 0..3 {
                let mid = 0.5 * (o[a].0 + o[a].1);
                assert!((arrays["centroid"].1[3 * n + a] - mid).abs() < 1e-12, "{at:?}");
            }
        }
        let mut area = 0.0;
        for a in 0..3 {
            let across = len[(a + 1) % 3] * len[(a + 2) % 3];
            for plane in [lo[a], hi[a]] {
                if plane >= o[a].2 && plane < o[a].2 + cell[a] {
                    area += across;
                }
            }
        }
        assert!((arrays["boundary_area"].1[n] - area).abs() < 1e-14, "{at:?}");
    }
    // Σ boundary_area is the box's area; the z apertures inside the box are its
    // cross-section in each cell face.
    let total: f64 = arrays["boundary_area"].1.iter().sum();
    let box_area = 2.0 * (1.25 * 0.75 + 1.25 * 1.2 + 0.75 * 1.2);
    assert!((total - box_area).abs() < 1e-13);
    let z_face = |i: usize, j: usize, k: usize| arrays["aperture_z"].1[(i * 3 + j) * 6 + k];
    assert!((z_face(1, 1, 3) - 1.0).abs() < 1e-14 && z_face(1, 1, 5) == 0.0);
    assert!((z_face(0, 1, 2) - 0.5).abs() < 1e-14, "x from 0.25 to 0.5: half the face");

    // .vti: the same arrays by name; the apertures as field arrays.
    let vti = dir.path().join("c.vti");
    moments_to(&vti);
    let xml = String::from_utf8_lossy(&std::fs::read(&vti).unwrap()).to_string();
    for name in [
        "centroid\" NumberOfComponents=\"3\"",
        "aperture_x\" NumberOfComponents=\"1\" NumberOfTuples=\"75\"",
    ] {
        assert!(xml.contains(name), "{name}");
    }
    // Bad combinations are refused by name.
    let out = meshvol(&[
        "grid",
        p(&mesh),
        "--cells",
        "4,3,5",
        "--moments",
        "--out",
        p(&dir.path().join("c.npy")),
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("give --out cells.npz, cells.vti or cells.zarr"), "{err}");
}

#[test]
fn grid_union_moments_write_the_cut_cells_of_the_union() {
    // Two boxes overlapping in [1, 2] × [0.5, 2] × [1.25, 2], one file each.
    let dir = tempfile::tempdir().unwrap();
    let (a_lo, a_hi) = ([0.0, 0.0, 0.0], [2.0, 2.0, 2.0]);
    let (b_lo, b_hi) = ([1.0, 0.5, 1.25], [3.0, 2.5, 3.0]);
    let a = write(dir.path(), "a.obj", box_obj(a_lo, a_hi, 1));
    let b = write(dir.path(), "b.obj", box_obj(b_lo, b_hi, 1));
    // No grid plane on a box face.
    let grid = ["--cells", "8,8,8", "--bounds", "-0.3,-0.2,-0.35,3.3,3,3.65"];
    let (origin, cell) = ([-0.3, -0.2, -0.35], [0.45, 0.4, 0.5]);
    let npz = dir.path().join("u.npz");
    let run = |out: &Path, extra: &[&str]| {
        let args = [&["grid", p(&a), p(&b), "--union"][..], &grid[..], extra].concat();
        json(&meshvol(&[&args[..], &["--out", p(out), "--json"]].concat()))
    };
    let summary = run(&npz, &["--moments", "--second-moments", "--face-centroids"]);
    assert_eq!((summary["moments"].clone(), summary["union"].clone()), (true.into(), true.into()));
    assert_eq!(summary["columns_unresolved"], 0);
    let arrays = read_npz(&npz);
    let names: Vec<&str> = arrays.keys().map(String::as_str).collect();
    let mut want = vec![
        "aperture_x",
        "aperture_x_centroid",
        "aperture_y",
        "aperture_y_centroid",
        "aperture_z",
        "aperture_z_centroid",
        "boundary_area",
        "boundary_centroid",
        "boundary_vector",
        "cell_size",
        "centroid",
        "fraction",
        "inertia",
        "origin",
        "volume",
    ];
    want.sort();
    assert_eq!(names, want);
    assert_eq!(arrays["inertia"].0, [8, 8, 8, 3, 3]);
    assert_eq!(arrays["aperture_y"].0, [8, 9, 8]);
    // Every cell against inclusion–exclusion of the boxes: volume and first moment.
    let meet = |lo: [f64; 3], hi: [f64; 3], c0: [f64; 3]| {
        let len = [0, 1, 2].map(|d| (hi[d].min(c0[d] + cell[d]) - lo[d].max(c0[d])).max(0.0));
        let mid = [0, 1, 2].map(|d| 0.5 * (hi[d].min(c0[d] + cell[d]) + lo[d].max(c0[d])));
        let v: f64 = len.iter().product();
        (v, mid.map(|m| m * v))
    };
    let (ab_lo, ab_hi) = ([1.0, 0.5, 1.25], [2.0, 2.0, 2.0]);
    for n in 0..512 {
        let at = [n / 64, n / 8 % 8, n % 8];
        let c0 = [0, 1, 2].map(|d| origin[d] + at[d] as f64 * cell[d]);
        let parts = [meet(a_lo, a_hi, c0), meet(b_lo, b_hi, c0), meet(ab_lo, ab_hi, c0)];
        let volume = parts[0].0 + parts[1].0 - parts[2].0;
        assert!((arrays["volume"].1[n] - volume).abs() < 1e-12, "{at:?}");
        for d in 0..3 {
            let m = parts[0].1[d] + parts[1].1[d] - parts[2].1[d];
            let got = arrays["volume"].1[n] * arrays["centroid"].1[3 * n + d];
            assert!((got - m).abs() < 1e-12, "{at:?}");
        }
    }
    // The union's surface: both boxes' areas, less the faces each hides in the other.
    let area: f64 = arrays["boundary_area"].1.iter().sum();
    let hidden = 2.0 * (1.5 * 0.75 + 0.75 + 1.5);
    assert!((area - (24.0 + 22.0 - hidden)).abs() < 1e-11, "{area}");
    // The volumes are `grid --union`'s.
    let npy = dir.path().join("u.npy");
    run(&npy, &[]);
    let (_, volumes) = read_npy(&npy);
    for (x, y) in arrays["volume"].1.iter().zip(&volumes) {
        assert!((x - y).abs() < 1e-12);
    }
    // A body that is not a solid (two shells overlapping in one file: the cells' bounds
    // do not hold) has no exact boundary to give: refused, naming why; the volumes alone
    // are still given.
    let two = dir.path().join("two.obj");
    std::fs::write(&two, box_obj(a_lo, a_hi, 1) + &box_obj([1.0; 3], [3.0; 3], 9)).unwrap();
    let args = ["grid", p(&two), p(&b), "--union", "--cells", "6,6,6"];
    let out = meshvol(&[&args[..], &["--moments", "--out", p(&npz)]].concat());
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("the union's boundary could not be resolved in"), "{err}");
    assert!(meshvol(&[&args[..], &["--out", p(&npy)]].concat()).status.success());
    // .vti too (.zarr: `grid_zarr.rs`).
    let vti = dir.path().join("u.vti");
    run(&vti, &["--moments"]);
    let xml = String::from_utf8_lossy(&std::fs::read(&vti).unwrap()).to_string();
    assert!(xml.contains("boundary_vector\" NumberOfComponents=\"3\""));
}

#[test]
fn grid_second_moments_and_face_centroids_of_a_box() {
    let dir = tempfile::tempdir().unwrap();
    let (lo, hi) = ([0.25, 0.5, -0.3], [1.5, 1.25, 0.9]);
    let mesh = write(dir.path(), "box.obj", box_obj(lo, hi, 1));
    let (origin, cell) = ([0.0, 0.0, -0.5], [0.5, 0.5, 0.3]);
    let run = |out: &Path, extra: &[&str]| {
        let args = ["grid", p(&mesh), "--cells", "4,3,5", "--bounds", "0,0,-0.5,2,1.5,1"];
        meshvol(&[&args[..], &["--moments", "--out", p(out)], extra].concat())
    };
    let npz = dir.path().join("c.npz");
    let summary = json(&run(&npz, &["--second-moments", "--face-centroids", "--json"]));
    assert_eq!(
        (&summary["second_moments"], &summary["face_centroids"]),
        (&true.into(), &true.into())
    );
    let arrays = read_npz(&npz);
    assert_eq!(arrays["inertia"].0, [4, 3, 5, 3, 3]);
    assert_eq!(arrays["aperture_x_centroid"].0, [5, 3, 5, 3]);
    assert_eq!(arrays["aperture_y_centroid"].0, [4, 4, 5, 3]);
    assert_eq!(arrays["aperture_z_centroid"].0, [4, 3, 6, 3]);
    let range = |a: usize, n: usize| {
        let c0 = origin[a] + n as f64 * cell[a];
        (c0.max(lo[a]), (c0 + cell[a]).min(hi[a]))
    };
    for n in 0..60 {
        let at = [n / 15, n / 5 % 3, n % 5];
        let len = [0, 1, 2].map(|a| {
            let (a0, a1) = range(a, at[a]);
            (a1 - a0).max(0.0)
        });
        let v: f64 = len.iter().product();
        // The overlap box about its centre: V (l_b² + l_c²) / 12 on the diagonal, no products.
        for a in 0..3 {
            for b in 0..3 {
                let want = if a == b {
                    v * (len[(a + 1) % 3].powi(2) + len[(a + 2) % 3].powi(2)) / 12.0
                } else {
                    0.0
                };
                let got = arrays["inertia"].1[9 * n + 3 * a + b];
                assert!((got - want).abs() < 1e-15, "{at:?} [{a}][{b}]: {got} vs {want}");
            }
        }
    }
    // z faces: the rectangle of the box in the face, its middle; NaN outside the box.
    let z = |i: usize, j: usize, k: usize| {
        let n = ((i * 3 + j) * 6 + k) * 3;
        arrays["aperture_z_centroid"].1[n..n + 3].to_vec()
    };
    let middle = |a: usize, n: usize| 0.5 * (range(a, n).0 + range(a, n).1);
    for (i, j, k) in [(0, 1, 2), (1, 1, 3), (2, 2, 1)] {
        let want = [middle(0, i), middle(1, j), origin[2] + k as f64 * cell[2]];
        let got = z(i, j, k);
        assert!(got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-14), "{got:?} vs {want:?}");
    }
    assert!(z(3, 0, 2).iter().all(|x| x.is_nan()) && z(1, 1, 5).iter().all(|x| x.is_nan()));

    // .vti: the inertia as a 9-component cell array, the centroids as field arrays.
    let vti = dir.path().join("c.vti");
    assert!(run(&vti, &["--second-moments", "--face-centroids"]).status.success());
    let xml = String::from_utf8_lossy(&std::fs::read(&vti).unwrap()).to_string();
    for name in [
        "inertia\" NumberOfComponents=\"9\"",
        "aperture_x_centroid\" NumberOfComponents=\"3\" NumberOfTuples=\"75\"",
        "aperture_z_centroid\" NumberOfComponents=\"3\" NumberOfTuples=\"72\"",
    ] {
        assert!(xml.contains(name), "{name}");
    }
    // Without the flags, none of it; the flags need --moments.
    let plain = dir.path().join("plain.npz");
    let summary = json(&run(&plain, &["--json"]));
    assert_eq!(summary["second_moments"], false);
    assert!(!read_npz(&plain).contains_key("inertia"));
    let out =
        meshvol(&["grid", p(&mesh), "--cells", "4,3,5", "--out", p(&npz), "--second-moments"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--moments"));
}
