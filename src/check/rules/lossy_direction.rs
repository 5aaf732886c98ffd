//! Direction data stored with lossy JPEG compression.

use super::{bound_images, Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::document::image_header::ImageFormat;

pub(super) const RULE: Rule = Rule::new(
    "TEXTURE_LOSSY_DIRECTION",
    Severity::Hint,
    "channels",
    "A normal or anisotropy texture is stored as JPEG, whose compression distorts directions.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a `normalTexture`, `clearcoatNormalTexture` or `anisotropyTexture` bound to a JPEG image.

## Why
These textures store vectors, not colours. JPEG's chroma subsampling and block quantisation
are tuned for what the eye notices in colours; in a normal map they show up as blocky
shading and wobbling highlights, in an anisotropy map as a noisy direction field. PNG, WebP
lossless or KTX2 (UASTC) keep the vectors intact.

## Example
```json
{\"normalTexture\": {\"index\": 0}}  // texture 0 → image/jpeg
```
";

fn check(ctx: &mut Context) {
    let bound = bound_images(ctx);
    for (slot_use, image, info) in bound.iter() {
        let direction = slot_use.slot.is_normal() || slot_use.slot.key == "anisotropyTexture";
        if direction && info.format == ImageFormat::Jpeg {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} stores directions in image {image}, a JPEG: lossy compression distorts them; prefer PNG, lossless WebP or KTX2.",
                    slot_use.slot.key
                ),
            );
        }
    }
}
