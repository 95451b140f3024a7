//! Point sets for `meshvol hull`: text point files, or the vertices of any mesh file.
//!
//! # Text points (`.xyz`, `.txt`, `.csv`, `.pts`)
//! ```text
//! x,y,z,intensity          <- a first line that is not numbers is a header
//! 500000.125 6000000.5 12.25 80
//! 500000.250 6000000.5 12.50 82
//! ```
//! One point per line: the first three numbers, separated by blanks, commas or
//! semicolons; more numbers (normals, colours, intensity) are ignored. `#` starts a
//! comment; blank lines are skipped. A line with fewer than three numbers, or with a
//! word after the header, is an error at its line.
//!
//! Lines may end with LF, CRLF or CR alone (old Mac files).
//!
//! # Mesh files
//! A file with a mesh extension, or whose content is a mesh format (as [`crate::read`]
//! recognises it), is read as a mesh and its vertices are the points: a PLY with
//! vertices and no faces (a scanned point cloud) included. A binary STL has no shared
//! vertices: its points are its triangles' corners, repeated. Any other file (standard
//! input with `-` included) is read as text points.

use std::path::{Path, PathBuf};

use meshvol::Point;

use crate::error::ParseError;
use crate::source::Bytes;
use crate::{text, LoadedSurface, ReadError};

/// Where the points came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointSource {
    /// A text point file.
    Text,
    /// The vertices of a mesh file of this format.
    Mesh(crate::Format),
}

impl PointSource {
    /// `xyz` for text, else the mesh format's name.
    pub fn name(&self) -> &'static str {
        match self {
            PointSource::Text => "xyz",
            PointSource::Mesh(format) => format.name(),
        }
    }
}

/// Points read from a file.
#[derive(Clone, Debug, PartialEq)]
pub struct PointCloud {
    pub source: PointSource,
    pub points: Vec<Point>,
    pub warnings: Vec<String>,
}

/// Whether a path names a text point file by its extension.
fn is_text_points(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("xyz" | "txt" | "csv" | "pts"))
}

/// Reads the points of a text point file or the vertices of a mesh file.
///
/// ```
/// let dir = tempfile::tempdir()?;
/// let path = dir.path().join("cloud.csv");
/// std::fs::write(&path, "x,y,z\n0,0,0\n1,0,0\n0,1,0\n0,0,1\n")?;
/// let cloud = meshvol_io::read_points(&path)?;
/// assert_eq!(cloud.points[3], [0.0, 0.0, 1.0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_points(path: &Path) -> Result<PointCloud, ReadError> {
    let bytes = Bytes::open(path).map_err(|e| ReadError::of_file(path, e.to_string()))?;
    decompressed_points(path, bytes)
}

/// Reads points from bytes already in memory, as [`read_points`] would read a file at
/// `path` with this content (`path` gives the extension and names the file in errors).
/// Standard input is read with a path such as `-`: no extension, so the content decides
/// (compressed or not).
///
/// ```
/// let cloud = meshvol_io::read_points_bytes(std::path::Path::new("-"), b"0 0 0\n1 2 3\n".to_vec())?;
/// assert_eq!(cloud.points, vec![[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]]);
/// # Ok::<(), meshvol_io::ReadError>(())
/// ```
pub fn read_points_bytes(path: &Path, bytes: Vec<u8>) -> Result<PointCloud, ReadError> {
    decompressed_points(path, Bytes::Owned(bytes))
}

/// The points of `bytes`, decompressed first when compressed (by the name's extension,
/// or without one by their first bytes), within the stream limit.
fn decompressed_points(path: &Path, bytes: Bytes) -> Result<PointCloud, ReadError> {
    let Some(compression) = crate::compressed::Compression::of_input(path, &bytes) else {
        return points(path, bytes);
    };
    let wanted = |p: &Path| crate::InputKind::Points.accepts(p);
    let limit = crate::Limits::from_env().inflated_bytes;
    let (inner, data) = crate::compressed::decompress(path, &bytes, compression, wanted, limit)?;
    drop(bytes);
    points(&inner, Bytes::Owned(data)).map_err(|e| e.named_as(path, &inner))
}

/// Text points for a text extension; else a mesh file for a mesh extension or content
/// that is a mesh format; else (no extension, or another one) text points.
fn points(path: &Path, bytes: Bytes) -> Result<PointCloud, ReadError> {
    let mesh = !is_text_points(path)
        && (crate::family::has_mesh_extension(path) || crate::family::is_mesh_content(&bytes));
    if !mesh {
        // Old Mac files end lines with CR alone; the lines are split at LF.
        let lf = text::lf_line_ends(&bytes);
        let points = read_text_points(lf.as_deref().unwrap_or(&bytes))
            .map_err(|e| e.with_path(PathBuf::from(path)))?;
        return Ok(PointCloud { source: PointSource::Text, points, warnings: Vec::new() });
    }
    let loaded = crate::load(path, bytes, &crate::Limits::from_env(), None)?;
    let points = match loaded.surface {
        LoadedSurface::Mesh(mesh) => mesh.positions().to_vec(),
        other => other
            .into_mesh()
            .map_err(|e| ReadError::of_file(path, e.to_string()))?
            .positions()
            .to_vec(),
    };
    Ok(PointCloud { source: PointSource::Mesh(loaded.format), points, warnings: loaded.warnings })
}

/// The shortest point line, `0 0 0\n`, for bounding the reservation.
const MIN_POINT_LINE: usize = 6;

/// Parses text point lines.
fn read_text_points(bytes: &[u8]) -> Result<Vec<Point>, ParseError> {
    let bytes = &bytes[text::bom_len(bytes)..];
    let mut points = Vec::with_capacity(bytes.len() / MIN_POINT_LINE / 4);
    let mut seen_content = false;
    for (index, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = memchr::memchr(b'#', raw).map_or(raw, |hash| &raw[..hash]);
        let mut fields =
            line.split(|&b| text::is_blank(b) || b == b',' || b == b';').filter(|t| !t.is_empty());
        let Some(first) = fields.next() else { continue };
        let first_content = !seen_content;
        seen_content = true;
        let mut point = [0.0; 3];
        let mut count = 0;
        for token in std::iter::once(first).chain(fields).take(3) {
            match fast_float2::parse::<f64, _>(token) {
                Ok(x) if x.is_finite() => point[count] = x,
                Ok(_) => {
                    return Err(ParseError::line(
                        index as u64 + 1,
                        format!("'{}' is not a finite number", text::show(token)),
                    ))
                }
                // A header is words: a first line whose first token starts like a
                // number ('0x1', '1,5') is a point line that does not parse.
                Err(_) if first_content && count == 0 && !starts_like_a_number(token) => break,
                Err(_) => {
                    return Err(ParseError::line(
                        index as u64 + 1,
                        format!("expected numbers x y z, found '{}'", text::show(token)),
                    ))
                }
            }
            count += 1;
        }
        match count {
            3 => points.push(point),
            0 if first_content => {} // a header
            _ => {
                return Err(ParseError::line(
                    index as u64 + 1,
                    format!("expected three numbers x y z, found {count}"),
                ))
            }
        }
    }
    Ok(points)
}

/// Whether `token` starts as a number would: a digit, a sign or a point.
fn starts_like_a_number(token: &[u8]) -> bool {
    token.first().is_some_and(|c| c.is_ascii_digit() || matches!(c, b'+' | b'-' | b'.'))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_points_with_header_comments_and_extra_columns() {
        let text = "\u{feff}x y z r g b\n# scan 1\n1 2 3 255 0 0\n\n4,5,6\n-1e7;0.5;7 # last\n";
        let points = read_text_points(text.as_bytes()).unwrap();
        assert_eq!(points, vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [-1e7, 0.5, 7.0]]);
        assert!(read_text_points(b"").unwrap().is_empty());
    }

    #[test]
    fn errors_name_the_line() {
        let e = read_text_points(b"1 2 3\n4 5\n").unwrap_err();
        assert_eq!(
            (e.location, e.message.as_str()),
            (Some(crate::Location::Line(2)), "expected three numbers x y z, found 2")
        );
        let e = read_text_points(b"1 2 3\n4 five 6\n").unwrap_err();
        assert_eq!(e.message, "expected numbers x y z, found 'five'");
        let e = read_text_points(b"1 2 3\n4 nan 6\n").unwrap_err();
        assert_eq!(e.message, "'nan' is not a finite number");
        // A header that starts with a number is still checked as a point line.
        let e = read_text_points(b"3 points\n1 2 3\n").unwrap_err();
        assert_eq!(e.location, Some(crate::Location::Line(1)));
        // So is one whose first number does not parse: it is not silently dropped.
        let e = read_text_points(b"0x1 2 3\n4 5 6\n").unwrap_err();
        assert_eq!(
            (e.location, e.message.as_str()),
            (Some(crate::Location::Line(1)), "expected numbers x y z, found '0x1'")
        );
    }
}
