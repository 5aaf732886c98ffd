//! A KTX2 texture sampled with mipmaps that does not store them.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::gltf::unsigned;

pub(super) const RULE: Rule = Rule::new(
    "KTX2_MIPMAPS_MISSING",
    Severity::Warning,
    "channels",
    "A KTX2 texture minified through mipmaps (or with no sampler) stores fewer than its full mip chain.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a texture whose KHR_texture_basisu image is a KTX2 with fewer mip levels than its size
needs down to 1×1 (levelCount 0 or 1, say), when the texture has no sampler, or its sampler's
`minFilter` is a mipmap filter (9984–9987) or absent (viewers then pick a mipmap filter).

## Why
KHR_texture_basisu: \"When a texture refers to a sampler with mipmap minification or when the
sampler is undefined, the KTX image SHOULD contain a full mip pyramid.\" Basis Universal
textures cannot have mipmaps generated from their compressed blocks: engines decompress,
generate and re-upload them (slow, and larger in GPU memory), or sample level 0 only, which
shimmers as the surface recedes. Encode with mipmaps (`basisu -mipmap`, `toktx --genmipmap`).

## Example
A texture `{\"extensions\": {\"KHR_texture_basisu\": {\"source\": 0}}}` with no sampler, whose
1024×1024 KTX2 holds one level.
";

/// minFilter values that read mipmaps: NEAREST_MIPMAP_NEAREST … LINEAR_MIPMAP_LINEAR.
const MIPMAP_FILTERS: std::ops::RangeInclusive<u64> = 9984..=9987;

fn check(ctx: &mut Context) {
    let textures = ctx.items("textures");
    let samplers = ctx.items("samplers");
    for (index, texture) in textures.iter().enumerate() {
        let source = texture
            .get("extensions")
            .and_then(|e| e.get("KHR_texture_basisu"))
            .and_then(|b| unsigned(b, "source"));
        let Some(info) = source.and_then(|i| ctx.images.get(i as usize)?.as_ref()) else {
            continue;
        };
        let Some(layout) = info.ktx2.as_ref() else {
            continue;
        };
        if layout.levels >= info.full_mip_levels() {
            continue;
        }
        let min_filter = unsigned(texture, "sampler").map(|s| {
            samplers
                .get(s as usize)
                .and_then(|s| unsigned(s, "minFilter"))
        });
        let mipmapped = match min_filter {
            None | Some(None) => true,
            Some(Some(filter)) => MIPMAP_FILTERS.contains(&filter),
        };
        if mipmapped {
            let message = format!(
                "Texture {index} is minified through mipmaps but its KTX2 image ({}×{}) stores {} of its {} mip levels.",
                info.width,
                info.height,
                layout.levels,
                info.full_mip_levels()
            );
            ctx.emit(RULE.code(), format!("/textures/{index}"), message);
        }
    }
}
