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
//! Keywords in any case, tokens separated by any whitespace (lines ending with LF, CRLF or CR alone), a name that
//! is the rest of the `solid` / `endsolid` line (possibly empty, as OpenSCAD and FreeCAD
//! write it), and any number of `solid` blocks, whose triangles are concatenated; with
//! two or more solids each is an [`Object`](crate::Object) named after its `solid` line. The normal is not read (writers put `nan` there for
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
//! [`Mesh`] with three unshared vertices per facet, in `ascii.rs`.

mod ascii;

use meshvol::{Mesh, MeshError, Point, Surface};
use rayon::prelude::*;

use crate::error::{Location, ParseError};
use crate::source::Bytes;
use crate::text;
pub(crate) use ascii::read_ascii;

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
        self.triangle_f32(i).map(|p| p.map(f64::from))
    }

    /// The three vertices of triangle `i` as the file stores them.
    ///
    /// # Panics
    /// If `i >= self.triangle_count()`.
    #[inline]
    pub fn triangle_f32(&self, i: usize) -> [[f32; 3]; 3] {
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
fn vertex(record: &[u8; RECORD], at: usize) -> [f32; 3] {
    [f32_at(record, at), f32_at(record, at + 4), f32_at(record, at + 8)]
}

#[inline]
fn f32_at(record: &[u8; RECORD], at: usize) -> f32 {
    f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]])
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

    fn faces_are_triangles(&self) -> bool {
        true
    }

    #[inline]
    fn triangle_f32(&self, face: usize) -> Option<[[f32; 3]; 3]> {
        Some(StlSoup::triangle_f32(self, face))
    }

    fn release_pages(&self) {
        self.bytes.release_pages();
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
}
