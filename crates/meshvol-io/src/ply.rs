//! PLY (the Stanford polygon format): ASCII, binary little-endian and binary big-endian.
//!
//! ```text
//! ply
//! format binary_little_endian 1.0      # or ascii 1.0, binary_big_endian 1.0
//! comment written by ...               # comment and obj_info lines anywhere in the header
//! element vertex 8
//! property float x                     # any scalar type, any order, other properties too
//! property float y
//! property float z
//! property uchar red
//! element face 6
//! property list uchar int vertex_indices   # or vertex_index; any integer types
//! element edge 12                      # other elements: skipped
//! property int vertex1
//! property int vertex2
//! end_header
//! ...data, element by element in header order...
//! ```
//!
//! Scalar types: `char`/`int8`, `uchar`/`uint8`, `short`/`int16`, `ushort`/`uint16`,
//! `int`/`int32`, `uint`/`uint32`, `float`/`float32`, `double`/`float64`. Header lines may
//! end with CRLF; blank header lines are skipped; any other header line is an error.
//!
//! Read: the element named `vertex` (its `x`, `y`, `z` properties, of any scalar type;
//! every coordinate must be finite) and the element named `face` (its list
//! `vertex_indices`, or `vertex_index`, of an integer type; indices count from 0). Faces
//! of three or more vertices keep their size ([`meshvol::Faces::Polygons`] unless every
//! face is a triangle); faces of fewer vertices hold no area and are skipped with a
//! warning. Every other element and property is skipped. A file without a `face`
//! element (a point cloud) reads as a mesh with no faces. Data after the last declared
//! element is ignored with a warning.
//!
//! ASCII data: one element instance per line, values separated by blanks; blank lines
//! are skipped. A line with fewer values than its element's properties is an error; one
//! with more (VCG/MeshLab writes some) is read, and a warning counts such lines. Binary
//! data: the values packed in header order, no padding.
//!
//! Counts in the header are never trusted for allocation: a binary element of fixed size
//! must fit the bytes that remain before anything is reserved, and ASCII elements are
//! counted in the file's lines first. Errors say where: the line (ASCII), or the byte and
//! element instance (binary).
//!
//! # Speed
//!
//! ASCII bodies are cut into chunks at line ends, the lines of each chunk counted (so
//! each chunk knows which element its lines belong to), then parsed, both in parallel.
//! A binary vertex element of fixed record size is read in parallel over fixed chunks of
//! records. A binary face element is first read as if every face had the vertex count of
//! the first one (a fixed record size, in parallel); when a face differs, it is read
//! again record by record.

use meshvol::{Faces, Mesh, Point};
use rayon::prelude::*;

use crate::error::{Location, ParseError};
use crate::text::{self, NumberError};

/// How the data after the header is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Encoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn from_name(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

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

/// A property: a scalar, or a list of scalars preceded by its length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    properties: Vec<Property>,
    /// The header line that declared it.
    line: u64,
}

impl Element {
    /// The bytes of one binary record, when no property is a list.
    fn fixed_size(&self) -> Option<usize> {
        self.properties.iter().try_fold(0usize, |sum, p| match p.kind {
            Kind::Scalar(s) => Some(sum + s.size()),
            Kind::List { .. } => None,
        })
    }

    fn property(&self, name: &str) -> Option<usize> {
        self.properties.iter().position(|p| p.name == name)
    }
}

#[derive(Debug)]
struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Where the data starts.
    body: usize,
}

/// Which elements and properties hold the geometry.
struct Layout {
    /// The vertex element and the indices of its `x`, `y`, `z` properties.
    vertex: Option<(usize, [usize; 3])>,
    /// The face element and the index of its vertex index list.
    face: Option<(usize, usize)>,
    /// The declared vertex count (what face indices are checked against).
    vertices: usize,
}

/// Whether the bytes start with the PLY magic line.
pub(crate) fn looks_like_ply(bytes: &[u8]) -> bool {
    bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")
}

/// Parses a PLY file; returns its encoding and mesh.
pub(crate) fn read(
    bytes: &[u8],
    warnings: &mut Vec<String>,
) -> Result<(Encoding, Mesh), ParseError> {
    let header = parse_header(bytes)?;
    let layout = layout(&header)?;
    let mesh = match header.encoding {
        Encoding::Ascii => read_ascii(bytes, &header, &layout, warnings, ASCII_CHUNK)?,
        Encoding::BinaryLittleEndian => read_binary(bytes, &header, &layout, false, warnings)?,
        Encoding::BinaryBigEndian => read_binary(bytes, &header, &layout, true, warnings)?,
    };
    Ok((header.encoding, mesh))
}

fn parse_header(bytes: &[u8]) -> Result<Header, ParseError> {
    let mut pos = 0usize;
    let mut line_no = 0u64;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if pos >= bytes.len() {
            return Err(ParseError::line(
                line_no.max(1),
                "the header ends without 'end_header' (the file is cut short, or not PLY)",
            ));
        }
        let end = memchr::memchr(b'\n', &bytes[pos..]).map_or(bytes.len(), |i| pos + i);
        let line = &bytes[pos..end];
        pos = (end + 1).min(bytes.len());
        line_no += 1;
        let words: Vec<&[u8]> =
            line.split(|&b| text::is_blank(b)).filter(|w| !w.is_empty()).collect();
        let bad = |message: String| ParseError::line(line_no, message);
        if line_no == 1 {
            if words.as_slice() != [b"ply"] {
                return Err(bad("expected 'ply' on the first line".into()));
            }
            continue;
        }
        let Some(&keyword) = words.first() else { continue };
        match keyword {
            b"format" => {
                encoding = Some(match words.get(1).copied() {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::BinaryLittleEndian,
                    Some(b"binary_big_endian") => Encoding::BinaryBigEndian,
                    other => {
                        return Err(bad(format!(
                            "unknown format '{}' (ascii, binary_little_endian or \
                             binary_big_endian)",
                            text::show(other.unwrap_or_default())
                        )))
                    }
                });
                if !matches!(words.get(2).copied(), Some(b"1.0" | b"1")) {
                    return Err(bad(format!(
                        "unsupported PLY version '{}' (1.0 is read)",
                        text::show(words.get(2).copied().unwrap_or_default())
                    )));
                }
            }
            b"comment" | b"obj_info" => {}
            b"element" => {
                let (Some(name), Some(count), 3) = (words.get(1), words.get(2), words.len()) else {
                    return Err(bad("expected 'element NAME COUNT'".into()));
                };
                let count = std::str::from_utf8(count)
                    .ok()
                    .and_then(|c| c.parse::<u64>().ok())
                    .ok_or_else(|| bad(format!("invalid element count '{}'", text::show(count))))?;
                elements.push(Element {
                    name: text::show(name),
                    count,
                    properties: Vec::new(),
                    line: line_no,
                });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(bad("'property' before any 'element'".into()));
                };
                let type_of = |w: &[u8]| {
                    Scalar::from_name(w)
                        .ok_or_else(|| bad(format!("unknown property type '{}'", text::show(w))))
                };
                let (kind, name) = match words.as_slice() {
                    [_, b"list", count, item, name] => {
                        let count = type_of(count)?;
                        if !count.is_integer() {
                            return Err(bad("a list's count type must be an integer type".into()));
                        }
                        (Kind::List { count, item: type_of(item)? }, name)
                    }
                    [_, t, name] if *t != b"list" => (Kind::Scalar(type_of(t)?), name),
                    _ => {
                        return Err(bad(
                            "expected 'property TYPE NAME' or 'property list COUNT_TYPE \
                             ITEM_TYPE NAME'"
                                .into(),
                        ))
                    }
                };
                element.properties.push(Property { name: text::show(name), kind });
            }
            b"end_header" => break,
            other => return Err(bad(format!("unknown header keyword '{}'", text::show(other)))),
        }
    }
    let Some(encoding) = encoding else {
        return Err(ParseError::line(2, "the header has no 'format' line"));
    };
    Ok(Header { encoding, elements, body: pos })
}

fn layout(header: &Header) -> Result<Layout, ParseError> {
    let mut layout = Layout { vertex: None, face: None, vertices: 0 };
    let find = |name: &str| header.elements.iter().position(|e| e.name == name);
    if let Some(v) = find("vertex") {
        let element = &header.elements[v];
        let mut xyz = [0; 3];
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let p = element.property(axis).ok_or_else(|| {
                ParseError::line(
                    element.line,
                    format!("the vertex element has no property '{axis}'"),
                )
            })?;
            if !matches!(element.properties[p].kind, Kind::Scalar(_)) {
                return Err(ParseError::line(
                    element.line,
                    format!("vertex property '{axis}' is a list, not a number"),
                ));
            }
            xyz[k] = p;
        }
        layout.vertices = u32::try_from(element.count).map_err(|_| {
            ParseError::line(
                element.line,
                format!("{} vertices do not fit 32-bit indices", element.count),
            )
        })? as usize;
        layout.vertex = Some((v, xyz));
    }
    if let Some(f) = find("face") {
        let element = &header.elements[f];
        let list = element
            .property("vertex_indices")
            .or_else(|| element.property("vertex_index"))
            .ok_or_else(|| {
                ParseError::line(
                    element.line,
                    "the face element has no 'vertex_indices' (or 'vertex_index') list",
                )
            })?;
        match element.properties[list].kind {
            Kind::List { item, .. } if item.is_integer() => {}
            _ => {
                return Err(ParseError::line(
                    element.line,
                    format!(
                        "face property '{}' must be a list of an integer type",
                        element.properties[list].name
                    ),
                ))
            }
        }
        if layout.vertex.is_none() && element.count > 0 {
            return Err(ParseError::line(element.line, "faces, but no vertex element"));
        }
        layout.face = Some((f, list));
    }
    Ok(layout)
}

/// Builds the mesh from concatenated positions and faces.
fn mesh(
    positions: Vec<Point>,
    indices: Vec<u32>,
    face_ends: impl Iterator<Item = usize>,
    all_triangles: bool,
) -> Result<Mesh, ParseError> {
    let faces = if all_triangles {
        Faces::Triangles(indices.par_chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
    } else {
        Faces::Polygons { offsets: std::iter::once(0).chain(face_ends).collect(), indices }
    };
    Mesh::new(positions, faces).map_err(|e| ParseError::new(None, e.to_string()))
}

/// The warning for faces of fewer than three vertices.
fn warn_skipped(skipped: usize, first: Option<String>, warnings: &mut Vec<String>) {
    if skipped > 0 {
        warnings.push(format!(
            "skipped {skipped} faces with fewer than 3 vertices (the first at {})",
            first.unwrap_or_default()
        ));
    }
}

// ---------------------------------------------------------------------------------------
// Binary

/// Records per parallel work item.
const RECORD_CHUNK: usize = 64 * 1024;

/// Reads a binary body.
fn read_binary(
    bytes: &[u8],
    header: &Header,
    layout: &Layout,
    big: bool,
    warnings: &mut Vec<String>,
) -> Result<Mesh, ParseError> {
    let mut pos = header.body;
    let mut positions = Vec::new();
    let mut faces = BinaryFaces::default();
    for (e, element) in header.elements.iter().enumerate() {
        pos = match (layout.vertex, layout.face) {
            (Some((v, xyz)), _) if v == e => {
                let (p, end) = binary_vertices(bytes, pos, element, xyz, big)?;
                positions = p;
                end
            }
            (_, Some((f, list))) if f == e => {
                let (read, end) = binary_faces(bytes, pos, element, list, layout.vertices, big)?;
                faces = read;
                end
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
    warn_skipped(skipped, first_skipped.map(|f| format!("face {f}")), warnings);
    match uniform {
        Some(3) => Mesh::new(positions, Faces::Triangles(triangles))
            .map_err(|e| ParseError::new(None, e.to_string())),
        Some(k) => {
            let count = indices.len().checked_div(k).unwrap_or(0);
            mesh(positions, indices, (1..=count).map(|f| f * k), k == 3)
        }
        None => {
            let all_triangles = offsets.windows(2).all(|w| w[1] - w[0] == 3);
            mesh(positions, indices, offsets.into_iter().skip(1), all_triangles)
        }
    }
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
    element: &Element,
    list: usize,
    vertices: usize,
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
        let mut span = (0, 0);
        at = walk_record(bytes, at, element, f, big, |p, offset, n| {
            if p == list {
                span = (offset, n);
            }
        })?;
        let (offset, n) = span;
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

// ---------------------------------------------------------------------------------------
// ASCII

/// Target bytes per parallel chunk of an ASCII body.
const ASCII_CHUNK: usize = 1 << 20;

/// What an element's lines are read for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Vertex,
    Face,
    Skip,
}

/// The content lines `[first, end)` (counted over the whole body) that hold one element.
struct Span {
    end: u64,
    role: Role,
    element: usize,
}

/// What one chunk of an ASCII body gave.
#[derive(Default)]
struct AsciiChunk {
    positions: Vec<Point>,
    indices: Vec<u32>,
    /// The end of each face in `indices`.
    face_ends: Vec<usize>,
    skipped: usize,
    /// The offset of the first skipped face.
    first_skipped: Option<usize>,
    /// Lines with more values than their element's properties, and the first one.
    long_lines: usize,
    first_long: Option<usize>,
    error: Option<(usize, String)>,
}

/// Whether a line holds anything but blanks.
#[inline]
fn has_content(line: &[u8]) -> bool {
    line.iter().any(|&b| !text::is_blank(b))
}

/// Chunk boundaries at line starts, about `target` bytes apart.
fn line_boundaries(bytes: &[u8], start: usize, target: usize) -> Vec<usize> {
    let mut bounds = vec![start];
    let mut from = start.saturating_add(target);
    while from < bytes.len() {
        match memchr::memchr(b'\n', &bytes[from..]) {
            Some(i) if from + i + 1 < bytes.len() => {
                bounds.push(from + i + 1);
                from = (from + i + 1).saturating_add(target);
            }
            _ => break,
        }
    }
    bounds.push(bytes.len());
    bounds
}

/// Calls `f(start, end)` for each line of `bytes[start..end)` (without its newline).
#[inline]
fn for_each_line(bytes: &[u8], start: usize, end: usize, mut f: impl FnMut(usize, usize) -> bool) {
    let mut pos = start;
    while pos < end {
        let stop = memchr::memchr(b'\n', &bytes[pos..end]).map_or(end, |i| pos + i);
        if !f(pos, stop) {
            return;
        }
        pos = stop + 1;
    }
}

fn read_ascii(
    bytes: &[u8],
    header: &Header,
    layout: &Layout,
    warnings: &mut Vec<String>,
    chunk: usize,
) -> Result<Mesh, ParseError> {
    let bounds = line_boundaries(bytes, header.body, chunk.max(1));
    let counts: Vec<u64> = bounds
        .par_windows(2)
        .map(|w| {
            let mut n = 0u64;
            for_each_line(bytes, w[0], w[1], |s, e| {
                n += u64::from(has_content(&bytes[s..e]));
                true
            });
            n
        })
        .collect();
    let lines: u64 = counts.iter().sum();

    // Which content lines hold which element.
    let mut spans = Vec::with_capacity(header.elements.len());
    let mut declared = 0u64;
    for (e, element) in header.elements.iter().enumerate() {
        let role = match (layout.vertex, layout.face) {
            (Some((v, _)), _) if v == e => Role::Vertex,
            (_, Some((f, _))) if f == e => Role::Face,
            _ => Role::Skip,
        };
        if element.properties.is_empty() && element.count > 0 {
            return Err(ParseError::line(
                element.line,
                format!(
                    "element '{}' has no properties, so its lines cannot be read",
                    element.name
                ),
            ));
        }
        declared = declared
            .checked_add(element.count)
            .ok_or_else(|| ParseError::line(element.line, "the element counts overflow 64 bits"))?;
        if declared > lines {
            let read = element.count - (declared - lines);
            return Err(ParseError::at_offset(
                bytes,
                bytes.len(),
                format!(
                    "the header declares {} {} elements, but the file ends after {read}",
                    element.count, element.name
                ),
            ));
        }
        spans.push(Span { end: declared, role, element: e });
    }
    if lines > declared {
        warnings.push(format!("ignored {} lines after the declared elements", lines - declared));
    }

    let mut first_line = Vec::with_capacity(counts.len());
    let mut sum = 0;
    for c in &counts {
        first_line.push(sum);
        sum += c;
    }
    let chunks: Vec<AsciiChunk> = bounds
        .par_windows(2)
        .zip(first_line.par_iter())
        .map(|(w, &first)| ascii_chunk(bytes, w[0], w[1], first, &spans, header, layout))
        .collect();
    if let Some((at, message)) = chunks.iter().find_map(|c| c.error.as_ref()) {
        return Err(ParseError::at_offset(bytes, *at, message.clone()));
    }
    let skipped = chunks.iter().map(|c| c.skipped).sum();
    let first_skipped = chunks.iter().find_map(|c| c.first_skipped);
    warn_skipped(
        skipped,
        first_skipped.map(|at| format!("line {}", crate::error::line_of(bytes, at))),
        warnings,
    );
    let long_lines: usize = chunks.iter().map(|c| c.long_lines).sum();
    if let Some(at) = chunks.iter().find_map(|c| c.first_long) {
        warnings.push(format!(
            "{long_lines} lines have more values than their element's properties (the first \
             is line {}): the extra values were ignored",
            crate::error::line_of(bytes, at)
        ));
    }
    let vertex_count: usize = chunks.iter().map(|c| c.positions.len()).sum();
    let index_count: usize = chunks.iter().map(|c| c.indices.len()).sum();
    let face_count: usize = chunks.iter().map(|c| c.face_ends.len()).sum();
    let mut positions = Vec::with_capacity(vertex_count);
    let mut indices = Vec::with_capacity(index_count);
    let mut face_ends = Vec::with_capacity(face_count);
    for c in chunks {
        positions.extend_from_slice(&c.positions);
        let base = indices.len();
        face_ends.extend(c.face_ends.iter().map(|e| e + base));
        indices.extend_from_slice(&c.indices);
    }
    let all_triangles = index_count == 3 * face_count;
    mesh(positions, indices, face_ends.into_iter(), all_triangles)
}

/// Parses the lines `[start, end)`, whose first content line is content line `first`.
fn ascii_chunk(
    bytes: &[u8],
    start: usize,
    end: usize,
    first: u64,
    spans: &[Span],
    header: &Header,
    layout: &Layout,
) -> AsciiChunk {
    let mut chunk = AsciiChunk {
        positions: Vec::with_capacity((end - start) / 32),
        indices: Vec::with_capacity((end - start) / 8),
        face_ends: Vec::with_capacity((end - start) / 16),
        ..AsciiChunk::default()
    };
    let mut line = first;
    let mut span = spans.partition_point(|s| s.end <= first);
    for_each_line(bytes, start, end, |s, e| {
        let text = &bytes[..e];
        if !has_content(&text[s..]) {
            return true;
        }
        while span < spans.len() && spans[span].end <= line {
            span += 1;
        }
        let Some(current) = spans.get(span) else { return false };
        line += 1;
        let element = &header.elements[current.element];
        let result = match current.role {
            Role::Skip => Ok(e),
            Role::Vertex => {
                let xyz = layout.vertex.map_or([0; 3], |(_, xyz)| xyz);
                ascii_vertex(text, s, element, xyz).map(|(p, end)| {
                    chunk.positions.push(p);
                    end
                })
            }
            Role::Face => {
                let list = layout.face.map_or(0, |(_, list)| list);
                ascii_face(text, s, element, list, layout.vertices, &mut chunk)
            }
        };
        match result {
            Ok(end) => {
                if text::skip_blank(text, end) < e {
                    chunk.long_lines += 1;
                    chunk.first_long.get_or_insert(s);
                }
                true
            }
            Err(error) => {
                chunk.error = Some(error);
                false
            }
        }
    });
    chunk
}

/// Parses a non-negative integer token at `pos` of `line`; returns it and its end.
#[inline]
fn parse_integer(line: &[u8], pos: usize) -> Option<(i64, usize)> {
    let (negative, mut at) = match line.get(pos) {
        Some(b'-') => (true, pos + 1),
        Some(b'+') => (false, pos + 1),
        _ => (false, pos),
    };
    let digits = at;
    let mut value: i64 = 0;
    while let Some(&d) = line.get(at).filter(|d| d.is_ascii_digit()) {
        value = value.checked_mul(10)?.checked_add(i64::from(d - b'0'))?;
        at += 1;
    }
    if at == digits || line.get(at).is_some_and(|&b| !text::is_space(b)) {
        return None;
    }
    Some((if negative { -value } else { value }, at))
}

/// The error for a line that ends before its element's properties do.
fn too_few(s: usize, element: &Element, property: usize) -> (usize, String) {
    (
        s,
        format!(
            "expected {} values for the {} element, the line ends before '{}'",
            element.properties.len(),
            element.name,
            element.properties[property].name
        ),
    )
}

/// Skips one token at `pos`; returns its end, or `None` at the end of the line.
#[inline]
fn skip_token(line: &[u8], pos: usize) -> Option<usize> {
    let at = text::skip_blank(line, pos);
    (at < line.len()).then(|| text::token_end(line, at))
}

/// Reads a list's length at `pos`; returns it and its end.
#[inline]
fn list_length(
    line: &[u8],
    pos: usize,
    s: usize,
    element: &Element,
    p: usize,
) -> Result<(usize, usize), (usize, String)> {
    let at = text::skip_blank(line, pos);
    if at >= line.len() {
        return Err(too_few(s, element, p));
    }
    match parse_integer(line, at) {
        Some((n, end)) if n >= 0 => Ok((n as usize, end)),
        _ => Err((
            at,
            format!(
                "invalid length '{}' for list '{}'",
                text::show_token(line, at),
                element.properties[p].name
            ),
        )),
    }
}

/// Reads a vertex line starting at `s` (the line ends at `line.len()`); returns the point
/// and where its values end.
fn ascii_vertex(
    line: &[u8],
    s: usize,
    element: &Element,
    xyz: [usize; 3],
) -> Result<(Point, usize), (usize, String)> {
    let mut p = [0.0; 3];
    let mut pos = s;
    for (i, property) in element.properties.iter().enumerate() {
        match property.kind {
            Kind::Scalar(_) => match xyz.iter().position(|&k| k == i) {
                Some(axis) => {
                    let at = text::skip_blank(line, pos);
                    match text::parse_f64(line, at) {
                        Ok((value, end)) => {
                            p[axis] = value;
                            pos = end;
                        }
                        Err(NumberError::Missing) if at >= line.len() => {
                            return Err(too_few(s, element, i))
                        }
                        Err(NumberError::NonFinite) => {
                            return Err((
                                at,
                                format!("non-finite coordinate '{}'", text::show_token(line, at)),
                            ))
                        }
                        Err(_) => {
                            return Err((
                                at,
                                format!("invalid number '{}'", text::show_token(line, at)),
                            ))
                        }
                    }
                }
                None => pos = skip_token(line, pos).ok_or_else(|| too_few(s, element, i))?,
            },
            Kind::List { .. } => {
                let (n, end) = list_length(line, pos, s, element, i)?;
                pos = end;
                for _ in 0..n {
                    pos = skip_token(line, pos).ok_or_else(|| too_few(s, element, i))?;
                }
            }
        }
    }
    Ok((p, pos))
}

/// Reads a face line starting at `s` into the chunk; returns where its values end.
fn ascii_face(
    line: &[u8],
    s: usize,
    element: &Element,
    list: usize,
    vertices: usize,
    chunk: &mut AsciiChunk,
) -> Result<usize, (usize, String)> {
    let mut pos = s;
    let first = chunk.indices.len();
    let mut length = 0;
    for (i, property) in element.properties.iter().enumerate() {
        match property.kind {
            Kind::Scalar(_) => pos = skip_token(line, pos).ok_or_else(|| too_few(s, element, i))?,
            Kind::List { .. } => {
                let (n, end) = list_length(line, pos, s, element, i)?;
                pos = end;
                for _ in 0..n {
                    if i != list {
                        pos = skip_token(line, pos).ok_or_else(|| too_few(s, element, i))?;
                        continue;
                    }
                    let at = text::skip_blank(line, pos);
                    if at >= line.len() {
                        chunk.indices.truncate(first);
                        return Err((
                            s,
                            format!("the face declares {n} vertices, the line ends before"),
                        ));
                    }
                    match parse_integer(line, at) {
                        Some((index, end)) if index >= 0 && (index as u64) < vertices as u64 => {
                            chunk.indices.push(index as u32);
                            pos = end;
                        }
                        Some((index, _)) => {
                            chunk.indices.truncate(first);
                            return Err((
                                at,
                                format!(
                                    "vertex index {index} is out of range: the file has \
                                     {vertices} vertices"
                                ),
                            ));
                        }
                        None => {
                            chunk.indices.truncate(first);
                            return Err((
                                at,
                                format!("invalid vertex index '{}'", text::show_token(line, at)),
                            ));
                        }
                    }
                }
                if i == list {
                    length = n;
                }
            }
        }
    }
    if length < 3 {
        chunk.indices.truncate(first);
        chunk.skipped += 1;
        chunk.first_skipped.get_or_insert(s);
    } else {
        chunk.face_ends.push(chunk.indices.len());
    }
    Ok(pos)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Any chunking of an ASCII body gives what one pass gives.
    #[test]
    fn ascii_chunking_does_not_change_the_result() {
        use crate::text::mutate::assert_chunking_invisible;
        let mut file = String::from(
            "ply\nformat ascii 1.0\nelement vertex 8\nproperty float y\nproperty list uchar \
             float uv\nproperty float x\nproperty double z\nelement face 6\nproperty list \
             uchar int vertex_indices\nproperty uchar flags\nelement edge 2\nproperty int a\n\
             property int b\nend_header\n",
        );
        for i in 0..8 {
            file += &format!("{} 2 0.5 0.5 {} {}\n", i >> 1 & 1, i & 1, i >> 2 & 1);
        }
        for q in
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
        {
            file += &format!("4 {} {} {} {} 7\n", q[0], q[1], q[2], q[3]);
        }
        file += "0 1\n\n1 2\n";
        let pieces: &[&[u8]] =
            &[b"\n", b" ", b"3 ", b"2 0 1 0\n", b"-1", b"9", b"nan", b"1e999", b"x", b"\r\n"];
        let run = |bytes: &[u8], chunk: usize| {
            let mut warnings = vec![];
            let result = parse_header(bytes)
                .and_then(|h| {
                    let l = layout(&h)?;
                    read_ascii(bytes, &h, &l, &mut warnings, chunk)
                })
                .map(|m| (m.positions().to_vec(), m.faces().clone()))
                .map_err(|e| (e.location, e.message));
            (result, warnings)
        };
        let (ok, err) =
            assert_chunking_invisible(file.as_bytes(), pieces, 5, 2000, &[1, 20, 60], run);
        // Most mutations break a PLY line's value count: fewer inputs read.
        assert!(ok > 40 && err > 100, "{ok} {err}");
    }
}
