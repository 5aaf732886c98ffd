//! Material and texture vocabulary shared by the checker, the converter and the evaluator.

use super::unsigned;
use serde_json::Value;

/// Every image a texture may sample, in the order a viewer prefers them: `source`, then each
/// extension's `source` (KHR_texture_basisu, EXT_texture_webp, …).
pub fn texture_images(texture: &Value) -> impl Iterator<Item = u64> + '_ {
    let extensions = texture
        .get("extensions")
        .and_then(Value::as_object)
        .into_iter()
        .flat_map(|e| e.values());
    std::iter::once(texture)
        .chain(extensions)
        .filter_map(|holder| unsigned(holder, "source"))
}

/// The KHR_texture_transform object of a textureInfo.
pub fn texture_transform(info: &Value) -> Option<&Value> {
    info.get("extensions")?.get("KHR_texture_transform")
}

/// The texCoord set a textureInfo reads: KHR_texture_transform's `texCoord` override when
/// present, else its own `texCoord`, else 0.
pub fn effective_texcoord(info: &Value) -> u64 {
    texture_transform(info)
        .and_then(|t| unsigned(t, "texCoord"))
        .or_else(|| unsigned(info, "texCoord"))
        .unwrap_or(0)
}

/// The archived specular-glossiness extension.
pub const SPEC_GLOSS: &str = "KHR_materials_pbrSpecularGlossiness";
/// The unlit extension.
pub const UNLIT: &str = "KHR_materials_unlit";

/// The material extensions that extend the metallic-roughness BRDF: each one's README
/// excludes KHR_materials_pbrSpecularGlossiness and KHR_materials_unlit on the same material.
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
