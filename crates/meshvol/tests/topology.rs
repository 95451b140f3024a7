//! Topology checks on hand-built tricky cases, against facts known by construction.

mod common;

use common::checked;

use meshvol::shapes::{cuboid, torus, uv_sphere};
use meshvol::topology::{check, CheckOptions, Orientation, Weld};
use meshvol::{mass_properties, Mesh};

fn without_face(mesh: &Mesh, drop: usize) -> Mesh {
    let faces: Vec<&[u32]> =
        (0..mesh.face_count()).filter(|&f| f != drop).map(|f| mesh.face(f)).collect();
    Mesh::from_polygons(mesh.positions().to_vec(), faces).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn closed_box_and_torus_genus() {
    let c = checked(&cuboid([0.0; 3], [1.0; 3]));
    assert!(c.closed && c.consistently_oriented && c.bounds_a_volume());
    assert_eq!((c.vertices, c.edges, c.faces), (8, 12, 6));
    assert_eq!((c.euler_characteristic, c.shells[0].genus), (2, Some(0)));
    let t = checked(&torus(3.0, 1.0, 24, 12));
    assert_eq!((t.euler_characteristic, t.shells[0].genus), (0, Some(1)));
    assert!(close(t.volume, mass_properties(&torus(3.0, 1.0, 24, 12)).signed_volume));
}

#[test]
fn inside_out_sphere_is_inward_and_still_measured() {
    let sphere = uv_sphere(1.0, 32, 16);
    let inverted = sphere.flipped();
    let c = checked(&inverted);
    assert_eq!(c.orientation, Some(Orientation::Inward));
    assert_eq!(c.shells[0].wound_outward, Some(false));
    let expected = mass_properties(&sphere);
    assert!(close(c.volume, expected.signed_volume));
    let solid = mass_properties(&c.solid(&inverted));
    assert!(close(solid.signed_volume, expected.signed_volume));
    assert_eq!(c.repairs().0, inverted.face_count()); // every face turned
}

/// A 2×2×2 box with a 1×1×1 cavity off-centre: volume 7, centroid (8·1 − 1·0.75)/7.
fn box_with_cavity(cavity_wound_like_a_solid: bool) -> Mesh {
    let outer = cuboid([0.0; 3], [2.0; 3]);
    let inner = cuboid([0.25; 3], [1.25; 3]);
    Mesh::concatenate(&[outer, if cavity_wound_like_a_solid { inner } else { inner.flipped() }])
}

#[test]
fn cavity_is_subtracted_whatever_its_winding() {
    for like_a_solid in [false, true] {
        let mesh = box_with_cavity(like_a_solid);
        let c = checked(&mesh);
        assert_eq!((c.shells.len(), c.cavities), (2, 1), "{like_a_solid}");
        assert!(c.shells[1].cavity && !c.shells[0].cavity);
        assert_eq!(c.shells[1].parent, Some(0));
        assert!(close(c.volume, 7.0));
        assert!(c.overlapping_shells.is_empty());
        let expected_orientation =
            if like_a_solid { Orientation::Mixed } else { Orientation::Outward };
        assert_eq!(c.orientation, Some(expected_orientation));
        let mp = mass_properties(&c.solid(&mesh));
        assert!(close(mp.signed_volume, 7.0));
        let centroid = (8.0 - 0.75) / 7.0;
        assert!(mp.centroid.unwrap().iter().all(|&x| close(x, centroid)), "{:?}", mp.centroid);
        // The plain sum is wrong exactly when the cavity is wound like a solid.
        let plain = mass_properties(&mesh).signed_volume;
        assert!(close(plain, if like_a_solid { 9.0 } else { 7.0 }));
    }
}

#[test]
fn nested_solid_inside_a_cavity() {
    // Box, cavity, and an island inside the cavity: 8 − 3.375 + 1 (depth 0, 1, 2).
    let mesh = Mesh::concatenate(&[
        cuboid([0.0; 3], [2.0; 3]),
        cuboid([0.25; 3], [1.75; 3]),
        cuboid([0.5; 3], [1.5; 3]),
    ]);
    let c = checked(&mesh);
    assert_eq!(c.cavities, 1);
    assert_eq!(c.shells[2].parent, Some(1));
    assert!(close(c.volume, 8.0 - 3.375 + 1.0));
    assert!(close(mass_properties(&c.solid(&mesh)).signed_volume, 5.625));
}

#[test]
fn missing_face_is_capped_exactly_when_flat() {
    let open = without_face(&cuboid([0.0; 3], [1.0; 3]), 1);
    let c = checked(&open);
    assert!(!c.closed && !c.bounds_a_volume());
    assert_eq!((c.boundary_edges, c.boundary_loops), (4, 1));
    assert!(close(c.volume, 1.0));
    assert_eq!(c.volume_uncertainty, 0.0);
    assert!(close(mass_properties(&c.solid(&open)).signed_volume, 1.0));
    assert_eq!(c.repairs().2, 4); // a fan of four cap triangles
                                  // A hole in a sphere's side is not flat: the cap is a guess, and says so.
    let sphere = uv_sphere(1.0, 16, 8);
    let around_vertex_20: Vec<&[u32]> =
        (0..sphere.face_count()).map(|f| sphere.face(f)).filter(|f| !f.contains(&20)).collect();
    let holed = Mesh::from_polygons(sphere.positions().to_vec(), around_vertex_20).unwrap();
    let c = checked(&holed);
    assert_eq!(c.boundary_loops, 1);
    assert!(c.volume_uncertainty > 0.0);
    let truth = mass_properties(&sphere).signed_volume;
    assert!((c.volume - truth).abs() <= c.volume_uncertainty, "{} vs {truth}", c.volume);
}

#[test]
fn overlapping_shells_are_found() {
    // In general position, triangles cross.
    let mesh =
        Mesh::concatenate(&[cuboid([0.0; 3], [1.0; 3]), cuboid([0.5, 0.6, 0.7], [1.5, 1.6, 1.7])]);
    let c = checked(&mesh);
    assert_eq!(c.overlapping_shells, vec![[0, 1]]);
    assert_eq!(c.self_intersections, Some(0));
    assert!(!c.intersection_examples.is_empty() && !c.bounds_a_volume());
    // Symmetric: every crossing point lies on a quad's diagonal, so no triangle pair
    // crosses strictly; the vertex inside the other box still reveals the overlap.
    let mesh = Mesh::concatenate(&[cuboid([0.0; 3], [1.0; 3]), cuboid([0.5; 3], [1.5; 3])]);
    assert_eq!(checked(&mesh).overlapping_shells, vec![[0, 1]]);
    // Touching boxes (sharing a face's plane) do not overlap.
    let touching =
        Mesh::concatenate(&[cuboid([0.0; 3], [1.0; 3]), cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0])]);
    assert!(checked(&touching).overlapping_shells.is_empty());
}

#[test]
fn self_intersection_in_one_shell() {
    // Push the box's top corner (1, 1, 1) down through the bottom face.
    let mut p = cuboid([0.0; 3], [1.0; 3]).positions().to_vec();
    p[6] = [0.6, 0.6, -0.5];
    let mesh = Mesh::new(p, cuboid([0.0; 3], [1.0; 3]).faces().clone()).unwrap();
    let c = checked(&mesh);
    assert_eq!(c.shells.len(), 1);
    assert!(c.self_intersections.unwrap() > 0);
}

#[test]
fn mobius_strip_is_not_orientable() {
    // A strip of n quads around a circle with a half twist.
    let n = 12;
    let mut p = Vec::new();
    for i in 0..n {
        let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        let (dx, dz) = ((t / 2.0).cos() * 0.3, (t / 2.0).sin() * 0.3);
        let r = [t.cos(), t.sin(), 0.0];
        p.push([r[0] * (1.0 + dx), r[1] * (1.0 + dx), dz]);
        p.push([r[0] * (1.0 - dx), r[1] * (1.0 - dx), -dz]);
    }
    let quads: Vec<[u32; 4]> = (0..n)
        .map(|i| {
            let (a, b) = (2 * i, 2 * i + 1);
            // After a full turn the strip's sides have swapped.
            let (c, d) = if i + 1 == n { (1, 0) } else { (2 * i + 2, 2 * i + 3) };
            [a, c, d, b]
        })
        .collect();
    let mesh = Mesh::from_polygons(p, quads.iter().map(|q| &q[..])).unwrap();
    let c = checked(&mesh);
    assert!(!c.shells[0].orientable && !c.consistently_oriented);
    assert_eq!(c.orientation, Some(Orientation::Mixed));
    assert_eq!(c.boundary_loops, 1); // a Möbius strip has one edge
}

#[test]
fn bowtie_vertex_and_non_manifold_edge() {
    // Two tetrahedra sharing only the vertex at the origin.
    let t = |s: f64| {
        Mesh::from_triangles(
            vec![[0.0; 3], [s, 0.0, 0.0], [0.0, s, 0.0], [0.0, 0.0, s]],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
        .unwrap()
    };
    let bowtie = Mesh::concatenate(&[t(1.0), t(-1.0).flipped()]);
    let c = checked(&bowtie);
    assert_eq!((c.non_manifold_vertices, c.non_manifold_edges, c.shells.len()), (1, 0, 2));
    assert!(close(c.volume, 2.0 / 6.0));
    // Three triangles on one edge.
    let fin = Mesh::from_triangles(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    )
    .unwrap();
    assert_eq!(checked(&fin).non_manifold_edges, 1);
}

#[test]
fn duplicate_and_degenerate_faces_are_dropped() {
    let cube = cuboid([0.0; 3], [1.0; 3]).triangulated();
    let mut faces: Vec<Vec<u32>> = (0..cube.face_count()).map(|f| cube.face(f).to_vec()).collect();
    faces.push(faces[3].clone()); // duplicate
    faces.push(vec![faces[5][2], faces[5][0], faces[5][1]]); // same triangle, rotated
    let mut p = cube.positions().to_vec();
    // A second copy of vertex 1's position: welded, the face repeats a vertex.
    p.push(p[1]);
    faces.push(vec![0, 8, 1]);
    let mesh = Mesh::from_polygons(p, faces.iter().map(|f| &f[..])).unwrap();
    let c = checked(&mesh);
    assert_eq!((c.duplicate_faces, c.degenerate_faces, c.flat_faces), (2, 1, 0));
    assert_eq!(c.double_wall_faces, 0);
    assert!(c.closed);
    assert!(close(c.volume, 1.0));
    assert!(close(mass_properties(&c.solid(&mesh)).signed_volume, 1.0));
}

#[test]
fn unwelded_soup_welds_exactly_or_with_a_tolerance() {
    // A triangle soup: every triangle has its own copies of its corners.
    let cube = cuboid([0.0; 3], [1.0; 3]).triangulated();
    let mut p = Vec::new();
    let mut tris = Vec::new();
    for f in 0..cube.face_count() {
        let base = p.len() as u32;
        p.extend(cube.face(f).iter().map(|&i| cube.positions()[i as usize]));
        tris.push([base, base + 1, base + 2]);
    }
    let soup = Mesh::from_triangles(p.clone(), tris.clone()).unwrap();
    let c = checked(&soup);
    assert!(c.closed && c.vertices == 8);
    // Jitter the copies by 1e-9: exact welding leaves it open, a tolerance closes it.
    let jittered: Vec<_> =
        p.iter().enumerate().map(|(i, v)| v.map(|x| x + 1e-9 * (i % 3) as f64)).collect();
    let soup = Mesh::from_triangles(jittered, tris).unwrap();
    let exact = CheckOptions { weld: Weld::Exact, ..CheckOptions::default() };
    assert!(!check(&soup, &exact).unwrap().closed);
    let tol = CheckOptions { weld: Weld::Tolerance(1e-6), ..CheckOptions::default() };
    assert!(check(&soup, &tol).unwrap().closed);
    // The default retries within 1e-9 of the diagonal (√3 here) and says so.
    let auto = checked(&soup);
    assert!(auto.closed);
    let used = auto.weld_tolerance.unwrap();
    assert!((used - 1e-9 * 3f64.sqrt()).abs() < 1e-15, "{used}");
    // Jitter beyond that stays open by default.
    let far: Vec<_> =
        p.iter().enumerate().map(|(i, v)| v.map(|x| x + 1e-6 * (i % 3) as f64)).collect();
    let far =
        Mesh::from_triangles(far, (0..12u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect());
    let far = checked(&far.unwrap());
    assert!(!far.closed && far.weld_tolerance.is_none());
}

#[test]
fn same_result_at_any_thread_count() {
    let mesh = Mesh::concatenate(&[
        uv_sphere(2.0, 96, 48),
        uv_sphere(1.0, 64, 32),
        cuboid([1.5; 3], [3.0; 3]),
    ]);
    let run = |n| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
        pool.install(|| format!("{:?}", checked(&mesh)))
    };
    assert_eq!(run(1), run(3));
}

#[test]
fn repaired_mesh_is_a_clean_outward_solid() {
    // A cavity wound like a solid, plus an open box elsewhere, plus a duplicate face.
    let open_box = without_face(&cuboid([5.0; 3], [6.0; 3]), 2);
    let mut mesh = Mesh::concatenate(&[box_with_cavity(true), open_box]);
    let faces: Vec<Vec<u32>> = (0..mesh.face_count())
        .map(|f| mesh.face(f).to_vec())
        .chain([mesh.face(0).to_vec()])
        .collect();
    mesh = Mesh::from_polygons(mesh.positions().to_vec(), faces.iter().map(|f| &f[..])).unwrap();
    let c = checked(&mesh);
    assert_eq!((c.duplicate_faces, c.boundary_loops, c.cavities), (1, 1, 1));
    let repaired = c.solid_mesh(true);
    let again = checked(&repaired);
    assert!(again.closed && again.bounds_a_volume());
    assert_eq!(again.orientation, Some(Orientation::Outward));
    assert_eq!((again.duplicate_faces, again.cavities, again.shells.len()), (0, 1, 3));
    // Now even the plain signed sum is the solid's volume: 8 − 1 + 1.
    assert!(close(mass_properties(&repaired).signed_volume, 8.0));
    // Without caps the hole stays.
    assert_eq!(checked(&c.solid_mesh(false)).boundary_loops, 1);
}

/// Scattered boxes, some overlapping, some inside others: the overlapping pairs and the
/// cavities against every pair of boxes compared directly.
#[test]
fn scattered_boxes_against_all_pairs() {
    let mut rng = common::XorShift::new(0x51_7cc1_b727_220a);
    let mut boxes: Vec<([f64; 3], [f64; 3])> = (0..400)
        .map(|_| {
            let min = [0, 1, 2].map(|_| rng.unit() * 20.0);
            let size = 0.2 + rng.unit() * 1.5;
            (min, min.map(|x| x + size))
        })
        .collect();
    // A box inside the first (a cavity), and one inside that (an island).
    let corner = boxes[0].0;
    boxes.push((corner.map(|x| x + 0.02), corner.map(|x| x + 0.18)));
    boxes.push((corner.map(|x| x + 0.05), corner.map(|x| x + 0.15)));
    let mesh = Mesh::concatenate(&boxes.iter().map(|&(a, b)| cuboid(a, b)).collect::<Vec<_>>());
    let c = checked(&mesh);
    let inside = |a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3])| {
        (0..3).all(|k| b.0[k] < a.0[k] && a.1[k] < b.1[k])
    };
    let meet = |a: &([f64; 3], [f64; 3]), b: &([f64; 3], [f64; 3])| {
        (0..3).all(|k| a.0[k] < b.1[k] && b.0[k] < a.1[k])
    };
    let mut overlapping = Vec::new();
    for i in 0..boxes.len() {
        for j in i + 1..boxes.len() {
            let (a, b) = (&boxes[i], &boxes[j]);
            if meet(a, b) && !inside(a, b) && !inside(b, a) {
                overlapping.push([i, j]);
            }
        }
    }
    assert!(!overlapping.is_empty());
    assert_eq!(c.overlapping_shells, overlapping);
    let nested = (0..boxes.len())
        .filter(|&i| (0..boxes.len()).filter(|&j| inside(&boxes[i], &boxes[j])).count() % 2 == 1)
        .count();
    assert!(nested > 0);
    assert_eq!(c.cavities, nested);
}

/// A cavity whose every corner lies on its container's surface (a square hole through
/// a slab, modelled as a box whose top and bottom lie in the slab's): no corner can
/// tell inside from outside, but the cavity's walls are inside the slab. It is a
/// cavity, whichever way it is wound (it was a second solid, adding its volume).
#[test]
fn a_cavity_with_every_corner_on_its_container_is_a_cavity() {
    for hole in [
        cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 2.0]),
        cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 2.0]).flipped(),
    ] {
        let mesh = Mesh::concatenate(&[cuboid([0.0; 3], [4.0, 4.0, 2.0]), hole]);
        let c = checked(&mesh);
        assert_eq!((c.shells.len(), c.cavities, c.volume), (2, 1, 30.0));
        assert_eq!(mass_properties(&c.solid(&mesh)).signed_volume, 30.0);
    }
}

/// A large Möbius strip of `n` quads (non-orientable, one boundary loop), offset by `at`.
fn mobius(n: u32, at: f64) -> Mesh {
    let mut p = Vec::new();
    for i in 0..n {
        let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        let (dx, dz) = ((t / 2.0).cos() * 0.3, (t / 2.0).sin() * 0.3);
        let r = [t.cos(), t.sin(), 0.0];
        p.push([at + r[0] * (1.0 + dx), r[1] * (1.0 + dx), dz]);
        p.push([at + r[0] * (1.0 - dx), r[1] * (1.0 - dx), -dz]);
    }
    let quads: Vec<[u32; 4]> = (0..n)
        .map(|i| {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i + 1 == n { (1, 0) } else { (2 * i + 2, 2 * i + 3) };
            [a, c, d, b]
        })
        .collect();
    Mesh::from_polygons(p, quads.iter().map(|q| &q[..])).unwrap()
}

#[test]
fn messy_surfaces_check_the_same_at_any_thread_count() {
    // Large enough that every parallel stage splits (tens of thousands of faces per
    // part): nested spheres, one with faces wound against their neighbours, a Möbius
    // strip (orientation then comes from the walk), a bowtie, a fin, duplicates and a
    // double wall, scattered over the face order.
    let mut wound = uv_sphere(1.0, 160, 80).triangulated();
    let faces: Vec<Vec<u32>> = (0..wound.face_count())
        .map(|f| {
            let mut face = wound.face(f).to_vec();
            if f % 7 == 3 {
                face.reverse();
            }
            face
        })
        .collect();
    wound = Mesh::from_polygons(wound.positions().to_vec(), faces.iter().map(|f| &f[..])).unwrap();
    let tetra = |s: f64, x: f64| {
        Mesh::from_triangles(
            vec![[x, 0.0, 0.0], [x + s, 0.0, 0.0], [x, s, 0.0], [x, 0.0, s]],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
        .unwrap()
    };
    let fin = Mesh::from_triangles(
        vec![[9.0, 0.0, 0.0], [10.0, 0.0, 0.0], [9.0, 1.0, 0.0], [9.0, -1.0, 0.0], [9.0, 0.0, 1.0]],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    )
    .unwrap();
    let parts = Mesh::concatenate(&[
        uv_sphere(3.0, 160, 80),
        wound,
        mobius(4_000, 20.0),
        tetra(1.0, -9.0),
        tetra(-1.0, -9.0).flipped(),
        fin,
    ]);
    // Interleave the faces (shells then run in many pieces through the face order) and
    // repeat some: copies wound alike, and opposite ones (double walls).
    let n = parts.face_count();
    let mut order: Vec<Vec<u32>> = (0..n).map(|i| parts.face((i * 7919) % n).to_vec()).collect();
    for f in (0..n).step_by(997) {
        let face = parts.face(f).to_vec();
        order.push(face.clone());
        let mut back = face;
        back.reverse();
        if f % 2 == 0 {
            order.push(back);
        }
    }
    let mesh =
        Mesh::from_polygons(parts.positions().to_vec(), order.iter().map(|f| &f[..])).unwrap();
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let c = checked(&mesh);
            let solid = c.solid_mesh(true);
            (format!("{c:?}"), format!("{:?}", (solid.positions(), c.bodies())), c)
        })
    };
    let (one, one_solid, c) = run(1);
    assert!(c.shells.iter().any(|s| !s.orientable));
    assert!(c.non_manifold_vertices > 0 && c.non_manifold_edges > 0);
    assert!(c.duplicate_faces > 0 && c.double_wall_faces > 0 && !c.consistently_oriented);
    for threads in [2, 3, 8] {
        let (many, many_solid, _) = run(threads);
        assert!(one == many && one_solid == many_solid, "{threads} threads differ");
    }
}

#[test]
fn a_lone_shell_counts_as_it_does_beside_another() {
    // A check counts a lone shell from the whole surface's totals, and shells among
    // others one by one: the same counts either way. Each surface alone, then with a
    // tetrahedron far away (a second shell) after it.
    let tetra = Mesh::from_triangles(
        vec![[90.0, 0.0, 0.0], [91.0, 0.0, 0.0], [90.0, 1.0, 0.0], [90.0, 0.0, 1.0]],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
    .unwrap();
    let cube = cuboid([0.0; 3], [1.0; 3]).triangulated();
    let mut faces: Vec<Vec<u32>> = (0..cube.face_count()).map(|f| cube.face(f).to_vec()).collect();
    faces.push(faces[3].clone()); // a duplicate face, dropped
    let mut p = cube.positions().to_vec();
    p.push([5.0, 5.0, 5.0]); // a vertex no face uses
    let surfaces = [
        ("sphere", uv_sphere(1.0, 24, 12)),
        ("torus", torus(3.0, 1.0, 24, 12)),
        ("open box", without_face(&cuboid([0.0; 3], [1.0; 3]), 2)),
        ("Möbius strip", mobius(12, 0.0)),
        (
            "cube, duplicate face, unused vertex",
            Mesh::from_polygons(p, faces.iter().map(|f| &f[..])).unwrap(),
        ),
    ];
    for (name, mesh) in surfaces {
        let alone = checked(&mesh);
        assert_eq!(alone.shells.len(), 1, "{name}");
        let beside = checked(&Mesh::concatenate(&[mesh, tetra.clone()]));
        assert_eq!(beside.shells.len(), 2, "{name}");
        let (a, b) = (&alone.shells[0], &beside.shells[0]);
        assert_eq!(
            (a.faces, a.euler_characteristic, a.genus, a.closed, a.orientable),
            (b.faces, b.euler_characteristic, b.genus, b.closed, b.orientable),
            "{name}"
        );
        // The tetrahedron's own: χ = 4 − 6 + 4.
        assert_eq!((beside.shells[1].faces, beside.shells[1].euler_characteristic), (4, 2));
        assert_eq!(alone.euler_characteristic, a.euler_characteristic, "{name}");
    }
}
