//! Material and texture vocabulary shared by the checker, the converter and the evaluator:
//! texture sources and transforms, every texture slot with the channels it reads and their
//! colour space, and which material extensions exclude each other.

use super::{unsigned, Json};

/// Every image a texture may sample: `source`, then each extension's `source`
/// (KHR_texture_basisu, EXT_texture_webp, …).
pub(crate) fn texture_images<'a, J: Json<'a>>(texture: J) -> impl Iterator<Item = u64> + 'a {
    let extensions = (texture.get("extensions").into_iter()).flat_map(J::member_values);
    std::iter::once(texture)
        .chain(extensions)
        .filter_map(|holder| unsigned(holder, "source"))
}

/// The image-format extensions whose images gltfmat decodes, in the order it prefers them.
const DRAWN_EXTENSIONS: [&str; 2] = ["KHR_texture_basisu", "EXT_texture_webp"];

/// The image a viewer that supports KHR_texture_basisu and EXT_texture_webp draws for a
/// texture: such an extension's `source` (the fallback `source` is for viewers without it),
/// else `source`, else any other extension's.
pub(crate) fn drawn_image<'a, J: Json<'a>>(texture: J) -> Option<u64> {
    let extensions = texture.get("extensions");
    let known =
        (DRAWN_EXTENSIONS.iter()).find_map(|name| unsigned(extensions?.get(name)?, "source"));
    known.or_else(|| texture_images(texture).next())
}

/// The KHR_texture_transform object of a textureInfo.
pub(crate) fn texture_transform<'a, J: Json<'a>>(info: J) -> Option<J> {
    info.get("extensions")?.get("KHR_texture_transform")
}

/// The UV matrix a textureInfo applies, row-major `[a, b, c, d, e, f]` for
/// `(a·u + b·v + c, d·u + e·v + f)`: KHR_texture_transform's T · R · S, the identity without it.
pub(crate) fn uv_transform<'a, J: Json<'a>>(info: J) -> [f64; 6] {
    let Some(t) = texture_transform(info) else {
        return [1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    };
    let pair = |key: &str, default: [f64; 2]| {
        t.get(key).map_or(default, |a| {
            [0, 1].map(|i| a.item(i).and_then(J::as_f64).unwrap_or(default[i]))
        })
    };
    let [ox, oy] = pair("offset", [0.0, 0.0]);
    let [sx, sy] = pair("scale", [1.0, 1.0]);
    let r = t.get("rotation").and_then(J::as_f64).unwrap_or(0.0);
    let (s, c) = r.sin_cos();
    [c * sx, s * sy, ox, -s * sx, c * sy, oy]
}

/// The texCoord set a textureInfo reads: KHR_texture_transform's `texCoord` override when
/// present, else its own `texCoord`, else 0.
pub(crate) fn effective_texcoord<'a>(info: impl Json<'a>) -> u64 {
    texture_transform(info)
        .and_then(|t| unsigned(t, "texCoord"))
        .or_else(|| unsigned(info, "texCoord"))
        .unwrap_or(0)
}

/// The archived specular-glossiness extension.
pub(crate) const SPEC_GLOSS: &str = "KHR_materials_pbrSpecularGlossiness";
/// The unlit extension.
pub(crate) const UNLIT: &str = "KHR_materials_unlit";

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
pub(crate) enum Combination {
    Excluded,
    Allowed,
    Unknown,
}

pub(crate) fn combination(standalone: &str, other: &str) -> Combination {
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

/// Colour channels as a bit mask.
pub(crate) type Channels = u8;
pub(crate) const R: Channels = 1;
pub(crate) const G: Channels = 2;
pub(crate) const B: Channels = 4;
pub(crate) const A: Channels = 8;
pub(crate) const RGB: Channels = R | G | B;

/// Every texture slot a material can have: where it sits and which channels it reads how.
/// This is the one table the tangent, channel and colour-space rules read; the channel and
/// transfer columns come from each extension's spec (summarised in validator-anchors.md §5).
#[derive(Debug)]
pub(crate) struct TextureSlot {
    pub extension: Option<&'static str>,
    /// Core slots nested in `pbrMetallicRoughness`.
    pub in_pbr: bool,
    pub key: &'static str,
    /// Channels decoded with the sRGB transfer function (colours).
    pub srgb: Channels,
    /// Channels read as linear data.
    pub linear: Channels,
    /// Alpha is coverage, read only when the material's alphaMode is not OPAQUE.
    pub coverage_alpha: bool,
}

const fn slot(
    extension: Option<&'static str>,
    key: &'static str,
    srgb: Channels,
    linear: Channels,
) -> TextureSlot {
    TextureSlot {
        extension,
        in_pbr: false,
        key,
        srgb,
        linear,
        coverage_alpha: false,
    }
}

const fn core(key: &'static str, srgb: Channels, linear: Channels) -> TextureSlot {
    slot(None, key, srgb, linear)
}

const fn colour_with_coverage(mut slot: TextureSlot) -> TextureSlot {
    slot.coverage_alpha = true;
    slot
}

const fn in_pbr(mut slot: TextureSlot) -> TextureSlot {
    slot.in_pbr = true;
    slot
}

const ANISOTROPY: Option<&str> = Some("KHR_materials_anisotropy");
const CLEARCOAT: Option<&str> = Some("KHR_materials_clearcoat");
const DIFFUSE_TRANSMISSION: Option<&str> = Some("KHR_materials_diffuse_transmission");
const IRIDESCENCE: Option<&str> = Some("KHR_materials_iridescence");
const SPEC_GLOSS_SLOT: Option<&str> = Some(SPEC_GLOSS);
const SHEEN: Option<&str> = Some("KHR_materials_sheen");
const SPECULAR: Option<&str> = Some("KHR_materials_specular");

pub(crate) static TEXTURE_SLOTS: &[TextureSlot] = &[
    in_pbr(colour_with_coverage(core("baseColorTexture", RGB, 0))),
    in_pbr(core("metallicRoughnessTexture", 0, G | B)),
    core("normalTexture", 0, RGB),
    core("occlusionTexture", 0, R),
    core("emissiveTexture", RGB, 0),
    slot(ANISOTROPY, "anisotropyTexture", 0, RGB),
    slot(CLEARCOAT, "clearcoatTexture", 0, R),
    slot(CLEARCOAT, "clearcoatRoughnessTexture", 0, G),
    slot(CLEARCOAT, "clearcoatNormalTexture", 0, RGB),
    slot(DIFFUSE_TRANSMISSION, "diffuseTransmissionTexture", 0, A),
    slot(
        DIFFUSE_TRANSMISSION,
        "diffuseTransmissionColorTexture",
        RGB,
        0,
    ),
    slot(IRIDESCENCE, "iridescenceTexture", 0, R),
    slot(IRIDESCENCE, "iridescenceThicknessTexture", 0, G),
    colour_with_coverage(slot(SPEC_GLOSS_SLOT, "diffuseTexture", RGB, 0)),
    slot(SPEC_GLOSS_SLOT, "specularGlossinessTexture", RGB, A),
    slot(SHEEN, "sheenColorTexture", RGB, 0),
    slot(SHEEN, "sheenRoughnessTexture", 0, A),
    slot(SPECULAR, "specularTexture", 0, A),
    slot(SPECULAR, "specularColorTexture", RGB, 0),
    slot(
        Some("KHR_materials_transmission"),
        "transmissionTexture",
        0,
        R,
    ),
    slot(Some("KHR_materials_volume"), "thicknessTexture", 0, G),
];

impl TextureSlot {
    /// Normal maps: they need a tangent space, and their texels are unit vectors.
    pub(crate) fn is_normal(&self) -> bool {
        matches!(self.key, "normalTexture" | "clearcoatNormalTexture")
    }

    /// The channels this slot reads in `material`: (sRGB, linear).
    pub(crate) fn reads<'a, J: Json<'a>>(&self, material: J) -> (Channels, Channels) {
        let mode = material.get("alphaMode").and_then(J::as_str);
        let coverage = self.coverage_alpha && mode.is_some_and(|m| m != "OPAQUE");
        (self.srgb, self.linear | if coverage { A } else { 0 })
    }

    /// The slot's pointer relative to its material.
    pub(crate) fn pointer(&self) -> String {
        match (self.extension, self.in_pbr) {
            (Some(ext), _) => format!("/extensions/{ext}/{}", self.key),
            (None, true) => format!("/pbrMetallicRoughness/{}", self.key),
            (None, false) => format!("/{}", self.key),
        }
    }

    /// The slot's textureInfo object in a material, if present.
    pub(crate) fn lookup<'a, J: Json<'a>>(&self, material: J) -> Option<J> {
        let parent = match (self.extension, self.in_pbr) {
            (Some(ext), _) => material.get("extensions")?.get(ext)?,
            (None, true) => material.get("pbrMetallicRoughness")?,
            (None, false) => material,
        };
        parent.get(self.key).filter(|v| v.is_object())
    }
}
