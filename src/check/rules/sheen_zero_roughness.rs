//! A visible sheen with roughness zero.

use super::sheen_disabled::sheen_colour_is_zero;
use super::{Rule, Run};
use crate::check::animated::Animated;
use crate::check::context::{number, Context};
use crate::check::khronos::materials::extension;
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "SHEEN_ZERO_ROUGHNESS",
    Severity::Warning,
    "materials",
    "A visible sheen has sheenRoughnessFactor 0 (its default), where the Charlie distribution degenerates.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a `KHR_materials_sheen` object with a non-zero `sheenColorFactor` and a
`sheenRoughnessFactor` of 0, which is its default when the member is missing, unless
the asset changes it at runtime (an animation channel through
KHR_animation_pointer, or a KHR_interactivity graph's `pointer/set` or `pointer/interpolate`).

## Why
The Charlie sheen distribution D(h) = (2 + 1/r) sin(θ)^(1/r) / 2π with r = roughness² has no
limit at r = 0: the lobe collapses to a line at grazing angles. Engines avoid the division by
clamping r to different minimums, so the same material renders with a visibly different sheen
in each. Set the roughness the material was authored with (cloth is typically 0.3–0.8).

Spec: KHR_materials_sheen, \"sheenRoughnessFactor … default 0\" and the Charlie distribution in
its BRDF section; Conty & Kulla 2017.

## Example
```json
{\"KHR_materials_sheen\": {\"sheenColorFactor\": [1, 1, 1]}}
```
";

fn check(ctx: &mut Context) {
    let animated = Animated::of(ctx);
    for (i, pointer, material) in ctx.objects("materials") {
        let Some(sheen) = extension(material, "KHR_materials_sheen") else {
            continue;
        };
        let factor = "extensions/KHR_materials_sheen/sheenRoughnessFactor";
        if !sheen_colour_is_zero(sheen)
            && number(sheen, "sheenRoughnessFactor", 0.0) == 0.0
            && !animated.material_member(i, factor)
        {
            let at = if sheen.get("sheenRoughnessFactor").is_some() {
                "/sheenRoughnessFactor"
            } else {
                ""
            };
            ctx.emit(
                RULE.code(),
                format!("{pointer}/extensions/KHR_materials_sheen{at}"),
                "The sheen is visible but its roughness is 0 (the default): the Charlie distribution degenerates and engines clamp it differently.",
            );
        }
    }
}
