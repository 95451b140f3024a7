//! The union's interval is certified: ordered, containing the exact union volume, and
//! as narrow as asked where faces touch or lie on each other (coplanar contact), against
//! volumes computed by hand from boxes and prisms.

mod common;

use common::{face_lists, moved, open_box, polygons};

use meshvol::grid::{union, UnionVolume};
use meshvol::shapes::cuboid;
use meshvol::{mass_properties, Mesh};

/// A prism: the polygon `profile` (x, z), counter-clockwise and fan-triangulable from its
/// first vertex, extruded along y over [0, depth]. Each side wall is cut into `n × n`
/// quads split into triangles, as CAD exports tessellate, so a shifted copy's triangles
/// straddle the original's.
fn prism(profile: &[[f64; 2]], depth: f64, n: usize) -> Mesh {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut vertex = |p: [f64; 3]| {
        positions.push(p);
        positions.len() as u32 - 1
    };
    let m = profile.len();
    // Caps: fans from vertex 0, at y = 0 and y = depth.
    let front: Vec<u32> = profile.iter().map(|q| vertex([q[0], 0.0, q[1]])).collect();
    let back: Vec<u32> = profile.iter().map(|q| vertex([q[0], depth, q[1]])).collect();
    for k in 1..m - 1 {
        triangles.push([front[0], front[k], front[k + 1]]);
        triangles.push([back[0], back[k + 1], back[k]]);
    }
    // Walls: an (n + 1) × (n + 1) lattice per edge; the lattice's border reuses the
    // caps' corners only at the ends, so walls and caps share vertices by position only
    // (the union works on positions).
    for e in 0..m {
        let (a, b) = (profile[e], profile[(e + 1) % m]);
        let mut index = vec![vec![0u32; n + 1]; n + 1];
        for (s, row) in index.iter_mut().enumerate() {
            for (t, slot) in row.iter_mut().enumerate() {
                let f = s as f64 / n as f64;
                let x = if s == n { b[0] } else { a[0] + f * (b[0] - a[0]) };
                let z = if s == n { b[1] } else { a[1] + f * (b[1] - a[1]) };
                let y = if t == n { depth } else { depth * t as f64 / n as f64 };
                *slot = vertex([x, y, z]);
            }
        }
        for s in 0..n {
            for t in 0..n {
                let (p, q, r, w) =
                    (index[s][t], index[s + 1][t], index[s + 1][t + 1], index[s][t + 1]);
                triangles.push([p, r, q]);
                triangles.push([p, w, r]);
            }
        }
    }
    let mesh = Mesh::from_triangles(positions, triangles).unwrap();
    if mass_properties(&mesh).signed_volume < 0.0 {
        mesh.flipped()
    } else {
        mesh
    }
}

/// The stepped profile: [0, 2] × [0, 1] with [0, 1] × [1, 2] on top (area 3).
const STEP: [[f64; 2]; 6] =
    [[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]];

fn check(what: &str, u: &UnionVolume, exact: f64, tolerance: f64) {
    assert!(u.lower <= u.upper, "{what}: inverted [{}, {}]", u.lower, u.upper);
    assert!(
        u.lower <= exact && exact <= u.upper,
        "{what}: {exact} not in [{}, {}]",
        u.lower,
        u.upper
    );
    let width = u.upper - u.lower;
    assert!(
        width <= tolerance * exact,
        "{what}: width {width:e} = {:e} of the volume, asked {tolerance:e} ({u:?})",
        width / exact
    );
    assert!(u.bodies_not_solid.is_empty(), "{what}: {:?}", u.bodies_not_solid);
    assert!(u.upper <= u.sum_of_volumes * (1.0 + tolerance), "{what}: above the sum");
}

#[test]
fn a_cube_and_a_copy_shifted_by_thirty_percent() {
    let a = cuboid([0.0; 3], [1.0; 3]);
    let b = moved(&a, [0.3, 0.0, 0.0]);
    // [0, 1.3] × [0, 1]²: the shifted copy's far face is at fl(1 + 0.3).
    let exact = 1.0 + 0.3;
    for tolerance in [1e-6, 1e-9] {
        check("cubes", &union(&[a.clone(), b.clone()], tolerance).unwrap(), exact, tolerance);
    }
}

#[test]
fn a_stepped_prism_and_a_copy_shifted_by_thirty_percent() {
    // Profile union: z in [0, 1] spans x in [0, 2.6], z in [1, 2] spans [0, 1.6]; depth 1.
    // Its top faces at z = 1, bottoms at z = 0, both caps, and the left wall of the copy
    // (inside the original) lie on the original's faces.
    for n in [1, 3] {
        let a = prism(&STEP, 1.0, n);
        assert_eq!(mass_properties(&a).signed_volume, 3.0);
        let b = moved(&a, [0.6, 0.0, 0.0]);
        let exact = (2.0 + 0.6) + (1.0 + 0.6);
        for tolerance in [1e-6, 1e-9] {
            let u = union(&[a.clone(), b.clone()], tolerance).unwrap();
            check(&format!("steps, {n}×{n} walls, {tolerance:e}"), &u, exact, tolerance);
        }
    }
}

#[test]
fn glued_and_identical_bodies() {
    // Glued face to face along x and z: the sum.
    let a = prism(&STEP, 1.0, 2);
    for (d, what) in [([2.0, 0.0, 0.0], "glued along x"), ([0.0, 1.0, 0.0], "glued along y")] {
        let b = moved(&a, d);
        for tolerance in [1e-6, 1e-9] {
            let u = union(&[a.clone(), b.clone()], tolerance).unwrap();
            check(what, &u, 6.0, tolerance);
        }
    }
    // A copy: one volume; a copy tessellated differently: one volume too.
    let c = prism(&STEP, 1.0, 3);
    for tolerance in [1e-6, 1e-9] {
        check("copy", &union(&[a.clone(), a.clone()], tolerance).unwrap(), 3.0, tolerance);
        check("retessellated", &union(&[a.clone(), c.clone()], tolerance).unwrap(), 3.0, tolerance);
    }
}

/// `mesh` with x and y swapped (wound outward again) and moved by `d`.
fn swapped(mesh: &Mesh, d: [f64; 3]) -> Mesh {
    let positions = mesh.positions().iter().map(|p| [p[1] + d[0], p[0] + d[1], p[2] + d[2]]);
    let m = Mesh::new(positions.collect(), mesh.faces().clone()).unwrap();
    if mass_properties(&m).signed_volume < 0.0 {
        m.flipped()
    } else {
        m
    }
}

#[test]
fn extrusions_along_the_shift() {
    // Prisms extruded along x, shifted along x by 30 % of their length: every wall of
    // the copy lies on a wall of the original over 70 % of it. Off the grid's planes.
    let gon: Vec<[f64; 2]> = (0..20)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 20.0;
            [t.cos(), t.sin()]
        })
        .collect();
    for (profile, n) in [(&STEP[..], 2), (&gon[..], 1), (&gon[..], 3)] {
        let a = swapped(&prism(profile, 1.0, n), [0.137, 0.291, 0.05]);
        let area = mass_properties(&a).signed_volume;
        let b = moved(&a, [0.3, 0.0, 0.0]);
        for tolerance in [1e-6, 1e-9] {
            let u = union(&[a.clone(), b.clone()], tolerance).unwrap();
            eprintln!("{u:?}");
            check(&format!("extrusion {n} {tolerance:e}"), &u, area * 1.3, tolerance);
        }
    }
}

/// The sample part's triangles (binary STL: 80-byte header, count, 50 bytes each).
fn sample_part() -> Mesh {
    let bytes = include_bytes!("../../../samples/flanged-bushing.stl");
    let count = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in 0..count {
        let record = &bytes[84 + 50 * t..84 + 50 * (t + 1)];
        let mut corner = [0u32; 3];
        for (v, slot) in corner.iter_mut().enumerate() {
            let at = 12 + 12 * v;
            let p = [0, 1, 2].map(|k| {
                let b = &record[at + 4 * k..at + 4 * k + 4];
                f32::from_le_bytes(b.try_into().unwrap()) as f64
            });
            positions.push(p);
            *slot = positions.len() as u32 - 1;
        }
        triangles.push(corner);
    }
    Mesh::from_triangles(positions, triangles).unwrap()
}

#[test]
fn a_cad_part_and_a_copy_shifted_by_thirty_percent() {
    // The sample bushing and a copy shifted by 30 % of its width: its flange faces lie on
    // each other's planes. No closed form: the interval must hold the larger body and be
    // held by the sum, be as narrow as asked, and be the same bits on one thread.
    let a = sample_part();
    let bounds = mass_properties(&a).bounds.unwrap();
    let b = moved(&a, [0.3 * (bounds.max[0] - bounds.min[0]), 0.0, 0.0]);
    let volume = mass_properties(&a).signed_volume;
    for tolerance in [1e-6, 1e-9] {
        let u = union(&[a.clone(), b.clone()], tolerance).unwrap();
        assert!(volume <= u.upper && u.lower <= u.sum_of_volumes, "{u:?}");
        assert!(u.upper - u.lower <= tolerance * u.lower, "{u:?}");
        assert!(u.bodies_not_solid.is_empty() && u.columns_unresolved == 0, "{u:?}");
        let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let one = pool.install(|| union(&[a.clone(), b.clone()], tolerance).unwrap());
        assert_eq!(
            (one.lower.to_bits(), one.upper.to_bits()),
            (u.lower.to_bits(), u.upper.to_bits())
        );
    }
}

#[test]
fn a_tilted_box_and_a_copy_shifted_along_its_faces() {
    // A unit box with 4 × 4-lattice walls, turned by 0.5 rad about y and moved off the
    // origin, and a copy shifted by 0.3 along y: four tilted walls lie on each other's
    // planes up to the rounding of the turned coordinates (1e-16), which changes the
    // union's 1.3 by far less than the interval's rounding allowance.
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let p = prism(&square, 1.0, 4);
    let (c, s) = (0.5f64.cos(), 0.5f64.sin());
    let turn = |q: &[f64; 3]| [c * q[0] + s * q[2] + 10.1, q[1] + 3.3, -s * q[0] + c * q[2] + 7.7];
    let a = Mesh::new(p.positions().iter().map(turn).collect(), p.faces().clone()).unwrap();
    let b = moved(&a, [0.0, 0.3, 0.0]);
    for tolerance in [1e-6, 1e-9] {
        check("tilted boxes", &union(&[a.clone(), b.clone()], tolerance).unwrap(), 1.3, tolerance);
    }
}

#[test]
fn bodies_that_are_not_solids_are_named_and_the_interval_stays_ordered() {
    // Open boxes over a solid one, and a box with its top face wound the wrong way:
    // each gives cell volumes outside [0, |C|].
    let solid = cuboid([0.2, 0.1, 0.3], [1.4, 1.0, 1.1]);
    let mut twisted = cuboid([0.5; 3], [1.5; 3]);
    twisted = {
        let mut faces = face_lists(&twisted);
        faces[1].reverse();
        polygons(twisted.positions(), &faces)
    };
    // (An open box whose bottom lies on the grid's bottom plane adds nothing to any cell
    // and is not caught here: callers check that bodies are closed.)
    let unit_open_box = open_box([0.0; 3], [1.0; 3]);
    let cases: [(Vec<Mesh>, Vec<usize>); 2] = [
        (
            vec![
                solid.clone(),
                moved(&unit_open_box, [0.3, 0.2, 0.4]),
                moved(&unit_open_box, [0.6, 0.5, 0.5]),
            ],
            vec![1, 2],
        ),
        (vec![solid, twisted], vec![1]),
    ];
    for (bodies, not_solid) in cases {
        for tolerance in [1e-6, 1e-9] {
            let u = union(&bodies, tolerance).unwrap();
            assert!(u.lower <= u.upper, "inverted: {u:?}");
            assert_eq!(u.bodies_not_solid, not_solid, "{u:?}");
        }
    }
}
