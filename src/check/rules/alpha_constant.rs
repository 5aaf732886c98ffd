//! An alpha channel that a slot reads is the same everywhere (`--deep`).

use super::texels::Sampled;
use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::SlotUse;
use crate::diagnostic::Severity;
use crate::gltf::material::A;

pub(super) const RULE: Rule = Rule::new(
    "TEXTURE_ALPHA_CONSTANT",
    Severity::Info,
    "pixels",
    "With --deep: a slot reads the alpha channel, and the image's alpha is the same value everywhere.",
    DOC,
    Run::pixels(applies, inspect),
);

const DOC: &str = "\
## What it does
With `--deep`, for each texture binding that reads alpha (sheen roughness, glossiness,
specular strength, diffuse transmission, or base colour / diffuse coverage when `alphaMode` is
MASK or BLEND), decodes the image and reports when its alpha channel holds a single value,
saying which.

## Why
A constant alpha carries no data: the slot's factor can hold the value instead, and the image
could drop the channel. For coverage it often means a `BLEND` material that is in fact opaque
(sorting and overdraw for nothing), or for sheen roughness and glossiness an exporter that
filled alpha with 255 instead of the intended map.

## Example
A `sheenRoughnessTexture` whose alpha is 255 in every texel.
";

fn applies(slot_use: &SlotUse) -> bool {
    slot_use.reads().1 & A != 0
}

fn inspect(ctx: &mut Context, slot_use: &SlotUse, texels: &Sampled) {
    if !texels.has_alpha() {
        return; // TEXTURE_ALPHA_MISSING reports it from the header.
    }
    let mut range: Option<(f32, f32)> = None;
    texels.visit(|_, _, [.., alpha]| {
        let (low, high) = range.get_or_insert((alpha, alpha));
        *low = low.min(alpha);
        *high = high.max(alpha);
    });
    if let Some((_, high)) = range.filter(|(low, high)| low == high) {
        ctx.emit(
            RULE.code(),
            slot_use.pointer(),
            format!(
                "{} reads alpha, but every texel's alpha is {high:.4} (8-bit {}): the factor alone would do.",
                slot_use.slot.key,
                (high * 255.0).round()
            ),
        );
    }
}
