//! Mesh file readers for meshvol: STL (binary and ASCII), OBJ and OFF.
//!
//! [`read`] picks the format from the file's extension (any case: `.stl`, `.obj`,
//! `.off`), tells binary from ASCII STL by the file's size, and for other extensions
//! recognises the content (an OFF header, the binary STL size rule, a `solid` line, OBJ
//! statements). Each format's rules are in its module: [`stl`], [`obj`], [`off`].
//!
//! A binary STL is not copied: it stays memory-mapped and is read as a [`StlSoup`]. The
//! text formats are parsed (in parallel where the format allows) into a
//! [`meshvol::Mesh`]. Both implement [`meshvol::Surface`], and so does
//! [`LoadedSurface`], so kernels can take whatever was loaded.
//!
//! Nothing here panics on any input: every problem is a [`ReadError`] naming the file,
//! the place (line, byte or face) and what is wrong. Things that are read but not used
//! (OBJ line elements, bytes after a binary STL's triangles, several solids in one STL)
//! are reported in [`Loaded::warnings`].
//!
//! ```no_run
//! use meshvol::Surface;
//! let loaded = meshvol_io::read(std::path::Path::new("part.stl"))?;
//! let mut six_volume = 0.0;
//! for face in 0..loaded.surface.face_count() {
//!     loaded.surface.fan(face, |a, b, c| {
//!         six_volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
//!             + a[2] * (b[0] * c[1] - b[1] * c[0]);
//!     });
//! }
//! println!("{}: {} triangles, volume {}", loaded.format, loaded.triangle_count(), six_volume / 6.0);
//! # Ok::<(), meshvol_io::ReadError>(())
//! ```

use std::fmt;
use std::path::{Path, PathBuf};

use meshvol::{Mesh, Point, Surface};

mod error;
pub mod obj;
pub mod off;
mod source;
pub mod stl;
mod text;

pub use error::{Location, ReadError};
pub use stl::StlSoup;

use error::ParseError;
use source::Bytes;

/// A file format the readers know.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    StlBinary,
    StlAscii,
    Obj,
    Off,
}

impl Format {
    /// A short name: `stl-binary`, `stl-ascii`, `obj`, `off`.
    pub fn name(&self) -> &'static str {
        match self {
            Format::StlBinary => "stl-binary",
            Format::StlAscii => "stl-ascii",
            Format::Obj => "obj",
            Format::Off => "off",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The surface a file held.
#[derive(Debug)]
pub enum LoadedSurface {
    /// A binary STL, read in place.
    StlSoup(StlSoup),
    /// Anything else, parsed into a mesh.
    Mesh(Mesh),
}

impl LoadedSurface {
    /// The number of vertices: three per triangle for a binary STL (no welding).
    pub fn vertex_count(&self) -> usize {
        match self {
            LoadedSurface::StlSoup(s) => 3 * s.triangle_count(),
            LoadedSurface::Mesh(m) => m.vertex_count(),
        }
    }

    /// The number of triangles in the faces' fans.
    pub fn triangle_count(&self) -> usize {
        match self {
            LoadedSurface::StlSoup(s) => s.triangle_count(),
            LoadedSurface::Mesh(m) => m.triangle_count(),
        }
    }

    /// The surface as a [`Mesh`]: the parsed mesh, or a binary STL's triangles with three
    /// unshared vertices each (copied).
    pub fn into_mesh(self) -> Result<Mesh, meshvol::MeshError> {
        match self {
            LoadedSurface::StlSoup(s) => s.to_mesh(),
            LoadedSurface::Mesh(m) => Ok(m),
        }
    }
}

impl Surface for LoadedSurface {
    fn face_count(&self) -> usize {
        match self {
            LoadedSurface::StlSoup(s) => s.triangle_count(),
            LoadedSurface::Mesh(m) => m.face_count(),
        }
    }

    #[inline]
    fn fan(&self, face: usize, triangle: impl FnMut(Point, Point, Point)) {
        match self {
            LoadedSurface::StlSoup(s) => s.fan(face, triangle),
            LoadedSurface::Mesh(m) => m.fan(face, triangle),
        }
    }
}

/// A file read: its format, its surface, and what was read but not used.
#[derive(Debug)]
pub struct Loaded {
    pub format: Format,
    pub surface: LoadedSurface,
    pub warnings: Vec<String>,
}

impl Loaded {
    /// The number of vertices (three per triangle for STL: no welding).
    pub fn vertex_count(&self) -> usize {
        self.surface.vertex_count()
    }

    /// The number of faces.
    pub fn face_count(&self) -> usize {
        self.surface.face_count()
    }

    /// The number of triangles in the faces' fans (a face of k vertices counts k − 2).
    pub fn triangle_count(&self) -> usize {
        self.surface.triangle_count()
    }
}

/// Reads a mesh file, choosing the format by extension, then by content.
pub fn read(path: &Path) -> Result<Loaded, ReadError> {
    let bytes = Bytes::open(path).map_err(|e| ReadError {
        path: path.to_path_buf(),
        location: None,
        message: e.to_string(),
    })?;
    load(path, bytes)
}

/// Reads a mesh from bytes already in memory, as [`read`] would read a file at `path`
/// with these contents (`path` gives the extension and names the file in errors).
pub fn read_bytes(path: &Path, bytes: Vec<u8>) -> Result<Loaded, ReadError> {
    load(path, Bytes::Owned(bytes))
}

/// The format families an extension or a sniff can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Family {
    Stl,
    Obj,
    Off,
}

fn load(path: &Path, bytes: Bytes) -> Result<Loaded, ReadError> {
    let with_path = |e: ParseError| e.with_path(PathBuf::from(path));
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let family = match ext.as_deref() {
        Some("stl") => Family::Stl,
        Some("obj") => Family::Obj,
        Some("off") => Family::Off,
        _ => sniff(&bytes).ok_or_else(|| {
            let what = match &ext {
                Some(ext) => format!("the extension '.{ext}' is not one of .stl, .obj, .off"),
                None => "the file has no extension".to_string(),
            };
            let what = if bytes.is_empty() {
                format!("{what}, and the file is empty")
            } else {
                format!("{what}, and the content looks like none of STL, OBJ, OFF")
            };
            ReadError { path: path.to_path_buf(), location: None, message: what }
        })?,
    };
    let mut warnings = Vec::new();
    let (format, surface) = match family {
        Family::Stl => match stl::classify(&bytes).map_err(with_path)? {
            stl::Kind::Binary { triangles, trailing } => {
                let soup = stl::read_binary(bytes, triangles, trailing, &mut warnings)
                    .map_err(with_path)?;
                (Format::StlBinary, LoadedSurface::StlSoup(soup))
            }
            stl::Kind::Ascii => {
                let mesh = stl::read_ascii(&bytes, &mut warnings).map_err(with_path)?;
                (Format::StlAscii, LoadedSurface::Mesh(mesh))
            }
        },
        Family::Obj => {
            let mesh = obj::read(&bytes, &mut warnings).map_err(with_path)?;
            (Format::Obj, LoadedSurface::Mesh(mesh))
        }
        Family::Off => {
            let mesh = off::read(&bytes, &mut warnings).map_err(with_path)?;
            (Format::Off, LoadedSurface::Mesh(mesh))
        }
    };
    Ok(Loaded { format, surface, warnings })
}

/// Recognises a format by content: an OFF header, the binary STL size rule, a leading
/// `solid`, or lines of OBJ statements.
fn sniff(bytes: &[u8]) -> Option<Family> {
    if off::looks_like_off(bytes) {
        Some(Family::Off)
    } else if stl::is_binary_stl_by_size(bytes) || stl::is_ascii_stl(bytes) {
        Some(Family::Stl)
    } else if obj::looks_like_obj(bytes) {
        Some(Family::Obj)
    } else {
        None
    }
}
