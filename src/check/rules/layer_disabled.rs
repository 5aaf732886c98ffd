//! Textures of a material layer whose factor switches the layer off.

use super::{Rule, Run};
use crate::check::animated::Animated;
use crate::check::context::{number, Context};
use crate::check::khronos::materials::{extension, slot_uses};
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "LAYER_TEXTURE_DISABLED",
    Severity::Warning,
    "materials",
    "A layer's texture is bound while the layer's factor is zero (its default), which switches the layer off: the texture does nothing.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a texture of KHR_materials_clearcoat, _iridescence, _transmission,
_diffuse_transmission or _volume whose layer is off because its factor is 0 — the default of
each of these factors when the member is missing — unless
the asset changes it at runtime (an animation channel through
KHR_animation_pointer, or a KHR_interactivity graph's `pointer/set` or `pointer/interpolate`):

| extension | factor | textures that then do nothing |
|---|---|---|
| clearcoat | `clearcoatFactor` | `clearcoatTexture`, `clearcoatRoughnessTexture`, `clearcoatNormalTexture` |
| iridescence | `iridescenceFactor` | `iridescenceTexture`, `iridescenceThicknessTexture` |
| transmission | `transmissionFactor` | `transmissionTexture` |
| diffuse transmission | `diffuseTransmissionFactor` | `diffuseTransmissionTexture` (`diffuseTransmissionColorTexture` too) |
| volume | `thicknessFactor` | `thicknessTexture` (the material is thin-walled) |

(Sheen has its own rule, SHEEN_TEXTURE_DISABLED.)

## Why
Each texture is multiplied by its factor, and the READMEs say what a zero factor means:
\"If `clearcoatFactor` (in the extension) is zero, the whole clearcoat layer is disabled.\";
\"If `iridescenceFactor` is zero (default), the iridescence extension has no effect on the
material.\"; for volume, \"If the value is 0 the material is thin-walled.\" The textures are
downloaded and decoded for nothing, and the author almost always meant the layer to show: an
exporter wrote the texture and not the factor, expecting a default of 1.

## Example
```json
{\"KHR_materials_clearcoat\": {\"clearcoatTexture\": {\"index\": 0}}}
```
";

/// Each layer's factor, and whether a zero factor also switches off the slot of `key`.
fn factor_of(extension: &str, key: &str) -> Option<&'static str> {
    Some(match (extension, key) {
        ("KHR_materials_clearcoat", _) => "clearcoatFactor",
        ("KHR_materials_iridescence", _) => "iridescenceFactor",
        ("KHR_materials_transmission", _) => "transmissionFactor",
        ("KHR_materials_diffuse_transmission", _) => "diffuseTransmissionFactor",
        ("KHR_materials_volume", "thicknessTexture") => "thicknessFactor",
        _ => return None,
    })
}

fn check(ctx: &mut Context) {
    let animated = Animated::of(ctx);
    for slot_use in slot_uses(ctx).iter() {
        let Some(name) = slot_use.slot.extension else {
            continue;
        };
        let Some(factor) = factor_of(name, slot_use.slot.key) else {
            continue;
        };
        let Some(layer) = extension(slot_use.material, name) else {
            continue;
        };
        let member = format!("extensions/{name}/{factor}");
        if number(layer, factor, 0.0) == 0.0
            && !animated.material_member(slot_use.material_index, &member)
        {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} has no effect: {factor} is 0 (its default), which switches the layer off.",
                    slot_use.slot.key
                ),
            );
        }
    }
}
