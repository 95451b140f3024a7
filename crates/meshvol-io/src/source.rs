//! The bytes of a file: memory-mapped when the file can be mapped, read into memory
//! otherwise (empty files, pipes), or handed over by the caller.

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
        let mut file = File::open(path)?;
        let meta = file.metadata()?;
        if meta.is_dir() {
            return Err(std::io::Error::other("is a directory, not a mesh file"));
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
        let mut data = Vec::new();
        file.read_to_end(&mut data)?;
        Ok(Bytes::Owned(data))
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
