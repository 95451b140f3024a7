//! Shared inputs for meshvol's criterion benches (`cargo bench -p meshvol-bench`).
//! Benches live in their own crate so that `cargo test` never builds criterion or the
//! peer crates they compare against.

use meshvol::shapes::uv_sphere;
use meshvol::Mesh;

/// A triangulated UV sphere of radius 1 with about `triangles` triangles
/// (2·segments·(rings − 1) with segments = 2·rings).
pub fn sphere_with_triangles(triangles: usize) -> Mesh {
    let rings = ((triangles as f64 / 4.0).sqrt().round() as u32).max(3);
    uv_sphere(1.0, 2 * rings, rings + 1).triangulated()
}
