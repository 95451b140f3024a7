//! `meshvol.volume(vertices, faces, check=...)`: the volume alone, reading NumPy arrays
//! in place where it can.
//!
//! Unchecked (`check=False`), float64 (n, 3) vertices and (m, 3) int32, int64, uint32
//! or uint64 faces, C-contiguous, aligned and in native byte order, are borrowed
//! (`PyReadonlyArray`) and read in place by the core's volume pass
//! ([`meshvol::triangles_signed_volume`]): nothing is copied. Any other input (float32
//! or integer coordinates, other layouts, polygon faces, lists) is copied into a
//! [`meshvol::Mesh`] as `Mesh(vertices, faces)` does. Checked (the default), the volume
//! is that of the checked solid, as `Mesh(vertices, faces).mass_properties()` gives it
//! (with its warnings).
//!
//! The borrowed path keeps the GIL while it reads (unlike every other computation of
//! the package, which copies its input and releases it): with the GIL held no Python
//! code can write the arrays meanwhile. It takes a millisecond or two per million
//! triangles.

use crate::errors::invalid;
use crate::mesh::{from_arrays, PyMesh};
use meshvol::volume::VertexIndex;
use meshvol::Point;
use numpy::{Element, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// The signed volume of a triangle or polygon mesh given as arrays, and a bound on its
/// rounding error: (volume, volume_error_bound).
///
/// vertices is an (n, 3) coordinate array and faces an (m, 3) index array (or (m, k),
/// or a list of polygons), as Mesh(vertices, faces) takes them. check=True (the default)
/// measures the checked solid (turned outward, cavities subtracted, holes capped: its
/// volume is never negative), the .volume and .volume_error_bound of
/// Mesh(vertices, faces).mass_properties() (with its warnings). check=False measures the
/// surface as wound (negative when wound inward), in one pass, and reads float64 vertices with int32/int64/uint32/uint64
/// (m, 3) faces in place when both are C-contiguous: no copy is made (other inputs are
/// copied once). Its result has the same bits as
/// Mesh(vertices, faces).mass_properties(check=False)'s signed_volume and
/// volume_error_bound.
///
/// >>> import numpy as np, meshvol
/// >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
/// >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)
/// >>> volume, bound = meshvol.volume(v, f, check=False)
/// >>> volume == 1 / 6, bound < 1e-15
/// (True, True)
/// >>> meshvol.volume(v, f)[0] == 1 / 6
/// True
#[pyfunction]
#[pyo3(signature = (vertices, faces, check = true))]
pub fn volume(
    py: Python<'_>,
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
    check: bool,
) -> PyResult<(f64, f64)> {
    if check {
        let mesh = Bound::new(py, PyMesh::from(from_arrays(py, vertices, faces)?))?;
        let mp = mesh.call_method0("mass_properties")?;
        return Ok((
            mp.getattr("volume")?.extract()?,
            mp.getattr("volume_error_bound")?.extract()?,
        ));
    }
    if let Some(result) = borrowed(vertices, faces) {
        let v = result.map_err(invalid)?;
        return Ok((v.signed_volume, v.volume_error_bound));
    }
    let mesh = from_arrays(py, vertices, faces)?;
    let v = py.detach(|| meshvol::signed_volume(&mesh));
    Ok((v.signed_volume, v.volume_error_bound))
}

/// An (n, N) array's data in place, when it is of type `T`, C-contiguous and aligned.
fn rows<'py, T: Element, const N: usize>(
    array: &Bound<'py, PyAny>,
) -> Option<PyReadonlyArray2<'py, T>> {
    let array = array.cast::<PyArray2<T>>().ok()?;
    if !array.is_c_contiguous() || array.shape()[1] != N {
        return None;
    }
    let readonly = array.try_readonly().ok()?;
    readonly.as_slice().ok()?;
    Some(readonly)
}

/// The volume of borrowed arrays; `None` when they cannot be read in place.
fn borrowed(
    vertices: &Bound<'_, PyAny>,
    faces: &Bound<'_, PyAny>,
) -> Option<Result<meshvol::Volume, meshvol::MeshError>> {
    let positions = rows::<f64, 3>(vertices)?;
    let positions: &[Point] = positions.as_slice().ok()?.as_chunks::<3>().0;
    fn run<I: Element + VertexIndex>(
        positions: &[Point],
        faces: &Bound<'_, PyAny>,
    ) -> Option<Result<meshvol::Volume, meshvol::MeshError>> {
        let faces = rows::<I, 3>(faces)?;
        let triangles = faces.as_slice().ok()?.as_chunks::<3>().0;
        Some(meshvol::triangles_signed_volume(positions, triangles))
    }
    run::<i64>(positions, faces)
        .or_else(|| run::<i32>(positions, faces))
        .or_else(|| run::<u32>(positions, faces))
        .or_else(|| run::<u64>(positions, faces))
}
