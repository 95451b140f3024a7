//! glTF 2.0: `.gltf` (a JSON document) and `.glb` (the binary container).
//!
//! Read: the triangles of every mesh primitive reached from the default scene (`scene`,
//! or the first scene when it is absent, or every root node when there are no scenes),
//! each placed by its node's global transform (the product of the `matrix`, or of
//! translation · rotation · scale, of the node and all its parents). Each node with a
//! mesh becomes an [`Object`](crate::Object) named after the node (or its mesh, or
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
//! beside the `.gltf` file (in the current directory for standard input). Units:
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

use std::borrow::Cow;
use std::path::Path;

use base64::Engine;
use meshvol::{Mesh, Point};
use rayon::prelude::*;
use serde::Deserialize;

use crate::error::{Location, ParseError};
use crate::transform::{Affine, Placed};
use crate::Object;

/// What a glTF file gave.
pub(crate) struct Scene {
    pub mesh: Mesh,
    pub objects: Vec<Object>,
    /// Whether it was a GLB container.
    pub binary: bool,
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

// The parts of the document that are read. Unknown members are ignored.

#[derive(Deserialize, Default)]
#[serde(default)]
struct Document {
    asset: Option<Asset>,
    scene: Option<usize>,
    scenes: Vec<SceneNodes>,
    nodes: Vec<Node>,
    meshes: Vec<GltfMesh>,
    accessors: Vec<Accessor>,
    #[serde(rename = "bufferViews")]
    buffer_views: Vec<BufferView>,
    buffers: Vec<Buffer>,
    #[serde(rename = "extensionsRequired")]
    extensions_required: Vec<String>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct Asset {
    version: String,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct SceneNodes {
    nodes: Vec<usize>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct Node {
    name: Option<String>,
    children: Vec<usize>,
    mesh: Option<usize>,
    matrix: Option<[f64; 16]>,
    translation: Option<[f64; 3]>,
    rotation: Option<[f64; 4]>,
    scale: Option<[f64; 3]>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct GltfMesh {
    name: Option<String>,
    primitives: Vec<Primitive>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct Primitive {
    attributes: Attributes,
    indices: Option<usize>,
    mode: Option<u64>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct Attributes {
    #[serde(rename = "POSITION")]
    position: Option<usize>,
}

#[derive(Deserialize)]
struct Accessor {
    #[serde(rename = "bufferView")]
    buffer_view: Option<usize>,
    #[serde(rename = "byteOffset", default)]
    byte_offset: u64,
    #[serde(rename = "componentType")]
    component_type: u64,
    #[serde(default)]
    normalized: bool,
    count: u64,
    #[serde(rename = "type")]
    kind: String,
    sparse: Option<Sparse>,
}

#[derive(Deserialize)]
struct Sparse {
    count: u64,
    indices: SparseIndices,
    values: SparseValues,
}

#[derive(Deserialize)]
struct SparseIndices {
    #[serde(rename = "bufferView")]
    buffer_view: usize,
    #[serde(rename = "byteOffset", default)]
    byte_offset: u64,
    #[serde(rename = "componentType")]
    component_type: u64,
}

#[derive(Deserialize)]
struct SparseValues {
    #[serde(rename = "bufferView")]
    buffer_view: usize,
    #[serde(rename = "byteOffset", default)]
    byte_offset: u64,
}

#[derive(Deserialize)]
struct BufferView {
    buffer: usize,
    #[serde(rename = "byteOffset", default)]
    byte_offset: u64,
    #[serde(rename = "byteLength")]
    byte_length: u64,
    #[serde(rename = "byteStride")]
    byte_stride: Option<u64>,
}

#[derive(Deserialize)]
struct Buffer {
    uri: Option<String>,
    #[serde(rename = "byteLength")]
    byte_length: u64,
}

/// An error at a JSON item.
fn at(item: impl Into<String>, message: impl Into<String>) -> ParseError {
    ParseError::new(Some(Location::Json(item.into())), message)
}

/// An accessor component type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Component {
    I8,
    U8,
    I16,
    U16,
    U32,
    F32,
}

impl Component {
    fn from_code(code: u64) -> Option<Component> {
        Some(match code {
            5120 => Component::I8,
            5121 => Component::U8,
            5122 => Component::I16,
            5123 => Component::U16,
            5125 => Component::U32,
            5126 => Component::F32,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Component::I8 | Component::U8 => 1,
            Component::I16 | Component::U16 => 2,
            Component::U32 | Component::F32 => 4,
        }
    }

    /// The value at `bytes[at..]` (in range), as `f64`, normalized to [-1, 1] or [0, 1]
    /// when asked.
    #[inline]
    fn read(self, bytes: &[u8], at: usize, normalized: bool) -> f64 {
        let b = |n: usize| bytes[at + n];
        match (self, normalized) {
            (Component::F32, _) => f64::from(f32::from_le_bytes([b(0), b(1), b(2), b(3)])),
            (Component::U32, _) => f64::from(u32::from_le_bytes([b(0), b(1), b(2), b(3)])),
            (Component::I8, false) => f64::from(b(0) as i8),
            (Component::U8, false) => f64::from(b(0)),
            (Component::I16, false) => f64::from(i16::from_le_bytes([b(0), b(1)])),
            (Component::U16, false) => f64::from(u16::from_le_bytes([b(0), b(1)])),
            (Component::I8, true) => (f64::from(b(0) as i8) / 127.0).max(-1.0),
            (Component::U8, true) => f64::from(b(0)) / 255.0,
            (Component::I16, true) => {
                (f64::from(i16::from_le_bytes([b(0), b(1)])) / 32767.0).max(-1.0)
            }
            (Component::U16, true) => f64::from(u16::from_le_bytes([b(0), b(1)])) / 65535.0,
        }
    }

    /// An index at `bytes[at..]` (in range), its bits read as unsigned (callers accept
    /// only the unsigned types).
    #[inline]
    fn index(self, bytes: &[u8], at: usize) -> u32 {
        match self {
            Component::I8 | Component::U8 => u32::from(bytes[at]),
            Component::I16 | Component::U16 => {
                u32::from(u16::from_le_bytes([bytes[at], bytes[at + 1]]))
            }
            Component::U32 | Component::F32 => {
                u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
            }
        }
    }
}

/// The chunks of a GLB container: the JSON, and the `BIN` chunk if any.
fn glb_chunks<'a>(
    bytes: &'a [u8],
    warnings: &mut Vec<String>,
) -> Result<(&'a [u8], Option<&'a [u8]>), ParseError> {
    let u32_at = |at: usize| {
        bytes.get(at..at + 4).map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let byte =
        |at: usize, message: String| ParseError::new(Some(Location::Byte(at as u64)), message);
    let version = u32_at(4).ok_or_else(|| byte(bytes.len(), "truncated GLB header".into()))?;
    if version != 2 {
        return Err(byte(4, format!("GLB version {version} is not read (2 is)")));
    }
    let length = u32_at(8).ok_or_else(|| byte(bytes.len(), "truncated GLB header".into()))?;
    if length > bytes.len() {
        return Err(byte(
            bytes.len(),
            format!("truncated: the GLB header says {length} bytes, the file has {}", bytes.len()),
        ));
    }
    if length < bytes.len() {
        warnings.push(format!(
            "{} bytes after the GLB's declared length ({length}) were ignored",
            bytes.len() - length
        ));
    }
    let bytes = &bytes[..length];
    let mut pos = 12;
    let mut json = None;
    let mut bin = None;
    while pos < bytes.len() {
        let (Some(len), Some(kind)) = (u32_at(pos), u32_at(pos + 4)) else {
            return Err(byte(pos, "truncated GLB chunk header".into()));
        };
        let data = pos + 8;
        let end = data.checked_add(len).filter(|&e| e <= bytes.len()).ok_or_else(|| {
            byte(pos, format!("GLB chunk of {len} bytes runs past the end of the file"))
        })?;
        match kind {
            0x4E4F_534A if json.is_none() => json = Some(&bytes[data..end]),
            0x004E_4942 if bin.is_none() => bin = Some(&bytes[data..end]),
            _ => {}
        }
        if json.is_none() {
            return Err(byte(pos, "the first GLB chunk is not JSON".into()));
        }
        pos = end;
    }
    let json = json.ok_or_else(|| byte(12, "the GLB has no JSON chunk".into()))?;
    Ok((json, bin))
}

/// Reads a `.gltf` or `.glb` file; `path` locates external buffers.
pub(crate) fn read(
    path: &Path,
    bytes: &[u8],
    warnings: &mut Vec<String>,
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
    let buffers = Buffers { doc: &doc, path, bin, loaded: Vec::new(), file_bytes: bytes.len() };
    let (mesh, objects) = place(&doc, buffers, warnings)?;
    Ok(Scene { mesh, objects, binary })
}

/// The buffers' bytes, loaded on first use.
struct Buffers<'a> {
    doc: &'a Document,
    path: &'a Path,
    bin: Option<&'a [u8]>,
    loaded: Vec<Option<Cow<'a, [u8]>>>,
    file_bytes: usize,
}

impl<'a> Buffers<'a> {
    fn get(&mut self, index: usize) -> Result<&[u8], ParseError> {
        let item = format!("buffers[{index}]");
        let buffer =
            self.doc.buffers.get(index).ok_or_else(|| at(item.clone(), "no such buffer"))?;
        if self.loaded.len() < self.doc.buffers.len() {
            self.loaded.resize_with(self.doc.buffers.len(), || None);
        }
        if self.loaded[index].is_none() {
            let data: Cow<'a, [u8]> = match &buffer.uri {
                None => match (index, self.bin) {
                    (0, Some(bin)) => Cow::Borrowed(bin),
                    _ => return Err(at(item, "no uri, and it is not a GLB's BIN chunk")),
                },
                Some(uri) if uri.starts_with("data:") => {
                    let (_, encoded) = uri.split_once(";base64,").ok_or_else(|| {
                        at(item.clone(), "a data: URI that is not base64 is not read")
                    })?;
                    let engine = base64::engine::GeneralPurpose::new(
                        &base64::alphabet::STANDARD,
                        base64::engine::GeneralPurposeConfig::new().with_decode_padding_mode(
                            base64::engine::DecodePaddingMode::Indifferent,
                        ),
                    );
                    Cow::Owned(engine.decode(encoded.trim_end()).map_err(|e| {
                        at(item.clone(), format!("invalid base64 in its data: URI: {e}"))
                    })?)
                }
                Some(uri) => {
                    let name = percent_decode(uri);
                    if name.contains("://") || name.starts_with('/') {
                        return Err(at(item, format!("'{uri}' is not a relative file name")));
                    }
                    let file = self.path.parent().unwrap_or(Path::new("")).join(&name);
                    Cow::Owned(std::fs::read(&file).map_err(|e| {
                        at(item.clone(), format!("cannot read '{}': {e}", file.display()))
                    })?)
                }
            };
            let length = usize::try_from(buffer.byte_length).unwrap_or(usize::MAX);
            if data.len() < length {
                return Err(at(
                    item,
                    format!(
                        "byteLength is {}, but the data has {} bytes",
                        buffer.byte_length,
                        data.len()
                    ),
                ));
            }
            self.loaded[index] = Some(match data {
                Cow::Borrowed(b) => Cow::Borrowed(&b[..length]),
                Cow::Owned(mut v) => {
                    v.truncate(length);
                    Cow::Owned(v)
                }
            });
        }
        Ok(self.loaded[index].as_deref().unwrap_or_default())
    }

    /// The bytes of a buffer view whose buffer is loaded and which lies inside it, and
    /// its stride if it declares one.
    fn loaded_view(&self, index: usize) -> Option<(&[u8], Option<u64>)> {
        let view = self.doc.buffer_views.get(index)?;
        let buffer = self.loaded.get(view.buffer)?.as_deref()?;
        let start = usize::try_from(view.byte_offset).ok()?;
        let end = start.checked_add(usize::try_from(view.byte_length).ok()?)?;
        Some((buffer.get(start..end)?, view.byte_stride))
    }

    /// The bytes of a buffer view, and its stride if it declares one.
    fn view(&mut self, index: usize) -> Result<(&[u8], Option<usize>), ParseError> {
        let item = format!("bufferViews[{index}]");
        let doc = self.doc;
        let view =
            doc.buffer_views.get(index).ok_or_else(|| at(item.clone(), "no such buffer view"))?;
        let buffer = self.get(view.buffer)?;
        let range = usize::try_from(view.byte_offset)
            .ok()
            .zip(usize::try_from(view.byte_length).ok())
            .and_then(|(o, l)| Some(o..o.checked_add(l)?))
            .filter(|r| r.end <= buffer.len())
            .ok_or_else(|| {
                at(
                    item.clone(),
                    format!(
                        "bytes {}..+{} lie outside buffer {} ({} bytes)",
                        view.byte_offset,
                        view.byte_length,
                        view.buffer,
                        buffer.len()
                    ),
                )
            })?;
        let stride = match view.byte_stride {
            Some(s) => Some(
                usize::try_from(s)
                    .ok()
                    .filter(|&s| s > 0)
                    .ok_or_else(|| at(item, format!("invalid byteStride {s}")))?,
            ),
            None => None,
        };
        Ok((&buffer[range], stride))
    }
}

/// `%XX` escapes decoded (URIs name files with spaces as `%20`).
fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                i += 3;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Reads accessor `index`, of `kind` with `components` values per element: each element
/// decoded by `decode(bytes, offset, component type, normalized)` in parallel, straight
/// into the result; sparse values applied.
fn read_accessor<T: Copy + Default + Send>(
    buffers: &mut Buffers<'_>,
    index: usize,
    kind: &str,
    components: usize,
    decode: impl Fn(&[u8], usize, Component, bool) -> T + Sync,
) -> Result<Vec<T>, ParseError> {
    let item = format!("accessors[{index}]");
    let doc = buffers.doc;
    let accessor = doc.accessors.get(index).ok_or_else(|| at(item.clone(), "no such accessor"))?;
    if accessor.kind != kind {
        return Err(at(item, format!("type is {}, expected {kind}", accessor.kind)));
    }
    let component = Component::from_code(accessor.component_type).ok_or_else(|| {
        at(item.clone(), format!("invalid componentType {}", accessor.component_type))
    })?;
    let element = components * component.size();
    let count = usize::try_from(accessor.count).unwrap_or(usize::MAX);
    let mut values = match accessor.buffer_view {
        Some(view) => {
            let (data, stride) = buffers.view(view)?;
            let stride = stride.unwrap_or(element);
            let data =
                strided(data, accessor.byte_offset, count, stride, element).ok_or_else(|| {
                    at(
                        item.clone(),
                        format!(
                            "{} elements of {element} bytes (stride {stride}) from byte {} do \
                             not fit buffer view {view} ({} bytes)",
                            accessor.count,
                            accessor.byte_offset,
                            data.len()
                        ),
                    )
                })?;
            let normalized = accessor.normalized;
            (0..count)
                .into_par_iter()
                .with_min_len(4096)
                .map(|i| decode(data, i * stride, component, normalized))
                .collect()
        }
        None => {
            if count > buffers.file_bytes {
                return Err(at(
                    item,
                    format!(
                        "{count} elements without a buffer view: more than the file's {} \
                         bytes could describe",
                        buffers.file_bytes
                    ),
                ));
            }
            vec![T::default(); count]
        }
    };
    if let Some(sparse) = &accessor.sparse {
        let item = format!("{item}.sparse");
        let n = usize::try_from(sparse.count).unwrap_or(usize::MAX);
        let index_type = Component::from_code(sparse.indices.component_type)
            .filter(|c| matches!(c, Component::U8 | Component::U16 | Component::U32))
            .ok_or_else(|| at(item.clone(), "invalid index componentType"))?;
        let (data, _) = buffers.view(sparse.indices.buffer_view)?;
        let indices: Vec<usize> =
            strided(data, sparse.indices.byte_offset, n, index_type.size(), index_type.size())
                .ok_or_else(|| at(item.clone(), "the indices do not fit their buffer view"))?
                .chunks_exact(index_type.size())
                .take(n)
                .map(|b| index_type.index(b, 0) as usize)
                .collect();
        let (data, _) = buffers.view(sparse.values.buffer_view)?;
        let data = strided(data, sparse.values.byte_offset, n, element, element)
            .ok_or_else(|| at(item.clone(), "the values do not fit their buffer view"))?;
        for (k, &target) in indices.iter().enumerate() {
            if target >= count {
                return Err(at(item, format!("index {target} is out of range ({count} elements)")));
            }
            values[target] = decode(data, k * element, component, accessor.normalized);
        }
    }
    Ok(values)
}

/// The triangles of a `TRIANGLES` primitive read straight from its index accessor `a`
/// (checked against `n` positions), when the indices are tightly packed and not sparse
/// (the common case, as index buffer views have no stride); `None` otherwise.
fn packed_triangles(
    buffers: &Buffers<'_>,
    a: usize,
    n: usize,
) -> Result<Option<Vec<[u32; 3]>>, ParseError> {
    let item = format!("accessors[{a}]");
    let Some(accessor) = buffers.doc.accessors.get(a) else { return Ok(None) };
    let component = match accessor.component_type {
        5121 => Component::U8,
        5123 => Component::U16,
        5125 => Component::U32,
        _ => return Ok(None),
    };
    let (Some(view), None, "SCALAR") =
        (accessor.buffer_view, &accessor.sparse, accessor.kind.as_str())
    else {
        return Ok(None);
    };
    let Some((data, None)) = buffers.loaded_view(view) else { return Ok(None) };
    let size = component.size();
    let count = usize::try_from(accessor.count).unwrap_or(usize::MAX);
    let Some(data) = strided(data, accessor.byte_offset, count, size, size) else {
        return Ok(None);
    };
    // One loop per index type, each reading whole triangles.
    let data = &data[..count / 3 * 3 * size];
    let tris: Vec<[u32; 3]> = match component {
        Component::U8 => data
            .par_chunks_exact(3)
            .with_min_len(4096)
            .map(|t| [t[0], t[1], t[2]].map(u32::from))
            .collect(),
        Component::U16 => data
            .par_chunks_exact(6)
            .with_min_len(4096)
            .map(|t| [0, 2, 4].map(|k| u32::from(u16::from_le_bytes([t[k], t[k + 1]]))))
            .collect(),
        _ => data
            .par_chunks_exact(12)
            .with_min_len(4096)
            .map(|t| [0, 4, 8].map(|k| u32::from_le_bytes([t[k], t[k + 1], t[k + 2], t[k + 3]])))
            .collect(),
    };
    let bad = tris.par_iter().position_first(|t| t.iter().any(|&i| i as usize >= n));
    if let Some(t) = bad {
        let (k, v) = (0..3)
            .map(|k| (3 * t + k, tris[t][k]))
            .find(|&(_, v)| v as usize >= n)
            .unwrap_or((3 * t, 0));
        return Err(at(
            item,
            format!("index {v} (element {k}) is out of range: POSITION has {n} elements"),
        ));
    }
    Ok(Some(tris))
}

/// The bytes of `count` elements of `element` bytes, `stride` apart, from `offset` of
/// `data`; `None` when they do not fit.
fn strided(data: &[u8], offset: u64, count: usize, stride: usize, element: usize) -> Option<&[u8]> {
    let offset = usize::try_from(offset).ok()?;
    if stride < element {
        return None;
    }
    let end = match count {
        0 => offset,
        n => (n - 1).checked_mul(stride)?.checked_add(element)?.checked_add(offset)?,
    };
    data.get(offset..end)
}

/// A node's own transform.
fn local(node: &Node) -> Affine {
    if let Some(m) = node.matrix {
        // Column-major.
        return Affine([0, 1, 2].map(|r| [m[r], m[4 + r], m[8 + r], m[12 + r]]));
    }
    let [tx, ty, tz] = node.translation.unwrap_or([0.0; 3]);
    let [x, y, z, w] = node.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]);
    let [sx, sy, sz] = node.scale.unwrap_or([1.0; 3]);
    let r = [
        [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w)],
        [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w)],
        [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)],
    ];
    Affine([
        [r[0][0] * sx, r[0][1] * sy, r[0][2] * sz, tx],
        [r[1][0] * sx, r[1][1] * sy, r[1][2] * sz, ty],
        [r[2][0] * sx, r[2][1] * sy, r[2][2] * sz, tz],
    ])
}

/// A node with a mesh, placed.
struct Instance {
    node: usize,
    mesh: usize,
    placement: Affine,
}

/// The nodes with meshes reached from the default scene, in depth-first order.
fn instances(doc: &Document) -> Result<Vec<Instance>, ParseError> {
    let roots: Vec<usize> = match (doc.scene, doc.scenes.first()) {
        (Some(s), _) => {
            doc.scenes.get(s).ok_or_else(|| at("scene", format!("no scene {s}")))?.nodes.clone()
        }
        (None, Some(first)) => first.nodes.clone(),
        (None, None) => {
            let mut child = vec![false; doc.nodes.len()];
            for node in &doc.nodes {
                for &c in &node.children {
                    if let Some(flag) = child.get_mut(c) {
                        *flag = true;
                    }
                }
            }
            (0..doc.nodes.len()).filter(|&n| !child[n]).collect()
        }
    };
    let mut seen = vec![false; doc.nodes.len()];
    let mut out = Vec::new();
    let mut stack: Vec<(usize, Affine)> =
        roots.iter().rev().map(|&n| (n, Affine::IDENTITY)).collect();
    while let Some((n, parent)) = stack.pop() {
        let node = doc.nodes.get(n).ok_or_else(|| at("scenes", format!("no node {n}")))?;
        if std::mem::replace(&mut seen[n], true) {
            return Err(at(
                format!("nodes[{n}]"),
                "reached twice: the node hierarchy must be a forest (no cycles, no shared \
                 children)",
            ));
        }
        let placement = local(node).then(&parent);
        if !placement.is_finite() {
            return Err(at(format!("nodes[{n}]"), "its transform is not finite"));
        }
        if let Some(mesh) = node.mesh {
            if mesh >= doc.meshes.len() {
                return Err(at(format!("nodes[{n}].mesh"), format!("no mesh {mesh}")));
            }
            out.push(Instance { node: n, mesh, placement });
        }
        for &c in node.children.iter().rev() {
            if c >= doc.nodes.len() {
                return Err(at(format!("nodes[{n}].children"), format!("no node {c}")));
            }
            stack.push((c, placement));
        }
    }
    Ok(out)
}

/// How a primitive's vertices form triangles.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Triangles,
    Strip,
    Fan,
}

impl Mode {
    fn triangles(self, n: usize) -> usize {
        match self {
            Mode::Triangles => n / 3,
            Mode::Strip | Mode::Fan => n.saturating_sub(2),
        }
    }

    /// The vertices (positions in the index list) of triangle `i`.
    #[inline]
    fn corners(self, i: usize) -> [usize; 3] {
        match self {
            Mode::Triangles => [3 * i, 3 * i + 1, 3 * i + 2],
            Mode::Strip if i.is_multiple_of(2) => [i, i + 1, i + 2],
            Mode::Strip => [i, i + 2, i + 1],
            Mode::Fan => [i + 1, i + 2, 0],
        }
    }
}

/// A primitive's mode, `None` for points and lines.
fn mode(primitive: &Primitive, item: &str) -> Result<Option<Mode>, ParseError> {
    match primitive.mode.unwrap_or(4) {
        0..=3 => Ok(None),
        4 => Ok(Some(Mode::Triangles)),
        5 => Ok(Some(Mode::Strip)),
        6 => Ok(Some(Mode::Fan)),
        m => Err(at(format!("{item}.mode"), format!("invalid mode {m}"))),
    }
}

/// The element count of accessor `index`, once its data are known to fit its buffer
/// view (or the file's size, without one): a count that can be trusted for reserving.
fn checked_count(buffers: &mut Buffers<'_>, index: usize) -> Result<u64, ParseError> {
    let item = format!("accessors[{index}]");
    let doc = buffers.doc;
    let accessor = doc.accessors.get(index).ok_or_else(|| at(item.clone(), "no such accessor"))?;
    let components = match accessor.kind.as_str() {
        "SCALAR" => 1,
        "VEC3" => 3,
        other => return Err(at(item, format!("type {other} holds no positions or indices"))),
    };
    let component = Component::from_code(accessor.component_type).ok_or_else(|| {
        at(item.clone(), format!("invalid componentType {}", accessor.component_type))
    })?;
    let count = usize::try_from(accessor.count).unwrap_or(usize::MAX);
    let fits = match accessor.buffer_view {
        Some(view) => {
            let element = components * component.size();
            let (data, stride) = buffers.view(view)?;
            strided(data, accessor.byte_offset, count, stride.unwrap_or(element), element).is_some()
        }
        None => count <= buffers.file_bytes,
    };
    if !fits {
        return Err(at(item, format!("its {count} elements do not fit its data")));
    }
    Ok(accessor.count)
}

/// The number of vertices and triangles of a primitive.
fn primitive_size(
    buffers: &mut Buffers<'_>,
    primitive: &Primitive,
    mode: Mode,
) -> Result<(u64, u64), ParseError> {
    let vertices = match primitive.attributes.position {
        Some(a) => checked_count(buffers, a)?,
        None => 0,
    };
    let listed = match primitive.indices {
        Some(a) => checked_count(buffers, a)?,
        None => vertices,
    };
    let triangles = mode.triangles(usize::try_from(listed).unwrap_or(usize::MAX)) as u64;
    Ok((vertices, triangles))
}

/// Reads the scene's primitives into one mesh.
fn place(
    doc: &Document,
    mut buffers: Buffers<'_>,
    warnings: &mut Vec<String>,
) -> Result<(Mesh, Vec<Object>), ParseError> {
    let instances = instances(doc)?;

    // Totals first: an accessor's count is checked against its data when it is read,
    // and an instanced mesh counts once per instance.
    let mut vertices = 0u64;
    let mut triangles = 0u64;
    let mut skipped = 0usize;
    for instance in &instances {
        for (p, primitive) in doc.meshes[instance.mesh].primitives.iter().enumerate() {
            let item = format!("meshes[{}].primitives[{p}]", instance.mesh);
            match mode(primitive, &item)? {
                Some(mode) => {
                    let (v, t) = primitive_size(&mut buffers, primitive, mode)?;
                    vertices = vertices.saturating_add(v);
                    triangles = triangles.saturating_add(t);
                }
                None => skipped += 1,
            }
        }
    }
    if skipped > 0 {
        warnings.push(format!("skipped {skipped} point and line primitives (no volume)"));
    }
    let mut placed = Placed::with_capacity(vertices, triangles)
        .map_err(|message| ParseError::new(None, message))?;

    for instance in &instances {
        let first = placed.triangle_count();
        for (p, primitive) in doc.meshes[instance.mesh].primitives.iter().enumerate() {
            let item = format!("meshes[{}].primitives[{p}]", instance.mesh);
            let Some(mode) = mode(primitive, &item)? else { continue };
            let position = primitive
                .attributes
                .position
                .ok_or_else(|| at(item.clone(), "no POSITION attribute"))?;
            let positions: Vec<Point> =
                read_accessor(&mut buffers, position, "VEC3", 3, |data, at, c, normalized| {
                    match c {
                        // The common case, without a type dispatch per coordinate.
                        Component::F32 => [0, 4, 8].map(|k| {
                            let b = [
                                data[at + k],
                                data[at + k + 1],
                                data[at + k + 2],
                                data[at + k + 3],
                            ];
                            f64::from(f32::from_le_bytes(b))
                        }),
                        _ => [0, 1, 2].map(|k| c.read(data, at + k * c.size(), normalized)),
                    }
                })?;
            let bad = positions.par_iter().position_first(|p| p.iter().any(|c| !c.is_finite()));
            if let Some(bad) = bad {
                return Err(at(
                    format!("accessors[{position}]"),
                    format!("element {bad} is not finite"),
                ));
            }
            let n = positions.len();
            if let (Mode::Triangles, Some(a)) = (mode, primitive.indices) {
                if let Some(tris) = packed_triangles(&buffers, a, n)? {
                    placed.add_owned(positions, tris, &instance.placement);
                    continue;
                }
            }
            let listed: Vec<u32> = match primitive.indices {
                Some(a) => {
                    let item = format!("accessors[{a}]");
                    let ty = doc.accessors.get(a).map_or(0, |a| a.component_type);
                    if !matches!(ty, 5121 | 5123 | 5125) {
                        return Err(at(item, "indices must be unsigned byte, short or int"));
                    }
                    let values = read_accessor(&mut buffers, a, "SCALAR", 1, |data, at, c, _| {
                        c.index(data, at)
                    })?;
                    if let Some((k, &v)) =
                        values.par_iter().enumerate().find_first(|(_, &v)| v as usize >= n)
                    {
                        return Err(at(
                            item,
                            format!(
                                "index {v} (element {k}) is out of range: POSITION has {n} \
                                 elements"
                            ),
                        ));
                    }
                    values
                }
                None => {
                    let n32 = u32::try_from(n).map_err(|_| {
                        at(item.clone(), format!("{n} vertices do not fit 32-bit indices"))
                    })?;
                    (0..n32).collect()
                }
            };
            let count = mode.triangles(listed.len());
            let tris: Vec<[u32; 3]> =
                (0..count).into_par_iter().map(|t| mode.corners(t).map(|k| listed[k])).collect();
            placed.add_owned(positions, tris, &instance.placement);
        }
        let node = &doc.nodes[instance.node];
        let name = node
            .name
            .clone()
            .or_else(|| doc.meshes[instance.mesh].name.clone())
            .unwrap_or_else(|| format!("node {}", instance.node));
        placed.close_object(name, first);
    }
    placed.finish().map_err(|e| ParseError::new(None, e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_cover_the_polygon() {
        assert_eq!(Mode::Strip.triangles(5), 3);
        assert_eq!(Mode::Strip.corners(0), [0, 1, 2]);
        assert_eq!(Mode::Strip.corners(1), [1, 3, 2]);
        assert_eq!(Mode::Fan.corners(1), [2, 3, 0]);
        assert_eq!(Mode::Triangles.triangles(7), 2);
    }

    #[test]
    fn trs_is_translation_rotation_scale() {
        // A quarter turn about z (quaternion (0, 0, sin 45°, cos 45°)), scale 2, shift x.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let node = Node {
            translation: Some([10.0, 0.0, 0.0]),
            rotation: Some([0.0, 0.0, h, h]),
            scale: Some([2.0, 2.0, 2.0]),
            ..Node::default()
        };
        let p = local(&node).apply([1.0, 0.0, 0.0]);
        assert!((p[0] - 10.0).abs() < 1e-12 && (p[1] - 2.0).abs() < 1e-12, "{p:?}");
        let m = Node {
            matrix: Some([1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 5., 6., 7., 1.]),
            ..Node::default()
        };
        assert_eq!(local(&m).apply([1.0, 1.0, 1.0]), [6.0, 7.0, 8.0]);
        assert_eq!(percent_decode("a%20b%zz.bin"), "a b%zz.bin");
    }
}
