//! A slot reads alpha from an image that has none.

use super::{bound_images, Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::gltf::material::A;

pub(super) const RULE: Rule = Rule::new(
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
`baseColorTexture` / `diffuseTexture` when `alphaMode` is `MASK` or `BLEND` and the factor's
alpha is 1. A base colour whose factor alpha is below 1 is translucent as its author meant
(coverage = factor alpha × texel alpha, and the factor carries it), so an RGB texture there
loses nothing and is not reported.

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
        if linear & A != 0 && known && !info.channels.has_alpha() && !factor_carries_alpha(slot_use)
        {
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

/// Whether the slot is a base colour whose factor's alpha is below 1: the coverage the
/// author meant is then the factor's (glTF 2.0 §3.9.2: the factor multiplies the texel).
fn factor_carries_alpha(slot_use: &crate::check::context::SlotUse) -> bool {
    let factor = match slot_use.slot.key {
        "baseColorTexture" => slot_use
            .material
            .get("pbrMetallicRoughness")
            .and_then(|p| p.get("baseColorFactor")),
        "diffuseTexture" => slot_use
            .material
            .get("extensions")
            .and_then(|e| e.get("KHR_materials_pbrSpecularGlossiness"))
            .and_then(|e| e.get("diffuseFactor")),
        _ => return false,
    };
    let alpha = factor
        .and_then(|f| f.as_array())
        .and_then(|f| f.get(3))
        .and_then(|a| a.as_f64());
    alpha.is_some_and(|a| a < 1.0)
}
