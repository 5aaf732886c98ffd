//! URIs in glTF: data URIs decoded in memory, relative references read from the asset's own
//! folder only. Nothing is ever fetched from a network, and no path may leave the folder.

use super::file::FileChunk;
use super::file::{read_opened_with_id, FileError, FileId, Kept};
use super::{Bytes, Pieces};
use base64::Engine;
use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};
use std::sync::{Arc, Mutex, Weak};

/// What a `uri` string is.
#[derive(Debug, PartialEq)]
pub(crate) enum UriKind {
    /// `data:[<media type>][;base64],<data>`
    Data {
        /// The media type, `text/plain;charset=US-ASCII` when absent.
        media_type: String,
        /// The decoded data.
        bytes: Vec<u8>,
        /// Whether the base64's last character holds bits past the data (see
        /// [`has_stray_bits`]); they are dropped, as browsers drop them.
        stray_bits: bool,
    },
    /// A relative reference, `\` read as `/`, then percent-decoded.
    Relative(String),
    /// Has a scheme (http, https, file, …): never read.
    NonRelative,
    /// An absolute path (`/x`, `C:\x`, `\\server\x`): never read.
    AbsolutePath,
    /// A relative reference with a query or fragment (`x.bin?v=2`, `#f`): not a file name,
    /// never read (the Khronos validator calls it non-relative).
    QueryOrFragment,
    /// A relative reference whose percent escapes do not decode (`%zz`, or bytes that are
    /// no UTF-8) or decode to a NUL byte (`%00`): it names no file that can be read.
    Undecodable(String),
}

/// Classifies a URI; `Err` carries the parser's explanation for an invalid one.
pub(crate) fn classify(uri: &str) -> Result<UriKind, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        return parse_data(rest);
    }
    if let Some(colon) = uri.find(':') {
        let scheme = &uri[..colon];
        let before_path = !uri[..colon].contains(['/', '?', '#']);
        if before_path {
            if scheme.is_empty() {
                return Err("Invalid empty scheme".into());
            }
            if scheme.len() == 1 && scheme.chars().all(|c| c.is_ascii_alphabetic()) {
                return Ok(UriKind::AbsolutePath);
            }
            if !scheme.starts_with(|c: char| c.is_ascii_alphabetic())
                || !scheme
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
            {
                return Err(format!("Invalid scheme '{scheme}'"));
            }
            return Ok(UriKind::NonRelative);
        }
    }
    if uri.starts_with('/') || uri.starts_with('\\') {
        return Ok(UriKind::AbsolutePath);
    }
    if uri.contains(['?', '#']) {
        return Ok(UriKind::QueryOrFragment);
    }
    // A backslash separates folders, as browsers (the WHATWG URL parser) and the Khronos
    // validator read it: assets written on Windows name `Textures\a.png`. An escaped one
    // (`%5C`) stays a character of the name.
    Ok(match percent_decode(&uri.replace('\\', "/")) {
        // The operating system would refuse it, saying only "invalid argument".
        Ok(path) if path.contains('\0') => {
            UriKind::Undecodable("it decodes to a NUL byte (%00), which no file name holds".into())
        }
        Ok(path) => UriKind::Relative(path),
        Err(why) => UriKind::Undecodable(why),
    })
}

/// Standard base64 whose padding may be left out, as the Khronos validator (and browsers)
/// read data URIs; padding that is written must be right (see [`normalized_base64`]). Bits
/// past the data in the last character are dropped, as browsers drop them (the Khronos
/// validator refuses them: see [`has_stray_bits`]).
const BASE64: base64::engine::GeneralPurpose = base64::engine::GeneralPurpose::new(
    &base64::alphabet::STANDARD,
    base64::engine::GeneralPurposeConfig::new()
        .with_decode_padding_mode(base64::engine::DecodePaddingMode::Indifferent)
        .with_decode_allow_trailing_bits(true),
);

/// A data URI's media type and payload, and whether the payload is base64.
fn split_data(rest: &str) -> Result<(&str, &str, bool), String> {
    let Some((header, payload)) = rest.split_once(',') else {
        return Err("Expecting ','".into());
    };
    let mut params = header.split(';');
    let media_type = params.next().unwrap_or_default();
    let mut base64 = false;
    for param in params {
        if param == "base64" {
            base64 = true;
        } else if !param.contains('=') {
            return Err("Expecting '='".into());
        }
    }
    Ok((media_type, payload, base64))
}

fn parse_data(rest: &str) -> Result<UriKind, String> {
    let (media_type, payload, base64) = split_data(rest)?;
    let (bytes, stray_bits) = if base64 {
        let text = normalized_base64(payload)?;
        let bytes = (BASE64.decode(&*text)).map_err(|e| format!("Invalid base64: {e}"))?;
        (bytes, stray_bits(&text))
    } else {
        (percent_decode(payload)?.into_bytes(), false)
    };
    Ok(UriKind::Data {
        media_type: media_type.to_string(),
        bytes,
        stray_bits,
    })
}

/// Whether `uri` is a valid base64 data URI whose last character holds bits past the data
/// (`RUV=` for the two bytes `EE`, which `RUU=` writes). RFC 4648 lets a decoder refuse
/// them; browsers drop them; the Khronos validator stops reading the whole file there.
pub(crate) fn has_stray_bits(uri: &str) -> bool {
    let Some(Ok((_, payload, true))) = uri.strip_prefix("data:").map(split_data) else {
        return false;
    };
    normalized_base64(payload).is_ok_and(|text| stray_bits(&text))
}

/// Whether normalised base64 `text` ends in a character with bits past its data.
fn stray_bits(text: &str) -> bool {
    let data = text.trim_end_matches('=').as_bytes();
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    // Two characters carry a byte and four bits more; three carry two bytes and two bits.
    let unused = match data.len() % 4 {
        2 => 0b1111,
        3 => 0b11,
        _ => return false,
    };
    data.last().is_some_and(|&c| value(c) & unused != 0)
}

/// A data URI's base64 as the Khronos validator reads it (and a URI parser normalises it):
/// a character may be percent-escaped, the URL-safe `-` and `_` stand for `+` and `/`, and
/// padding, when written, is at most two `=` that end a multiple of four characters. The
/// payload itself when it needs no rewriting (a data URI may be hundreds of megabytes).
fn normalized_base64(payload: &str) -> Result<std::borrow::Cow<'_, str>, String> {
    let invalid = |at: usize| format!("Invalid base64 data (at character {})", at + 1);
    if !payload.contains(['%', '-', '_']) {
        check_base64_text(payload.as_bytes(), invalid)?;
        return Ok(payload.into());
    }
    let bytes = payload.as_bytes();
    let mut out = Vec::with_capacity(payload.len());
    let mut at = 0;
    while at < bytes.len() {
        let (byte, width) = match bytes[at] {
            b'%' => {
                let hex = payload.get(at + 1..at + 3).ok_or_else(|| invalid(at))?;
                (u8::from_str_radix(hex, 16).map_err(|_| invalid(at))?, 3)
            }
            byte => (byte, 1),
        };
        out.push(match byte {
            b'-' => b'+',
            b'_' => b'/',
            byte => byte,
        });
        at += width;
    }
    check_base64_text(&out, invalid)?;
    // Only ASCII letters, digits, `+`, `/` and `=` pass the check.
    Ok(String::from_utf8(out).map_err(|_| invalid(0))?.into())
}

/// Whether `text` is base64 whose padding, if any, is whole (see [`normalized_base64`]).
fn check_base64_text(text: &[u8], invalid: impl Fn(usize) -> String) -> Result<(), String> {
    let data = text.iter().position(|&b| b == b'=').unwrap_or(text.len());
    let alphabet = |b: &u8| b.is_ascii_alphanumeric() || matches!(b, b'+' | b'/');
    if let Some(at) = text[..data].iter().position(|b| !alphabet(b)) {
        return Err(invalid(at));
    }
    let padding = &text[data..];
    if padding.iter().any(|&b| b != b'=') {
        return Err("Invalid base64 padding, '=' not at the end".into());
    }
    if padding.len() > 2 {
        return Err("Invalid base64 padding, more than two '=' characters".into());
    }
    if !padding.is_empty() && !text.len().is_multiple_of(4) {
        return Err(format!(
            "Invalid base64 padding, padded length must be multiple of four, is {}",
            text.len()
        ));
    }
    Ok(())
}

fn percent_decode(text: &str) -> Result<String, String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = text.get(i + 1..i + 3).ok_or("Truncated percent escape")?;
            out.push(
                u8::from_str_radix(hex, 16)
                    .map_err(|_| format!("Invalid percent escape '%{hex}'"))?,
            );
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "Percent escapes do not form UTF-8".into())
}

/// Why an external resource could not be read.
#[derive(Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// No such file.
    #[error("{0}: no such file")]
    NotFound(String),
    /// The path resolves outside the asset's folder (`..`, or a symlink leading out).
    #[error("{0}: outside the asset's folder")]
    OutsideFolder(String),
    /// Reading is not possible for this input (e.g. stdin with no folder).
    #[error("external resources cannot be read for this input")]
    NoFolder,
    /// Larger than a resource may be (bytes).
    #[error("too large ({0} bytes)")]
    TooLarge(u64),
    /// No such file, but one whose name differs only in letter case (which a
    /// case-insensitive file system would have read).
    #[error("{uri}: no such file; {found} differs only in letter case")]
    CaseMismatch {
        /// The path the asset names.
        uri: String,
        /// The file that exists.
        found: String,
    },
    /// A folder, FIFO, socket or device: never read.
    #[error("{0}: not a regular file ({1})")]
    NotRegular(String, &'static str),
    /// Reading failed.
    #[error("{0}")]
    Io(String),
}

/// Where external files come from. The CLI confines reads to the asset's folder; library
/// users can plug in their own store.
///
/// The bytes are shared: a loader should give one file named by many URIs (10^4 buffers
/// or images of one asset may name the same file) as one copy, as [`FolderResources`] does.
pub trait ResourceLoader: Sync {
    /// Reads `relative_path` (already percent-decoded), relative to the asset.
    fn load(&self, relative_path: &str) -> Result<Arc<Bytes>, LoadError>;

    /// Reads a buffer's file as [`load`](Self::load) does, or leaves a large one in its
    /// opened file to be read a range at a time (from 32 MiB on).
    fn load_buffer(&self, relative_path: &str) -> Result<Kept, LoadError> {
        self.load(relative_path).map(Kept::Read)
    }

    /// Notes a file the asset names that this run may not read (a buffer when only the
    /// materials are wanted, a 1.0 shader): it is the asset's all the same, and an output
    /// must not replace it. A loader that keeps no such list ignores it.
    fn named(&self, _relative_path: &str) {}

    /// The files read under a name differing only in letter case from the one asked for
    /// (asked, read), for a loader that repairs such names (see
    /// [`FolderResources::repairing_letter_case`]); none for the others.
    fn letter_case_repairs(&self) -> Vec<(String, String)> {
        Vec::new()
    }
}

/// Notes every file the asset at `root` names (its buffers', images' and 1.0 shaders' URIs)
/// with `loader` (see [`ResourceLoader::named`]).
pub(crate) fn note_named_files(root: super::Node, loader: &dyn ResourceLoader) {
    let elements = |key| {
        let member = root.get(key);
        let listed = member
            .and_then(super::Node::as_array)
            .into_iter()
            .flat_map(|a| a.iter());
        let keyed = member
            .and_then(super::Node::as_object)
            .into_iter()
            .flat_map(|o| o.values());
        listed.chain(keyed)
    };
    let mut noted = std::collections::HashSet::new();
    for element in ["buffers", "images", "shaders"]
        .into_iter()
        .flat_map(elements)
    {
        // A data URI names no file (and is not decoded here only to be dropped).
        let is_data = |u: &str| u.get(..5).is_some_and(|s| s.eq_ignore_ascii_case("data:"));
        let uri = element.get("uri").and_then(super::Node::as_str);
        let file = uri.filter(|u| !is_data(u) && noted.insert(*u));
        if let Some(Ok(UriKind::Relative(path))) = file.map(classify) {
            loader.named(&path);
        }
    }
}

/// The bytes a `uri` names: a data URI's own, or a file read through `loader`. Non-relative
/// URIs are not fetched and absolute paths not read (both are errors saying so).
pub(crate) fn load_uri(uri: &str, loader: &dyn ResourceLoader) -> Result<Arc<Bytes>, String> {
    match classify(uri)? {
        UriKind::Data { bytes, .. } => Ok(Arc::new(bytes.into())),
        UriKind::Relative(path) => loader.load(&path).map_err(|e| e.to_string()),
        UriKind::NonRelative => Err(format!("'{uri}' is not a relative URI; not fetched")),
        UriKind::AbsolutePath => Err(format!("'{uri}' is an absolute path; not read")),
        UriKind::QueryOrFragment => Err(format!("'{uri}' has a query or fragment; not read")),
        UriKind::Undecodable(why) => Err(format!("'{uri}': {why}; not read")),
    }
}

/// No external resources (stdin, or in-memory checks).
pub struct NoResources;

impl ResourceLoader for NoResources {
    fn load(&self, _: &str) -> Result<Arc<Bytes>, LoadError> {
        Err(LoadError::NoFolder)
    }
}

/// Files held in memory by relative path (an upgrade's output, checked before it is written).
#[derive(Debug, Default)]
pub struct MemoryResources {
    /// Files by relative path.
    pub files: HashMap<String, Arc<Bytes>>,
}

impl ResourceLoader for MemoryResources {
    fn load(&self, relative: &str) -> Result<Arc<Bytes>, LoadError> {
        self.files
            .get(relative)
            .cloned()
            .ok_or_else(|| LoadError::NotFound(relative.to_string()))
    }
}

/// The folder external files of the asset at `path` are read from.
pub fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Reads files below one folder, refusing anything that resolves outside it. The folder is
/// opened once and every file is opened through that handle, resolved by the system
/// beneath it (cap-std): a `..` or a symlink that leads out cannot be followed, even when
/// it is swapped in while the asset is being read.
pub struct FolderResources {
    folder: Result<cap_std::fs::Dir, String>,
    /// The folder's absolute path as given (its links not followed, as a viewer resolves a
    /// URI against the asset's address), against which a URI that climbs out of the folder
    /// and names its way back in is read (see [`inside`]).
    address: Option<PathBuf>,
    /// Every file read so far, so that a writer can leave them alone.
    read: Mutex<Vec<FileId>>,
    /// What was made of each file still in use, by its identity and whether it was read
    /// whole: a file many URIs name (under any spelling or link) is read once, not once
    /// for each (10^3 buffers naming one 1 MB file held 1 GB).
    shared: Mutex<HashMap<(FileId, Whole), Held>>,
    /// Whether a name that finds no file reads the one file beside it that differs only in
    /// letter case, and the names so read (asked, read).
    letter_case: Option<Mutex<Vec<(String, String)>>>,
}

/// Whether a file was read whole ([`ResourceLoader::load`]) or as a buffer, perhaps left
/// in its file ([`ResourceLoader::load_buffer`]).
type Whole = bool;

/// A file's bytes as long as someone holds them.
enum Held {
    Read(Weak<Bytes>),
    File(Weak<FileChunk>),
    Pieces(Weak<Pieces>),
}

impl Held {
    fn of(kept: &Kept) -> Held {
        match kept {
            Kept::Read(bytes) => Held::Read(Arc::downgrade(bytes)),
            Kept::File(chunk) => Held::File(Arc::downgrade(chunk)),
            Kept::Pieces(pieces) => Held::Pieces(Arc::downgrade(pieces)),
        }
    }

    fn get(&self) -> Option<Kept> {
        match self {
            Held::Read(bytes) => bytes.upgrade().map(Kept::Read),
            Held::File(chunk) => chunk.upgrade().map(Kept::File),
            Held::Pieces(pieces) => pieces.upgrade().map(Kept::Pieces),
        }
    }
}

impl FolderResources {
    /// Resources of the asset at `asset`: the files of its folder.
    pub fn beside(asset: &Path) -> Self {
        Self::new(folder_of(asset))
    }

    /// Resources below `folder`.
    pub fn new(folder: impl AsRef<Path>) -> Self {
        let folder = folder.as_ref();
        FolderResources {
            folder: cap_std::fs::Dir::open_ambient_dir(folder, cap_std::ambient_authority())
                .map_err(|e| format!("{}: {e}", folder.display())),
            address: std::path::absolute(match folder.as_os_str().is_empty() {
                true => Path::new("."),
                false => folder,
            })
            .ok(),
            read: Default::default(),
            shared: Default::default(),
            letter_case: None,
        }
    }

    /// These resources, reading for a name that finds no file the one file beside it whose
    /// name differs only in letter case (as Windows and macOS read it), and keeping a list
    /// of such reads. For a conversion: an asset made on a case-insensitive system reads
    /// there as its author saw it. A check does not repair: the name is wrong where names
    /// are case-sensitive (a web server), and `check` says so.
    pub fn repairing_letter_case(mut self) -> Self {
        self.letter_case = Some(Mutex::default());
        self
    }

    /// The files read so far, and those the asset names that were not read (see
    /// [`ResourceLoader::named`]), by identity.
    pub fn files_read(&self) -> Vec<FileId> {
        self.read
            .lock()
            .map(|read| read.clone())
            .unwrap_or_default()
    }

    fn open(&self, uri_path: &str) -> Result<std::fs::File, LoadError> {
        let Some(relative) = inside(uri_path, self.address.as_deref()) else {
            return Err(LoadError::OutsideFolder(uri_path.to_string()));
        };
        let folder = self.folder.as_ref().map_err(|e| LoadError::Io(e.clone()))?;
        let mut options = cap_std::fs::OpenOptions::new();
        options.read(true);
        super::file::non_blocking(&mut options);
        match folder.open_with(&relative, &options) {
            Ok(file) => Ok(file.into_std()),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                let alike = differing_in_case(folder, &relative);
                // Only one such file is read for it: of two, neither is surely the one meant.
                if let ([found], Some(repairs)) = (&alike[..], &self.letter_case) {
                    let alike = relative.with_file_name(found);
                    if let Ok(file) = folder.open_with(&alike, &options) {
                        let read = alike.to_string_lossy().into_owned();
                        if let Ok(mut repairs) = repairs.lock() {
                            repairs.push((uri_path.to_string(), read));
                        }
                        return Ok(file.into_std());
                    }
                }
                Err(match alike.into_iter().next() {
                    Some(found) => LoadError::CaseMismatch {
                        uri: uri_path.to_string(),
                        found,
                    },
                    None => LoadError::NotFound(uri_path.to_string()),
                })
            }
            // cap-std refuses an escape with PermissionDenied and no OS error code; the
            // system's own EACCES carries one.
            Err(e)
                if e.kind() == std::io::ErrorKind::PermissionDenied
                    && e.raw_os_error().is_none() =>
            {
                Err(LoadError::OutsideFolder(uri_path.to_string()))
            }
            Err(e) => Err(LoadError::Io(e.to_string())),
        }
    }
}

/// The names of the files beside `relative`'s that differ from it only in letter case.
fn differing_in_case(folder: &cap_std::fs::Dir, path: &Path) -> Vec<String> {
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        return Vec::new();
    };
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty());
    let listing = match parent {
        Some(parent) => folder.read_dir(parent),
        None => folder.entries(),
    };
    (listing.into_iter().flatten().flatten())
        .filter_map(|entry| entry.file_name().into_string().ok())
        .filter(|candidate| candidate.eq_ignore_ascii_case(name))
        .collect()
}

/// A URI's path as a path below the folder at `address`: the path itself when it never
/// climbs above the folder, or, when it starts by climbing out and names its way back in
/// along the folder's own address (`../SubFolder/a.png` read from `SubFolder`, which is where
/// a viewer resolving the URI against the asset's address reads it), the rest after that
/// round trip. `None` when it leads out, or climbs out anywhere else. What is left is opened
/// through the folder's handle, so no spelling of a path can lead out of it.
fn inside(path: &str, address: Option<&Path>) -> Option<PathBuf> {
    let mut components = (Path::new(path).components())
        .filter(|c| *c != Component::CurDir)
        .peekable();
    let mut climbed = 0;
    while components.next_if_eq(&Component::ParentDir).is_some() {
        climbed += 1;
    }
    if climbed > 0 {
        let folder: Vec<Component> = address?.components().collect();
        let way_back = &folder[folder.len().checked_sub(climbed)?..];
        for step in way_back {
            let named = matches!(step, Component::Normal(_));
            if !named || components.next() != Some(*step) {
                return None;
            }
        }
    }
    let rest: PathBuf = components.collect();
    (!leaves_folder(&rest)).then_some(rest)
}

/// Whether a relative path names something outside its folder by its words alone (`..`
/// past the top, a root or a drive).
fn leaves_folder(relative: &Path) -> bool {
    let mut depth = 0i32;
    for component in relative.components() {
        match component {
            Component::ParentDir => depth -= 1,
            Component::Normal(_) => depth += 1,
            Component::CurDir => {}
            Component::RootDir | Component::Prefix(_) => return true,
        }
        if depth < 0 {
            return true;
        }
    }
    false
}

/// What reads an opened file: what it made of it and the file's identity.
type ReadOpened = fn(std::fs::File) -> Result<(Kept, Option<FileId>), FileError>;

impl FolderResources {
    /// Opens `relative` and gives what `read` makes of the handle (or what it made of the
    /// same file before, while that is in use), noting the file as read.
    fn read_with(&self, relative: &str, whole: Whole, read: ReadOpened) -> Result<Kept, LoadError> {
        let file = self.open(relative)?;
        let failed = |e| match e {
            FileError::NotRegular(kind) => LoadError::NotRegular(relative.to_string(), kind),
            FileError::TooLarge(size) => LoadError::TooLarge(size),
            other => LoadError::Io(other.to_string()),
        };
        let opened = file.metadata().ok().and_then(|m| FileId::of(&m));
        let earlier = opened.and_then(|id| {
            let shared = self.shared.lock().ok()?;
            shared.get(&(id, whole))?.get()
        });
        if let Some(kept) = earlier {
            return Ok(kept);
        }
        let (kept, id) = read(file).map_err(failed)?;
        if let Some(id) = id {
            if let Ok(mut shared) = self.shared.lock() {
                shared.insert((id, whole), Held::of(&kept));
            }
            if let Ok(mut read) = self.read.lock() {
                read.push(id);
            }
        }
        Ok(kept)
    }
}

/// [`read_opened_with_id`] as a [`Kept`].
fn read_whole(file: std::fs::File) -> Result<(Kept, Option<FileId>), FileError> {
    read_opened_with_id(file).map(|(bytes, id)| (Kept::Read(Arc::new(bytes.into())), id))
}

impl ResourceLoader for FolderResources {
    fn load(&self, relative: &str) -> Result<Arc<Bytes>, LoadError> {
        // A whole read (and what the cache holds of one) is never left in its file.
        match self.read_with(relative, true, read_whole)? {
            Kept::Read(bytes) => Ok(bytes),
            Kept::File(_) | Kept::Pieces(_) => {
                Err(LoadError::Io(format!("{relative}: not read whole")))
            }
        }
    }

    fn load_buffer(&self, relative: &str) -> Result<Kept, LoadError> {
        self.read_with(relative, false, super::file::read_or_keep)
    }

    fn letter_case_repairs(&self) -> Vec<(String, String)> {
        let repairs = self.letter_case.as_ref().and_then(|r| r.lock().ok());
        let mut repairs = repairs.map(|r| r.clone()).unwrap_or_default();
        repairs.sort();
        repairs.dedup();
        repairs
    }

    fn named(&self, relative: &str) {
        let opened = self
            .open(relative)
            .ok()
            .and_then(|file| file.metadata().ok());
        if let (Some(id), Ok(mut read)) = (opened.as_ref().and_then(FileId::of), self.read.lock()) {
            read.push(id);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_uris_decode() {
        assert_eq!(
            classify("data:application/octet-stream;base64,AAEC").unwrap(),
            UriKind::Data {
                media_type: "application/octet-stream".into(),
                bytes: vec![0, 1, 2],
                stray_bits: false,
            }
        );
        assert!(classify("data:application/octet-stream;;base64,AA==").is_err());
        assert!(classify("data:").is_err());
    }

    #[test]
    fn base64_is_read_with_escapes_url_safe_letters_and_only_whole_padding() {
        let bytes = |payload: &str| match classify(&format!("data:a/b;base64,{payload}")) {
            Ok(UriKind::Data { bytes, .. }) => Ok(bytes),
            Ok(other) => panic!("{other:?}"),
            Err(why) => Err(why),
        };
        assert_eq!(bytes("RQ==").unwrap(), b"E");
        assert_eq!(bytes("RQ").unwrap(), b"E");
        assert_eq!(bytes("RQ%3d%3D").unwrap(), b"E");
        assert_eq!(bytes("%52Q==").unwrap(), b"E");
        assert_eq!(bytes("-_8=").unwrap(), [0xfb, 0xff]);
        for wrong in [
            "RQ=", "R===", "RQ=x", "R%2", "R%zz==", "RQ==%20", "RQ== ", "@@@@",
        ] {
            assert!(bytes(wrong).is_err(), "{wrong}");
        }
    }

    #[test]
    fn bits_past_the_data_are_dropped_and_told() {
        let data = |payload: &str| format!("data:a/b;base64,{payload}");
        for (payload, decoded, stray) in [
            ("RUU=", &b"EE"[..], false),
            ("RUV=", b"EE", true),
            ("RU%56", b"EE", true),
            ("RQ==", b"E", false),
            ("Ra", b"E", true),
            ("RUVF", b"EEE", false),
        ] {
            let Ok(UriKind::Data {
                bytes, stray_bits, ..
            }) = classify(&data(payload))
            else {
                panic!("{payload}");
            };
            assert_eq!((&bytes[..], stray_bits), (decoded, stray), "{payload}");
            assert_eq!(has_stray_bits(&data(payload)), stray, "{payload}");
        }
        assert!(!has_stray_bits("data:a/b,Ra"));
        assert!(!has_stray_bits("data:a/b;base64,Ra="));
    }

    #[test]
    fn uris_are_classified() {
        assert_eq!(
            classify("http://example.com/a.bin").unwrap(),
            UriKind::NonRelative
        );
        assert_eq!(classify("/etc/passwd").unwrap(), UriKind::AbsolutePath);
        assert_eq!(classify("C:\\x.bin").unwrap(), UriKind::AbsolutePath);
        assert_eq!(
            classify("a%20b.bin").unwrap(),
            UriKind::Relative("a b.bin".into())
        );
        assert_eq!(
            classify("Textures\\a.png").unwrap(),
            UriKind::Relative("Textures/a.png".into()),
            "a backslash separates folders, as browsers read it"
        );
        assert_eq!(
            classify("Textures%5Ca.png").unwrap(),
            UriKind::Relative("Textures\\a.png".into()),
            "an escaped one is part of the name"
        );
        // Which the operating system refuses as an "invalid argument", naming nothing.
        assert!(matches!(
            classify("a%00b.bin").unwrap(),
            UriKind::Undecodable(why) if why.contains("NUL byte")
        ));
        assert!(classify(":").is_err());
    }

    /// A converter's loader reads, for a name that finds no file, the one file whose name
    /// differs only in letter case, and lists it; of two such files it reads neither, and a
    /// checker's loader reads none.
    #[test]
    fn a_name_in_another_letter_case_reads_its_one_file_only_when_repairing() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("tex")).unwrap();
        std::fs::write(dir.path().join("tex/Wood.png"), b"w").unwrap();
        if dir.path().join("tex/wood.PNG").exists() {
            return; // a case-insensitive file system finds the name itself
        }
        let repairing = FolderResources::new(dir.path()).repairing_letter_case();
        assert_eq!(&repairing.load("tex/wood.PNG").unwrap()[..], b"w");
        assert_eq!(
            repairing.letter_case_repairs(),
            [("tex/wood.PNG".to_string(), "tex/Wood.png".to_string())]
        );
        let checking = FolderResources::new(dir.path());
        assert!(matches!(
            checking.load("tex/wood.PNG"),
            Err(LoadError::CaseMismatch { .. })
        ));
        assert!(checking.letter_case_repairs().is_empty());
        std::fs::write(dir.path().join("tex/WOOD.png"), b"W").unwrap();
        let two = FolderResources::new(dir.path()).repairing_letter_case();
        assert!(matches!(
            two.load("tex/wood.PNG"),
            Err(LoadError::CaseMismatch { .. })
        ));
        assert!(two.letter_case_repairs().is_empty());
    }

    #[test]
    fn paths_cannot_leave_the_folder() {
        let dir = tempfile::tempdir().unwrap();
        let dir = dir.path();
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        std::fs::write(dir.join("sub/a.bin"), b"x").unwrap();
        std::fs::write(dir.join("b.bin"), b"outside").unwrap();
        let loader = FolderResources::new(dir.join("sub"));
        assert_eq!(&loader.load("a.bin").unwrap()[..], b"x");
        for out in [
            "../b.bin",
            "../other/a.bin",
            "../sub/../b.bin",
            "/etc/passwd",
        ] {
            let refused = loader.load(out);
            assert!(matches!(refused, Err(LoadError::OutsideFolder(_))), "{out}");
        }
        assert!(matches!(
            loader.load("missing.bin"),
            Err(LoadError::NotFound(_))
        ));
        // On a case-sensitive file system the near miss is named.
        if !dir.join("SUB/A.BIN").exists() {
            assert_eq!(
                loader.load("A.bin").unwrap_err().to_string(),
                "A.bin: no such file; a.bin differs only in letter case"
            );
        }
        #[cfg(unix)]
        {
            std::fs::write(dir.join("secret"), b"s").unwrap();
            let _ = std::os::unix::fs::symlink(dir.join("secret"), dir.join("sub/link"));
            assert!(matches!(
                loader.load("link"),
                Err(LoadError::OutsideFolder(_))
            ));
        }
    }

    /// A viewer resolves a URI against the asset's address: climbing out of the folder and
    /// naming one's way back in along its own path stays in it.
    #[test]
    fn a_path_that_climbs_out_and_names_its_way_back_in_is_read_from_the_folder() {
        let dir = tempfile::tempdir().unwrap();
        let top = dir.path().join("top");
        std::fs::create_dir_all(top.join("sub/textures")).unwrap();
        std::fs::write(top.join("sub/textures/a.png"), b"x").unwrap();
        let loader = FolderResources::new(top.join("sub"));
        for back in [
            "../sub/textures/a.png",
            "./../sub/./textures/a.png",
            "../../top/sub/textures/a.png",
            "../sub/textures/../textures/a.png",
        ] {
            assert_eq!(&loader.load(back).unwrap()[..], b"x", "{back}");
        }
        // The way back must be the folder's own: a sibling of another name is outside.
        std::fs::create_dir_all(top.join("other/textures")).unwrap();
        std::fs::write(top.join("other/textures/a.png"), b"y").unwrap();
        let refused = loader.load("../other/textures/a.png");
        assert!(matches!(refused, Err(LoadError::OutsideFolder(_))));
    }

    /// 10^3 buffers naming one file must not hold 10^3 copies of it.
    #[test]
    fn a_file_named_many_ways_is_read_once_while_its_bytes_are_held() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("sub")).unwrap();
        std::fs::write(dir.path().join("a.bin"), b"first").unwrap();
        let loader = FolderResources::new(dir.path());
        let first = loader.load("a.bin").unwrap();
        let mut names = vec!["./a.bin", "sub/../a.bin"];
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("a.bin", dir.path().join("link.bin")).unwrap();
            names.push("link.bin");
        }
        for name in names {
            assert!(Arc::ptr_eq(&first, &loader.load(name).unwrap()), "{name}");
        }
        // Read as a buffer it is shared among buffers, apart from the whole reads.
        let Kept::Read(buffer) = loader.load_buffer("a.bin").unwrap() else {
            panic!("a small file is read")
        };
        let Kept::Read(again) = loader.load_buffer("./a.bin").unwrap() else {
            panic!("a small file is read")
        };
        assert!(Arc::ptr_eq(&buffer, &again));
        // Once nobody holds them, the file is read anew: a later change is seen.
        drop((first, buffer, again));
        std::fs::write(dir.path().join("a.bin"), b"second").unwrap();
        assert_eq!(&loader.load("a.bin").unwrap()[..], b"second");
    }
}
