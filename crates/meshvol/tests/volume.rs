//! The volume-only path (`meshvol::volume`): the same bits as `mass_properties`, its
//! bound holding against the exact rational volume, any index type, any thread count.

use meshvol::shapes::{torus, uv_sphere};
use meshvol::volume::{signed_volume, triangles_signed_volume, PARALLEL_TRIANGLES};
use meshvol::{mass_properties, Mesh, MeshError, Point, Surface};
use num_bigint::BigInt;

/// A tiny deterministic generator (xorshift64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// x as m·2^e exactly.
fn dyadic(x: f64) -> (BigInt, i64) {
    if x == 0.0 {
        return (BigInt::from(0), 0);
    }
    let bits = x.to_bits();
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1 << 52) - 1);
    let (m, e) = if exp == 0 { (frac, -1074) } else { (frac | (1 << 52), exp - 1075) };
    let m = BigInt::from(m);
    (if bits >> 63 == 1 { -m } else { m }, e)
}

/// `x · 2^shift` as an integer (exact for the dyadic values used here).
fn scaled(x: f64, shift: i64) -> BigInt {
    let (m, e) = dyadic(x);
    let s = e + shift;
    assert!(s >= 0, "not an integer at this scale");
    m << s as usize
}

/// Coordinates on a 2⁻¹⁰ grid: 6V·2³⁰ is the integer Σ det of the scaled coordinates.
const GRID_BITS: i64 = 10;

/// 6·V·2^(3·GRID_BITS), exactly, for coordinates on the grid.
fn exact_six_volume_scaled(positions: &[Point], triangles: &[[u32; 3]]) -> BigInt {
    let int = |x: f64| -> i128 {
        let v = x * (1u64 << GRID_BITS) as f64;
        assert_eq!(v, v.trunc());
        v as i128
    };
    let mut total = BigInt::from(0);
    let mut part: i128 = 0;
    for (n, t) in triangles.iter().enumerate() {
        let [a, b, c] = t.map(|i| positions[i as usize].map(int));
        part += a[0] * (b[1] * c[2] - b[2] * c[1])
            + a[1] * (b[2] * c[0] - b[0] * c[2])
            + a[2] * (b[0] * c[1] - b[1] * c[0]);
        if n % 1024 == 1023 {
            total += part;
            part = 0;
        }
    }
    total + part
}

/// |computed − V| ≤ bound, in exact arithmetic.
fn assert_bound_holds(positions: &[Point], triangles: &[[u32; 3]], value: f64, bound: f64) {
    let six_v = exact_six_volume_scaled(positions, triangles);
    // Everything times 6·2^(30 + 1100) is an integer.
    let shift = 1100;
    let exact = six_v << shift as usize;
    let computed = scaled(value, shift + 3 * GRID_BITS) * 6;
    let allowed = scaled(bound, shift + 3 * GRID_BITS) * 6;
    let error = if computed > exact { &computed - &exact } else { &exact - &computed };
    assert!(error <= allowed, "error exceeds the bound {bound} at value {value}");
}

/// `n` random triangles over `v` random vertices on the 2⁻¹⁰ grid, within `size` of
/// `offset`.
fn soup(rng: &mut Rng, v: usize, n: usize, size: u64, offset: f64) -> (Vec<Point>, Vec<[u32; 3]>) {
    let positions = (0..v)
        .map(|_| [0; 3].map(|_| offset + rng.below(size << GRID_BITS) as f64 / 1024.0))
        .collect();
    let triangles = (0..n).map(|_| [0; 3].map(|_| rng.below(v as u64) as u32)).collect();
    (positions, triangles)
}

/// A mesh's positions and triangles snapped to the grid.
fn snapped(mesh: &Mesh, offset: f64) -> (Vec<Point>, Vec<[u32; 3]>) {
    let mesh = mesh.triangulated();
    let positions = mesh
        .positions()
        .iter()
        .map(|p| p.map(|x| offset + (x * 1024.0).round() / 1024.0))
        .collect();
    let triangles = (0..mesh.face_count())
        .map(|f| {
            let face = mesh.face(f);
            [face[0], face[1], face[2]]
        })
        .collect();
    (positions, triangles)
}

/// A surface that reads a mesh's faces as fans only (no arrays to take the fast path),
/// saying that every face is one triangle when `.1` (as a binary STL read in place
/// does: the mass properties then read it four faces a SIMD step).
struct Fans<'a>(&'a Mesh, bool);

impl Surface for Fans<'_> {
    fn face_count(&self) -> usize {
        self.0.face_count()
    }

    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        self.0.fan(face, triangle)
    }

    fn faces_are_triangles(&self) -> bool {
        self.1
    }
}

fn check_all_ways(positions: &[Point], triangles: &[[u32; 3]]) {
    let mesh = Mesh::from_triangles(positions.to_vec(), triangles.to_vec()).unwrap();
    let mp = mass_properties(&mesh);
    let v = signed_volume(&mesh);
    assert_eq!(v.signed_volume.to_bits(), mp.signed_volume.to_bits());
    assert_eq!(v.volume_error_bound.to_bits(), mp.volume_error_bound.to_bits());
    assert_eq!(v.triangles, mp.triangles);
    let as_i32: Vec<[i32; 3]> = triangles.iter().map(|t| t.map(|i| i as i32)).collect();
    let as_i64: Vec<[i64; 3]> = triangles.iter().map(|t| t.map(i64::from)).collect();
    for w in [
        triangles_signed_volume(positions, triangles).unwrap(),
        triangles_signed_volume(positions, &as_i32).unwrap(),
        triangles_signed_volume(positions, &as_i64).unwrap(),
    ] {
        assert_eq!(w, v);
    }
    // The generic path (faces read as fans) gives the same bits as the SIMD lanes, for
    // the volume and for every mass property (Debug prints −0.0 apart from 0.0).
    assert_eq!(signed_volume(&Fans(&mesh, false)), v);
    assert_eq!(format!("{:?}", mass_properties(&Fans(&mesh, false))), format!("{mp:?}"));
    assert_eq!(format!("{:?}", mass_properties(&Fans(&mesh, true))), format!("{mp:?}"));
    assert_bound_holds(positions, triangles, v.signed_volume, v.volume_error_bound);
}

#[test]
fn random_soups_match_mass_properties_and_the_exact_volume() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    // Sizes around the SIMD groups (4) and the chunks (16384); near and far from the
    // origin (far: the move from r to the origin is loose, so the exact sum is taken).
    for (v, n, size, offset) in [
        (4, 1, 4, 0.0),
        (5, 3, 8, 0.0),
        (10, 7, 100, -50.0),
        (100, 1001, 1000, 3.0),
        (5000, 16_384 + 5, 64, 1024.0),
        (3000, 40_003, 1 << 10, -7.5),
        (50, 999, 4, 1048576.0),
    ] {
        let (positions, triangles) = soup(&mut rng, v, n, size, offset);
        check_all_ways(&positions, &triangles);
    }
}

#[test]
fn closed_meshes_match_mass_properties_and_the_exact_volume() {
    for offset in [0.0, 1000.0, -1048576.0] {
        let (positions, triangles) = snapped(&uv_sphere(100.0, 97, 48), offset);
        check_all_ways(&positions, &triangles);
        let (positions, triangles) = snapped(&torus(50.0, 20.0, 61, 31), offset);
        check_all_ways(&positions, &triangles);
    }
}

#[test]
fn polygon_faces_take_the_generic_path() {
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let quads: [&[u32]; 6] =
        [&[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7]];
    let cube = Mesh::from_polygons(p, quads).unwrap();
    let (v, mp) = (signed_volume(&cube), mass_properties(&cube));
    assert_eq!((v.signed_volume, v.volume_error_bound), (1.0, mp.volume_error_bound));
    assert_eq!((v.faces, v.triangles), (6, 12));
}

#[test]
fn same_bits_on_one_thread_and_on_a_pool() {
    // Above PARALLEL_TRIANGLES the chunks run on the pool; below, on the caller's
    // thread: the same chunks either way.
    let sphere = uv_sphere(100.0, 400, 320).triangulated();
    assert!(sphere.face_count() > PARALLEL_TRIANGLES);
    let run = |threads| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| (signed_volume(&sphere), mass_properties(&sphere)))
    };
    let (one, three) = (run(1), run(3));
    assert_eq!(one.0, three.0);
    assert_eq!(one.0.signed_volume.to_bits(), one.1.signed_volume.to_bits());
    assert_eq!(one.0.volume_error_bound.to_bits(), three.1.volume_error_bound.to_bits());
}

#[test]
fn bad_indices_and_coordinates_are_errors() {
    let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut t = vec![[0i64, 2, 1]; 9];
    t[6] = [0, 1, 7];
    assert_eq!(
        triangles_signed_volume(&p, &t),
        Err(MeshError::IndexOutOfRange { face: 6, index: 7, vertices: 4 })
    );
    t[6] = [0, -1, 2];
    assert_eq!(
        triangles_signed_volume(&p, &t),
        Err(MeshError::NegativeIndex { face: 6, index: -1 })
    );
    t[6] = [0, 1, 2];
    t[8] = [0, 1, 4];
    assert_eq!(
        triangles_signed_volume(&p, &t),
        Err(MeshError::IndexOutOfRange { face: 8, index: 4, vertices: 4 })
    );
    // Bad faces in later chunks of a parallel pass: the first in face order is named.
    let mut many = vec![[0i32, 2, 1]; 3 * PARALLEL_TRIANGLES];
    many[2 * PARALLEL_TRIANGLES + 5] = [0, 9, 1];
    many[PARALLEL_TRIANGLES + 3] = [0, 1, -2];
    assert_eq!(
        triangles_signed_volume(&p, &many),
        Err(MeshError::NegativeIndex { face: PARALLEL_TRIANGLES + 3, index: -2 })
    );
    let q = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, f64::NAN, 0.0], [0.0, 0.0, 1.0]];
    assert_eq!(
        triangles_signed_volume(&q, &[[0u32, 1, 3], [0, 2, 1]]).map_err(|e| e.to_string()),
        Err("vertex 2 has a non-finite coordinate (NaN)".to_string())
    );
    // Unused vertices are not read.
    assert!(triangles_signed_volume(&q, &[[0u32, 1, 3]]).is_ok());
    let empty: [[u32; 3]; 0] = [];
    assert_eq!(triangles_signed_volume(&p, &empty).unwrap().signed_volume, 0.0);
}

#[test]
fn signed_zero_bounds_keep_the_scalar_order() {
    // Extremes at zero, reached as −0.0 and +0.0 in different orders: the bounds keep
    // whichever came first, as the scalar loop does.
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for n in [5, 8, 13, 1000, 1003] {
        let positions: Vec<Point> = (0..64)
            .map(|_| {
                [0; 3].map(|_| match rng.below(4) {
                    0 => 0.0,
                    1 => -0.0,
                    2 => rng.below(100) as f64 / 8.0,
                    _ => -(rng.below(100) as f64) / 8.0 * 0.0,
                })
            })
            .collect();
        let triangles: Vec<[u32; 3]> =
            (0..n).map(|_| [0; 3].map(|_| rng.below(64) as u32)).collect();
        let mesh = Mesh::from_triangles(positions, triangles).unwrap();
        let scalar = format!("{:?}", mass_properties(&Fans(&mesh, false)));
        assert_eq!(format!("{:?}", mass_properties(&mesh)), scalar);
        assert_eq!(format!("{:?}", mass_properties(&Fans(&mesh, true))), scalar);
    }
}

/// A surface read face by face only (no arrays, no word that its faces are triangles),
/// keeping what it says of its vector area: the scalar loop over the same faces.
struct FaceByFace<S>(S);

impl<S: Surface> Surface for FaceByFace<S> {
    fn face_count(&self) -> usize {
        self.0.face_count()
    }

    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        self.0.fan(face, triangle)
    }

    fn vector_area_is_zero(&self) -> bool {
        self.0.vector_area_is_zero()
    }
}

#[test]
fn a_checked_solid_of_triangles_has_the_bits_of_the_face_by_face_loop() {
    use meshvol::topology::{check, CheckOptions};
    // A sphere wound inward (turned by the solid) with a cavity missing a face (its hole
    // capped), a face given twice and a collapsed face (both dropped): the solid's
    // faces are some of the surface's, turned, then caps.
    let (mut positions, outer) = snapped(&uv_sphere(10.0, 48, 24), 0.25);
    let mut triangles: Vec<[u32; 3]> = outer.iter().map(|&[a, b, c]| [a, c, b]).collect();
    let (inner, inner_triangles) = snapped(&uv_sphere(3.0, 24, 12), 0.25);
    let base = positions.len() as u32;
    positions.extend(inner);
    triangles
        .extend(inner_triangles.iter().skip(1).map(|&[a, b, c]| [a + base, c + base, b + base]));
    triangles.push(triangles[7]);
    triangles.push([0, 0, 1]);
    let mesh = Mesh::from_triangles(positions, triangles).unwrap();
    let checked = check(&mesh, &CheckOptions::default()).unwrap();
    let solid = checked.solid(&mesh);
    assert!(solid.faces_are_triangles());
    assert!(
        solid.surface_faces() < mesh.face_count() && solid.face_count() > solid.surface_faces()
    );
    let fast = mass_properties(&solid);
    assert_eq!(format!("{fast:?}"), format!("{:?}", mass_properties(&FaceByFace(solid))));
    // And the solid is the one meant: the cavity subtracted.
    let expected = meshvol::shapes::uv_sphere_volume(10.0, 48, 24)
        - meshvol::shapes::uv_sphere_volume(3.0, 24, 12);
    assert!((fast.signed_volume - expected).abs() < 1.0, "{} {expected}", fast.signed_volume);
}
