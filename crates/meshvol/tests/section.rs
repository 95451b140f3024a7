//! Sections of closed meshes compared with areas known in closed form.

use std::f64::consts::PI;

use meshvol::polygon::{area_properties, polygon_issues};
use meshvol::section::{section, Plane};
use meshvol::shapes::{cuboid, torus, uv_sphere};
use meshvol::{Faces, Mesh};

/// Meshes side by side in one mesh, as triangles.
fn merge(meshes: &[Mesh]) -> Mesh {
    Mesh::concatenate(&meshes.iter().map(Mesh::triangulated).collect::<Vec<_>>())
}

/// The area of a regular m-gon of circumradius r.
fn regular_polygon_area(m: u32, r: f64) -> f64 {
    m as f64 / 2.0 * r * r * (2.0 * PI / m as f64).sin()
}

fn assert_close(actual: f64, expected: f64, relative: f64) {
    assert!(
        (actual - expected).abs() <= relative * expected.abs(),
        "got {actual}, expected {expected}"
    );
}

#[test]
fn sphere_section_is_the_regular_polygon_between_its_rings() {
    let (radius, m, n) = (2.0, 48, 24);
    let sphere = uv_sphere(radius, m, n);
    // Height 0.3 lies in the band between rings k and k + 1 (φ = πk/n from the pole).
    let h = 0.3;
    let k = ((h / radius).acos() * n as f64 / PI).floor();
    let (phi0, phi1) = (PI * k / n as f64, PI * (k + 1.0) / n as f64);
    let (z0, z1) = (radius * phi0.cos(), radius * phi1.cos());
    let (r0, r1) = (radius * phi0.sin(), radius * phi1.sin());
    let r = r0 + (h - z0) / (z1 - z0) * (r1 - r0);
    let s = section(&sphere, &Plane::axis(2, h).unwrap());
    assert_eq!((s.loops, s.open_chains, s.ambiguous_edges, s.misoriented_loops), (1, 0, 0, 0));
    // Each planar quad is cut through both of its fan triangles: a point on every
    // polygon edge (on the quad's diagonal) besides the m corners.
    assert_eq!(s.polygons[0].exterior.len(), 2 * m as usize);
    assert_close(s.signed_area, regular_polygon_area(m, r), 1e-14);
    let p = area_properties(&s.polygons);
    assert_close(p.area, regular_polygon_area(m, r), 1e-14);
    // A regular polygon's polar moment about its centre (the origin here): each of its
    // m triangles from the centre gives (2·area/12)·r²·(2 + cos(2π/m)).
    let c = p.centroid.unwrap();
    assert!(c[0].abs() < 1e-14 && c[1].abs() < 1e-14);
    let polar = p.area * r * r / 6.0 * (2.0 + (2.0 * PI / m as f64).cos());
    assert_close(p.inertia.polar, polar, 1e-13);
}

#[test]
fn torus_sections_are_annuli_and_on_plane_vertices_count_as_above() {
    let (major, minor, m, n) = (3.0, 1.0, 64, 16);
    let t = torus(major, minor, m, n);
    let annulus =
        |outer: f64, inner: f64| regular_polygon_area(m, outer) - regular_polygon_area(m, inner);
    // z = 0 passes through profile vertices at x = R ± r: the limit from below.
    let s = section(&t, &Plane::axis(2, 0.0).unwrap());
    assert_eq!((s.loops, s.polygons.len(), s.polygons[0].holes.len()), (2, 1, 1));
    let expected = annulus(major + minor, major - minor);
    assert_close(area_properties(&s.polygons).area, expected, 1e-14);
    assert_close(s.signed_area, expected, 1e-14);
    assert!(polygon_issues(&s.polygons).is_empty());
    // Between profile vertices: the radii follow the profile's edges.
    let step = 2.0 * PI / n as f64;
    let h = 0.5 * minor * step.sin();
    let outer = major + minor + (h / (minor * step.sin())) * (minor * step.cos() - minor);
    let inner = major - minor - (h / (minor * step.sin())) * (minor * step.cos() - minor);
    let s = section(&t, &Plane::axis(2, h).unwrap());
    assert_close(area_properties(&s.polygons).area, annulus(outer, inner), 1e-13);
    // A vertical cut through the axis: two regular n-gons of circumradius r.
    let s = section(&t, &Plane::axis(1, 0.0).unwrap());
    assert_eq!((s.loops, s.polygons.len(), s.misoriented_loops), (2, 2, 0));
    // Loops wind counter-clockwise in the (x, z) frame of y = 0 too.
    assert_close(s.signed_area, 2.0 * regular_polygon_area(n, minor), 1e-14);
    assert_close(area_properties(&s.polygons).area, 2.0 * regular_polygon_area(n, minor), 1e-14);
}

#[test]
fn tilted_plane_through_a_cube_cuts_a_regular_hexagon() {
    for offset in [0.0, 1.0e6] {
        let cube = cuboid([offset; 3], [offset + 1.0; 3]);
        let plane = Plane::new([offset + 0.5; 3], [1.0, 1.0, 1.0]).unwrap();
        let s = section(&cube, &plane);
        assert_eq!(s.loops, 1);
        // A regular hexagon with side √2/2.
        let expected = 3.0 * 3f64.sqrt() / 4.0;
        let p = area_properties(&s.polygons);
        assert_close(p.area, expected, 1e-14);
        // Its centroid is the plane's point: (0, 0) in the plane's frame.
        let c = p.centroid.unwrap();
        assert!(c[0].abs() < 1e-14 && c[1].abs() < 1e-14, "{c:?}");
        let f = plane.frame();
        let unit = |v: [f64; 3]| (v.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-15;
        assert!(unit(f.normal) && unit(f.u) && unit(f.v));
    }
}

#[test]
fn cavities_become_holes_and_islands_exteriors() {
    // A hollow box (cavity wound inward) with a small solid box inside the cavity.
    let outer = cuboid([0.0; 3], [10.0; 3]);
    let cavity = cuboid([2.0; 3], [8.0; 3]).flipped();
    let island = cuboid([4.0; 3], [5.0; 3]);
    let s = section(&merge(&[outer, cavity, island]), &Plane::axis(2, 4.5).unwrap());
    assert_eq!((s.loops, s.polygons.len(), s.misoriented_loops), (3, 2, 0));
    assert_eq!(area_properties(&s.polygons).area, 100.0 - 36.0 + 1.0);
    assert_eq!(s.signed_area, 65.0);
    // The same cavity wound outward is counted as misoriented.
    let wrong = merge(&[cuboid([0.0; 3], [10.0; 3]), cuboid([2.0; 3], [8.0; 3])]);
    let s = section(&wrong, &Plane::axis(2, 4.5).unwrap());
    assert_eq!((s.misoriented_loops, area_properties(&s.polygons).area), (1, 64.0));
}

#[test]
fn open_and_far_surfaces() {
    // A box without its x = 1 side: the section does not close.
    let cube = cuboid([0.0; 3], [1.0; 3]).triangulated();
    let Faces::Triangles(all) = cube.faces() else { unreachable!() };
    let on_side = |t: &[u32; 3]| t.iter().all(|&i| cube.positions()[i as usize][0] == 1.0);
    let kept = all.iter().copied().filter(|t| !on_side(t)).collect();
    let open = Mesh::from_triangles(cube.positions().to_vec(), kept).unwrap();
    let s = section(&open, &Plane::axis(2, 0.5).unwrap());
    assert_eq!((s.loops, s.open_chains, s.polygons.len()), (0, 1, 0));
    // Far from the origin an axis section keeps world coordinates exactly.
    let o = 4.0e6;
    let s =
        section(&cuboid([o, o, o], [o + 3.0, o + 2.0, o + 1.0]), &Plane::axis(0, o + 1.5).unwrap());
    let p = area_properties(&s.polygons);
    assert_eq!((p.area, p.centroid), (2.0, Some([o + 1.0, o + 0.5])));
    // No crossing at all, and bad planes.
    assert_eq!(section(&open, &Plane::axis(2, 7.0).unwrap()).segments, 0);
    assert!(Plane::new([0.0; 3], [0.0; 3]).is_err());
    assert!(Plane::new([f64::NAN, 0.0, 0.0], [0.0, 0.0, 1.0]).is_err());
    assert!(Plane::axis(3, 0.0).is_err());
}

/// A face with a corner on one of its edges (a T-junction, closed by a sliver triangle)
/// fanned from another corner has a diagonal lying on that edge: the edge is then
/// crossed by four triangles, two each way. Every crossing must still be chained: the
/// section is the same whichever corner the face starts at (it was lost, area 0, for
/// the starts whose fan has that diagonal).
#[test]
fn a_fan_diagonal_along_an_edge_keeps_the_section() {
    let cube = cuboid([0.0; 3], [1.0; 3]);
    let mut positions = cube.positions().to_vec();
    let at = |p: [f64; 3]| positions.iter().position(|&q| q == p).unwrap() as u32;
    let (t00, t10, t11, t01) =
        (at([0.0, 0.0, 1.0]), at([1.0, 0.0, 1.0]), at([1.0, 1.0, 1.0]), at([0.0, 1.0, 1.0]));
    positions.push([0.5, 0.0, 1.0]);
    let m = positions.len() as u32 - 1;
    let top = |f: &[u32]| f.iter().all(|&v| positions[v as usize][2] == 1.0);
    let others: Vec<Vec<u32>> =
        (0..cube.face_count()).map(|f| cube.face(f).to_vec()).filter(|f| !top(f)).collect();
    for first in 0..5 {
        let mut pentagon = vec![t00, m, t10, t11, t01];
        pentagon.rotate_left(first);
        let mut faces = others.clone();
        faces.push(pentagon);
        faces.push(vec![t00, t10, m]);
        let mesh = Mesh::from_polygons(positions.clone(), faces.iter().map(|f| &f[..])).unwrap();
        for (axis, level) in [(0, 0.25), (0, 0.75), (1, 0.5)] {
            let s = section(&mesh, &Plane::axis(axis, level).unwrap());
            let area = area_properties(&s.polygons).area;
            assert_eq!((s.open_chains, area), (0, 1.0), "start {first}, axis {axis} at {level}");
        }
    }
}

/// Two unit cubes sharing an edge along each axis in turn: the planes across that edge
/// cut two unit squares touching at a corner, whose crossings of the shared edge can
/// be chained either way. They must stay two loops (and two polygons) for every face
/// order, whichever way the plane's frame turns.
#[test]
fn sections_touching_at_a_shared_edge_stay_apart() {
    for axis in 0..3 {
        // The second cube is moved by 1 along the two other axes.
        let mut far = [2.0; 3];
        let mut near = [1.0; 3];
        far[axis] = 1.0;
        near[axis] = 0.0;
        let meshes = [cuboid([0.0; 3], [1.0; 3]), cuboid(near, far)];
        let joined = Mesh::concatenate(&meshes);
        // One vertex per position, so that the shared edge is one edge of four faces.
        let mut positions: Vec<[f64; 3]> = Vec::new();
        let mut id = |p: [f64; 3]| match positions.iter().position(|&q| q == p) {
            Some(i) => i as u32,
            None => {
                positions.push(p);
                positions.len() as u32 - 1
            }
        };
        let faces: Vec<Vec<u32>> = (0..joined.face_count())
            .map(|f| joined.face(f).iter().map(|&v| id(joined.positions()[v as usize])).collect())
            .collect();
        for first in 0..faces.len() {
            let mut order = faces.clone();
            order.rotate_left(first);
            let mesh =
                Mesh::from_polygons(positions.clone(), order.iter().map(|f| &f[..])).unwrap();
            let s = section(&mesh, &Plane::axis(axis, 0.5).unwrap());
            let area = area_properties(&s.polygons).area;
            let got = (s.loops, s.polygons.len(), s.open_chains, area);
            assert_eq!(got, (2, 2, 0, 2.0), "edge along {axis}, faces from {first}");
        }
    }
}
