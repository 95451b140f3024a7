//! One answer whatever the file's order or pose, through the command (issue 26): a few
//! solids written as OBJ files, again with their faces shuffled, corners rotated,
//! vertices renumbered, moved by a signed axis permutation (a mirror with its faces
//! reversed), translated by 2ᵏ and scaled by 2, must give the same `volume`, `check`,
//! `grid` (cell by cell), `profile`, `below`, `section`, `union` and `hull` answers,
//! moved and scaled as they must be; and on every real file of the corpus, `volume`,
//! Σ `grid` and the `profile`'s top agree. The kernels' own invariance suite is
//! crates/meshvol/tests/invariance; docs/invariance.md has the table.

mod common;
use common::{f, meshvol, read_npy, read_npz};

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

/// The mesh files of the corpus (the formats meshvol reads), sorted; the members of its
/// zip archives are extracted into `scratch` (each archive into a folder of its own, so
/// that a glTF finds its buffers) and listed too.
fn corpus_files(scratch: &Path) -> Option<Vec<PathBuf>> {
    let corpus =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/trimesh-models");
    if !corpus.exists() {
        eprintln!("corpus not found at {}, skipping", corpus.display());
        return None;
    }
    let mut listed: Vec<PathBuf> =
        std::fs::read_dir(&corpus).unwrap().map(|e| e.unwrap().path()).collect();
    listed.sort();
    let extension =
        |p: &Path| p.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let archives: Vec<PathBuf> = listed.iter().filter(|p| extension(p) == "zip").cloned().collect();
    for archive in &archives {
        let mut zip = zip::ZipArchive::new(std::fs::File::open(archive).unwrap()).unwrap();
        let into = scratch.join(archive.file_name().unwrap());
        for i in 0..zip.len() {
            let mut member = zip.by_index(i).unwrap();
            let Some(name) = member.enclosed_name() else { continue };
            if member.is_dir() || name.starts_with("__MACOSX") {
                continue;
            }
            let path = into.join(name);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::io::copy(&mut member, &mut std::fs::File::create(&path).unwrap()).unwrap();
            listed.push(path);
        }
    }
    let meshes = ["stl", "obj", "off", "ply", "3mf", "gltf", "glb"];
    Some(listed.into_iter().filter(|p| meshes.contains(&extension(p).as_str())).collect())
}

/// What one real file gives: `None` when it cannot be measured (unreadable, or a flat
/// surface `grid` or `profile` refuses with an error), else a disagreement, if any.
fn disagreement(file: &Path) -> Option<Option<String>> {
    let path = common::p(file);
    let name = || {
        let corpus = "shared/corpus/trimesh-models/";
        path.rsplit_once(corpus).map_or(path.to_string(), |(_, n)| n.to_string())
    };
    let run = |args: &[&str]| -> Result<Value, String> {
        let out = meshvol(args);
        if out.status.success() {
            Ok(serde_json::from_slice(&out.stdout).unwrap())
        } else {
            Err(String::from_utf8_lossy(&out.stderr).trim().to_string())
        }
    };
    let volume = match run(&["volume", path, "--json", "-q"]) {
        Ok(v) => v,
        Err(e) => {
            eprintln!("{}: not measured: {}", name(), e.lines().next().unwrap_or(""));
            return None;
        }
    };
    let (grid, profile) = (
        run(&["grid", path, "--cells", "4,4,4", "--json", "-q"]),
        run(&["profile", path, "--levels", "4", "--json", "-q"]),
    );
    let (grid, profile) = match (grid, profile) {
        (Ok(g), Ok(p)) => (g, p),
        (g, p) => {
            let errors: Vec<String> = [g.err(), p.err()].into_iter().flatten().collect();
            // A flat surface, or one whose checked solid has no faces left (a
            // double-sided surface: `volume` says 0 and why).
            let refused = ["flat", "empty", "no vertices", "no faces"];
            if errors.iter().all(|e| refused.iter().any(|r| e.contains(r))) {
                eprintln!("{}: refused: {}", name(), errors.join("; "));
                return None;
            }
            return Some(Some(format!("{}: an error: {}", name(), errors.join("; "))));
        }
    };
    let v = f(&volume["volume"]);
    let allowed =
        REL * v.abs() + f(&volume["volume_uncertainty"]) + f(&volume["volume_error_bound"]);
    if let Some(wrong) = cut_cells_disagree(path, &volume, &grid) {
        return Some(Some(format!("{}: {wrong}", name())));
    }
    let (total, top) = (f(&grid["total"]), f(&profile["volume_below"][4]));
    let off = (total - v).abs().max((top - v).abs());
    Some((off > allowed).then(|| {
        format!(
            "{}: volume {v}, Σ grid {total}, profile top {top}: off by {off:e}, allowed {allowed:e} (uncertainty {})",
            name(),
            volume["volume_uncertainty"]
        )
    }))
}

/// |x| ≤ bound, false for NaN.
fn small(x: f64, bound: f64) -> bool {
    x.abs() <= bound
}

/// The cut cells of a real file (`grid --moments` over its box) against `volume` and
/// `grid`: the same total as `grid`, the divergence theorem on every cell, Σ
/// `boundary_area` = the solid's area (the surface's and its caps'), Σ `volume · centroid` = its first moment, Σ
/// `boundary_vector` = 0 (the checked solid is closed), and the cells' `inertia` moved to
/// the solid's centroid (parallel axis theorem) sum to its `inertia`.
fn cut_cells_disagree(path: &str, volume: &Value, grid: &Value) -> Option<String> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cells.npz");
    let args = [
        &["grid", path, "--cells", "4,4,4", "--moments", "--second-moments"][..],
        &["--face-centroids", "--out", common::p(&out), "--json", "-q"],
    ]
    .concat();
    let run = meshvol(&args);
    if !run.status.success() {
        return Some(format!("grid --moments failed: {}", String::from_utf8_lossy(&run.stderr)));
    }
    let summary: Value = serde_json::from_slice(&run.stdout).unwrap();
    if summary["total"] != grid["total"] {
        return Some(format!(
            "grid --moments total {} vs grid {}",
            summary["total"], grid["total"]
        ));
    }
    let a = read_npz(&out);
    let h: Vec<f64> = a["cell_size"].1.clone();
    let (area, v) = (f(&volume["area"]), f(&volume["volume"]));
    let tolerance = 1e-9 * area.max(f64::MIN_POSITIVE);
    let at = |name: &str, shape: [usize; 3], [i, j, k]: [usize; 3]| {
        a[name].1[(i * shape[1] + j) * shape[2] + k]
    };
    for n in 0..64 {
        let c = [n / 16, n / 4 % 4, n % 4];
        for d in 0..3 {
            let mut shape = [4; 3];
            shape[d] = 5;
            let mut next = c;
            next[d] += 1;
            let name = ["aperture_x", "aperture_y", "aperture_z"][d];
            let face = h[(d + 1) % 3] * h[(d + 2) % 3];
            let flux = (at(name, shape, next) - at(name, shape, c)) * face;
            let off = flux + a["boundary_vector"].1[3 * n + d];
            if !small(off, tolerance) {
                return Some(format!("cell {c:?} axis {d}: the divergence is {off:e}"));
            }
        }
    }
    // The solid's boundary: the surface's own area and the caps over its holes.
    let total_area: f64 = a["boundary_area"].1.iter().sum();
    let area = area + f(&volume["cap_area"]);
    if !small(total_area - area, tolerance) {
        return Some(format!("Σ boundary_area {total_area} vs area and caps {area}"));
    }
    let net: Vec<f64> =
        (0..3).map(|d| a["boundary_vector"].1.iter().skip(d).step_by(3).sum()).collect();
    if net.iter().any(|&x| !small(x, tolerance)) {
        return Some(format!("Σ boundary_vector {net:?}"));
    }
    if let Some(centroid) = volume["centroid"].as_array() {
        let extent: f64 = (0..3).map(|d| h[d] * 4.0).fold(0.0, f64::max);
        let origin = &a["origin"].1;
        for d in 0..3 {
            // About the grid's corner, to keep the comparison's rounding small.
            let moment: f64 = a["volume"]
                .1
                .iter()
                .zip(a["centroid"].1.iter().skip(d).step_by(3))
                .map(|(vol, x)| vol * (x - origin[d]))
                .sum();
            let expected = v * (f(&centroid[d]) - origin[d]);
            if !small(moment - expected, 1e-9 * v.abs() * extent + tolerance * extent) {
                return Some(format!("first moment {d}: {moment} vs {expected}"));
            }
        }
        let g: Vec<f64> = (0..3).map(|d| f(&centroid[d])).collect();
        let inertia = volume["inertia"].as_array().unwrap();
        let want = |a: usize, b: usize| f(&inertia[a].as_array().unwrap()[b]);
        let scale = (0..3).map(|a| want(a, a).abs()).fold(0.0, f64::max);
        let summed = summed_inertia(&a["inertia"].1, &a["volume"].1, &a["centroid"].1, &g);
        for (n, got) in summed.iter().enumerate() {
            let (r, c) = (n / 3, n % 3);
            if !small(got - want(r, c), 1e-9 * scale + tolerance * extent * extent * extent) {
                return Some(format!("Σ inertia [{r}][{c}]: {got} vs {}", want(r, c)));
            }
        }
    }
    None
}

/// The cells' inertia tensors (9 a cell) moved to `g` and summed (parallel axis theorem:
/// the covariance about `g` is `Σ C_cell + V (c − g)(c − g)ᵀ`), row by row.
fn summed_inertia(inertia: &[f64], volume: &[f64], centroid: &[f64], g: &[f64]) -> [f64; 9] {
    let mut cov = [0.0; 9];
    for (n, v) in volume.iter().enumerate() {
        let i = &inertia[9 * n..9 * n + 9];
        let half_trace = (i[0] + i[4] + i[8]) / 2.0;
        let r: Vec<f64> = (0..3).map(|d| centroid[3 * n + d] - g[d]).collect();
        for a in 0..3 {
            for b in 0..3 {
                let own = if a == b { half_trace - i[4 * a] } else { -i[3 * a + b] };
                cov[3 * a + b] += own + v * r[a] * r[b];
            }
        }
    }
    let trace = cov[0] + cov[4] + cov[8];
    std::array::from_fn(|n| if n % 4 == 0 { trace - cov[n] } else { -cov[n] })
}

/// On every real file, `volume`, Σ `grid` (over the file's box) and the top of its
/// `profile` are one number, within 10⁻⁹ of it plus the uncertainty `volume` states (the
/// caps on holes) and its rounding bound; or the file is flat and refused with an error.
#[test]
fn on_every_real_file_volume_grid_and_profile_agree() {
    let scratch = tempfile::tempdir().unwrap();
    let Some(files) = corpus_files(scratch.path()) else { return };
    let results: Vec<Option<Option<String>>> = std::thread::scope(|scope| {
        let (even, odd): (Vec<_>, Vec<_>) = files.iter().enumerate().partition(|(i, _)| i % 2 == 0);
        let workers: Vec<_> = [even, odd]
            .into_iter()
            .map(|part| {
                scope.spawn(move || {
                    part.into_iter().map(|(_, f)| disagreement(f)).collect::<Vec<_>>()
                })
            })
            .collect();
        workers.into_iter().flat_map(|w| w.join().unwrap()).collect()
    });
    let measured = results.iter().filter(|r| r.is_some()).count();
    let disagree: Vec<String> = results.into_iter().flatten().flatten().collect();
    eprintln!("{measured} of {} files measured", files.len());
    assert!(measured > 0, "no corpus file could be measured");
    assert!(
        disagree.is_empty(),
        "{} of {measured} files disagree:\n{}",
        disagree.len(),
        disagree.join("\n")
    );
}
