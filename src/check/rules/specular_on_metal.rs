//! KHR_materials_ior / KHR_materials_specular on a fully metallic material.

use super::{Rule, Run};
use crate::check::animated::Animated;
use crate::check::context::{number, Context};
use crate::check::khronos::materials::extension;
use crate::diagnostic::Severity;
use crate::document::Node;

pub(super) const RULE: Rule = Rule::new(
    "SPECULAR_ON_METAL",
    Severity::Warning,
    "materials",
    "KHR_materials_ior or KHR_materials_specular is set on a fully metallic material, where it has no effect.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports `KHR_materials_ior` and `KHR_materials_specular` on a material whose metallic value
is 1 everywhere: `metallicFactor` is 1 (its default when missing, also when the whole
`pbrMetallicRoughness` object is), there is no `metallicRoughnessTexture` that could lower it, and
the asset does not change it at runtime (an animation channel through
KHR_animation_pointer, or a KHR_interactivity graph's `pointer/set` or `pointer/interpolate`):
a factor that changes is not 1 all the time.

## Why
Both extensions change only the dielectric Fresnel term; a metal's reflectance is its base
colour. On a fully metallic material they do nothing. The common cause is forgetting
`metallicFactor: 0`, whose default of 1 turns the intended dielectric into a metal.

Spec: KHR_materials_ior and KHR_materials_specular (both modify `dielectric_brdf` only);
glTF 2.0 §3.9.2 (metallicFactor default 1).

## Example
```json
{\"extensions\": {\"KHR_materials_ior\": {\"ior\": 1.45}}}
```
";

fn check(ctx: &mut Context) {
    for (pointer, material) in fully_metallic(ctx) {
        for name in ["KHR_materials_ior", "KHR_materials_specular"] {
            if extension(material, name).is_some() {
                ctx.emit(
                    RULE.code(),
                    format!("{pointer}/extensions/{name}"),
                    format!("{name} has no effect: the material is fully metallic (metallicFactor is 1, its default, and no texture lowers it)."),
                );
            }
        }
    }
}

/// The materials whose metallic value is 1 everywhere and always: `metallicFactor` 1 (its
/// default when missing), no `metallicRoughnessTexture` that could lower it, and no change at
/// runtime (see [`Animated`]).
pub(super) fn fully_metallic<'a>(ctx: &Context<'a>) -> Vec<(String, Node<'a>)> {
    let animated = Animated::of(ctx);
    (ctx.objects("materials"))
        .filter(|(i, _, material)| {
            let pbr = material.get("pbrMetallicRoughness");
            let metallic = pbr.map_or(1.0, |p| number(p, "metallicFactor", 1.0));
            metallic >= 1.0
                && pbr.is_none_or(|p| p.get("metallicRoughnessTexture").is_none())
                && !animated.material_member(*i, "pbrMetallicRoughness/metallicFactor")
        })
        .map(|(_, pointer, material)| (pointer, material))
        .collect()
}
