//! One answer whatever the file's order or pose, through the command (issue 26): a few
//! solids written as OBJ files, again with their faces shuffled, corners rotated,
//! vertices renumbered, moved by a signed axis permutation (a mirror with its faces
//! reversed), translated by 2ᵏ and scaled by 2, must give the same `volume`, `check`,
//! `grid` (cell by cell), `profile`, `below`, `section`, `union` and `hull` answers,
//! moved and scaled as they must be; and on every real file of the corpus, `volume`,
//! Σ `grid` and the `profile`'s top agree (`invariance/corpus.rs`). The kernels' own
//! invariance suite is crates/meshvol/tests/invariance; docs/invariance.md has the table.

mod common;
#[path = "invariance/corpus.rs"]
mod corpus;
use common::{f, meshvol, read_npy};

use meshvol::shapes::{cuboid, torus};
use meshvol::Mesh;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Issue 26's bound.
const REL: f64 = 1e-9;

/// The grid's cells along x, y and z (of the untransformed files).
const COUNTS: [usize; 3] = [3, 4, 5];

fn near(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= REL * scale.abs()
}

#[track_caller]
fn assert_near(what: &str, got: f64, want: f64, scale: f64) {
    assert!(near(got, want, scale), "{what}: {got} against {want} (allowed {:e})", REL * scale);
}

/// The JSON object of a run that must succeed.
fn json(args: &[&str]) -> Value {
    let out = meshvol(args);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{args:?}: {e}"))
}

fn vector(v: &Value) -> [f64; 3] {
    [f(&v[0]), f(&v[1]), f(&v[2])]
}

/// A mesh as index lists, and what is done to it.
#[derive(Clone)]
struct Solid {
    positions: Vec<[f64; 3]>,
    faces: Vec<Vec<u32>>,
}

/// A transform of a file: new axis a = signs[a] · scale · old axis axes[a] + shift[a];
/// `seed` shuffles faces, rotates corners and renumbers vertices.
#[derive(Clone, Debug)]
struct Transform {
    seed: u64,
    axes: [usize; 3],
    signs: [f64; 3],
    scale: f64,
    shift: [f64; 3],
}

impl Transform {
    fn point(&self, p: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|a| self.signs[a] * self.scale * p[self.axes[a]] + self.shift[a])
    }

    fn direction(&self, v: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|a| self.signs[a] * v[self.axes[a]])
    }

    fn is_mirror(&self) -> bool {
        let odd = matches!(self.axes, [1, 0, 2] | [0, 2, 1] | [2, 1, 0]);
        odd != (self.signs.iter().filter(|&&s| s < 0.0).count() % 2 == 1)
    }

    /// The axis of the transformed file that old axis `b` became.
    fn new_axis(&self, b: usize) -> usize {
        (0..3).find(|&a| self.axes[a] == b).unwrap()
    }

    fn apply(&self, s: &Solid) -> Solid {
        let mut state = self.seed;
        let mut next = |n: usize| {
            // xorshift64: a fixed, reproducible sequence per seed.
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n as u64) as usize
        };
        let n = s.positions.len();
        let mut id: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            id.swap(i, next(i + 1));
        }
        let mut positions = vec![[0.0; 3]; n];
        for (v, &p) in s.positions.iter().enumerate() {
            positions[id[v]] = self.point(p);
        }
        let mut faces: Vec<Vec<u32>> = s
            .faces
            .iter()
            .map(|f| {
                let mut f: Vec<u32> = f.iter().map(|&v| id[v as usize] as u32).collect();
                let k = next(f.len());
                f.rotate_left(k);
                if self.is_mirror() {
                    f.reverse();
                }
                f
            })
            .collect();
        for i in (1..faces.len()).rev() {
            faces.swap(i, next(i + 1));
        }
        Solid { positions, faces }
    }
}

fn identity() -> Transform {
    Transform { seed: 0, axes: [0, 1, 2], signs: [1.0; 3], scale: 1.0, shift: [0.0; 3] }
}

/// Three transforms: a shuffle with a mirror, a rotation with a far translation, and a
/// scaling with sign flips.
fn transforms() -> Vec<Transform> {
    vec![
        Transform {
            seed: 11,
            axes: [1, 0, 2],
            signs: [1.0, 1.0, 1.0],
            scale: 1.0,
            shift: [0.0; 3],
        },
        Transform {
            seed: 12,
            axes: [1, 2, 0],
            signs: [1.0; 3],
            scale: 1.0,
            shift: [1024.0, -4096.0, 256.0],
        },
        Transform {
            seed: 13,
            axes: [2, 1, 0],
            signs: [-1.0, -1.0, 1.0],
            scale: 2.0,
            shift: [0.5, 0.0, -8.0],
        },
    ]
}

fn of_mesh(mesh: &Mesh) -> Solid {
    let faces = (0..mesh.face_count()).map(|f| mesh.face(f).to_vec()).collect();
    Solid { positions: mesh.positions().to_vec(), faces }
}

fn obj(dir: &Path, name: &str, s: &Solid) -> PathBuf {
    let mut text = String::new();
    for p in &s.positions {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for face in &s.faces {
        let ids: Vec<String> = face.iter().map(|v| (v + 1).to_string()).collect();
        text += &format!("f {}\n", ids.join(" "));
    }
    common::write(dir, name, text)
}

/// Every coordinate rounded to a multiple of 2⁻²⁴ (so that the transforms are exact).
fn snapped(mut s: Solid) -> Solid {
    for p in &mut s.positions {
        *p = p.map(|x| (x * 16777216.0).round() / 16777216.0);
    }
    s
}

/// The solids: a box with a cavity (quads; volume 7), a torus (triangles, snapped), an
/// open box (capped: volume 1), each with a generic point inside its box for planes.
fn solids() -> Vec<(&'static str, Solid, [f64; 3])> {
    let cavity =
        Mesh::concatenate(&[cuboid([0.0; 3], [2.0; 3]), cuboid([0.5; 3], [1.5; 3]).flipped()]);
    let torus = snapped(of_mesh(&torus(1.5, 0.5, 12, 6).triangulated()));
    let mut open = of_mesh(&cuboid([0.0; 3], [1.0; 3]));
    open.faces.retain(|f| !f.iter().all(|&v| open.positions[v as usize][2] == 1.0));
    vec![
        ("cavity", of_mesh(&cavity), [0.8125, 1.3125, 0.6875]),
        ("torus", torus, [0.3125, -0.40625, 0.15625]),
        ("open", open, [0.40625, 0.59375, 0.34375]),
    ]
}

/// What the commands say about one file.
struct Answers {
    volume: Value,
    check: Value,
    grid: Value,
    cells: (Vec<usize>, Vec<f64>),
    profile: Vec<Value>,
    below: Value,
    above: Value,
    section: Vec<Value>,
    union: Value,
    hull: Value,
}

fn answers(dir: &Path, file: &Path, t: &Transform, inside: [f64; 3]) -> Answers {
    let path = common::p(file);
    let npy = dir.join("cells.npy");
    // The grid over the file's box, with the counts moved with the axes: each cell of
    // the moved file's grid is a cell of the first grid, moved.
    let counts = [0, 1, 2].map(|a| COUNTS[t.axes[a]]);
    let cells_arg = format!("{},{},{}", counts[0], counts[1], counts[2]);
    let grid = json(&["grid", path, "--cells", &cells_arg, "--json", "--out", common::p(&npy)]);
    let cells = read_npy(&npy);
    let profile = (0..3)
        .map(|b| {
            let axis = ["x", "y", "z"][t.new_axis(b)];
            json(&["profile", path, "--levels", "4", "--axis", axis, "--json"])
        })
        .collect();
    let normal = t.direction([0.48, -0.6, 0.64]);
    let o = t.point(inside);
    let d: f64 = (0..3).map(|a| normal[a] * o[a]).sum();
    let plane = |n: [f64; 3], d: f64| format!("{},{},{},{}", n[0], n[1], n[2], d);
    let below = json(&["below", path, "--plane", &plane(normal, d), "--json"]);
    let above = json(&["below", path, "--plane", &plane(normal.map(|x| -x), -d), "--json"]);
    let section = (0..3)
        .map(|b| {
            let a = t.new_axis(b);
            let arg = format!("{}={}", ["x", "y", "z"][a], o[a]);
            json(&["section", path, "--plane", &arg, "--json"])
        })
        .collect();
    Answers {
        volume: json(&["volume", path, "--json"]),
        check: {
            let out = meshvol(&["check", path, "--json"]);
            serde_json::from_slice(&out.stdout).unwrap()
        },
        grid,
        cells,
        profile,
        below,
        above,
        section,
        union: json(&["union", path, "--json"]),
        hull: json(&["hull", path, "--json"]),
    }
}

/// The check's facts that no transform changes.
fn facts(c: &Value) -> Value {
    let keys = [
        "bounds_a_volume",
        "closed",
        "welded_vertices",
        "edges",
        "boundary_edges",
        "boundary_loops",
        "non_manifold_edges",
        "non_manifold_vertices",
        "degenerate_faces",
        "flat_faces",
        "duplicate_faces",
        "double_wall_faces",
        "consistently_oriented",
        "orientation",
        "winding",
        "shells",
        "cavities",
        "self_intersections",
        "euler_characteristic",
    ];
    keys.iter().map(|k| (k.to_string(), c[k].clone())).collect::<serde_json::Map<_, _>>().into()
}

fn compare(name: &str, a: &Answers, b: &Answers, t: &Transform) {
    let (s, s3) = (t.scale, t.scale.powi(3));
    let what = |w: &str| format!("{name}: {w} under {t:?}");
    let v = f(&a.volume["volume"]);
    assert_near(&what("volume"), f(&b.volume["volume"]), s3 * v, s3 * v);
    let area = f(&a.volume["area"]);
    assert_near(&what("area"), f(&b.volume["area"]), s * s * area, s * s * area);
    let reach = 4.0 * s + t.shift.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (c0, c1) = (vector(&a.volume["centroid"]), vector(&b.volume["centroid"]));
    let moved = t.point(c0);
    for k in 0..3 {
        assert_near(&what("centroid"), c1[k], moved[k], reach);
    }
    let u = f(&a.volume["volume_uncertainty"]);
    assert_near(&what("uncertainty"), f(&b.volume["volume_uncertainty"]), s3 * u, s3 * v);
    assert_eq!(facts(&b.check), facts(&a.check), "{}", what("check"));
    assert_eq!(b.check["verdict"], a.check["verdict"], "{}", what("verdict"));

    // Σ grid = volume, and each cell where the transform sends it.
    for (label, g, scale) in [("before", &a.grid, 1.0), ("after", &b.grid, s3)] {
        assert_near(&format!("{name}: Σ grid {label} {t:?}"), f(&g["total"]), scale * v, scale * v);
    }
    let ((n0, v0), (n1, v1)) = (&a.cells, &b.cells);
    assert_eq!(n0, &COUNTS.to_vec());
    assert_eq!(n1, &[0, 1, 2].map(|a| COUNTS[t.axes[a]]).to_vec());
    let index = |n: &[usize], ijk: [usize; 3]| (ijk[0] * n[1] + ijk[1]) * n[2] + ijk[2];
    for i in 0..COUNTS[0] {
        for j in 0..COUNTS[1] {
            for k in 0..COUNTS[2] {
                let old = [i, j, k];
                let new = [0, 1, 2].map(|a| {
                    let b = t.axes[a];
                    if t.signs[a] < 0.0 {
                        COUNTS[b] - 1 - old[b]
                    } else {
                        old[b]
                    }
                });
                let (x0, x1) = (v0[index(n0, old)], v1[index(n1, new)]);
                assert_near(&what(&format!("grid cell {old:?}")), x1, s3 * x0, s3 * v);
            }
        }
    }

    // Profiles along each old axis, read from the top where the axis is flipped.
    for b_axis in 0..3 {
        let flipped = t.signs[t.new_axis(b_axis)] < 0.0;
        let (p0, p1) = (&a.profile[b_axis], &b.profile[b_axis]);
        let top = f(&p0["volume_below"][4]);
        assert_near(&what("profile top"), top, v, v);
        for k in 0..=4 {
            let from = if flipped { 4 - k } else { k };
            let want =
                if flipped { v - f(&p0["volume_below"][from]) } else { f(&p0["volume_below"][k]) };
            assert_near(
                &what(&format!("profile {b_axis} level {k}")),
                f(&p1["volume_below"][k]),
                s3 * want,
                s3 * v,
            );
        }
    }

    // below: moved with the solid; below + above = volume.
    for (label, x, scale) in [("before", a, 1.0), ("after", b, s3)] {
        let whole = f(&x.below["volume"]) + f(&x.above["volume"]);
        assert_near(&format!("{name}: below + above {label} {t:?}"), whole, scale * v, scale * v);
    }
    assert_near(&what("below"), f(&b.below["volume"]), s3 * f(&a.below["volume"]), s3 * v);
    assert_near(
        &what("wetted area"),
        f(&b.below["wetted_area"]),
        s * s * f(&a.below["wetted_area"]),
        s * s * area,
    );
    let (w0, w1) = (f(&a.below["section_area"]), f(&b.below["section_area"]));
    assert_near(&what("waterplane"), w1, s * s * w0, s * s * area);

    for k in 0..3 {
        let (x0, x1) = (f(&a.section[k]["area"]), f(&b.section[k]["area"]));
        assert_near(&what(&format!("section across {k}")), x1, s * s * x0, s * s * area);
    }

    for (label, x, scale) in [("before", a, 1.0), ("after", b, s3)] {
        let (lower, upper) = (f(&x.union["lower"]), f(&x.union["upper"]));
        let want = scale * v;
        let slack = REL * want;
        assert!(
            lower - slack <= want && want <= upper + slack,
            "{name}: union [{lower}, {upper}] {label} {t:?} against {want}"
        );
    }
    assert_eq!(b.union["bodies"], a.union["bodies"], "{}", what("union bodies"));
    // Whether the interval is proven depends on the solid, not on its pose.
    assert_eq!(b.union["certified"], a.union["certified"], "{}", what("union certified"));

    let h = f(&a.hull["volume"]);
    assert_near(&what("hull"), f(&b.hull["volume"]), s3 * h, s3 * h);
    assert_eq!(b.hull["hull_vertices"], a.hull["hull_vertices"], "{}", what("hull vertices"));
}

#[test]
fn every_command_answers_the_same_for_every_order_and_pose() {
    let dir = tempfile::tempdir().unwrap();
    for (name, solid, inside) in solids() {
        let file = obj(dir.path(), &format!("{name}.obj"), &solid);
        let base = answers(dir.path(), &file, &identity(), inside);
        for (i, t) in transforms().iter().enumerate() {
            let moved = obj(dir.path(), &format!("{name}-{i}.obj"), &t.apply(&solid));
            let other = answers(dir.path(), &moved, t, inside);
            compare(name, &base, &other, t);
        }
    }
}
