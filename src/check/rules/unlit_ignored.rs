//! Lighting textures on an unlit material.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::{extension, slot_uses};
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "UNLIT_IGNORED_TEXTURE",
    Severity::Warning,
    "materials",
    "An unlit material carries a normal, occlusion or metallic-roughness texture, which unlit shading ignores.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports `normalTexture`, `occlusionTexture` and `pbrMetallicRoughness.metallicRoughnessTexture`
on a material with `KHR_materials_unlit`.

## Why
Unlit shading uses only base colour, alpha and vertex colours. These textures are lighting
inputs: a renderer that supports the extension downloads them for nothing, and one that does
not (the only reader of the PBR fallback) shows a lit material the author did not design.
Usually they are left over from the material the unlit one was made from.

Spec: KHR_materials_unlit, \"Extending Materials\" (properties other than baseColor are only
fallbacks).

## Example
```json
{\"normalTexture\": {\"index\": 0}, \"extensions\": {\"KHR_materials_unlit\": {}}}
```
";

const LIGHTING_SLOTS: &[&str] = &[
    "normalTexture",
    "occlusionTexture",
    "metallicRoughnessTexture",
];

fn check(ctx: &mut Context) {
    for slot_use in slot_uses(ctx).iter() {
        let unlit = extension(slot_use.material, "KHR_materials_unlit").is_some();
        if unlit && LIGHTING_SLOTS.contains(&slot_use.slot.key) {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} is ignored by unlit shading; only clients without KHR_materials_unlit would use it.",
                    slot_use.slot.key
                ),
            );
        }
    }
}
