//! The union's cut cells (`grid --union --moments`: the cut cells of `union_boundary`)
//! on every real file of the corpus, the checked solid against a turned and shifted copy
//! of itself: the divergence theorem holds in every cell, the cells' volumes are the
//! union's cell volumes resolved on the measuring grid itself (`union_cell_volumes`, a
//! second resolution on other columns), and their sum lies in `union`'s certified
//! interval. Every file whose check vouches for a solid is measured; the others (shells
//! overlapping, faces crossing) may be refused, never given wrong.

mod common;

use meshvol::assembly::Affine;
use meshvol::grid::{cut_cells, union, union_boundary, union_cell_volumes, Grid};
use meshvol::surface::Moved;
use meshvol::topology::{check, CheckOptions};
use meshvol::Surface;
use meshvol_report::intersect::prepare;
use meshvol_report::subject::{Source, Subject};
use rayon::prelude::*;
use std::path::Path;

/// A turn by `angle` about (1, 1, 1)/√3 (Rodrigues) about `centre`, then a shift.
fn pose(angle: f64, centre: [f64; 3], shift: [f64; 3]) -> Affine {
    let (s, c) = angle.sin_cos();
    let u = [1.0 / 3f64.sqrt(); 3];
    let cross = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
    let r: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let id = if i == j { 1.0 } else { 0.0 };
            c * id + s * cross[i][j] + (1.0 - c) * u[i] * u[j]
        })
    });
    let t: [f64; 3] = std::array::from_fn(|i| {
        centre[i] - (0..3).map(|j| r[i][j] * centre[j]).sum::<f64>() + shift[i]
    });
    Affine(std::array::from_fn(|i| [r[i][0], r[i][1], r[i][2], t[i]]))
}

#[test]
fn on_every_real_file_the_unions_cut_cells_hold_the_identities() {
    let Some(files) = common::corpus_files() else { return };
    // Files in parallel (the kernels' own parallelism is little on files this small): a
    // file's outcome is None (not measured), Some(Err(why)) (refused) or Some(Ok(vouched)).
    let outcomes: Vec<Option<Result<bool, String>>> =
        files.par_iter().map(|file| measure(file)).collect();
    let measured = outcomes.iter().filter(|o| matches!(o, Some(Ok(_)))).count();
    let vouched_measured = outcomes.iter().filter(|o| matches!(o, Some(Ok(true)))).count();
    let refused: Vec<&String> =
        outcomes.iter().flatten().filter_map(|o| o.as_ref().err()).collect();
    eprintln!("{measured} files measured ({vouched_measured} vouched for); refused: {refused:#?}");
    assert!(vouched_measured >= 50, "{vouched_measured} of {measured}, refused: {refused:#?}");
}

/// The checks above on one file: None when it is not measured (unreadable, too large,
/// no volume), the refusal when the union's boundary is refused (never for a file the
/// check vouches for), else whether the check vouches for it.
fn measure(file: &Path) -> Option<Result<bool, String>> {
    let loaded = meshvol_io::read(file).ok()?;
    let mesh = loaded.surface.into_mesh().ok()?;
    if mesh.face_count() > 8_000 {
        return None;
    }
    let checked = check(&mesh, &CheckOptions::default()).ok()?;
    let source = Source::arrays(mesh.vertex_count());
    let subject = Subject { source: &source, surface: &mesh, check: Some(&checked) };
    let solid = subject.measured();
    let mp = meshvol::mass_properties(&solid);
    let b = mp.bounds?;
    if mp.signed_volume.abs() < 1e-9 * (0..3).map(|k| b.max[k] - b.min[k]).product::<f64>() {
        return None;
    }
    let size: [f64; 3] = std::array::from_fn(|k| b.max[k] - b.min[k]);
    let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (b.max[k] + b.min[k]));
    let moved = pose(0.4, centre, size.map(|s| 0.2 * s));
    let bodies = [Moved::new(&solid, None), Moved::new(&solid, Some(moved))];
    let name = file.file_name().unwrap().to_string_lossy().to_string();
    // The per-cell bounds resolution checks itself against hold for solids: a body
    // whose shells overlap or whose faces cross may be refused, one the check vouches
    // for (as the boundary method of `intersect` needs) may not.
    let vouched = prepare(&subject).is_some();
    let boundary = match union_boundary(&bodies) {
        Ok(b) => b,
        Err(e) => {
            assert!(!vouched, "{name}: {e}");
            return Some(Err(format!("{name}: {e}")));
        }
    };
    // A grid over both with a margin, planes off the bodies' own.
    let (mut lo, mut hi) = (b.min, b.max);
    for body in &bodies {
        for f in 0..body.face_count() {
            body.fan(f, |p, q, r| {
                for v in [p, q, r] {
                    for k in 0..3 {
                        lo[k] = lo[k].min(v[k]);
                        hi[k] = hi[k].max(v[k]);
                    }
                }
            });
        }
    }
    let margin = 0.013 * size.iter().cloned().fold(0.0, f64::max);
    let grid =
        Grid::from_bounds(lo.map(|x| x - margin), hi.map(|x| x + margin), [9, 8, 7]).unwrap();
    let c = cut_cells(&boundary, &grid).unwrap();
    let [_, ny, nz] = grid.counts;
    let [dx, dy, dz] = grid.cell;
    let cell = grid.cell_volume();
    let faces = [dy * dz, dx * dz, dx * dy];
    for n in 0..grid.cell_count() {
        let (i, j, k) = (n / (ny * nz), n / nz % ny, n % nz);
        let v = c.boundary_vector[n];
        let d = [
            (c.aperture[0][((i + 1) * ny + j) * nz + k] - c.aperture[0][n]) * faces[0] + v[0],
            (c.aperture[1][(i * (ny + 1) + j + 1) * nz + k]
                - c.aperture[1][(i * (ny + 1) + j) * nz + k])
                * faces[1]
                + v[1],
            (c.aperture[2][(i * ny + j) * (nz + 1) + k + 1]
                - c.aperture[2][(i * ny + j) * (nz + 1) + k])
                * faces[2]
                + v[2],
        ];
        for a in 0..3 {
            assert!(d[a].abs() < 1e-9 * faces[a], "{name} cell {n}: divergence {d:?}");
        }
    }
    let (volumes, unresolved) = union_cell_volumes(&bodies, &grid).unwrap();
    if unresolved == 0 {
        for (n, (x, y)) in c.volume.iter().zip(&volumes).enumerate() {
            assert!((x - y).abs() < 1e-9 * cell, "{name} cell {n}: {x} vs {y}");
        }
    }
    let u = union(&bodies, 1e-9).unwrap();
    let total: f64 = c.volume.iter().sum();
    let slack = 1e-9 * u.upper;
    assert!(u.lower - slack <= total && total <= u.upper + slack, "{name}: {total} {u:?}");
    Some(Ok(vouched))
}
