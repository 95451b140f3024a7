//! glTF 2.0: `.gltf` (a JSON document) and `.glb` (the binary container).
//!
//! Read: the triangles of every mesh primitive reached from the default scene (`scene`,
//! or the first scene when it is absent, or every root node when there are no scenes),
//! each placed by its node's global transform (the product of the `matrix`, or of
//! translation · rotation · scale, of the node and all its parents). Each node with a
//! mesh becomes an [`Object`] named after the node (or its mesh, or
//! `node N`). A mirroring transform (negative determinant) reverses the winding, as the
//! specification says, so outward faces stay outward.
//!
//! Primitives: modes `TRIANGLES` (4, the default), `TRIANGLE_STRIP` (5) and
//! `TRIANGLE_FAN` (6), with or without `indices` (unsigned byte, short or int); the
//! `POSITION` attribute as `VEC3` floats, or integers (normalized or not, as
//! `KHR_mesh_quantization` allows); sparse accessors; any byte stride. Points and lines
//! (modes 0–3) hold no volume: skipped with a warning. Files that require
//! `KHR_draco_mesh_compression` or `EXT_meshopt_compression` are errors (not read).
//!
//! Buffers: the GLB `BIN` chunk, `data:` URIs (base64), or files named by a relative URI
//! beside the `.gltf` file, or beside it in the zip archive it was read from. Units:
//! glTF lengths are metres (specification, §3.4), so [`crate::Loaded::unit`] is metres.
//!
//! Nothing is trusted: every index is checked, every accessor must lie inside its buffer
//! view and buffer, and an accessor without a buffer view (zeros, with optional sparse
//! values) may hold at most as many elements as the file has bytes. The node hierarchy
//! must be a forest: a node reached twice (a cycle, or a shared child) is an error.
//! Errors name the JSON item (`meshes[0].primitives[1]`, `accessors[3]`), the line of a
//! JSON syntax error, or the byte of a GLB container error.
//!
//! Speed: positions are decoded and placed, and indices checked and turned into
//! triangles, in parallel.
//!
//! Files: this one reads the document; `schema.rs` holds its serde types, `buffers.rs`
//! the GLB chunks, buffers and accessors, `scene.rs` the nodes, primitives and placing.

mod buffers;
mod scene;
mod schema;

use std::path::Path;

use meshvol::Mesh;

use crate::compressed::Archive;
use crate::error::{Location, ParseError};
use crate::limits::Limits;
use crate::object::Object;
use buffers::{glb_chunks, Buffers};
use scene::place;
use schema::{at, Document};

/// What a glTF file gave.
pub(crate) struct Scene {
    pub mesh: Mesh,
    pub objects: Vec<Object>,
    /// Each mesh instance (a node with a mesh): a body.
    pub bodies: Vec<Object>,
    /// Whether it was a GLB container.
    pub binary: bool,
    /// Which primitive each placed copy is, when a mesh is placed more than once.
    pub assembly: Option<meshvol::assembly::Assembly>,
}

/// Whether the bytes start with the GLB magic.
pub(crate) fn looks_like_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(b"glTF")
}

/// Whether the bytes start (after whitespace or a BOM) with a JSON object.
pub(crate) fn looks_like_json(bytes: &[u8]) -> bool {
    let start = crate::text::skip_space(bytes, crate::text::bom_len(bytes));
    bytes.get(start) == Some(&b'{')
}

/// Reads a `.gltf` or `.glb` file within `limits`; `path`, or the zip `archive` it was
/// read from, holds its external buffers.
pub(crate) fn read(
    path: &Path,
    archive: Option<Archive<'_>>,
    bytes: &[u8],
    warnings: &mut Vec<String>,
    limits: &Limits,
) -> Result<Scene, ParseError> {
    let binary = looks_like_glb(bytes);
    let (json, bin) = if binary { glb_chunks(bytes, warnings)? } else { (bytes, None) };
    let doc: Document = serde_json::from_slice(json).map_err(|e| {
        if binary {
            ParseError::new(
                Some(Location::Byte(20)),
                format!("the JSON chunk is not a glTF document: {e}"),
            )
        } else {
            ParseError::line(e.line().max(1) as u64, format!("not a glTF document: {e}"))
        }
    })?;
    if let Some(asset) = &doc.asset {
        if !asset.version.starts_with('2') {
            return Err(at(
                "asset.version",
                format!("glTF version '{}' is not read (2.0 is)", asset.version),
            ));
        }
    }
    for ext in &doc.extensions_required {
        if ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression" {
            return Err(at(
                "extensionsRequired",
                format!("the meshes are compressed with {ext}, which is not read"),
            ));
        }
    }
    let buffers =
        Buffers { doc: &doc, path, archive, bin, loaded: Vec::new(), file_bytes: bytes.len() };
    let g = place(&doc, buffers, warnings, limits)?;
    Ok(Scene { mesh: g.mesh, objects: g.objects, bodies: g.bodies, binary, assembly: g.assembly })
}
