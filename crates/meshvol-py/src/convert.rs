//! Python objects in: coordinate arrays, face arrays and polygon lists, checked and copied
//! into the core library's types.
//!
//! Anything NumPy's `asarray` accepts is accepted (arrays of any memory layout, lists,
//! tuples, trimesh's `TrackedArray`). Coordinates may be float64 (read as they are),
//! float32 (widened once, as the readers widen STL's floats) or float16 and integers
//! (converted by NumPy); faces may be any integer dtype. Nothing else is guessed at:
//! booleans, complex numbers, strings and `longdouble` (which float64 would round) are
//! refused with a message naming the dtype.

use crate::errors::{bad_argument, invalid};
use meshvol::{Faces, MeshError};
use meshvol_report::plane::PlaneArg;
use numpy::{
    Element, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

/// A shape as Python prints it: `(5,)`, `(5, 2)`.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => {
            let parts: Vec<String> = shape.iter().map(usize::to_string).collect();
            format!("({})", parts.join(", "))
        }
    }
}

/// `obj` as an aligned NumPy array: itself, an aligned copy of it (ndarray views need
/// aligned data; pickle protocol 5 buffers, as Dask sends arrays, and `frombuffer` at an
/// odd offset give unaligned ones), or `numpy.asarray(obj)`.
fn as_ndarray<'py>(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<Bound<'py, PyUntypedArray>> {
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        if array.getattr("flags")?.getattr("aligned")?.extract::<bool>()? {
            return Ok(array.clone());
        }
        let copy = obj.py().import("numpy")?.call_method1("array", (array,))?;
        return copy.cast_into::<PyUntypedArray>().map_err(|e| invalid(format!("{what}: {e}")));
    }
    let converted = obj
        .py()
        .import("numpy")?
        .call_method1("asarray", (obj,))
        .map_err(|e| invalid(format!("{what} cannot be read as an array: {e}")))?;
    converted.cast_into::<PyUntypedArray>().map_err(|e| invalid(format!("{what}: {e}")))
}

/// The rows of an (n, N) array as points, widened to f64.
fn rows<T: Element + Copy + Into<f64>, const N: usize>(
    array: &Bound<'_, PyArray2<T>>,
) -> PyResult<Vec<[f64; N]>> {
    let readonly = array.try_readonly().map_err(invalid)?;
    let view = readonly.as_array();
    if view.ncols() != N {
        return Err(invalid(format!("expected {N} columns, got {}", view.ncols())));
    }
    Ok(match view.as_slice() {
        Some(flat) => flat.chunks_exact(N).map(|c| std::array::from_fn(|k| c[k].into())).collect(),
        None => view.rows().into_iter().map(|r| std::array::from_fn(|k| r[k].into())).collect(),
    })
}

/// An (n, N) array of coordinates (`what` names it in errors), as f64 points. Finiteness
/// is left to the caller, whose error can say which point.
pub fn coordinates<const N: usize>(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; N]>> {
    let array = as_ndarray(obj, what)?;
    let shape = array.shape();
    if shape.len() != 2 || shape[1] != N {
        return Err(invalid(format!(
            "{what} must be an (n, {N}) array of coordinates; got shape {}",
            shape_text(shape)
        )));
    }
    if let Ok(a) = array.cast::<PyArray2<f64>>() {
        return rows::<f64, N>(a);
    }
    if let Ok(a) = array.cast::<PyArray2<f32>>() {
        return rows::<f32, N>(a);
    }
    let dtype = array.dtype();
    let convertible = matches!(dtype.kind(), b'f' | b'i' | b'u') && dtype.itemsize() <= 8;
    if !convertible {
        return Err(invalid(format!(
            "{what} must be numbers (float64, float32 or integers); got dtype {dtype}"
        )));
    }
    let widened = array.call_method1("astype", ("float64",))?;
    let widened = widened.cast::<PyArray2<f64>>().map_err(|e| invalid(format!("{what}: {e}")))?;
    rows::<f64, N>(widened)
}

/// The error for vertex index `value` of face `face`.
fn index_error(face: usize, value: i128, vertices: usize) -> PyErr {
    if value < 0 {
        invalid(format!(
            "face {face} uses vertex index {value}, which is negative (indices count from 0)"
        ))
    } else {
        let index = u64::try_from(value).unwrap_or(u64::MAX);
        invalid(MeshError::IndexOutOfRange { face, index, vertices })
    }
}

/// Vertex index `value` of face `face`, checked against the vertex count.
#[inline(always)]
fn vertex_index<T: Copy + Into<i128>>(face: usize, value: T, vertices: usize) -> PyResult<u32>
where
    u32: TryFrom<T>,
{
    match u32::try_from(value) {
        Ok(i) if (i as usize) < vertices => Ok(i),
        _ => Err(index_error(face, value.into(), vertices)),
    }
}

/// The faces of an (m, k) integer array: triangles for k = 3, else polygons of k vertices.
fn index_rows<T: Element + Copy + Into<i128>>(
    array: &Bound<'_, PyArray2<T>>,
    vertices: usize,
) -> PyResult<Faces>
where
    u32: TryFrom<T>,
{
    let readonly = array.try_readonly().map_err(invalid)?;
    let view = readonly.as_array();
    let (m, k) = view.dim();
    if k == 3 {
        let mut triangles = Vec::with_capacity(m);
        match view.as_slice() {
            Some(flat) => {
                for (face, t) in flat.chunks_exact(3).enumerate() {
                    let index = |x: T| vertex_index(face, x, vertices);
                    triangles.push([index(t[0])?, index(t[1])?, index(t[2])?]);
                }
            }
            None => {
                for (face, t) in view.rows().into_iter().enumerate() {
                    let index = |x: T| vertex_index(face, x, vertices);
                    triangles.push([index(t[0])?, index(t[1])?, index(t[2])?]);
                }
            }
        }
        return Ok(Faces::Triangles(triangles));
    }
    let mut indices = Vec::with_capacity(m * k);
    for (face, row) in view.rows().into_iter().enumerate() {
        for &x in row.iter() {
            indices.push(vertex_index(face, x, vertices)?);
        }
    }
    Ok(Faces::Polygons { offsets: (0..=m).map(|f| f * k).collect(), indices })
}

const FACES_FORM: &str = "faces must be an (m, 3) integer array of vertex indices, an (m, k) \
                          one for faces of k vertices, or a list of polygons (lists of indices)";

/// Faces from an integer array.
fn faces_of_array(array: &Bound<'_, PyUntypedArray>, vertices: usize) -> PyResult<Faces> {
    let shape = array.shape();
    if array.len() == 0 && shape.len() <= 2 {
        return Ok(Faces::Triangles(Vec::new()));
    }
    if shape.len() != 2 || shape[1] < 3 {
        return Err(invalid(format!("{FACES_FORM}; got shape {}", shape_text(shape))));
    }
    let dtype = array.dtype();
    let kind = dtype.kind();
    if !matches!(kind, b'i' | b'u') {
        return Err(invalid(format!("faces must be integer vertex indices; got dtype {dtype}")));
    }
    macro_rules! each_integer_type {
        ($($t:ty),*) => {
            $(
                if let Ok(a) = array.cast::<PyArray2<$t>>() {
                    return index_rows(a, vertices);
                }
            )*
        };
    }
    each_integer_type!(i64, i32, u32, u64, i16, u16, i8, u8);
    // Another byte order: let NumPy convert.
    let converted =
        array.call_method1("astype", (if kind == b'i' { "int64" } else { "uint64" },))?;
    if let Ok(a) = converted.cast::<PyArray2<i64>>() {
        return index_rows(a, vertices);
    }
    let a = converted.cast::<PyArray2<u64>>().map_err(|e| invalid(format!("faces: {e}")))?;
    index_rows(a, vertices)
}

/// Faces from a list of polygons of any sizes.
fn faces_of_polygons(obj: &Bound<'_, PyAny>, vertices: usize) -> PyResult<Faces> {
    let mut offsets = vec![0];
    let mut indices = Vec::new();
    let items = obj.try_iter().map_err(|_| invalid(FACES_FORM))?;
    for (face, item) in items.enumerate() {
        let polygon: Vec<i64> = item?.extract().map_err(|e| {
            invalid(format!("face {face} must be a sequence of integer vertex indices: {e}"))
        })?;
        if polygon.len() < 3 {
            return Err(invalid(MeshError::TooFewVertices { face, count: polygon.len() }));
        }
        for value in polygon {
            indices.push(vertex_index(face, value, vertices)?);
        }
        offsets.push(indices.len());
    }
    if offsets.windows(2).all(|w| w[1] - w[0] == 3) {
        let triangles = indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        return Ok(Faces::Triangles(triangles));
    }
    Ok(Faces::Polygons { offsets, indices })
}

/// Faces over `vertices` vertices: an integer array, or a list of polygons.
pub fn faces(obj: &Bound<'_, PyAny>, vertices: usize) -> PyResult<Faces> {
    if let Ok(array) = obj.cast::<PyUntypedArray>() {
        if array.ndim() == 1 && array.dtype().kind() == b'O' {
            return faces_of_polygons(obj, vertices); // NumPy's ragged arrays
        }
        return faces_of_array(&as_ndarray(obj, "faces")?, vertices);
    }
    let sequence = obj.cast::<PyList>().is_ok() || obj.cast::<PyTuple>().is_ok();
    if sequence && obj.len()? == 0 {
        return Ok(Faces::Triangles(Vec::new()));
    }
    // A regular nested list is an integer array; a ragged one (polygons of several
    // sizes) is not, and neither is a generator.
    let numpy = obj.py().import("numpy")?;
    if let Ok(array) = numpy.call_method1("asarray", (obj,)) {
        if let Ok(array) = array.cast::<PyUntypedArray>() {
            if array.ndim() == 2 && array.dtype().kind() != b'O' {
                return faces_of_array(array, vertices);
            }
        }
    }
    faces_of_polygons(obj, vertices)
}

/// A mesh-like object's `vertices` and `faces` (a trimesh.Trimesh, a meshvol.Mesh, …).
pub fn mesh_like<'py>(
    obj: &Bound<'py, PyAny>,
) -> PyResult<Option<(Bound<'py, PyAny>, Bound<'py, PyAny>)>> {
    if obj.hasattr("vertices")? && obj.hasattr("faces")? {
        Ok(Some((obj.getattr("vertices")?, obj.getattr("faces")?)))
    } else {
        Ok(None)
    }
}

/// A numeric argument (`what`) of exactly `shape`, from any array-like (a NumPy array,
/// a list, a tuple), as f64 values in row-major order. `form` says what it is, as the
/// error names it: "bounds must be ((x0, y0, z0), (x1, y1, z1)), an array-like of shape
/// (2, 3); got shape (3,)". Integers are widened; booleans, strings and complex numbers
/// are a TypeError naming the dtype.
pub fn float_argument(
    obj: &Bound<'_, PyAny>,
    what: &str,
    shape: &[usize],
    form: &str,
) -> PyResult<Vec<f64>> {
    let array = argument_array(obj, what, shape, form)?;
    let kind = array.dtype().kind();
    if !matches!(kind, b'f' | b'i' | b'u') || array.dtype().itemsize() > 8 {
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{what} must be numbers, {form}: an array-like of shape {}; got dtype {}",
            shape_text(shape),
            array.dtype()
        )));
    }
    array
        .call_method1("astype", ("float64",))?
        .call_method0("ravel")?
        .call_method0("tolist")?
        .extract()
}

/// A whole-number argument (`what`) of exactly `shape`, as `float_argument` but of an
/// integer dtype (floats that are whole numbers are accepted too: `(2.0, 3, 4)`).
pub fn int_argument(
    obj: &Bound<'_, PyAny>,
    what: &str,
    shape: &[usize],
    form: &str,
) -> PyResult<Vec<i64>> {
    let array = argument_array(obj, what, shape, form)?;
    let kind = array.dtype().kind();
    let type_error = || {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{what} must be whole numbers, {form}: an array-like of shape {}; got dtype {}",
            shape_text(shape),
            array.dtype()
        ))
    };
    match kind {
        b'i' | b'u' => {}
        b'f' => {
            let values: Vec<f64> =
                array.call_method0("ravel")?.call_method0("tolist")?.extract()?;
            if values.iter().all(|v| v.fract() == 0.0 && v.abs() < 9.0e15) {
                return Ok(values.iter().map(|&v| v as i64).collect());
            }
            return Err(type_error());
        }
        _ => return Err(type_error()),
    }
    let values: Vec<i128> = array.call_method0("ravel")?.call_method0("tolist")?.extract()?;
    Ok(values
        .iter()
        .map(|&v| i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX }))
        .collect())
}

/// `obj` as a NumPy array of `shape`; a ValueError naming `what` and the shape expected
/// otherwise.
fn argument_array<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    shape: &[usize],
    form: &str,
) -> PyResult<Bound<'py, PyUntypedArray>> {
    let expected = shape_text(shape);
    let array = obj.py().import("numpy")?.call_method1("asarray", (obj,)).map_err(|e| {
        crate::errors::bad_argument(format!(
            "{what} must be {form}, an array-like of shape {expected}; it cannot be read as an \
             array: {e}"
        ))
    })?;
    let array = array
        .cast_into::<PyUntypedArray>()
        .map_err(|e| crate::errors::bad_argument(e.to_string()))?;
    if array.shape() != shape || array.dtype().kind() == b'O' {
        let got = if array.dtype().kind() == b'O' {
            "a ragged or non-numeric sequence".to_string()
        } else {
            format!("shape {}", shape_text(array.shape()))
        };
        return Err(crate::errors::bad_argument(format!(
            "{what} must be {form}, an array-like of shape {expected}; got {got}"
        )));
    }
    Ok(array)
}

/// Three numbers (a vector argument).
pub fn vector3(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<[f64; 3]> {
    let v = float_argument(obj, what, &[3], "(x, y, z)")?;
    Ok([v[0], v[1], v[2]])
}

/// A box argument: (min corner, max corner), as a (2, 3) array-like.
pub fn bounds(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<([f64; 3], [f64; 3])> {
    let v = float_argument(obj, what, &[2, 3], "((x0, y0, z0), (x1, y1, z1))")?;
    Ok(([v[0], v[1], v[2]], [v[3], v[4], v[5]]))
}

/// A plane argument: text in any form the command's `--plane` takes ('z=H', 'x=H',
/// 'y=H', 'nx,ny,nz,d', 'px,py,pz,nx,ny,nz', read by its parser), a (2, 3) array-like (a
/// point, a normal), or four numbers (nx, ny, nz, d) for n·x = d: what `Mesh.section`
/// and `Mesh.below` take, as `meshvol section --plane` and `meshvol below --plane` do.
pub fn plane_arg(plane: &Bound<'_, PyAny>) -> PyResult<PlaneArg> {
    const FORM: &str =
        "plane must be 'z=H' ('x=H', 'y=H'), [point, normal] (a (2, 3) array-like), \
                        or (nx, ny, nz, d)";
    let arg = if let Ok(text) = plane.extract::<String>() {
        text.parse::<PlaneArg>().map_err(bad_argument)?
    } else {
        let numpy = plane.py().import("numpy")?;
        let size: usize = numpy
            .call_method1("size", (plane,))
            .and_then(|s| s.extract())
            .map_err(|_| bad_argument(FORM))?;
        if size == 4 {
            let v = crate::convert::float_argument(plane, "plane", &[4], "(nx, ny, nz, d)")?;
            PlaneArg::NormalOffset { normal: [v[0], v[1], v[2]], d: v[3] }
        } else {
            let v = crate::convert::float_argument(plane, "plane", &[2, 3], "[point, normal]")?;
            PlaneArg::PointNormal { point: [v[0], v[1], v[2]], normal: [v[3], v[4], v[5]] }
        }
    };
    Ok(arg)
}
