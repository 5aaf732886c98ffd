//! KHR_materials_dispersion on a thin-walled volume.

use super::{Rule, Run};
use crate::check::animated::Animated;
use crate::check::context::{number, Context};
use crate::check::khronos::materials::extension;
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "DISPERSION_THIN_WALLED",
    Severity::Warning,
    "materials",
    "KHR_materials_dispersion is set on a material whose volume is thin-walled (thicknessFactor 0, its default): nothing refracts, so nothing disperses.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports `KHR_materials_dispersion` on a material whose `KHR_materials_volume` has a
`thicknessFactor` of 0, its default when missing, unless
the asset changes it at runtime (an animation channel through
KHR_animation_pointer, or a KHR_interactivity graph's `pointer/set` or `pointer/interpolate`). (Dispersion without any volume is the
Khronos warning KHR_MATERIALS_DISPERSION_NO_VOLUME.)

## Why
KHR_materials_dispersion builds on KHR_materials_volume \"as this builds upon its volumetric
effect\": it separates colours as light refracts through the volume. KHR_materials_volume:
\"If the value is 0 the material is thin-walled\" — light passes the surface without
refracting, so the dispersion does nothing. The author usually forgot the thickness.

## Example
```json
{\"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": 1},
  \"KHR_materials_volume\": {}, \"KHR_materials_dispersion\": {\"dispersion\": 0.3}}}
```
";

fn check(ctx: &mut Context) {
    let animated = Animated::of(ctx);
    for (i, pointer, material) in ctx.objects("materials") {
        let thickness = "extensions/KHR_materials_volume/thicknessFactor";
        let thin = extension(material, "KHR_materials_volume")
            .is_some_and(|volume| number(volume, "thicknessFactor", 0.0) == 0.0)
            && !animated.material_member(i, thickness);
        if thin && extension(material, "KHR_materials_dispersion").is_some() {
            ctx.emit(
                RULE.code(),
                format!("{pointer}/extensions/KHR_materials_dispersion"),
                "KHR_materials_dispersion has no effect: the volume is thin-walled (thicknessFactor 0, its default), so nothing refracts.",
            );
        }
    }
}
