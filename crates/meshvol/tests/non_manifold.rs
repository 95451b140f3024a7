//! Non-manifold solids: the faces around an edge where more than two meet are paired
//! into sheets, and what stays open is capped, so that every measure of the checked
//! solid (mass properties, grid cells, profile, the part below a plane) is one integral.
//! Expected values are the constructions' closed forms; agreement between commands is
//! checked on constructions that have none (a Möbius strip).

mod common;

use common::{face_lists, polygons};
use meshvol::below::below;
use meshvol::grid::{cell_volumes, profile, Axis, Grid, Levels};
use meshvol::section::{section, Plane};
use meshvol::shapes::cuboid;
use meshvol::topology::{check, Check, CheckOptions};
use meshvol::{mass_properties, Mesh, Point};

/// A mesh of several parts, each positions and face lists.
fn joined(parts: &[(Vec<Point>, Vec<Vec<u32>>)]) -> Mesh {
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for (p, f) in parts {
        let base = positions.len() as u32;
        positions.extend_from_slice(p);
        faces.extend(f.iter().map(|face| face.iter().map(|&v| v + base).collect::<Vec<u32>>()));
    }
    polygons(&positions, &faces)
}

/// An axis-aligned box as positions and quads, wound outward or inward.
fn block(min: Point, max: Point, outward: bool) -> (Vec<Point>, Vec<Vec<u32>>) {
    let b = cuboid(min, max);
    let mut faces = face_lists(&b);
    if !outward {
        faces.iter_mut().for_each(|f| f.reverse());
    }
    (b.positions().to_vec(), faces)
}

/// `mesh` with its faces in another order and each face's corners rotated: a
/// deterministic shuffle by the multiplier `k` (coprime with the face count).
fn shuffled(mesh: &Mesh, k: usize) -> Mesh {
    let lists = face_lists(mesh);
    let n = lists.len();
    let faces: Vec<Vec<u32>> = (0..n)
        .map(|i| {
            let mut f = lists[(i * k + 3) % n].clone();
            let r = i % f.len();
            f.rotate_left(r);
            f
        })
        .collect();
    polygons(mesh.positions(), &faces)
}

/// Every measure of the checked solid of `mesh`: its volume, Σ grid cells over a box
/// enclosing it, a profile's top, and the parts below and above an oblique plane.
fn measures(mesh: &Mesh) -> (Check, [f64; 5]) {
    let c = check(mesh, &CheckOptions::default()).unwrap();
    let solid = c.solid(mesh);
    let mp = mass_properties(&solid);
    let b = mp.bounds.unwrap();
    let pad = |i: usize| 0.25 * (b.max[i] - b.min[i]);
    let origin = [b.min[0] - pad(0), b.min[1] - pad(1), b.min[2] - pad(2)];
    let cell = [0, 1, 2].map(|i| (b.max[i] - b.min[i] + 2.0 * pad(i)) / 5.0);
    let grid = Grid { origin, cell, counts: [5, 5, 5] };
    let cells: f64 = cell_volumes(&solid, &grid).unwrap().iter().sum();
    let top = *profile(&solid, Axis::X, Levels::Count(4)).unwrap().volume_below.last().unwrap();
    let n = [0.3, 0.2, 1.0];
    let o = mp.centroid.unwrap();
    let under = below(&solid, &Plane::new(o, n).unwrap()).part.signed_volume;
    let over = below(&solid, &Plane::new(o, n.map(|x| -x)).unwrap()).part.signed_volume;
    (c, [mp.signed_volume, cells, top, under, over])
}

/// Asserts that every measure of `mesh` is `volume` (within `slack`, relative), and that
/// the check's own volume is too.
fn assert_every_measure(name: &str, mesh: &Mesh, volume: f64, slack: f64) -> Check {
    let (c, [v, cells, top, under, over]) = measures(mesh);
    let close = |x: f64| (x - volume).abs() <= slack * volume.abs().max(1.0);
    assert!(close(v), "{name}: volume {v}, want {volume}");
    assert!(close(c.volume), "{name}: the check's volume {}, want {volume}", c.volume);
    assert!(close(cells), "{name}: Σ grid {cells}, want {volume}");
    assert!(close(top), "{name}: profile top {top}, want {volume}");
    assert!(close(under + over), "{name}: below {under} + above {over}, want {volume}");
    c
}

#[test]
fn two_boxes_touching_along_an_edge_are_two_closed_bodies() {
    for outward in [true, false] {
        let mesh = joined(&[
            block([0.0; 3], [1.0; 3], true),
            block([1.0, 1.0, 0.0], [2.0, 2.0, 1.0], outward),
        ]);
        for k in [1, 5, 7] {
            let name = format!("second box outward {outward}, shuffle {k}");
            let c = assert_every_measure(&name, &shuffled(&mesh, k), 2.0, 1e-12);
            assert_eq!(c.non_manifold_edges, 1, "{name}");
            assert_eq!(c.unpaired_at_non_manifold_edges, 0, "{name}");
            assert_eq!(c.shells.len(), 2, "{name}");
            assert!(c.shells.iter().all(|s| s.closed && s.volume == 1.0), "{name}: {:?}", c.shells);
            assert_eq!(c.bodies().len(), 2, "{name}");
        }
    }
}

#[test]
fn the_section_through_an_edge_where_bodies_touch_closes() {
    // Two squares touching at a corner: the crossings of the shared edge start two
    // segments and end two, and every segment must be chained into a loop.
    for outward in [true, false] {
        let mesh = joined(&[
            block([0.0; 3], [1.0; 3], true),
            block([1.0, 1.0, 0.0], [2.0, 2.0, 1.0], outward),
        ]);
        let c = check(&mesh, &CheckOptions::default()).unwrap();
        let s = section(&c.solid(&mesh), &Plane::axis(2, 0.5).unwrap());
        assert_eq!((s.open_chains, s.loops, s.signed_area), (0, 2, 2.0), "outward {outward}");
    }
}

#[test]
fn three_bodies_around_one_edge_pair_by_body() {
    // Boxes in the first and third quadrants around the z axis, and in the second a
    // prism over the triangle (0, 0), (cos 100°, sin 100°), (cos 170°, sin 170°), wound
    // inward: six faces meet at the edge from (0, 0, 0) to (0, 0, 1).
    let (u, w) = (100f64.to_radians(), 170f64.to_radians());
    let corners = [[0.0, 0.0], [u.cos(), u.sin()], [w.cos(), w.sin()]];
    let mut prism: Vec<Point> = corners.iter().map(|c| [c[0], c[1], 0.0]).collect();
    prism.extend(corners.iter().map(|c| [c[0], c[1], 1.0]));
    // Wound inward: the bottom counter-clockwise seen from above, and so on.
    let prism_faces =
        vec![vec![0, 1, 2], vec![3, 5, 4], vec![0, 3, 4, 1], vec![1, 4, 5, 2], vec![2, 5, 3, 0]];
    let mesh = joined(&[
        block([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], true),
        block([-1.0, -1.0, 0.0], [0.0, 0.0, 1.0], true),
        (prism, prism_faces),
    ]);
    let volume = 2.0 + 0.5 * (w - u).sin();
    for k in [1, 5, 11] {
        let c = assert_every_measure(&format!("shuffle {k}"), &shuffled(&mesh, k), volume, 1e-12);
        assert_eq!((c.non_manifold_edges, c.unpaired_at_non_manifold_edges), (1, 0));
        assert_eq!(c.shells.len(), 3);
    }
}

#[test]
fn a_fin_on_an_edge_is_left_alone_and_holds_no_volume() {
    let (mut p, mut f) = block([0.0; 3], [1.0; 3], true);
    // A triangle standing out of the box's edge from (1, 0, 0) to (1, 0, 1).
    let (a, b) = (
        p.iter().position(|&x| x == [1.0, 0.0, 0.0]),
        p.iter().position(|&x| x == [1.0, 0.0, 1.0]),
    );
    p.push([2.0, -1.0, 0.5]);
    f.push(vec![a.unwrap() as u32, b.unwrap() as u32, 8]);
    let mesh = polygons(&p, &f);
    for k in [1, 3] {
        let c = assert_every_measure(&format!("shuffle {k}"), &shuffled(&mesh, k), 1.0, 1e-12);
        assert_eq!((c.non_manifold_edges, c.unpaired_at_non_manifold_edges), (1, 1));
        assert!(!c.doubts().is_empty());
    }
}

#[test]
fn a_box_with_an_inner_wall_is_the_box() {
    // Two half boxes sharing the wall x = ½, written once: its four edges are each met
    // by three faces.
    let (p0, f0) = block([0.0; 3], [0.5, 1.0, 1.0], true);
    let (p1, f1) = block([0.5, 0.0, 0.0], [1.0; 3], true);
    let mut mesh_faces = f0.clone();
    let wall = |p: &[Point], f: &Vec<u32>| f.iter().all(|&v| p[v as usize][0] == 0.5);
    mesh_faces
        .extend(f1.iter().filter(|f| !wall(&p1, f)).map(|f| f.iter().map(|&v| v + 8).collect()));
    let mut positions = p0;
    positions.extend(p1);
    // Weld the halves' shared corners through the check's exact weld.
    let mesh = polygons(&positions, &mesh_faces);
    for k in [1, 5] {
        let c = assert_every_measure(&format!("shuffle {k}"), &shuffled(&mesh, k), 1.0, 1e-12);
        assert_eq!(c.non_manifold_edges, 4);
    }
}

#[test]
fn every_face_of_a_hex_grid_is_measured_alike_by_every_command() {
    // All faces of a 3×3×3 grid of unit cells, each once: no closed solid exists (inner
    // faces meet the outer surface three at an edge). The outer box holds 27; whatever
    // the check makes of it, every command must give the same number, and the stated
    // uncertainty must reach the box's.
    let n = 3u32;
    let id = |i: u32, j: u32, k: u32| (i * (n + 1) + j) * (n + 1) + k;
    let mut positions = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            for k in 0..=n {
                positions.push([i as f64, j as f64, k as f64]);
            }
        }
    }
    let mut faces = Vec::new();
    for i in 0..=n {
        for j in 0..n {
            for k in 0..n {
                faces.push(vec![
                    id(i, j, k),
                    id(i, j + 1, k),
                    id(i, j + 1, k + 1),
                    id(i, j, k + 1),
                ]);
                faces.push(vec![
                    id(j, i, k),
                    id(j, i, k + 1),
                    id(j + 1, i, k + 1),
                    id(j + 1, i, k),
                ]);
                faces.push(vec![
                    id(j, k, i),
                    id(j + 1, k, i),
                    id(j + 1, k + 1, i),
                    id(j, k + 1, i),
                ]);
            }
        }
    }
    let mesh = polygons(&positions, &faces);
    let (c, m) = measures(&mesh);
    for x in [m[1], m[2], m[3] + m[4], c.volume] {
        assert!((x - m[0]).abs() <= 1e-12 * m[0].abs().max(1.0), "measures disagree: {m:?}");
    }
    assert!(
        (m[0] - 27.0).abs() <= c.volume_uncertainty,
        "{m:?} ± {} misses 27",
        c.volume_uncertainty
    );
    assert!(c.unpaired_at_non_manifold_edges > 0 && !c.doubts().is_empty());
}

#[test]
fn a_mobius_strip_is_measured_alike_by_every_command() {
    // Non-orientable: its seam is capped with the boundary, so the measures agree.
    let steps = 40;
    let mut positions = Vec::new();
    for i in 0..steps {
        let a = std::f64::consts::TAU * i as f64 / steps as f64;
        for s in [-0.3, 0.3] {
            let r = 1.0 + s * (a / 2.0).cos();
            positions.push([r * a.cos(), r * a.sin(), s * (a / 2.0).sin()]);
        }
    }
    let mut faces = Vec::new();
    for i in 0..steps {
        let j = (i + 1) % steps;
        let (a0, a1) = (2 * i, 2 * i + 1);
        let (b0, b1) = if j == 0 { (1, 0) } else { (2 * j, 2 * j + 1) };
        faces.push(vec![a0, b0, b1]);
        faces.push(vec![a0, b1, a1]);
    }
    let mesh = polygons(&positions, &faces);
    let (c, m) = measures(&mesh);
    assert!(c.shells.iter().any(|s| !s.orientable));
    for x in [m[1], m[2], m[3] + m[4]] {
        assert!((x - m[0]).abs() <= 1e-12, "measures disagree: {m:?}");
    }
}

/// Two boxes touching along an edge are two spheres (χ = 2, genus 0) whatever the face
/// order: the vertices of the shared edge belong to both, once each (they were counted
/// once per run of consecutive faces of a shell, so faces of the two boxes interleaved
/// around them gave χ from 3 to 6 and genus −1 or −2).
#[test]
fn bodies_touching_along_an_edge_are_spheres_in_any_face_order() {
    let mesh =
        joined(&[block([0.0; 3], [1.0; 3], true), block([1.0, 1.0, 0.0], [2.0, 2.0, 1.0], true)]);
    for k in [1, 5, 7, 11] {
        let c = check(&shuffled(&mesh, k), &CheckOptions::default()).unwrap();
        let shells: Vec<_> = c.shells.iter().map(|s| (s.euler_characteristic, s.genus)).collect();
        assert_eq!(shells, [(2, Some(0)); 2], "faces shuffled by {k}");
    }
}
