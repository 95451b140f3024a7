//! ASCII PLY bodies: one element instance per line, values separated by blanks.
//!
//! The body is cut into chunks at line ends, the lines of each chunk counted (so each
//! chunk knows which element its lines belong to), then parsed, both in parallel.
//! Errors name the line.

use meshvol::Point;
use rayon::prelude::*;

use super::body::{self, Body, Layout, STRIP_END};
use super::header::{Element, Header, Kind};
use crate::error::ParseError;
use crate::text::{self, NumberError};

/// Target bytes per parallel chunk of an ASCII body.
pub(super) const CHUNK: usize = 1 << 20;

/// What an element's lines are read for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Vertex,
    Face,
    Strip,
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
    /// Strip indices (see [`Body::strips`]).
    strips: Vec<u32>,
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

/// Reads an ASCII body, in chunks of about `chunk` bytes.
pub(super) fn read(
    bytes: &[u8],
    header: &Header,
    layout: &Layout,
    warnings: &mut Vec<String>,
    chunk: usize,
) -> Result<Body, ParseError> {
    let bounds = text::line_boundaries(bytes, header.body, chunk.max(1), |_| true);
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
        let role = match (layout.vertex, layout.face, layout.strips) {
            (Some((v, _)), _, _) if v == e => Role::Vertex,
            (_, Some((f, _)), _) if f == e => Role::Face,
            (_, _, Some((s, _))) if s == e => Role::Strip,
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
    body::warn_skipped(
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
    let mut strips = Vec::new();
    for c in chunks {
        positions.extend_from_slice(&c.positions);
        let base = indices.len();
        face_ends.extend(c.face_ends.iter().map(|e| e + base));
        indices.extend_from_slice(&c.indices);
        strips.extend_from_slice(&c.strips);
    }
    let all_triangles = index_count == 3 * face_count;
    let faces = body::faces(indices, face_ends.into_iter(), all_triangles);
    Ok(Body { positions, faces, strips })
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
        let result =
            match current.role {
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
                    let first = chunk.indices.len();
                    ascii_list(text, s, element, list, layout.vertices, false, &mut chunk.indices)
                        .map(|(end, length)| {
                            if length < 3 {
                                chunk.indices.truncate(first);
                                chunk.skipped += 1;
                                chunk.first_skipped.get_or_insert(s);
                            } else {
                                chunk.face_ends.push(chunk.indices.len());
                            }
                            end
                        })
                }
                Role::Strip => {
                    let list = layout.strips.map_or(0, |(_, list)| list);
                    ascii_list(text, s, element, list, layout.vertices, true, &mut chunk.strips)
                        .map(|(end, _)| {
                            chunk.strips.push(STRIP_END);
                            end
                        })
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

/// Reads the index list `list` of a face or strip line starting at `s` onto `out`;
/// returns where the line's values end and the list's length. With `strip`, -1 (between
/// strips) is read as [`STRIP_END`]. On an error `out` is as it was.
fn ascii_list(
    line: &[u8],
    s: usize,
    element: &Element,
    list: usize,
    vertices: usize,
    strip: bool,
    out: &mut Vec<u32>,
) -> Result<(usize, usize), (usize, String)> {
    let first = out.len();
    let mut pos = s;
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
                    let index = match parse_integer(line, at) {
                        _ if at >= line.len() => Err((
                            s,
                            format!(
                                "the {} declares {n} vertices, the line ends before",
                                if strip { "strip" } else { "face" }
                            ),
                        )),
                        Some((index, end)) if index >= 0 && (index as u64) < vertices as u64 => {
                            pos = end;
                            Ok(index as u32)
                        }
                        Some((-1, end)) if strip => {
                            pos = end;
                            Ok(STRIP_END)
                        }
                        Some((index, _)) => Err((
                            at,
                            format!(
                                "vertex index {index} is out of range: the file has \
                                 {vertices} vertices"
                            ),
                        )),
                        None => Err((
                            at,
                            format!("invalid vertex index '{}'", text::show_token(line, at)),
                        )),
                    };
                    match index {
                        Ok(index) => out.push(index),
                        Err(error) => {
                            out.truncate(first);
                            return Err(error);
                        }
                    }
                }
                if i == list {
                    length = n;
                }
            }
        }
    }
    Ok((pos, length))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Any chunking of an ASCII body gives what one pass gives.
    #[test]
    fn ascii_chunking_does_not_change_the_result() {
        use crate::text::mutate::{assert_chunking_invisible, outcome};
        let mut file = String::from(
            "ply\nformat ascii 1.0\nelement vertex 8\nproperty float y\nproperty list uchar \
             float uv\nproperty float x\nproperty double z\nelement face 6\nproperty list \
             uchar int vertex_indices\nproperty uchar flags\nelement edge 2\nproperty int a\n\
             property int b\nelement tristrips 1\nproperty list uchar int vertex_indices\n\
             end_header\n",
        );
        for i in 0..8 {
            file += &format!("{} 2 0.5 0.5 {} {}\n", i >> 1 & 1, i & 1, i >> 2 & 1);
        }
        for q in
            [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
        {
            file += &format!("4 {} {} {} {} 7\n", q[0], q[1], q[2], q[3]);
        }
        file += "0 1\n\n1 2\n6 0 1 2 -1 3 4\n";
        let pieces: &[&[u8]] =
            &[b"\n", b" ", b"3 ", b"2 0 1 0\n", b"-1", b"9", b"nan", b"1e999", b"x", b"\r\n"];
        let run = |bytes: &[u8], chunk: usize| {
            outcome(|w| {
                let h = super::super::header::parse(bytes, w)?;
                let l = super::super::layout(&h)?;
                read(bytes, &h, &l, w, chunk).map(|b| (b.positions, b.faces, b.strips))
            })
        };
        let (ok, err) =
            assert_chunking_invisible(file.as_bytes(), pieces, 5, 2000, &[1, 20, 60], run);
        // Most mutations break a PLY line's value count: fewer inputs read.
        assert!(ok > 40 && err > 100, "{ok} {err}");
    }
}
