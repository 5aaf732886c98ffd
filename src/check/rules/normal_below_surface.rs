//! Normal-map texels pointing below the surface (`--deep`).

use super::texels::Sampled;
use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::SlotUse;
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "NORMAL_TEXEL_BELOW_SURFACE",
    Severity::Warning,
    "pixels",
    "With --deep: normal-map texels have a blue value of 0.5 or less, a normal pointing into the surface.",
    DOC,
    Run::pixels(applies, inspect),
);

const DOC: &str = "\
## What it does
With `--deep`, decodes each `normalTexture` and `clearcoatNormalTexture` and counts texels
whose blue value is 0.5 or less, which maps to Z ≤ 0: a tangent-space normal that points into
the surface or lies in it. Only the texels the material's meshes sample are counted (their
UVs through the binding's texCoord set, texture transform and wrap modes, with the bilinear
filter's neighbours); the black gutters between UV islands are never seen. Where those UVs
cannot be read (compressed by Draco or meshopt, or in a buffer that could not be read) every
texel is counted, and the message says \"of N texels\" rather than \"of N texels the meshes
sample\": gutters may then be among them. It reports when such texels are at least 0.1% of
those sampled: fewer are isolated texels (seams, compression noise) that filtering and mipmaps
average away. Reports the count and the first one. The length of the vectors is not judged:
renderers normalise every normal before lighting, so a map whose texels are longer or shorter
than 1 shades as its directions say.

## Why
A shading normal below the surface lights the surface from behind: black or inverted spots.
Such texels mean the image is not a tangent-space normal map (a height or bump map, a
two-channel map with an empty blue channel, an sRGB-converted map, or one with Z flipped).

Spec: glTF 2.0 §3.9.3, \"Normal textures SHOULD NOT contain blue values less than or equal to
0.5\" (blue (0.5 .. 1.0] maps to Z (0 .. 1]).

## Example
A bump map (grey heights below 128) bound as `normalTexture`.
";

fn applies(slot_use: &SlotUse) -> bool {
    slot_use.slot.is_normal()
}

fn inspect(ctx: &mut Context, slot_use: &SlotUse, texels: &Sampled) {
    let tally = texels.tally(|[_, _, blue, _]| blue <= 0.5);
    if tally.visible() {
        ctx.emit(
            RULE.code(),
            slot_use.pointer(),
            format!(
                "Normal-map texels point into the surface (blue ≤ 0.5, Z ≤ 0): {}.",
                tally.describe()
            ),
        );
    }
}
