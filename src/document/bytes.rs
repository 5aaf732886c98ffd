//! The bytes of an asset or resource. They are always read into memory, never mapped: a
//! mapped file that another process truncates kills the reader with SIGBUS, and a stranger's
//! upload may be rewritten while it is checked.

use std::ops::Deref;

/// A file's bytes, read into memory.
pub type Bytes = Vec<u8>;

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
