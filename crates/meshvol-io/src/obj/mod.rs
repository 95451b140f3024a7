//! Wavefront OBJ: the polygon geometry.
//!
//! Read, one statement per line (lines may end with LF, CRLF or CR alone, as old Mac
//! files do; a line ending with `\\` continues on the next):
//! - `v x y z [w | r g b ...]`: a vertex; the first three numbers are its position,
//!   further columns (a weight, vertex colours) are allowed and not read.
//! - `f i j k ...`: a face of three or more vertices; a face of fewer holds no area and
//!   is skipped, with a warning that counts them and names the first one's line. Each token is `v`, `v/vt`,
//!   `v/vt/vn` or `v//vn`; only `v` is used. Indices start at 1; a negative index counts
//!   back from the last vertex defined so far (-1 is the latest). A positive index may
//!   name a vertex defined later in the file: ranges are checked after reading. Faces keep
//!   their size ([`meshvol::Faces::Polygons`] unless every face is a triangle).
//!
//! Objects: `o name` starts an object; in a file without `o` statements, `g name` starts
//! one. An object holds the faces up to the next such statement; the faces before the
//! first one form an object with an empty name; objects without faces are left out (see
//! [`crate::Object`]).
//!
//! Ignored quietly: comments (`#`), `vt`, `vn`, `vp`, `s`, `usemtl`, `mtllib`.
//! Counted and reported in one warning: `l` (line) and `p` (point) elements, which hold
//! no volume, and other statements (free-form curves and surfaces).
//!
//! Errors, with the line: a `v` with fewer than three numbers, a NaN or infinite
//! coordinate, index 0, an index out of range, a line that does not start with a
//! statement keyword, more than `u32::MAX` vertices.
//!
//! The parser works on bytes, with no allocation per line, in parallel: the file is cut
//! into chunks at line ends; each chunk is parsed on its own, negative indices kept
//! relative to the chunk's own vertex count; the chunks' vertex counts then fix every
//! index in a second, parallel pass.

use meshvol::{Faces, Mesh, Point};
use rayon::prelude::*;

use crate::error::ParseError;
use crate::object::Object;
use crate::text::{self, NumberError};

/// Target bytes per parallel chunk.
const CHUNK: usize = 1 << 20;

/// Added to a chunk-relative index (which may be negative, naming a vertex of an earlier
/// chunk) so that it is stored as a negative number, apart from absolute indices (≥ 0).
const RELATIVE: i64 = 1 << 62;

/// Indices beyond this are errors at once (no mesh has that many vertices).
const MAX_INDEX: i64 = 1 << 40;

/// What kind of statement a line holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Statement {
    Vertex,
    Face,
    Line,
    Point,
    /// `o name`.
    Object,
    /// `g name`.
    Group,
    /// Known and not needed, or empty / comment.
    Skip,
    /// A keyword that is not read.
    Unknown,
    /// Not a keyword at all.
    Invalid,
}

/// Whether byte `i` ends a word: a blank, a newline, or the end.
#[inline]
fn ends_word(b: &[u8], i: usize) -> bool {
    b.get(i).is_none_or(|&c| text::is_space(c))
}

/// Classifies the statement whose first non-blank byte is at `s`; returns the kind and
/// where its keyword ends.
#[inline]
fn classify(b: &[u8], s: usize) -> (Statement, usize) {
    // The common cases first.
    match b.get(s) {
        None | Some(b'\n') | Some(b'#') => return (Statement::Skip, s),
        Some(b'v') if ends_word(b, s + 1) => return (Statement::Vertex, s + 1),
        Some(b'f') if ends_word(b, s + 1) => return (Statement::Face, s + 1),
        _ => {}
    }
    let e = text::token_end(b, s);
    let kind = match &b[s..e] {
        b"l" => Statement::Line,
        b"p" => Statement::Point,
        b"o" => Statement::Object,
        b"g" => Statement::Group,
        b"vt" | b"vn" | b"vp" | b"s" | b"usemtl" | b"mtllib" => Statement::Skip,
        [first, rest @ ..]
            if first.is_ascii_alphabetic()
                && rest.iter().all(|b| b.is_ascii_alphanumeric() || *b == b'_') =>
        {
            Statement::Unknown
        }
        _ => Statement::Invalid,
    };
    (kind, e)
}

/// Whether a line ends with `\` (before blanks or CR): it continues on the next line.
#[inline]
fn continues(line: &[u8]) -> bool {
    let mut e = line.len();
    while e > 0 && text::is_blank(line[e - 1]) {
        e -= 1;
    }
    e > 0 && line[e - 1] == b'\\'
}

/// The start of the next line after `pos`, skipping continued lines.
#[inline]
fn skip_line(b: &[u8], mut pos: usize) -> usize {
    if b.get(pos) == Some(&b'\n') {
        return pos + 1;
    }
    loop {
        match memchr::memchr(b'\n', &b[pos.min(b.len())..]) {
            None => return b.len(),
            Some(i) => {
                let nl = pos + i;
                if !continues(&b[pos..nl]) {
                    return nl + 1;
                }
                pos = nl + 1;
            }
        }
    }
}

/// Skips blanks and line continuations (`\`, blanks, newline).
#[inline]
fn skip_blank_continued(b: &[u8], mut pos: usize) -> usize {
    loop {
        pos = text::skip_blank(b, pos);
        if b.get(pos) != Some(&b'\\') {
            return pos;
        }
        let after = text::skip_blank(b, pos + 1);
        match b.get(after) {
            Some(b'\n') => pos = after + 1,
            None => return after,
            Some(_) => return pos,
        }
    }
}

/// Whether the start of the file reads as OBJ (for files whose extension says nothing):
/// text whose lines are all known statements, with at least one vertex.
pub(crate) fn looks_like_obj(bytes: &[u8]) -> bool {
    let start = text::bom_len(bytes);
    let mut prefix = &bytes[start..bytes.len().min(start + (64 << 10))];
    if prefix.len() < bytes.len() - start {
        // Whole lines only.
        prefix = &prefix[..memchr::memrchr(b'\n', prefix).unwrap_or(0)];
    }
    if !text::looks_like_text(prefix) {
        return false;
    }
    let mut vertices = 0;
    let mut pos = 0;
    while pos < prefix.len() {
        let s = text::skip_blank(prefix, pos);
        let (kind, e) = classify(prefix, s);
        match kind {
            Statement::Vertex => vertices += 1,
            Statement::Invalid | Statement::Unknown => return false,
            _ => {}
        }
        pos = skip_line(prefix, e);
    }
    vertices > 0
}

/// What one chunk gave.
#[derive(Default)]
struct Chunk {
    positions: Vec<Point>,
    /// Vertex indices: ≥ 0 absolute (0-based); < 0 chunk-relative minus [`RELATIVE`].
    indices: Vec<i64>,
    /// End of each face in `indices`.
    face_ends: Vec<usize>,
    /// The faces of fewer than three vertices, skipped: their places among the chunk's
    /// `f` statements (ascending), and the offset of the first.
    skipped: Vec<usize>,
    first_skipped: Option<usize>,
    all_triangles: bool,
    lines: usize,
    points: usize,
    unknown: usize,
    unknown_names: Vec<String>,
    /// `o` and `g` statements: which, the byte range of the name, the chunk's face count
    /// before it.
    markers: Vec<(Statement, (usize, usize), usize)>,
    error: Option<(usize, String)>,
}

/// Parses an OBJ file into a mesh and its objects.
pub(crate) fn read(
    bytes: &[u8],
    warnings: &mut Vec<String>,
) -> Result<(Mesh, Vec<Object>), ParseError> {
    read_chunked(bytes, warnings, CHUNK)
}

/// The objects that `o` statements start, or `g` statements where there is no `o`.
fn objects(bytes: &[u8], chunks: &[Chunk]) -> Vec<Object> {
    let kind = if chunks.iter().any(|c| c.markers.iter().any(|m| m.0 == Statement::Object)) {
        Statement::Object
    } else {
        Statement::Group
    };
    let mut starts = vec![(String::new(), 0)];
    let mut faces = 0;
    for chunk in chunks {
        for &(k, (s, e), first) in &chunk.markers {
            if k == kind {
                starts.push((text::lossy_name(&bytes[s..e]), faces + first));
            }
        }
        faces += chunk.face_ends.len();
    }
    let ends: Vec<usize> = starts.iter().skip(1).map(|s| s.1).chain([faces]).collect();
    starts
        .into_iter()
        .zip(ends)
        .filter(|((_, start), end)| end > start)
        .map(|((name, start), end)| Object { name, faces: start..end })
        .collect()
}

/// [`read`] with chunks of about `chunk` bytes.
fn read_chunked(
    bytes: &[u8],
    warnings: &mut Vec<String>,
    chunk: usize,
) -> Result<(Mesh, Vec<Object>), ParseError> {
    let start = text::bom_len(bytes);
    let bounds = line_boundaries(bytes, start, chunk.max(1));
    let chunks: Vec<Chunk> =
        bounds.par_windows(2).map(|w| parse_chunk(bytes, w[0], w[1])).collect();
    if let Some((at, message)) = chunks.iter().find_map(|c| c.error.as_ref()) {
        return Err(ParseError::at_offset(bytes, *at, message.clone()));
    }

    let vertex_count: usize = chunks.iter().map(|c| c.positions.len()).sum();
    if u32::try_from(vertex_count).is_err() {
        return Err(ParseError::new(
            None,
            format!("{vertex_count} vertices do not fit 32-bit indices"),
        ));
    }
    warn_ignored(&chunks, warnings);
    let skipped: usize = chunks.iter().map(|c| c.skipped.len()).sum();
    if let Some(at) = chunks.iter().find_map(|c| c.first_skipped) {
        warnings.push(format!(
            "skipped {skipped} faces with fewer than 3 vertices (the first at line {})",
            crate::error::line_of(bytes, at)
        ));
    }
    let objects = objects(bytes, &chunks);

    // Where each chunk's vertices and indices start in the whole mesh.
    let mut vertex_base = Vec::with_capacity(chunks.len());
    let mut index_base = Vec::with_capacity(chunks.len());
    let (mut v, mut i) = (0usize, 0usize);
    for c in &chunks {
        vertex_base.push(v);
        index_base.push(i);
        v += c.positions.len();
        i += c.indices.len();
    }
    // All triangles: resolve straight into the triangle array.
    let all_triangles = chunks.iter().all(|c| c.all_triangles);
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut indices: Vec<u32> = Vec::new();
    let out: &mut [u32] = if all_triangles {
        triangles = vec![[0; 3]; i / 3];
        triangles.as_flattened_mut()
    } else {
        indices = vec![0; i];
        &mut indices
    };
    let mut slices = Vec::with_capacity(chunks.len());
    let mut rest = out;
    for c in &chunks {
        let (head, tail) = rest.split_at_mut(c.indices.len().min(rest.len()));
        slices.push(head);
        rest = tail;
    }
    let bad = chunks
        .par_iter()
        .zip(slices.into_par_iter())
        .zip(vertex_base.par_iter())
        .enumerate()
        .map(|(k, ((chunk, out), &base))| {
            resolve(chunk, out, base, vertex_count).map(|(at, message)| (k, at, message))
        })
        .find_first(|bad| bad.is_some())
        .flatten();
    if let Some((k, at, message)) = bad {
        let chunk = &chunks[k];
        let mut face = chunk.face_ends.partition_point(|&end| end <= at);
        // The kept face's place among the `f` statements, skipped ones included.
        for &s in &chunk.skipped {
            if s <= face {
                face += 1;
            }
        }
        let offset = face_offset(bytes, bounds[k], bounds[k + 1], face);
        return Err(ParseError::at_offset(bytes, offset, message));
    }

    let mut positions = Vec::with_capacity(vertex_count);
    for c in &chunks {
        positions.extend_from_slice(&c.positions);
    }
    let faces = if all_triangles {
        Faces::Triangles(triangles)
    } else {
        let face_count: usize = chunks.iter().map(|c| c.face_ends.len()).sum();
        let mut offsets = Vec::with_capacity(face_count + 1);
        offsets.push(0);
        for (c, &base) in chunks.iter().zip(&index_base) {
            offsets.extend(c.face_ends.iter().map(|&e| base + e));
        }
        Faces::Polygons { offsets, indices }
    };
    drop(chunks);
    let mesh = Mesh::new(positions, faces).map_err(|e| ParseError::new(None, e.to_string()))?;
    Ok((mesh, objects))
}

/// Turns a chunk's stored indices into absolute ones; on a bad index returns its
/// position in the chunk's index list and the message.
fn resolve(
    chunk: &Chunk,
    out: &mut [u32],
    base: usize,
    vertices: usize,
) -> Option<(usize, String)> {
    for (at, (&stored, slot)) in chunk.indices.iter().zip(out.iter_mut()).enumerate() {
        let absolute = if stored >= 0 { stored } else { stored + RELATIVE + base as i64 };
        if absolute < 0 {
            return Some((
                at,
                format!(
                    "negative vertex index points before the first vertex ({} too far back)",
                    -absolute
                ),
            ));
        }
        if absolute as u64 >= vertices as u64 {
            let message = if stored >= 0 {
                format!(
                    "vertex index {} is out of range: the file has {vertices} vertices",
                    absolute + 1
                )
            } else {
                format!("negative vertex index is out of range ({vertices} vertices)")
            };
            return Some((at, message));
        }
        *slot = absolute as u32;
    }
    None
}

/// One warning for everything read and not used.
fn warn_ignored(chunks: &[Chunk], warnings: &mut Vec<String>) {
    let lines: usize = chunks.iter().map(|c| c.lines).sum();
    let points: usize = chunks.iter().map(|c| c.points).sum();
    let mut parts = Vec::new();
    if lines > 0 {
        parts.push(format!("{lines} line elements (l)"));
    }
    if points > 0 {
        parts.push(format!("{points} point elements (p)"));
    }
    if !parts.is_empty() {
        warnings.push(format!("ignored {}", parts.join(" and ")));
    }
    let unknown: usize = chunks.iter().map(|c| c.unknown).sum();
    if unknown > 0 {
        let mut names: Vec<&str> = Vec::new();
        for name in chunks.iter().flat_map(|c| &c.unknown_names) {
            if !names.contains(&name.as_str()) && names.len() < 8 {
                names.push(name);
            }
        }
        warnings.push(format!("ignored {unknown} unsupported statements ({})", names.join(", ")));
    }
}

/// Chunk boundaries at line starts, about `target` bytes apart, never inside a
/// continued line.
fn line_boundaries(bytes: &[u8], start: usize, target: usize) -> Vec<usize> {
    text::line_boundaries(bytes, start, target, |nl| {
        let line_start = memchr::memrchr(b'\n', &bytes[..nl]).map_or(0, |j| j + 1);
        !continues(&bytes[line_start..nl])
    })
}

/// The byte offset of the `face`-th face statement in `[start, end)`.
fn face_offset(bytes: &[u8], start: usize, end: usize, face: usize) -> usize {
    let b = &bytes[..end];
    let mut seen = 0;
    let mut pos = start;
    while pos < b.len() {
        let s = text::skip_blank(b, pos);
        let (kind, e) = classify(b, s);
        if kind == Statement::Face {
            if seen == face {
                return s;
            }
            seen += 1;
        }
        pos = skip_line(b, e);
    }
    end
}

/// Parses the lines in `[start, end)`; `end` is a line start or the end of the file.
fn parse_chunk(bytes: &[u8], start: usize, end: usize) -> Chunk {
    let b = &bytes[..end];
    let mut chunk = Chunk {
        // About 30 bytes per vertex line and per face line.
        positions: Vec::with_capacity((end - start) / 64),
        indices: Vec::with_capacity((end - start) / 16),
        face_ends: Vec::with_capacity((end - start) / 64),
        all_triangles: true,
        ..Chunk::default()
    };
    let mut pos = start;
    while pos < b.len() {
        let s = text::skip_blank(b, pos);
        let (kind, e) = classify(b, s);
        let result = match kind {
            Statement::Vertex => parse_vertex(b, s, e).map(|(p, end)| {
                chunk.positions.push(p);
                end
            }),
            Statement::Face => parse_face(b, s, e, &mut chunk),
            Statement::Skip => Ok(e),
            Statement::Object | Statement::Group => {
                let line_end = memchr::memchr(b'\n', &b[e..]).map_or(b.len(), |i| e + i);
                chunk.markers.push((kind, (e, line_end), chunk.face_ends.len()));
                Ok(e)
            }
            Statement::Line => {
                chunk.lines += 1;
                Ok(e)
            }
            Statement::Point => {
                chunk.points += 1;
                Ok(e)
            }
            Statement::Unknown => {
                chunk.unknown += 1;
                let name = &b[s..e];
                if chunk.unknown_names.len() < 8
                    && !chunk.unknown_names.iter().any(|n| n.as_bytes() == name)
                {
                    chunk.unknown_names.push(text::show(name));
                }
                Ok(e)
            }
            Statement::Invalid => {
                Err((s, format!("expected an OBJ statement, found '{}'", text::show(&b[s..e]))))
            }
        };
        match result {
            Ok(e) => pos = skip_line(b, e),
            Err(error) => {
                chunk.error = Some(error);
                break;
            }
        }
    }
    chunk
}

/// Reads the first three numbers after `v` (keyword at `s`, arguments from `pos`);
/// returns the point and where reading stopped.
#[inline]
fn parse_vertex(b: &[u8], s: usize, mut pos: usize) -> Result<(Point, usize), (usize, String)> {
    let mut p = [0.0; 3];
    for (found, c) in p.iter_mut().enumerate() {
        pos = skip_blank_continued(b, pos);
        match text::parse_f64(b, pos) {
            Ok((value, end)) => {
                *c = value;
                pos = end;
            }
            Err(NumberError::Missing) if matches!(b.get(pos), None | Some(b'\n' | b'#')) => {
                return Err((s, format!("expected 3 coordinates after 'v', found {found}")))
            }
            Err(NumberError::NonFinite) => {
                return Err((pos, format!("non-finite coordinate '{}'", text::show_token(b, pos))))
            }
            Err(_) => return Err((pos, format!("invalid number '{}'", text::show_token(b, pos)))),
        }
    }
    Ok((p, pos))
}

/// Reads the vertex indices of an `f` statement (keyword at `s`, arguments from `pos`);
/// returns where reading stopped.
#[inline]
fn parse_face(
    b: &[u8],
    s: usize,
    mut pos: usize,
    chunk: &mut Chunk,
) -> Result<usize, (usize, String)> {
    let local = chunk.positions.len() as i64;
    let first = chunk.indices.len();
    loop {
        pos = skip_blank_continued(b, pos);
        let token = pos;
        let (negative, digits) = match b.get(pos) {
            None | Some(b'\n' | b'#') => break,
            Some(b'-') => (true, pos + 1),
            Some(b'+') => (false, pos + 1),
            Some(_) => (false, pos),
        };
        pos = digits;
        let mut value: i64 = 0;
        while let Some(&d) = b.get(pos).filter(|d| d.is_ascii_digit()) {
            value = value * 10 + i64::from(d - b'0');
            if value > MAX_INDEX {
                let shown = text::show_token(b, token);
                return Err((token, format!("vertex index '{shown}' is too large")));
            }
            pos += 1;
        }
        if pos == digits || !(ends_word(b, pos) || b[pos] == b'/') {
            let shown = text::show_token(b, token);
            return Err((token, format!("invalid vertex index '{shown}'")));
        }
        // Skip `/vt/vn`.
        pos = text::token_end(b, pos);
        if value == 0 {
            return Err((token, "vertex index 0: OBJ indices start at 1".to_string()));
        }
        chunk.indices.push(if negative { local - value - RELATIVE } else { value - 1 });
    }
    let count = chunk.indices.len() - first;
    if count < 3 {
        chunk.indices.truncate(first);
        chunk.skipped.push(chunk.face_ends.len() + chunk.skipped.len());
        chunk.first_skipped.get_or_insert(s);
        return Ok(pos);
    }
    chunk.all_triangles &= count == 3;
    chunk.face_ends.push(chunk.indices.len());
    Ok(pos)
}

#[cfg(test)]
mod tests;
