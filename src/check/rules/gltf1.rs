//! glTF 1.0 input: recognised, its PBR material blocks validated, and the user pointed at
//! `gltfmat upgrade`.

use super::{Rule, Run};
use crate::check::context::{member, Context};
use crate::check::schema;
use crate::diagnostic::khronos;
use crate::diagnostic::Severity;
use crate::document::Node;
use crate::legacy::pbr::{self, Model, EXTENSION_NAMES};

pub(crate) const RULE: Rule = Rule::new(
    "GLTF_1_0_ASSET",
    Severity::Error,
    "gltf1",
    "The asset is glTF 1.0: run `gltfmat upgrade` to convert it to glTF 2.0.",
    DOC,
    Run::CORE,
);

const DOC: &str = "\
## What it does
Recognises a glTF 1.0 document (`asset.version` \"1.0\", or a GLB with version 1) and tells the
user to convert it with `gltfmat upgrade`. In the default profile the 2.0 passes do not run
on it; its PBR material blocks are validated instead (see `GLTF_1_0_PBR_MATERIAL`).

## Why
glTF 1.0 is not loadable by today's engines; its objects are keyed by id and its materials
are shader techniques. Reporting hundreds of 2.0 schema errors would hide the one fix.
`--profile khronos` reports what the Khronos validator reports instead.

## Example
```json
{\"asset\": {\"version\": \"1.0\"}, \"materials\": {\"mat\": {\"technique\": \"t\"}}}
```
";

pub(crate) const PBR_RULE: Rule = Rule::new(
    "GLTF_1_0_PBR_MATERIAL",
    Severity::Info,
    "gltf1",
    "A glTF 1.0 material uses a WEB3D / KHR / FRAUNHOFER / EXT _materials_pbr draft; says what `gltfmat upgrade` makes of it.",
    PBR_DOC,
    Run::CORE,
);

const PBR_DOC: &str = "\
## What it does
For each glTF 1.0 material with a `WEB3D_materials_pbr`, `KHR_materials_pbr`,
`FRAUNHOFER_materials_pbr` or `EXT_materials_pbr` block, validates the block against
gltfmat's schema for the drafts (`schema/gltf1/materials_pbr.schema.json`: the `technique` or
`materialModel` value, member names, 0–1 ranges) with the usual schema codes, reports texture
ids that do not resolve (`UNRESOLVED_REFERENCE`), a block that names no model
(`UNDEFINED_PROPERTY`), and then this info saying which model was found and what
`gltfmat upgrade` will convert it to.

A specular-glossiness block can be read three ways (the drafts' Appendix, the 2016 Appendix
alone, the January 2017 example shader), which differ by several ΔE on most materials: the
ambiguity is the drafts'. `gltfmat upgrade` converts under one of them, the Appendix by default
(the reading the ratified KHR_materials_pbrSpecularGlossiness kept; `--draft-reading` picks
another), is exact under it, and prints the other readings' distance beside its proof.

## Why
These drafts were never ratified and no engine reads them today; gltf-pipeline upgrades the
file around them and leaves the material with dangling string ids. Knowing before the upgrade
which blocks are malformed saves a round trip.

## Example
```json
{\"materials\": {\"gold\": {\"extensions\": {\"FRAUNHOFER_materials_pbr\": {
  \"materialModel\": \"PBR_metal_roughness\", \"values\": {\"metallicFactor\": 1.5}}}}}}
```
reports `VALUE_NOT_IN_RANGE` at `/materials/gold/extensions/FRAUNHOFER_materials_pbr/values/metallicFactor`.
";

/// The whole 1.0 check (default profile).
pub(crate) fn check(ctx: &mut Context) {
    ctx.emit(
        RULE.code(),
        "/asset/version",
        "This is a glTF 1.0 asset. Run `gltfmat upgrade IN -o OUT` to convert it to glTF 2.0.",
    );
    let Some(materials) = ctx.root.get("materials").and_then(Node::as_object) else {
        return;
    };
    for (id, material) in materials {
        let pointer = member("/materials", id);
        for name in EXTENSION_NAMES {
            if let Some(block) = material.get("extensions").and_then(|e| e.get(*name)) {
                check_pbr_block(ctx, name, block, &format!("{pointer}/extensions/{name}"));
            }
        }
    }
}

fn check_pbr_block(ctx: &mut Context, name: &'static str, block: Node, pointer: &str) {
    let found = schema::validate_gltf1_pbr(block, pointer);
    ctx.diagnostics.extend(found);
    if pbr::declared_model(block).is_none() {
        ctx.emit(
            khronos::UNDEFINED_PROPERTY,
            pointer,
            "Property 'materialModel' (or the July 2016 'technique') must be defined.",
        );
    }
    let textures = ctx.root.get("textures");
    if let Some(values) = block.get("values").and_then(Node::as_object) {
        for (key, value) in values {
            let Some(id) = value.as_str() else { continue };
            if textures.and_then(|t| t.get(id)).is_none() {
                ctx.emit(
                    khronos::UNRESOLVED_REFERENCE,
                    member(&format!("{pointer}/values"), key),
                    format!("Unresolved reference: {id}."),
                );
            }
        }
    }
    if let Some(pbr) = pbr::parse(name, block) {
        let target = match pbr.model {
            Model::MetalRoughness => "core pbrMetallicRoughness (metallic moved from R to B)",
            Model::SpecularGlossiness => {
                "metal-roughness + KHR_materials_specular + KHR_materials_ior (or KHR_materials_pbrSpecularGlossiness with --specular-glossiness extension)"
            }
        };
        ctx.emit(
            PBR_RULE.code(),
            pointer,
            format!(
                "{name} {:?} material: `gltfmat upgrade` converts it to {target}.",
                pbr.model
            ),
        );
    }
}
