//! `meshvol below`: a box barge heeled at its displacement, against the closed form of
//! its centre of buoyancy.

mod common;
use common::{f, meshvol, write};

#[test]
fn a_heeled_barge_at_its_displacement() {
    // Beam 2 (y), depth 1, length 4; displacement 4 (draft 0.5 upright). Heeled by θ
    // with the same displacement, the waterplane passes through (·, 1, 0.5) and the
    // centre of buoyancy moves to y = 1 + B² tan θ / (12 T), z = T/2 + B² tan² θ / (24 T).
    let dir = tempfile::tempdir().unwrap();
    let mut obj = String::new();
    for k in 0..8 {
        obj += &format!("v {} {} {}\n", 4 * (k & 1), 2 * (k >> 1 & 1), k >> 2 & 1);
    }
    for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        obj += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    let path = write(dir.path(), "barge.obj", obj);
    let (beam, draft) = (2.0, 0.5);
    for degrees in [0.0f64, 10.0, 20.0] {
        let heel = degrees.to_string();
        let out =
            meshvol(&["below", path.to_str().unwrap(), "--volume", "4", "--heel", &heel, "--json"]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let t = degrees.to_radians();
        let (y, z) = (
            1.0 + beam * beam * t.tan() / (12.0 * draft),
            draft / 2.0 + beam * beam * t.tan().powi(2) / (24.0 * draft),
        );
        let c = &v["centroid"];
        assert!((f(&v["volume"]) - 4.0).abs() < 1e-12, "{v}");
        assert!((f(&c[1]) - y).abs() < 1e-9 && (f(&c[2]) - z).abs() < 1e-9, "{degrees}°: {v}");
        assert!((f(&v["section_area"]) - 4.0 * beam / t.cos()).abs() < 1e-9, "{v}");
    }
}
