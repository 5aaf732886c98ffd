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
