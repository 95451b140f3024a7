//! A glTF file's bytes: the GLB container's chunks, buffers (the `BIN` chunk, `data:`
//! URIs, files beside the document or in its zip archive), buffer views, and accessors
//! decoded from them.

use std::borrow::Cow;
use std::io::Read;
use std::path::{self, Path, PathBuf};

use base64::Engine;
use rayon::prelude::*;

use super::schema::{at, Document};
use crate::compressed::Archive;
use crate::error::{Location, ParseError};

/// An accessor component type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Component {
    I8,
    U8,
    I16,
    U16,
    U32,
    F32,
}

impl Component {
    pub(super) fn from_code(code: u64) -> Option<Component> {
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

    pub(super) fn size(self) -> usize {
        match self {
            Component::I8 | Component::U8 => 1,
            Component::I16 | Component::U16 => 2,
            Component::U32 | Component::F32 => 4,
        }
    }

    /// The value at `bytes[at..]` (in range), as `f64`, normalized to [-1, 1] or [0, 1]
    /// when asked.
    #[inline]
    pub(super) fn read(self, bytes: &[u8], at: usize, normalized: bool) -> f64 {
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
    pub(super) fn index(self, bytes: &[u8], at: usize) -> u32 {
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
pub(super) fn glb_chunks<'a>(
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
/// The relative path a buffer's `uri` names (percent-decoded), refused unless it stays
/// in the glTF's folder: no `..`, no root, no scheme. So a file cannot make meshvol read
/// another file's bytes (`../../secret`, `%2e%2e/`).
fn relative_name(uri: &str) -> Result<PathBuf, String> {
    let name = percent_decode(uri);
    let relative = PathBuf::from(&name);
    let plain = relative
        .components()
        .all(|c| matches!(c, path::Component::Normal(_) | path::Component::CurDir));
    if name.contains("://") || name.is_empty() || !plain {
        return Err(format!(
            "'{uri}' is not a file in the glTF's folder (buffers are read from there only)"
        ));
    }
    Ok(relative)
}

/// The file at `relative` beside the glTF at `gltf`, confined to its folder: it must
/// resolve (symbolic links followed) inside the folder, to a regular file, so a link
/// cannot lead out of it or to a device (`/dev/zero`). A glTF read from standard input
/// has no folder: its buffers must be in the file (GLB), in `data:` URIs, or in the zip
/// archive it came in.
fn confined_file(gltf: &Path, uri: &str, relative: &Path) -> Result<PathBuf, String> {
    if gltf.as_os_str() == "-" {
        return Err(format!(
            "'{uri}' names a file, but a glTF from standard input has no folder: send a GLB, \
             data: URIs, or a zip of the .gltf and its buffers"
        ));
    }
    let folder = gltf.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let cannot = |p: &Path, e: std::io::Error| format!("cannot read '{}': {e}", p.display());
    let folder = folder.canonicalize().map_err(|e| cannot(folder, e))?;
    let file = folder.join(relative);
    let resolved = file.canonicalize().map_err(|e| cannot(&file, e))?;
    if !resolved.starts_with(&folder) {
        return Err(format!("'{uri}' leads out of the glTF's folder (a symbolic link)"));
    }
    if !resolved.metadata().map_err(|e| cannot(&file, e))?.is_file() {
        return Err(format!("'{uri}' is not a regular file"));
    }
    Ok(resolved)
}

/// The first `length` bytes (at most) of the buffer file `uri`: a member of the zip
/// archive the glTF came in, else a file beside it ([`confined_file`]).
fn external(
    gltf: &Path,
    archive: Option<Archive<'_>>,
    uri: &str,
    length: u64,
) -> Result<Vec<u8>, String> {
    let relative = relative_name(uri)?;
    if let Some(archive) = archive {
        return archive.read(&relative, length);
    }
    let file = confined_file(gltf, uri, &relative)?;
    let mut data = Vec::new();
    // Never more than byteLength bytes, whatever the file holds.
    std::fs::File::open(&file)
        .and_then(|f| f.take(length).read_to_end(&mut data))
        .map_err(|e| format!("cannot read '{}': {e}", file.display()))?;
    Ok(data)
}

/// The buffers' bytes, loaded on first use.
pub(super) struct Buffers<'a> {
    pub(super) doc: &'a Document,
    pub(super) path: &'a Path,
    /// The zip archive the glTF came in, whose members its external buffers are.
    pub(super) archive: Option<Archive<'a>>,
    pub(super) bin: Option<&'a [u8]>,
    pub(super) loaded: Vec<Option<Cow<'a, [u8]>>>,
    pub(super) file_bytes: usize,
}

impl<'a> Buffers<'a> {
    pub(super) fn get(&mut self, index: usize) -> Result<&[u8], ParseError> {
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
                Some(uri) => Cow::Owned(
                    external(self.path, self.archive, uri, buffer.byte_length)
                        .map_err(|e| at(item.clone(), e))?,
                ),
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
    pub(super) fn loaded_view(&self, index: usize) -> Option<(&[u8], Option<u64>)> {
        let view = self.doc.buffer_views.get(index)?;
        let buffer = self.loaded.get(view.buffer)?.as_deref()?;
        let start = usize::try_from(view.byte_offset).ok()?;
        let end = start.checked_add(usize::try_from(view.byte_length).ok()?)?;
        Some((buffer.get(start..end)?, view.byte_stride))
    }

    /// The bytes of a buffer view, and its stride if it declares one.
    pub(super) fn view(&mut self, index: usize) -> Result<(&[u8], Option<usize>), ParseError> {
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
pub(super) fn percent_decode(uri: &str) -> String {
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
pub(super) fn read_accessor<T: Copy + Default + Send>(
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
pub(super) fn packed_triangles(
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
pub(super) fn strided(
    data: &[u8],
    offset: u64,
    count: usize,
    stride: usize,
    element: usize,
) -> Option<&[u8]> {
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
