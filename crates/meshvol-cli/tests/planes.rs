//! One plane syntax for every command that takes a plane (`below --plane`,
//! `section --plane`): `z=H`, a point and a normal, a normal and an offset. Each form of
//! one plane gives the closed-form volume and section of a box cut by it.

mod common;
use common::{box_obj, f, meshvol, p, write};
use serde_json::Value;

/// The box [0, 4] × [0, 2] × [0, 1].
fn slab(dir: &std::path::Path) -> std::path::PathBuf {
    write(dir, "slab.obj", box_obj([0.0; 3], [4.0, 2.0, 1.0], 1, true, false))
}

fn json(args: &[&str]) -> Value {
    let out = meshvol(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn every_form_of_a_plane_cuts_the_same_part_below() {
    let dir = tempfile::tempdir().unwrap();
    let box_ = slab(dir.path());
    // (forms of one plane, the volume below it, the centroid of that part), by hand.
    let planes: [(&[&str], f64, [f64; 3]); 3] = [
        // z = 0.25: a 4 × 2 × 0.25 slab.
        (&["z=0.25", "0,0,1,0.25", "0,0,4,1", "3,1,0.25,0,0,1"], 2.0, [2.0, 1.0, 0.125]),
        // y = 0.5: a 4 × 0.5 × 1 slab.
        (&["y=0.5", "0,1,0,0.5", "1,0.5,1,0,2,0"], 2.0, [2.0, 0.25, 0.5]),
        // x + z = 2: the prism over the trapezoid x ≤ 2 − z, area 1.5, times 2 in y; its
        // centroid x̄ = ∫∫ x / 1.5 = (7/6) / 1.5, z̄ = ∫∫ z / 1.5 = (2/3) / 1.5.
        (&["1,0,1,2", "2,0,0,1,0,1", "0,0,2,3,0,3"], 3.0, [7.0 / 9.0, 1.0, 4.0 / 9.0]),
    ];
    for (forms, volume, centroid) in planes {
        for form in forms {
            let v = json(&["below", p(&box_), "--plane", form, "--json"]);
            assert!(close(f(&v["volume"]), volume), "{form}: {v}");
            for k in 0..3 {
                assert!(close(f(&v["centroid"][k]), centroid[k]), "{form}: {v}");
            }
        }
    }
}

#[test]
fn every_form_of_a_plane_gives_the_same_section() {
    let dir = tempfile::tempdir().unwrap();
    let box_ = slab(dir.path());
    // (forms, the section's area, its centroid in space), by hand: z = 0.5 cuts a 4 × 2
    // rectangle; x + z = 2 a 2 × √2 one from (2, ·, 0) to (1, ·, 1).
    let planes: [(&[&str], f64, [f64; 3]); 2] = [
        (&["z=0.5", "0,0,1,0.5", "0,0,-3,-1.5", "1,1,0.5,0,0,1"], 8.0, [2.0, 1.0, 0.5]),
        (&["1,0,1,2", "2,0,0,1,0,1"], 2.0 * 2f64.sqrt(), [1.5, 1.0, 0.5]),
    ];
    for (forms, area, centroid) in planes {
        for form in forms {
            let v = json(&["section", p(&box_), "--plane", form, "--json"]);
            assert!(close(f(&v["area"]), area), "{form}: {v}");
            for k in 0..3 {
                assert!((f(&v["centroid_3d"][k]) - centroid[k]).abs() < 1e-12, "{form}: {v}");
            }
        }
    }
}

#[test]
fn a_malformed_plane_is_a_usage_error_naming_the_forms() {
    let dir = tempfile::tempdir().unwrap();
    let box_ = slab(dir.path());
    for command in ["below", "section"] {
        for (plane, says) in [
            ("w=1", "'w' is not an axis"),
            ("1,2,3", "found 3 number(s)"),
            ("0,0,0,1", "normal is zero"),
            ("z=nan", "'nan' is not a finite number"),
        ] {
            let out = meshvol(&[command, p(&box_), "--plane", plane]);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{command} {plane}: {err}");
            assert!(err.contains(says) && err.contains("NX,NY,NZ,D"), "{command}: {err}");
            assert!(out.stdout.is_empty());
        }
        // Each flag's help names every form.
        let help = String::from_utf8_lossy(&meshvol(&[command, "--help"]).stdout).into_owned();
        for form in ["z=H", "PX,PY,PZ,NX,NY,NZ", "NX,NY,NZ,D"] {
            assert!(help.contains(form), "{command} --help lacks {form}: {help}");
        }
    }
}
