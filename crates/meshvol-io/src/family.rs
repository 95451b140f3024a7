//! Which format a file is: the families an extension names, and recognition by content
//! (magic bytes, headers, the binary STL size rule, lines of OBJ statements).

use crate::{gltf, obj, off, ply, stl, text, threemf};
use std::path::Path;

/// The format families an extension or a sniff can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Family {
    Stl,
    Obj,
    Off,
    Ply,
    ThreeMf,
    Gltf,
}

impl Family {
    pub(crate) fn of_extension(ext: &str) -> Option<Family> {
        Some(match ext {
            "stl" => Family::Stl,
            "obj" => Family::Obj,
            "off" => Family::Off,
            "ply" => Family::Ply,
            "3mf" => Family::ThreeMf,
            "gltf" | "glb" => Family::Gltf,
            _ => return None,
        })
    }

    pub(crate) fn name(self) -> &'static str {
        match self {
            Family::Stl => "STL",
            Family::Obj => "OBJ",
            Family::Off => "OFF",
            Family::Ply => "PLY",
            Family::ThreeMf => "3MF",
            Family::Gltf => "glTF",
        }
    }

    /// Whether the content can be this family's (a cheap check of its first bytes).
    pub(crate) fn accepts(self, bytes: &[u8]) -> bool {
        match self {
            Family::Stl => stl::classify(bytes).is_ok(),
            Family::Obj => obj::looks_like_obj(bytes),
            Family::Off => off::looks_like_off(bytes),
            Family::Ply => ply::looks_like_ply(bytes),
            Family::ThreeMf => threemf::looks_like_zip(bytes),
            Family::Gltf => gltf::looks_like_glb(bytes) || gltf::looks_like_json(bytes),
        }
    }
}

/// Whether the path's extension names a mesh format.
pub(crate) fn has_mesh_extension(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    ext.as_deref().and_then(Family::of_extension).is_some()
}

/// Whether the content is a mesh format [`read`] recognises (text with CR line ends
/// included).
pub(crate) fn is_mesh_content(bytes: &[u8]) -> bool {
    sniff_lines(bytes, text::lf_line_ends(bytes).as_deref()).is_some()
}

/// [`sniff`], then, for text with CR line ends, `sniff` of `lf`, its copy with LF ones.
pub(crate) fn sniff_lines(bytes: &[u8], lf: Option<&[u8]>) -> Option<Family> {
    sniff(bytes).or_else(|| lf.and_then(sniff))
}

/// Recognises a format by content: magic bytes (PLY, GLB, zip), an OFF header, the
/// binary STL size rule, a leading `solid`, a JSON object, or lines of OBJ statements.
fn sniff(bytes: &[u8]) -> Option<Family> {
    if ply::looks_like_ply(bytes) {
        Some(Family::Ply)
    } else if gltf::looks_like_glb(bytes) {
        Some(Family::Gltf)
    } else if threemf::looks_like_zip(bytes) {
        Some(Family::ThreeMf)
    } else if off::looks_like_off(bytes) {
        Some(Family::Off)
    } else if stl::is_binary_stl_by_size(bytes) || stl::is_ascii_stl(bytes) {
        Some(Family::Stl)
    } else if gltf::looks_like_json(bytes) {
        Some(Family::Gltf)
    } else if obj::looks_like_obj(bytes) {
        Some(Family::Obj)
    } else {
        None
    }
}
