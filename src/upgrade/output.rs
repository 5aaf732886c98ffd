//! Placing an upgraded asset into files (`.glb` with everything embedded, or `.gltf` with
//! `.bin` and images beside it), checking those exact bytes, and writing them atomically.

use super::Upgraded;
use crate::check::{check_bytes, CheckOptions, Report};
use crate::document::uri::MemoryResources;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// The files of an output asset: the main one first, named relative to its folder.
#[derive(Debug, Clone)]
pub struct Files {
    pub main: (String, Vec<u8>),
    pub side: Vec<(String, Vec<u8>)>,
}

/// Lays the asset out as files named after `main_name` (`x.glb`, or `x.gltf` + `x.bin` +
/// `x-<n>-<image>.png`).
pub fn layout(upgraded: &Upgraded, main_name: &str) -> Files {
    if main_name.to_ascii_lowercase().ends_with(".glb") {
        Files {
            main: (main_name.to_string(), glb(upgraded)),
            side: Vec::new(),
        }
    } else {
        separate(upgraded, main_name)
    }
}

fn glb(upgraded: &Upgraded) -> Vec<u8> {
    let mut json = upgraded.json.clone();
    // Images follow the geometry in the one binary chunk, each 4-byte aligned.
    let mut length = upgraded.binary.len();
    let mut views = json["bufferViews"].as_array().cloned().unwrap_or_default();
    for (i, image) in upgraded.images.iter().enumerate() {
        length = length.div_ceil(4) * 4;
        views.push(json!({"buffer": 0, "byteOffset": length, "byteLength": image.bytes.len()}));
        length += image.bytes.len();
        json["images"][i]["bufferView"] = json!(views.len() - 1);
        json["images"][i]["mimeType"] = json!(image.mime_type);
    }
    if !views.is_empty() {
        json["bufferViews"] = Value::Array(views);
    }
    if length > 0 {
        json["buffers"] = json!([{"byteLength": length}]);
    }
    let mut text = serde_json::to_vec(&json).unwrap_or_default();
    text.resize(text.len().div_ceil(4) * 4, b' ');
    let padded = length.div_ceil(4) * 4;
    let chunks = 8 + text.len() + if length == 0 { 0 } else { 8 + padded };
    let mut out = Vec::with_capacity(12 + chunks);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend(((12 + chunks) as u32).to_le_bytes());
    out.extend((text.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&text);
    if length > 0 {
        out.extend((padded as u32).to_le_bytes());
        out.extend(b"BIN\0");
        let start = out.len();
        out.extend(&upgraded.binary);
        for image in &upgraded.images {
            out.resize(start + (out.len() - start).div_ceil(4) * 4, 0);
            out.extend(&image.bytes);
        }
        out.resize(start + padded, 0);
    }
    out
}

fn separate(upgraded: &Upgraded, main_name: &str) -> Files {
    let stem = main_name
        .rsplit_once('.')
        .map_or(main_name, |(stem, _)| stem)
        .to_string();
    let mut json = upgraded.json.clone();
    let mut side = Vec::new();
    if !upgraded.binary.is_empty() {
        let name = format!("{stem}.bin");
        json["buffers"][0]["uri"] = json!(uri_escape(&name));
        side.push((name, upgraded.binary.clone()));
    }
    for (i, image) in upgraded.images.iter().enumerate() {
        let name = format!("{stem}-{}", image.file_name);
        json["images"][i]["uri"] = json!(uri_escape(&name));
        side.push((name, image.bytes.clone()));
    }
    let mut text = serde_json::to_vec_pretty(&json).unwrap_or_default();
    text.push(b'\n');
    Files {
        main: (main_name.to_string(), text),
        side,
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

/// gltfmat's own check of the exact bytes that would be written. The files are lent to the
/// checker and handed back, so a large asset is not copied for it; a report with errors keeps
/// its copy (the document's bytes) for printing.
pub fn verify(mut files: Files) -> (Files, Report) {
    let resources = MemoryResources {
        files: std::mem::take(&mut files.side).into_iter().collect(),
    };
    let main = std::mem::take(&mut files.main.1);
    let mut report = check_bytes(&files.main.0, main, &resources, &CheckOptions::default());
    if report.has_errors() {
        // Nothing will be written: the report keeps the bytes, to show where the errors are.
        files.main.1 = report.document.bytes.to_vec();
    } else {
        files.main.1 = std::mem::take(&mut report.document.bytes).into_vec();
    }
    files.side = resources.files.into_iter().collect();
    files.side.sort();
    (files, report)
}

#[derive(Debug)]
pub enum WriteError {
    /// The output would replace the input.
    WouldOverwriteInput(PathBuf),
    /// A file exists and `force` was not given.
    Exists(PathBuf),
    Io(PathBuf, std::io::Error),
}

impl std::fmt::Display for WriteError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WriteError::WouldOverwriteInput(p) => {
                write!(
                    f,
                    "{} is the input: the input is never overwritten",
                    p.display()
                )
            }
            WriteError::Exists(p) => {
                write!(f, "{} exists (use --force to replace it)", p.display())
            }
            WriteError::Io(p, e) => write!(f, "{}: {e}", p.display()),
        }
    }
}

/// Writes every file into `folder`: each goes to a temporary file first and is renamed into
/// place only when all were written, so a failure leaves no half-written output. The input
/// is never replaced, and existing files only with `force`.
pub fn write(
    files: &Files,
    folder: &Path,
    input: Option<&Path>,
    force: bool,
) -> Result<(), WriteError> {
    let all: Vec<&(String, Vec<u8>)> = std::iter::once(&files.main).chain(&files.side).collect();
    let input = input.and_then(|p| p.canonicalize().ok());
    for (name, _) in &all {
        let target = folder.join(name);
        if let (Some(input), Ok(existing)) = (&input, target.canonicalize()) {
            if *input == existing {
                return Err(WriteError::WouldOverwriteInput(target));
            }
        }
        if target.exists() && !force {
            return Err(WriteError::Exists(target));
        }
    }
    let mut written = Vec::new();
    for (name, bytes) in &all {
        let temporary = folder.join(format!(".{name}.gltfmat-{}.tmp", std::process::id()));
        if let Err(e) = std::fs::write(&temporary, bytes) {
            written.iter().for_each(|(t, _): &(PathBuf, PathBuf)| {
                let _ = std::fs::remove_file(t);
            });
            let _ = std::fs::remove_file(&temporary);
            return Err(WriteError::Io(temporary, e));
        }
        written.push((temporary, folder.join(name)));
    }
    for (temporary, target) in &written {
        std::fs::rename(temporary, target).map_err(|e| WriteError::Io(target.clone(), e))?;
    }
    Ok(())
}
