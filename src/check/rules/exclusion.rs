//! Material extensions that the specs forbid on the same material.

use super::{Rule, Run, Supersession};
use crate::check::context::Context;
use crate::diagnostic::{khronos, Diagnostic, Severity};
use crate::document::Node;
use crate::gltf::material::{combination, Combination, SPEC_GLOSS, UNLIT};

pub(crate) const RULE: Rule = Rule::new(
    "MATERIAL_EXTENSION_EXCLUDED",
    Severity::Error,
    "materials",
    "A material extension is combined with KHR_materials_pbrSpecularGlossiness or KHR_materials_unlit, which its spec forbids.",
    DOC,
    Run::document(check),
)
.superseding(&[Supersession {
    code: khronos::MULTIPLE_EXTENSIONS,
    why: "Replaced by MATERIAL_EXTENSION_EXCLUDED for real exclusions and dropped for combinations the specs allow; an extension object extensionsUsed does not declare, or one that is no object, is absent (UNDECLARED_EXTENSION or TYPE_MISMATCH reports it), where the Khronos validator counts it.",
    keeps: doubtful_combination,
}]);

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

/// Whether the specification-gloss or unlit extension at the finding's pointer shares its
/// material with an extension whose compatibility no spec states.
fn doubtful_combination(ctx: &Context, finding: &Diagnostic) -> bool {
    let Some((extensions, standalone)) = finding.pointer().and_then(|p| p.rsplit_once('/')) else {
        return true;
    };
    let others = ctx.root.pointer(extensions).and_then(Node::as_object);
    (others.into_iter().flat_map(|o| o.keys()))
        .filter(|other| *other != standalone)
        .any(|other| combination(standalone, other) == Combination::Unknown)
}

fn check(ctx: &mut Context) {
    for (_, pointer, material) in ctx.objects("materials") {
        let Some(extensions) = material.get("extensions").and_then(Node::as_object) else {
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
