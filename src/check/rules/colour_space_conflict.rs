//! One image read as sRGB colour by one slot and as linear data by another.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::{slot_uses, Channels, A, B, G, R};
use crate::diagnostic::Severity;

pub const RULE: Rule = Rule::new(
    "IMAGE_COLOR_SPACE_CONFLICT",
    Severity::Warning,
    "colour-space",
    "The same image channel is read as sRGB colour by one texture slot and as linear data by another.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a texture binding that reads a channel of an image as linear data (metallic-roughness,
occlusion, normal, sheen roughness, anisotropy, glossiness alpha, clearcoat, transmission …)
when an earlier binding reads the same channel of the same image as sRGB colour (base colour,
emissive, sheen colour, specular colour, diffuse, specular-glossiness RGB), or the other way
round. Channels are compared one by one: base colour RGB with sheen roughness in the alpha of
the same image is fine. The pointer is the later binding; the message names the earlier one.

## Why
Engines decode a texture once, with one transfer function chosen by its use. Reading one
image both ways means one of the uses gets wrongly decoded values (roughly a 2.2 gamma error),
or the engine silently duplicates the texture in GPU memory. See KhronosGroup/glTF#2308.

## Example
Texture 0 used as `baseColorTexture` and as `occlusionTexture` (R is read as sRGB colour and
as linear occlusion).
";

fn check(ctx: &mut Context) {
    let uses = slot_uses(ctx);
    let image_count = ctx.items("images").len();
    for image in 0..image_count {
        let on_image: Vec<_> = uses.iter().filter(|u| u.images.contains(&image)).collect();
        for (later, this) in on_image.iter().enumerate() {
            let (srgb, linear) = this.reads();
            let earlier = on_image[..later].iter().find_map(|e| {
                let (e_srgb, e_linear) = e.reads();
                let clash = (e_srgb & linear) | (e_linear & srgb);
                (clash != 0).then_some((e, clash))
            });
            if let Some((earlier, clash)) = earlier {
                ctx.emit(
                    RULE.code(),
                    this.pointer.clone(),
                    format!(
                        "Image {image} channel(s) {} are read as {} here but as {} by {}.",
                        channel_names(clash),
                        if srgb & clash != 0 {
                            "sRGB colour"
                        } else {
                            "linear data"
                        },
                        if srgb & clash != 0 {
                            "linear data"
                        } else {
                            "sRGB colour"
                        },
                        earlier.pointer
                    ),
                );
            }
        }
    }
}

fn channel_names(mask: Channels) -> String {
    [(R, 'R'), (G, 'G'), (B, 'B'), (A, 'A')]
        .iter()
        .filter(|(bit, _)| mask & bit != 0)
        .map(|(_, name)| *name)
        .collect()
}
