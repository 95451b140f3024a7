//! The hull checked against its definition (exact predicates, independent of the
//! algorithm), a brute-force hull, and closed-form polyhedra.

use super::{convex_hull, Degeneracy, Hull};
use crate::test_rng::XorShift;
use crate::vector::orient3d;
use crate::Point;

/// A point uniformly in the unit ball, by rejection from the cube.
fn in_ball(rng: &mut XorShift) -> Point {
    loop {
        let p = [0.0; 3].map(|_: f64| 2.0 * rng.unit() - 1.0);
        if p.iter().map(|x| x * x).sum::<f64>() <= 1.0 {
            return p;
        }
    }
}

/// A point on the unit sphere (rounded onto it).
fn on_sphere(rng: &mut XorShift) -> Point {
    loop {
        let p = in_ball(rng);
        let r = p.iter().map(|x| x * x).sum::<f64>().sqrt();
        if r > 0.1 {
            return p.map(|x| x / r);
        }
    }
}

fn triangles(hull: &Hull) -> (Vec<Point>, Vec<[u32; 3]>) {
    let mesh = hull.mesh.as_ref().expect("a solid hull");
    let triangles = (0..mesh.face_count())
        .map(|f| <[u32; 3]>::try_from(mesh.face(f)).expect("triangles"))
        .collect();
    (mesh.positions().to_vec(), triangles)
}

/// The definition of a convex hull, checked exactly: the mesh is a closed 2-manifold of
/// genus 0 wound outward, its vertices are input points, and no input point is outside
/// any face's plane. With `strict`, neighbouring faces also turn strictly (points in
/// general position have no coplanar neighbours).
fn check_hull(points: &[Point], hull: &Hull, strict: bool) {
    let (positions, triangles) = triangles(hull);
    let inputs: std::collections::HashSet<[u64; 3]> =
        points.iter().map(|p| p.map(f64::to_bits)).collect();
    assert!(positions.iter().all(|p| inputs.contains(&p.map(f64::to_bits))));
    let mut edges = std::collections::HashMap::new();
    for (f, t) in triangles.iter().enumerate() {
        for i in 0..3 {
            let previous = edges.insert((t[i], t[(i + 1) % 3]), f);
            assert!(previous.is_none(), "edge {:?} used twice in one direction", t);
        }
        let [a, b, c] = t.map(|v| positions[v as usize]);
        for &q in points {
            assert!(orient3d(a, b, c, q) >= 0.0, "{q:?} is outside face {t:?}");
        }
    }
    for (&(u, w), &f) in &edges {
        let g = edges[&(w, u)];
        let [a, b, c] = triangles[f].map(|v| positions[v as usize]);
        let opposite = triangles[g].iter().find(|&&v| v != u && v != w).unwrap();
        let turn = orient3d(a, b, c, positions[*opposite as usize]);
        assert!(if strict { turn > 0.0 } else { turn >= 0.0 }, "faces {f} and {g} fold");
    }
    let (v, e, f) = (positions.len() as i64, edges.len() as i64 / 2, triangles.len() as i64);
    assert_eq!(v - e + f, 2, "Euler characteristic");
    assert!(hull.volume() > 0.0 && hull.properties.signed_volume > 0.0);
}

/// The hull's outward faces by brute force, for points in general position: the
/// triples with every other point strictly on one side.
fn brute_force_faces(points: &[Point]) -> Vec<[usize; 3]> {
    let n = points.len();
    let mut faces = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let sides: Vec<f64> = (0..n)
                    .filter(|&q| q != i && q != j && q != k)
                    .map(|q| orient3d(points[i], points[j], points[k], points[q]))
                    .collect();
                if sides.iter().all(|&s| s > 0.0) {
                    faces.push([i, j, k]);
                } else if sides.iter().all(|&s| s < 0.0) {
                    faces.push([i, k, j]);
                }
            }
        }
    }
    faces
}

fn volume_of(points: &[Point], faces: &[[usize; 3]]) -> f64 {
    let o = points[0];
    faces
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| crate::vector::sub(points[v], o));
            crate::vector::dot(a, crate::vector::cross(b, c)) / 6.0
        })
        .sum()
}

#[test]
fn random_clouds_are_hulled_exactly() {
    let mut rng = XorShift::new(0x5eed_0f4a);
    let cube = |rng: &mut XorShift| [0.0; 3].map(|_: f64| rng.unit());
    let generators: [fn(&mut XorShift) -> Point; 3] = [in_ball, on_sphere, cube];
    for generate in generators {
        for n in [4, 5, 10, 100, 3000] {
            let points: Vec<Point> = (0..n).map(|_| generate(&mut rng)).collect();
            let hull = convex_hull(&points).unwrap();
            check_hull(&points, &hull, true);
        }
    }
}

#[test]
fn small_clouds_match_a_brute_force_hull() {
    let mut rng = XorShift::new(0xb0b_cafe);
    for round in 0..20 {
        let points: Vec<Point> = (0..10 + 2 * round)
            .map(|_| if round % 2 == 0 { in_ball(&mut rng) } else { on_sphere(&mut rng) })
            .collect();
        let hull = convex_hull(&points).unwrap();
        let expected = brute_force_faces(&points);
        // Same faces (as sets of vertices) and the same volume.
        let (positions, triangles) = triangles(&hull);
        let index = |p: Point| points.iter().position(|&q| q == p).unwrap();
        let mut ours: Vec<Vec<usize>> = triangles
            .iter()
            .map(|t| {
                let mut t = t.map(|v| index(positions[v as usize])).to_vec();
                t.sort();
                t
            })
            .collect();
        let mut theirs: Vec<Vec<usize>> = expected
            .iter()
            .map(|t| {
                let mut t = t.to_vec();
                t.sort();
                t
            })
            .collect();
        ours.sort();
        theirs.sort();
        assert_eq!(ours, theirs, "round {round}");
        let volume = volume_of(&points, &expected);
        assert!((hull.volume() - volume).abs() <= 1e-13 * volume, "round {round}");
    }
}

#[test]
fn platonic_solids_with_points_inside_have_their_closed_form_volume() {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let cube: Vec<Point> =
        (0..8).map(|i| [0, 1, 2].map(|k| if i >> k & 1 == 1 { 1.0 } else { -1.0 })).collect();
    let octahedron: Vec<Point> = (0..6)
        .map(|i| {
            let mut p = [0.0; 3];
            p[i % 3] = if i < 3 { 1.0 } else { -1.0 };
            p
        })
        .collect();
    let mut icosahedron = Vec::new();
    for s in [-1.0, 1.0] {
        for t in [-phi, phi] {
            icosahedron.extend([[0.0, s, t], [s, t, 0.0], [t, 0.0, s]]);
        }
    }
    // Edge 2: the icosahedron's volume is 5(3 + √5)/12 · 2³.
    let cases = [
        (cube, 8.0, 8),
        (octahedron, 4.0 / 3.0, 6),
        (icosahedron, 10.0 * (3.0 + 5f64.sqrt()) / 3.0, 12),
    ];
    let mut rng = XorShift::new(0x1c05a);
    for (corners, volume, count) in cases {
        let mut points = corners.clone();
        // Points well inside (the inscribed ball of each has radius above 0.5).
        points.extend((0..500).map(|_| in_ball(&mut rng).map(|x| 0.5 * x)));
        points.extend(corners.iter().rev());
        let hull = convex_hull(&points).unwrap();
        check_hull(&points, &hull, false);
        assert!((hull.volume() - volume).abs() <= 1e-14 * volume, "{}", hull.volume());
        assert_eq!(hull.mesh.unwrap().vertex_count(), count);
    }
}

#[test]
fn points_on_a_sphere_approach_its_volume() {
    let mut rng = XorShift::new(0x5f3759df);
    let ball = 4.0 / 3.0 * std::f64::consts::PI;
    let mut previous = f64::INFINITY;
    for n in [1000, 10_000, 100_000] {
        let points: Vec<Point> = (0..n).map(|_| on_sphere(&mut rng)).collect();
        let deficit = ball - convex_hull(&points).unwrap().volume();
        // An inscribed polytope misses the caps beyond its faces, fewer and thinner the
        // more vertices it has.
        assert!(deficit > 0.0 && deficit < previous, "n = {n}: {deficit}");
        previous = deficit;
    }
    assert!(previous < 1e-3, "{previous}");
}

#[test]
fn lattice_polytopes_have_only_their_corners_as_vertices() {
    // An 11³ integer grid: the cube [0, 10]³, with 11² points on each face.
    let grid: Vec<Point> =
        (0..11 * 11 * 11).map(|i| [i % 11, i / 11 % 11, i / 121].map(|x| x as f64)).collect();
    let hull = convex_hull(&grid).unwrap();
    check_hull(&grid, &hull, false);
    assert_eq!(hull.volume(), 1000.0);
    assert_eq!(hull.mesh.as_ref().unwrap().vertex_count(), 8);
    assert_eq!(hull.mesh.unwrap().face_count(), 12);
    // The lattice points of the octahedron |x| + |y| + |z| ≤ 6, each three times.
    let mut octahedron = Vec::new();
    for _ in 0..3 {
        for i in 0..13 * 13 * 13 {
            let p = [i % 13, i / 13 % 13, i / 169].map(|x| x as f64 - 6.0);
            if p.iter().map(|x| x.abs()).sum::<f64>() <= 6.0 {
                octahedron.push(p);
            }
        }
    }
    let hull = convex_hull(&octahedron).unwrap();
    check_hull(&octahedron, &hull, false);
    assert_eq!(hull.volume(), 4.0 / 3.0 * 216.0);
    assert_eq!(hull.mesh.unwrap().vertex_count(), 6);
}

#[test]
fn duplicates_and_cospherical_points_change_nothing() {
    // Integer points on the sphere x² + y² + z² = 25 (many cospherical and coplanar
    // quadruples), each twice.
    let mut points = Vec::new();
    for i in 0..11 * 11 * 11 {
        let p = [i % 11, i / 11 % 11, i / 121].map(|x| x as f64 - 5.0);
        if p.iter().map(|x| x * x).sum::<f64>() == 25.0 {
            points.push(p);
            points.push(p);
        }
    }
    let hull = convex_hull(&points).unwrap();
    check_hull(&points, &hull, false);
    // Every one of these points is a corner: none is inside the hull of the others.
    assert_eq!(hull.mesh.unwrap().vertex_count(), points.len() / 2);
    let degenerate = convex_hull(&vec![[1.0, 2.0, 3.0]; 10]).unwrap();
    assert_eq!(degenerate.degeneracy, Some(Degeneracy::AllCoincide));
}

#[test]
fn the_hull_is_the_same_on_any_number_of_threads() {
    let mut rng = XorShift::new(0x7_7777);
    let points: Vec<Point> = (0..200_000).map(|_| on_sphere(&mut rng)).collect();
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let hull = pool.install(|| convex_hull(&points).unwrap());
        (triangles(&hull), hull.volume().to_bits())
    };
    assert_eq!(on(1), on(3));
}

#[test]
fn chunked_hulls_keep_every_corner() {
    // Two chunks' worth of points in a ball, then four chunks' worth of lattice points in
    // file order (128 × 128 at each of four heights, inside the ball): runs of
    // consecutive points would be flat slabs, every point kept.
    let mut rng = XorShift::new(0xc4a2_4c5d);
    let mut points: Vec<Point> = (0..2 * super::CHUNK_POINTS).map(|_| in_ball(&mut rng)).collect();
    for z in [-0.2, 0.0, 0.2, 0.4] {
        points.extend(
            (0..128 * 128).map(|i| [(i % 128) as f64 / 254.0, (i / 128) as f64 / 254.0, z]),
        );
    }
    let kept = super::candidates(&points, &()).expect("chunks pay for points in a ball");
    // Every chunk is spread over the whole cloud: each keeps its corners only (the
    // lattice layers are inside the ball), in all far fewer than one chunk's points.
    assert!(kept.len() < super::CHUNK_POINTS / 2, "{}", kept.len());
    assert!(kept.windows(2).all(|w| w[0] < w[1]), "kept in increasing order, once each");
    let hull = convex_hull(&points).unwrap();
    let direct = super::incremental::hull_triangles(&points, &());
    let corners = |triangles: Vec<[u32; 3]>| {
        let mut v: Vec<u32> = triangles.into_iter().flatten().collect();
        v.sort();
        v.dedup();
        v.into_iter().map(|i| points[i as usize]).collect::<Vec<Point>>()
    };
    let mut ours = hull.mesh.as_ref().unwrap().positions().to_vec();
    ours.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut expected = corners(direct);
    expected.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(ours, expected);
    // Points on a sphere keep most of the first chunk: no chunks.
    let sphere: Vec<Point> = (0..5 * super::CHUNK_POINTS).map(|_| on_sphere(&mut rng)).collect();
    assert!(super::candidates(&sphere, &()).is_none());
}

#[test]
fn progress_counts_the_points_in_each_stage() {
    // A ball big enough to be hulled in chunks first: each stage's count grows to its
    // total, and the hull is the one without a hook.
    let mut rng = XorShift::new(41);
    let ball: Vec<Point> = (0..5 * super::CHUNK_POINTS).map(|_| in_ball(&mut rng)).collect();
    let record = crate::progress::testing::Record::default();
    let hull = super::convex_hull_with(&ball, &record).unwrap();
    assert_eq!(hull.volume(), convex_hull(&ball).unwrap().volume());
    let stages = record.counted_stages();
    assert_eq!(stages[..2], ["hulling chunks of points", "inserting points"], "{stages:?}");
}
