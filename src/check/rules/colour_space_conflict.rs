//! One image read as sRGB colour by one slot and as linear data by another.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::{by_image, slot_uses, Channels, A, B, G, R};
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
    for (image, on_image) in by_image(&uses, ctx.items("images").len())
        .iter()
        .enumerate()
    {
        let mut first = FirstReaders::default();
        for (order, this) in on_image.iter().enumerate() {
            let (srgb, linear) = this.reads();
            if let Some(earlier) = first.earliest_clash(srgb, linear) {
                let (e_srgb, e_linear) = on_image[earlier].reads();
                let clash = (e_srgb & linear) | (e_linear & srgb);
                let (here, there) = if srgb & clash != 0 {
                    ("sRGB colour", "linear data")
                } else {
                    ("linear data", "sRGB colour")
                };
                ctx.emit(
                    RULE.code(),
                    this.pointer.clone(),
                    format!(
                        "Image {image} channel(s) {} are read as {here} here but as {there} by {}.",
                        channel_names(clash),
                        on_image[earlier].pointer
                    ),
                );
            }
            first.record(order, srgb, linear);
        }
    }
}

/// For each channel, the first use (by order) that reads it as sRGB and as linear data, so
/// that the earliest use a later one clashes with is found without rescanning them all.
#[derive(Default)]
struct FirstReaders {
    srgb: [Option<usize>; 4],
    linear: [Option<usize>; 4],
}

impl FirstReaders {
    fn earliest_clash(&self, srgb: Channels, linear: Channels) -> Option<usize> {
        CHANNELS
            .iter()
            .enumerate()
            .flat_map(|(c, &bit)| {
                let against_srgb = (linear & bit != 0).then_some(self.srgb[c]).flatten();
                let against_linear = (srgb & bit != 0).then_some(self.linear[c]).flatten();
                [against_srgb, against_linear]
            })
            .flatten()
            .min()
    }

    fn record(&mut self, order: usize, srgb: Channels, linear: Channels) {
        for (c, &bit) in CHANNELS.iter().enumerate() {
            if srgb & bit != 0 {
                self.srgb[c].get_or_insert(order);
            }
            if linear & bit != 0 {
                self.linear[c].get_or_insert(order);
            }
        }
    }
}

const CHANNELS: [Channels; 4] = [R, G, B, A];

fn channel_names(mask: Channels) -> String {
    [(R, 'R'), (G, 'G'), (B, 'B'), (A, 'A')]
        .iter()
        .filter(|(bit, _)| mask & bit != 0)
        .map(|(_, name)| *name)
        .collect()
}
