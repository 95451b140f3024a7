//! The native part of meshvol's Python package (`meshvol._meshvol`); the package itself
//! (`python/meshvol/__init__.py`) re-exports everything defined here.
//!
//! # Shape of the bindings
//! - Inputs (vertex, face, point and ring arrays, and anything NumPy can turn into one)
//!   are copied once into the core library's types: f64 positions (float32 and integer
//!   coordinates widened) and u32 indices, checked on the way (shapes, dtypes, index
//!   ranges, finite coordinates). A NumPy array handed in can be changed or freed by
//!   Python code at any time, including from another thread while the GIL is released,
//!   so the core never reads it in place. The one exception is `volume(check=False)`
//!   (`volume.rs`), which reads C-contiguous float64 and integer arrays in place, with the
//!   GIL held throughout.
//! - Outputs are NumPy arrays that own Rust's buffers (`into_pyarray`: no copy), or
//!   read-only views of a mesh's own storage (`Mesh.vertices`, `Mesh.faces`).
//! - Every computation runs with the GIL released (`Python::detach`).
//! - Every error is a Python exception with the command's message: [`errors`].

mod batch;
mod below;
mod check;
mod convert;
mod cutfill;
mod dict;
mod errors;
mod grid;
mod hull;
mod intersect;
mod load;
mod measures;
mod mesh;
mod polygon;
mod properties;
mod section;
mod shell;
mod timings;
mod units;
mod volume;

use pyo3::prelude::*;

#[pymodule]
fn _meshvol(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MeshError", py.get_type::<errors::MeshError>())?;
    m.add("ReadError", py.get_type::<errors::ReadError>())?;
    m.add("InvalidMeshError", py.get_type::<errors::InvalidMeshError>())?;
    m.add("LossyWriteError", py.get_type::<errors::LossyWriteError>())?;
    m.add("MeshWarning", py.get_type::<errors::MeshWarning>())?;
    m.add_class::<mesh::PyMesh>()?;
    m.add_class::<properties::PyMassProperties>()?;
    m.add_class::<check::PyCheck>()?;
    m.add_class::<shell::PyShell>()?;
    m.add_class::<grid::PyProfile>()?;
    m.add_class::<grid::PyUnion>()?;
    m.add_class::<polygon::PyAreaProperties>()?;
    m.add_class::<hull::PyHull>()?;
    m.add_class::<below::PyBelow>()?;
    m.add_class::<cutfill::PyCutFill>()?;
    m.add_class::<intersect::PyIntersection>()?;
    m.add_class::<section::PySection>()?;
    m.add_function(wrap_pyfunction!(load::load, m)?)?;
    m.add_function(wrap_pyfunction!(grid::union, m)?)?;
    m.add_function(wrap_pyfunction!(intersect::intersection, m)?)?;
    m.add_function(wrap_pyfunction!(intersect::intersections, m)?)?;
    m.add_function(wrap_pyfunction!(polygon::polygon_area, m)?)?;
    m.add_function(wrap_pyfunction!(hull::convex_hull, m)?)?;
    m.add_function(wrap_pyfunction!(hull::hull_volume, m)?)?;
    m.add_function(wrap_pyfunction!(cutfill::cutfill, m)?)?;
    m.add_function(wrap_pyfunction!(batch::_measure_files, m)?)?;
    m.add_function(wrap_pyfunction!(batch::_expand, m)?)?;
    m.add_function(wrap_pyfunction!(batch::_mesh_name_endings, m)?)?;
    m.add_function(wrap_pyfunction!(volume::volume, m)?)?;
    Ok(())
}
