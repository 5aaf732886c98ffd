//! Placing an upgraded asset into files (`.glb` with everything embedded, or `.gltf` with
//! `.bin` and images beside it), checking those exact bytes, and writing them atomically.

use super::Json;
use super::Upgraded;
use crate::check::{check_glb_pieces, check_shared_bytes, CheckOptions, Report};
use crate::document::file::{FileId, Kept};
use crate::document::uri::{LoadError, ResourceLoader};
use crate::document::{Bytes, Piece, Pieces};
use serde_json::json;
use std::path::Path;
use std::sync::Arc;

use crate::output::Temporary;
use crate::output::{may_write, WriteError};

/// One output file: its name (relative to the output folder) and its bytes, a head in one
/// piece and then data in shared pieces, written one after the other. The geometry and
/// images are shared with the upgrade, so laying out a large asset copies none of them,
/// and neither does checking it.
#[derive(Debug, Clone)]
pub struct File {
    /// The file name, without a folder.
    pub name: String,
    /// What comes first: a GLB's header, JSON chunk and BIN chunk header; a `.gltf`'s text.
    /// Shared with the check of the output, which reads it while it is written.
    pub head: Arc<Bytes>,
    /// Then the data: a GLB's BIN chunk data, a `.bin`'s runs, an image.
    pub data: Pieces,
}

impl File {
    fn text(name: String, text: impl Into<Bytes>) -> Self {
        File {
            name,
            head: Arc::new(text.into()),
            data: Pieces::default(),
        }
    }

    fn data(name: String, data: Pieces) -> Self {
        File {
            name,
            head: Arc::default(),
            data,
        }
    }

    /// The file's bytes, piece by piece, in order.
    pub fn slices(&self) -> impl Iterator<Item = &[u8]> {
        std::iter::once(&self.head[..]).chain(self.data.slices())
    }

    /// Writes the file's bytes to `out`, piece by piece.
    pub fn write_to(&self, out: &mut impl std::io::Write) -> std::io::Result<()> {
        crate::output::write_parts(out, self.slices())
    }

    /// The file's bytes in one piece (a copy).
    pub fn bytes(&self) -> Vec<u8> {
        self.slices().collect::<Vec<_>>().concat()
    }
}

/// The files of an output asset: the main one, and those its URIs name.
#[derive(Debug, Clone)]
pub struct Files {
    /// The file the user named.
    pub main: File,
    /// The files it refers to (`.bin`, images).
    pub side: Vec<File>,
}

/// Lays the asset out as files named after `main_name` (`x.glb`, or `x.gltf` + `x.bin` +
/// `x-<n>-<image>.png`).
pub fn layout(upgraded: &Upgraded, main_name: &str) -> Files {
    layout_with(upgraded.json.clone(), upgraded, main_name)
}

/// Lays the asset out as [`layout`] does, then lets go of its JSON tree (`upgraded.json` is
/// left `null`): the files hold it as text, and checking them parses a tree of its own. At
/// 10^5 materials that is the difference between two trees in memory and one.
pub fn layout_releasing_json(upgraded: &mut Upgraded, main_name: &str) -> Files {
    // Its owned tail becomes a piece the files share, rather than one they copy.
    upgraded.binary.seal();
    let json = std::mem::take(&mut upgraded.json);
    layout_with(json, upgraded, main_name)
}

/// The files of `json` with the binary and images of `upgraded` (the text is made here;
/// the binary and the images are shared). The members the layout places (buffers,
/// bufferViews, images) are changed where they lie, never copied: an asset of 10^5
/// accessors has 10^5 bufferViews.
fn layout_with(mut root: Json, upgraded: &Upgraded, main_name: &str) -> Files {
    // A null where the layout places data says nothing: the layout writes its own.
    root.remove_nulls(&PLACED);
    if main_name.to_ascii_lowercase().ends_with(".glb") {
        Files {
            main: glb(root, upgraded, main_name),
            side: Vec::new(),
        }
    } else {
        separate(root, upgraded, main_name)
    }
}

/// The members of the asset's root the layout writes.
const PLACED: [&str; 3] = ["buffers", "bufferViews", "images"];

fn glb(mut json: Json, upgraded: &Upgraded, name: &str) -> File {
    // Images follow the geometry in the one binary chunk, each 4-byte aligned.
    let mut length = upgraded.binary.len();
    let mut body = upgraded.binary.pieces();
    for (i, image) in images_to_place(upgraded) {
        let aligned = length.div_ceil(4) * 4;
        body.push(Piece::whole(vec![0; aligned - length]));
        body.push(Piece::new(image.bytes.clone(), 0..image.bytes.len()));
        let view = json!({"buffer": 0, "byteOffset": aligned, "byteLength": image.bytes.len()});
        let index = json.items_mut("bufferViews").push(&view);
        length = aligned + image.bytes.len();
        if let Some(images) = json.items_mut_if_array("images") {
            images.update(i, |placed| {
                if placed.is_object() {
                    placed["bufferView"] = json!(index);
                    placed["mimeType"] = json!(image.mime_type);
                }
            });
        }
    }
    if length > 0 {
        set_buffer_length(&mut json, length);
    }
    // The JSON is written straight into the head, after the 20 bytes of headers it fills in.
    // Room for the headers, the text, its padding and the BIN chunk's header: growing a
    // 30 MB text doubles it.
    let mut head = Vec::with_capacity(20 + json.text_len() + 3 + 8);
    head.resize(20, 0);
    json.append_to(&mut head);
    drop(json);
    head.resize(head.len().div_ceil(4) * 4, b' ');
    let json_length = head.len() - 20;
    let padded = length.div_ceil(4) * 4;
    let chunks = 8 + json_length + if length == 0 { 0 } else { 8 + padded };
    head[..4].copy_from_slice(b"glTF");
    head[4..8].copy_from_slice(&2u32.to_le_bytes());
    head[8..12].copy_from_slice(&((12 + chunks) as u32).to_le_bytes());
    head[12..16].copy_from_slice(&(json_length as u32).to_le_bytes());
    head[16..20].copy_from_slice(b"JSON");
    if length == 0 {
        return File::text(name.to_string(), head);
    }
    head.extend((padded as u32).to_le_bytes());
    head.extend(b"BIN\0");
    body.push(Piece::whole(vec![0; padded - length]));
    File {
        name: name.to_string(),
        head: Arc::new(head.into()),
        data: Pieces::new(body),
    }
}

fn separate(mut json: Json, upgraded: &Upgraded, main_name: &str) -> Files {
    let stem = main_name
        .rsplit_once('.')
        .map_or(main_name, |(stem, _)| stem)
        .to_string();
    let mut side = Vec::new();
    if !upgraded.binary.is_empty() {
        let name = format!("{stem}.bin");
        if let Some(buffers) = json.items_mut_if_array("buffers") {
            buffers.update(0, |buffer| {
                if buffer.is_object() {
                    buffer["uri"] = json!(uri_escape(&name));
                }
            });
        }
        side.push(File::data(name, Pieces::new(upgraded.binary.pieces())));
    }
    for (i, image) in images_to_place(upgraded) {
        let name = format!("{stem}-{}", image.file_name);
        if let Some(images) = json.items_mut_if_array("images") {
            images.update(i, |placed| {
                if placed.is_object() {
                    placed["uri"] = json!(uri_escape(&name));
                }
            });
        }
        let piece = Piece::new(image.bytes.clone(), 0..image.bytes.len());
        side.push(File::data(name, Pieces::new([piece])));
    }
    // Indented for a person to read, unless there is more than a person reads: at 10^5
    // objects the indentation doubles the text, and the check that reads it.
    let mut text = if json.text_len() <= PRETTY_UP_TO {
        json.to_vec_pretty()
    } else {
        json.to_vec()
    };
    text.push(b'\n');
    Files {
        main: File::text(main_name.to_string(), text),
        side,
    }
}

/// The largest JSON (compact) a `.gltf` output is indented for reading.
const PRETTY_UP_TO: usize = 4 << 20;

/// The images that need a place in the output (those already in a bufferView have one,
/// and one that could not be read keeps the input's `uri`), with their indices.
fn images_to_place(upgraded: &Upgraded) -> impl Iterator<Item = (usize, &super::EncodedImage)> {
    (upgraded.images.iter().enumerate())
        .filter(|(_, image)| !image.in_binary && image.unread.is_none())
}

/// The one buffer's byteLength, keeping its other members (a 2.0 input's name, extras).
fn set_buffer_length(json: &mut Json, length: usize) {
    let first_is_object =
        (json.items("buffers").and_then(|b| b.get(0))).is_some_and(|b| b.is_object());
    if first_is_object {
        let buffers = json.items_mut("buffers");
        buffers.update(0, |buffer| buffer["byteLength"] = json!(length));
    } else {
        json.insert("buffers", &json!([{"byteLength": length}]));
    }
}

/// Percent-escapes what a relative URI reference cannot hold literally.
fn uri_escape(name: &str) -> String {
    name.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' => {
                (b as char).to_string()
            }
            other => format!("%{other:02X}"),
        })
        .collect()
}

/// gltfmat's own check of the files, in memory: the data of a GLB's BIN chunk and of a
/// `.bin` is read where it lies in the upgrade, never joined into one copy first.
pub fn verify(files: &Files) -> Report {
    let resources = SideFiles(&files.side);
    let main = &files.main;
    let options = CheckOptions::default();
    if main.data.is_empty() {
        return check_shared_bytes(&main.name, main.head.clone(), &resources, &options);
    }
    check_glb_pieces(
        &main.name,
        main.head.clone(),
        main.data.clone(),
        &resources,
        &options,
    )
}

/// The side files, as the check of the main one reads them.
struct SideFiles<'f>(&'f [File]);

impl SideFiles<'_> {
    fn find(&self, path: &str) -> Result<&File, LoadError> {
        (self.0.iter().find(|file| file.name == path))
            .ok_or_else(|| LoadError::NotFound(path.to_string()))
    }
}

impl ResourceLoader for SideFiles<'_> {
    fn load(&self, path: &str) -> Result<Arc<Bytes>, LoadError> {
        self.find(path).map(|file| Arc::new(file.bytes().into()))
    }

    fn load_buffer(&self, path: &str) -> Result<Kept, LoadError> {
        // Side files are data only (`File::data`): their pieces are the whole file.
        let file = self.find(path)?;
        Ok(Kept::Pieces(Arc::new(file.data.clone())))
    }
}

/// `Err(length)` when `main` is a GLB longer than its 32-bit length field can say: the
/// header would name another length, and writing gigabytes only for the check to refuse
/// them is not done.
fn fits_glb(main: &File) -> Result<(), u64> {
    let length = (main.head.len() + main.data.len()) as u64;
    let glb = main.head.starts_with(b"glTF");
    match glb && length > u64::from(u32::MAX) {
        true => Err(length),
        false => Ok(()),
    }
}

/// The asset as one GLB in memory named `name` (`x.glb`), laid out as
/// [`layout_releasing_json`] lays it out, and [`verify`]'s report of those bytes; `Err(length)`
/// when the GLB is longer than its 32-bit length field can say.
pub fn checked_glb(upgraded: &mut Upgraded, name: &str) -> Result<(File, Report), u64> {
    let files = layout_releasing_json(upgraded, name);
    fits_glb(&files.main)?;
    let report = verify(&files);
    Ok((files.main, report))
}

/// The errors an output may have and still be written: those of the input it was made
/// from, counted by code (a pass-through keeps them, and the user asked for the materials to
/// be converted, not the asset repaired). An output with an error of a code the input did not
/// have, or more of one, is refused.
#[derive(Debug, Default, Clone)]
pub struct Tolerated(std::collections::HashMap<&'static str, usize>);

impl Tolerated {
    /// No error at all.
    pub fn none() -> Tolerated {
        Tolerated::default()
    }

    /// The errors `input` (the report of the asset upgraded) has.
    pub fn errors_of(input: &Report) -> Tolerated {
        let mut counts = std::collections::HashMap::new();
        for d in input
            .diagnostics
            .iter()
            .filter(|d| d.severity == crate::Severity::Error)
        {
            *counts.entry(d.code.name()).or_default() += 1;
        }
        Tolerated(counts)
    }

    /// Whether `output` has no error beyond these.
    pub fn accepts(&self, output: &Report) -> bool {
        let mut counts: std::collections::HashMap<&str, usize> = Default::default();
        for d in output
            .diagnostics
            .iter()
            .filter(|d| d.severity == crate::Severity::Error)
        {
            *counts.entry(d.code.name()).or_default() += 1;
        }
        (counts.iter()).all(|(code, n)| self.0.get(code).is_some_and(|allowed| n <= allowed))
    }

    /// How many errors are tolerated.
    pub fn count(&self) -> usize {
        self.0.values().sum()
    }
}

/// The outcome of `write_checked`: the check of the files, and whether they were kept.
pub struct Checked {
    /// The check of the files as written.
    pub report: Report,
    /// False when the check found an error: then nothing was written.
    pub written: bool,
}

/// Writes every file into `folder` under a temporary name while the same bytes are checked
/// (the writing on a second thread: for a large asset both take about as long), and renames
/// them into place as one set, under a lock on the folder, only when the check finds no
/// error and every file was written; otherwise the temporaries are removed and nothing is
/// left behind. The bytes checked are the bytes written: both come from the one `files`.
/// Without `force` no existing file is replaced; with it, existing files are, except the
/// `protected` ones (see [`may_write`]). `tolerated` says which errors the caller accepts
/// (those a 2.0 input had already); with none tolerated any error refuses the output.
pub fn write_checked(
    files: &Files,
    folder: &Path,
    protected: &[FileId],
    force: bool,
    tolerated: &Tolerated,
) -> Result<Checked, WriteError> {
    let all: Vec<&File> = std::iter::once(&files.main).chain(&files.side).collect();
    for file in &all {
        may_write(&folder.join(&file.name), protected, force)?;
    }
    fits_glb(&files.main)
        .map_err(|bytes| WriteError::GlbTooLarge(folder.join(&files.main.name), bytes))?;
    crate::output::remove_stale(folder);
    let (written, report) = std::thread::scope(|scope| {
        let writer = scope.spawn(|| {
            let write = |file: &File| Temporary::write(folder, &file.name, file.slices());
            let side = files
                .side
                .iter()
                .map(write)
                .collect::<Result<Vec<_>, _>>()?;
            Ok((side, write(&files.main)?))
        });
        let report = verify(files);
        let written = writer.join().unwrap_or_else(|_| {
            let failed = std::io::Error::other("the thread writing the files failed");
            Err(WriteError::Io(folder.join(&files.main.name), failed))
        });
        (written, report)
    });
    let (side, main) = written?;
    if !tolerated.accepts(&report) {
        return Ok(Checked {
            report,
            written: false,
        });
    }
    // Side files first: the main file never names missing data.
    let temporaries: Vec<Temporary> = side.into_iter().chain(std::iter::once(main)).collect();
    crate::output::place_all(folder, temporaries, force)?;
    Ok(Checked {
        report,
        written: true,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A main file of `head` then `megabytes` pieces of one shared megabyte (held once).
    fn file(head: &[u8], megabytes: usize) -> Files {
        let megabyte = Arc::new(vec![0u8; 1 << 20].into());
        let pieces = (0..megabytes).map(|_| Piece::new(Arc::clone(&megabyte), 0..1 << 20));
        let main = File {
            name: "out.glb".into(),
            head: Arc::new(head.into()),
            data: Pieces::new(pieces),
        };
        Files {
            main,
            side: Vec::new(),
        }
    }

    #[test]
    fn a_glb_past_4_gib_is_refused_before_anything_is_written() {
        let folder = tempfile::tempdir().unwrap();
        let too_long = file(b"glTF", 4096);
        let refused = write_checked(&too_long, folder.path(), &[], false, &Tolerated::none()).err();
        let expected = 4 + (4096u64 << 20);
        assert!(
            matches!(refused, Some(WriteError::GlbTooLarge(_, n)) if n == expected),
            "{refused:?}"
        );
        assert_eq!(std::fs::read_dir(folder.path()).unwrap().count(), 0);
        assert_eq!(fits_glb(&file(b"glTF", 4095).main), Ok(()));
        assert_eq!(
            fits_glb(&file(b"{}", 4096).main),
            Ok(()),
            "a .gltf has no such field"
        );
    }
}
