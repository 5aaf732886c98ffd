//! Anisotropy materials need a tangent space even without an anisotropy texture.

use super::{Rule, Run, Supersession};
use crate::check::context::{unsigned, Context};
use crate::diagnostic::{khronos, Diagnostic, Severity};
use crate::document::Node;

pub(super) const RULE: Rule = Rule::new(
    "ANISOTROPY_NO_TANGENT_SPACE",
    Severity::Error,
    "materials",
    "A primitive uses a KHR_materials_anisotropy material but has no NORMAL + TANGENT and its material no normal texture.",
    DOC,
    Run::document(check),
)
.superseding(&[Supersession {
    code: khronos::UNUSED_MESH_TANGENT,
    why: "Not reported on anisotropy materials: KHR_materials_anisotropy reads the tangent even without an anisotropyTexture. Nor where the material carries an extension gltfmat does not read, which may need the tangent (KHR_materials_coat's coatNormalTexture and coat anisotropy do).",
    keeps: surely_unused,
}]);

const DOC: &str = "\
## What it does
Reports a mesh primitive whose material uses `KHR_materials_anisotropy`, has no texture that
already demands a tangent space (normal, clearcoat normal or anisotropy texture), and which
provides no `NORMAL` + `TANGENT` attributes. The pointer is the primitive's `material`.

## Why
The anisotropy direction is defined in the tangent frame, with or without an
`anisotropyTexture` (`anisotropyRotation` rotates the tangent). The spec says the material
MUST have a defined tangent space. The Khronos validator derives the tangent requirement from
textures only, so an untextured anisotropy material without tangents passes silently and
each engine invents its own direction. When a texture demands tangents, the Khronos codes
`MESH_PRIMITIVE_NO_TANGENT_SPACE` / `MESH_PRIMITIVE_GENERATED_TANGENT_SPACE` already apply
and this rule stays silent.

Spec: KHR_materials_anisotropy, \"Anisotropy\" (tangent space MUST be defined).

## Example
```json
{\"materials\": [{\"extensions\": {\"KHR_materials_anisotropy\": {\"anisotropyStrength\": 0.6}}}],
 \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1}, \"material\": 0}]}]}
```
";

/// Whether the primitive of an unused TANGENT has a material that surely does not read it:
/// without KHR_materials_anisotropy and without an extension the profile does not read.
fn surely_unused(ctx: &Context, finding: &Diagnostic) -> bool {
    let primitive = (finding.pointer())
        .and_then(|p| p.strip_suffix("/attributes/TANGENT"))
        .and_then(|p| ctx.root.pointer(p));
    let material = primitive.and_then(|p| unsigned(p, "material"));
    !material
        .and_then(|m| ctx.material_needs.get(&(m as usize)))
        .is_some_and(|needs| needs.anisotropy || needs.unread_extension)
}

fn check(ctx: &mut Context) {
    for (_, mesh_pointer, mesh) in ctx.objects("meshes") {
        let Some(primitives) = mesh.get("primitives").and_then(Node::as_array) else {
            continue;
        };
        for (p, primitive) in primitives.iter().enumerate() {
            let Some(needs) =
                unsigned(primitive, "material").and_then(|m| ctx.material_needs.get(&(m as usize)))
            else {
                continue;
            };
            let has = |name: &str| {
                primitive
                    .get("attributes")
                    .and_then(|a| a.get(name))
                    .is_some()
            };
            if needs.anisotropy && !needs.needs_tangent && !(has("NORMAL") && has("TANGENT")) {
                ctx.emit(
                    RULE.code(),
                    format!("{mesh_pointer}/primitives/{p}/material"),
                    "The anisotropy material needs a tangent space, but the primitive has no NORMAL + TANGENT and the material no normal texture to generate one from.",
                );
            }
        }
    }
}
