//! On every real file of the corpus (`../shared/corpus`, skipped when it is not there),
//! `volume`, Σ `grid` and the `profile`'s top agree, and `grid --moments`'s cut cells
//! agree with `volume`: a module of the invariance suite.

use super::REL;
use crate::common::{self, f, meshvol, read_npz};
use serde_json::Value;
use std::path::{Path, PathBuf};

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
