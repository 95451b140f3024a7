//! Slivers, duplicate faces and double walls on the unit cube, against facts known by
//! construction: a zero-area sliver closing a T-junction keeps the solid closed, a
//! face repeated with the same winding collapses to one, and copies wound opposite ways
//! (glued boxes, a double-sided triangle) cancel in pairs.

mod common;

use common::{checked, face_lists, polygons};

use meshvol::shapes::cuboid;
use meshvol::topology::{check, Check, CheckOptions, Orientation, Weld};
use meshvol::{mass_properties, Mesh};

/// The unit cube as quads wound counter-clockwise seen from outside: positions and faces.
fn cube_faces() -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let cube = cuboid([0.0; 3], [1.0; 3]);
    (cube.positions().to_vec(), face_lists(&cube))
}

/// Puts a new vertex at the midpoint of the edge from `a` to `b`, splits the quad that
/// traverses a → b into three triangles using it (a T-junction: the other face along the
/// edge still uses a–b), and fills the junction with the zero-area sliver (a, b, m), so
/// that every edge is used twice. Returns the sliver's face index.
fn t_junction(p: &mut Vec<[f64; 3]>, faces: &mut Vec<Vec<u32>>, a: u32, b: u32) -> usize {
    let m = p.len() as u32;
    let (pa, pb) = (p[a as usize], p[b as usize]);
    p.push([0, 1, 2].map(|k| (pa[k] + pb[k]) / 2.0));
    let f = faces
        .iter()
        .position(|q| q.len() == 4 && (0..4).any(|i| q[i] == a && q[(i + 1) % 4] == b))
        .expect("a quad traversing a -> b");
    let q = faces.remove(f);
    let i = q.iter().position(|&v| v == a).unwrap();
    let [_, _, c, d] = [0, 1, 2, 3].map(|k| q[(i + k) % 4]);
    faces.extend([vec![a, m, d], vec![m, b, c], vec![m, c, d]]);
    faces.push(vec![a, b, m]);
    faces.len() - 1
}

fn assert_closed_unit_solid(c: &Check, mesh: &Mesh) {
    assert!(c.closed && c.bounds_a_volume(), "{}", c.verdict());
    assert_eq!((c.boundary_edges, c.boundary_loops, c.non_manifold_edges), (0, 0, 0));
    assert_eq!(c.shells.len(), 1);
    assert_eq!(c.volume, 1.0);
    assert_eq!(mass_properties(&c.solid(mesh)).signed_volume, 1.0);
}

#[test]
fn sliver_filling_a_t_junction_keeps_the_cube_closed() {
    let (mut p, mut faces) = cube_faces();
    let sliver = t_junction(&mut p, &mut faces, 0, 1);
    let mesh = polygons(&p, &faces);
    let c = checked(&mesh);
    assert_closed_unit_solid(&c, &mesh);
    assert_eq!((c.degenerate_faces, c.flat_faces, c.duplicate_faces), (1, 1, 0));
    assert_eq!(c.orientation, Some(Orientation::Outward));
    assert_eq!(c.self_intersections, Some(0));
    assert_eq!(c.repairs().1, 0); // nothing dropped: the sliver is part of the solid
                                  // Its three edges are each matched by a different face: without it, a 3-edge hole.
    let without: Vec<Vec<u32>> =
        faces.iter().enumerate().filter(|&(f, _)| f != sliver).map(|(_, q)| q.clone()).collect();
    let open = checked(&polygons(&p, &without));
    assert_eq!((open.boundary_edges, open.boundary_loops, open.closed), (3, 1, false));
}

#[test]
fn several_slivers_and_a_collapsed_face() {
    let (mut p, mut faces) = cube_faces();
    // Three T-junctions on three edges, each on a different quad.
    t_junction(&mut p, &mut faces, 0, 1); // bottom-front edge, front quad split
    t_junction(&mut p, &mut faces, 2, 6); // vertical back-right edge, right quad split
    t_junction(&mut p, &mut faces, 7, 4); // top-left edge, top quad split
    let mesh = polygons(&p, &faces);
    let c = checked(&mesh);
    assert_closed_unit_solid(&c, &mesh);
    assert_eq!((c.degenerate_faces, c.flat_faces), (3, 3));
    // A face with a repeated welded vertex is still dropped, without opening a hole.
    p.push(p[5]);
    let copy_of_5 = (p.len() - 1) as u32;
    faces.push(vec![5, 6, copy_of_5]);
    let mesh = polygons(&p, &faces);
    let c = checked(&mesh);
    assert_closed_unit_solid(&c, &mesh);
    assert_eq!((c.degenerate_faces, c.flat_faces, c.repairs().1), (4, 3, 1));
    // Exact welding and a tolerance agree.
    for weld in [Weld::Exact, Weld::Tolerance(1e-6)] {
        let c = check(&mesh, &CheckOptions { weld, ..CheckOptions::default() }).unwrap();
        assert_closed_unit_solid(&c, &mesh);
    }
}

#[test]
fn boxes_glued_face_to_face_cancel_their_double_wall() {
    // Both boxes keep their copy of the square at x = 1, wound opposite ways.
    let mesh =
        Mesh::concatenate(&[cuboid([0.0; 3], [1.0; 3]), cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0])]);
    let c = checked(&mesh);
    assert!(c.closed && c.bounds_a_volume(), "{}", c.verdict());
    assert_eq!((c.shells.len(), c.non_manifold_edges, c.boundary_edges), (1, 0, 0));
    assert_eq!((c.duplicate_faces, c.double_wall_faces), (2, 2));
    assert_eq!(c.volume, 2.0);
    assert_eq!(mass_properties(&c.solid(&mesh)).signed_volume, 2.0);
    // One box of 2 × 1 × 1 with its long sides split: V − E + F = 12 − 20 + 10.
    assert_eq!((c.euler_characteristic, c.shells[0].genus), (2, Some(0)));
}

#[test]
fn repeated_face_with_the_same_winding_collapses_to_one() {
    let (p, mut faces) = cube_faces();
    faces.push(faces[2].clone());
    let rotated = faces[4].clone();
    faces.push(vec![rotated[2], rotated[3], rotated[0], rotated[1]]);
    let mesh = polygons(&p, &faces);
    let c = checked(&mesh);
    assert_closed_unit_solid(&c, &mesh);
    assert_eq!((c.duplicate_faces, c.double_wall_faces), (2, 0));
}

#[test]
fn opposite_copies_cancel_in_pairs_and_one_of_the_rest_stays() {
    // Face 2 three times: as wound, reversed, as wound again: one pair cancels.
    let (p, mut faces) = cube_faces();
    let f = faces[2].clone();
    faces.push(f.iter().rev().copied().collect());
    faces.push(f);
    let mesh = polygons(&p, &faces);
    let c = checked(&mesh);
    assert_closed_unit_solid(&c, &mesh);
    assert_eq!((c.duplicate_faces, c.double_wall_faces), (2, 2));
    // Triangles: the reversed copy is an odd permutation, a rotated one even.
    let cube = cuboid([0.0; 3], [1.0; 3]).triangulated();
    let mut tris: Vec<Vec<u32>> = (0..cube.face_count()).map(|f| cube.face(f).to_vec()).collect();
    let t = tris[0].clone();
    tris.push(vec![t[1], t[0], t[2]]); // odd: opposite
    tris.push(vec![t[2], t[0], t[1]]); // even: the same
    let mesh = polygons(cube.positions(), &tris);
    let c = checked(&mesh);
    assert_closed_unit_solid(&c, &mesh);
    assert_eq!((c.duplicate_faces, c.double_wall_faces), (2, 2));
}

#[test]
fn double_sided_internal_triangle_cancels() {
    let (mut p, mut faces) = cube_faces();
    let base = p.len() as u32;
    p.extend([[0.2, 0.3, 0.4], [0.7, 0.2, 0.5], [0.4, 0.8, 0.6]]);
    faces.push(vec![base, base + 1, base + 2]);
    faces.push(vec![base, base + 2, base + 1]);
    let mesh = polygons(&p, &faces);
    let c = checked(&mesh);
    assert_closed_unit_solid(&c, &mesh);
    assert_eq!((c.duplicate_faces, c.double_wall_faces), (2, 2));
    assert_eq!(c.self_intersections, Some(0));
}
