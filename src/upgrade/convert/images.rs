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
        for (id, image) in self.source.dictionary("images") {
            let at = pointer("images", id);
            let bytes =
                self.source
                    .image_bytes(image)
                    .map_err(|reason| UpgradeError::Resource {
                        pointer: at.clone(),
                        reason,
                    })?;
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
