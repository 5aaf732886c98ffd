//! The bytes of an asset or resource. They are read, never mapped: a mapped file that
//! another process truncates kills the reader with SIGBUS, and a stranger's upload may be
//! rewritten while it is checked. A large GLB's BIN chunk is read a range at a time from
//! its opened file (a range the file no longer holds reads as nothing).

use super::file::{FileChunk, Kept};
use std::borrow::Cow;
use std::ops::Range;

/// A file's bytes, read into memory.
pub type Bytes = Vec<u8>;

/// A buffer's bytes: borrowed from the document (the GLB BIN chunk), left in the GLB's file
/// (the BIN chunk of a large GLB, read a range at a time), or held (an external file or a
/// data URI).
pub enum BufferData<'a> {
    /// Borrowed from the GLB BIN chunk.
    Glb(&'a [u8]),
    /// The BIN chunk of a large GLB, still in its file.
    InFile(&'a FileChunk),
    /// Read from an external file or a data URI.
    Loaded(Bytes),
    /// A large external file, still in the file.
    LoadedInFile(FileChunk),
}

impl From<Kept> for BufferData<'_> {
    fn from(kept: Kept) -> Self {
        match kept {
            Kept::Read(bytes) => BufferData::Loaded(bytes),
            Kept::InFile(chunk) => BufferData::LoadedInFile(chunk),
        }
    }
}

impl BufferData<'_> {
    /// How many bytes the buffer holds.
    pub fn len(&self) -> usize {
        match self {
            BufferData::Glb(bytes) => bytes.len(),
            BufferData::InFile(chunk) => chunk.len(),
            BufferData::Loaded(bytes) => bytes.len(),
            BufferData::LoadedInFile(chunk) => chunk.len(),
        }
    }

    /// Whether the buffer holds no byte.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The bytes at `range`: borrowed when they are in memory, read now when they are in a
    /// file; `None` when the range is outside the buffer (or the file no longer holds it).
    pub fn get(&self, range: Range<usize>) -> Option<Cow<'_, [u8]>> {
        match self {
            BufferData::Glb(bytes) => bytes.get(range).map(Cow::Borrowed),
            BufferData::InFile(chunk) => chunk.read(range).map(Cow::Owned),
            BufferData::Loaded(bytes) => bytes.get(range).map(Cow::Borrowed),
            BufferData::LoadedInFile(chunk) => chunk.read(range).map(Cow::Owned),
        }
    }

    /// The whole buffer when it is in memory.
    pub fn in_memory(&self) -> Option<&[u8]> {
        match self {
            BufferData::Glb(bytes) => Some(bytes),
            BufferData::InFile(_) | BufferData::LoadedInFile(_) => None,
            BufferData::Loaded(bytes) => Some(bytes),
        }
    }
}
