//! Reading files as a stranger may have laid them out. Only regular files are read: a FIFO
//! would block forever and a device never ends. What is read is decided by the opened
//! handle, never by a name looked at before opening, so a file swapped in between cannot be
//! read in its place. Reads are bounded by the largest file a glTF asset can use.

use super::bytes::{Bytes, Elsewhere};
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
pub fn read(path: &Path) -> Result<Vec<u8>, FileError> {
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
pub const LARGE_FILE_BYTES: u64 = 32 << 20;

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
        return Ok((
            Kept::Elsewhere(Arc::new(Elsewhere::File(chunk))),
            FileId::of(&metadata),
        ));
    }
    let (bytes, id) = read_opened_with_id(file)?;
    Ok((Kept::Read(Arc::new(bytes.into())), id))
}

/// A buffer's bytes as a loader gives them (a file from `LARGE_FILE_BYTES` up stays in it),
/// shared: every URI naming the same file gets the same bytes.
#[derive(Debug, Clone)]
pub enum Kept {
    /// Read whole.
    Read(Arc<Bytes>),
    /// Left in the file, or in pieces.
    Elsewhere(Arc<Elsewhere>),
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
pub fn read_opened(file: File) -> Result<Vec<u8>, FileError> {
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

/// An opened regular file's bytes, whole: from [`READ_IN_PARTS_FROM`] up mapped while
/// leased (on Linux, where a lease can be had), read otherwise (see
/// [`super::uri::FolderResources::leasing_large_files`]). Filling fresh memory is
/// most of a large read's cost (a 176 MB buffer: 55 to 270 ms here, mapped: 5 ms).
pub(crate) fn lease_or_read(file: File) -> Result<(Bytes, Option<FileId>), FileError> {
    #[cfg(target_os = "linux")]
    let file = {
        let metadata = file.metadata()?;
        check_regular(&metadata)?;
        if (READ_IN_PARTS_FROM as u64..=MAX_FILE_BYTES).contains(&metadata.len()) {
            match Leased::of(file) {
                Ok(leased) => return Ok((leased.into(), FileId::of(&metadata))),
                Err(file) => file,
            }
        } else {
            file
        }
    };
    read_opened_with_id(file).map(|(bytes, id)| (bytes.into(), id))
}

/// A regular file mapped into memory while this process holds a read lease on it. Mapping
/// a file is safe only while no other process shrinks it (reading a page past its end
/// ends the reader with SIGBUS) or rewrites it (bytes checked could differ from bytes
/// written). The lease is granted only when no process has the file open for writing,
/// and any process that then opens it for writing or truncates it must first break the
/// lease: it waits until the lease is let go, or for `/proc/sys/fs/lease-break-time`
/// (45 s by default), and the breaking shows here ([`Leased::unbroken`]).
#[cfg(target_os = "linux")]
pub struct Leased {
    map: memmap2::Mmap,
    /// Holds the lease: it ends when the file is closed.
    file: File,
}

#[cfg(target_os = "linux")]
impl Leased {
    /// The file mapped, or the file back when no lease can be had (another process has it
    /// open for writing, this process neither owns it nor may lease others' files, its
    /// file system has no leases) or mapping fails: the caller reads it instead.
    fn of(file: File) -> Result<Leased, File> {
        use std::os::fd::AsRawFd;
        let fd = file.as_raw_fd();
        // SAFETY: fcntl on a descriptor this function owns, with integer arguments only.
        let leased = unsafe { libc::fcntl(fd, libc::F_SETLEASE, libc::F_RDLCK) } == 0;
        // A lease names this process to be signalled when it is broken, and that signal
        // (SIGIO) would end it: nobody is named, and the breaking is read from the lease.
        // SAFETY: as above.
        if !leased || unsafe { libc::fcntl(fd, libc::F_SETOWN, 0) } != 0 {
            return Err(Self::let_go(file));
        }
        // The length is taken under the lease: before it, the file could still change.
        let Some(length) = file.metadata().ok().map(|m| m.len() as usize) else {
            return Err(Self::let_go(file));
        };
        // Not populated when mapped: its pages are mapped as the walks over it first read
        // them, on all cores (a 176 MB file took 13 ms to populate on one, 10 ms to fault
        // in on two; the upgrade's median fell from 173 to 166 ms over 61 runs).
        // SAFETY: while the lease holds, no process can shrink or rewrite the file; one that
        // breaks it waits lease-break-time first, and the break is reported before any
        // output is kept (`unbroken`).
        let map = unsafe { memmap2::MmapOptions::new().len(length).map(&file) };
        match map {
            Ok(map) => Ok(Leased { map, file }),
            Err(_) => Err(Self::let_go(file)),
        }
    }

    /// Whether the lease still holds: no process has opened the file for writing or
    /// truncated it since it was taken (a break in progress reads as no lease).
    pub fn unbroken(&self) -> bool {
        use std::os::fd::AsRawFd;
        // SAFETY: fcntl on the descriptor this value owns.
        unsafe { libc::fcntl(self.file.as_raw_fd(), libc::F_GETLEASE) == libc::F_RDLCK }
    }

    fn let_go(file: File) -> File {
        use std::os::fd::AsRawFd;
        // SAFETY: as in `of`; undoing a lease that was not taken does nothing.
        unsafe { libc::fcntl(file.as_raw_fd(), libc::F_SETLEASE, libc::F_UNLCK) };
        file
    }
}

#[cfg(target_os = "linux")]
impl std::ops::Deref for Leased {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        &self.map
    }
}

/// From this size up a file is read in parts on all cores: filling fresh memory costs more
/// in page faults than in copying, and faults on several cores at once take their share of
/// the time each (a 176 MB buffer: 130 ms read in one part, 70 ms in two).
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

/// Whether this system grants file leases at all (`/proc/sys/fs/leases-enable`).
#[cfg(all(test, target_os = "linux"))]
pub(crate) fn leases_enabled() -> bool {
    std::fs::read_to_string("/proc/sys/fs/leases-enable").is_ok_and(|v| v.trim() == "1")
}

/// Opens `path` for writing as another process would, but told not to wait for a lease:
/// refused while one holds, and the lease's break has begun.
#[cfg(all(test, target_os = "linux"))]
pub(crate) fn open_for_writing_without_waiting(path: &Path) -> io::Result<File> {
    let mut writer = std::fs::OpenOptions::new();
    writer.write(true);
    std::os::unix::fs::OpenOptionsExt::custom_flags(&mut writer, libc::O_NONBLOCK);
    writer.open(path)
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
        assert_eq!(read(&path).unwrap(), b"abc");
    }

    #[test]
    fn large_files_are_read_in_parts_as_they_are_now() {
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("large.bin");
        let length = READ_IN_PARTS_FROM + 12_345;
        let content: Vec<u8> = (0..length).map(|i| (i * 7 + i / 4096) as u8).collect();
        std::fs::write(&path, &content).unwrap();
        assert_eq!(read(&path).unwrap(), content);
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
        let refused = read(folder.path()).unwrap_err();
        assert_eq!(refused.to_string(), "not a regular file (a folder)");
    }

    #[cfg(unix)]
    #[test]
    fn devices_and_fifos_are_refused_without_reading_or_waiting() {
        let refused = read(Path::new("/dev/zero")).unwrap_err();
        assert_eq!(refused.to_string(), "not a regular file (a device)");
        let folder = tempfile::tempdir().unwrap();
        let fifo = folder.path().join("pipe.gltf");
        let name = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path; mkfifo only creates the node.
        assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
        let refused = read(&fifo).unwrap_err();
        assert_eq!(refused.to_string(), "not a regular file (a FIFO)");
    }

    #[cfg(target_os = "linux")]
    fn large_file(folder: &Path) -> (std::path::PathBuf, Vec<u8>) {
        let path = folder.join("large.bin");
        let content: Vec<u8> = (0..READ_IN_PARTS_FROM + 4321)
            .map(|i| (i * 13) as u8)
            .collect();
        std::fs::write(&path, &content).unwrap();
        (path, content)
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_large_file_nobody_writes_is_mapped_and_opening_it_for_writing_breaks_the_lease() {
        let folder = tempfile::tempdir().unwrap();
        let (path, content) = large_file(folder.path());
        let (bytes, id) = lease_or_read(File::open(&path).unwrap()).unwrap();
        assert_eq!(&bytes[..], &content[..]);
        assert_eq!(id, FileId::of_path(&path));
        if !leases_enabled() {
            eprintln!("LEASES DISABLED ON THIS SYSTEM: the file was read, not mapped");
            assert!(!bytes.is_leased());
            return;
        }
        assert!(
            bytes.is_leased(),
            "this process owns the file and nobody writes it"
        );
        assert!(bytes.still_as_read());
        // An opener for writing must break the lease first: without waiting it is told to
        // come back, and the break has begun (no signal reaches this process, which a
        // signal's default would end).
        let refused = open_for_writing_without_waiting(&path).unwrap_err();
        assert_eq!(refused.kind(), io::ErrorKind::WouldBlock, "{refused}");
        assert!(!bytes.still_as_read(), "the broken lease shows");
        drop(bytes);
        assert!(
            open_for_writing_without_waiting(&path).is_ok(),
            "the lease went with the bytes"
        );
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_large_file_open_for_writing_and_a_small_file_are_read_not_mapped() {
        let folder = tempfile::tempdir().unwrap();
        let (path, content) = large_file(folder.path());
        let writing = std::fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .unwrap();
        let (bytes, _) = lease_or_read(File::open(&path).unwrap()).unwrap();
        assert!(!bytes.is_leased());
        assert_eq!(&bytes[..], &content[..]);
        drop(writing);
        let small = folder.path().join("small.bin");
        std::fs::write(&small, &content[..1000]).unwrap();
        let (bytes, _) = lease_or_read(File::open(&small).unwrap()).unwrap();
        assert!(!bytes.is_leased());
        assert_eq!(&bytes[..], &content[..1000]);
    }
}
