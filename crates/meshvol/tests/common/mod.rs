//! Helpers shared by the core crate's integration tests: the random generator the unit
//! tests use too, and meshes made from the standard solids of [`meshvol::shapes`].
// Each test file uses some of them.
#![allow(dead_code, unused_imports)]

#[path = "../../src/test_rng.rs"]
mod test_rng;

use meshvol::grid::{CutCells, Grid};
use meshvol::shapes::cuboid;
use meshvol::Mesh;
pub(crate) use test_rng::XorShift;

/// A closed, star-shaped triangle mesh: a UV sphere (12 × 7) whose vertices are pushed in
/// and out by `radii` (taken in turn), then scaled by `scale` and moved by `offset`.
pub fn bumpy_sphere(radii: &[f64], scale: f64, offset: [f64; 3]) -> Mesh {
    let base = meshvol::shapes::uv_sphere(1.0, 12, 7).triangulated();
    let bumped = base.positions().iter().zip(radii.iter().cycle());
    let positions = bumped.map(|(v, r)| [0, 1, 2].map(|k| v[k] * r * scale + offset[k])).collect();
    Mesh::new(positions, base.faces().clone()).unwrap()
}

/// `mesh` with every position mapped by `f`, its faces unchanged.
pub fn mapped(mesh: &Mesh, f: impl Fn([f64; 3]) -> [f64; 3]) -> Mesh {
    Mesh::new(mesh.positions().iter().map(|&p| f(p)).collect(), mesh.faces().clone()).unwrap()
}

/// `mesh` moved by `d`.
pub fn moved(mesh: &Mesh, d: [f64; 3]) -> Mesh {
    mapped(mesh, |p| [p[0] + d[0], p[1] + d[1], p[2] + d[2]])
}

/// The faces of `mesh` as lists of vertex indices.
pub fn face_lists(mesh: &Mesh) -> Vec<Vec<u32>> {
    (0..mesh.face_count()).map(|f| mesh.face(f).to_vec()).collect()
}

/// A mesh of polygon faces given as index lists.
pub fn polygons(p: &[[f64; 3]], faces: &[Vec<u32>]) -> Mesh {
    Mesh::from_polygons(p.to_vec(), faces.iter().map(|f| &f[..])).unwrap()
}

/// A box without its top face (the face whose corners all have z = max).
pub fn open_box(min: [f64; 3], max: [f64; 3]) -> Mesh {
    let closed = cuboid(min, max);
    let top = |face: &Vec<u32>| face.iter().all(|&v| closed.positions()[v as usize][2] == max[2]);
    let faces: Vec<Vec<u32>> = face_lists(&closed).into_iter().filter(|f| !top(f)).collect();
    assert_eq!(faces.len(), closed.face_count() - 1);
    polygons(closed.positions(), &faces)
}

/// Clips polygon `poly` to `lo ≤ p[d] ≤ hi` (Sutherland–Hodgman), in any dimension.
pub fn clip<const D: usize>(poly: Vec<[f64; D]>, d: usize, lo: f64, hi: f64) -> Vec<[f64; D]> {
    let mut out = poly;
    for (limit, keep_below) in [(hi, true), (lo, false)] {
        let inside = |p: &[f64; D]| if keep_below { p[d] <= limit } else { p[d] >= limit };
        let input = std::mem::take(&mut out);
        for (n, q) in input.iter().enumerate() {
            let p = input[(n + input.len() - 1) % input.len()];
            let (pi, qi) = (inside(&p), inside(q));
            if pi != qi {
                let t = (limit - p[d]) / (q[d] - p[d]);
                out.push(std::array::from_fn(|e| p[e] + t * (q[e] - p[e])));
            }
            if qi {
                out.push(*q);
            }
        }
        if out.len() < 3 {
            return Vec::new();
        }
    }
    out
}

/// The overlap of [a0, a1] and [b0, b1] (empty: lo ≥ hi).
pub fn overlap(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0.max(b.0), a.1.min(b.1))
}

/// `Σ_faces ± aperture · face area · axis + boundary_vector` for cell `(i, j, k)` of cut
/// cells: zero (to rounding) by the divergence theorem on the cut cell.
pub fn divergence(c: &CutCells, [i, j, k]: [usize; 3]) -> [f64; 3] {
    let [_, ny, nz] = c.grid.counts;
    let [dx, dy, dz] = c.grid.cell;
    let ax = |i: usize, j: usize, k: usize| c.aperture[0][(i * ny + j) * nz + k];
    let ay = |i: usize, j: usize, k: usize| c.aperture[1][(i * (ny + 1) + j) * nz + k];
    let az = |i: usize, j: usize, k: usize| c.aperture[2][(i * ny + j) * (nz + 1) + k];
    let v = c.boundary_vector[c.grid.index([i, j, k])];
    [
        (ax(i + 1, j, k) - ax(i, j, k)) * dy * dz + v[0],
        (ay(i, j + 1, k) - ay(i, j, k)) * dx * dz + v[1],
        (az(i, j, k + 1) - az(i, j, k)) * dx * dy + v[2],
    ]
}

/// Every cell `[i, j, k]` of `grid`, in C order.
pub fn cells(grid: &Grid) -> impl Iterator<Item = [usize; 3]> {
    let [nx, ny, nz] = grid.counts;
    (0..nx).flat_map(move |i| (0..ny).flat_map(move |j| (0..nz).map(move |k| [i, j, k])))
}

/// A random rotation: the matrix of a uniformly drawn unit quaternion's direction.
pub fn rotation(rng: &mut XorShift) -> [[f64; 3]; 3] {
    let q = [0; 4].map(|_| rng.unit() - 0.5);
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|c| c / n);
    [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
        [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
        [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
    ]
}

/// The compensated sum of `v`.
pub fn sum(v: &[f64]) -> f64 {
    let mut s = meshvol::accumulate::CompensatedSum::default();
    v.iter().for_each(|&x| s.add(x));
    s.value()
}

/// Asserts that `a` and `b` differ by at most `tolerance`.
pub fn assert_close(what: &str, a: f64, b: f64, tolerance: f64) {
    assert!((a - b).abs() <= tolerance, "{what}: {a} vs {b} (difference {:e})", a - b);
}

/// A grid of `counts` cells over the surface's bounding box grown by `margin` of its
/// size on each side.
pub fn grid_around(mesh: &Mesh, counts: [usize; 3], margin: f64) -> Grid {
    let b = meshvol::mass_properties(mesh).bounds.unwrap();
    let size = b.size();
    let cell = [0, 1, 2].map(|a| size[a] * (1.0 + 2.0 * margin) / counts[a] as f64);
    let origin = [0, 1, 2].map(|a| b.min[a] - margin * size[a]);
    Grid::new(origin, cell, counts).unwrap()
}

/// Two overlapping boxes in one mesh, a dirty surface (its cells count the overlap twice,
/// as the raw surface says).
pub fn overlapping_boxes() -> Mesh {
    let a = cuboid([0.0; 3], [1.0, 0.7, 0.9]);
    let b = cuboid([0.4, 0.3, 0.2], [1.3, 1.1, 1.2]);
    let (mut p, mut f) = (a.positions().to_vec(), face_lists(&a));
    let n = p.len() as u32;
    p.extend_from_slice(b.positions());
    f.extend(face_lists(&b).into_iter().map(|f| f.iter().map(|v| v + n).collect()));
    polygons(&p, &f)
}

/// The check of `mesh` with the default options.
pub fn checked(mesh: &Mesh) -> meshvol::topology::Check {
    meshvol::topology::check(mesh, &meshvol::topology::CheckOptions::default()).unwrap()
}
