//! GLB container reader (binary glTF, version 2).
//!
//! Every failure is a diagnostic with a byte offset; nothing is allocated from a declared
//! length: chunks are ranges into the input, and every sum is checked against the real size.
//! The offsets and the order of checks follow the Khronos validator so reports are comparable.

use crate::diagnostic::{khronos, Code, Diagnostic, Location, Sink};
use std::ops::Range;

const MAGIC: &[u8; 4] = b"glTF";
const HEADER_LEN: usize = 12;
const CHUNK_HEADER_LEN: usize = 8;
pub(super) const CHUNK_JSON: u32 = 0x4E4F_534A;
pub(super) const CHUNK_BIN: u32 = 0x004E_4942;

/// The UTF-8 byte order mark.
const BOM: [u8; 3] = [0xEF, 0xBB, 0xBF];

/// What a GLB holds: where its JSON and BIN chunks are, and what was wrong on the way.
#[derive(Debug, Default)]
pub(crate) struct GlbParts {
    pub version: u32,
    /// The JSON chunk's bytes (empty when the chunk was empty and more bytes followed it:
    /// the Khronos validator then parses an empty document, which is INVALID_JSON).
    pub json: Option<Range<usize>>,
    pub bin: Option<Range<usize>>,
    /// Whether the bytes end inside a chunk (its header or its data, or right after the
    /// header of an empty one): the Khronos validator then keeps what its JSON reader found
    /// but loads no resource and reads no data.
    pub cut_short: bool,
}

fn at(code: Code, offset: usize, message: impl Into<std::borrow::Cow<'static, str>>) -> Diagnostic {
    Diagnostic::new(code, Location::Offset(offset as u64), message)
}

fn read_u32(bytes: &(impl GlbBytes + ?Sized), pos: usize) -> u32 {
    u32::from_le_bytes([0, 1, 2, 3].map(|i| bytes.byte(pos + i)))
}

/// What the reader needs of a GLB's bytes: its length and the bytes of its headers. A GLB
/// whose BIN chunk was left in its file ([`Holed`]) is read as the whole file is.
pub(crate) trait GlbBytes {
    /// The length of the whole file.
    fn len(&self) -> usize;
    /// The byte at `pos` (< `len`), which the reader asks only of headers.
    fn byte(&self, pos: usize) -> u8;
}

impl GlbBytes for [u8] {
    fn len(&self) -> usize {
        <[u8]>::len(self)
    }

    fn byte(&self, pos: usize) -> u8 {
        self[pos]
    }
}

/// A GLB read but for one chunk's data (the BIN chunk of a large file, read only as its
/// views are walked): the bytes before it, those after it, and where it lies.
pub(crate) struct Holed<'b> {
    pub before: &'b [u8],
    pub hole: Range<usize>,
    pub after: &'b [u8],
}

impl GlbBytes for Holed<'_> {
    fn len(&self) -> usize {
        self.hole.end + self.after.len()
    }

    fn byte(&self, pos: usize) -> u8 {
        match pos.checked_sub(self.hole.end) {
            Some(in_after) => self.after.get(in_after).copied().unwrap_or(0),
            None => self.before.get(pos).copied().unwrap_or(0),
        }
    }
}

/// True when the bytes start like a GLB file (magic `glTF`).
pub(crate) fn looks_like_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// Reads the container; every problem goes to `diags`.
pub(crate) fn read(bytes: &(impl GlbBytes + ?Sized), diags: &mut dyn Sink) -> GlbParts {
    let mut parts = GlbParts::default();
    let Some(declared) = read_header(bytes, &mut parts, diags) else {
        return parts;
    };
    let mut pos = HEADER_LEN;
    let mut index = 0usize;
    let mut saw_empty_json = false;
    // Chunk by chunk as the Khronos validator streams them: the header's checks (length,
    // place, type, duplicates) all come before the data is found missing.
    while pos < bytes.len() {
        if pos == declared {
            diags.push(at(
                khronos::GLB_EXTRA_DATA,
                pos,
                "Extra data after the end of GLB stream.",
            ));
            return parts;
        }
        if bytes.len() - pos < CHUNK_HEADER_LEN {
            diags.push(at(
                khronos::GLB_UNEXPECTED_END_OF_CHUNK_HEADER,
                bytes.len(),
                "Unexpected end of chunk header.",
            ));
            parts.cut_short = true;
            return parts;
        }
        let chunk = Chunk {
            start: pos,
            length: read_u32(bytes, pos) as usize,
            kind: read_u32(bytes, pos + 4),
            index,
        };
        check_chunk_header(&chunk, declared, diags);
        // Saturating: on a 32-bit target a 4 GiB length would wrap.
        let data_start = pos + CHUNK_HEADER_LEN;
        let data_end = data_start.saturating_add(chunk.length);
        let complete = data_end <= bytes.len();
        chunk.take(
            bytes,
            data_start..data_end,
            &mut parts,
            &mut saw_empty_json,
            diags,
        );
        if !complete {
            diags.push(at(
                khronos::GLB_UNEXPECTED_END_OF_CHUNK_DATA,
                bytes.len(),
                "Unexpected end of chunk data.",
            ));
            parts.cut_short = true;
            return parts;
        }
        // An empty chunk that ends the bytes leaves the validator's reader waiting for its
        // (no) data: cut short, though nothing is said.
        if chunk.length == 0 && data_end == bytes.len() {
            parts.cut_short = true;
            return parts;
        }
        pos = data_end;
        index += 1;
    }
    if pos != declared {
        diags.push(at(
            khronos::GLB_LENGTH_MISMATCH,
            pos,
            format!("Declared length ({declared}) does not match GLB length ({pos})."),
        ));
    }
    parts
}

/// Reads the 12-byte header into `parts` (its version); the declared length, or `None` when
/// the header is cut short, not a GLB's or of another version, and nothing more is read.
fn read_header(
    bytes: &(impl GlbBytes + ?Sized),
    parts: &mut GlbParts,
    diags: &mut dyn Sink,
) -> Option<usize> {
    if bytes.len() < HEADER_LEN {
        diags.push(at(
            khronos::GLB_UNEXPECTED_END_OF_HEADER,
            bytes.len(),
            "Unexpected end of header.",
        ));
        return None;
    }
    if [0, 1, 2, 3].map(|i| bytes.byte(i)) != *MAGIC {
        diags.push(at(
            khronos::GLB_INVALID_MAGIC,
            0,
            "Invalid GLB magic value.",
        ));
        return None;
    }
    parts.version = read_u32(bytes, 4);
    if parts.version != 2 {
        let hint = if parts.version == 1 {
            " This is a glTF 1.0 binary (KHR_binary_glTF): run `gltfmat upgrade` to convert it."
        } else {
            ""
        };
        diags.push(at(
            khronos::GLB_INVALID_VERSION,
            4,
            format!("Invalid GLB version value {}.{hint}", parts.version),
        ));
        return None;
    }
    let declared = read_u32(bytes, 8) as usize;
    if declared <= HEADER_LEN {
        diags.push(at(
            khronos::GLB_LENGTH_TOO_SMALL,
            8,
            format!("Declared GLB length ({declared}) is too small."),
        ));
    }
    Some(declared)
}

/// A chunk header as read.
struct Chunk {
    start: usize,
    length: usize,
    kind: u32,
    /// Its place among the chunks, from 0.
    index: usize,
}

impl Chunk {
    /// Takes the chunk's data (at `data` in `bytes`, which may end before it) by its type.
    fn take(
        &self,
        bytes: &(impl GlbBytes + ?Sized),
        data: std::ops::Range<usize>,
        parts: &mut GlbParts,
        saw_empty_json: &mut bool,
        diags: &mut dyn Sink,
    ) {
        let complete = data.end <= bytes.len();
        let range = complete.then_some(data.clone());
        match self.kind {
            CHUNK_JSON => {
                let more_follows = data.end < bytes.len();
                // Cut short, the JSON is never whole, and the validator's streaming parser
                // says nothing of it but of a byte order mark, which it rejects at once: the
                // bytes held are then parsed, to be rejected the same way.
                let start = data.start;
                let bom =
                    (0..3).all(|i| start + i < bytes.len() && bytes.byte(start + i) == BOM[i]);
                let range = range.or(bom.then_some(start..bytes.len()));
                self.take_json(range, more_follows, parts, saw_empty_json, diags);
            }
            CHUNK_BIN => self.take_bin(range, parts, diags),
            _ => diags.push(at(
                khronos::GLB_UNKNOWN_CHUNK_TYPE,
                self.start,
                format!("Unknown GLB chunk type: 0x{:08x}.", self.kind),
            )),
        }
    }

    /// Takes a JSON chunk's data `range` (`None`: cut short) as the asset's JSON, unless
    /// one came before.
    fn take_json(
        &self,
        range: Option<Range<usize>>,
        more_follows: bool,
        parts: &mut GlbParts,
        saw_empty_json: &mut bool,
        diags: &mut dyn Sink,
    ) {
        if self.length == 0 {
            diags.push(at(
                khronos::GLB_EMPTY_CHUNK,
                self.start,
                "Chunk (JSON) cannot have zero length.",
            ));
        }
        if parts.json.is_some() || *saw_empty_json {
            self.duplicate("JSON", diags);
        } else if self.length == 0 {
            *saw_empty_json = true;
            // The validator feeds an empty chunk to its JSON parser (which then reports
            // INVALID_JSON) only when more bytes follow it.
            parts.json = more_follows.then_some(range).flatten();
        } else {
            parts.json = range;
        }
    }

    /// Takes a BIN chunk's data `range` (`None`: cut short) as the binary buffer, unless
    /// one came before.
    fn take_bin(&self, range: Option<Range<usize>>, parts: &mut GlbParts, diags: &mut dyn Sink) {
        if self.index > 1 && parts.bin.is_none() {
            diags.push(at(
                khronos::GLB_UNEXPECTED_BIN_CHUNK,
                self.start,
                "BIN chunk must be the second chunk.",
            ));
        }
        if self.length == 0 {
            diags.push(at(
                khronos::GLB_EMPTY_BIN_CHUNK,
                self.start,
                "Empty BIN chunk should be omitted.",
            ));
        }
        if parts.bin.is_some() {
            self.duplicate("BIN", diags);
        } else {
            parts.bin = range;
        }
    }

    fn duplicate(&self, name: &str, diags: &mut dyn Sink) {
        diags.push(at(
            khronos::GLB_DUPLICATE_CHUNK,
            self.start,
            format!("Chunk of type {name} has already been used."),
        ));
    }
}

/// The checks on a chunk header that do not depend on its type's state: alignment, fit in
/// the declared length, JSON first.
fn check_chunk_header(chunk: &Chunk, declared: usize, diags: &mut dyn Sink) {
    let (start, kind) = (chunk.start, chunk.kind);
    if !chunk.length.is_multiple_of(4) {
        diags.push(at(
            khronos::GLB_CHUNK_LENGTH_UNALIGNED,
            start,
            format!("Length of 0x{kind:08x} chunk is not aligned to 4-byte boundaries."),
        ));
    }
    if (start + CHUNK_HEADER_LEN).saturating_add(chunk.length) > declared {
        diags.push(at(
            khronos::GLB_CHUNK_TOO_BIG,
            start,
            format!(
                "Chunk (0x{kind:08x}) length ({}) does not fit total GLB length.",
                chunk.length
            ),
        ));
    }
    if chunk.index == 0 && kind != CHUNK_JSON {
        diags.push(at(
            khronos::GLB_UNEXPECTED_FIRST_CHUNK,
            start,
            format!("First chunk must be of JSON type. Found 0x{kind:08x} instead."),
        ));
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A GLB of `chunks` (type, data), its header declaring `declared` bytes or its length.
    pub(in crate::document) fn glb(chunks: &[(u32, &[u8])], declared: Option<u32>) -> Vec<u8> {
        let mut body = Vec::new();
        for (kind, data) in chunks {
            body.extend_from_slice(&(data.len() as u32).to_le_bytes());
            body.extend_from_slice(&kind.to_le_bytes());
            body.extend_from_slice(data);
        }
        let mut out = b"glTF".to_vec();
        out.extend_from_slice(&2u32.to_le_bytes());
        let len = declared.unwrap_or((12 + body.len()) as u32);
        out.extend_from_slice(&len.to_le_bytes());
        out.extend(body);
        out
    }

    fn codes(found: &[Diagnostic]) -> Vec<Code> {
        found.iter().map(|d| d.code).collect()
    }

    fn read(bytes: &[u8]) -> (GlbParts, Vec<Diagnostic>) {
        let mut found = Vec::new();
        (super::read(bytes, &mut found), found)
    }

    #[test]
    fn a_valid_glb_has_json_and_bin_ranges() {
        let bytes = glb(&[(CHUNK_JSON, b"{}  "), (CHUNK_BIN, &[1, 2, 3, 4])], None);
        let (parts, found) = read(&bytes);
        assert!(found.is_empty());
        assert_eq!(&bytes[parts.json.unwrap()], b"{}  ");
        assert_eq!(&bytes[parts.bin.unwrap()], &[1, 2, 3, 4]);
    }

    #[test]
    fn a_chunk_claiming_4_gib_is_reported_without_allocating() {
        let mut bytes = glb(&[(CHUNK_JSON, b"{}  ")], Some(u32::MAX));
        bytes[12..16].copy_from_slice(&u32::MAX.to_le_bytes());
        let (_, found) = read(&bytes);
        assert_eq!(
            codes(&found),
            vec![
                khronos::GLB_CHUNK_LENGTH_UNALIGNED,
                khronos::GLB_CHUNK_TOO_BIG,
                khronos::GLB_UNEXPECTED_END_OF_CHUNK_DATA
            ]
        );
    }

    #[test]
    fn unknown_chunks_are_skipped_with_a_warning() {
        let bytes = glb(
            &[
                (CHUNK_JSON, b"{}  "),
                (0x1234, b"abcd"),
                (CHUNK_BIN, b"wxyz"),
            ],
            None,
        );
        let (parts, found) = read(&bytes);
        assert_eq!(
            codes(&found),
            vec![
                khronos::GLB_UNKNOWN_CHUNK_TYPE,
                khronos::GLB_UNEXPECTED_BIN_CHUNK
            ]
        );
        assert!(parts.bin.is_some());
    }

    #[test]
    fn a_truncated_chunk_is_judged_by_its_header_before_its_missing_data() {
        // An empty JSON chunk, then JSON text read as a chunk header: length '{\r\n ',
        // type '  "a', and the file ends. The type and the empty document are reported too.
        let mut bytes = glb(&[(CHUNK_JSON, b"")], Some(32));
        bytes.extend_from_slice(b"{\r\n   \"accessors\"");
        bytes.truncate(32);
        let (parts, found) = read(&bytes);
        assert_eq!(
            codes(&found),
            vec![
                khronos::GLB_EMPTY_CHUNK,
                khronos::GLB_CHUNK_LENGTH_UNALIGNED,
                khronos::GLB_CHUNK_TOO_BIG,
                khronos::GLB_UNKNOWN_CHUNK_TYPE,
                khronos::GLB_UNEXPECTED_END_OF_CHUNK_DATA
            ]
        );
        assert_eq!(
            parts.json,
            Some(20..20),
            "the empty JSON chunk is parsed, at its place"
        );
        assert_eq!(found[4].location, Location::Offset(32));
    }

    #[test]
    fn a_truncated_second_json_chunk_is_still_a_duplicate() {
        let mut bytes = glb(&[(CHUNK_JSON, b"{}  "), (CHUNK_JSON, b"{}  ")], None);
        bytes.truncate(bytes.len() - 2);
        let (parts, found) = read(&bytes);
        assert_eq!(
            codes(&found),
            vec![
                khronos::GLB_DUPLICATE_CHUNK,
                khronos::GLB_UNEXPECTED_END_OF_CHUNK_DATA
            ]
        );
        assert!(parts.json.is_some());
    }

    #[test]
    fn version_1_points_to_upgrade() {
        let mut bytes = glb(&[(CHUNK_JSON, b"{}  ")], None);
        bytes[4] = 1;
        let (_, found) = read(&bytes);
        assert_eq!(codes(&found), vec![khronos::GLB_INVALID_VERSION]);
        assert!(found[0].message.contains("gltfmat upgrade"));
    }
}
