//! The parts of a glTF document that are read, as serde types, and [`at`], an error at
//! one of its items. Unknown members are ignored.

use serde::Deserialize;

use crate::error::{Location, ParseError};

/// An error at a JSON item.
pub(super) fn at(item: impl Into<String>, message: impl Into<String>) -> ParseError {
    ParseError::new(Some(Location::Json(item.into())), message)
}

#[derive(Deserialize, Default)]
#[serde(default)]
pub(super) struct Document {
    pub(super) asset: Option<Asset>,
    pub(super) scene: Option<usize>,
    pub(super) scenes: Vec<SceneNodes>,
    pub(super) nodes: Vec<Node>,
    pub(super) meshes: Vec<GltfMesh>,
    pub(super) accessors: Vec<Accessor>,
    #[serde(rename = "bufferViews")]
    pub(super) buffer_views: Vec<BufferView>,
    pub(super) buffers: Vec<Buffer>,
    #[serde(rename = "extensionsRequired")]
    pub(super) extensions_required: Vec<String>,
    #[serde(rename = "extensionsUsed")]
    pub(super) extensions_used: Vec<String>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
pub(super) struct Asset {
    pub(super) version: String,
}

#[derive(Deserialize, Default)]
#[serde(default)]
pub(super) struct SceneNodes {
    pub(super) nodes: Vec<usize>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
pub(super) struct Node {
    pub(super) name: Option<String>,
    pub(super) children: Vec<usize>,
    pub(super) mesh: Option<usize>,
    pub(super) matrix: Option<[f64; 16]>,
    pub(super) translation: Option<[f64; 3]>,
    pub(super) rotation: Option<[f64; 4]>,
    pub(super) scale: Option<[f64; 3]>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
pub(super) struct GltfMesh {
    pub(super) name: Option<String>,
    pub(super) primitives: Vec<Primitive>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
pub(super) struct Primitive {
    pub(super) attributes: Attributes,
    pub(super) indices: Option<usize>,
    pub(super) mode: Option<u64>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
pub(super) struct Attributes {
    #[serde(rename = "POSITION")]
    pub(super) position: Option<usize>,
}

#[derive(Deserialize)]
pub(super) struct Accessor {
    #[serde(rename = "bufferView")]
    pub(super) buffer_view: Option<usize>,
    #[serde(rename = "byteOffset", default)]
    pub(super) byte_offset: u64,
    #[serde(rename = "componentType")]
    pub(super) component_type: u64,
    #[serde(default)]
    pub(super) normalized: bool,
    pub(super) count: u64,
    #[serde(rename = "type")]
    pub(super) kind: String,
    pub(super) sparse: Option<Sparse>,
}

#[derive(Deserialize)]
pub(super) struct Sparse {
    pub(super) count: u64,
    pub(super) indices: SparseIndices,
    pub(super) values: SparseValues,
}

#[derive(Deserialize)]
pub(super) struct SparseIndices {
    #[serde(rename = "bufferView")]
    pub(super) buffer_view: usize,
    #[serde(rename = "byteOffset", default)]
    pub(super) byte_offset: u64,
    #[serde(rename = "componentType")]
    pub(super) component_type: u64,
}

#[derive(Deserialize)]
pub(super) struct SparseValues {
    #[serde(rename = "bufferView")]
    pub(super) buffer_view: usize,
    #[serde(rename = "byteOffset", default)]
    pub(super) byte_offset: u64,
}

#[derive(Deserialize)]
pub(super) struct BufferView {
    pub(super) buffer: usize,
    #[serde(rename = "byteOffset", default)]
    pub(super) byte_offset: u64,
    #[serde(rename = "byteLength")]
    pub(super) byte_length: u64,
    #[serde(rename = "byteStride")]
    pub(super) byte_stride: Option<u64>,
}

#[derive(Deserialize)]
pub(super) struct Buffer {
    pub(super) uri: Option<String>,
    #[serde(rename = "byteLength")]
    pub(super) byte_length: u64,
}
