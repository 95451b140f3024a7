//! The boundary method against closed forms and against the grid method, an
//! independent algorithm (column pieces, not faces' regions).

use super::*;
use crate::grid::intersection;
use crate::shapes::{cuboid, torus, uv_sphere};
use crate::surface::Moved;
use crate::test_rng::XorShift;
use crate::Mesh;

fn turn_about_z(angle: f64, shift: Point) -> Affine {
    let (s, c) = angle.sin_cos();
    Affine([[c, -s, 0.0, shift[0]], [s, c, 0.0, shift[1]], [0.0, 0.0, 1.0, shift[2]]])
}

/// A rotation from a random unit quaternion and a shift within `reach` of the origin.
fn random_pose(rng: &mut XorShift, reach: f64) -> Affine {
    let mut q = [0.0; 4];
    for x in &mut q {
        *x = 2.0 * rng.unit() - 1.0;
    }
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|v| v / n);
    let r = [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
        [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
    ];
    let t = [0, 1, 2].map(|_| reach * (2.0 * rng.unit() - 1.0));
    Affine([0, 1, 2].map(|i| [r[i][0], r[i][1], r[i][2], t[i]]))
}

#[test]
fn offset_boxes_overlap_in_the_box_between_them() {
    // [0, 2]³ ∩ [0.7, 2.9] × [0.4, 2.3] × [1.1, 3.2] = 1.3 × 1.6 × 0.9, centre known.
    let a = Body::new(&cuboid([0.0; 3], [2.0; 3]));
    let b = Body::new(&cuboid([0.7, 0.4, 1.1], [2.9, 2.3, 3.2]));
    let o = overlap(&a, None, &b, None).unwrap();
    let exact = 1.3 * 1.6 * 0.9;
    assert!((o.volume - exact).abs() <= o.error, "{} vs {exact} ± {}", o.volume, o.error);
    assert!(o.error < 1e-12, "{}", o.error);
    let c = o.centroid.unwrap();
    for (k, want) in [1.35, 1.2, 1.55].iter().enumerate() {
        assert!((c[k] - want).abs() < 1e-13, "{c:?}");
    }
    // Box inertia about its centre: m(b² + c²)/12 and so on.
    let (x, y, z) = (1.3f64, 1.6f64, 0.9f64);
    let i = o.inertia.unwrap();
    assert!((i[0][0] - exact * (y * y + z * z) / 12.0).abs() < 1e-13, "{i:?}");
    assert!((i[2][2] - exact * (x * x + y * y) / 12.0).abs() < 1e-13, "{i:?}");
    assert!(i[0][1].abs() < 1e-13);
    // Interface: A's faces inside B are its x = 2, y = 2 and z = 2 faces' parts, B's
    // inside A its x = 0.7, y = 0.4, z = 1.1 faces' parts.
    let area = 2.0 * (y * z + x * z + x * y);
    assert!((o.contact_area - area).abs() < 1e-13, "{}", o.contact_area);
    // ∫ n dA over ∂B inside A: B's faces there look in −x, −y, −z.
    let want = [-y * z, -x * z, -x * y];
    for k in 0..3 {
        assert!((o.contact_vector[k] - want[k]).abs() < 1e-13, "{:?}", o.contact_vector);
        assert!((o.contact_vector_a[k] + want[k]).abs() < 1e-13);
    }
}

#[test]
fn a_box_turned_about_z_inside_a_taller_box_is_a_square_turned_in_a_square() {
    // A 2×2×1 slab turned by θ about z (centred) cut by the 2×2×3 column it sits in:
    // in plan, two congruent squares turned by θ share an octagon of area
    // 4 − 4·(corner triangles); each corner triangle is cut off by the turned side.
    let angle: f64 = 0.3;
    let a = Body::new(&cuboid([-1.0, -1.0, -1.5], [1.0, 1.0, 1.5]));
    let b = Body::new(&cuboid([-1.0, -1.0, -0.5], [1.0, 1.0, 0.5]));
    let o = overlap(&a, None, &b, Some(turn_about_z(angle, [0.0; 3]))).unwrap();
    // The octagon: side 2 squares turned by θ: overlap area = 4 − 4·t(θ) with the
    // corner triangle's legs a = (1 − cos θ... ) solved from the geometry below.
    let (s, c) = angle.sin_cos();
    // A corner of the fixed square outside the turned one is a right triangle with
    // legs p and q where p + q + √(p² + q²) = 2 and q/p = tan θ... its legs are
    // p = 2 / (1 + tan θ + sec θ)·1 and q = p tan θ.
    let p = 2.0 / (1.0 + s / c + 1.0 / c);
    let q = p * s / c;
    let area = 4.0 - 4.0 * 0.5 * p * q;
    assert!((o.volume - area).abs() <= o.error + 1e-14, "{} vs {area}", o.volume);
}

#[test]
fn a_body_wholly_inside_another_is_found_by_a_ray() {
    let a = Body::new(&uv_sphere(1.0, 24, 12));
    let b = Body::new(&cuboid([-0.3, -0.2, -0.25], [0.2, 0.3, 0.35]));
    let o = overlap(&a, None, &b, None).unwrap();
    assert!((o.volume - 0.15).abs() <= o.error + 1e-16, "{} ± {}", o.volume, o.error);
    // Wholly inside: the interface is all of B, with no net normal.
    assert!((o.contact_area - 2.0 * (0.25 + 0.3 + 0.3)).abs() < 1e-14);
    assert!(o.contact_vector.iter().all(|x| x.abs() < 1e-14));
    // And the other way round.
    let o = overlap(&b, None, &a, None).unwrap();
    assert!((o.volume - 0.15).abs() <= o.error + 1e-15);
}

#[test]
fn bodies_apart_share_nothing() {
    let a = Body::new(&cuboid([0.0; 3], [1.0; 3]));
    let b = Body::new(&cuboid([2.0; 3], [3.0; 3]));
    let o = overlap(&a, None, &b, None).unwrap();
    assert_eq!((o.volume, o.contact_area, o.centroid), (0.0, 0.0, None));
}

#[test]
fn coincident_faces_are_left_to_the_grid() {
    let a = Body::new(&cuboid([0.0; 3], [1.0; 3]));
    let b = Body::new(&cuboid([0.5, 0.0, 0.0], [1.5, 1.0, 1.0]));
    assert_eq!(overlap(&a, None, &b, None), Err(Degenerate::Coplanar));
}

#[test]
fn an_open_surface_is_unfit() {
    let m = cuboid([0.0; 3], [1.0; 3]).triangulated();
    let crate::Faces::Triangles(t) = m.faces() else { unreachable!() };
    let m = Mesh::from_triangles(m.positions().to_vec(), t[1..].to_vec()).unwrap();
    let body = Body::new(&m);
    assert!(body.unfit().is_some());
    assert_eq!(overlap(&body, None, &body, None), Err(Degenerate::Unfit));
}

/// The grid method's interval and moments for the same placed bodies.
fn by_grid(a: &Mesh, pa: Affine, b: &Mesh, pb: Affine) -> crate::grid::Intersection {
    intersection(&Moved::new(a, Some(pa)), &Moved::new(b, Some(pb)), 1e-10).unwrap()
}

#[test]
fn random_poses_agree_with_the_grid_method() {
    let shapes = [uv_sphere(1.0, 32, 16), torus(1.0, 0.4, 32, 16), cuboid([-0.7; 3], [0.6; 3])];
    let bodies: Vec<Body> = shapes.iter().map(Body::new).collect();
    let mut rng = XorShift::new(7);
    let mut compared = 0;
    for n in 0..24 {
        let (i, j) = (n % 3, (n / 3) % 3);
        let (pa, pb) = (random_pose(&mut rng, 0.5), random_pose(&mut rng, 0.5));
        let o = overlap(&bodies[i], Some(pa), &bodies[j], Some(pb)).unwrap();
        let g = by_grid(&shapes[i], pa, &shapes[j], pb);
        assert!(o.error < 1e-10 * o.volume.max(1e-3), "{} ± {}", o.volume, o.error);
        // The two intervals hold the same exact number: they must meet.
        assert!(
            o.volume - o.error <= g.upper && g.lower <= o.volume + o.error,
            "pose {n}: {} ± {} vs [{}, {}]",
            o.volume,
            o.error,
            g.lower,
            g.upper
        );
        if let (Some(m), Some(c)) = (g.moments, o.centroid) {
            for k in 0..3 {
                assert!((m.centroid[k] - c[k]).abs() < 1e-9, "{:?} vs {c:?}", m.centroid);
                for l in 0..3 {
                    let i = o.inertia.unwrap()[k][l];
                    assert!((m.inertia[k][l] - i).abs() < 1e-9 * (1.0 + i.abs()), "{k}{l}");
                }
            }
            compared += 1;
        }
        if let Some(contact) = g.contact {
            assert!((contact.area - o.contact_area).abs() < 1e-8 * (1.0 + o.contact_area));
            for k in 0..3 {
                assert!((contact.vector[k] - o.contact_vector[k]).abs() < 1e-8);
            }
        }
    }
    assert!(compared >= 16, "{compared}");
}

#[test]
fn the_same_bits_at_any_thread_count_and_face_order() {
    let mesh = uv_sphere(1.0, 96, 48).triangulated();
    let a = Body::new(&mesh);
    let pose = turn_about_z(0.2, [0.6, 0.3, 0.1]);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| overlap(&a, None, &a, Some(pose)).unwrap())
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(5));
    // Faces listed backwards and each turned to start at another corner: the same body.
    let crate::Faces::Triangles(t) = mesh.faces() else { unreachable!() };
    let mut t = t.clone();
    t.reverse();
    for f in t.iter_mut() {
        f.rotate_left(1);
    }
    let shuffled = Mesh::from_triangles(mesh.positions().to_vec(), t).unwrap();
    let b = Body::new(&shuffled);
    let other = overlap(&b, None, &b, Some(pose)).unwrap();
    assert!((other.volume - one.volume).abs() <= one.error + other.error);
}
