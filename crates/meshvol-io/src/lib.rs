//! Mesh file readers for meshvol: STL (binary and ASCII), OBJ, OFF, PLY, 3MF, glTF/GLB.
//!
//! [`read`] picks the format from the file's extension (any case: `.stl`, `.obj`,
//! `.off`, `.ply`, `.3mf`, `.gltf`, `.glb`) and checks it against the content: where the
//! content is clearly another format (a `.stl` that is OBJ text, a `.ply` that is a GLB),
//! that format is read and a warning says so. Files without a known extension (and
//! standard input, read with [`read_bytes`]) are recognised by content: the PLY, GLB and
//! zip (3MF) magic bytes, a glTF JSON object, an OFF header, the binary STL size rule, a
//! `solid` line, OBJ statements. [`Loaded::format_source`] says which decided. Each
//! format's rules are in its module: [`stl`], [`obj`], [`off`], [`ply`], [`threemf`],
//! [`gltf`]. A compressed file (`part.stl.gz`, `.bz2`, `.zst`, a `.zip` of one mesh) is
//! decompressed first, within the stream limit, and read as the file it holds
//! ([`compressed`]).
//!
//! A binary STL is not copied: it stays memory-mapped and is read as a [`StlSoup`]. The
//! other formats are parsed (in parallel where the format allows) into a
//! [`meshvol::Mesh`]. Both implement [`meshvol::Surface`], and so does
//! [`LoadedSurface`], so kernels can take whatever was loaded.
//!
//! # Objects
//!
//! Files that hold several named parts (solids of an ASCII STL, OBJ `o` or `g` groups,
//! 3MF build items, glTF nodes with meshes) list them in [`Loaded::objects`]: contiguous
//! runs of the surface's faces, in file order, covering every face, each with its name.
//! The list is empty when the file holds fewer than two objects: a single part, or a
//! format without objects (binary STL, OFF, PLY). Measure one object with
//! [`meshvol::surface::FaceRange`].
//!
//! Where the format makes its objects separate parts (3MF objects, components and build
//! items: each placed mesh; glTF mesh instances), they are also [`Loaded::bodies`]: the
//! check nests shells within a body only, so a part inside its packaging is two solids,
//! not a part with a cavity. An ASCII STL's solids and an OBJ's groups are not bodies:
//! slicers read such a file as one model, and a group is often a piece of one surface
//! (a material, a smoothing group), so a shell inside another is a cavity there.
//!
//! # Units
//!
//! A file that declares its length unit sets [`Loaded::unit`]: a 3MF model's `unit`
//! attribute (millimetres when absent, as the 3MF specification says), and glTF, whose
//! specification fixes metres. The other formats carry no unit.
//!
//! Nothing here panics on any input: every problem is a [`ReadError`] naming the file,
//! the place (line, byte, face, archive part or JSON item) and what is wrong. Things that
//! are read but not used (OBJ line elements, bytes after a binary STL's triangles, glTF
//! point and line primitives) are reported in [`Loaded::warnings`].
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

pub mod compressed;
mod error;
mod family;
pub mod geojson;
pub mod gltf;
pub mod grid_out;
mod length_unit;
pub mod limits;
pub mod memory;
pub mod obj;
mod object;
pub mod off;
pub mod ply;
pub mod points;
mod polygon_feature;
pub mod polygons;
mod source;
pub mod stl;
mod text;
pub mod threemf;
mod transform;
pub mod walk;
pub mod wkt;
pub mod write;

pub use error::{Location, ReadError};
pub use length_unit::LengthUnit;
pub use object::Object;
pub use points::{read_points, read_points_bytes, PointCloud, PointSource};
pub use polygons::{
    read_polygons, read_polygons_bytes, PolygonFeature, PolygonFile, PolygonFormat,
};
pub use stl::StlSoup;
pub use walk::InputKind;

use compressed::Compression;
use error::ParseError;
use family::{has_mesh_extension, sniff_lines, Family};
pub use limits::{Budget, Limits};
use source::Bytes;
pub use source::{read_stream, stream_limit, stream_limit_setting, STREAM_LIMIT_VARIABLE};

/// A file format the readers know.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    StlBinary,
    StlAscii,
    Obj,
    Off,
    PlyAscii,
    PlyBinaryLittleEndian,
    PlyBinaryBigEndian,
    ThreeMf,
    /// glTF 2.0 JSON (`.gltf`), buffers embedded or beside it.
    Gltf,
    /// Binary glTF 2.0 (`.glb`).
    Glb,
}

impl Format {
    /// A short name: `stl-binary`, `stl-ascii`, `obj`, `off`, `ply-ascii`,
    /// `ply-binary-le`, `ply-binary-be`, `3mf`, `gltf`, `glb`.
    pub fn name(&self) -> &'static str {
        match self {
            Format::StlBinary => "stl-binary",
            Format::StlAscii => "stl-ascii",
            Format::Obj => "obj",
            Format::Off => "off",
            Format::PlyAscii => "ply-ascii",
            Format::PlyBinaryLittleEndian => "ply-binary-le",
            Format::PlyBinaryBigEndian => "ply-binary-be",
            Format::ThreeMf => "3mf",
            Format::Gltf => "gltf",
            Format::Glb => "glb",
        }
    }
}

/// What decided the format of a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FormatSource {
    /// The file's extension, and the content agreed.
    Extension,
    /// The content: the file had no known extension (or was standard input), or its
    /// content is clearly another format than its extension says (a warning says so).
    Content,
}

impl FormatSource {
    /// `extension` or `content`.
    pub fn name(&self) -> &'static str {
        match self {
            FormatSource::Extension => "extension",
            FormatSource::Content => "content",
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

    fn indexed_triangles(&self) -> Option<(&[Point], &[[u32; 3]])> {
        match self {
            LoadedSurface::StlSoup(s) => s.indexed_triangles(),
            LoadedSurface::Mesh(m) => m.indexed_triangles(),
        }
    }

    fn faces_are_triangles(&self) -> bool {
        match self {
            LoadedSurface::StlSoup(s) => s.faces_are_triangles(),
            LoadedSurface::Mesh(m) => m.faces_are_triangles(),
        }
    }

    #[inline]
    fn triangle_f32(&self, face: usize) -> Option<[[f32; 3]; 3]> {
        match self {
            LoadedSurface::StlSoup(s) => Surface::triangle_f32(s, face),
            LoadedSurface::Mesh(m) => m.triangle_f32(face),
        }
    }

    fn release_pages(&self) {
        if let LoadedSurface::StlSoup(s) = self {
            s.release_pages()
        }
    }
}

/// A file read: its format, its surface, its objects and unit, and what was read but
/// not used.
#[derive(Debug)]
pub struct Loaded {
    pub format: Format,
    /// Whether the extension or the content decided the format.
    pub format_source: FormatSource,
    pub surface: LoadedSurface,
    /// The file's objects when it holds two or more (see the crate docs); else empty.
    pub objects: Vec<Object>,
    /// The file's separate bodies when the format makes its objects separate parts (3MF,
    /// glTF; see the crate docs) and it holds two or more; else empty (one body).
    pub bodies: Vec<Object>,
    /// The length unit the file declares, if its format declares one.
    pub unit: Option<LengthUnit>,
    pub warnings: Vec<String>,
    /// How the surface was assembled from copies of parts, when the file places a part
    /// more than once (3MF components and items, glTF nodes): lets the check check each
    /// part once ([`meshvol::topology::check_assembled`]).
    pub assembly: Option<meshvol::assembly::Assembly>,
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

    /// The faces of each of [`Loaded::bodies`], as the check takes them.
    pub fn body_faces(&self) -> Vec<std::ops::Range<usize>> {
        self.bodies.iter().map(|b| b.faces.clone()).collect()
    }
}

/// Reads a mesh file, choosing the format by extension and content. A compressed file
/// (`.gz`, `.bz2`, `.zst`, `.zip`; without an extension, by its first bytes) is
/// decompressed first, within the stream limit ([`compressed`]).
pub fn read(path: &Path) -> Result<Loaded, ReadError> {
    read_file_within(path, &Limits::from_env())
}

/// [`read`] within `limits` instead of the command's (a read that no check follows needs
/// less memory: `checked: false`).
pub fn read_file_within(path: &Path, limits: &Limits) -> Result<Loaded, ReadError> {
    let bytes = Bytes::open(path).map_err(|e| ReadError::of_file(path, e.to_string()))?;
    read_within(path, bytes, limits)
}

/// Reads a mesh from bytes already in memory, as [`read`] would read a file at `path`
/// with these contents (`path` gives the extension, names the file in errors, and is
/// where a `.gltf` file's external buffers are looked for). Standard input is read with
/// a path such as `-`: no extension, so the content decides, compressed (gzip, bzip2,
/// Zstandard, zip) or not. A path ending in `.gz`, `.bz2`, `.zst` or `.zip` is
/// decompressed first, as [`read`] does (an upload named `part.stl.gz`).
pub fn read_bytes(path: &Path, bytes: Vec<u8>) -> Result<Loaded, ReadError> {
    read_bytes_within(path, bytes, &Limits::from_env())
}

/// [`read_bytes`] within `limits` instead of the command's: an error past one says
/// which in its `budget`.
pub fn read_bytes_within(
    path: &Path,
    bytes: Vec<u8>,
    limits: &Limits,
) -> Result<Loaded, ReadError> {
    read_within(path, Bytes::Owned(bytes), limits)
}

/// [`read_bytes_within`] of bytes owned or mapped.
fn read_within(path: &Path, bytes: Bytes, limits: &Limits) -> Result<Loaded, ReadError> {
    let Some(compression) = Compression::of_input(path, &bytes) else {
        return load(path, bytes, limits, None);
    };
    let (inner, data) = compressed::decompress(
        path,
        &bytes,
        compression,
        has_mesh_extension,
        limits.inflated_bytes,
    )?;
    let data = Bytes::Owned(data);
    // A zip's member (`parts.zip/scene.gltf`, not a 3MF package read whole) keeps the
    // archive: a glTF's external buffers are its other members.
    let member = inner.strip_prefix(path).ok().filter(|_| compression == Compression::Zip);
    let loaded = match member {
        Some(member) => {
            let archive =
                compressed::Archive { bytes: &bytes, member, limit: limits.inflated_bytes };
            load(&inner, data, limits, Some(archive))
        }
        None => {
            drop(bytes);
            load(&inner, data, limits, None)
        }
    };
    loaded.map_err(|e| e.named_as(path, &inner))
}

/// The object list's rule: two or more objects, else none.
fn objects_if_several(objects: Vec<Object>) -> Vec<Object> {
    if objects.len() >= 2 {
        objects
    } else {
        Vec::new()
    }
}

fn load(
    path: &Path,
    bytes: Bytes,
    limits: &Limits,
    archive: Option<compressed::Archive<'_>>,
) -> Result<Loaded, ReadError> {
    let with_path = |e: ParseError| e.with_path(PathBuf::from(path));
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let mut warnings = Vec::new();
    let by_extension = ext.as_deref().and_then(Family::of_extension);
    // Text with CR line ends (old Mac files), as a copy with LF ones: the text readers and
    // the sniffs of text formats split lines at LF.
    let lf = text::lf_line_ends(&bytes);
    let lines: &[u8] = lf.as_deref().unwrap_or(&bytes);
    let found = sniff_lines(&bytes, lf.as_deref());
    let (family, format_source) = match (by_extension, found) {
        (Some(named), Some(found))
            if named != found && !named.accepts(&bytes) && !named.accepts(lines) =>
        {
            warnings.push(format!(
                "the content is {}, not {} as the extension '.{}' says: read as {}",
                found.name(),
                named.name(),
                ext.as_deref().unwrap_or_default(),
                found.name()
            ));
            (found, FormatSource::Content)
        }
        (Some(named), _) => (named, FormatSource::Extension),
        (None, Some(found)) => (found, FormatSource::Content),
        (None, None) => {
            let what = match &ext {
                Some(ext) => format!(
                    "the extension '.{ext}' is not one of .stl, .obj, .off, .ply, .3mf, .gltf, \
                     .glb"
                ),
                None => "the file has no extension".to_string(),
            };
            let what = if bytes.is_empty() {
                format!("{what}, and the file is empty")
            } else {
                format!("{what}, and the content looks like none of STL, OBJ, OFF, PLY, 3MF, glTF")
            };
            return Err(ReadError::of_file(path, what));
        }
    };
    memory::fits(family, &bytes, limits.memory, limits.checked).map_err(with_path)?;
    let mut objects = Vec::new();
    let mut bodies = Vec::new();
    let mut unit = None;
    let mut assembly = None;
    let (format, surface) = match family {
        Family::Stl => match stl::classify(&bytes).map_err(with_path)? {
            stl::Kind::Binary { triangles, trailing } => {
                let soup = stl::read_binary(bytes, triangles, trailing, &mut warnings)
                    .map_err(with_path)?;
                (Format::StlBinary, LoadedSurface::StlSoup(soup))
            }
            stl::Kind::Ascii => {
                let (mesh, solids) = stl::read_ascii(lines, &mut warnings).map_err(with_path)?;
                objects = solids;
                (Format::StlAscii, LoadedSurface::Mesh(mesh))
            }
        },
        Family::Obj => {
            let (mesh, groups) = obj::read(lines, &mut warnings).map_err(with_path)?;
            objects = groups;
            (Format::Obj, LoadedSurface::Mesh(mesh))
        }
        Family::Off => {
            let mesh = off::read(lines, &mut warnings).map_err(with_path)?;
            (Format::Off, LoadedSurface::Mesh(mesh))
        }
        Family::Ply => {
            // PLY minds CR line ends itself: a binary body must be read from the file's own
            // bytes.
            let (encoding, mesh) = ply::read(&bytes, &mut warnings).map_err(with_path)?;
            let format = match encoding {
                ply::Encoding::Ascii => Format::PlyAscii,
                ply::Encoding::BinaryLittleEndian => Format::PlyBinaryLittleEndian,
                ply::Encoding::BinaryBigEndian => Format::PlyBinaryBigEndian,
            };
            (format, LoadedSurface::Mesh(mesh))
        }
        Family::ThreeMf => {
            let model = threemf::read(&bytes, &mut warnings, limits).map_err(with_path)?;
            objects = model.objects;
            bodies = model.bodies;
            unit = Some(model.unit);
            assembly = model.assembly;
            (Format::ThreeMf, LoadedSurface::Mesh(model.mesh))
        }
        Family::Gltf => {
            let scene =
                gltf::read(path, archive, &bytes, &mut warnings, limits).map_err(with_path)?;
            objects = scene.objects;
            bodies = scene.bodies;
            unit = Some(LengthUnit::Metre);
            assembly = scene.assembly;
            let format = if scene.binary { Format::Glb } else { Format::Gltf };
            (format, LoadedSurface::Mesh(scene.mesh))
        }
    };
    Ok(Loaded {
        format,
        format_source,
        surface,
        objects: objects_if_several(objects),
        bodies: objects_if_several(bodies),
        unit,
        warnings,
        assembly,
    })
}
