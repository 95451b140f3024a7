//! `meshvol grid --out cells.zarr`: the Zarr v3 group read here by hand (its zarr.json
//! files, consolidated metadata and raw little-endian chunks) against the `.npy` the
//! command writes for the same grid, against a box's closed-form volume, and its
//! coordinate arrays against the cells' centres computed from the bounds.

mod common;
use common::{box_obj, f, meshvol, numbers, p, read_npy, read_npz, read_zarr, write};

use serde_json::Value;

/// OBJ text of a tetrahedron-fan octahedron: centre `c`, half-diagonal `r`; volume
/// 4r³/3, and its faces lie on no grid plane below.
fn octahedron(c: [f64; 3], r: f64) -> String {
    let mut s = String::new();
    for (a, sign) in [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0), (2, 1.0), (2, -1.0)] {
        let mut v = c;
        v[a] += sign * r;
        s += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    // Vertices: 1 +x, 2 −x, 3 +y, 4 −y, 5 +z, 6 −z; faces wound outward.
    for t in
        [[1, 3, 5], [3, 2, 5], [2, 4, 5], [4, 1, 5], [3, 1, 6], [2, 3, 6], [4, 2, 6], [1, 4, 6]]
    {
        s += &format!("f {} {} {}\n", t[0], t[1], t[2]);
    }
    s
}

/// The group's `zarr.json`, checked to consolidate exactly `members`' metadata (each
/// member's own `zarr.json`).
fn group_meta(store: &std::path::Path, members: &[&str]) -> Value {
    let read = |at: &std::path::Path| -> Value {
        serde_json::from_slice(&std::fs::read(at.join("zarr.json")).unwrap()).unwrap()
    };
    let group = read(store);
    assert_eq!(group["node_type"], "group");
    let consolidated = &group["consolidated_metadata"];
    assert_eq!(consolidated["kind"], "inline");
    let listed = consolidated["metadata"].as_object().unwrap();
    let mut names: Vec<&str> = listed.keys().map(String::as_str).collect();
    let mut want = members.to_vec();
    names.sort();
    want.sort();
    assert_eq!(names, want);
    for name in members {
        assert_eq!(listed[*name], read(&store.join(name)), "{name}");
    }
    group
}

/// The coordinate arrays beside the cut cells: the cells' centres and the faces' planes.
const COORDINATES: [&str; 6] = ["x", "y", "z", "x_face", "y_face", "z_face"];

fn json(args: &[&str]) -> Value {
    let out = meshvol(args);
    assert!(out.status.success(), "stderr: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

#[test]
fn zarr_chunks_hold_the_npy_cells() {
    let dir = tempfile::tempdir().unwrap();
    let (centre, r) = ([0.31, -0.17, 0.23], 1.1);
    let mesh = write(dir.path(), "octahedron.obj", octahedron(centre, r));
    let (npy, store) = (dir.path().join("c.npy"), dir.path().join("c.zarr"));
    let bounds = "-1.2,-1.4,-1.1,1.6,1.3,1.5";
    let grid = ["grid", p(&mesh), "--cells", "11,9,13", "--bounds", bounds, "--json"];
    let from_npy = json(&[&grid[..], &["--out", p(&npy)]].concat());
    let from_zarr = json(&[&grid[..], &["--out", p(&store), "--chunks", "4,5,6"]].concat());

    let (meta, cells) = read_zarr(&store.join("volume"));
    assert_eq!(numbers(&meta["shape"]), [11, 9, 13]);
    assert_eq!(numbers(&meta["chunk_grid"]["configuration"]["chunk_shape"]), [4, 5, 6]);
    assert_eq!(meta["dimension_names"], serde_json::json!(["x", "y", "z"]));
    let group = group_meta(&store, &["volume", "x", "y", "z"]);
    assert_eq!(group["attributes"]["origin"], serde_json::json!([-1.2, -1.4, -1.1]));
    assert_eq!(group["attributes"]["values"], "volume");
    // The cells' centres, from the bounds and the summary's cell size.
    for (a, (lo, n)) in [(-1.2, 11), (-1.4, 9), (-1.1, 13)].into_iter().enumerate() {
        let name = ["x", "y", "z"][a];
        let (meta, centres) = read_zarr(&store.join(name));
        assert_eq!(meta["dimension_names"], serde_json::json!([name]));
        let cell = f(&from_zarr["cell_size"][a]);
        let want: Vec<f64> = (0..n).map(|i| lo + (i as f64 + 0.5) * cell).collect();
        assert_eq!(centres, want);
    }
    let (shape, values) = read_npy(&npy);
    assert_eq!(shape, [11, 9, 13]);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&cells), bits(&values));
    // Independent of both: the octahedron's volume, and the same summary either way.
    let volume = 4.0 * r * r * r / 3.0;
    assert!((cells.iter().sum::<f64>() - volume).abs() < 1e-13);
    for key in ["total", "cells_full", "cells_partial", "cells_empty"] {
        assert_eq!(from_zarr[key], from_npy[key], "{key}");
    }
    assert_eq!(from_zarr["chunks"], serde_json::json!([4, 5, 6]));
    assert_eq!(from_npy["chunks"], Value::Null);
    // A corner chunk wholly outside the octahedron (its nearest corner (0.84, 0.1, 1.3)
    // is 1.87 from the centre in the 1-norm) holds only zeros and is not stored.
    assert!(!store.join("volume/c/2/1/2").exists() && store.join("volume/c/1/1/1").exists());

    // Written again over itself with other chunks and as fractions: nothing stale.
    json(&[&grid[..], &["--out", p(&store), "--chunks", "11,2,13", "--fraction"]].concat());
    let (_, fractions) = read_zarr(&store.join("fraction"));
    let group = group_meta(&store, &["fraction", "x", "y", "z"]);
    assert_eq!(group["attributes"]["values"], "fraction");
    assert!(!store.join("volume").exists());
    let cell = (2.8 / 11.0) * (2.7 / 9.0) * (2.6 / 13.0);
    for (fraction, v) in fractions.iter().zip(&values) {
        assert!((fraction - v / cell).abs() <= 1e-15, "{fraction} vs {}", v / cell);
    }
}

#[test]
fn zarr_misuse_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write(dir.path(), "o.obj", octahedron([0.0; 3], 1.0));
    let file = write(dir.path(), "taken.zarr", "not a directory");
    let run = |extra: &[&str]| {
        let out = meshvol(&[&["grid", p(&mesh), "--cells", "4,4,4"][..], extra].concat());
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (code, err) = run(&["--out", p(&file)]);
    assert_eq!(code, Some(1));
    assert!(err.contains("taken.zarr: is a file"), "{err}");
    let (code, err) = run(&["--chunks", "2,2,2"]);
    assert_eq!(code, Some(1));
    assert!(err.contains("--chunks is for a .zarr output"), "{err}");
    let store = dir.path().join("u.zarr");
    let (code, err) = run(&["--out", p(&store), "--union"]);
    assert_eq!(code, Some(1));
    assert!(err.contains("--union (without --moments) and --png need the whole grid"), "{err}");
    let (code, _) = run(&["--out", p(&store), "--chunks", "0,2,2"]);
    assert_eq!(code, Some(2));
}

#[test]
fn zarr_moments_group_holds_the_npz_arrays_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let (centre, r) = ([0.31, -0.17, 0.23], 1.1);
    let octahedron = write(dir.path(), "octahedron.obj", octahedron(centre, r));
    // A box on its own bounding box: its faces on the grid's far faces, whose cells and
    // apertures (the far x faces, written by the last chunk row) hold them.
    let cube =
        write(dir.path(), "box.obj", box_obj([0.1, -0.3, 0.2], [1.4, 0.9, 1.1], 1, true, false));
    let cases = [
        // Bounds through the solid: its section on the far faces is their aperture.
        (&octahedron, vec!["--cells", "12,9,13", "--bounds", "-0.5,-1.4,-1.1,0.9,0.6,1.0"]),
        (&cube, vec!["--cells", "11,7,5"]),
    ];
    let (npz, store) = (dir.path().join("c.npz"), dir.path().join("c.zarr"));
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let extras = ["--second-moments", "--face-centroids"];
    let cases = cases.into_iter().flat_map(|(m, g)| [(m, g.clone(), &[][..]), (m, g, &extras[..])]);
    for (mesh, grid, flags) in cases {
        let args = [&["grid", p(mesh), "--moments", "--json"][..], &grid[..], flags].concat();
        let from_npz = json(&[&args[..], &["--out", p(&npz)]].concat());
        let arrays = read_npz(&npz);
        let nx: usize = grid[1].split(',').next().unwrap().parse().unwrap();
        // Chunks that divide NX (the x faces' NX + 1 layers then end in a chunk row of
        // their own) and that do not, one cell thick, and the whole grid.
        for chunks in ["4,5,6", "3,2,13", "5,4,4", "1,3,2", &format!("{nx},64,64")] {
            let from_zarr = json(&[&args[..], &["--out", p(&store), "--chunks", chunks]].concat());
            let mut members: Vec<&str> = arrays.keys().map(String::as_str).collect();
            members.retain(|n| *n != "origin" && *n != "cell_size");
            members.extend(COORDINATES);
            let group = group_meta(&store, &members);
            for (key, name) in [("origin", "origin"), ("cell_size", "cell_size")] {
                let want = &arrays[name].1;
                let got: Vec<f64> =
                    group["attributes"][key].as_array().unwrap().iter().map(f).collect();
                assert_eq!(bits(&got), bits(want), "{key}");
            }
            let mut names = Vec::new();
            for (name, (shape, values)) in &arrays {
                if name == "origin" || name == "cell_size" {
                    continue;
                }
                let (meta, stored) = read_zarr(&store.join(name));
                assert_eq!(&numbers(&meta["shape"]), shape, "{name} in chunks {chunks}");
                assert_eq!(bits(&stored), bits(values), "{name} in chunks {chunks}");
                names.push(name.clone());
            }
            // Every cut-cell array and the coordinates, no other.
            names.extend(COORDINATES.map(String::from));
            names.sort();
            let mut held: Vec<String> = std::fs::read_dir(&store)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .filter(|n| n != "zarr.json")
                .collect();
            held.sort();
            assert_eq!(held, names);
            // The 9 arrays, and with the extras `inertia` and the 3 face centroids.
            assert_eq!(names.len(), 15 + 4 * usize::from(!flags.is_empty()), "{names:?}");
            if !flags.is_empty() {
                let (meta, _) = read_zarr(&store.join("inertia"));
                let dims = serde_json::json!(["x", "y", "z", "row", "column"]);
                assert_eq!(meta["dimension_names"], dims);
                let (meta, _) = read_zarr(&store.join("aperture_y_centroid"));
                let dims = serde_json::json!(["x", "y_face", "z", "component"]);
                assert_eq!(meta["dimension_names"], dims);
            }
            let (meta, _) = read_zarr(&store.join("aperture_x"));
            assert_eq!(meta["dimension_names"], serde_json::json!(["x_face", "y", "z"]));
            let (meta, _) = read_zarr(&store.join("centroid"));
            assert_eq!(meta["dimension_names"], serde_json::json!(["x", "y", "z", "component"]));
            let keys = ["total", "cells_full", "cells_partial", "cells_empty", "moments", "cells"];
            for key in keys.into_iter().chain(["second_moments", "face_centroids"]) {
                assert_eq!(from_zarr[key], from_npz[key], "{key}");
            }
        }
    }
    // Independent of both: the octahedron's volume in the cells.
    json(
        &[
            &["grid", p(&octahedron), "--cells", "5,6,7", "--moments"][..],
            &["--json", "--out", p(&store)],
        ]
        .concat(),
    );
    let (_, volume) = read_zarr(&store.join("volume"));
    assert!((volume.iter().sum::<f64>() - 4.0 * r * r * r / 3.0).abs() < 1e-13);
}

#[test]
fn a_unions_moments_group_holds_its_npz_arrays_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let a = write(dir.path(), "o.obj", octahedron([0.31, -0.17, 0.23], 1.1));
    let b = write(dir.path(), "b.obj", box_obj([0.1, -0.3, 0.2], [1.4, 0.9, 1.1], 1, true, false));
    let (npz, store) = (dir.path().join("u.npz"), dir.path().join("u.zarr"));
    let args = [
        "grid",
        p(&a),
        p(&b),
        "--union",
        "--cells",
        "9,7,8",
        "--moments",
        "--second-moments",
        "--face-centroids",
        "--json",
    ];
    let from_npz = json(&[&args[..], &["--out", p(&npz)]].concat());
    let from_zarr = json(&[&args[..], &["--out", p(&store), "--chunks", "4,3,5"]].concat());
    assert_eq!(from_zarr["total"], from_npz["total"]);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let arrays = read_npz(&npz);
    assert_eq!(arrays.len(), 15);
    // Every array but the grid's origin and cell size (the group's attributes).
    let cut_cells = arrays.iter().filter(|(n, _)| *n != "origin" && *n != "cell_size");
    for (name, (shape, values)) in cut_cells {
        let (meta, stored) = read_zarr(&store.join(name));
        assert_eq!(&numbers(&meta["shape"]), shape, "{name}");
        assert_eq!(bits(&stored), bits(values), "{name}");
    }
}

#[test]
fn a_moments_group_and_a_volumes_array_over_each_other_leave_nothing_behind() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = write(dir.path(), "o.obj", octahedron([0.0; 3], 1.0));
    let store = dir.path().join("c.zarr");
    let grid = ["grid", p(&mesh), "--cells", "4,4,4", "--out", p(&store), "--chunks", "2,2,2"];
    json(&[&grid[..], &["--json", "--density", "2"]].concat());
    assert!(store.join("mass/c/0/0/0").exists());
    json(&[&grid[..], &["--json", "--moments"]].concat());
    assert!(!store.join("mass").exists() && store.join("volume/c/0/0/0").exists());
    assert!(store.join("x_face").exists());
    // And back: the volumes alone over the group leave none of its other arrays, and a
    // file of the user's in the folder is not touched.
    std::fs::write(store.join("notes.txt"), "mine").unwrap();
    json(&[&grid[..], &["--json"]].concat());
    assert!(store.join("volume/c/0/0/0").exists() && !store.join("x_face").exists());
    assert!(!store.join("centroid").exists() && store.join("notes.txt").exists());
    group_meta(&store, &["volume", "x", "y", "z"]);
}
