//! The bytes of an asset or resource: read into memory, or memory-mapped when large, so
//! that checking a 1 GB GLB neither copies it nor zeroes a 1 GB buffer first.

use std::fs::File;
use std::ops::Deref;
use std::path::Path;

/// Files at least this large are mapped; below it a read is cheaper than the mapping.
const MAP_THRESHOLD: u64 = 1 << 20;

/// A file's bytes: read into memory, or memory-mapped when large.
#[derive(Debug)]
pub enum Bytes {
    /// Read into memory.
    Owned(Vec<u8>),
    /// Memory-mapped (files of 1 MiB or more).
    Mapped(memmap2::Mmap),
}

impl Bytes {
    /// Reads a file, mapping it when large (falling back to a read when mapping fails).
    pub fn open(path: &Path) -> std::io::Result<Bytes> {
        let file = File::open(path)?;
        if file.metadata()?.len() >= MAP_THRESHOLD {
            // SAFETY: the mapping is read-only and private to this process. If another
            // process truncates the file while it is being checked, reads past the new end
            // fault: the same hazard as every mmap-based reader, accepted for inputs that
            // are not being rewritten while they are checked.
            if let Ok(map) = unsafe { memmap2::Mmap::map(&file) } {
                return Ok(Bytes::Mapped(map));
            }
        }
        std::fs::read(path).map(Bytes::Owned)
    }

    /// Tells the system that `part` (a slice of these bytes) will not be read again soon,
    /// so a mapped file's pages can leave this process's memory. They are read back from
    /// the file if touched again, so this never changes what is read. Nothing happens for
    /// bytes in memory or slices from elsewhere.
    pub fn release(&self, part: &[u8]) {
        let Bytes::Mapped(map) = self else { return };
        let base = map.as_ptr() as usize;
        let start = part.as_ptr() as usize;
        if start < base || start + part.len() > base + map.len() {
            return;
        }
        // Rounded inward to 64 KiB, a multiple of every common page size.
        const ALIGN: usize = 1 << 16;
        let first = (start - base).next_multiple_of(ALIGN);
        let end = (start - base + part.len()) / ALIGN * ALIGN;
        if end > first {
            // SAFETY: the mapping is read-only and file-backed, so dropping its pages loses
            // nothing: a later read faults them back in from the file.
            let dropped = unsafe {
                map.unchecked_advise_range(memmap2::UncheckedAdvice::DontNeed, first, end - first)
            };
            // Advice only: when refused, the pages simply stay.
            drop(dropped);
        }
    }

    /// The bytes as an owned vector (a copy when mapped).
    pub fn into_vec(self) -> Vec<u8> {
        match self {
            Bytes::Owned(v) => v,
            Bytes::Mapped(map) => map.to_vec(),
        }
    }
}

impl Default for Bytes {
    fn default() -> Self {
        Bytes::Owned(Vec::new())
    }
}

impl Deref for Bytes {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        match self {
            Bytes::Owned(v) => v,
            Bytes::Mapped(map) => map,
        }
    }
}

impl AsRef<[u8]> for Bytes {
    fn as_ref(&self) -> &[u8] {
        self
    }
}

/// A buffer's bytes: borrowed from the document (the GLB BIN chunk), or held (an external
/// file or a data URI).
pub enum BufferData<'a> {
    /// Borrowed from the GLB BIN chunk.
    Glb(&'a [u8]),
    /// Read from an external file or a data URI.
    Loaded(Bytes),
}

impl Deref for BufferData<'_> {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        match self {
            BufferData::Glb(bytes) => bytes,
            BufferData::Loaded(bytes) => bytes,
        }
    }
}

impl From<Vec<u8>> for Bytes {
    fn from(bytes: Vec<u8>) -> Self {
        Bytes::Owned(bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_files_are_read_and_large_ones_mapped_with_the_same_content() {
        let folder = std::env::temp_dir().join(format!("gltfmat-bytes-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let small = folder.join("small.bin");
        let large = folder.join("large.bin");
        std::fs::write(&small, b"abc").unwrap();
        let big: Vec<u8> = (0..MAP_THRESHOLD as usize + 7).map(|i| i as u8).collect();
        std::fs::write(&large, &big).unwrap();
        assert!(matches!(Bytes::open(&small).unwrap(), Bytes::Owned(_)));
        let mapped = Bytes::open(&large).unwrap();
        assert!(matches!(mapped, Bytes::Mapped(_)));
        assert_eq!(&mapped[..], &big[..]);
        // Released pages are read back from the file, unchanged.
        mapped.release(&mapped[..]);
        assert_eq!(&mapped[..], &big[..]);
        assert_eq!(mapped.into_vec(), big);
        std::fs::remove_dir_all(&folder).unwrap();
    }
}
