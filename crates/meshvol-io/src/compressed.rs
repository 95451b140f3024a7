//! Compressed inputs: `part.stl.gz`, `part.obj.bz2`, `part.ply.zst`, `parts.zip`.
//!
//! A file whose last extension is `.gz` (gzip, concatenated members included), `.bz2`,
//! `.zst` (Zstandard) or `.zip` is decompressed in memory and read as the file it holds:
//! for `.gz`, `.bz2` and `.zst` the format is the one the name names without the last
//! extension (`part.stl.gz` is STL), else the content's; a `.zip` must hold exactly one
//! file the reader reads (by extension: for meshes `.stl`, `.obj`, `.off`, `.ply`,
//! `.3mf`, `.gltf`, `.glb`; hidden members and macOS's `__MACOSX/` folder are passed
//! over), which is read as `archive.zip/member.stl`: a zip with none, or with several, is
//! an error listing its members. A `.gltf` member's external buffers (`scene.bin`) are
//! read from the same archive ([`Archive`]).
//!
//! An input without an extension (standard input, `-`) has no name to say it is
//! compressed: its first bytes do ([`Compression::of_input`]: the gzip, bzip2, Zstandard
//! and zip signatures), and it is decompressed as a file of that kind is.
//!
//! Decompression is bounded as streams are: a file that inflates past
//! [`stream_limit`](crate::stream_limit) bytes (2 GiB, `MESHVOL_MAX_STREAM_BYTES`) is
//! refused with an error naming it, before more is held (a "zip bomb" costs at most the
//! limit). A damaged stream is an error naming the file and the compression.

use std::io::{Cursor, Read};
use std::path::{Path, PathBuf};

use crate::limits::Budget;
use crate::source::STREAM_LIMIT_VARIABLE;
use crate::ReadError;

/// The extensions of the compressed forms read, without the dot.
pub const COMPRESSED_EXTENSIONS: [&str; 4] = ["gz", "bz2", "zst", "zip"];

/// A compression the readers undo.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compression {
    Gzip,
    Bzip2,
    Zstd,
    Zip,
}

impl Compression {
    /// The compression a path's last extension names (any case), if any.
    pub fn of_path(path: &Path) -> Option<Compression> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "gz" => Compression::Gzip,
            "bz2" => Compression::Bzip2,
            "zst" => Compression::Zstd,
            "zip" => Compression::Zip,
            _ => return None,
        })
    }

    /// The compression of an input: the one its name's last extension names or, for a
    /// name without an extension (standard input, `-`), the one its first bytes show.
    pub fn of_input(path: &Path, bytes: &[u8]) -> Option<Compression> {
        if path.extension().is_some() {
            return Compression::of_path(path);
        }
        Compression::of_content(bytes)
    }

    /// The compression whose signature the bytes start with (RFC 1952's gzip, bzip2's
    /// `BZh` and block size, RFC 8878's Zstandard frame, a zip's local file header).
    pub fn of_content(bytes: &[u8]) -> Option<Compression> {
        if bytes.starts_with(&[0x1f, 0x8b]) {
            Some(Compression::Gzip)
        } else if bytes.starts_with(b"BZh") && bytes.get(3).is_some_and(u8::is_ascii_digit) {
            Some(Compression::Bzip2)
        } else if bytes.starts_with(&[0x28, 0xb5, 0x2f, 0xfd]) {
            Some(Compression::Zstd)
        } else if bytes.starts_with(b"PK\x03\x04") {
            Some(Compression::Zip)
        } else {
            None
        }
    }

    fn name(self) -> &'static str {
        match self {
            Compression::Gzip => "gzip",
            Compression::Bzip2 => "bzip2",
            Compression::Zstd => "Zstandard",
            Compression::Zip => "zip",
        }
    }
}

/// The decompressed content of `bytes` (read from `path`, compressed by `compression`),
/// inflated up to `limit` bytes, and the name it is read under: `part.stl` for
/// `part.stl.gz`, `archive.zip/member.stl` for a zip's one member that `wanted` accepts
/// (by its name).
pub(crate) fn decompress(
    path: &Path,
    bytes: &[u8],
    compression: Compression,
    wanted: impl Fn(&Path) -> bool,
    limit: u64,
) -> Result<(PathBuf, Vec<u8>), ReadError> {
    let damaged = |e: std::io::Error| {
        ReadError::of_file(path, format!("not a readable {} file: {e}", compression.name()))
    };
    let inner = path.with_extension("");
    match compression {
        Compression::Gzip => {
            let data =
                bounded(path, flate2::read::MultiGzDecoder::new(bytes), limit).map_err(damaged)?;
            Ok((inner, data?))
        }
        Compression::Bzip2 => {
            let data =
                bounded(path, bzip2::read::MultiBzDecoder::new(bytes), limit).map_err(damaged)?;
            Ok((inner, data?))
        }
        Compression::Zstd => {
            let decoder = ruzstd::decoding::StreamingDecoder::new(bytes)
                .map_err(|e| damaged(std::io::Error::other(e.to_string())))?;
            let data = bounded(path, decoder, limit).map_err(damaged)?;
            Ok((inner, data?))
        }
        Compression::Zip => unzip(path, bytes, wanted, limit),
    }
}

/// All of `reader`, or an error naming `path` (and the budget) when it goes on past
/// `limit` bytes.
fn bounded(
    path: &Path,
    reader: impl Read,
    limit: u64,
) -> std::io::Result<Result<Vec<u8>, ReadError>> {
    let mut data = Vec::new();
    reader.take(limit.saturating_add(1)).read_to_end(&mut data)?;
    if data.len() as u64 > limit {
        let message = format!(
            "decompresses to more than {limit} bytes: refused (a compressed input is read \
             up to {STREAM_LIMIT_VARIABLE} bytes, 2 GiB unless it says otherwise)"
        );
        return Ok(Err(ReadError {
            budget: Some(Budget::InflatedBytes),
            ..ReadError::of_file(path, message)
        }));
    }
    Ok(Ok(data))
}

/// The zip archive a file was read from (`parts.zip/scene.gltf`): a glTF's external
/// buffers are the archive's members, named relative to the glTF's folder in it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Archive<'a> {
    /// The archive's bytes.
    pub(crate) bytes: &'a [u8],
    /// The file read, as a member name (`models/scene.gltf`).
    pub(crate) member: &'a Path,
    /// The most bytes a member is inflated to.
    pub(crate) limit: u64,
}

impl Archive<'_> {
    /// The first `length` bytes (at most; fewer if the member is shorter) of the member
    /// at `relative` (a relative path without `..`) from the folder of [`Archive::member`].
    pub(crate) fn read(&self, relative: &Path, length: u64) -> Result<Vec<u8>, String> {
        let folder = self.member.parent().unwrap_or(Path::new(""));
        let parts: Vec<String> = folder
            .join(relative)
            .components()
            .filter(|c| matches!(c, std::path::Component::Normal(_)))
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        let name = parts.join("/");
        let mut archive = zip::ZipArchive::new(Cursor::new(self.bytes))
            .map_err(|e| format!("not a readable zip archive: {e}"))?;
        let file = archive.by_name(&name).map_err(|_| {
            format!(
                "'{name}' is not in the zip archive the glTF is in: zip the .glb, or the \
                 folder with the .gltf and its buffers"
            )
        })?;
        let mut data = Vec::new();
        let limit = length.min(self.limit);
        file.take(limit)
            .read_to_end(&mut data)
            .map_err(|e| format!("cannot read '{name}' from the zip archive: {e}"))?;
        Ok(data)
    }
}

/// Whether a zip member is hidden or an archiver's own: a name starting with `.` in any
/// folder (`._part.stl`, macOS's resource forks) or under `__MACOSX/`.
fn hidden(name: &str) -> bool {
    name.split('/').any(|part| part.starts_with('.') || part == "__MACOSX")
}

/// The one member of a zip archive that `wanted` accepts, decompressed.
fn unzip(
    path: &Path,
    bytes: &[u8],
    wanted: impl Fn(&Path) -> bool,
    limit: u64,
) -> Result<(PathBuf, Vec<u8>), ReadError> {
    let damaged = |e: String| ReadError::of_file(path, format!("not a readable zip archive: {e}"));
    let mut archive =
        zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| damaged(e.to_string()))?;
    let names: Vec<String> = archive.file_names().map(str::to_string).collect();
    let mut members: Vec<&String> = names
        .iter()
        .filter(|n| !n.ends_with('/') && !hidden(n) && wanted(Path::new(n.as_str())))
        .collect();
    members.sort();
    let list = |names: &[&String]| {
        const SHOWN: usize = 10;
        let mut s: Vec<&str> = names.iter().take(SHOWN).map(|n| n.as_str()).collect();
        let more = names.len().saturating_sub(SHOWN);
        let more = if more > 0 { format!(" and {more} more") } else { String::new() };
        if s.is_empty() {
            s.push("none");
        }
        format!("{}{more}", s.join(", "))
    };
    let member = match members.as_slice() {
        [one] => (*one).clone(),
        // A 3MF package named .zip is read as the 3MF it is.
        [] if names.iter().any(|n| n.starts_with("3D/") && n.ends_with(".model"))
            && wanted(Path::new("model.3mf")) =>
        {
            return Ok((path.with_extension("3mf"), bytes.to_vec()));
        }
        [] => {
            let all: Vec<&String> = names.iter().filter(|n| !n.ends_with('/')).collect();
            return Err(ReadError::of_file(
                path,
                format!(
                    "the archive holds no file meshvol reads here (its files: {}): a .zip must \
                     hold exactly one",
                    list(&all)
                ),
            ));
        }
        several => {
            return Err(ReadError::of_file(
                path,
                format!(
                    "the archive holds {} files meshvol reads ({}): a .zip must hold exactly \
                     one; unzip it and give the folder instead",
                    several.len(),
                    list(several)
                ),
            ))
        }
    };
    let inner = path.join(&member);
    let file = archive
        .by_name(&member)
        .map_err(|e| ReadError::of_file(&inner, format!("cannot read the archive member: {e}")))?;
    let data = bounded(&inner, file, limit)
        .map_err(|e| ReadError::of_file(&inner, format!("cannot read the archive member: {e}")))?;
    Ok((inner, data?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// A limit none of these inputs comes near.
    const LIMIT: u64 = 1 << 30;

    fn gz(data: &[u8]) -> Vec<u8> {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        e.write_all(data).unwrap();
        e.finish().unwrap()
    }

    #[test]
    fn past_the_limit_is_an_error_naming_the_budget() {
        let data = gz(&[b'#'; 1001]);
        let (_, back) =
            decompress(Path::new("a.obj.gz"), &data, Compression::Gzip, |_| true, 1001).unwrap();
        assert_eq!(back, [b'#'; 1001]);
        let e = decompress(Path::new("a.obj.gz"), &data, Compression::Gzip, |_| true, 1000)
            .unwrap_err();
        assert_eq!(e.budget, Some(Budget::InflatedBytes), "{e}");
        assert!(e.message.contains("more than 1000 bytes"), "{e}");
    }

    #[test]
    fn gzip_names_the_inner_file_and_damage_is_an_error() {
        let (inner, data) = decompress(
            Path::new("a/part.stl.gz"),
            &gz(b"hello"),
            Compression::Gzip,
            |_| true,
            LIMIT,
        )
        .unwrap();
        assert_eq!((inner, data), (PathBuf::from("a/part.stl"), b"hello".to_vec()));
        let err =
            decompress(Path::new("x.obj.gz"), b"not gzip", Compression::Gzip, |_| true, LIMIT)
                .unwrap_err();
        assert!(err.to_string().contains("x.obj.gz") && err.to_string().contains("gzip"), "{err}");
        let err =
            decompress(Path::new("x.obj.zst"), b"not zstd", Compression::Zstd, |_| true, LIMIT)
                .unwrap_err();
        assert!(err.to_string().contains("Zstandard"), "{err}");
    }

    /// Bytes in memory named `part.obj.gz` (an upload) are read as `read` reads such a
    /// file: decompressed, then as the OBJ inside, with the same faces as the plain bytes.
    #[test]
    fn bytes_with_a_compressed_name_are_decompressed_first() {
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        let plain = crate::read_bytes(Path::new("part.obj"), obj.to_vec()).unwrap();
        let packed = crate::read_bytes(Path::new("part.obj.gz"), gz(obj)).unwrap();
        assert_eq!(packed.format.name(), "obj");
        assert_eq!(packed.face_count(), plain.face_count());
        assert_eq!(packed.vertex_count(), plain.vertex_count());
        let err = crate::read_bytes(Path::new("part.obj.gz"), obj.to_vec()).unwrap_err();
        assert!(err.to_string().contains("part.obj.gz"), "{err}");
    }

    /// Damaged streams of every form (bytes changed, cut short) are errors or data, never
    /// a panic.
    #[test]
    fn damaged_streams_never_panic() {
        let data: Vec<u8> = (0..4000u32).map(|i| (i * 7 % 251) as u8).collect();
        let bz = {
            let mut e = bzip2::write::BzEncoder::new(Vec::new(), bzip2::Compression::fast());
            e.write_all(&data).unwrap();
            e.finish().unwrap()
        };
        let zst = ruzstd::encoding::compress_to_vec(
            &data[..],
            ruzstd::encoding::CompressionLevel::Fastest,
        );
        let zip = {
            let mut z = zip::ZipWriter::new(Cursor::new(Vec::new()));
            z.start_file("a.stl", zip::write::SimpleFileOptions::default()).unwrap();
            z.write_all(&data).unwrap();
            z.finish().unwrap().into_inner()
        };
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            state.wrapping_mul(0x2545_F491_4F6C_DD1D)
        };
        for (compression, good) in [
            (Compression::Gzip, gz(&data)),
            (Compression::Bzip2, bz),
            (Compression::Zstd, zst),
            (Compression::Zip, zip),
        ] {
            let (_, back) =
                decompress(Path::new("a.stl.x"), &good, compression, |_| true, LIMIT).unwrap();
            assert_eq!(back, data, "{compression:?}");
            for _ in 0..300 {
                let mut bad = good.clone();
                for _ in 0..1 + next() % 4 {
                    let at = (next() % bad.len() as u64) as usize;
                    bad[at] = next() as u8;
                }
                if next() % 3 == 0 {
                    bad.truncate((next() % bad.len() as u64) as usize);
                }
                let _ = decompress(Path::new("a.stl.x"), &bad, compression, |_| true, LIMIT);
            }
        }
    }

    #[test]
    fn extensions_name_compressions() {
        assert_eq!(Compression::of_path(Path::new("a.STL.GZ")), Some(Compression::Gzip));
        assert_eq!(Compression::of_path(Path::new("a.zst")), Some(Compression::Zstd));
        assert_eq!(Compression::of_path(Path::new("a.stl")), None);
    }
}
