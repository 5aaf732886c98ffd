//! Normal-map texels far from unit length (`--deep`).

use super::texels::Texels;
use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::SlotUse;
use crate::diagnostic::Severity;

pub const RULE: Rule = Rule::new(
    "NORMAL_TEXEL_NOT_UNIT",
    Severity::Warning,
    "pixels",
    "With --deep: normal-map texels decode to vectors far from unit length.",
    DOC,
    Run::pixels(applies, inspect),
);

const DOC: &str = "\
## What it does
With `--deep`, decodes each `normalTexture` and `clearcoatNormalTexture` and counts texels whose
vector (RGB mapped to [-1, 1]) has a length outside [0.9, 1.1]. 8-bit quantisation alone
stays within 0.01. Reports the count and the first such texel.

## Why
glTF normal textures hold unit vectors. Texels far from unit length mean the image is not a
tangent-space normal map (a height or bump map, a two-channel map with an empty blue
channel, an object-space map, an sRGB-converted map). Engines normalise and shade it anyway,
so the surface looks faceted or lit from the wrong side, differently in each engine.

Spec: glTF 2.0 §3.9.3, \"normal vectors … MUST be normalized\" (texel values map to [-1, 1]).

## Example
A bump map (grey heights) bound as `normalTexture`.
";

const TOLERANCE: f32 = 0.1;

fn applies(slot_use: &SlotUse) -> bool {
    slot_use.slot.is_normal()
}

fn inspect(ctx: &mut Context, slot_use: &SlotUse, texels: &Texels) {
    let tally = texels.tally(|[r, g, b, _]| {
        let v = [2.0 * r - 1.0, 2.0 * g - 1.0, 2.0 * b - 1.0];
        let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        (length - 1.0).abs() > TOLERANCE
    });
    if tally.count > 0 {
        ctx.emit(
            RULE.code(),
            slot_use.pointer.clone(),
            format!(
                "Normal-map texels are far from unit length: {}.",
                tally.describe()
            ),
        );
    }
}
