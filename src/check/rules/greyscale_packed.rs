//! A slot that packs different data into R, G and B is bound to a greyscale image.

use super::{bound_images, Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::gltf::material::RGB;

pub(super) const RULE: Rule = Rule::new(
    "TEXTURE_GREYSCALE_PACKED",
    Severity::Warning,
    "channels",
    "A slot that reads separate data from two or more colour channels is bound to a greyscale image.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a texture binding whose slot reads two or more of R, G, B as separate linear data —
`metallicRoughnessTexture` (G roughness, B metallic), `normalTexture` and
`clearcoatNormalTexture` (XYZ), `anisotropyTexture` (RG direction, B strength) — when the bound
image is greyscale (luminance or luminance-alpha).

## Why
A greyscale image samples with R = G = B, so roughness equals metallic, or every normal points
along (1, 1, 1): almost always a texture exported with the wrong channel mode. Colour slots
(base colour, specular colour, sheen colour …) may legitimately be grey, so they are not
reported: a grey `specularColorTexture` is an untinted specular, which is valid and common.

Spec: glTF 2.0 §3.9.2 (metallicRoughnessTexture channels), §3.9.3 (normal texture);
KHR_materials_anisotropy (anisotropyTexture channels).

## Example
A `metallicRoughnessTexture` pointing at an 8-bit greyscale PNG.
";

fn check(ctx: &mut Context) {
    let bound = bound_images(ctx);
    for (slot_use, image, info) in bound.iter() {
        let (_, linear) = slot_use.reads();
        if (linear & RGB).count_ones() >= 2 && info.channels.is_grey() {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} reads separate data from its colour channels, but image {image} is greyscale, so they all read the same value.",
                    slot_use.slot.key
                ),
            );
        }
    }
}
