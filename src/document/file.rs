//! Reading files as a stranger may have laid them out. Only regular files are read: a FIFO
//! would block forever and a device never ends. What is read is decided by the opened
//! handle, never by a name looked at before opening, so a file swapped in between cannot be
//! read in its place. Reads are bounded by the largest file a glTF asset can use.

use super::bytes::{Bytes, Pieces};
use std::borrow::Cow;
use std::fs::{File, FileType, Metadata};
use std::io::{self, Read};
use std::path::Path;
use std::sync::Arc;

/// The largest file read. A GLB's length is a 32-bit field, and no buffer, image or `.gltf`
/// a viewer can load is larger; anything bigger is refused rather than read into memory.
pub const MAX_FILE_BYTES: u64 = u32::MAX as u64;

/// Why a file was not read.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FileError {
    /// A folder, FIFO, socket or device.
    #[error("not a regular file ({0})")]
    NotRegular(&'static str),
    /// Larger than [`MAX_FILE_BYTES`].
    #[error("too large ({0} bytes; at most {MAX_FILE_BYTES} are read)")]
    TooLarge(u64),
    /// Opening or reading failed.
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// Reads the regular file at `path` (a symlink is followed: the caller named it).
pub fn read_file(path: &Path) -> Result<Vec<u8>, FileError> {
    read_opened(open(path)?)
}

/// Opens the file at `path` for reading, without waiting on a FIFO (it is refused when read).
pub(crate) fn open(path: &Path) -> Result<File, FileError> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    non_blocking(&mut options);
    Ok(options.open(path)?)
}

/// Binary data from this size up is not read whole: a GLB's BIN chunk data, or an external
/// buffer file, stays in its file and each view is read as it is walked, so checking a
/// 160 MB asset does not hold 160 MB.
pub(crate) const LARGE_FILE_BYTES: u64 = 32 << 20;

/// A large GLB read but for its BIN chunk's data: the bytes before that data, where it lies
/// and the bytes after it (see [`LARGE_FILE_BYTES`]).
pub(crate) struct SplitGlb {
    pub before: Vec<u8>,
    pub bin: FileChunk,
    pub after: Vec<u8>,
}

/// Splits an opened regular file when it is a large GLB of a JSON chunk then a BIN chunk
/// that lies inside the file; `Ok(Err(file))` hands back any other file, to be read whole.
#[cfg(unix)]
pub(crate) fn split_large_glb(file: File) -> Result<Result<SplitGlb, File>, FileError> {
    use std::os::unix::fs::FileExt;
    let metadata = file.metadata()?;
    check_regular(&metadata)?;
    let length = metadata.len();
    let mut header = [0u8; 20];
    if length < LARGE_FILE_BYTES || file.read_exact_at(&mut header, 0).is_err() {
        return Ok(Err(file));
    }
    let word = |bytes: &[u8], at: usize| {
        u64::from(u32::from_le_bytes([0, 1, 2, 3].map(|i| bytes[at + i])))
    };
    const JSON: u64 = 0x4E4F_534A;
    const BIN: u64 = 0x004E_4942;
    let is_glb = &header[..4] == b"glTF" && word(&header, 4) == 2 && word(&header, 16) == JSON;
    let bin_header = 20 + word(&header, 12);
    if !is_glb || bin_header + 8 > length {
        return Ok(Err(file));
    }
    let mut before = vec![0u8; bin_header as usize + 8];
    file.read_exact_at(&mut before, 0)?;
    let data = bin_header + 8;
    let end = data + word(&before, bin_header as usize);
    if word(&before, bin_header as usize + 4) != BIN || end > length {
        return Ok(Err(file));
    }
    let mut after = vec![0u8; (length - end) as usize];
    file.read_exact_at(&mut after, end)?;
    let bin = FileChunk {
        file,
        offset: data,
        length: (end - data) as usize,
    };
    Ok(Ok(SplitGlb { before, bin, after }))
}

#[cfg(not(unix))]
pub(crate) fn split_large_glb(file: File) -> Result<Result<SplitGlb, File>, FileError> {
    Ok(Err(file))
}

/// A chunk's data left in its (opened, regular) file, read a range at a time. A range the
/// file no longer holds (it was truncated meanwhile) reads as nothing, never as a fault.
#[derive(Debug)]
pub struct FileChunk {
    file: File,
    offset: u64,
    length: usize,
}

/// An opened file's bytes: read whole, or, from [`LARGE_FILE_BYTES`] up, left in the file
/// (where positioned reads can read them), with the identity of the file.
pub(crate) fn read_or_keep(file: File) -> Result<(Kept, Option<FileId>), FileError> {
    let metadata = file.metadata()?;
    check_regular(&metadata)?;
    if cfg!(unix) && metadata.len() >= LARGE_FILE_BYTES {
        let chunk = FileChunk {
            file,
            offset: 0,
            length: metadata.len() as usize,
        };
        return Ok((Kept::File(Arc::new(chunk)), FileId::of(&metadata)));
    }
    let (bytes, id) = read_opened_with_id(file)?;
    Ok((Kept::Read(Arc::new(bytes.into())), id))
}

/// The bytes of an input file, or of a buffer, as gltfmat holds them, shared (every URI
/// naming the same file gets the same bytes): read whole into memory, left in the opened file
/// (a file from 32 MiB up, a large GLB's BIN chunk) and read a range at a time,
/// or in pieces (an upgrade's output, checked without being joined first).
#[derive(Debug, Clone)]
pub enum Kept {
    /// Read whole.
    Read(Arc<Bytes>),
    /// Left in the file.
    File(Arc<FileChunk>),
    /// In pieces.
    Pieces(Arc<Pieces>),
}

impl Kept {
    /// How many bytes there are.
    pub fn len(&self) -> usize {
        match self {
            Kept::Read(bytes) => bytes.len(),
            Kept::File(chunk) => chunk.len(),
            Kept::Pieces(pieces) => pieces.len(),
        }
    }

    /// Whether there is no byte.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The bytes at `range`: borrowed when they are in memory in one piece, read now when
    /// they are in a file; `None` when the range is outside them (or the file no longer
    /// holds it).
    pub fn get(&self, range: std::ops::Range<usize>) -> Option<Cow<'_, [u8]>> {
        match self {
            Kept::Read(bytes) => bytes.get(range).map(Cow::Borrowed),
            Kept::File(chunk) => chunk.read(range).map(Cow::Owned),
            Kept::Pieces(pieces) => pieces.get(range),
        }
    }

    /// All the bytes, when they are in memory in one piece.
    pub fn in_memory(&self) -> Option<&[u8]> {
        match self {
            Kept::Read(bytes) => Some(bytes),
            Kept::File(_) | Kept::Pieces(_) => None,
        }
    }
}

impl FileChunk {
    /// Where the chunk's data lies in its file (for its range in the GLB).
    pub fn offset(&self) -> u64 {
        self.offset
    }

    /// The chunk's length as its header declares it.
    pub fn len(&self) -> usize {
        self.length
    }

    /// Whether the chunk holds no byte.
    pub fn is_empty(&self) -> bool {
        self.length == 0
    }

    /// The bytes at `range` of the chunk, read now.
    pub fn read(&self, range: std::ops::Range<usize>) -> Option<Vec<u8>> {
        if range.end > self.length || range.start > range.end {
            return None;
        }
        let mut bytes = vec![0u8; range.len()];
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileExt;
            let at = self.offset.checked_add(range.start as u64)?;
            self.file.read_exact_at(&mut bytes, at).ok()?;
        }
        Some(bytes)
    }
}

/// Opening a FIFO for reading waits for a writer unless it is non-blocking; the handle is
/// then refused as not regular, so no read ever sees the flag.
#[cfg(unix)]
pub(crate) fn non_blocking(options: &mut impl NonBlocking) {
    options.set_non_blocking();
}

#[cfg(not(unix))]
pub(crate) fn non_blocking<T>(_: &mut T) {}

/// Open options that can open without blocking.
#[cfg(unix)]
pub(crate) trait NonBlocking {
    fn set_non_blocking(&mut self);
}

#[cfg(unix)]
impl NonBlocking for std::fs::OpenOptions {
    fn set_non_blocking(&mut self) {
        std::os::unix::fs::OpenOptionsExt::custom_flags(self, libc::O_NONBLOCK);
    }
}

#[cfg(unix)]
impl NonBlocking for cap_std::fs::OpenOptions {
    fn set_non_blocking(&mut self) {
        cap_std::fs::OpenOptionsExt::custom_flags(self, libc::O_NONBLOCK);
    }
}

/// Reads an opened file when it is a regular file of at most [`MAX_FILE_BYTES`]. A file
/// that grows while it is read is cut at that bound; one that shrinks is read as it now is.
pub(crate) fn read_opened(file: File) -> Result<Vec<u8>, FileError> {
    read_opened_with_id(file).map(|(bytes, _)| bytes)
}

/// [`read_opened`], also giving the identity of the file read.
pub(crate) fn read_opened_with_id(file: File) -> Result<(Vec<u8>, Option<FileId>), FileError> {
    let metadata = file.metadata()?;
    check_regular(&metadata)?;
    let length = metadata.len() as usize;
    let mut bytes = read_parts(&file, length)?;
    // Then the rest: all of a small file, or what a large one grew by meanwhile, to the
    // same bound as any stream.
    let read = bytes.len();
    let rest = read_bounded(
        &file,
        length.saturating_sub(read),
        MAX_FILE_BYTES - read as u64,
    )?;
    if bytes.is_empty() {
        bytes = rest;
    } else {
        bytes.extend_from_slice(&rest);
    }
    Ok((bytes, FileId::of(&metadata)))
}

/// From this size up a file is read in parts on all cores: filling fresh memory costs more
/// in page faults than in copying, and faults on several cores at once take their share of
/// the time each (the figures are in docs/performance.md).
const READ_IN_PARTS_FROM: usize = 16 << 20;

/// The first `length` bytes of the file, or as many as it still holds (it may have been
/// truncated meanwhile), read from its start in parts at once, with positioned reads; the
/// handle's position is left after them.
fn read_parts(file: &File, length: usize) -> io::Result<Vec<u8>> {
    use rayon::prelude::*;
    if length < READ_IN_PARTS_FROM || !cfg!(unix) {
        return Ok(Vec::new());
    }
    let mut bytes = vec![0u8; length];
    crate::system::advise_huge_pages(&mut bytes);
    let part = length.div_ceil(rayon::current_num_threads().max(1));
    let filled: Vec<usize> = (bytes.par_chunks_mut(part).enumerate())
        .map(|(i, place)| fill_at(file, place, (i * part) as u64))
        .collect::<io::Result<_>>()?;
    // A part read short ends what was read: the file is read as it now is.
    let whole = filled
        .iter()
        .position(|&n| n < part)
        .map_or(length, |i| i * part + filled[i]);
    bytes.truncate(whole.min(length));
    io::Seek::seek(&mut &*file, io::SeekFrom::Start(bytes.len() as u64))?;
    Ok(bytes)
}

/// Reads into `place` from `offset` until it is full or the file ends; how many bytes.
fn fill_at(file: &File, place: &mut [u8], offset: u64) -> io::Result<usize> {
    let mut filled = 0;
    while filled < place.len() {
        match read_at(file, &mut place[filled..], offset + filled as u64) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(filled)
}

#[cfg(unix)]
fn read_at(file: &File, place: &mut [u8], offset: u64) -> io::Result<usize> {
    std::os::unix::fs::FileExt::read_at(file, place, offset)
}

#[cfg(not(unix))]
fn read_at(_: &File, _: &mut [u8], _: u64) -> io::Result<usize> {
    Ok(0)
}

/// Reads a stream (stdin, a pipe) to its end, but never more than [`MAX_FILE_BYTES`], the
/// most a glTF asset can be: an endless stream is refused as too large, not read until
/// memory runs out.
pub fn read_stream(stream: impl Read) -> Result<Vec<u8>, FileError> {
    read_bounded(stream, 0, MAX_FILE_BYTES)
}

fn read_bounded(stream: impl Read, expected: usize, most: u64) -> Result<Vec<u8>, FileError> {
    let mut bytes = Vec::with_capacity(expected);
    stream.take(most + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > most {
        return Err(FileError::TooLarge(bytes.len() as u64));
    }
    Ok(bytes)
}

fn check_regular(metadata: &Metadata) -> Result<(), FileError> {
    if !metadata.is_file() {
        return Err(FileError::NotRegular(kind(&metadata.file_type())));
    }
    if metadata.len() > MAX_FILE_BYTES {
        return Err(FileError::TooLarge(metadata.len()));
    }
    Ok(())
}

/// Which file a handle or path reaches, whatever name or link led to it: two paths reach
/// the same file exactly when their identities are equal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FileId {
    device: u64,
    inode: u64,
}

impl FileId {
    /// The identity of the file `metadata` describes (None where the system gives none).
    pub fn of(metadata: &Metadata) -> Option<FileId> {
        #[cfg(unix)]
        {
            use std::os::unix::fs::MetadataExt;
            Some(FileId {
                device: metadata.dev(),
                inode: metadata.ino(),
            })
        }
        #[cfg(not(unix))]
        {
            let _ = metadata;
            None
        }
    }

    /// The identity of the file `path` leads to (following symlinks), if it exists.
    pub fn of_path(path: &Path) -> Option<FileId> {
        FileId::of(&std::fs::metadata(path).ok()?)
    }
}

/// What a file that is not regular is, in words.
pub(crate) fn kind(file_type: &FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO";
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return "a device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    if file_type.is_dir() {
        "a folder"
    } else if file_type.is_symlink() {
        "a symlink"
    } else {
        "not a file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_endless_stream_is_read_up_to_the_bound_and_refused() {
        assert_eq!(read_bounded(&b"abcd"[..], 0, 4).unwrap(), b"abcd");
        let endless = std::io::repeat(0);
        assert!(matches!(
            read_bounded(endless, 0, 1 << 20),
            Err(FileError::TooLarge(n)) if n == (1 << 20) + 1
        ));
    }

    #[test]
    fn regular_files_are_read_whole() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("a.bin");
        std::fs::write(&path, b"abc").unwrap();
        assert_eq!(read_file(&path).unwrap(), b"abc");
    }

    #[test]
    fn large_files_are_read_in_parts_as_they_are_now() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("large.bin");
        let length = READ_IN_PARTS_FROM + 12_345;
        let content: Vec<u8> = (0..length).map(|i| (i * 7 + i / 4096) as u8).collect();
        std::fs::write(&path, &content).unwrap();
        assert_eq!(read_file(&path).unwrap(), content);
        // A file shorter than its length said (truncated meanwhile) is read as it is.
        let opened = File::open(&path).unwrap();
        assert_eq!(read_parts(&opened, length + (1 << 20)).unwrap(), content);
        let mut rest = Vec::new();
        io::Read::read_to_end(&mut &opened, &mut rest).unwrap();
        assert!(rest.is_empty(), "the handle is left after what was read");
    }

    #[test]
    fn folders_are_refused_as_not_regular() {
        let folder = tempfile::tempdir().unwrap();
        let refused = read_file(folder.path()).unwrap_err();
        assert_eq!(refused.to_string(), "not a regular file (a folder)");
    }

    #[cfg(unix)]
    #[test]
    fn devices_and_fifos_are_refused_without_reading_or_waiting() {
        let refused = read_file(Path::new("/dev/zero")).unwrap_err();
        assert_eq!(refused.to_string(), "not a regular file (a device)");
        let folder = tempfile::tempdir().unwrap();
        let fifo = folder.path().join("pipe.gltf");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|status| status.success()), "mkfifo {fifo:?}");
        let refused = read_file(&fifo).unwrap_err();
        assert_eq!(refused.to_string(), "not a regular file (a FIFO)");
    }
}
