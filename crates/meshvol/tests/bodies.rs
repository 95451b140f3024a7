//! The bodies of a checked solid (`Check::bodies`): each outermost shell with what is
//! nested in it, each closed by its own caps, so that measuring a body gives its volume
//! and the bodies add up to the solid. Expected values are closed forms.

mod common;

use common::open_box;

use meshvol::shapes::cuboid;
use meshvol::surface::FaceSubset;
use meshvol::topology::{check, CheckOptions};
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
