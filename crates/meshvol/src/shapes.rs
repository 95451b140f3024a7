//! Closed solids with known measurements, wound outward: for tests, benchmarks and
//! examples.
//!
//! The UV sphere and torus are solids of revolution whose quads are planar trapezoids,
//! so their polyhedral volume has a closed form: a half-plane region A revolved
//! polygonally through m equal steps has volume m·sin(2π/m)·∫∫_A x dA (each horizontal
//! slice is a ring of m triangles of area ½·x²·sin(2π/m)). [`uv_sphere_volume`] and
//! [`torus_volume`] state it for each.

use crate::Mesh;
use std::f64::consts::PI;

/// An axis-aligned box with six quad faces.
pub fn cuboid(min: [f64; 3], max: [f64; 3]) -> Mesh {
    let [x0, y0, z0] = min;
    let [x1, y1, z1] = max;
    let positions = vec![
        [x0, y0, z0],
        [x1, y0, z0],
        [x1, y1, z0],
        [x0, y1, z0],
        [x0, y0, z1],
        [x1, y0, z1],
        [x1, y1, z1],
        [x0, y1, z1],
    ];
    let quads: [&[u32]; 6] =
        [&[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7]];
    Mesh::from_polygons(positions, quads).expect("a box is a valid mesh")
}

/// The tetrahedron (a, b, c, d), wound outward when (b − a)·((c − a) × (d − a)) > 0.
pub fn tetrahedron(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> Mesh {
    Mesh::from_triangles(vec![a, b, c, d], vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
        .expect("a tetrahedron is a valid mesh")
}

/// A UV sphere: `segments` meridians, `rings` bands from pole to pole; triangles at the
/// poles, planar quads between. Has 2·segments·(rings − 1) fan triangles.
pub fn uv_sphere(radius: f64, segments: u32, rings: u32) -> Mesh {
    let (m, n) = (segments.max(3), rings.max(2));
    let mut positions = vec![[0.0, 0.0, radius]];
    for k in 1..n {
        let phi = PI * k as f64 / n as f64;
        for j in 0..m {
            let theta = 2.0 * PI * j as f64 / m as f64;
            let x = radius * phi.sin();
            positions.push([x * theta.cos(), x * theta.sin(), radius * phi.cos()]);
        }
    }
    positions.push([0.0, 0.0, -radius]);
    let south = positions.len() as u32 - 1;
    let ring = |k: u32, j: u32| 1 + (k - 1) * m + j % m;
    let mut offsets = vec![0];
    let mut indices = Vec::new();
    let mut face = |f: &[u32]| {
        indices.extend_from_slice(f);
        offsets.push(indices.len());
    };
    for j in 0..m {
        face(&[0, ring(1, j), ring(1, j + 1)]);
        for k in 1..n - 1 {
            face(&[ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1)]);
        }
        face(&[south, ring(n - 1, j + 1), ring(n - 1, j)]);
    }
    Mesh::new(positions, crate::Faces::Polygons { offsets, indices }).expect("valid sphere")
}

/// The exact volume of [`uv_sphere`]'s polyhedron.
pub fn uv_sphere_volume(radius: f64, segments: u32, rings: u32) -> f64 {
    let (m, n) = (segments.max(3), rings.max(2));
    let meridian: Vec<(f64, f64)> = (0..=n)
        .map(|k| {
            let phi = PI * k as f64 / n as f64;
            (radius * phi.sin(), radius * phi.cos())
        })
        .collect();
    // ∫∫ x dA of the region between the axis and the meridian polyline: for each segment
    // (x linear in z), ∫ x²/2 dz = Δz·(x₀² + x₀x₁ + x₁²)/6.
    let moment: f64 = meridian
        .windows(2)
        .map(|w| {
            let ((x0, z0), (x1, z1)) = (w[0], w[1]);
            (z0 - z1) * (x0 * x0 + x0 * x1 + x1 * x1) / 6.0
        })
        .sum();
    m as f64 * (2.0 * PI / m as f64).sin() * moment
}

/// Revolves a closed profile polygon about the z axis in `segments` equal steps.
///
/// `profile` lists (x, z) points with x > 0, counter-clockwise in the (x, z) plane
/// (x to the right, z up); every face is a planar trapezoid, wound outward. Parts
/// turned on a lathe (bushings, flanges, spools) are such solids.
pub fn revolve(profile: &[(f64, f64)], segments: u32) -> Mesh {
    let (m, n) = (segments.max(3), profile.len() as u32);
    let mut positions = Vec::with_capacity((m * n) as usize);
    for i in 0..m {
        let theta = 2.0 * PI * i as f64 / m as f64;
        positions.extend(profile.iter().map(|&(x, z)| [x * theta.cos(), x * theta.sin(), z]));
    }
    let at = |i: u32, j: u32| (i % m) * n + j % n;
    let quads: Vec<[u32; 4]> = (0..m)
        .flat_map(|i| (0..n).map(move |j| [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]))
        .collect();
    Mesh::from_polygons(positions, quads.iter().map(|q| &q[..])).expect("valid revolved solid")
}

/// The exact volume of [`revolve`]'s polyhedron: m·sin(2π/m)·∫∫ x dA over the profile,
/// with ∫∫ x dA = Σ (x₀ + x₁)·(x₀z₁ − x₁z₀)/6 over the profile's edges (Green's theorem).
pub fn revolve_volume(profile: &[(f64, f64)], segments: u32) -> f64 {
    let m = segments.max(3) as f64;
    let moment: f64 = (0..profile.len())
        .map(|k| {
            let ((x0, z0), (x1, z1)) = (profile[k], profile[(k + 1) % profile.len()]);
            (x0 + x1) * (x0 * z1 - x1 * z0) / 6.0
        })
        .sum();
    m * (2.0 * PI / m).sin() * moment
}

/// A torus around the z axis: a regular `minor_segments`-gon of circumradius `minor`
/// centred at distance `major`, revolved in `major_segments` steps; planar quads.
pub fn torus(major: f64, minor: f64, major_segments: u32, minor_segments: u32) -> Mesh {
    revolve(&torus_profile(major, minor, minor_segments), major_segments)
}

fn torus_profile(major: f64, minor: f64, segments: u32) -> Vec<(f64, f64)> {
    let n = segments.max(3);
    (0..n)
        .map(|j| {
            let phi = 2.0 * PI * j as f64 / n as f64;
            (major + minor * phi.cos(), minor * phi.sin())
        })
        .collect()
}
/// The exact volume of [`torus`]'s polyhedron: m·sin(2π/m)·A·R, with A the area of the
/// regular n-gon, (n/2)·r²·sin(2π/n), whose centroid lies at R.
pub fn torus_volume(major: f64, minor: f64, major_segments: u32, minor_segments: u32) -> f64 {
    let (m, n) = (major_segments.max(3) as f64, minor_segments.max(3) as f64);
    let polygon_area = n / 2.0 * minor * minor * (2.0 * PI / n).sin();
    m * (2.0 * PI / m).sin() * polygon_area * major
}
