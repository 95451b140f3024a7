//! STL, binary and ASCII.
//!
//! # Binary
//!
//! An 80-byte header (free text; it often starts with `solid`), a little-endian `u32`
//! triangle count n, then n records of 50 bytes: a normal (3 × `f32`, ignored), three
//! vertices (3 × 3 × `f32`, little-endian), and a `u16` attribute (ignored).
//!
//! # ASCII
//!
//! ```text
//! solid [name]
//!   facet normal nx ny nz
//!     outer loop
//!       vertex x y z
//!       vertex x y z
//!       vertex x y z
//!     endloop
//!   endfacet
//! endsolid [name]
//! ```
//!
//! Keywords in any case, tokens separated by any whitespace (CRLF included), a name that
//! is the rest of the `solid` / `endsolid` line (possibly empty, as OpenSCAD and FreeCAD
//! write it), and any number of `solid` blocks, whose triangles are concatenated; with
//! two or more solids each is an [`Object`] named after its `solid` line. The normal is not read (writers put `nan` there for
//! degenerate facets). Each facet must have exactly three vertices. A file that ends
//! inside a solid after a complete facet is accepted with a warning; one that ends inside
//! a facet is an error.
//!
//! # Telling them apart
//!
//! By size, never by the word `solid` (binary headers often start with it): a file whose
//! length is exactly 84 + 50·n, n the count at byte 80, is binary. Otherwise a file that
//! is text and starts (after whitespace or a byte order mark) with `solid` is ASCII; a
//! longer file is binary with ignored trailing bytes (a warning); a shorter one is a
//! truncated binary file (an error).
//!
//! # Storage
//!
//! A binary file is not copied: [`StlSoup`] keeps the file's bytes (a memory map) and
//! reads each triangle's `f32` coordinates from them, widened to `f64`. Every coordinate
//! is checked to be finite once, in parallel, when the file is opened. An ASCII file is
//! parsed in parallel (chunks cut at lines that start with `facet`) into a
//! [`Mesh`] with three unshared vertices per facet.

use meshvol::{Mesh, MeshError, Point, Surface};
use rayon::prelude::*;

use crate::error::{line_of, Location, ParseError};
use crate::source::Bytes;
use crate::text::{self, NumberError};
use crate::Object;

/// Bytes before the first record: the 80-byte header and the triangle count.
const DATA: usize = 84;
/// Bytes per triangle record.
const RECORD: usize = 50;
/// Where the triangle count sits.
const COUNT: usize = 80;

/// What an STL file's bytes hold.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Binary with `triangles` records, followed by `trailing` bytes that are ignored.
    Binary {
        triangles: usize,
        trailing: u64,
    },
    Ascii,
}

/// Tells binary from ASCII STL (see the module docs).
pub(crate) fn classify(bytes: &[u8]) -> Result<Kind, ParseError> {
    let len = bytes.len() as u64;
    let declared = declared_triangles(bytes);
    let needed = declared.map(|n| DATA as u64 + RECORD as u64 * u64::from(n));
    if needed == Some(len) {
        return binary_kind(declared, 0);
    }
    if is_ascii_stl(bytes) {
        return Ok(Kind::Ascii);
    }
    let (Some(n), Some(needed)) = (declared, needed) else {
        let message = if bytes.is_empty() {
            "empty file".to_string()
        } else {
            format!(
                "{len} bytes is too short for a binary STL (its header alone is 84 bytes), \
                 and it is not an ASCII STL (it does not start with 'solid')"
            )
        };
        return Err(ParseError::new(None, message));
    };
    if len > needed {
        return binary_kind(Some(n), len - needed);
    }
    Err(ParseError::new(
        Some(Location::Byte(len)),
        format!(
            "truncated: header claims {n} triangles (needs {needed} bytes) but the file has \
             {len} bytes"
        ),
    ))
}

fn binary_kind(declared: Option<u32>, trailing: u64) -> Result<Kind, ParseError> {
    let n = declared.unwrap_or(0);
    let triangles = usize::try_from(n).map_err(|_| {
        ParseError::new(None, format!("{n} triangles do not fit this machine's address space"))
    })?;
    Ok(Kind::Binary { triangles, trailing })
}

/// The triangle count of a binary header, if the file is long enough to have one.
fn declared_triangles(bytes: &[u8]) -> Option<u32> {
    let raw = bytes.get(COUNT..DATA)?;
    Some(u32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]]))
}

/// Whether the bytes start, after whitespace or a BOM, with the word `solid` and look
/// like text for their first kilobyte.
pub(crate) fn is_ascii_stl(bytes: &[u8]) -> bool {
    let start = text::skip_space(bytes, text::bom_len(bytes));
    let rest = &bytes[start..];
    text::starts_with_word(rest, b"solid")
        && text::looks_like_text(&bytes[..bytes.len().min(start + 1024)])
}

/// Whether `bytes` satisfy the binary size rule exactly.
pub(crate) fn is_binary_stl_by_size(bytes: &[u8]) -> bool {
    declared_triangles(bytes)
        .is_some_and(|n| DATA as u64 + RECORD as u64 * u64::from(n) == bytes.len() as u64)
}

/// A binary STL's triangles, read straight from the file's bytes: a triangle soup (no
/// shared vertices), each face one triangle.
///
/// Built only by the readers, which check that every coordinate is finite.
pub struct StlSoup {
    bytes: Bytes,
    triangles: usize,
}

impl std::fmt::Debug for StlSoup {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StlSoup")
            .field("header", &String::from_utf8_lossy(self.header()))
            .field("triangles", &self.triangles)
            .finish()
    }
}

impl StlSoup {
    /// Checks the records (every vertex coordinate finite) and wraps the bytes.
    /// `bytes` must hold at least `84 + 50 * triangles` bytes.
    pub(crate) fn new(bytes: Bytes, triangles: usize) -> Result<StlSoup, ParseError> {
        let end = triangles
            .checked_mul(RECORD)
            .and_then(|n| n.checked_add(DATA))
            .filter(|&end| end <= bytes.len())
            .ok_or_else(|| ParseError::new(None, "triangle records exceed the file"))?;
        check_finite(&bytes[DATA..end])?;
        Ok(StlSoup { bytes, triangles })
    }

    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// The 80-byte header, as written (often text such as `solid name` or
    /// `COLOR=` for Materialise / VisCAM colours).
    pub fn header(&self) -> &[u8] {
        &self.bytes[..COUNT]
    }

    /// The three vertices of triangle `i`, widened to `f64`.
    ///
    /// # Panics
    /// If `i >= self.triangle_count()`.
    #[inline]
    pub fn triangle(&self, i: usize) -> [Point; 3] {
        assert!(i < self.triangles, "triangle {i} of {}", self.triangles);
        let start = DATA + RECORD * i;
        let record: &[u8; RECORD] = self.bytes[start..start + RECORD]
            .try_into()
            .expect("a record slice is RECORD bytes long");
        [vertex(record, 12), vertex(record, 24), vertex(record, 36)]
    }

    /// The 16-bit attribute of triangle `i` (a colour in some writers).
    ///
    /// # Panics
    /// If `i >= self.triangle_count()`.
    pub fn attribute(&self, i: usize) -> u16 {
        assert!(i < self.triangles, "triangle {i} of {}", self.triangles);
        let at = DATA + RECORD * i + 48;
        u16::from_le_bytes([self.bytes[at], self.bytes[at + 1]])
    }

    /// The same triangles as a [`Mesh`] with three unshared vertices per triangle
    /// (no welding).
    pub fn to_mesh(&self) -> Result<Mesh, MeshError> {
        let positions: Vec<Point> =
            (0..self.triangles).into_par_iter().flat_map_iter(|i| self.triangle(i)).collect();
        soup_mesh(positions)
    }
}

#[inline]
fn vertex(record: &[u8; RECORD], at: usize) -> Point {
    [f32_at(record, at), f32_at(record, at + 4), f32_at(record, at + 8)]
}

#[inline]
fn f32_at(record: &[u8; RECORD], at: usize) -> f64 {
    f64::from(f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]]))
}

impl Surface for StlSoup {
    fn face_count(&self) -> usize {
        self.triangles
    }

    #[inline]
    fn fan(&self, face: usize, mut triangle: impl FnMut(Point, Point, Point)) {
        let [a, b, c] = StlSoup::triangle(self, face);
        triangle(a, b, c);
    }
}

/// Records per parallel work item when checking coordinates.
const CHECK_CHUNK: usize = 16 * 1024;

/// Finds the first record (in file order) with a NaN or infinite vertex coordinate.
fn check_finite(records: &[u8]) -> Result<(), ParseError> {
    let bad = records.par_chunks(RECORD * CHECK_CHUNK).enumerate().find_map_first(|(c, chunk)| {
        chunk.chunks_exact(RECORD).enumerate().find_map(|(r, record)| {
            (12..48).step_by(4).find_map(|at| {
                let bits = u32::from_le_bytes([
                    record[at],
                    record[at + 1],
                    record[at + 2],
                    record[at + 3],
                ]);
                // All exponent bits set: infinity or NaN.
                (bits & 0x7f80_0000 == 0x7f80_0000).then_some((c * CHECK_CHUNK + r, at, bits))
            })
        })
    });
    match bad {
        None => Ok(()),
        Some((triangle, at, bits)) => {
            let value = f32::from_bits(bits);
            let vertex = (at - 12) / 12;
            let axis = ["x", "y", "z"][(at - 12) % 12 / 4];
            let byte = DATA + RECORD * triangle + at;
            Err(ParseError::new(
                Some(Location::Face(triangle)),
                format!("non-finite coordinate {value} in vertex {vertex} ({axis}) at byte {byte}"),
            ))
        }
    }
}

/// A mesh of unshared triangles: vertices 3i, 3i + 1, 3i + 2 form triangle i.
fn soup_mesh(positions: Vec<Point>) -> Result<Mesh, MeshError> {
    let n = positions.len();
    if u32::try_from(n).is_err() {
        return Err(MeshError::TooManyVertices { vertices: n });
    }
    let triangles = (0..n as u32 / 3).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    Mesh::from_triangles(positions, triangles)
}

/// Reads a binary STL whose layout [`classify`] accepted.
pub(crate) fn read_binary(
    bytes: Bytes,
    triangles: usize,
    trailing: u64,
    warnings: &mut Vec<String>,
) -> Result<StlSoup, ParseError> {
    if trailing > 0 {
        warnings.push(format!(
            "{trailing} bytes after the {triangles} triangles the header declares were ignored"
        ));
    }
    StlSoup::new(bytes, triangles)
}

/// Where a chunk of an ASCII file starts and ends, in what state it starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    /// Between solids: expecting `solid` or the end.
    Outside,
    /// Inside a solid: expecting `facet` or `endsolid`.
    InSolid,
}

/// What one chunk of an ASCII file gave.
struct Chunk {
    positions: Vec<Point>,
    /// The solids opened in the chunk.
    solids: Vec<Solid>,
    end_state: State,
    /// The first token of the chunk (where a state mismatch is reported).
    first_token: usize,
    error: Option<(usize, String)>,
}

/// A `solid` line: the byte range of its name, and the chunk's facet count before it.
#[derive(Clone, Copy)]
struct Solid {
    name: (usize, usize),
    first_facet: usize,
}

/// Target bytes per parallel chunk of an ASCII file.
const ASCII_CHUNK: usize = 1 << 20;

/// Parses an ASCII STL into a mesh with three vertices per facet, and its solids.
pub(crate) fn read_ascii(
    bytes: &[u8],
    warnings: &mut Vec<String>,
) -> Result<(Mesh, Vec<Object>), ParseError> {
    read_ascii_chunked(bytes, warnings, ASCII_CHUNK)
}

/// [`read_ascii`] with chunks of about `chunk` bytes.
fn read_ascii_chunked(
    bytes: &[u8],
    warnings: &mut Vec<String>,
    chunk: usize,
) -> Result<(Mesh, Vec<Object>), ParseError> {
    let start = text::bom_len(bytes);
    let bounds = facet_boundaries(bytes, start, chunk.max(1));
    let chunks: Vec<Chunk> = bounds
        .par_windows(2)
        .enumerate()
        .map(|(i, w)| {
            let state = if i == 0 { State::Outside } else { State::InSolid };
            parse_chunk(bytes, w[0], w[1], state)
        })
        .collect();

    let mut state = State::Outside;
    for (i, chunk) in chunks.iter().enumerate() {
        if i > 0 && state != State::InSolid {
            let at = chunk.first_token;
            let found = text::show_token(bytes, at);
            return Err(ParseError::at_offset(
                bytes,
                at,
                format!("expected 'solid', found '{found}'"),
            ));
        }
        if let Some((at, message)) = &chunk.error {
            return Err(ParseError::at_offset(bytes, *at, message.clone()));
        }
        state = chunk.end_state;
    }
    if state == State::InSolid {
        warnings.push(format!(
            "the file ends at line {} without 'endsolid'",
            line_of(bytes, bytes.len())
        ));
    }

    // Each solid runs to the next one's first facet.
    let mut starts = Vec::new();
    let mut facets = 0;
    for chunk in &chunks {
        starts.extend(chunk.solids.iter().map(|s| (s.name, facets + s.first_facet)));
        facets += chunk.positions.len() / 3;
    }
    let objects = starts
        .iter()
        .enumerate()
        .map(|(i, &((s, e), first))| Object {
            name: text::lossy_name(&bytes[s..e]),
            faces: first..starts.get(i + 1).map_or(facets, |next| next.1),
        })
        .collect();

    let mut positions = Vec::with_capacity(3 * facets);
    for chunk in chunks {
        positions.extend_from_slice(&chunk.positions);
    }
    let mesh = soup_mesh(positions).map_err(|e| ParseError::new(None, e.to_string()))?;
    Ok((mesh, objects))
}

/// Chunk boundaries: `start`, then line starts whose first token is `facet`, at least
/// `target` bytes apart, then the end.
fn facet_boundaries(bytes: &[u8], start: usize, target: usize) -> Vec<usize> {
    let mut bounds = vec![start];
    let mut from = start.saturating_add(target);
    'outer: while from < bytes.len() {
        let mut line = match memchr::memchr(b'\n', &bytes[from..]) {
            Some(i) => from + i + 1,
            None => break,
        };
        loop {
            let first = text::skip_blank(bytes, line);
            if text::starts_with_word(&bytes[first..], b"facet") {
                bounds.push(line);
                from = line.saturating_add(target);
                continue 'outer;
            }
            match memchr::memchr(b'\n', &bytes[line..]) {
                Some(i) => line += i + 1,
                None => break 'outer,
            }
        }
    }
    bounds.push(bytes.len());
    bounds
}

/// A token: where it starts and ends.
#[derive(Clone, Copy)]
struct Token {
    start: usize,
    end: usize,
}

/// Reads tokens of the whole file from a position.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    #[inline]
    fn next(&mut self) -> Option<Token> {
        let start = text::skip_space(self.bytes, self.pos);
        if start >= self.bytes.len() {
            self.pos = start;
            return None;
        }
        let end = text::token_end(self.bytes, start);
        self.pos = end;
        Some(Token { start, end })
    }

    #[inline]
    fn is(&self, token: Token, word: &[u8]) -> bool {
        self.bytes[token.start..token.end].eq_ignore_ascii_case(word)
    }

    fn show(&self, token: Token) -> String {
        text::show(&self.bytes[token.start..token.end])
    }

    /// Skips to the end of the line (for `solid` and `endsolid` names); returns the
    /// name's range, trimmed.
    fn rest_of_line(&mut self) -> (usize, usize) {
        let end = memchr::memchr(b'\n', &self.bytes[self.pos..])
            .map_or(self.bytes.len(), |i| self.pos + i);
        let mut s = text::skip_blank(self.bytes, self.pos).min(end);
        let mut e = end;
        while e > s && text::is_space(self.bytes[e - 1]) {
            e -= 1;
        }
        if s > e {
            s = e;
        }
        self.pos = end;
        (s, e)
    }

    /// An error for a missing keyword at the next token (or the end of the file).
    fn expected(&mut self, what: &str) -> (usize, String) {
        match self.next() {
            Some(t) => (t.start, format!("expected {what}, found '{}'", self.show(t))),
            None => (self.bytes.len(), format!("expected {what}, found the end of the file")),
        }
    }

    fn expect(&mut self, word: &[u8], what: &str) -> Result<(), (usize, String)> {
        let save = self.pos;
        match self.next() {
            Some(t) if self.is(t, word) => Ok(()),
            _ => {
                self.pos = save;
                Err(self.expected(what))
            }
        }
    }
}

/// Parses the chunk `[start, end)` (whole facets), starting in `state`.
fn parse_chunk(bytes: &[u8], start: usize, end: usize, mut state: State) -> Chunk {
    let mut cur = Cursor { bytes, pos: start };
    let mut chunk = Chunk {
        positions: Vec::with_capacity((end - start) / 80),
        solids: Vec::new(),
        end_state: state,
        first_token: text::skip_space(bytes, start),
        error: None,
    };
    let result = loop {
        let Some(tok) = cur.next() else { break Ok(()) };
        if tok.start >= end {
            break Ok(());
        }
        match state {
            State::Outside if cur.is(tok, b"solid") => {
                let name = cur.rest_of_line();
                chunk.solids.push(Solid { name, first_facet: chunk.positions.len() / 3 });
                state = State::InSolid;
            }
            State::Outside => {
                break Err((tok.start, format!("expected 'solid', found '{}'", cur.show(tok))))
            }
            State::InSolid if cur.is(tok, b"facet") => {
                if let Err(e) = parse_facet(&mut cur, tok, &mut chunk.positions) {
                    break Err(e);
                }
            }
            State::InSolid if cur.is(tok, b"endsolid") => {
                cur.rest_of_line();
                state = State::Outside;
            }
            State::InSolid => {
                break Err((
                    tok.start,
                    format!("expected 'facet' or 'endsolid', found '{}'", cur.show(tok)),
                ))
            }
        }
    };
    chunk.end_state = state;
    chunk.error = result.err();
    chunk
}

/// Parses one facet after its `facet` token, pushing its three vertices.
fn parse_facet(
    cur: &mut Cursor<'_>,
    facet: Token,
    positions: &mut Vec<Point>,
) -> Result<(), (usize, String)> {
    // The normal: skipped up to `outer`, whatever it holds.
    loop {
        let save = cur.pos;
        match cur.next() {
            Some(t) if cur.is(t, b"outer") => break,
            Some(t) if cur.is(t, b"normal") => {}
            Some(t) if !is_keyword(&cur.bytes[t.start..t.end]) => {}
            _ => {
                cur.pos = save;
                return Err(cur.expected("'outer loop'"));
            }
        }
    }
    cur.expect(b"loop", "'loop' after 'outer'")?;
    let mut count = 0usize;
    loop {
        let save = cur.pos;
        match cur.next() {
            Some(t) if cur.is(t, b"vertex") => {
                let p = parse_vertex(cur, t)?;
                if count < 3 {
                    positions.push(p);
                }
                count += 1;
            }
            Some(t) if cur.is(t, b"endloop") => break,
            _ => {
                cur.pos = save;
                return Err(cur.expected("'vertex' or 'endloop'"));
            }
        }
    }
    if count != 3 {
        return Err((
            facet.start,
            format!("facet has {count} vertices; an STL facet needs exactly 3"),
        ));
    }
    cur.expect(b"endfacet", "'endfacet'")
}

/// Whether a token is one of the STL keywords (which cannot be part of a normal).
fn is_keyword(token: &[u8]) -> bool {
    [&b"vertex"[..], b"endloop", b"endfacet", b"facet", b"solid", b"endsolid", b"loop"]
        .iter()
        .any(|k| token.eq_ignore_ascii_case(k))
}

/// Reads the three coordinates after a `vertex` token.
#[inline]
fn parse_vertex(cur: &mut Cursor<'_>, vertex: Token) -> Result<Point, (usize, String)> {
    let mut p = [0.0; 3];
    for (found, c) in p.iter_mut().enumerate() {
        let at = text::skip_space(cur.bytes, cur.pos);
        match text::parse_f64(cur.bytes, at) {
            Ok((value, end)) => {
                *c = value;
                cur.pos = end;
            }
            Err(NumberError::Missing) => {
                return Err((
                    vertex.start,
                    format!("expected 3 coordinates after 'vertex', found {found}"),
                ))
            }
            Err(NumberError::Invalid) => {
                return Err((at, format!("invalid number '{}'", text::show_token(cur.bytes, at))))
            }
            Err(NumberError::NonFinite) => {
                return Err((
                    at,
                    format!("non-finite coordinate '{}'", text::show_token(cur.bytes, at)),
                ))
            }
        }
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classify_by_size_then_solid() {
        let mut bin = b"solid looks like text".to_vec();
        bin.resize(80, b' ');
        bin.extend_from_slice(&1u32.to_le_bytes());
        bin.extend_from_slice(&[0u8; 50]);
        assert_eq!(classify(&bin), Ok(Kind::Binary { triangles: 1, trailing: 0 }));
        assert_eq!(classify(b"solid\nendsolid\n"), Ok(Kind::Ascii));
        assert_eq!(classify(b"\xEF\xBB\xBF  solid x\nendsolid x"), Ok(Kind::Ascii));
        assert!(classify(b"").is_err());
        assert!(classify(b"solidity").is_err());
        bin.extend_from_slice(b"xyz");
        assert_eq!(classify(&bin), Ok(Kind::Binary { triangles: 1, trailing: 3 }));
    }

    #[test]
    fn boundaries_are_at_facet_lines() {
        let facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
        let file = format!("solid a\n{}endsolid a\n", facet.repeat(10));
        let bounds = facet_boundaries(file.as_bytes(), 0, 100);
        assert!(bounds.len() > 3);
        for &b in &bounds[1..bounds.len() - 1] {
            assert!(file[b..].starts_with("facet"));
        }
        let mut warnings = vec![];
        let chunks: Vec<_> = bounds
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                let s = if i == 0 { State::Outside } else { State::InSolid };
                parse_chunk(file.as_bytes(), w[0], w[1], s).positions.len()
            })
            .collect();
        assert_eq!(chunks.iter().sum::<usize>(), 30);
        assert_eq!(read_ascii(file.as_bytes(), &mut warnings).unwrap().0.face_count(), 10);
    }

    /// Any chunking gives what one sequential pass gives: the same triangles or the same
    /// error at the same place, and the same warnings.
    #[test]
    fn chunking_does_not_change_the_result() {
        use crate::text::mutate::assert_chunking_invisible;
        let facet = |x: f64| {
            format!(
                "  facet normal 0 0 1\n    outer loop\n      vertex {x} 0 0\n      vertex 1 {x} 0\n      vertex 0 1 {x}\n    endloop\n  endfacet\n"
            )
        };
        let mut file = String::from("solid a\n");
        for i in 0..6 {
            file += &facet(i as f64);
        }
        file += "endsolid a\nsolid\n";
        for i in 0..5 {
            file += &facet(10.0 + i as f64);
        }
        file += "endsolid\n";
        let pieces: &[&[u8]] = &[
            b"facet",
            b"\nfacet ",
            b"endfacet\n",
            b"solid x\n",
            b"\nendsolid\n",
            b"vertex 1 2 3\n",
            b"outer loop",
            b"endloop",
            b"\n",
            b" ",
            b"nan",
            b"1e999",
            b"x",
        ];
        let run = |bytes: &[u8], chunk: usize| {
            let mut warnings = vec![];
            let result = read_ascii_chunked(bytes, &mut warnings, chunk)
                .map(|(m, objects)| (m.positions().to_vec(), objects))
                .map_err(|e| (e.location, e.message));
            (result, warnings)
        };
        let (ok, err) =
            assert_chunking_invisible(file.as_bytes(), pieces, 7, 3000, &[1, 30, 150], run);
        assert!(ok > 100 && err > 100, "{ok} {err}");
    }
}
