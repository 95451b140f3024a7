//! The interface of two overlapping bodies (`Intersection::contact`): its area against
//! faces measured by hand (boxes, in any orientation), the spheres' lens against its
//! spherical caps, a sphere's vertical band on a slab (turned frames on a strip of
//! columns) against its faces measured one by one, and its vector against the
//! derivative of the overlap volume taken by finite differences of the volume (a second
//! computation); with ∫ n dA over ∂A ∩ B the opposite of that over ∂B ∩ A, since ∂(A∩B)
//! is closed.

mod common;

use common::{mapped, moved, XorShift};

use meshvol::grid::{intersection, Contact};
use meshvol::shapes::{cuboid, uv_sphere};
use meshvol::Mesh;

fn contact(a: &Mesh, b: &Mesh) -> Contact {
    intersection(a, b, 1e-9).unwrap().contact.expect("a contact")
}

fn close(got: [f64; 3], want: [f64; 3], tolerance: f64, what: &str) {
    for k in 0..3 {
        assert!((got[k] - want[k]).abs() <= tolerance, "{what}: {got:?} vs {want:?}");
    }
}

/// A rotation by the unit quaternion `q`.
fn rotation(q: [f64; 4]) -> [[f64; 3]; 3] {
    let [w, x, y, z] = q;
    [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
        [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
    ]
}

fn random_rotation(rng: &mut XorShift) -> [[f64; 3]; 3] {
    let q = [0; 4].map(|_| rng.unit() * 2.0 - 1.0);
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    rotation(q.map(|x| x / n))
}

fn apply(r: &[[f64; 3]; 3], p: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2])
}

#[test]
fn two_boxes_touch_along_the_faces_each_has_inside_the_other() {
    // Unit cubes, B shifted by (1/2, 1/4, 1/8): the overlap is (1/2)(3/4)(7/8). Inside B
    // lie A's faces x = 1 (3/4 × 7/8), y = 1 (1/2 × 7/8) and z = 1 (1/2 × 3/4); B's faces
    // x = 1/2, y = 1/4, z = 1/8 inside A have the same areas, normals −x, −y, −z.
    let a = cuboid([0.0; 3], [1.0; 3]);
    let shift = [0.5, 0.25, 0.125];
    let faces = [0.75 * 0.875, 0.5 * 0.875, 0.5 * 0.75];
    let b = moved(&a, shift);
    let c = contact(&a, &b);
    assert!((c.area - 2.0 * faces.iter().sum::<f64>()).abs() < 1e-12, "{}", c.area);
    close(c.vector, faces.map(|f| -f), 1e-12, "∂B ∩ A");
    close(c.vector_a, faces, 1e-12, "∂A ∩ B");
    // d|A∩B|/dt_x = d/dt (1/2 − t)(3/4)(7/8) = −(3/4)(7/8): the x component.
    // The same boxes turned any way: the area stays, the vectors turn with them.
    // Turns by small angles about x make walls steep: 10⁻⁴ (counted in a turned frame)
    // and 10⁻² (in the plan pass, its plan area magnified a hundredfold).
    let about_x = |angle: f64| rotation([(angle / 2.0).cos(), (angle / 2.0).sin(), 0.0, 0.0]);
    let mut rng = XorShift::new(11);
    let turns = [about_x(1e-4), about_x(1e-2)];
    for r in turns.into_iter().chain((0..4).map(|_| random_rotation(&mut rng))) {
        let turn = |m: &Mesh| mapped(m, |p| apply(&r, p));
        let t = contact(&turn(&a), &turn(&b));
        assert!((t.area - c.area).abs() < 1e-9, "turned: {}", t.area);
        close(t.vector, apply(&r, c.vector), 1e-9, "turned ∂B ∩ A");
        close(t.vector_a, apply(&r, c.vector_a), 1e-9, "turned ∂A ∩ B");
    }
}

#[test]
fn faces_the_boxes_share_the_same_way_round_are_not_an_interface() {
    // Shifted in x and y only: the tops and bottoms lie on each other, outside both.
    let a = cuboid([0.0; 3], [1.0; 3]);
    let c = contact(&a, &moved(&a, [0.5, 0.25, 0.0]));
    assert!((c.area - 2.0 * (0.75 + 0.5)).abs() < 1e-12, "{}", c.area);
    close(c.vector, [-0.75, -0.5, 0.0], 1e-12, "∂B ∩ A");
}

#[test]
fn a_body_inside_another_touches_it_all_over_with_no_net_normal() {
    let outer = cuboid([-2.0; 3], [2.0; 3]);
    let inner = uv_sphere(1.0, 32, 16);
    let c = contact(&outer, &inner);
    let area: f64 = meshvol::mass_properties(&inner).area;
    assert!((c.area - area).abs() < 1e-9 * area, "{} vs {area}", c.area);
    close(c.vector, [0.0; 3], 1e-9, "closed surface");
    // The direction of what rounding leaves of cancelling normals is no normal.
    assert_eq!(c.normal(), None, "{:?}", c.vector);
    // Nor the other way round, the cube seen from the sphere: it touches nothing of
    // the cube's surface (no interface on A's side reaches B).
    assert_eq!(contact(&inner, &outer).normal(), None);
}

#[test]
fn bodies_apart_have_no_interface() {
    let a = cuboid([0.0; 3], [1.0; 3]);
    for shift in [[3.0, 0.0, 0.0], [1.0, 0.0, 0.0]] {
        let c = contact(&a, &moved(&a, shift));
        assert_eq!((c.area, c.vector), (0.0, [0.0; 3]), "{shift:?}");
        assert_eq!(c.normal(), None);
    }
}

#[test]
fn the_lens_of_two_spheres_is_bounded_by_two_caps() {
    // Radius 1, centres 1 apart along (0.6, 0, 0.8): each cap has height h = 1/2 and base
    // radius a = √3/2; area 2πh each, vector area πa² along the axis. The polyhedra are
    // within 2e-3 of the smooth values at 256 × 128.
    let a = uv_sphere(1.0, 256, 128);
    let axis = [0.6, 0.0, 0.8];
    let b = moved(&a, axis);
    let c = contact(&a, &b);
    let pi = std::f64::consts::PI;
    let area = 2.0 * 2.0 * pi * 0.5;
    assert!((c.area - area).abs() < 2e-3 * area, "{} vs {area}", c.area);
    let lens = pi * 0.75;
    close(c.vector, axis.map(|x| -x * lens), 2e-3 * lens, "B's cap faces back into A");
    let n = c.normal().unwrap();
    close(n, axis.map(|x| -x), 1e-3, "normal");
}

#[test]
fn the_contact_vector_is_the_derivative_of_the_overlap() {
    // A sphere and a turned box in general position: (|A∩(B+δe)| − |A∩(B−δe)|)/2δ for
    // each axis e. The overlap is a smooth piecewise cubic in the shift, so the central
    // difference is within O(δ²) of the derivative.
    let mut rng = XorShift::new(5);
    let sphere = uv_sphere(1.0, 48, 24);
    for round in 0..3 {
        let r = random_rotation(&mut rng);
        let offset = [0; 3].map(|_| rng.unit() - 0.5);
        let block = mapped(&cuboid([-0.7, -0.4, -0.9], [0.5, 0.6, 0.3]), |p| {
            let q = apply(&r, p);
            [q[0] + offset[0] + 0.6, q[1] + offset[1], q[2] + offset[2]]
        });
        let c = contact(&sphere, &block);
        let delta = 1e-4;
        let derivative = [0, 1, 2].map(|k| {
            let mut d = [0.0; 3];
            d[k] = delta;
            let plus = intersection(&sphere, &moved(&block, d), 1e-12).unwrap().volume();
            d[k] = -delta;
            let minus = intersection(&sphere, &moved(&block, d), 1e-12).unwrap().volume();
            (plus - minus) / (2.0 * delta)
        });
        let size = c.vector.iter().map(|x| x.abs()).fold(0.0, f64::max);
        close(c.vector, derivative, 1e-4 * size.max(1e-3), &format!("round {round}"));
        // ∂(A∩B) is closed: ∫ n dA over ∂A ∩ B is the opposite.
        close(c.vector_a, c.vector.map(|x| -x), 1e-9 * c.area, &format!("round {round}"));
    }
}

#[test]
fn level_faces_far_inside_the_common_box_are_counted_in_their_columns() {
    // A sphere with an odd number of rings has a band of vertical faces across z = 0,
    // counted in the turned frames only: on a slab holding z < 0, those frames' grids
    // are thin strips of the common box's columns (the slab's own walls lie outside
    // it). ∂B ∩ A is the lower half of the sphere's faces, measured here face by face;
    // ∂A ∩ B is the slab's top inside the sphere, the regular 48-gon of the band's
    // radius, facing up; the lower half's vector area closes that 48-gon: −its area ẑ.
    let (segments, rings) = (48, 25);
    let b = uv_sphere(1.0, segments, rings);
    let a = cuboid([-2.0, -2.0, -1.5], [2.0, 2.0, 0.0]);
    let p = b.positions();
    let mut lower_half = 0.0;
    for f in 0..b.face_count() {
        let face = b.face(f);
        let corners: Vec<[f64; 3]> = face.iter().map(|&v| p[v as usize]).collect();
        let mut area = [0.0; 3];
        for k in 1..corners.len() - 1 {
            let (u, v) = (sub(corners[k], corners[0]), sub(corners[k + 1], corners[0]));
            let n =
                [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
            (0..3).for_each(|j| area[j] += 0.5 * n[j]);
        }
        let area = area.iter().map(|x| x * x).sum::<f64>().sqrt();
        let (low, high) = corners
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), c| (l.min(c[2]), h.max(c[2])));
        // The band's faces are rectangles across z = 0: the part below is in proportion.
        lower_half += if high <= 0.0 {
            area
        } else if low < 0.0 {
            area * -low / (high - low)
        } else {
            0.0
        };
    }
    let pi = std::f64::consts::PI;
    let radius = (pi * 12.0 / 25.0).sin();
    let polygon = 0.5 * segments as f64 * radius * radius * (2.0 * pi / segments as f64).sin();
    let i = intersection(&a, &b, 1e-9).unwrap();
    let c = i.contact.expect("a contact");
    let want = lower_half + polygon;
    assert!((c.area - want).abs() < 1e-9 * want, "{} vs {want}", c.area);
    close(c.vector, [0.0, 0.0, -polygon], 1e-9, "B's lower half faces down");
    close(c.vector_a, [0.0, 0.0, polygon], 1e-9, "the slab's top faces up");
    // By the sphere's symmetry about z = 0, the overlap is half its volume.
    let half = 0.5 * meshvol::shapes::uv_sphere_volume(1.0, segments, rings);
    assert!(i.lower - 1e-12 <= half && half <= i.upper + 1e-12, "{half} in {i:?}");
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
