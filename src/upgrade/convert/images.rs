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
            let format = image_header::read(&bytes).map_err(|e| UpgradeError::Resource {
                pointer: at.clone(),
                reason: format!("not a readable image ({e:?})"),
            })?;
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
