//! meshvol: exact, fast measurements of solids bounded by triangle and polygon meshes.
//!
//! The library does geometry only: no files, no printing, no global state. Readers
//! (`meshvol-io`) turn bytes into a [`Mesh`] or another [`Surface`]; kernels turn a
//! surface into numbers.

pub mod mesh;

pub use mesh::{Faces, Mesh, MeshError, Surface};

/// A point or vector in 3D.
pub type Point = [f64; 3];
