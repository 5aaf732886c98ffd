//! Samplers (1.0 defaults written out), images (embedded, external or in the binary) and textures.

use crate::document::image_header;
use crate::document::Node;
use crate::gltf::gl;
use crate::upgrade::builder::{pointer, Builder};
use crate::upgrade::{NoteKind, UpgradeError};
use serde_json::{json, Value};

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn samplers(&mut self) {
        let samplers = self.source.dictionary("samplers");
        for (id, sampler) in &samplers {
            let mut out = Self::named(id, *sampler);
            // 1.0 defaults, written out: 2.0 leaves missing filters to the implementation.
            for (key, default) in [
                ("magFilter", gl::LINEAR),
                ("minFilter", gl::NEAREST_MIPMAP_LINEAR),
                ("wrapS", gl::REPEAT),
                ("wrapT", gl::REPEAT),
            ] {
                let value = sampler.get(key).and_then(Node::as_u64).unwrap_or(default);
                out.insert(key.into(), json!(value));
            }
            self.push_from("samplers", Value::Object(out), pointer("samplers", id));
        }
        if !samplers.is_empty() {
            self.note(
                "/samplers",
                NoteKind::Decision,
                "1.0 sampler defaults (LINEAR / NEAREST_MIPMAP_LINEAR / REPEAT) written out explicitly.",
            );
        }
    }

    pub(in crate::upgrade) fn images(&mut self) -> Result<(), UpgradeError> {
        // The images some texture samples (looked up once: a stranger's asset may hold 10^5
        // images and textures).
        let sampled: std::collections::HashSet<String> = (self.source.dictionary("textures"))
            .iter()
            .filter_map(|(_, texture)| Some(texture.get("source")?.as_str()?.to_string()))
            .collect();
        for (id, image) in self.source.dictionary("images") {
            let at = pointer("images", id);
            let bytes = match self.source.image_bytes(image) {
                Ok(bytes) => bytes,
                // An image no texture samples draws nothing: without it the output is exactly
                // what the 1.0 asset drew.
                Err(reason) if !sampled.contains(id) => {
                    let text =
                        format!("image not read ({reason}) and sampled by no texture: left out.");
                    self.note(&at, NoteKind::Dropped, text);
                    continue;
                }
                Err(reason) => {
                    return Err(UpgradeError::Resource {
                        pointer: at.clone(),
                        reason,
                    })
                }
            };
            let format = match image_header::read(&bytes) {
                Ok(format) => format,
                Err(e) if !sampled.contains(id) => {
                    let text = format!(
                        "{} and sampled by no texture: left out.",
                        unreadable(&bytes, &e)
                    );
                    self.note(&at, NoteKind::Dropped, text);
                    continue;
                }
                Err(e) => {
                    let reason = format!(
                        "{}: convert it to PNG or JPEG (or KTX2) first.",
                        unreadable(&bytes, &e)
                    );
                    return Err(UpgradeError::Resource {
                        pointer: at,
                        reason,
                    });
                }
            };
            let mime_type = format.format.mime_type().to_string();
            let index = self.add_image(Self::named(id, image), bytes, mime_type, id);
            self.record_origin("images", index, pointer("images", id));
        }
        Ok(())
    }

    pub(in crate::upgrade) fn textures(&mut self) {
        for (id, texture) in self.source.dictionary("textures") {
            let mut out = Self::named(id, texture);
            if let Some(i) = self.index_of("samplers", texture.get("sampler")) {
                out.insert("sampler".into(), json!(i));
            }
            if let Some(i) = self.index_of("images", texture.get("source")) {
                out.insert("source".into(), json!(i));
            }
            let format = texture.get("format").and_then(Node::as_u64).unwrap_or(6408);
            if !matches!(format, 6407 | 6408) {
                self.note(
                    pointer("textures", id),
                    NoteKind::Dropped,
                    format!("texture format {format} (ALPHA/LUMINANCE) has no 2.0 equivalent; the image is sampled as stored."),
                );
            }
            self.push_from("textures", Value::Object(out), pointer("textures", id));
        }
    }
}

/// Why an image's bytes are no image glTF 2.0 carries, naming the formats 1.0 assets were
/// written with that 2.0 has no place for (Cesium's models used KTX and Crunch).
fn unreadable(bytes: &[u8], error: &image_header::HeaderError) -> String {
    const OTHERS: &[(&[u8], &str)] = &[
        (b"\xABKTX 11\xBB", "KTX (version 1)"),
        (b"Hx", "Crunch (.crn)"),
        (b"DDS ", "DDS"),
        (b"GIF8", "GIF"),
        (b"BM", "BMP"),
        (b"II*\0", "TIFF"),
        (b"MM\0*", "TIFF"),
        (b"PVR\x03", "PVR"),
    ];
    match OTHERS.iter().find(|(magic, _)| bytes.starts_with(magic)) {
        Some((_, name)) => format!("a {name} image, which glTF 2.0 does not carry"),
        None => match error {
            image_header::HeaderError::Unrecognized => "not an image format glTF 2.0 carries (PNG, JPEG; KTX2 and WebP through their extensions)".to_string(),
            image_header::HeaderError::UnexpectedEnd => "an image cut short".to_string(),
            image_header::HeaderError::Invalid(why) => format!("an image that cannot be read ({why})"),
        },
    }
}
