//! Anisotropy texels with no direction (`--deep`).

use super::texels::Sampled;
use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::SlotUse;
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "ANISOTROPY_DIRECTION_UNDEFINED",
    Severity::Warning,
    "pixels",
    "With --deep: anisotropy texels with a non-zero strength have a near-zero direction vector.",
    DOC,
    Run::pixels(applies, inspect),
);

const DOC: &str = "\
## What it does
With `--deep`, decodes each `anisotropyTexture` and counts texels whose strength (B) is not
zero while their direction, (R, G) mapped to [-1, 1], is shorter than 1/64 — for 8-bit data,
the texels at or next to (128, 128). As for NORMAL_TEXEL_BELOW_SURFACE, only the texels the
material's meshes sample are counted (every texel where their UVs cannot be read), and it
reports when they are at least 0.1% of those. Reports the count and the first such texel.

## Why
The spec normalises the direction vector; a zero vector has no direction, so engines divide
by zero (NaN, black pixels) or pick an arbitrary axis. Texels with zero strength are not
reported: their direction is never used.

Spec: KHR_materials_anisotropy, \"anisotropyTexture … red and green channels represent the
anisotropy direction in [-1, 1] tangent, bitangent space\".

## Example
An anisotropy map painted mid-grey (128, 128, 255).
";

/// Shorter than this, a direction is noise: two 8-bit steps from the centre.
const MIN_DIRECTION: f32 = 1.0 / 64.0;

fn applies(slot_use: &SlotUse) -> bool {
    slot_use.slot.key == "anisotropyTexture"
        && slot_use.extension_number("anisotropyStrength", 0.0) > 0.0
}

fn inspect(ctx: &mut Context, slot_use: &SlotUse, texels: &Sampled) {
    let tally = texels.tally(|[r, g, b, _]| {
        let (x, y) = (2.0 * r - 1.0, 2.0 * g - 1.0);
        b > 0.0 && x.hypot(y) < MIN_DIRECTION
    });
    if tally.visible() {
        ctx.emit(
            RULE.code(),
            slot_use.pointer(),
            format!(
                "Anisotropy direction is undefined (near-zero RG) where the strength is not zero: {}.",
                tally.describe()
            ),
        );
    }
}
