//! Bytes → document: container detection, GLB chunks, JSON, and external resources.

pub(crate) mod bytes;
pub(crate) mod file;
pub(crate) mod glb;
pub(crate) mod image_decode;
pub(crate) mod image_header;
pub(crate) mod json;
pub(crate) mod tree;
pub(crate) mod uri;

use crate::diagnostic::{khronos, Diagnostic, Location, Severity, Sink};
pub(crate) use bytes::{Bytes, Piece, Pieces};
use file::Kept;
use std::borrow::Cow;
use std::ops::Range;
use std::sync::Arc;
pub(crate) use tree::{Array, Node, Object, StringId, Tree};

/// How the asset is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Container {
    /// JSON text (`.gltf`).
    Gltf,
    /// Binary container (`.glb`).
    Glb,
}

impl Container {
    /// The media type of the container.
    pub(crate) fn mime_type(self) -> &'static str {
        match self {
            Container::Gltf => "model/gltf+json",
            Container::Glb => "model/gltf-binary",
        }
    }
}

/// A parsed asset. The bytes are kept so that diagnostics can be located and BIN data read
/// without copies.
#[derive(Debug)]
pub(crate) struct Document<R = Tree> {
    /// The whole file (shared: a check of an upgrade's output reads the bytes being
    /// written, without a copy).
    pub bytes: Arc<Bytes>,
    /// How it is stored.
    pub container: Container,
    /// Where the JSON text lies in `bytes`.
    pub json_range: Range<usize>,
    /// `None` when the JSON could not be parsed (the reason went to the reader's sink).
    pub root: Option<R>,
    /// Where the GLB BIN chunk's data lies in `bytes`, if there is one.
    pub bin: Option<Range<usize>>,
    /// The GLB BIN chunk's data when it is not in `bytes`, which then holds what comes
    /// before it: left in the file (a large GLB read by [`read_path`]), or in pieces (an
    /// upgrade's output, see [`read_glb_pieces`]).
    pub bin_elsewhere: Option<Kept>,
    /// A GLB whose bytes end inside a chunk (see [`glb::GlbParts::cut_short`]).
    pub cut_short: bool,
}

/// A buffer's bytes: borrowed from the document (a GLB's BIN chunk in memory, or left in its
/// file or in pieces), or as a loader gave them (an external file or a data URI).
pub(crate) enum BufferData<'a> {
    /// The GLB BIN chunk, in memory with the document.
    Glb(&'a [u8]),
    /// The GLB BIN chunk, held apart from the document's bytes.
    Bin(&'a Kept),
    /// An external file or a data URI (shared by every buffer naming the file).
    Loaded(Kept),
}

impl BufferData<'_> {
    fn kept(&self) -> Result<&Kept, &[u8]> {
        match self {
            BufferData::Glb(bytes) => Err(bytes),
            BufferData::Bin(kept) => Ok(kept),
            BufferData::Loaded(kept) => Ok(kept),
        }
    }

    /// How many bytes the buffer holds.
    pub(crate) fn len(&self) -> usize {
        self.kept().map_or_else(<[u8]>::len, Kept::len)
    }

    /// The bytes at `range` (see [`Kept::get`]).
    pub(crate) fn get(&self, range: Range<usize>) -> Option<Cow<'_, [u8]>> {
        match self.kept() {
            Ok(kept) => kept.get(range),
            Err(bytes) => bytes.get(range).map(Cow::Borrowed),
        }
    }

    /// The whole buffer when it is in memory in one piece.
    pub(crate) fn in_memory(&self) -> Option<&[u8]> {
        match self.kept() {
            Ok(kept) => kept.in_memory(),
            Err(bytes) => Some(bytes),
        }
    }
}

impl<R> Document<R> {
    /// The JSON text.
    pub(crate) fn json_text(&self) -> &[u8] {
        // Empty when the bytes were handed back to their owner (see `upgrade::output::verify`).
        self.bytes.get(self.json_range.clone()).unwrap_or_default()
    }

    /// The GLB BIN chunk's data, when it is in memory.
    pub(crate) fn bin(&self) -> Option<&[u8]> {
        self.bin.clone().and_then(|r| self.bytes.get(r))
    }

    /// The GLB BIN chunk's data, in memory or still in the file.
    pub(crate) fn bin_data(&self) -> Option<BufferData<'_>> {
        match &self.bin_elsewhere {
            Some(kept) => Some(BufferData::Bin(kept)),
            None => self.bin().map(BufferData::Glb),
        }
    }
}

impl Document<Tree> {
    /// Major version declared by `asset.version`, if readable. 1.0 exporters also wrote it as
    /// a number (`"version": 1`), and 1.0 objects are keyed by id, which gives them away when
    /// the version is missing.
    pub(crate) fn major_version(&self) -> Option<u64> {
        let root = self.root.as_ref()?.root();
        match root.get("asset").and_then(|a| a.get("version")) {
            Some(v) if v.is_string() => v.as_str()?.split('.').next()?.parse().ok(),
            Some(v) => v.as_f64().map(|v| v as u64),
            None => root.get("scenes").is_some_and(Node::is_object).then_some(1),
        }
    }
}

/// Reads a `.gltf` or `.glb` from its bytes. The container is recognised by its magic, or by
/// the name's `.glb` ending (so a broken GLB is reported as one, not as invalid JSON).
/// Problems with the container and the JSON go to `diagnostics`.
pub(crate) fn read(bytes: impl Into<Bytes>, name: &str, diagnostics: &mut dyn Sink) -> Document {
    read_shared(Arc::new(bytes.into()), name, diagnostics)
}

/// [`read`] of bytes shared with their owner (an upgrade's output, checked as it is
/// written).
pub(crate) fn read_shared(bytes: Arc<Bytes>, name: &str, diagnostics: &mut dyn Sink) -> Document {
    read_with(bytes, name, diagnostics, json::parse)
}

/// Why a document read without reporting (a comparison's, an upgrade's) has no JSON tree:
/// the first error its reading found, with where it lies (`check` lists every finding).
pub(crate) fn why_unreadable(diagnostics: &[Diagnostic]) -> String {
    let first = diagnostics.iter().find(|d| d.severity == Severity::Error);
    match first {
        // A syntax error's message gives its line and column; its pointer is the root.
        Some(d) if d.location == Location::Pointer(String::new()) => {
            format!("{} ({})", d.message, d.code.name())
        }
        Some(d) => format!("{} ({} at {})", d.message, d.code.name(), d.location),
        None => "its JSON root is not an object".into(),
    }
}

fn read_with<R>(
    bytes: Arc<Bytes>,
    name: &str,
    diagnostics: &mut dyn Sink,
    parse: fn(&[u8]) -> Result<R, json::SyntaxError>,
) -> Document<R> {
    let named_glb = name.to_ascii_lowercase().ends_with(".glb");
    let (container, json_range, bin, cut_short) = if glb::looks_like_glb(&bytes) || named_glb {
        let parts = glb::read(&bytes[..], diagnostics);
        (Container::Glb, parts.json, parts.bin, parts.cut_short)
    } else {
        (Container::Gltf, Some(0..bytes.len()), None, false)
    };
    let root = match &json_range {
        Some(range) => parse_json(&bytes[range.clone()], diagnostics, parse),
        None => None,
    };
    Document {
        json_range: json_range.unwrap_or(0..0),
        bytes,
        container,
        root,
        bin,
        bin_elsewhere: None,
        cut_short,
    }
}

/// Reads the asset at `path` as [`read`] reads its bytes, except that a large GLB's BIN
/// chunk data is left in the file (see [`file::LARGE_FILE_BYTES`]): its views are read as
/// they are walked. Fails only when the file cannot be opened or read.
pub(crate) fn read_path(
    path: &std::path::Path,
    diagnostics: &mut dyn Sink,
) -> Result<Document, file::FileError> {
    let name = path.display().to_string();
    let split = match file::split_large_glb(file::open(path)?)? {
        Ok(split) => split,
        Err(opened) => return Ok(read(file::read_opened(opened)?, &name, diagnostics)),
    };
    let start = split.bin.offset() as usize;
    let chunk = Kept::File(Arc::new(split.bin));
    Ok(read_holed(
        Arc::new(split.before.into()),
        start,
        chunk,
        &split.after,
        diagnostics,
    ))
}

/// Reads a GLB whose BIN chunk's data is in `pieces`, `head` being everything before it (up
/// to and with the BIN chunk's header): an upgrade's output is checked as it is written,
/// without joining its geometry and images into one copy first.
pub(crate) fn read_glb_pieces(
    head: Arc<Bytes>,
    pieces: Pieces,
    diagnostics: &mut dyn Sink,
) -> Document {
    let start = head.len();
    read_holed(
        head,
        start,
        Kept::Pieces(Arc::new(pieces)),
        &[],
        diagnostics,
    )
}

/// A GLB of the bytes `before`, then (from `start`) the BIN chunk's data `elsewhere`, then
/// `after`, read as if it were all in one piece.
fn read_holed(
    before: Arc<Bytes>,
    start: usize,
    elsewhere: Kept,
    after: &[u8],
    diagnostics: &mut dyn Sink,
) -> Document {
    let hole = start..start + elsewhere.len();
    let holed = glb::Holed {
        before: &before,
        hole: hole.clone(),
        after,
    };
    let parts = glb::read(&holed, diagnostics);
    let json_range = parts.json.filter(|r| r.end <= before.len());
    let root =
        (json_range.clone()).and_then(|range| parse_json(&before[range], diagnostics, json::parse));
    Document {
        json_range: json_range.unwrap_or(0..0),
        bytes: before,
        container: Container::Glb,
        root,
        bin: None,
        bin_elsewhere: (parts.bin == Some(hole)).then_some(elsewhere),
        cut_short: parts.cut_short,
    }
}

fn parse_json<R>(
    text: &[u8],
    diagnostics: &mut dyn Sink,
    parse: fn(&[u8]) -> Result<R, json::SyntaxError>,
) -> Option<R> {
    match parse(text) {
        Ok(value) => Some(value),
        Err(error) => {
            let (line, col) = json::LineIndex::new(text).line_col(error.offset);
            let mut d = Diagnostic::at(
                khronos::INVALID_JSON,
                "",
                format!(
                    "Invalid JSON data. Parser output: {} (line {line}, column {col})",
                    error.message
                ),
            );
            d.span_hint = Some(error.offset);
            diagnostics.push(d);
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A GLB whose BIN chunk is past [`file::LARGE_FILE_BYTES`] (zeros).
    fn large_glb(folder: &std::path::Path) -> std::path::PathBuf {
        let length = file::LARGE_FILE_BYTES as usize + (1 << 20);
        let mut json =
            format!(r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{length}}}]}}"#);
        while json.len() % 4 != 0 {
            json.push(' ');
        }
        let chunks = [
            (glb::CHUNK_JSON, json.as_bytes()),
            (glb::CHUNK_BIN, &vec![0; length][..]),
        ];
        let glb = glb::tests::glb(&chunks, None);
        let path = folder.join("large.glb");
        std::fs::write(&path, glb).unwrap();
        path
    }

    #[test]
    fn a_large_glbs_bin_chunk_is_left_in_its_file_and_read_in_parts() {
        let folder = tempfile::tempdir().unwrap();
        let path = large_glb(folder.path());
        let mut findings = Vec::new();
        let document = read_path(&path, &mut findings).unwrap();
        assert!(findings.is_empty(), "{findings:?}");
        assert!(matches!(document.bin_elsewhere, Some(Kept::File(_))));
        assert!(
            document.bytes.len() < 1 << 20,
            "{} bytes held",
            document.bytes.len()
        );
        assert_eq!(
            document.bin_data().unwrap().get(0..12).map(|b| b.len()),
            Some(12)
        );
    }

    #[test]
    fn a_large_glb_truncated_after_it_was_opened_reads_as_nothing_not_a_fault() {
        let folder = tempfile::tempdir().unwrap();
        let path = large_glb(folder.path());
        let document = read_path(&path, &mut Vec::new()).unwrap();
        let bin = document.bin_data().unwrap();
        assert_eq!(bin.get(0..12).map(|b| b.len()), Some(12));
        let file = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        file.set_len(100).unwrap();
        assert!(bin.get(0..12).is_none());
    }
}
