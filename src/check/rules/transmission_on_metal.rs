//! KHR_materials_transmission on a fully metallic material.

use super::specular_on_metal::fully_metallic;
use super::{Rule, Run};
use crate::check::context::{number, Context};
use crate::check::khronos::materials::extension;
use crate::diagnostic::Severity;

pub(super) const RULE: Rule = Rule::new(
    "TRANSMISSION_ON_METAL",
    Severity::Warning,
    "materials",
    "KHR_materials_transmission transmits light through a fully metallic material, where it has no effect: the material renders as an opaque metal.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports `KHR_materials_transmission` with a `transmissionFactor` above 0 on a material whose
metallic value is 1 everywhere: `metallicFactor` is 1 (its default when missing), no
`metallicRoughnessTexture` could lower it, and
the asset does not change it at runtime (an animation channel through
KHR_animation_pointer, or a KHR_interactivity graph's `pointer/set` or `pointer/interpolate`).

## Why
KHR_materials_transmission: \"Metals effectively absorb all refracted light […]. Therefore,
for a material with `metallicFactor=1.0`, the value of `transmissionFactor` doesn't matter.\"
The glass the author meant renders as a dark, opaque metal. The usual cause is an exporter
that omits `metallicFactor`, whose default of 1 turns the dielectric into a metal.

## Example
```json
{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.9, 0.9, 0.9, 1]},
 \"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": 0.76}}}
```
";

fn check(ctx: &mut Context) {
    for (pointer, material) in fully_metallic(ctx) {
        let Some(transmission) = extension(material, "KHR_materials_transmission") else {
            continue;
        };
        let factor = number(transmission, "transmissionFactor", 0.0);
        if factor > 0.0 {
            ctx.emit(
                RULE.code(),
                format!("{pointer}/extensions/KHR_materials_transmission/transmissionFactor"),
                format!("transmissionFactor {factor} has no effect: the material is fully metallic (metallicFactor is 1, its default, and no texture lowers it), and a metal transmits nothing."),
            );
        }
    }
}
