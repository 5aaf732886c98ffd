//! A KTX2 image whose data format descriptor declares the wrong transfer function for its use.

use super::{bound_images, Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::document::image_header::{ImageFormat, Transfer};

pub(super) const RULE: Rule = Rule::new(
    "KTX2_TRANSFER_MISMATCH",
    Severity::Error,
    "colour-space",
    "A KTX2 image declares sRGB but is read as data (normals, roughness …), or declares linear but is read as colour.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a texture binding whose KTX2 image (KHR_texture_basisu) has a data format descriptor
whose transfer function contradicts what the binding reads: `KHR_DF_TRANSFER_SRGB` on an
image read only as data (normal, occlusion, metallic-roughness, clearcoat, transmission …),
or `KHR_DF_TRANSFER_LINEAR` on one read only as colour (base colour, emissive, sheen colour,
specular colour …). An image read both ways is IMAGE_COLOR_SPACE_CONFLICT's concern.

## Why
KHR_texture_basisu: \"Color space information in the DFD MUST match the expected usage\":
colour data has the sRGB transfer function, non-colour data (e.g. normal maps) the linear
one. Unlike a PNG's tag, which engines ignore, the descriptor decides the GPU format a
viewer transcodes to: an sRGB normal map is decoded through the sRGB curve before shading
(bent normals, wrong roughness), a linear base colour is shown too dark.

## Example
A `normalTexture` whose KTX2 was encoded without `--linear` (its DFD says sRGB).
";

fn check(ctx: &mut Context) {
    let bound = bound_images(ctx);
    for (slot_use, image, info) in bound.iter() {
        if info.format != ImageFormat::Ktx2 {
            continue;
        }
        let (srgb, linear) = slot_use.reads();
        let (declared, read_as) = match info.transfer {
            Some(Transfer::Srgb) if srgb == 0 && linear != 0 => ("sRGB", "linear data"),
            Some(Transfer::Linear) if srgb != 0 && linear == 0 => ("linear", "sRGB colour"),
            _ => continue,
        };
        ctx.emit(
            RULE.code(),
            slot_use.pointer(),
            format!(
                "{} reads KTX2 image {image} as {read_as}, but its data format descriptor declares the {declared} transfer function; viewers decode it as declared.",
                slot_use.slot.key
            ),
        );
    }
}
