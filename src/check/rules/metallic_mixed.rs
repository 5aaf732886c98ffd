//! Metallic values between metal and dielectric.

use super::texels::Sampled;
use super::{Rule, Run, LARGE_AREA};
use crate::check::context::{number, Context};
use crate::check::khronos::materials::SlotUse;
use crate::diagnostic::Severity;
use crate::document::Node;

pub(super) const RULE: Rule = Rule::new(
    "PBR_METALLIC_MIXED",
    Severity::Hint,
    "plausibility",
    "Metallic is between 0.1 and 0.9, a mix of metal and dielectric that few real surfaces have.",
    DOC,
    Run::both(check_factor, applies, inspect),
);

const DOC: &str = "\
## What it does
Reports a `metallicFactor` strictly between 0.1 and 0.9 on a material without a
metallic-roughness texture, and with `--deep` a metallic-roughness texture whose metallic
(B times the factor) lies in that range over more than 10% of its texels.

## Why
A surface is either a metal or not; intermediate values belong only to the anti-aliased
transitions between the two (rust edges, dust). Large areas of half-metal usually mean a
specular or gloss map was reused as metallic, and they shade as a physically impossible
material that looks different under every environment. It is an opinion, not a spec rule: it
runs only with `--enable-group plausibility`. Factors are compared as the single-precision
values engines load, so 0.1 written as 0.100000001490116 is a dielectric.

## Example
```json
{\"pbrMetallicRoughness\": {\"metallicFactor\": 0.5}}
```
";

/// Strictly between 0.1 and 0.9, compared in single precision: a float32 0.1 read back as
/// a double lies just above 0.1.
fn is_mixed(metallic: f64) -> bool {
    let metallic = metallic as f32;
    metallic > 0.1 && metallic < 0.9
}

fn metallic_factor(material: Node) -> f64 {
    material
        .get("pbrMetallicRoughness")
        .map_or(1.0, |p| number(p, "metallicFactor", 1.0))
}

fn check_factor(ctx: &mut Context) {
    for (_, pointer, material) in ctx.objects("materials") {
        let pbr = material.get("pbrMetallicRoughness");
        let textured = pbr.is_some_and(|p| p.get("metallicRoughnessTexture").is_some());
        let metallic = metallic_factor(material);
        if !textured && is_mixed(metallic) {
            ctx.emit(
                RULE.code(),
                format!("{pointer}/pbrMetallicRoughness/metallicFactor"),
                format!("metallicFactor {metallic} is neither metal nor dielectric."),
            );
        }
    }
}

fn applies(slot_use: &SlotUse) -> bool {
    slot_use.slot.key == "metallicRoughnessTexture"
}

fn inspect(ctx: &mut Context, slot_use: &SlotUse, texels: &Sampled) {
    let factor = metallic_factor(slot_use.material);
    let tally = texels.tally(|[_, _, b, _]| is_mixed(f64::from(b) * factor));
    if tally.fraction() > LARGE_AREA {
        ctx.emit(
            RULE.code(),
            slot_use.pointer(),
            format!("Metallic is between 0.1 and 0.9 in {}.", tally.describe()),
        );
    }
}
