//! The bodies of a checked solid (`Check::bodies`): each outermost shell with what is
//! nested in it, each closed by its own caps, so that measuring a body gives its volume
//! and the bodies add up to the solid; and the separate objects of a file given to the
//! check as bodies, within which alone shells nest. Expected values are closed forms.

mod common;

use common::open_box;

use meshvol::assembly::{Affine, Assembly, Placement};
use meshvol::shapes::cuboid;
use meshvol::surface::FaceSubset;
use meshvol::topology::{
    check, check_assembled, check_in_stages, BodyOverlap, Check, CheckOptions,
};
use meshvol::{mass_properties, Mesh};

/// Each body's volume, measured over the checked solid.
fn body_volumes(mesh: &Mesh) -> (Vec<usize>, Vec<f64>, f64) {
    let c = check(mesh, &CheckOptions::default()).unwrap();
    let solid = c.solid(mesh);
    let bodies = c.bodies();
    let volumes = bodies
        .iter()
        .map(|b| mass_properties(&FaceSubset::new(solid, b.faces.clone())).signed_volume);
    (bodies.iter().map(|b| b.shell).collect(), volumes.collect(), c.volume)
}

#[test]
fn a_cavity_and_an_island_belong_to_their_outer_shell() {
    // A 10-cube with a 6-cube cavity holding a 2-cube island, and a unit cube apart.
    let mesh = Mesh::concatenate(&[
        cuboid([0.0; 3], [10.0; 3]),
        cuboid([2.0; 3], [8.0; 3]),
        cuboid([4.0; 3], [6.0; 3]),
        cuboid([20.0; 3], [21.0; 3]),
    ]);
    let (shells, volumes, total) = body_volumes(&mesh);
    assert_eq!(shells, [0, 3]);
    assert_eq!(volumes, [1000.0 - 216.0 + 8.0, 1.0]);
    assert_eq!(total, 793.0);
}

/// An open square pyramid: the rim (x0..x0+1) × (y0..y0+1) at height `top`, the apex
/// `depth` below its centre; volume depth / 3.
fn open_pyramid(x0: f64, y0: f64, top: f64, depth: f64) -> Mesh {
    let positions = vec![
        [x0, y0, top],
        [x0 + 1.0, y0, top],
        [x0 + 1.0, y0 + 1.0, top],
        [x0, y0 + 1.0, top],
        [x0 + 0.5, y0 + 0.5, top - depth],
    ];
    Mesh::from_triangles(positions, vec![[1, 0, 4], [2, 1, 4], [3, 2, 4], [0, 3, 4]]).unwrap()
}

#[test]
fn holes_are_capped_within_their_own_shell() {
    // An open box and an open pyramid whose rims meet at the corner (1, 1, 1) only: a
    // boundary loop must not wander from one rim into the other, or each body's cap
    // closes the wrong hole.
    let mesh =
        Mesh::concatenate(&[open_box([0.0; 3], [1.0; 3]), open_pyramid(1.0, 1.0, 1.0, 0.75)]);
    let c = check(&mesh, &CheckOptions::default()).unwrap();
    assert_eq!((c.shells.len(), c.boundary_loops), (2, 2));
    let (shells, mut volumes, total) = body_volumes(&mesh);
    assert_eq!(shells, [0, 1]);
    // Flat rims: each cap restores the missing face exactly.
    volumes.sort_by(f64::total_cmp);
    assert_eq!(volumes, [0.25, 1.0]);
    assert_eq!(total, 1.25);
    let mut shell_volumes: Vec<f64> = c.shells.iter().map(|s| s.volume).collect();
    shell_volumes.sort_by(f64::total_cmp);
    assert_eq!(shell_volumes, [0.25, 1.0]);
}

/// `meshes` side by side, each a separate object, checked with the objects as bodies.
fn objects(meshes: &[Mesh]) -> (Mesh, Check) {
    let mut runs = Vec::new();
    for m in meshes {
        let start = runs.last().map_or(0, |r: &std::ops::Range<usize>| r.end);
        runs.push(start..start + m.face_count());
    }
    let mesh = Mesh::concatenate(meshes);
    let c = check_in_stages(&mesh, &runs, &CheckOptions::default(), &()).unwrap();
    (mesh, c)
}

#[test]
fn an_object_inside_another_is_a_solid_and_they_overlap() {
    // A part (a unit cube) in its packaging (a 4-cube): two objects, so two solids whose
    // volumes add up, 64 + 1, with the pair reported as nested. As one object, the inner
    // shell is a cavity: 64 − 1.
    let (big, small) = (cuboid([0.0; 3], [4.0; 3]), cuboid([1.0; 3], [2.0; 3]));
    let (mesh, c) = objects(&[big.clone(), small.clone()]);
    assert_eq!((c.cavities, c.volume), (0, 65.0));
    assert_eq!(c.overlapping_bodies, [BodyOverlap { bodies: [0, 1], nested: true }]);
    assert!(c.overlapping_shells.is_empty() && !c.bounds_a_volume());
    assert!(c.doubts().iter().any(|d| d.contains("object 0 and object 1: one lies inside")));
    assert_eq!(mass_properties(&c.solid(&mesh)).signed_volume, 65.0);
    // Each object is a body of the solid: the union sees two.
    let bodies: Vec<usize> = c.bodies().iter().map(|b| b.shell).collect();
    assert_eq!(bodies, [0, 1]);
    let one = check(&mesh, &CheckOptions::default()).unwrap();
    assert_eq!((one.cavities, one.volume), (1, 63.0));
    assert!(one.overlapping_bodies.is_empty() && one.bounds_a_volume());
}

#[test]
fn objects_whose_surfaces_cross_overlap_and_cavities_stay_inside_their_object() {
    // Two 2-cubes sharing a 1 × 2 × 2 slab: their surfaces cross.
    let (_, c) = objects(&[cuboid([0.0; 3], [2.0; 3]), cuboid([1.0, 0.5, 0.5], [3.0, 2.5, 2.5])]);
    assert_eq!(c.overlapping_bodies, [BodyOverlap { bodies: [0, 1], nested: false }]);
    assert!(c.overlapping_shells.is_empty());
    assert_eq!(c.volume, 16.0);
    // A hollow box (one object: a 10-cube with a 6-cube cavity) and a ball-like 2-cube
    // lying in the cavity (another object): inside two shells of the box, so in its void,
    // sharing no volume. The box keeps its cavity.
    let hollow = Mesh::concatenate(&[cuboid([0.0; 3], [10.0; 3]), cuboid([2.0; 3], [8.0; 3])]);
    let (_, c) = objects(&[hollow, cuboid([4.0; 3], [6.0; 3])]);
    assert!(c.overlapping_bodies.is_empty(), "{:?}", c.overlapping_bodies);
    assert_eq!((c.cavities, c.volume), (1, 1000.0 - 216.0 + 8.0));
    assert!(c.bounds_a_volume());
}

#[test]
fn copies_checked_once_keep_their_objects() {
    // One unit cube placed three times apart, each copy an object: the check of the part
    // put side by side must say which object each body is, as the whole's check does.
    let shift = |x: f64| Affine([[1.0, 0.0, 0.0, x], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]);
    let part = cuboid([0.0; 3], [1.0; 3]);
    let placements: Vec<Placement> =
        [0.0, 3.0, 6.0].map(|x| Placement { part: 0, transform: shift(x) }).to_vec();
    let copies: Vec<Mesh> =
        [0.0, 3.0, 6.0].map(|x| cuboid([x, 0.0, 0.0], [x + 1.0, 1.0, 1.0])).to_vec();
    let (mesh, whole) = objects(&copies);
    let assembly = Assembly { parts: vec![part], placements };
    let n = copies[0].face_count();
    let runs = [0..n, n..2 * n, 2 * n..3 * n];
    let parts =
        check_assembled(&mesh, Some(&assembly), &runs, &CheckOptions::default(), &()).unwrap();
    let of = |c: &Check| c.bodies().iter().map(|b| b.object).collect::<Vec<_>>();
    assert_eq!(of(&parts), [Some(0), Some(1), Some(2)]);
    assert_eq!(of(&parts), of(&whole));
    assert_eq!((parts.volume, parts.overlapping_bodies.len()), (3.0, 0));
}
