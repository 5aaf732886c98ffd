//! A PNG tagged as linear is read as sRGB colour.

use super::{bound_images, Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::document::image_header::{ImageFormat, Transfer};

pub(super) const RULE: Rule = Rule::new(
    "IMAGE_LINEAR_IN_SRGB_SLOT",
    Severity::Hint,
    "colour-space",
    "An image tagged as linear (PNG gAMA 1.0) is bound to a slot that decodes it as sRGB.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a colour slot (base colour, emissive, sheen colour, specular colour, diffuse,
diffuse-transmission colour, specular-glossiness RGB) bound to a PNG whose `gAMA` chunk says
its values are linear (gamma 1.0).

## Why
glTF decodes colour textures with the sRGB transfer function whatever the file says. If the
texels were written from linear values (a bake or a render), the colour renders too dark and
too saturated in every engine: re-encode the image as sRGB. If the tag is wrong, glTF engines
are unaffected but tools that honour it (browsers, resizers, texture compressors) brighten the
image: remove the tag. The tag alone cannot tell the two apart, and some exporters stamp
gamma 1.0 on every PNG they write whatever it holds (Microsoft's glTF exporter does, on sRGB
colour textures), which is why this is only a hint. Images with a custom ICC profile or an
unusual gamma are the Khronos `IMAGE_FEATURES_UNSUPPORTED` concern and are not repeated here.

Spec: glTF 2.0 §3.9.2 (\"baseColorTexture … MUST be encoded with the sRGB transfer function\").

## Example
A `baseColorTexture` pointing at a PNG with `gAMA` = 100000.
";

fn check(ctx: &mut Context) {
    let bound = bound_images(ctx);
    for (slot_use, image, info) in bound.iter() {
        let (srgb, _) = slot_use.reads();
        if info.format != ImageFormat::Ktx2 && srgb != 0 && info.transfer == Some(Transfer::Linear)
        {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} decodes image {image} as sRGB, but the image is tagged linear (gAMA 1.0): linear texels render too dark, and a wrong tag makes tools that honour it brighten the image.",
                    slot_use.slot.key
                ),
            );
        }
    }
}
