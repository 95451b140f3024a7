//! Binary PLY bodies (either byte order): records packed in header order, no padding.
//!
//! A vertex element of fixed record size is read in parallel over fixed chunks of
//! records. A face element is first read as if every face had the vertex count of the
//! first one (a fixed record size, in parallel); when a face differs, it is read again
//! record by record. Strips are read record by record (files with strips are small and
//! old). Errors name the byte and the element instance.

use meshvol::{Faces, Point};
use rayon::prelude::*;

use super::body::{self, Body, Layout, STRIP_END};
use super::header::{Element, Header, Kind, Scalar};
use crate::error::{Location, ParseError};

/// Reads `N` bytes at `at`; the caller guarantees they are in range.
#[inline]
fn array<const N: usize>(bytes: &[u8], at: usize) -> [u8; N] {
    let mut out = [0; N];
    out.copy_from_slice(&bytes[at..at + N]);
    out
}

/// The value of scalar type `t` at byte `at` (in range), as `f64`.
#[inline]
fn read_f64(bytes: &[u8], at: usize, t: Scalar, big: bool) -> f64 {
    macro_rules! get {
        ($ty:ty, $n:literal) => {{
            let raw = array::<$n>(bytes, at);
            if big {
                <$ty>::from_be_bytes(raw)
            } else {
                <$ty>::from_le_bytes(raw)
            }
        }};
    }
    match t {
        Scalar::I8 => f64::from(bytes[at] as i8),
        Scalar::U8 => f64::from(bytes[at]),
        Scalar::I16 => f64::from(get!(i16, 2)),
        Scalar::U16 => f64::from(get!(u16, 2)),
        Scalar::I32 => f64::from(get!(i32, 4)),
        Scalar::U32 => f64::from(get!(u32, 4)),
        Scalar::F32 => f64::from(get!(f32, 4)),
        Scalar::F64 => get!(f64, 8),
    }
}

/// The value of integer type `t` at byte `at` (in range).
#[inline]
fn read_int(bytes: &[u8], at: usize, t: Scalar, big: bool) -> i64 {
    match t {
        Scalar::I8 => i64::from(bytes[at] as i8),
        Scalar::U8 => i64::from(bytes[at]),
        Scalar::I16 | Scalar::U16 | Scalar::I32 | Scalar::U32 => read_f64(bytes, at, t, big) as i64,
        // Only integer types reach here (checked in the header).
        Scalar::F32 | Scalar::F64 => -1,
    }
}

/// Records per parallel work item.
const RECORD_CHUNK: usize = 64 * 1024;

/// Reads a binary body.
pub(super) fn read(
    bytes: &[u8],
    header: &Header,
    layout: &Layout,
    big: bool,
    warnings: &mut Vec<String>,
) -> Result<Body, ParseError> {
    let mut pos = header.body;
    let mut positions = Vec::new();
    let mut faces = BinaryFaces::default();
    let mut strips = Vec::new();
    for (e, element) in header.elements.iter().enumerate() {
        pos = match (layout.vertex, layout.face, layout.strips) {
            (Some((v, xyz)), _, _) if v == e => {
                let (p, end) = binary_vertices(bytes, pos, element, xyz, big)?;
                positions = p;
                end
            }
            (_, Some((f, list)), _) if f == e => {
                let indexed = Indexed { element, list, vertices: layout.vertices };
                let (read, end) = binary_faces(bytes, pos, indexed, big)?;
                faces = read;
                end
            }
            (_, _, Some((s, list))) if s == e => {
                let indexed = Indexed { element, list, vertices: layout.vertices };
                binary_strips(bytes, pos, indexed, big, &mut strips)?
            }
            _ => skip_binary(bytes, pos, element, big)?,
        };
    }
    if pos < bytes.len() {
        warnings.push(format!(
            "{} bytes after the declared elements were ignored (from byte {pos})",
            bytes.len() - pos
        ));
    }
    let BinaryFaces { indices, triangles, uniform, offsets, skipped, first_skipped } = faces;
    body::warn_skipped(skipped, first_skipped.map(|f| format!("face {f}")), warnings);
    let faces = match uniform {
        Some(3) => Faces::Triangles(triangles),
        Some(k) => {
            let count = indices.len().checked_div(k).unwrap_or(0);
            body::faces(indices, (1..=count).map(|f| f * k), false)
        }
        None => {
            let all_triangles = offsets.windows(2).all(|w| w[1] - w[0] == 3);
            body::faces(indices, offsets.into_iter().skip(1), all_triangles)
        }
    };
    Ok(Body { positions, faces, strips })
}

/// An element with a list of vertex indices (faces or strips).
#[derive(Clone, Copy)]
struct Indexed<'a> {
    element: &'a Element,
    /// The list property.
    list: usize,
    /// The vertex count, which every index must be below.
    vertices: usize,
}

/// Reads the `tristrips` element into `strips` (see [`Body::strips`]); returns where
/// it ends. Only -1 may stand between strips; any other index must name a vertex.
fn binary_strips(
    bytes: &[u8],
    pos: usize,
    Indexed { element, list, vertices }: Indexed<'_>,
    big: bool,
    strips: &mut Vec<u32>,
) -> Result<usize, ParseError> {
    let Kind::List { item, .. } = element.properties[list].kind else {
        return Err(ParseError::line(element.line, "the strip index property is not a list"));
    };
    let mut at = pos;
    for instance in 0..element.count {
        let (end, offset, n) = list_of_record(bytes, at, element, instance, big, list)?;
        at = end;
        for j in 0..n {
            let at = offset + j * item.size();
            match read_int(bytes, at, item, big) {
                -1 => strips.push(STRIP_END),
                index if index >= 0 && (index as u64) < vertices as u64 => {
                    strips.push(index as u32)
                }
                index => {
                    return Err(ParseError::new(
                        Some(Location::Byte(at as u64)),
                        format!(
                            "{} {instance}: vertex index {index} is out of range: the file \
                             has {vertices} vertices",
                            element.name
                        ),
                    ))
                }
            }
        }
        strips.push(STRIP_END);
    }
    Ok(at)
}

/// The end of `count` records of `size` bytes from `pos`, if the file holds them.
fn fixed_end(
    bytes: &[u8],
    pos: usize,
    element: &Element,
    size: usize,
) -> Result<usize, ParseError> {
    usize::try_from(element.count)
        .ok()
        .and_then(|n| n.checked_mul(size))
        .and_then(|n| n.checked_add(pos))
        .filter(|&end| end <= bytes.len())
        .ok_or_else(|| {
            ParseError::new(
                Some(Location::Byte(bytes.len() as u64)),
                format!(
                    "truncated: the header declares {} {} elements of {size} bytes from byte \
                     {pos}, but the file has {} bytes",
                    element.count,
                    element.name,
                    bytes.len()
                ),
            )
        })
}

/// Walks one binary record of a variable-size element from `pos`; calls
/// `visit(property, offset, length)` for each property (length 1 for a scalar, the item
/// count for a list, whose items start at `offset`). Returns the record's end.
#[inline]
fn walk_record(
    bytes: &[u8],
    pos: usize,
    element: &Element,
    instance: u64,
    big: bool,
    mut visit: impl FnMut(usize, usize, usize),
) -> Result<usize, ParseError> {
    let mut at = pos;
    let short = |at: usize| {
        ParseError::new(
            Some(Location::Byte(at as u64)),
            format!("truncated: the file ends inside {} {instance}", element.name),
        )
    };
    for (p, property) in element.properties.iter().enumerate() {
        match property.kind {
            Kind::Scalar(s) => {
                let end = at + s.size();
                if end > bytes.len() {
                    return Err(short(at));
                }
                visit(p, at, 1);
                at = end;
            }
            Kind::List { count, item } => {
                let items_at = at + count.size();
                if items_at > bytes.len() {
                    return Err(short(at));
                }
                let n = read_int(bytes, at, count, big);
                let end = usize::try_from(n)
                    .ok()
                    .and_then(|n| n.checked_mul(item.size()))
                    .and_then(|b| b.checked_add(items_at))
                    .filter(|&end| end <= bytes.len())
                    .ok_or_else(|| {
                        ParseError::new(
                            Some(Location::Byte(at as u64)),
                            format!(
                                "{} {instance}: list '{}' of {n} items runs past the end of \
                                 the file",
                                element.name, property.name
                            ),
                        )
                    })?;
                visit(p, items_at, n as usize);
                at = end;
            }
        }
    }
    Ok(at)
}

/// Walks one record from `pos`; returns its end, and where the items of its list
/// property `list` start and how many there are.
fn list_of_record(
    bytes: &[u8],
    pos: usize,
    element: &Element,
    instance: u64,
    big: bool,
    list: usize,
) -> Result<(usize, usize, usize), ParseError> {
    let mut span = (0, 0);
    let end = walk_record(bytes, pos, element, instance, big, |p, offset, n| {
        if p == list {
            span = (offset, n);
        }
    })?;
    Ok((end, span.0, span.1))
}

/// Skips an element's records.
fn skip_binary(
    bytes: &[u8],
    pos: usize,
    element: &Element,
    big: bool,
) -> Result<usize, ParseError> {
    if let Some(size) = element.fixed_size() {
        return fixed_end(bytes, pos, element, size);
    }
    // Each record holds at least one list count, so this loop ends within the file.
    let mut at = pos;
    for i in 0..element.count {
        at = walk_record(bytes, at, element, i, big, |_, _, _| {})?;
    }
    Ok(at)
}

/// The error for a non-finite coordinate.
fn non_finite(vertex: usize, axis: usize, value: f64, at: usize) -> ParseError {
    ParseError::new(
        Some(Location::Byte(at as u64)),
        format!("vertex {vertex}: non-finite coordinate {value} ({})", ["x", "y", "z"][axis]),
    )
}

/// Reads the vertex element: returns the positions and where the element ends.
fn binary_vertices(
    bytes: &[u8],
    pos: usize,
    element: &Element,
    xyz: [usize; 3],
    big: bool,
) -> Result<(Vec<Point>, usize), ParseError> {
    let types = xyz.map(|p| match element.properties[p].kind {
        Kind::Scalar(s) => s,
        // The layout admits scalars only.
        Kind::List { item, .. } => item,
    });
    let Some(size) = element.fixed_size() else {
        // Lists in the vertex element: record by record.
        let mut positions = Vec::new();
        let mut at = pos;
        for i in 0..element.count {
            let mut p = [0.0; 3];
            at = walk_record(bytes, at, element, i, big, |prop, offset, _| {
                for k in 0..3 {
                    if prop == xyz[k] {
                        p[k] = read_f64(bytes, offset, types[k], big);
                    }
                }
            })?;
            if let Some(k) = p.iter().position(|c| !c.is_finite()) {
                return Err(non_finite(i as usize, k, p[k], at));
            }
            positions.push(p);
        }
        return Ok((positions, at));
    };
    let end = fixed_end(bytes, pos, element, size)?;
    let offsets = xyz.map(|p| {
        element.properties[..p]
            .iter()
            .map(|q| match q.kind {
                Kind::Scalar(s) => s.size(),
                Kind::List { .. } => 0,
            })
            .sum::<usize>()
    });
    let n = (end - pos) / size;
    let mut positions = vec![[0.0; 3]; n];
    let bad = positions
        .par_chunks_mut(RECORD_CHUNK)
        .zip(bytes[pos..end].par_chunks(RECORD_CHUNK * size))
        .enumerate()
        .map(|(c, (out, records))| {
            for (i, (p, record)) in out.iter_mut().zip(records.chunks_exact(size)).enumerate() {
                for k in 0..3 {
                    p[k] = read_f64(record, offsets[k], types[k], big);
                }
                if let Some(k) = p.iter().position(|c| !c.is_finite()) {
                    return Some((c * RECORD_CHUNK + i, k, p[k]));
                }
            }
            None
        })
        .find_first(Option::is_some)
        .flatten();
    if let Some((vertex, k, value)) = bad {
        return Err(non_finite(vertex, k, value, pos + vertex * size + offsets[k]));
    }
    Ok((positions, end))
}

/// The faces of a binary face element.
#[derive(Default)]
struct BinaryFaces {
    indices: Vec<u32>,
    /// The faces when every one is a triangle (`uniform` is `Some(3)`).
    triangles: Vec<[u32; 3]>,
    /// `Some(k)`: every face has k vertices. `None`: faces end at `offsets`.
    uniform: Option<usize>,
    offsets: Vec<usize>,
    skipped: usize,
    first_skipped: Option<u64>,
}

/// Why the parallel, fixed-size reading of faces stopped.
enum FaceProblem {
    /// A face with another vertex count: the records are not of one size.
    NotUniform,
    /// A face index that is negative or not below the vertex count.
    BadIndex { face: usize, index: i64, at: usize },
}

fn bad_index(face: u64, index: i64, vertices: usize, at: usize) -> ParseError {
    ParseError::new(
        Some(Location::Face(face as usize)),
        format!(
            "vertex index {index} is out of range: the file has {vertices} vertices (byte {at})"
        ),
    )
}

/// Reads the face element: returns its faces and where it ends.
fn binary_faces(
    bytes: &[u8],
    pos: usize,
    Indexed { element, list, vertices }: Indexed<'_>,
    big: bool,
) -> Result<(BinaryFaces, usize), ParseError> {
    let Kind::List { count: count_type, item } = element.properties[list].kind else {
        return Err(ParseError::line(element.line, "the face index property is not a list"));
    };
    // Try one record size for all: the other properties scalars, and every face with the
    // vertex count of the first.
    let others_are_scalars = element
        .properties
        .iter()
        .enumerate()
        .all(|(p, q)| p == list || matches!(q.kind, Kind::Scalar(_)));
    if others_are_scalars && element.count > 0 {
        let before: usize = element.properties[..list]
            .iter()
            .map(|q| if let Kind::Scalar(s) = q.kind { s.size() } else { 0 })
            .sum();
        let after: usize = element.properties[list + 1..]
            .iter()
            .map(|q| if let Kind::Scalar(s) = q.kind { s.size() } else { 0 })
            .sum();
        let first = pos + before;
        if first + count_type.size() <= bytes.len() {
            let k = read_int(bytes, first, count_type, big);
            if let Ok(k @ 3..=1024) = usize::try_from(k) {
                let size = before + count_type.size() + k * item.size() + after;
                if let Ok(end) = fixed_end(bytes, pos, element, size) {
                    let n = (end - pos) / size;
                    // Triangles go straight into the mesh's triangle array.
                    let mut triangles: Vec<[u32; 3]> = Vec::new();
                    let mut polygons: Vec<u32> = Vec::new();
                    let indices: &mut [u32] = if k == 3 {
                        triangles = vec![[0; 3]; n];
                        triangles.as_flattened_mut()
                    } else {
                        polygons = vec![0; n * k];
                        &mut polygons
                    };
                    let problem = indices
                        .par_chunks_mut(RECORD_CHUNK * k)
                        .zip(bytes[pos..end].par_chunks(RECORD_CHUNK * size))
                        .enumerate()
                        .map(|(c, (out, records))| {
                            for (i, (face, record)) in
                                out.chunks_exact_mut(k).zip(records.chunks_exact(size)).enumerate()
                            {
                                if read_int(record, before, count_type, big) != k as i64 {
                                    return Some(FaceProblem::NotUniform);
                                }
                                let items = before + count_type.size();
                                for (j, slot) in face.iter_mut().enumerate() {
                                    let at = items + j * item.size();
                                    let index = read_int(record, at, item, big);
                                    if index < 0 || index as u64 >= vertices as u64 {
                                        let face = c * RECORD_CHUNK + i;
                                        return Some(FaceProblem::BadIndex { face, index, at });
                                    }
                                    *slot = index as u32;
                                }
                            }
                            None
                        })
                        .find_first(Option::is_some)
                        .flatten();
                    match problem {
                        None => {
                            let faces = BinaryFaces {
                                indices: polygons,
                                triangles,
                                uniform: Some(k),
                                ..BinaryFaces::default()
                            };
                            return Ok((faces, end));
                        }
                        Some(FaceProblem::BadIndex { face, index, at }) => {
                            return Err(bad_index(
                                face as u64,
                                index,
                                vertices,
                                pos + face * size + at,
                            ))
                        }
                        Some(FaceProblem::NotUniform) => {}
                    }
                }
            }
        }
    }

    // Record by record.
    let remaining = bytes.len().saturating_sub(pos);
    let mut faces = BinaryFaces {
        indices: Vec::with_capacity(remaining / item.size().max(1) / 2),
        offsets: vec![0],
        ..BinaryFaces::default()
    };
    let mut at = pos;
    for f in 0..element.count {
        let (end, offset, n) = list_of_record(bytes, at, element, f, big, list)?;
        at = end;
        if n < 3 {
            faces.skipped += 1;
            faces.first_skipped.get_or_insert(f);
            continue;
        }
        for j in 0..n {
            let at = offset + j * item.size();
            let index = read_int(bytes, at, item, big);
            if index < 0 || index as u64 >= vertices as u64 {
                return Err(bad_index(f, index, vertices, at));
            }
            faces.indices.push(index as u32);
        }
        faces.offsets.push(faces.indices.len());
    }
    Ok((faces, at))
}
