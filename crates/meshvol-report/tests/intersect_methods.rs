//! The two methods of `intersect` (the boundary method on prepared bodies, the grid
//! method) are independent algorithms certifying the same number: on every real file of
//! the corpus against a turned and shifted copy of itself, and on dirty constructions
//! (an open box the check caps, a box with a T-junction, touching copies), their
//! intervals must meet and their moments and interface agree.

mod common;

use meshvol::assembly::Affine;
use meshvol::shapes::{cuboid, uv_sphere};
use meshvol::topology::{check, CheckOptions};
use meshvol::{Faces, Mesh};
use meshvol_report::intersect::{intersect_prepared, prepare, IntersectReport};
use meshvol_report::subject::{Source, Subject};

/// Both methods on `mesh` against itself moved by `pose`: (boundary, grid).
fn both(mesh: &Mesh, pose: Affine) -> Option<(IntersectReport, IntersectReport)> {
    let checked = check(mesh, &CheckOptions::default()).ok()?;
    let source = Source::arrays(mesh.vertex_count());
    let s = Subject { source: &source, surface: mesh, check: Some(&checked) };
    let body = prepare(&s)?;
    let poses = [None, Some(pose)];
    let boundary = intersect_prepared(&s, &s, [Some(&body); 2], poses, 1e-9, &()).ok()?;
    let grid = intersect_prepared(&s, &s, [None, None], poses, 1e-9, &()).ok()?;
    Some((boundary, grid))
}

/// The intervals meet; the moments and the interface agree within `rel` of the scale.
fn agree(name: &str, b: &IntersectReport, g: &IntersectReport, rel: f64) {
    assert_ne!(g.method, "boundary", "{name}");
    // Boxes apart or touching are seen by both before any method.
    assert_eq!(b.method == "boxes", g.method == "boxes", "{name}");
    let slack = 1e-12 * g.interval.upper.max(b.interval.upper);
    assert!(
        b.interval.lower <= g.interval.upper + slack
            && g.interval.lower <= b.interval.upper + slack,
        "{name}: boundary [{}, {}] and grid [{}, {}] do not meet",
        b.interval.lower,
        b.interval.upper,
        g.interval.lower,
        g.interval.upper
    );
    // Moments mean something where the volume is known to a part in a thousand (not a
    // flat "solid" of rounding-sized volume).
    if !(b.interval.lower > 0.999 * b.interval.upper && g.interval.lower > 0.999 * g.interval.upper)
    {
        return;
    }
    let scale = b.volume_a.cbrt();
    if let (Some(p), Some(q)) = (b.centroid, g.centroid) {
        for k in 0..3 {
            assert!((p[k] - q[k]).abs() <= rel * scale, "{name}: centroid {p:?} vs {q:?}");
        }
    }
    if let (Some(p), Some(q)) = (b.contact_area, g.contact_area) {
        assert!((p - q).abs() <= rel * scale * scale, "{name}: contact area {p} vs {q}");
    }
}

fn turn(angle: f64, shift: [f64; 3]) -> Affine {
    let (s, c) = angle.sin_cos();
    // About the axis (1, 1, 1)/√3 (Rodrigues), then shifted.
    let u = [1.0 / 3f64.sqrt(); 3];
    let mut m = [[0.0; 4]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let cross = match (i, j) {
                (0, 1) => -u[2],
                (0, 2) => u[1],
                (1, 0) => u[2],
                (1, 2) => -u[0],
                (2, 0) => -u[1],
                (2, 1) => u[0],
                _ => 0.0,
            };
            m[i][j] = c * f64::from(u8::from(i == j)) + s * cross + (1.0 - c) * u[i] * u[j];
        }
        m[i][3] = shift[i];
    }
    Affine(m)
}

#[test]
fn dirty_constructions_give_meeting_intervals() {
    // An open box (its top missing): the check caps it, and the cap's vertices are the
    // box's, so the boundary method takes the capped solid.
    let boxed = cuboid([0.0; 3], [1.0; 3]).triangulated();
    let Faces::Triangles(t) = boxed.faces() else { unreachable!() };
    let open = Mesh::from_triangles(boxed.positions().to_vec(), t[..10].to_vec()).unwrap();
    // A T-junction: a triangle with the edge from (0, 0, 0) to (1, 0, 0) split at the
    // edge's middle, which the triangle across the edge does not have.
    let mut points = boxed.positions().to_vec();
    points.push([0.5, 0.0, 0.0]);
    let middle = (points.len() - 1) as u32;
    let at = |p: [f64; 3]| points.iter().position(|q| *q == p).unwrap() as u32;
    let (v0, v1) = (at([0.0; 3]), at([1.0, 0.0, 0.0]));
    let mut split = t.clone();
    let k = split.iter().position(|f| f.contains(&v0) && f.contains(&v1)).unwrap();
    let f = split[k];
    let i = (0..3)
        .find(|&i| f[i] == v0 && f[(i + 1) % 3] == v1 || f[i] == v1 && f[(i + 1) % 3] == v0)
        .unwrap();
    let (a, b, c) = (f[i], f[(i + 1) % 3], f[(i + 2) % 3]);
    split[k] = [a, middle, c];
    split.push([middle, b, c]);
    let t_junction = Mesh::from_triangles(points, split).unwrap();
    let sphere = uv_sphere(1.0, 48, 24).triangulated();
    let mut boundary_used = 0;
    for (name, mesh) in [("open box", &open), ("t-junction", &t_junction), ("sphere", &sphere)] {
        for (k, pose) in
            [turn(0.3, [0.31, 0.17, 0.23]), turn(1.1, [0.4, -0.2, 0.1])].into_iter().enumerate()
        {
            let Some((b, g)) = both(mesh, pose) else { continue };
            boundary_used += usize::from(b.method == "boundary");
            agree(&format!("{name}, pose {k}"), &b, &g, 1e-6);
        }
    }
    assert!(boundary_used >= 4, "{boundary_used}");
    // Touching copies: a box and the same box turned a quarter about z (exactly, so
    // every face lies on a face of the other): coplanar, left to the grid.
    let quarter = Affine([[0.0, -1.0, 0.0, 1.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
    let (b, _) = both(&boxed, quarter).unwrap();
    assert_eq!(b.method, "grid");
    assert!(b.interval.lower <= 1.0 && 1.0 <= b.interval.upper, "{b:?}");
}

#[test]
fn on_every_real_file_the_two_methods_meet() {
    let Some(files) = common::corpus_files() else { return };
    let (mut measured, mut by_boundary) = (0, 0);
    for file in files {
        let Ok(loaded) = meshvol_io::read(&file) else { continue };
        let Ok(mesh) = loaded.surface.into_mesh() else { continue };
        // The grid method's side of the comparison is the slow one: files it measures in
        // well under a second.
        if mesh.face_count() > 20_000 {
            continue;
        }
        let Some(b) = meshvol::mass_properties(&mesh).bounds else { continue };
        let size: Vec<f64> = (0..3).map(|k| b.max[k] - b.min[k]).collect();
        let centre: Vec<f64> = (0..3).map(|k| 0.5 * (b.max[k] + b.min[k])).collect();
        // Turned about the box's centre by 0.4 rad and moved by a fifth of its size.
        let r = turn(0.4, [0.0; 3]);
        let shift: Vec<f64> = (0..3)
            .map(|i| {
                let turned: f64 = (0..3).map(|j| r.0[i][j] * centre[j]).sum();
                centre[i] - turned + 0.2 * size[i]
            })
            .collect();
        let pose = Affine([0, 1, 2].map(|i| [r.0[i][0], r.0[i][1], r.0[i][2], shift[i]]));
        let Some((bound, grid)) = both(&mesh, pose) else { continue };
        measured += 1;
        by_boundary += usize::from(bound.method == "boundary");
        let name = file.file_name().unwrap().to_string_lossy().to_string();
        agree(&name, &bound, &grid, 1e-6);
    }
    eprintln!("{measured} files compared, {by_boundary} by the boundary method");
    assert!(by_boundary >= 5, "{by_boundary} of {measured}");
}
