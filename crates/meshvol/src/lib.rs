//! meshvol: exact, fast measurements of solids bounded by triangle and polygon meshes.
//!
//! The library does geometry only: no files, no printing, no global state. Readers
//! (`meshvol-io`) turn bytes into a [`Mesh`] or another [`Surface`]; kernels turn a
//! surface into numbers:
//!
//! - [`mass_properties`]: volume, area, centroid and inertia in one parallel pass, with a
//!   bound on the rounding error and the same bits at any thread count;
//! - [`signed_volume`] and [`triangles_signed_volume`] (arrays read in place): the signed
//!   volume and its rounding bound alone, the same bits as [`mass_properties`]'s, in SIMD
//!   lanes and on one thread below 200k triangles;
//! - [`exact_signed_volume`]: the correctly rounded volume of the polyhedron;
//! - [`polygon::area_properties`] and [`polygon::polygon_issues`]: area, centroid and
//!   second moments of plane polygons with holes, and whether their rings are simple;
//! - [`section::section`]: the cross-section of a surface by a plane, as polygons;
//! - `hull::convex_hull`: the convex hull of a point set;
//! - [`surface`]: parts of a surface, several surfaces as one, or one turned inside out,
//!   read as surfaces of their own, and the connected parts of a surface;
//! - [`grid::cell_volumes`], [`grid::profile`] and [`grid::union`]: the exact volume in
//!   each cell of a grid, volume below each level along an axis, and the volume of a union
//!   of overlapping bodies as a certified interval;
//! - [`cutfill::cut_fill`]: cut and fill volumes between two height-field surfaces (or a
//!   surface and a level), exact for triangulations, in total and per plan cell.
//!
//! Threads come from the caller's rayon pool (`ThreadPool::install`).

pub mod accumulate;
pub mod assembly;
pub mod below;
mod buckets;
mod bvh;
pub mod cutfill;
mod eigen;
pub mod exact;
pub mod grid;
pub mod hull;
mod lanes;
pub mod mesh;
pub mod overlap;
pub mod polygon;
pub mod progress;
pub mod properties;
pub mod section;
pub mod shapes;
pub mod surface;
#[cfg(test)]
mod test_rng;
pub mod topology;
mod union_find;
mod vector;
pub mod volume;
mod volume_sums;

pub use exact::{exact_signed_volume, ExactError};
pub use mesh::{Faces, Mesh, MeshError, Surface};
pub use properties::{mass_properties, Bounds, MassProperties, Principal};
pub use volume::{signed_volume, triangles_signed_volume, Volume};

/// A point or vector in 3D.
pub type Point = [f64; 3];
