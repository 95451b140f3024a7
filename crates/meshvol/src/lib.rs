//! meshvol: exact, fast measurements of solids bounded by triangle and polygon meshes.
//!
//! The library does geometry only: no files, no printing, no global state. Readers
//! (`meshvol-io`) turn bytes into a [`Mesh`] or another [`Surface`]; kernels turn a
//! surface into numbers:
//!
//! - [`mass_properties`]: volume, area, centroid and inertia in one parallel pass, with a
//!   bound on the rounding error and the same bits at any thread count;
//! - [`exact_signed_volume`]: the correctly rounded volume of the polyhedron.
//!
//! Threads come from the caller's rayon pool (`ThreadPool::install`).

pub mod accumulate;
mod bvh;
mod eigen;
pub mod exact;
pub mod mesh;
pub mod properties;
pub mod shapes;
pub mod topology;
mod vector;

pub use exact::{exact_signed_volume, ExactError};
pub use mesh::{FaceRange, Faces, Mesh, MeshError, Surface};
pub use properties::{mass_properties, Bounds, MassProperties, Principal};

/// A point or vector in 3D.
pub type Point = [f64; 3];
