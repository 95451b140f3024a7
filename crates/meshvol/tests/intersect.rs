//! The intersection's interval is certified: it holds volumes computed by hand (boxes,
//! a cube turned 45° against a cube, exact polygon areas × heights), the part of a
//! sphere below a plane found by `below` (a second algorithm), and the lens of two
//! spheres; and it keeps the identities of sets under swaps, shuffles and exact motions.

mod common;

use common::{mapped, moved, polygons, XorShift};

use meshvol::below::below;
use meshvol::grid::{intersection, overlapping_boxes, Intersection};
use meshvol::section::Plane;
use meshvol::shapes::{cuboid, uv_sphere};
use meshvol::MassProperties;
use meshvol::{mass_properties, Mesh};

/// Asserts that `i` holds `exact` and is at most `width` wide relative to it (absolute
/// where `exact` is 0).
fn holds(i: &Intersection, exact: f64, width: f64, what: &str) {
    let scale = exact.abs().max(1.0);
    assert!(
        i.lower <= exact && exact <= i.upper,
        "{what}: [{}, {}] misses {exact}",
        i.lower,
        i.upper
    );
    assert!(i.upper - i.lower <= width * scale, "{what}: width {}", i.upper - i.lower);
    assert_eq!(i.columns_unresolved, 0, "{what}");
}

/// Asserts that the intersection's moments are those of `truth` within 1e-9 relative
/// (the centroid relative to the body's size `size`).
fn same_moments(i: &Intersection, truth: &MassProperties, size: f64, what: &str) {
    let m = i.moments.unwrap_or_else(|| panic!("{what}: no moments"));
    assert!((m.volume - truth.signed_volume).abs() <= 1e-9 * truth.signed_volume, "{what}");
    let c = truth.centroid.unwrap();
    for a in 0..3 {
        assert!((m.centroid[a] - c[a]).abs() <= 1e-9 * size, "{what}: {:?} vs {c:?}", m.centroid);
    }
    let largest = (0..3).map(|a| truth.inertia[a][a]).fold(0.0, f64::max);
    for r in 0..3 {
        for k in 0..3 {
            let (got, want) = (m.inertia[r][k], truth.inertia[r][k]);
            assert!(
                (got - want).abs() <= 1e-9 * largest,
                "{what}: {:?} vs {:?}",
                m.inertia,
                truth.inertia
            );
        }
    }
}

/// The prism over the convex polygon `ring` (xy, counter-clockwise) from z0 to z1.
fn prism(ring: &[[f64; 2]], z0: f64, z1: f64) -> Mesh {
    let m = ring.len() as u32;
    let mut p: Vec<[f64; 3]> = ring.iter().map(|q| [q[0], q[1], z0]).collect();
    p.extend(ring.iter().map(|q| [q[0], q[1], z1]));
    let mut faces = vec![(0..m).rev().collect::<Vec<u32>>(), (m..2 * m).collect()];
    for k in 0..m {
        let n = (k + 1) % m;
        faces.push(vec![k, n, m + n, m + k]);
    }
    polygons(&p, &faces)
}

/// The square |x| + |y| ≤ r: a cube's cross-section turned 45° about z.
fn diamond(r: f64) -> Vec<[f64; 2]> {
    vec![[r, 0.0], [0.0, r], [-r, 0.0], [0.0, -r]]
}

#[test]
fn boxes_overlap_by_the_product_of_their_overlaps() {
    let a = cuboid([0.1, -0.3, 0.25], [2.7, 1.9, 1.5]);
    let b = cuboid([1.3, 0.7, -1.0], [4.0, 1.45, 0.875]);
    let exact = (2.7 - 1.3) * (1.45 - 0.7) * (0.875 - 0.25);
    let i = intersection(&a, &b, 1e-9).unwrap();
    holds(&i, exact, 1e-9, "box ∩ box");
    let common = mass_properties(&cuboid([1.3, 0.7, 0.25], [2.7, 1.45, 0.875]));
    same_moments(&i, &common, 2.7, "box ∩ box");
    let (va, vb) = (2.6 * 2.2 * 1.25, 2.7 * 0.75 * 1.875);
    let a_minus_b = i.a_minus_b();
    assert!(a_minus_b.lower <= va - exact && va - exact <= a_minus_b.upper);
    let iou = i.iou();
    let truth = exact / (va + vb - exact);
    assert!(iou.lower <= truth * (1.0 + 1e-12) && truth <= iou.upper * (1.0 + 1e-12));
    assert!((i.dice().value - 2.0 * exact / (va + vb)).abs() < 1e-9);
}

#[test]
fn boxes_apart_or_touching_give_exactly_zero() {
    let a = cuboid([0.0; 3], [1.0; 3]);
    for d in [[3.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 0.5, 1.0], [-1.0, -1.0, -1.0]] {
        let b = moved(&a, d);
        let i = intersection(&a, &b, 1e-9).unwrap();
        assert_eq!((i.lower, i.upper), (0.0, 0.0), "{d:?}");
        assert_eq!(i.grid.cell_count(), 1, "no grid was built for {d:?}");
        assert_eq!(i.iou().value, 0.0);
        assert_eq!(i.a_minus_b().value, 1.0);
    }
}

#[test]
fn a_cube_turned_45_degrees_against_a_cube() {
    let a = prism(&[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]], 0.0, 1.0);
    // Overlapping: the diamond's corners stick out; its area inside the square is
    // 2r² − 4(r − 1)² for 1 ≤ r ≤ 2; heights overlap over [0.25, 1].
    let b = prism(&diamond(1.5), 0.25, 2.0);
    let exact = (2.0 * 1.5f64.powi(2) - 4.0 * 0.5f64.powi(2)) * 0.75;
    let i = intersection(&a, &b, 1e-9).unwrap();
    holds(&i, exact, 1e-9, "overlapping");
    // The common part is the octagon the square and the diamond share, over [0.25, 1].
    let octagon = [
        [1.0, -0.5],
        [1.0, 0.5],
        [0.5, 1.0],
        [-0.5, 1.0],
        [-1.0, 0.5],
        [-1.0, -0.5],
        [-0.5, -1.0],
        [0.5, -1.0],
    ];
    let truth = mass_properties(&prism(&octagon, 0.25, 1.0));
    same_moments(&i, &truth, 2.0, "octagon");
    // Inside: the diamond wholly in the square, over part of its height.
    let c = prism(&diamond(0.875), 0.125, 0.5);
    let exact = 2.0 * 0.875f64.powi(2) * 0.375;
    let i = intersection(&a, &c, 1e-9).unwrap();
    holds(&i, exact, 1e-9, "inside");
    assert!((i.b_minus_a().value).abs() < 1e-9);
}

#[test]
fn a_sphere_and_a_large_box_cut_the_sphere_below_a_plane() {
    let sphere = uv_sphere(1.0, 96, 48);
    for h in [0.3, -0.55, 0.0] {
        let slab = cuboid([-3.0, -3.0, -3.0], [3.0, 3.0, h]);
        let part = below(&sphere, &Plane::new([0.0, 0.0, h], [0.0, 0.0, 1.0]).unwrap()).part;
        let exact = part.signed_volume;
        let i = intersection(&sphere, &slab, 1e-9).unwrap();
        // `below`'s own rounding is far under the interval's allowance.
        holds(&i, exact, 1e-9, &format!("below {h}"));
        same_moments(&i, &part, 1.0, &format!("below {h}"));
    }
}

#[test]
fn two_spheres_meet_in_a_lens() {
    // Fine UV spheres of radius 1, centres 1 apart: the smooth lens π(4R + d)(2R − d)²/12
    // is within the polyhedra's discretization (2e-3 relative at 256 × 128).
    let a = uv_sphere(1.0, 256, 128);
    let b = moved(&a, [0.6, 0.0, 0.8]);
    let (r, d) = (1.0, 1.0);
    let smooth = std::f64::consts::PI * (4.0 * r + d) * (2.0 * r - d).powi(2) / 12.0;
    let i = intersection(&a, &b, 1e-9).unwrap();
    assert!(i.upper - i.lower <= 1e-9 * smooth, "width {}", i.upper - i.lower);
    assert!((i.volume() - smooth).abs() < 2e-3 * smooth, "{} vs {smooth}", i.volume());
    // The union from the same interval, and the identities of sets.
    let va = mass_properties(&a).signed_volume;
    assert!((i.a_minus_b().value + i.volume() - va).abs() < 1e-12);
    assert!(i.iou().upper <= 1.0);
    // The spheres are symmetric through the midpoint of their centres: so is the lens.
    let c = i.moments.unwrap().centroid;
    let mid = [0.3, 0.0, 0.4];
    assert!((0..3).all(|k| (c[k] - mid[k]).abs() < 1e-9), "{c:?}");
}

#[test]
fn a_body_with_itself_is_itself() {
    for body in [uv_sphere(1.0, 32, 16), prism(&diamond(1.25), -0.5, 0.75)] {
        let v = mass_properties(&body).signed_volume;
        let i = intersection(&body, &body, 1e-9).unwrap();
        holds(&i, v, 1e-9, "A ∩ A");
        same_moments(&i, &mass_properties(&body), 1.0, "A ∩ A");
        assert!((i.iou().value - 1.0).abs() < 1e-9);
        // Wound inward, it is measured turned outward.
        let inward = body.flipped();
        let j = intersection(&body, &inward, 1e-9).unwrap();
        assert_eq!(j.flipped, vec![1]);
        holds(&j, v, 1e-9, "A ∩ A turned");
    }
}

#[test]
fn order_shuffles_and_exact_motions_change_nothing() {
    let a = uv_sphere(1.0, 48, 24);
    let b = moved(&prism(&diamond(1.0), -0.5, 2.0), [0.25, 0.5, 0.0]);
    let reference = intersection(&a, &b, 1e-9).unwrap();
    let width = reference.upper - reference.lower;
    let same = |i: &Intersection, what: &str| {
        assert!((i.volume() - reference.volume()).abs() <= width, "{what}: {}", i.volume());
    };
    same(&intersection(&b, &a, 1e-9).unwrap(), "swapped");
    // Faces shuffled.
    let mut rng = XorShift::new(7);
    let shuffle = |m: &Mesh, rng: &mut XorShift| {
        let mut faces: Vec<Vec<u32>> = (0..m.face_count()).map(|f| m.face(f).to_vec()).collect();
        for k in (1..faces.len()).rev() {
            faces.swap(k, rng.below(k as u64 + 1) as usize);
        }
        polygons(m.positions(), &faces)
    };
    let (sa, sb) = (shuffle(&a, &mut rng), shuffle(&b, &mut rng));
    same(&intersection(&sa, &sb, 1e-9).unwrap(), "shuffled");
    // Exact motions of both: a dyadic translation, a quarter turn about z, axes cycled.
    let motions: [fn([f64; 3]) -> [f64; 3]; 3] = [
        |p| [p[0] + 8.5, p[1] - 3.25, p[2] + 0.125],
        |p| [-p[1], p[0], p[2]],
        |p| [p[2], p[0], p[1]],
    ];
    for (n, f) in motions.into_iter().enumerate() {
        same(&intersection(&mapped(&a, f), &mapped(&b, f), 1e-9).unwrap(), &format!("motion {n}"));
    }
}

#[test]
fn overlapping_boxes_are_the_pairs_a_plain_double_loop_finds() {
    let mut rng = XorShift::new(11);
    let mut boxes = Vec::new();
    for n in 0..300 {
        if n % 50 == 7 {
            boxes.push(None);
            continue;
        }
        // Corners on a coarse lattice, so boxes often share faces (touching: no pair).
        let lo: [f64; 3] = std::array::from_fn(|_| rng.below(40) as f64 * 0.25);
        let hi: [f64; 3] = std::array::from_fn(|a| lo[a] + 0.25 * (1 + rng.below(8)) as f64);
        boxes.push(Some(meshvol::Bounds { min: lo, max: hi }));
    }
    let mut plain = Vec::new();
    for i in 0..boxes.len() {
        for j in i + 1..boxes.len() {
            if let (Some(p), Some(q)) = (boxes[i], boxes[j]) {
                if (0..3).all(|a| p.min[a] < q.max[a] && q.min[a] < p.max[a]) {
                    plain.push((i, j));
                }
            }
        }
    }
    assert!(plain.len() > 100, "{}", plain.len());
    assert_eq!(overlapping_boxes(&boxes), plain);
}

#[test]
fn the_same_bits_at_any_thread_count() {
    let a = uv_sphere(1.0, 64, 32);
    let b = moved(&uv_sphere(0.75, 40, 20), [0.5, 0.25, 0.125]);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| intersection(&a, &b, 1e-9).unwrap())
    };
    let one = run(1);
    assert!(one.moments.is_some() && one.contact.is_some());
    for threads in [2, 3, 8] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}
