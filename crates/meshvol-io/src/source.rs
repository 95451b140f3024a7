//! The bytes of a file: memory-mapped when the file can be mapped, read into memory
//! otherwise (empty files, pipes), or handed over by the caller.
//!
//! Streams (pipes, standard input) have no size to check before reading, and may never
//! end: they are read up to [`stream_limit`] bytes and refused beyond it. Devices
//! (`/dev/zero`, `/dev/random`) are refused outright. What the bytes may cost in memory
//! is bounded by [`available_memory`] ([`crate::memory`] estimates it).

use std::fs::File;
use std::io::Read;
use std::ops::Deref;
use std::path::Path;

use memmap2::Mmap;

/// Owned file contents.
pub(crate) enum Bytes {
    Mapped(Mmap),
    Owned(Vec<u8>),
}

impl Bytes {
    /// Maps the file at `path`, or reads it when mapping is not possible.
    pub fn open(path: &Path) -> std::io::Result<Bytes> {
        let file = File::open(path)?;
        let meta = file.metadata()?;
        if meta.is_dir() {
            return Err(std::io::Error::other("is a directory, not a mesh file"));
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            let kind = meta.file_type();
            if kind.is_char_device() || kind.is_block_device() {
                return Err(std::io::Error::other("is a device, not a mesh file"));
            }
        }
        if meta.is_file() && meta.len() > 0 {
            // SAFETY: the map is read-only and lives as long as the returned value. As
            // with every memory map, another process truncating or rewriting the file
            // while it is mapped can make reads fail (SIGBUS) or change under us; mesh
            // files being measured are not expected to be modified concurrently.
            if let Ok(map) = unsafe { Mmap::map(&file) } {
                return Ok(Bytes::Mapped(map));
            }
        }
        Ok(Bytes::Owned(read_stream(file)?))
    }
}

/// The environment variable that sets [`stream_limit`], in bytes.
pub const STREAM_LIMIT_VARIABLE: &str = "MESHVOL_MAX_STREAM_BYTES";

/// The most bytes read from a stream (a pipe, standard input): 2 GiB, or what
/// `MESHVOL_MAX_STREAM_BYTES` says. (A 40-million-triangle binary STL is 2 GB.)
pub fn stream_limit() -> u64 {
    stream_limit_setting().ok().flatten().unwrap_or(2 << 30)
}

/// What `MESHVOL_MAX_STREAM_BYTES` says: nothing when it is unset, or an error naming
/// it when it is not a number of bytes (`256MiB`), for a program that refuses to start
/// on a bad setting rather than use the default.
pub fn stream_limit_setting() -> Result<Option<u64>, String> {
    match std::env::var(STREAM_LIMIT_VARIABLE) {
        Err(std::env::VarError::NotPresent) => Ok(None),
        Ok(v) => match v.trim().parse() {
            Ok(n) => Ok(Some(n)),
            Err(_) => Err(format!("{STREAM_LIMIT_VARIABLE}={v} is not a number of bytes")),
        },
        Err(std::env::VarError::NotUnicode(v)) => {
            Err(format!("{STREAM_LIMIT_VARIABLE}={v:?} is not a number of bytes"))
        }
    }
}

/// All of a stream, refused beyond [`stream_limit`] bytes.
pub fn read_stream(stream: impl Read) -> std::io::Result<Vec<u8>> {
    let limit = stream_limit();
    let mut data = Vec::new();
    stream.take(limit.saturating_add(1)).read_to_end(&mut data)?;
    if data.len() as u64 > limit {
        return Err(std::io::Error::other(format!(
            "the stream goes on past {limit} bytes: save it to a file, or raise \
             {STREAM_LIMIT_VARIABLE}"
        )));
    }
    Ok(data)
}

impl Bytes {
    /// Lets the system drop a mapped file's resident pages (a binary STL checked in
    /// place: its 50 bytes a triangle are read by welding, and not again by the check).
    /// A later read faults them back in from the file. Owned bytes stay as they are.
    pub fn release_pages(&self) {
        #[cfg(unix)]
        if let Bytes::Mapped(map) = self {
            // SAFETY: the map is read-only, so it holds no changes of its own: dropping
            // its pages loses nothing, and the next read maps the file's bytes again (the same bytes, as long as the file is not rewritten while
            // mapped, which every read of a map already assumes; see `Bytes::open`). A
            // refusal (an old kernel) only leaves the pages where they are.
            let _ = unsafe { map.unchecked_advise(memmap2::UncheckedAdvice::DontNeed) };
        }
    }
}

impl Deref for Bytes {
    type Target = [u8];

    #[inline]
    fn deref(&self) -> &[u8] {
        match self {
            Bytes::Mapped(m) => m,
            Bytes::Owned(v) => v,
        }
    }
}

/// The environment variable that sets [`available_memory`], in bytes.
pub const MEMORY_LIMIT_VARIABLE: &str = "MESHVOL_MEMORY_LIMIT";

/// The memory a read may use: `MESHVOL_MEMORY_LIMIT` bytes when it is set to a number,
/// else what /proc/meminfo calls available (free memory and the caches the system can
/// drop), where there is one; `None` elsewhere.
pub fn available_memory() -> Option<u128> {
    match std::env::var(MEMORY_LIMIT_VARIABLE).ok().and_then(|v| v.trim().parse().ok()) {
        Some(limit) => Some(limit),
        None => meminfo_available(),
    }
}

fn meminfo_available() -> Option<u128> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
