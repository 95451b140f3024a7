//! Polygon files for `meshvol area`: WKT ([`crate::wkt`]), GeoJSON ([`crate::geojson`])
//! and plain text rings.
//!
//! The format comes from the extension (`.wkt`; `.geojson` or `.json`; `.txt`, `.xy`,
//! `.csv`), else (standard input included) from the content: `{` starts GeoJSON, a
//! geometry keyword followed by `(` or `EMPTY` WKT, a number or a header line a text
//! ring. Lines may end with LF, CRLF or CR alone (old Mac files).
//!
//! # Text rings
//! ```text
//! # x y, one vertex per line (space, tab, comma or semicolon between)
//! 500000.0 6000000.0
//! 500040.0 6000000.0
//! 500040.0 6000030.0
//!
//! 500010.0 6000010.0      <- after a blank line: a hole
//! 500020.0 6000010.0
//! 500020.0 6000020.0
//! ```
//! `#` starts a comment. A first line that is not numbers is a header and skipped.
//! Blank lines separate rings: the first ring is the exterior, the others are its holes.
//! A closing copy of a ring's first vertex is dropped. Errors give the line.

use std::path::{Path, PathBuf};

use meshvol::polygon::{Point2, Polygon};

pub use crate::polygon_feature::PolygonFeature;

use crate::error::ParseError;
use crate::source::Bytes;
use crate::{text, ReadError};

/// A polygon file's format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PolygonFormat {
    Wkt,
    GeoJson,
    /// `x y` lines.
    TextRing,
}

impl PolygonFormat {
    /// `wkt`, `geojson` or `text`.
    pub fn name(&self) -> &'static str {
        match self {
            PolygonFormat::Wkt => "wkt",
            PolygonFormat::GeoJson => "geojson",
            PolygonFormat::TextRing => "text",
        }
    }
}

/// A polygon file read: its format, its features in file order, and what was read but
/// not used.
#[derive(Clone, Debug, PartialEq)]
pub struct PolygonFile {
    pub format: PolygonFormat,
    pub features: Vec<PolygonFeature>,
    pub warnings: Vec<String>,
}

/// Reads a polygon file (WKT, GeoJSON or a text ring).
///
/// ```
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("lot.wkt");
/// std::fs::write(&path, "POLYGON ((0 0, 4 0, 4 2, 0 2, 0 0))")?;
/// let file = meshvol_io::read_polygons(&path)?;
/// let p = meshvol::polygon::area_properties(&file.features[0].polygons);
/// assert_eq!(p.area, 8.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_polygons(path: &Path) -> Result<PolygonFile, ReadError> {
    let bytes = Bytes::open(path).map_err(|e| ReadError::of_file(path, e.to_string()))?;
    read_polygons_bytes(path, &bytes)
}

/// Reads polygons from bytes as [`read_polygons`] would read a file at `path` with this
/// content (`path` gives the extension and names the file in errors). Compressed bytes
/// (by the name's extension, or without one by their first bytes) are decompressed
/// first, within the stream limit.
///
/// Standard input is read with a path such as `-`: no extension, so the content decides.
pub fn read_polygons_bytes(path: &Path, bytes: &[u8]) -> Result<PolygonFile, ReadError> {
    if let Some(compression) = crate::compressed::Compression::of_input(path, bytes) {
        let wanted = |p: &Path| crate::InputKind::Polygons.accepts(p);
        let limit = crate::Limits::from_env().inflated_bytes;
        let (inner, data) = crate::compressed::decompress(path, bytes, compression, wanted, limit)?;
        return polygons(&inner, &data).map_err(|e| e.named_as(path, &inner));
    }
    polygons(path, bytes)
}

/// [`read_polygons_bytes`] of bytes not compressed.
fn polygons(path: &Path, bytes: &[u8]) -> Result<PolygonFile, ReadError> {
    let with_path = |e: ParseError| e.with_path(PathBuf::from(path));
    // Old Mac files end lines with CR alone; every reader here counts lines at LF.
    let lf = text::lf_line_ends(bytes);
    let bytes = lf.as_deref().unwrap_or(bytes);
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let format = match ext.as_deref() {
        Some("wkt") => PolygonFormat::Wkt,
        Some("geojson" | "json") => PolygonFormat::GeoJson,
        Some("txt" | "xy" | "csv") => PolygonFormat::TextRing,
        _ => {
            let start = text::skip_space(bytes, text::bom_len(bytes));
            match bytes.get(start) {
                Some(b'{') => PolygonFormat::GeoJson,
                _ if looks_like_wkt(&bytes[start..]) => PolygonFormat::Wkt,
                // A letter: a text ring's header line (`x,y`).
                Some(b) if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'+' | b'.' | b'#') => {
                    PolygonFormat::TextRing
                }
                _ => {
                    return Err(ReadError {
                        path: path.to_path_buf(),
                        location: None,
                        message: "not a polygon file: expected WKT, GeoJSON or x y lines \
                                  (extensions .wkt, .geojson, .json, .txt, .xy, .csv)"
                            .to_string(),
                        budget: None,
                    })
                }
            }
        }
    };
    let mut warnings = Vec::new();
    let features = match format {
        PolygonFormat::Wkt => crate::wkt::read(bytes, &mut warnings),
        PolygonFormat::GeoJson => crate::geojson::read(bytes, &mut warnings),
        PolygonFormat::TextRing => {
            read_text_ring(bytes).map(|polygons| vec![PolygonFeature { name: None, polygons }])
        }
    }
    .map_err(with_path)?;
    Ok(PolygonFile { format, features, warnings })
}

/// Whether the text starts like a WKT geometry: `SRID=`, or a word, an optional `Z`,
/// `M` or `ZM`, then `(` or `EMPTY` (any case).
fn looks_like_wkt(bytes: &[u8]) -> bool {
    let word = |at: usize| {
        let at = text::skip_blank(bytes, at);
        let end = at + bytes[at..].iter().take_while(|b| b.is_ascii_alphabetic()).count();
        (at, end)
    };
    if bytes.len() >= 5 && bytes[..5].eq_ignore_ascii_case(b"SRID=") {
        return true;
    }
    let (start, mut end) = word(0);
    if start == end {
        return false;
    }
    let (s, e) = word(end);
    if matches!(bytes[s..e].to_ascii_uppercase().as_slice(), b"Z" | b"M" | b"ZM") {
        end = e;
    }
    let (s, e) = word(end);
    bytes[s..e].eq_ignore_ascii_case(b"EMPTY") || bytes.get(s) == Some(&b'(')
}

/// The numbers of a text line split at blanks, commas and semicolons, into `out`;
/// `Err(token)` for a token that is not a finite number.
fn numbers<'a>(line: &'a [u8], out: &mut Vec<f64>) -> Result<(), &'a [u8]> {
    out.clear();
    let separator = |b: &u8| text::is_blank(*b) || matches!(b, b',' | b';');
    for token in line.split(separator).filter(|t| !t.is_empty()) {
        match fast_float2::parse::<f64, _>(token) {
            Ok(x) if x.is_finite() => out.push(x),
            _ => return Err(token),
        }
    }
    Ok(())
}

/// Parses `x y` lines; blank lines separate the exterior from holes.
fn read_text_ring(bytes: &[u8]) -> Result<Vec<Polygon>, ParseError> {
    let bytes = &bytes[text::bom_len(bytes)..];
    let mut rings: Vec<Vec<Point2>> = vec![Vec::new()];
    let mut values = Vec::new();
    let mut seen_content = false;
    for (index, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let number = index as u64 + 1;
        let comment = memchr::memchr(b'#', raw);
        let line = comment.map_or(raw, |hash| &raw[..hash]);
        if line.iter().all(|&b| text::is_blank(b)) {
            // A comment line does not end a ring; a blank one does.
            if comment.is_none() && rings.last().is_some_and(|r| !r.is_empty()) {
                rings.push(Vec::new());
            }
            continue;
        }
        let first_content = !seen_content;
        seen_content = true;
        match numbers(line, &mut values) {
            Err(_) if first_content => continue, // a header
            Err(token) => {
                return Err(ParseError::line(
                    number,
                    format!("expected numbers x y, found '{}'", text::show(token)),
                ))
            }
            Ok(()) if values.len() < 2 => {
                return Err(ParseError::line(
                    number,
                    format!("expected two numbers x y, found {}", values.len()),
                ))
            }
            Ok(()) => {
                if let Some(ring) = rings.last_mut() {
                    ring.push([values[0], values[1]]);
                }
            }
        }
    }
    rings.retain(|r| !r.is_empty());
    for ring in &mut rings {
        if ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
    }
    let mut rings = rings.into_iter();
    let Some(exterior) = rings.next() else {
        return Err(ParseError::new(None, "no vertices: expected lines of x y"));
    };
    Ok(vec![Polygon::new(exterior, rings.collect())])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_rings_with_header_comments_and_holes() {
        let text = "x,y\n# a lot\n0,0\n4 0\n4;2\n0\t2\n0 0\n\n# the hole\n1 1\n2 1\n2 1.5\n";
        let file = read_polygons_bytes(Path::new("lot.txt"), text.as_bytes()).unwrap();
        assert_eq!(file.format, PolygonFormat::TextRing);
        let p = &file.features[0].polygons[0];
        assert_eq!(p.exterior, vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]]);
        assert_eq!(p.holes, vec![vec![[1.0, 1.0], [2.0, 1.0], [2.0, 1.5]]]);
    }

    #[test]
    fn errors_and_detection() {
        let e = read_polygons_bytes(Path::new("lot.txt"), b"0 0\n1 0\n1 x\n").unwrap_err();
        assert_eq!(e.to_string(), "lot.txt: line 3: expected numbers x y, found 'x'");
        let e = read_polygons_bytes(Path::new("lot.txt"), b"0 0\n5\n").unwrap_err();
        assert_eq!(e.to_string(), "lot.txt: line 2: expected two numbers x y, found 1");
        let e = read_polygons_bytes(Path::new("lot.txt"), b"# nothing\n").unwrap_err();
        assert!(e.to_string().contains("no vertices"));
        let e = read_polygons_bytes(Path::new("lot"), b"\x00\x01").unwrap_err();
        assert!(e.message.contains("not a polygon file"));
        let formats = [
            (&b"{\"type\": \"Polygon\", \"coordinates\": []}"[..], PolygonFormat::GeoJson),
            (b"POLYGON EMPTY", PolygonFormat::Wkt),
            (b"1 2\n3 4\n5 0\n", PolygonFormat::TextRing),
        ];
        for (content, format) in formats {
            assert_eq!(read_polygons_bytes(Path::new("lot"), content).unwrap().format, format);
        }
    }
}
