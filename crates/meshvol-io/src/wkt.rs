//! WKT (well-known text) polygons: reading `POLYGON`, `MULTIPOLYGON` and
//! `GEOMETRYCOLLECTION`s of them, and writing a `MULTIPOLYGON`.
//!
//! ```text
//! POLYGON ((0 0, 4 0, 4 2, 0 2, 0 0), (1 0.5, 2 0.5, 2 1.5, 1 1.5, 1 0.5))
//! MULTIPOLYGON (((0 0, 1 0, 1 1, 0 0)), ((5 5, 6 5, 6 6, 5 5)))
//! SRID=25832;POLYGON Z ((500000 6000000 12, 500010 6000000 12, 500010 6000010 12, 500000 6000000 12))
//! ```
//!
//! A file may hold several geometries, separated by white space or `;`: each is a
//! feature. Keywords are read in any case; `Z`, `M` and `ZM` coordinates are accepted
//! and only x and y are used; an EWKT `SRID=…;` prefix is skipped; `EMPTY` gives an
//! empty feature. A ring's closing copy of its first point is dropped; a ring that is
//! not closed is closed implicitly, with a warning. Geometries without area (`POINT`,
//! `LINESTRING`, …) are errors. Errors give the line and the column.
//!
//! The own parser (and not the `wkt` crate) is for the located errors; the format is
//! small.

use std::io::{self, Write};

use meshvol::polygon::{Point2, Polygon};

use crate::error::ParseError;
use crate::polygon_feature::PolygonFeature;
use crate::text;

/// Nesting deeper than this is refused (GEOMETRYCOLLECTIONs inside each other), so
/// hostile input cannot exhaust the stack.
const MAX_DEPTH: u32 = 64;

struct Parser<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: u64,
    line_start: usize,
    /// Rings that were not closed, for one warning.
    unclosed: usize,
    first_unclosed_line: u64,
    /// Whether some coordinates had more than two numbers.
    extra_dimensions: bool,
}

impl<'a> Parser<'a> {
    fn error(&self, message: impl std::fmt::Display) -> ParseError {
        let column = self.pos.saturating_sub(self.line_start) + 1;
        ParseError::line(self.line, format!("column {column}: {message}"))
    }

    /// What is at the current position, for messages.
    fn found(&self) -> String {
        if self.pos >= self.bytes.len() {
            "the end of the file".to_string()
        } else {
            let end = (self.pos..self.bytes.len())
                .find(|&i| {
                    matches!(self.bytes[i], b',' | b'(' | b')' | b';')
                        || text::is_space(self.bytes[i])
                })
                .unwrap_or(self.bytes.len());
            let end = end.max(self.pos + 1);
            format!("'{}'", text::show(&self.bytes[self.pos..end]))
        }
    }

    fn skip_space(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if b == b'\n' {
                self.line += 1;
                self.line_start = self.pos + 1;
            } else if !text::is_blank(b) {
                break;
            }
            self.pos += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_space();
        self.bytes.get(self.pos).copied()
    }

    fn expect(&mut self, byte: u8, what: &str) -> Result<(), ParseError> {
        if self.peek() == Some(byte) {
            self.pos += 1;
            Ok(())
        } else {
            Err(self.error(format!("expected {what}, found {}", self.found())))
        }
    }

    /// A keyword (letters, digits after the first, `_`), upper-cased.
    fn word(&mut self) -> Option<String> {
        self.skip_space();
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_') {
            self.pos += 1;
        }
        (self.pos > start)
            .then(|| String::from_utf8_lossy(&self.bytes[start..self.pos]).to_ascii_uppercase())
    }

    fn number(&mut self) -> Result<f64, ParseError> {
        self.skip_space();
        let rest = &self.bytes[self.pos..];
        match fast_float2::parse_partial::<f64, _>(rest) {
            Ok((value, used))
                if rest
                    .get(used)
                    .is_none_or(|&b| matches!(b, b',' | b')' | b'(') || text::is_space(b)) =>
            {
                if !value.is_finite() {
                    return Err(self.error(format!("{} is not a finite number", self.found())));
                }
                self.pos += used;
                Ok(value)
            }
            _ => Err(self.error(format!("expected a number, found {}", self.found()))),
        }
    }

    /// `x y [z [m]]`: the first two.
    fn position(&mut self) -> Result<Point2, ParseError> {
        let x = self.number()?;
        let y = self.number()?;
        while !matches!(self.peek(), Some(b',' | b')') | None) {
            self.number()?;
            self.extra_dimensions = true;
        }
        Ok([x, y])
    }

    /// `(p, p, …)`, without the closing copy of the first point.
    fn ring(&mut self) -> Result<Vec<Point2>, ParseError> {
        self.expect(b'(', "'(' to open a ring")?;
        let line = self.line;
        let mut ring = vec![self.position()?];
        while self.peek() == Some(b',') {
            self.pos += 1;
            ring.push(self.position()?);
        }
        self.expect(b')', "',' or ')' after a coordinate")?;
        if ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        } else {
            if self.unclosed == 0 {
                self.first_unclosed_line = line;
            }
            self.unclosed += 1;
        }
        Ok(ring)
    }

    /// `EMPTY` (true) or nothing (false): after a type keyword and its dimension.
    fn empty(&mut self) -> Result<bool, ParseError> {
        let save = (self.pos, self.line, self.line_start);
        match self.word().as_deref() {
            Some("EMPTY") => Ok(true),
            Some("Z" | "M" | "ZM") => self.empty(),
            Some(other) => Err(self.error(format!("expected '(' or EMPTY, found '{other}'"))),
            None => {
                (self.pos, self.line, self.line_start) = save;
                Ok(false)
            }
        }
    }

    /// The body of a POLYGON: `((ring), (hole), …)`.
    fn polygon(&mut self) -> Result<Polygon, ParseError> {
        self.expect(b'(', "'(' to open a polygon")?;
        let exterior = self.ring()?;
        let mut holes = Vec::new();
        while self.peek() == Some(b',') {
            self.pos += 1;
            holes.push(self.ring()?);
        }
        self.expect(b')', "',' or ')' after a ring")?;
        Ok(Polygon::new(exterior, holes))
    }

    /// A geometry, its polygons appended to `out`.
    fn geometry(&mut self, out: &mut Vec<Polygon>, depth: u32) -> Result<(), ParseError> {
        if depth > MAX_DEPTH {
            return Err(self.error(format!("geometries nested more than {MAX_DEPTH} deep")));
        }
        let start = self.pos;
        let Some(kind) = self.word() else {
            return Err(self.error(format!("expected a geometry type, found {}", self.found())));
        };
        match kind.as_str() {
            "POLYGON" => {
                if !self.empty()? {
                    out.push(self.polygon()?);
                }
            }
            "MULTIPOLYGON" => {
                if !self.empty()? {
                    self.expect(b'(', "'(' to open a multipolygon")?;
                    out.push(self.polygon()?);
                    while self.peek() == Some(b',') {
                        self.pos += 1;
                        out.push(self.polygon()?);
                    }
                    self.expect(b')', "',' or ')' after a polygon")?;
                }
            }
            "GEOMETRYCOLLECTION" => {
                if !self.empty()? {
                    self.expect(b'(', "'(' to open a geometry collection")?;
                    self.geometry(out, depth + 1)?;
                    while self.peek() == Some(b',') {
                        self.pos += 1;
                        self.geometry(out, depth + 1)?;
                    }
                    self.expect(b')', "',' or ')' after a geometry")?;
                }
            }
            "POINT" | "MULTIPOINT" | "LINESTRING" | "MULTILINESTRING" | "CIRCULARSTRING"
            | "COMPOUNDCURVE" => {
                self.pos = start;
                return Err(self.error(format!(
                    "a {kind} has no area: expected POLYGON, MULTIPOLYGON or GEOMETRYCOLLECTION"
                )));
            }
            _ => {
                self.pos = start;
                return Err(self.error(format!(
                    "'{kind}' is not a geometry type read here: expected POLYGON, \
                     MULTIPOLYGON or GEOMETRYCOLLECTION"
                )));
            }
        }
        Ok(())
    }

    /// An optional EWKT `SRID=…;` prefix.
    fn srid(&mut self) {
        self.skip_space();
        let rest = &self.bytes[self.pos..];
        if rest.len() >= 5 && rest[..5].eq_ignore_ascii_case(b"SRID=") {
            if let Some(semicolon) = memchr::memchr(b';', rest) {
                self.pos += semicolon + 1;
            }
        }
    }
}

/// Reads every geometry of a WKT file, one feature each.
pub(crate) fn read(
    bytes: &[u8],
    warnings: &mut Vec<String>,
) -> Result<Vec<PolygonFeature>, ParseError> {
    let start = text::bom_len(bytes);
    let mut p = Parser {
        bytes,
        pos: start,
        line: 1,
        line_start: start,
        unclosed: 0,
        first_unclosed_line: 0,
        extra_dimensions: false,
    };
    let mut features = Vec::new();
    loop {
        while matches!(p.peek(), Some(b';')) {
            p.pos += 1;
        }
        if p.peek().is_none() {
            break;
        }
        p.srid();
        let mut polygons = Vec::new();
        p.geometry(&mut polygons, 0)?;
        features.push(PolygonFeature { name: None, polygons });
    }
    if features.is_empty() {
        return Err(ParseError::new(None, "no geometry: the file is empty"));
    }
    if p.unclosed > 0 {
        warnings.push(format!(
            "{} ring(s) not closed (first at line {}): closed implicitly",
            p.unclosed, p.first_unclosed_line
        ));
    }
    if p.extra_dimensions {
        warnings.push("coordinates have z or m values: only x and y are used".to_string());
    }
    Ok(features)
}

/// Writes one ring, closed, as `(x y, x y, …)`.
fn write_ring(out: &mut impl Write, ring: &[Point2]) -> io::Result<()> {
    out.write_all(b"(")?;
    for (i, p) in ring.iter().chain(ring.first()).enumerate() {
        if i > 0 {
            out.write_all(b", ")?;
        }
        write!(out, "{} {}", p[0], p[1])?;
    }
    out.write_all(b")")
}

/// Writes polygons as one `MULTIPOLYGON` (or `MULTIPOLYGON EMPTY`) and a newline, in
/// Rust's shortest round-trip number form: reading it back gives the same bits.
///
/// ```
/// use meshvol::polygon::Polygon;
/// let square = Polygon::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], vec![]);
/// let mut out = Vec::new();
/// meshvol_io::wkt::write_multipolygon(&mut out, &[square]).unwrap();
/// assert_eq!(String::from_utf8(out).unwrap(), "MULTIPOLYGON (((0 0, 1 0, 1 1, 0 1, 0 0)))\n");
/// ```
pub fn write_multipolygon(out: &mut impl Write, polygons: &[Polygon]) -> io::Result<()> {
    if polygons.is_empty() {
        return out.write_all(b"MULTIPOLYGON EMPTY\n");
    }
    out.write_all(b"MULTIPOLYGON (")?;
    for (i, polygon) in polygons.iter().enumerate() {
        if i > 0 {
            out.write_all(b", ")?;
        }
        out.write_all(b"(")?;
        for (k, ring) in polygon.rings().enumerate() {
            if k > 0 {
                out.write_all(b", ")?;
            }
            write_ring(out, ring)?;
        }
        out.write_all(b")")?;
    }
    out.write_all(b")\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<(Vec<PolygonFeature>, Vec<String>), ParseError> {
        crate::polygon_feature::with_warnings(read, s)
    }

    #[test]
    fn reads_polygons_multipolygons_and_collections() {
        let (f, w) = parse(
            "POLYGON ((0 0, 4 0, 4 2, 0 2, 0 0), (1 1, 2 1, 2 1.5, 1 1))\n\
             multipolygon (((0 0, 1 0, 1 1, 0 0)), ((5 5, 6 5, 6 6, 5 5)));\n\
             SRID=25832;GEOMETRYCOLLECTION (POLYGON Z ((0 0 1, 1 0 1, 1 1 1, 0 0 1)), POLYGON EMPTY)\n\
             POLYGON EMPTY",
        )
        .unwrap();
        assert_eq!(f.len(), 4);
        assert_eq!(f[0].polygons[0].exterior, vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]]);
        assert_eq!(f[0].polygons[0].holes[0].len(), 3);
        assert_eq!(f[1].polygons.len(), 2);
        assert_eq!(f[2].polygons.len(), 1);
        assert!(f[3].polygons.is_empty());
        assert_eq!(w, vec!["coordinates have z or m values: only x and y are used"]);
    }

    #[test]
    fn errors_give_line_and_column() {
        let e = parse("POLYGON ((0 0, 1 0,\n 1 x, 0 0))").unwrap_err();
        assert_eq!(e.to_string_for_test(), "line 2: column 4: expected a number, found 'x'");
        let e = parse("LINESTRING (0 0, 1 1)").unwrap_err();
        assert!(e.message.contains("has no area"), "{}", e.message);
        let e = parse("POLYGON ((0 0, 1 0, 1 1, 0 0)").unwrap_err();
        assert_eq!(
            e.to_string_for_test(),
            "line 1: column 30: expected ',' or ')' after a ring, found the end of the file"
        );
        let e = parse("POLYGON ((0 0, 1e999 0, 1 1, 0 0))").unwrap_err();
        assert!(e.message.contains("not a finite number"));
        assert!(parse("").is_err());
        let deep = "GEOMETRYCOLLECTION (".repeat(100);
        assert!(parse(&deep).unwrap_err().message.contains("nested"));
        let (_, w) = parse("POLYGON ((0 0, 1 0, 1 1))").unwrap();
        assert!(w[0].contains("not closed"));
    }

    #[test]
    fn writes_what_it_reads() {
        let polygons = vec![
            Polygon::new(
                vec![[0.1, 0.2], [1e7 + 0.3, 0.0], [1.0, 1.0 / 3.0]],
                vec![vec![[0.5, 0.5], [0.6, 0.5], [0.6, 0.6]]],
            ),
            Polygon::new(vec![[-1.0, -1.0], [-2.0, -1.0], [-2.0, -2.0]], vec![]),
        ];
        let mut out = Vec::new();
        write_multipolygon(&mut out, &polygons).unwrap();
        let (f, _) = parse(std::str::from_utf8(&out).unwrap()).unwrap();
        assert_eq!(f[0].polygons, polygons);
    }

    impl ParseError {
        fn to_string_for_test(&self) -> String {
            match &self.location {
                Some(l) => format!("{l}: {}", self.message),
                None => self.message.clone(),
            }
        }
    }
}
