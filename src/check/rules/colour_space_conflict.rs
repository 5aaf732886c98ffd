//! One image read as sRGB colour by one slot and as linear data by another.

use super::texels::{self, Texels};
use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::{by_image, slot_uses, SlotUse};
use crate::diagnostic::Severity;
use crate::gltf::material::{Channels, A, B, G, R};

pub(super) const RULE: Rule = Rule::new(
    "IMAGE_COLOR_SPACE_CONFLICT",
    Severity::Warning,
    "colour-space",
    "The same image channel is read as sRGB colour by one texture slot and as linear data by another.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports an image one texture binding reads as sRGB colour (base colour, emissive, sheen
colour, specular colour, diffuse, specular-glossiness RGB) and another reads as linear data
(metallic-roughness, occlusion, normal, sheen roughness, anisotropy, glossiness alpha,
clearcoat, transmission …) in the same channel. Channels are compared one by one: base colour
RGB with sheen roughness in the alpha of the same image is fine. There is one finding per
image, at the image; it names the first binding of each kind and counts the bindings that
clash. Such an image is decoded (within the `--deep` limits, even without `--deep`: clashes
are rare) and not reported when its clashing channels hold only 0 and 255, the two values
both readings agree on.

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
        let Some(conflict) = Conflict::find(on_image) else {
            continue;
        };
        if texels::decode_quietly(ctx, image).is_some_and(|t| conflict.harmless_on(&t)) {
            continue;
        }
        let message = format!(
            "Image {image} is read as sRGB colour by {} and as linear data by {} in channel(s) {}; {} of its {} bindings clash.",
            conflict.first_srgb,
            conflict.first_linear,
            channel_names(conflict.channels),
            conflict.clashing,
            on_image.len()
        );
        ctx.emit(RULE.code(), format!("/images/{image}"), message);
    }
}

/// How the bindings of one image disagree.
struct Conflict {
    first_srgb: String,
    first_linear: String,
    /// The channels read both ways.
    channels: Channels,
    /// Bindings that read at least one of those channels.
    clashing: usize,
}

impl Conflict {
    fn find(on_image: &[&SlotUse]) -> Option<Conflict> {
        let reads: Vec<_> = on_image.iter().map(|u| u.reads()).collect();
        let srgb = reads.iter().fold(0, |all, (s, _)| all | s);
        let linear = reads.iter().fold(0, |all, (_, l)| all | l);
        let channels = srgb & linear;
        if channels == 0 {
            return None;
        }
        let first = |kind: fn(&(Channels, Channels)) -> Channels| {
            let at = reads.iter().position(|r| kind(r) & channels != 0)?;
            Some(on_image[at].pointer())
        };
        Some(Conflict {
            first_srgb: first(|r| r.0)?,
            first_linear: first(|r| r.1)?,
            channels,
            clashing: reads
                .iter()
                .filter(|(s, l)| (s | l) & channels != 0)
                .count(),
        })
    }

    /// Whether every texel holds 0 or 255 in each clashing channel.
    fn harmless_on(&self, texels: &Texels) -> bool {
        let wanted: Vec<usize> = (0..4)
            .filter(|&c| self.channels & CHANNELS[c] != 0)
            .collect();
        texels
            .tally(|rgba| wanted.iter().any(|&c| rgba[c] != 0.0 && rgba[c] != 1.0))
            .count
            == 0
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
