//! Material extensions that the specs forbid on the same material.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use serde_json::Value;

pub const RULE: Rule = Rule::new(
    "MATERIAL_EXTENSION_EXCLUDED",
    Severity::Error,
    "materials",
    "A material extension is combined with KHR_materials_pbrSpecularGlossiness or KHR_materials_unlit, which its spec forbids.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a material extension whose specification says it must not be used together with
`KHR_materials_pbrSpecularGlossiness` or `KHR_materials_unlit` on the same material. The
pointer names the offending extension, not the one it collides with.

| extension | excludes |
|---|---|
| anisotropy, clearcoat, diffuse_transmission, dispersion, ior, iridescence, sheen, specular, transmission, volume | pbrSpecularGlossiness and unlit |
| emissive_strength | unlit only |

## Why
Each of these extensions extends the metallic-roughness BRDF. With specular-glossiness there
is no such BRDF to extend, and an unlit material has no lighting at all, so engines either
ignore the extension or render something the author never saw.

The Khronos validator reports only `MULTIPLE_EXTENSIONS`, a warning placed on the
specular-glossiness or unlit object whenever the material has any other extension, including
combinations the specs allow (specular-glossiness + emissive_strength) and unknown vendor
extensions. In the default profile gltfmat replaces that warning: real exclusions are this
error; allowed combinations are silent; `MULTIPLE_EXTENSIONS` remains only for extensions
whose compatibility gltfmat cannot know (vendor extensions, and unlit together with
specular-glossiness, on which neither spec speaks). `--profile khronos` reports the warning
exactly as the Khronos validator does.

Spec: each extension's README, section \"Extending Materials\" / \"Exclusions\".

## Example
```json
{\"extensions\": {\"KHR_materials_unlit\": {}, \"KHR_materials_sheen\": {\"sheenColorFactor\": [1, 1, 1]}}}
```
reports `/materials/0/extensions/KHR_materials_sheen`.
";

const SPEC_GLOSS: &str = "KHR_materials_pbrSpecularGlossiness";
const UNLIT: &str = "KHR_materials_unlit";

/// The extensions that exclude both specular-glossiness and unlit.
const EXTENDS_METAL_ROUGH: &[&str] = &[
    "KHR_materials_anisotropy",
    "KHR_materials_clearcoat",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_dispersion",
    "KHR_materials_ior",
    "KHR_materials_iridescence",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_volume",
];

/// What the specs say about `other` on a material that has the standalone extension
/// `standalone` (specular-glossiness or unlit).
#[derive(Debug, PartialEq, Eq)]
pub enum Combination {
    Excluded,
    Allowed,
    Unknown,
}

pub fn combination(standalone: &str, other: &str) -> Combination {
    if EXTENDS_METAL_ROUGH.contains(&other)
        || (standalone == UNLIT && other == "KHR_materials_emissive_strength")
    {
        Combination::Excluded
    } else if other == "KHR_materials_emissive_strength" {
        Combination::Allowed
    } else {
        Combination::Unknown
    }
}

fn check(ctx: &mut Context) {
    for (_, pointer, material) in ctx.objects("materials") {
        let Some(extensions) = material.get("extensions").and_then(Value::as_object) else {
            continue;
        };
        for standalone in [SPEC_GLOSS, UNLIT] {
            if !extensions.contains_key(standalone) {
                continue;
            }
            for other in extensions.keys() {
                if combination(standalone, other) == Combination::Excluded {
                    ctx.emit(
                        RULE.code(),
                        format!("{pointer}/extensions/{other}"),
                        format!("{other} must not be used together with {standalone} (its spec excludes the combination)."),
                    );
                }
            }
        }
    }
}
