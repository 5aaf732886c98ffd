//! A PNG explicitly tagged sRGB holds linear data.

use super::{bound_images, Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::document::image_header::{ImageFormat, Transfer};

pub(super) const RULE: Rule = Rule::new(
    "IMAGE_SRGB_IN_LINEAR_SLOT",
    Severity::Hint,
    "colour-space",
    "An image explicitly tagged sRGB is bound only to slots that read linear data.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a data slot (metallic-roughness, occlusion, normal, sheen roughness, anisotropy,
clearcoat, transmission …) bound to a PNG that carries an `sRGB` chunk or a `gAMA` of 1/2.2,
when that binding reads no channel as colour.

## Why
Data textures are sampled as linear values. An sRGB tag on one is harmless to glTF engines,
which ignore it, but image tools that honour the tag (resizers, compressors, texture
converters) will convert the values and bend roughness or normals. Many paint programs write
the tag by default, which is why this is only a hint.

## Example
An `occlusionTexture` pointing at a PNG with an `sRGB` chunk.
";

fn check(ctx: &mut Context) {
    let bound = bound_images(ctx);
    for (slot_use, image, info) in bound.iter() {
        let (srgb, linear) = slot_use.reads();
        if info.format != ImageFormat::Ktx2
            && srgb == 0
            && linear != 0
            && info.transfer == Some(Transfer::Srgb)
        {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} reads image {image} as linear data, but the image is tagged sRGB; tools that honour the tag will alter the values.",
                    slot_use.slot.key
                ),
            );
        }
    }
}
