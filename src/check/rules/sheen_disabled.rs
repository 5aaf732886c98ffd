//! Sheen textures on a material whose sheen colour is zero.

use super::{Rule, Run};
use crate::check::animated::Animated;
use crate::check::context::Context;
use crate::check::khronos::materials::{extension, slot_uses};
use crate::diagnostic::Severity;
use crate::document::Node;

pub(super) const RULE: Rule = Rule::new(
    "SHEEN_TEXTURE_DISABLED",
    Severity::Warning,
    "materials",
    "A sheen texture is set while sheenColorFactor is zero (its default), which disables the sheen layer.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports `sheenColorTexture` and `sheenRoughnessTexture` on a material whose
`sheenColorFactor` is [0, 0, 0] — which is also its default when the member is missing.

A sheen object that holds textures and no factor at all is reported too: it is exactly the
mistake this rule exists for (the textures are multiplied by the default factor 0). A factor
the asset changes at runtime (an animation channel through
KHR_animation_pointer, or a KHR_interactivity graph's `pointer/set` or `pointer/interpolate`) is not
zero throughout: it is not reported.

## Why
The sheen colour is the factor times the texture, so a zero factor turns the whole sheen layer
off and the textures are downloaded and decoded for nothing. The usual cause is an exporter
writing the textures but not the factor, expecting a default of 1 as for base colour.

Spec: KHR_materials_sheen, \"sheenColorFactor … default [0, 0, 0]\"; \"If the sheenColorFactor
is zero, the whole sheen layer is disabled.\"

## Example
```json
{\"KHR_materials_sheen\": {\"sheenColorTexture\": {\"index\": 0}}}
```
";

/// The sheen colour factor, [0, 0, 0] when missing.
pub(super) fn sheen_colour_is_zero(sheen: Node) -> bool {
    sheen
        .get("sheenColorFactor")
        .and_then(Node::as_array)
        .is_none_or(|f| f.iter().all(|c| c.as_f64() == Some(0.0)))
}

fn check(ctx: &mut Context) {
    let animated = Animated::of(ctx);
    for slot_use in slot_uses(ctx).iter() {
        if slot_use.slot.extension != Some("KHR_materials_sheen") {
            continue;
        }
        let sheen = extension(slot_use.material, "KHR_materials_sheen");
        let factor = "extensions/KHR_materials_sheen/sheenColorFactor";
        if sheen.is_some_and(sheen_colour_is_zero)
            && !animated.material_member(slot_use.material_index, factor)
        {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                format!(
                    "{} has no effect: sheenColorFactor is zero (its default), which disables the sheen layer.",
                    slot_use.slot.key
                ),
            );
        }
    }
}
