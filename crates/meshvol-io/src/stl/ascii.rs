//! ASCII STL: `solid` blocks of facets, parsed in parallel in chunks cut at lines that
//! start with `facet` (see the module docs of [`crate::stl`] for what is read).

use meshvol::{Mesh, Point};
use rayon::prelude::*;

use super::soup_mesh;
use crate::error::{line_of, ParseError};
use crate::object::Object;
use crate::text::{self, NumberError};

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
        use crate::text::mutate::{assert_chunking_invisible, outcome};
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
            outcome(|w| {
                read_ascii_chunked(bytes, w, chunk)
                    .map(|(m, objects)| (m.positions().to_vec(), objects))
            })
        };
        let (ok, err) =
            assert_chunking_invisible(file.as_bytes(), pieces, 7, 3000, &[1, 30, 150], run);
        assert!(ok > 100 && err > 100, "{ok} {err}");
    }
}
