//! A slot reads alpha from an image that has none.

use super::{bound_images, Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::gltf::material::A;

pub const RULE: Rule = Rule::new(
    "TEXTURE_ALPHA_MISSING",
    Severity::Warning,
    "channels",
    "A texture slot reads the alpha channel, but its image has no alpha: every texel reads 1.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a texture binding whose slot reads the alpha channel when the bound image (by its
header) has no alpha channel. Slots that read alpha: `sheenRoughnessTexture`,
`specularGlossinessTexture` (glossiness), `specularTexture`, `diffuseTransmissionTexture`, and
`baseColorTexture` / `diffuseTexture` when `alphaMode` is `MASK` or `BLEND`.

## Why
A missing alpha channel samples as 1.0, so the data the author meant to store is silently
replaced: sheen roughness and glossiness become their factors, a blended material becomes
opaque. This usually means the exporter dropped the alpha channel or packed the value into
RGB. The Khronos validator reads the channel layout but never compares it with the slot.

Spec: KHR_materials_sheen (\"roughness in the A channel\"), KHR_materials_pbrSpecularGlossiness
(\"glossiness in the A channel\"), glTF 2.0 §3.9.2 (base colour alpha).

## Example
A `sheenRoughnessTexture` pointing at an RGB PNG.
";

fn check(ctx: &mut Context) {
    let bound = bound_images(ctx);
    for (slot_use, image, info) in bound.iter() {
        let (_, linear) = slot_use.reads();
        let known = info.channels != crate::document::image_header::Channels::Unknown;
        if linear & A != 0 && known && !info.channels.has_alpha() {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} reads the alpha channel, but image {image} ({}) has none, so it samples 1.0 everywhere.",
                    slot_use.slot.key,
                    info.channels.name()
                ),
            );
        }
    }
}
