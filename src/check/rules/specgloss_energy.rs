//! Specular-glossiness factors that reflect more light than they receive.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::check::khronos::materials::extension;
use crate::diagnostic::Severity;
use serde_json::Value;

pub const RULE: Rule = Rule::new(
    "PBR_SPECGLOSS_ENERGY_GAIN",
    Severity::Hint,
    "plausibility",
    "A specular-glossiness material's diffuse plus max(specular) exceeds 1: it reflects more light than it receives.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
For `KHR_materials_pbrSpecularGlossiness` materials without diffuse or specular-glossiness
textures, reports a `diffuseFactor` channel that, added to the largest `specularFactor`
channel, exceeds 1. (With textures the factors are only upper bounds, so nothing is
reported.)

## Why
In the specular-glossiness model the diffuse and specular lobes are added without energy
conservation: the surface reflects up to diffuse + specular of the incoming light. Above 1 it
glows. It is also what limits a conversion to metal-roughness: `gltfmat upgrade` scales the
diffuse by (1 − max specular), and this hint says the source already broke the budget.

## Example
```json
{\"KHR_materials_pbrSpecularGlossiness\": {\"diffuseFactor\": [0.9, 0.9, 0.9, 1], \"specularFactor\": [0.5, 0.5, 0.5]}}
```
";

fn floats(object: &Value, key: &str, default: &[f64]) -> Vec<f64> {
    object
        .get(key)
        .and_then(Value::as_array)
        .map(|list| list.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_else(|| default.to_vec())
}

fn check(ctx: &mut Context) {
    let name = "KHR_materials_pbrSpecularGlossiness";
    for (_, pointer, material) in ctx.objects("materials") {
        let Some(spec_gloss) = extension(material, name) else {
            continue;
        };
        let textured = ["diffuseTexture", "specularGlossinessTexture"]
            .iter()
            .any(|key| spec_gloss.get(key).is_some());
        if textured {
            continue;
        }
        let diffuse = floats(spec_gloss, "diffuseFactor", &[1.0; 4]);
        let specular = floats(spec_gloss, "specularFactor", &[1.0; 3]);
        let max_specular = specular.iter().copied().fold(0.0, f64::max);
        let brightest = diffuse.iter().take(3).copied().fold(0.0, f64::max);
        if brightest + max_specular > 1.0 {
            ctx.emit(
                RULE.code(),
                format!("{pointer}/extensions/{name}"),
                format!("Diffuse {brightest} plus specular {max_specular} reflects more light than it receives ({:.2} > 1).", brightest + max_specular),
            );
        }
    }
}
