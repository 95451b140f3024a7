//! Errors: which file, where in it, and what went wrong.
//!
//! Every reader reports the place of a problem in the unit that fits the format: a line
//! number (1-based) in text formats, a byte offset (0-based) in binary ones, a face index
//! (0-based, like the face indices of [`meshvol::Mesh`]), a line of one part of a 3MF
//! archive, or the JSON path of a glTF item.

use std::fmt;
use std::path::{Path, PathBuf};

/// Which limit a read went past (a [`ReadError`]'s `budget`; the limits are
/// [`crate::Limits`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Budget {
    InflatedBytes,
    Placements,
    Faces,
    /// The memory available ([`crate::memory`]).
    Memory,
}

/// Where in a file a [`ReadError`] was found.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Location {
    /// A line of a text file, counted from 1.
    Line(u64),
    /// A byte offset, counted from 0.
    Byte(u64),
    /// A face (a triangle of a binary STL, a face element of a PLY), counted from 0.
    Face(usize),
    /// A line (counted from 1) of one part of an archive: `3D/3dmodel.model` in a 3MF.
    PartLine { part: String, line: u64 },
    /// An item of a JSON document, as a path: `accessors[3]`, `meshes[0].primitives[1]`.
    Json(String),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Byte(b) => write!(f, "byte {b}"),
            Location::Face(i) => write!(f, "face {i}"),
            Location::PartLine { part, line } => write!(f, "{part} line {line}"),
            Location::Json(path) => f.write_str(path),
        }
    }
}

/// A file that could not be read: its path, the place of the problem when one applies,
/// and what is wrong.
///
/// Displays as `{path}: line 12: expected 3 coordinates after 'vertex', found 2`, or
/// `{path}: {message}` when no place applies.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReadError {
    pub path: PathBuf,
    pub location: Option<Location>,
    pub message: String,
    /// The limit of the read ([`crate::Limits`]) that the file went past, if that is
    /// why it was refused.
    pub budget: Option<Budget>,
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.path.display())?;
        if let Some(location) = &self.location {
            write!(f, "{location}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for ReadError {}

impl ReadError {
    /// An error about the whole file at `path` (no place in it, no limit passed).
    pub(crate) fn of_file(path: &Path, message: impl Into<String>) -> ReadError {
        ReadError {
            path: path.to_path_buf(),
            location: None,
            message: message.into(),
            budget: None,
        }
    }

    /// This error about the decompressed `inner`, named as the file given
    /// (`part.stl.gz`); a zip member keeps its name (`parts.zip/part.stl`), which names
    /// the archive.
    pub(crate) fn named_as(mut self, given: &Path, inner: &Path) -> ReadError {
        if self.path == inner && !inner.starts_with(given) {
            self.path = given.to_path_buf();
        }
        self
    }
}

/// A problem found while parsing bytes, before the file's path is attached.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ParseError {
    pub location: Option<Location>,
    pub message: String,
    pub budget: Option<Budget>,
}

impl ParseError {
    pub fn new(location: Option<Location>, message: impl Into<String>) -> ParseError {
        ParseError { location, message: message.into(), budget: None }
    }

    /// An error at `line` (1-based).
    pub fn line(line: u64, message: impl Into<String>) -> ParseError {
        ParseError::new(Some(Location::Line(line)), message)
    }

    /// An error at the line that holds byte `offset` of `bytes`.
    pub fn at_offset(bytes: &[u8], offset: usize, message: impl Into<String>) -> ParseError {
        ParseError::line(line_of(bytes, offset), message)
    }

    /// The same error, saying that the read went past `budget`.
    pub fn over(self, budget: Budget) -> ParseError {
        ParseError { budget: Some(budget), ..self }
    }

    pub fn with_path(self, path: PathBuf) -> ReadError {
        ReadError { path, location: self.location, message: self.message, budget: self.budget }
    }
}

/// The 1-based number of the line that holds byte `offset` (the line after the last one
/// when `offset` is at or past the end).
pub(crate) fn line_of(bytes: &[u8], offset: usize) -> u64 {
    let end = offset.min(bytes.len());
    1 + memchr::memchr_iter(b'\n', &bytes[..end]).count() as u64
}
