//! `meshvol area`, `section` and `hull` on small files, checked against values known in
//! closed form.

mod common;
use common::{f, meshvol, write};

use serde_json::Value;

/// Runs a command that must succeed with one JSON object per line on stdout.
fn json(args: &[&str]) -> Vec<Value> {
    let out = meshvol(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance
}

#[test]
fn area_of_a_wkt_polygon_with_a_hole() {
    let dir = tempfile::tempdir().unwrap();
    // 4 × 2 rectangle minus a 1 × 1 square hole, the hole wound like the exterior.
    let lot = write(
        dir.path(),
        "lot.wkt",
        "POLYGON ((0 0, 4 0, 4 2, 0 2, 0 0), (1 0.5, 2 0.5, 2 1.5, 1 1.5, 1 0.5))\n",
    );
    let r = &json(&["area", "--json", lot.to_str().unwrap()])[0];
    assert_eq!(f(&r["area"]), 7.0);
    assert_eq!(f(&r["perimeter"]), 16.0);
    // Centroid: (8·2 − 1·1.5)/7 in x, 1 in y; ix = 4·2³/12 − 1/12; iy about x = 29/14 by
    // the parallel-axis theorem on each part.
    let cx = 14.5 / 7.0;
    assert!(close(f(&r["centroid"][0]), cx, 1e-15) && f(&r["centroid"][1]) == 1.0);
    assert!(close(f(&r["inertia"]["ix"]), 31.0 / 12.0, 1e-14));
    let iy = 2.0 * 64.0 / 12.0 + 8.0 * (2.0 - cx).powi(2) - (1.0 / 12.0 + (1.5 - cx).powi(2));
    assert!(close(f(&r["inertia"]["iy"]), iy, 1e-13));
    assert_eq!(f(&r["inertia"]["ixy"]), 0.0);
    assert_eq!(r["rings"][1]["role"], "hole");
    assert_eq!(f(&r["rings"][1]["signed_area"]), 1.0);
    assert_eq!(r["warnings"].as_array().unwrap().len(), 0);
}

#[test]
fn area_of_a_feature_collection_per_feature_and_total() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "lots.geojson",
        r#"{"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {"name": "a"}, "geometry": {"type": "Polygon",
                "coordinates": [[[0,0],[0,3],[2,3],[2,0],[0,0]]]}},
            {"type": "Feature", "properties": {"name": "bow tie"}, "geometry": {"type": "Polygon",
                "coordinates": [[[10,0],[12,2],[12,0],[10,2],[10,0]]]}}
        ]}"#,
    );
    let out = meshvol(&["area", "--json", path.to_str().unwrap()]);
    assert!(out.status.success());
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let features = r["features"].as_array().unwrap();
    assert_eq!((features[0]["name"].as_str(), f(&features[0]["area"])), (Some("a"), 6.0));
    // The bow tie's lobes cancel: its signed area is 0, and it is reported.
    assert_eq!(f(&features[1]["area"]), 0.0);
    assert!(features[1]["warnings"][0].as_str().unwrap().contains("intersects itself"));
    assert_eq!(f(&r["area"]), 6.0);
    assert_eq!(r["rings"][0]["orientation"], "cw");
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains("meshvol: warning:")
            && stderr.contains("feature 1: polygon 0 ring 0 intersects itself"),
        "{stderr}"
    );
}

#[test]
fn area_of_a_text_ring_at_utm_coordinates_is_exact() {
    // A 37.125 × 24.5 m parcel with a 2.25 × 3.5 m hole at (5e5, 6e6): all coordinates
    // are exact binary fractions, so the area is exactly 37.125·24.5 − 2.25·3.5.
    let dir = tempfile::tempdir().unwrap();
    let (x, y) = (512_345.25, 6_012_345.5);
    let ring = |rx: f64, ry: f64, w: f64, h: f64| {
        format!("{} {}\n{} {}\n{} {}\n{} {}\n", rx, ry, rx + w, ry, rx + w, ry + h, rx, ry + h)
    };
    let content =
        format!("x y\n{}\n{}", ring(x, y, 37.125, 24.5), ring(x + 3.0, y + 4.0, 2.25, 3.5));
    let path = write(dir.path(), "parcel.txt", &content);
    let r = &json(&["area", "--json", path.to_str().unwrap()])[0];
    assert_eq!(f(&r["area"]), 37.125 * 24.5 - 2.25 * 3.5);
    assert_eq!(r["format"], "text");
}

#[test]
fn area_errors_name_the_file_and_the_place() {
    let dir = tempfile::tempdir().unwrap();
    let bad = write(dir.path(), "bad.wkt", "POLYGON ((0 0, 1 0,\n1 1 oops, 0 0))");
    let out = meshvol(&["area", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.starts_with("meshvol: error: ")
            && stderr.contains("bad.wkt: line 2: column 5: expected a number, found 'oops'"),
        "{stderr}"
    );
    let bad =
        write(dir.path(), "bad.geojson", r#"{"type": "Polygon", "coordinates": [[[0, 0], [1]]]}"#);
    let stderr = String::from_utf8(meshvol(&["area", bad.to_str().unwrap()]).stderr).unwrap();
    assert!(
        stderr.contains("bad.geojson: geometry.coordinates[0][1]: expected a position"),
        "{stderr}"
    );
}

/// An OBJ of the box [0,a]×[0,b]×[0,c] with a square through-hole of side h along z,
/// centred: 16 vertices, quads wound outward.
fn tube_obj(a: f64, b: f64, c: f64, h: f64) -> String {
    let (x0, x1, y0, y1) = ((a - h) / 2.0, (a + h) / 2.0, (b - h) / 2.0, (b + h) / 2.0);
    let outer = [[0.0, 0.0], [a, 0.0], [a, b], [0.0, b]];
    let inner = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    let mut s = String::new();
    for z in [0.0, c] {
        for p in outer.iter().chain(&inner) {
            s += &format!("v {} {} {z}\n", p[0], p[1]);
        }
    }
    // Vertex k at z = 0 is k + 1, at z = c it is k + 9 (OBJ counts from 1).
    for k in 0..4 {
        let (o0, o1, i0, i1) = (k + 1, (k + 1) % 4 + 1, k + 5, (k + 1) % 4 + 5);
        s += &format!("f {o0} {o1} {} {}\n", o1 + 8, o0 + 8); // outer wall, facing out
        s += &format!("f {i1} {i0} {} {}\n", i0 + 8, i1 + 8); // inner wall, facing the hole
        s += &format!("f {o1} {o0} {i0} {i1}\n"); // bottom, facing down
        s += &format!("f {} {} {} {}\n", o0 + 8, o1 + 8, i1 + 8, i0 + 8); // top, facing up
    }
    s
}

#[test]
fn section_of_a_tube_has_a_hole_and_the_analytic_area() {
    let dir = tempfile::tempdir().unwrap();
    let tube = write(dir.path(), "tube.obj", tube_obj(4.0, 3.0, 2.0, 1.0));
    let t = tube.to_str().unwrap();
    // The file's own volume confirms the fixture: (4·3 − 1)·2.
    assert_eq!(f(&json(&["volume", "--json", t])[0]["volume"]), 22.0);
    let r = &json(&["section", t, "--plane", "z=0.5", "--json"])[0];
    assert_eq!((f(&r["area"]), f(&r["signed_area"])), (11.0, 11.0));
    assert_eq!((r["polygons"].as_u64(), r["holes"].as_u64()), (Some(1), Some(1)));
    assert_eq!(r["centroid"], serde_json::json!([2.0, 1.5]));
    assert_eq!(r["centroid_3d"], serde_json::json!([2.0, 1.5, 0.5]));
    // ix of the 4 × 3 rectangle minus the 1 × 1 hole, both centred.
    assert_eq!(f(&r["inertia"]["ix"]), 4.0 * 27.0 / 12.0 - 1.0 / 12.0);
    // A cut along x through the hole: two 1 × 2 strips, in (y, z).
    let r = &json(&["section", t, "--plane", "x=2", "--json"])[0];
    assert_eq!((f(&r["area"]), r["polygons"].as_u64()), (4.0, Some(2)));
    // z = 1 given as a point and a normal takes the general path (the plane's own 2D
    // frame); the WKT it writes, measured again, has the same area.
    let wkt = dir.path().join("cut.wkt");
    let r = &json(&[
        "section",
        t,
        "--plane",
        "2,1.5,1,0,0,1",
        "--json",
        "--out",
        wkt.to_str().unwrap(),
    ])[0];
    assert_eq!(f(&r["area"]), 11.0);
    let again = &json(&["area", "--json", wkt.to_str().unwrap()])[0];
    assert_eq!(f(&again["area"]), 11.0);
}

#[test]
fn section_prints_wkt_and_geojson() {
    let dir = tempfile::tempdir().unwrap();
    let tube = write(dir.path(), "tube.obj", tube_obj(4.0, 3.0, 2.0, 1.0));
    let t = tube.to_str().unwrap();
    let out = meshvol(&["section", t, "--plane", "z=1", "--wkt"]);
    let wkt = String::from_utf8(out.stdout).unwrap();
    assert!(wkt.starts_with("MULTIPOLYGON (((") && wkt.matches('(').count() == 4, "{wkt}");
    let out = meshvol(&["section", t, "--plane", "z=1", "--geojson"]);
    let g: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(g["geometry"]["type"], "MultiPolygon");
    assert_eq!(f(&g["properties"]["area"]), 11.0);
    // Rings closed, exterior counter-clockwise: 4 corners + the closing copy.
    let exterior = g["geometry"]["coordinates"][0][0].as_array().unwrap();
    assert_eq!(exterior.first(), exterior.last());
    // A plane that misses the mesh: empty, with a warning, not an error.
    let out = meshvol(&["section", t, "--plane", "z=5", "--json"]);
    assert!(out.status.success());
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(f(&r["area"]), 0.0);
    assert!(r["warnings"][0].as_str().unwrap().contains("does not cut"));
    // Bad planes are usage errors.
    let out = meshvol(&["section", t, "--plane", "w=1"]);
    assert_eq!(out.status.code(), Some(2));
}

/// Deterministic pseudo-random numbers in [0, 1) (xorshift64*).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn hull_of_a_far_away_box_cloud_is_exact_and_written() {
    // The corners of a 3 × 2 × 1.5 box at (1e7, 1e7, 1e5) and random points inside it,
    // on a 1/1024 grid so that every coordinate is exact.
    let dir = tempfile::tempdir().unwrap();
    let o = [1.0e7, 1.0e7, 1.0e5];
    let size = [3.0, 2.0, 1.5];
    let mut rng = Rng(1);
    let mut text = String::from("x,y,z\n");
    for i in 0..8 {
        let p: Vec<f64> = (0..3).map(|k| o[k] + size[k] * ((i >> k) & 1) as f64).collect();
        text += &format!("{},{},{}\n", p[0], p[1], p[2]);
    }
    for _ in 0..2000 {
        let p: Vec<f64> =
            (0..3).map(|k| o[k] + (rng.next() * size[k] * 1024.0).floor() / 1024.0).collect();
        text += &format!("{} {} {}\n", p[0], p[1], p[2]);
    }
    let cloud = write(dir.path(), "cloud.csv", &text);
    let out_obj = dir.path().join("hull.obj");
    let r =
        &json(&["hull", "--json", cloud.to_str().unwrap(), "--out", out_obj.to_str().unwrap()])[0];
    assert_eq!(r["points"].as_u64(), Some(2008));
    assert_eq!(f(&r["volume"]), 9.0);
    assert_eq!(f(&r["area"]), 2.0 * (6.0 + 4.5 + 3.0));
    assert_eq!(r["centroid"], serde_json::json!([o[0] + 1.5, o[1] + 1.0, o[2] + 0.75]));
    assert_eq!(r["hull_vertices"].as_u64(), Some(8));
    assert_eq!(r["hull_faces"].as_u64(), Some(12));
    // The written hull measures the same.
    let v = &json(&["volume", "--json", out_obj.to_str().unwrap()])[0];
    assert_eq!(f(&v["volume"]), 9.0);
}

#[test]
fn hull_of_mesh_vertices_and_point_clouds() {
    let dir = tempfile::tempdir().unwrap();
    // The tube's hull is its outer box: 4 × 3 × 2.
    let tube = write(dir.path(), "tube.obj", tube_obj(4.0, 3.0, 2.0, 1.0));
    assert_eq!(f(&json(&["hull", "--json", tube.to_str().unwrap()])[0]["volume"]), 24.0);
    // A point-only PLY: the unit tetrahedron's corners and its centroid.
    let ply = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.25 0.25 0.25\n";
    let ply = write(dir.path(), "tetra.ply", ply);
    let r = &json(&["hull", "--json", ply.to_str().unwrap()])[0];
    assert_eq!((r["points"].as_u64(), f(&r["volume"])), (Some(5), 1.0 / 6.0));
}

#[test]
fn degenerate_clouds_have_volume_zero_with_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        ("flat.xyz", "0 0 5\n1 0 5\n0 1 5\n1 1 5\n0.5 0.5 5\n", "coplanar"),
        ("line.xyz", "0 0 0\n1 1 1\n2 2 2\n", "collinear"),
        ("same.xyz", "1 2 3\n1 2 3\n1 2 3\n1 2 3\n1 2 3\n", "coincident"),
        ("empty.xyz", "x y z\n", "no points"),
    ];
    for (name, content, why) in cases {
        let path = write(dir.path(), name, content);
        let out = meshvol(&["hull", "--json", path.to_str().unwrap()]);
        assert!(out.status.success(), "{name}");
        let r: Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!((f(&r["volume"]), r["degenerate"].as_str()), (0.0, Some(why)), "{name}");
        assert!(String::from_utf8(out.stderr).unwrap().contains("volume is 0"), "{name}");
    }
    // Nothing to write for a flat cloud; a bad line is an error at its line.
    let flat = dir.path().join("flat.xyz");
    let out = meshvol(&[
        "hull",
        flat.to_str().unwrap(),
        "--out",
        dir.path().join("h.stl").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8(out.stderr).unwrap().contains("no hull to write"));
    let bad = write(dir.path(), "bad.xyz", "0 0 0\n1 0 0\n0 1\n");
    let out = meshvol(&["hull", bad.to_str().unwrap()]);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(stderr.contains("bad.xyz: line 3: expected three numbers x y z, found 2"), "{stderr}");
    let out = meshvol(&["hull", bad.to_str().unwrap(), "--out", "hull.xyz"]);
    assert_eq!(out.status.code(), Some(2));
}
