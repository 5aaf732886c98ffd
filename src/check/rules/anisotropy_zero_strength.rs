//! An anisotropy texture with anisotropyStrength zero.

use super::{Rule, Run};
use crate::check::animated::Animated;
use crate::check::context::Context;
use crate::check::khronos::materials::slot_uses;
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "ANISOTROPY_TEXTURE_ZERO_STRENGTH",
    Severity::Warning,
    "materials",
    "An anisotropyTexture is set while anisotropyStrength is 0 (its default), so it has no effect.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports an `anisotropyTexture` on a material whose `anisotropyStrength` is 0, which is also its
default when the member is missing, unless
the asset changes it at runtime (an animation channel through
KHR_animation_pointer, or a KHR_interactivity graph's `pointer/set` or `pointer/interpolate`).

## Why
The anisotropy strength is `anisotropyStrength` times the texture's blue channel, so a zero
factor makes the material isotropic whatever the texture holds; its direction (RG) is then
irrelevant too. The usual cause is an exporter that writes the texture but not the factor.

Spec: KHR_materials_anisotropy, \"anisotropyStrength … default 0\".

## Example
```json
{\"KHR_materials_anisotropy\": {\"anisotropyTexture\": {\"index\": 0}}}
```
";

fn check(ctx: &mut Context) {
    let animated = Animated::of(ctx);
    for slot_use in slot_uses(ctx).iter() {
        let strength = "extensions/KHR_materials_anisotropy/anisotropyStrength";
        if slot_use.slot.key == "anisotropyTexture"
            && slot_use.extension_number("anisotropyStrength", 0.0) == 0.0
            && !animated.material_member(slot_use.material_index, strength)
        {
            ctx.emit(
                RULE.code(),
                slot_use.pointer(),
                "anisotropyTexture has no effect: anisotropyStrength is 0 (its default), which multiplies the texture's strength.",
            );
        }
    }
}
