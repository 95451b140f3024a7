//! OFF (Object File Format, as written by Geomview, CGAL, MeshLab).
//!
//! ```text
//! OFF                 # optional keyword: OFF, COFF, NOFF, CNOFF (also STOFF and the like)
//! nv nf [ne]          # may follow the keyword on its line: "OFF 8 6 12", even "OFF8 6 12"
//! x y z [extra...]    # nv vertex lines: the first three numbers; normals, colours after
//! k i1 .. ik [colour] # nf face lines: k vertex indices counted from 0
//! ```
//!
//! `#` starts a comment anywhere; blank lines are skipped; lines may end with LF, CRLF or
//! CR alone (old Mac files). The edge count is not read. A face whose indices do not all
//! fit its line continues on the next lines (OFF readers such as Geomview's and CGAL's
//! read a stream of tokens); a warning counts such faces and names the first one's line.
//! Faces of fewer than three vertices hold no area: skipped with a warning that counts
//! them and names the first one's line.
//! Counts are never trusted for allocation: at most what the remaining bytes could hold
//! is reserved. Anything after the declared faces is ignored with a warning. Not read
//! (errors): binary OFF, 4D (`4OFF`) and n-dimensional (`nOFF`) files.
//!
//! Errors name the line: a missing or bad count, a vertex with fewer than three numbers
//! or a NaN / infinite one, a face index that is not a number or out of range, and a
//! file that ends before the declared vertices, faces, or a face's indices ("declared 8
//! vertices, file ends after 5").

use meshvol::{Faces, Mesh, Point};

use crate::error::ParseError;
use crate::text::{self, NumberError};

/// The shortest possible vertex line, `0 0 0\n`, for bounding reservations.
const MIN_VERTEX_LINE: usize = 6;
/// The shortest possible triangle line, `3 0 1 2\n`.
const MIN_FACE_LINE: usize = 8;

/// The non-empty lines of a file, comments removed.
struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// The number of the line last returned, or of the last line at the end.
    line: u64,
}

impl<'a> Lines<'a> {
    /// The next line with content: its number and its content (comment removed, not
    /// trimmed at the start).
    fn next(&mut self) -> Option<(u64, &'a [u8])> {
        while self.pos < self.bytes.len() {
            let rest = &self.bytes[self.pos..];
            let end = memchr::memchr(b'\n', rest).unwrap_or(rest.len());
            let mut line = &rest[..end];
            self.pos += end + 1;
            self.line += 1;
            if let Some(hash) = memchr::memchr(b'#', line) {
                line = &line[..hash];
            }
            if line.iter().any(|&b| !text::is_blank(b)) {
                return Some((self.line, line));
            }
        }
        None
    }

    fn remaining(&self) -> usize {
        self.bytes.len().saturating_sub(self.pos)
    }
}

/// How many faces had some property, and the line of the first.
#[derive(Default)]
struct Tally {
    count: usize,
    first: Option<u64>,
}

impl Tally {
    fn add(&mut self, line: u64) {
        self.count += 1;
        self.first.get_or_insert(line);
    }
}

/// Parses an OFF file.
pub(crate) fn read(bytes: &[u8], warnings: &mut Vec<String>) -> Result<Mesh, ParseError> {
    let start = text::bom_len(bytes);
    let mut lines = Lines { bytes: &bytes[start..], pos: 0, line: 0 };
    let Some((first_no, first)) = lines.next() else {
        return Err(ParseError::new(None, "empty file: no OFF header"));
    };

    // The header keyword, and where the counts are.
    let (counts_no, counts, counts_at) = match keyword(first) {
        Keyword::Off(after) => {
            let rest = &first[after..];
            let at = text::skip_blank(rest, 0);
            if at < rest.len() {
                if rest[at].is_ascii_alphabetic() {
                    return Err(ParseError::line(
                        first_no,
                        format!(
                            "expected the vertex and face counts after the OFF keyword, found \
                             '{}' (binary OFF is not read)",
                            text::show_token(rest, at)
                        ),
                    ));
                }
                (first_no, rest, at)
            } else {
                match lines.next() {
                    Some((no, line)) => (no, line, 0),
                    None => {
                        return Err(ParseError::line(
                            lines.line.max(1),
                            "expected the vertex and face counts after 'OFF', found the end \
                             of the file",
                        ))
                    }
                }
            }
        }
        Keyword::Unsupported(what) => {
            return Err(ParseError::line(first_no, format!("{what} OFF files are not read")))
        }
        Keyword::None => (first_no, first, 0),
    };
    let mut pos = counts_at;
    let nv = count(counts, &mut pos, counts_no, "vertex count")?;
    let nf = count(counts, &mut pos, counts_no, "face count")?;
    let Ok(nv32) = u32::try_from(nv) else {
        return Err(ParseError::line(
            counts_no,
            format!("{nv} vertices do not fit 32-bit indices"),
        ));
    };
    let nv = nv32 as usize;
    let nf = usize::try_from(nf).unwrap_or(usize::MAX);

    let mut positions: Vec<Point> = Vec::with_capacity(nv.min(lines.remaining() / MIN_VERTEX_LINE));
    while positions.len() < nv {
        let Some((no, line)) = lines.next() else {
            return Err(ParseError::line(
                lines.line.max(1),
                format!("declared {nv} vertices, file ends after {}", positions.len()),
            ));
        };
        positions.push(vertex(line, no)?);
    }

    let mut offsets: Vec<usize> =
        Vec::with_capacity(nf.saturating_add(1).min(lines.remaining() / MIN_FACE_LINE + 1));
    offsets.push(0);
    let mut indices: Vec<u32> = Vec::with_capacity(nf.saturating_mul(3).min(lines.remaining() / 2));
    let mut all_triangles = true;
    let (mut skipped, mut continued) = (Tally::default(), Tally::default());
    for done in 0..nf {
        let Some((no, line)) = lines.next() else {
            return Err(ParseError::line(
                lines.line.max(1),
                format!("declared {nf} faces, file ends after {done}"),
            ));
        };
        let first = indices.len();
        let (k, more_lines) = face(line, no, &mut lines, nv, &mut indices)?;
        if more_lines {
            continued.add(no);
        }
        if k < 3 {
            indices.truncate(first);
            skipped.add(no);
            continue;
        }
        all_triangles &= k == 3;
        offsets.push(indices.len());
    }
    if let Some(first) = skipped.first {
        warnings.push(format!(
            "skipped {} faces with fewer than 3 vertices (the first at line {first})",
            skipped.count
        ));
    }
    if let Some(first) = continued.first {
        warnings.push(format!(
            "{} faces continue on the next lines (the first at line {first})",
            continued.count
        ));
    }

    let mut extra = 0u64;
    let mut extra_from = 0;
    while let Some((no, _)) = lines.next() {
        if extra == 0 {
            extra_from = no;
        }
        extra += 1;
    }
    if extra > 0 {
        warnings.push(format!(
            "ignored {extra} lines after the {nf} declared faces (from line {extra_from})"
        ));
    }

    let faces = if all_triangles {
        Faces::Triangles(indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
    } else {
        Faces::Polygons { offsets, indices }
    };
    Mesh::new(positions, faces).map_err(|e| ParseError::new(None, e.to_string()))
}

/// Whether the first line with content starts with an OFF keyword (for files whose
/// extension says nothing).
pub(crate) fn looks_like_off(bytes: &[u8]) -> bool {
    let start = text::bom_len(bytes);
    let mut lines = Lines { bytes: &bytes[start..], pos: 0, line: 0 };
    match lines.next() {
        Some((_, line)) => match keyword(line) {
            Keyword::Off(end) => line.get(end).is_none_or(|b| !b.is_ascii_alphabetic()),
            Keyword::Unsupported(_) => true,
            Keyword::None => false,
        },
        None => false,
    }
}

enum Keyword {
    /// An OFF keyword ending at the given offset of the line.
    Off(usize),
    Unsupported(&'static str),
    None,
}

/// Reads `[ST][C][N][4][n]OFF` at the start of the line.
fn keyword(line: &[u8]) -> Keyword {
    let start = text::skip_blank(line, 0);
    let mut i = start;
    let at = |i: usize, s: &[u8]| line.get(i..).is_some_and(|r| r.starts_with(s));
    if at(i, b"ST") {
        i += 2;
    }
    if at(i, b"C") {
        i += 1;
    }
    if at(i, b"N") {
        i += 1;
    }
    let four = at(i, b"4");
    if four {
        i += 1;
    }
    let n = at(i, b"n");
    if n {
        i += 1;
    }
    if !at(i, b"OFF") {
        return Keyword::None;
    }
    if four {
        Keyword::Unsupported("4D (4OFF)")
    } else if n {
        Keyword::Unsupported("n-dimensional (nOFF)")
    } else {
        Keyword::Off(i + 3)
    }
}

/// Reads a non-negative integer count at `pos`.
fn count(line: &[u8], pos: &mut usize, no: u64, what: &str) -> Result<u64, ParseError> {
    let at = text::skip_blank(line, *pos);
    match integer(line, at) {
        Some((value, end)) if value >= 0 => {
            *pos = end;
            Ok(value as u64)
        }
        _ if at >= line.len() => Err(ParseError::line(no, format!("expected the {what}"))),
        _ => Err(ParseError::line(
            no,
            format!("expected the {what}, found '{}'", text::show_token(line, at)),
        )),
    }
}

/// An integer token (optional sign, digits, then blank or the end), saturated well below
/// overflow.
fn integer(line: &[u8], mut pos: usize) -> Option<(i64, usize)> {
    let negative = line.get(pos) == Some(&b'-');
    if negative || line.get(pos) == Some(&b'+') {
        pos += 1;
    }
    let digits = pos;
    let mut value: i64 = 0;
    while let Some(&b) = line.get(pos).filter(|b| b.is_ascii_digit()) {
        value = (value * 10 + i64::from(b - b'0')).min(1 << 50);
        pos += 1;
    }
    if pos == digits || line.get(pos).is_some_and(|&b| !text::is_space(b)) {
        return None;
    }
    Some((if negative { -value } else { value }, pos))
}

/// The first three numbers of a vertex line.
fn vertex(line: &[u8], no: u64) -> Result<Point, ParseError> {
    let mut p = [0.0; 3];
    let mut pos = 0;
    for (found, c) in p.iter_mut().enumerate() {
        pos = text::skip_blank(line, pos);
        match text::parse_f64(line, pos) {
            Ok((value, end)) => {
                *c = value;
                pos = end;
            }
            Err(NumberError::Missing) if pos >= line.len() => {
                return Err(ParseError::line(
                    no,
                    format!("expected 3 coordinates for a vertex, found {found}"),
                ))
            }
            Err(NumberError::NonFinite) => {
                return Err(ParseError::line(
                    no,
                    format!("non-finite coordinate '{}'", text::show_token(line, pos)),
                ))
            }
            Err(_) => {
                return Err(ParseError::line(
                    no,
                    format!("invalid number '{}'", text::show_token(line, pos)),
                ))
            }
        }
    }
    Ok(p)
}

/// Reads a face record that starts on `line` into `indices`: its vertex count, then that
/// many indices, on the next lines when `line` ends first. Returns the vertex count and
/// whether the record continued.
fn face(
    line: &[u8],
    no: u64,
    lines: &mut Lines<'_>,
    vertices: usize,
    indices: &mut Vec<u32>,
) -> Result<(usize, bool), ParseError> {
    let mut pos = 0;
    let k = count(line, &mut pos, no, "face's vertex count")?;
    let first = indices.len();
    let (mut line, mut line_no, mut continued) = (line, no, false);
    let mut found = 0u64;
    while found < k {
        pos = text::skip_blank(line, pos);
        if pos >= line.len() {
            let Some((next_no, next)) = lines.next() else {
                indices.truncate(first);
                return Err(ParseError::line(
                    no,
                    format!("face declares {k} vertices but the file ends after {found} indices"),
                ));
            };
            (line, line_no, pos, continued) = (next, next_no, 0, true);
            continue;
        }
        let Some((index, end)) = integer(line, pos) else {
            indices.truncate(first);
            return Err(ParseError::line(
                line_no,
                format!("invalid vertex index '{}'", text::show_token(line, pos)),
            ));
        };
        if index < 0 || index as u64 >= vertices as u64 {
            indices.truncate(first);
            return Err(ParseError::line(
                line_no,
                format!("vertex index {index} is out of range: the file has {vertices} vertices"),
            ));
        }
        indices.push(index as u32);
        pos = end;
        found += 1;
    }
    Ok((k as usize, continued))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords() {
        assert!(matches!(keyword(b"OFF"), Keyword::Off(3)));
        assert!(matches!(keyword(b"  CNOFF 1 2"), Keyword::Off(7)));
        assert!(matches!(keyword(b"STCOFF"), Keyword::Off(6)));
        assert!(matches!(keyword(b"OFF8 6 12"), Keyword::Off(3)));
        assert!(matches!(keyword(b"4OFF"), Keyword::Unsupported(_)));
        assert!(matches!(keyword(b"8 6 12"), Keyword::None));
    }
}
