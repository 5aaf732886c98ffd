//! Textures and materials: references, texCoord sets and tangent needs recorded for the mesh
//! pass, and the Khronos material-extension rules.

use super::context::{member, number, unsigned, Context, MaterialNeeds};
use super::resources::declared_mime;
use serde_json::Value;

/// Every texture slot a material can have: where it sits and how it is sampled.
#[derive(Debug)]
pub struct TextureSlot {
    pub extension: Option<&'static str>,
    /// Core slots nested in `pbrMetallicRoughness`.
    pub in_pbr: bool,
    pub key: &'static str,
    pub is_normal: bool,
}

const fn slot(extension: Option<&'static str>, in_pbr: bool, key: &'static str) -> TextureSlot {
    let is_normal = matches!(key.as_bytes(), b"normalTexture" | b"clearcoatNormalTexture");
    TextureSlot {
        extension,
        in_pbr,
        key,
        is_normal,
    }
}

pub static TEXTURE_SLOTS: &[TextureSlot] = &[
    slot(None, true, "baseColorTexture"),
    slot(None, true, "metallicRoughnessTexture"),
    slot(None, false, "normalTexture"),
    slot(None, false, "occlusionTexture"),
    slot(None, false, "emissiveTexture"),
    slot(Some("KHR_materials_anisotropy"), false, "anisotropyTexture"),
    slot(Some("KHR_materials_clearcoat"), false, "clearcoatTexture"),
    slot(
        Some("KHR_materials_clearcoat"),
        false,
        "clearcoatRoughnessTexture",
    ),
    slot(
        Some("KHR_materials_clearcoat"),
        false,
        "clearcoatNormalTexture",
    ),
    slot(
        Some("KHR_materials_diffuse_transmission"),
        false,
        "diffuseTransmissionTexture",
    ),
    slot(
        Some("KHR_materials_diffuse_transmission"),
        false,
        "diffuseTransmissionColorTexture",
    ),
    slot(
        Some("KHR_materials_iridescence"),
        false,
        "iridescenceTexture",
    ),
    slot(
        Some("KHR_materials_iridescence"),
        false,
        "iridescenceThicknessTexture",
    ),
    slot(
        Some("KHR_materials_pbrSpecularGlossiness"),
        false,
        "diffuseTexture",
    ),
    slot(
        Some("KHR_materials_pbrSpecularGlossiness"),
        false,
        "specularGlossinessTexture",
    ),
    slot(Some("KHR_materials_sheen"), false, "sheenColorTexture"),
    slot(Some("KHR_materials_sheen"), false, "sheenRoughnessTexture"),
    slot(Some("KHR_materials_specular"), false, "specularTexture"),
    slot(
        Some("KHR_materials_specular"),
        false,
        "specularColorTexture",
    ),
    slot(
        Some("KHR_materials_transmission"),
        false,
        "transmissionTexture",
    ),
    slot(Some("KHR_materials_volume"), false, "thicknessTexture"),
];

impl TextureSlot {
    /// The slot's pointer relative to its material.
    pub fn pointer(&self) -> String {
        match (self.extension, self.in_pbr) {
            (Some(ext), _) => format!("/extensions/{ext}/{}", self.key),
            (None, true) => format!("/pbrMetallicRoughness/{}", self.key),
            (None, false) => format!("/{}", self.key),
        }
    }

    /// The slot's textureInfo object in a material, if present.
    pub fn lookup<'v>(&self, material: &'v Value) -> Option<&'v Value> {
        let parent = match (self.extension, self.in_pbr) {
            (Some(ext), _) => material.get("extensions")?.get(ext)?,
            (None, true) => material.get("pbrMetallicRoughness")?,
            (None, false) => material,
        };
        parent.get(self.key).filter(|v| v.is_object())
    }
}

/// The texCoord a textureInfo reads, with KHR_texture_transform's override applied.
pub fn effective_texcoord(info: &Value) -> u64 {
    info.get("extensions")
        .and_then(|e| e.get("KHR_texture_transform"))
        .and_then(|t| unsigned(t, "texCoord"))
        .or_else(|| unsigned(info, "texCoord"))
        .unwrap_or(0)
}

pub fn check_textures(ctx: &mut Context) {
    for (_, pointer, texture) in ctx.objects("textures") {
        ctx.reference(texture, "sampler", &pointer, "samplers");
        if let Some(image) = ctx.reference(texture, "source", &pointer, "images") {
            check_texture_source_mime(
                ctx,
                image,
                &member(&pointer, "source"),
                &["image/jpeg", "image/png"],
            );
        }
        let webp = texture
            .get("extensions")
            .and_then(|e| e.get("EXT_texture_webp"));
        if let Some(webp) = webp.filter(|w| w.is_object()) {
            let webp_pointer = format!("{pointer}/extensions/EXT_texture_webp");
            if let Some(image) = ctx.reference(webp, "source", &webp_pointer, "images") {
                check_texture_source_mime(
                    ctx,
                    image,
                    &member(&webp_pointer, "source"),
                    &["image/webp"],
                );
            }
        }
    }
}

fn check_texture_source_mime(ctx: &mut Context, image: usize, pointer: &str, valid: &[&str]) {
    let declared = declared_mime(&ctx.items("images")[image]).or_else(|| {
        ctx.images[image]
            .as_ref()
            .map(|i| i.format.mime_type().to_string())
    });
    if let Some(mime) = declared.filter(|m| !valid.contains(&m.as_str())) {
        ctx.emit(
            "TEXTURE_INVALID_IMAGE_MIME_TYPE",
            pointer,
            format!("Invalid MIME type '{mime}' for the texture source. Valid MIME types are {valid:?}."),
        );
    }
}

pub fn check_materials(ctx: &mut Context) {
    ctx.material_needs = vec![MaterialNeeds::default(); ctx.items("materials").len()];
    for (i, pointer, material) in ctx.objects("materials") {
        let needs = texture_needs(ctx, material, &pointer);
        ctx.material_needs[i] = needs;
        check_alpha_cutoff(ctx, material, &pointer);
        check_extension_rules(ctx, material, &pointer);
    }
}

fn texture_needs(ctx: &mut Context, material: &Value, pointer: &str) -> MaterialNeeds {
    let mut needs = MaterialNeeds::default();
    for slot in TEXTURE_SLOTS {
        let Some(info) = slot.lookup(material) else {
            continue;
        };
        let info_pointer = format!("{pointer}{}", slot.pointer());
        ctx.reference(info, "index", &info_pointer, "textures");
        needs.texcoords.insert(effective_texcoord(info));
        if slot.is_normal || slot.key == "anisotropyTexture" {
            needs.needs_tangent = true;
        }
    }
    needs.can_generate_tangent = material.get("normalTexture").is_some_and(Value::is_object);
    needs.anisotropy = extension(material, "KHR_materials_anisotropy").is_some();
    needs
}

fn extension<'v>(material: &'v Value, name: &str) -> Option<&'v Value> {
    material
        .get("extensions")?
        .get(name)
        .filter(|v| v.is_object())
}

fn check_alpha_cutoff(ctx: &mut Context, material: &Value, pointer: &str) {
    let mode = material
        .get("alphaMode")
        .and_then(Value::as_str)
        .unwrap_or("OPAQUE");
    if material.get("alphaCutoff").is_some() && mode != "MASK" {
        ctx.emit(
            "MATERIAL_ALPHA_CUTOFF_INVALID_MODE",
            member(pointer, "alphaCutoff"),
            "Alpha cutoff is supported only for 'MASK' alpha mode.",
        );
    }
}

fn check_extension_rules(ctx: &mut Context, material: &Value, pointer: &str) {
    let ext_pointer = |name: &str| format!("{pointer}/extensions/{name}");
    let Some(extensions) = material.get("extensions").and_then(Value::as_object) else {
        return;
    };
    if extensions.len() > 1 {
        for standalone in ["KHR_materials_pbrSpecularGlossiness", "KHR_materials_unlit"] {
            if extensions.contains_key(standalone) {
                ctx.emit(
                    "MULTIPLE_EXTENSIONS",
                    ext_pointer(standalone),
                    "This extension may be incompatible with other extensions for the object.",
                );
            }
        }
    }
    let strength = extension(material, "KHR_materials_emissive_strength")
        .and_then(|e| e.get("emissiveStrength"));
    if strength.and_then(Value::as_f64).is_some_and(|s| s >= 0.0) {
        let emissive = material.get("emissiveFactor").and_then(Value::as_array);
        let zero = emissive.is_none_or(|f| f.iter().all(|c| c.as_f64() == Some(0.0)));
        if zero {
            ctx.emit(
                "KHR_MATERIALS_EMISSIVE_STRENGTH_ZERO_FACTOR",
                ext_pointer("KHR_materials_emissive_strength"),
                "Emissive strength has no effect when the emissive factor is zero or undefined.",
            );
        }
    }
    if let Some(volume) = extension(material, "KHR_materials_volume") {
        // An extension this validator does not know may well be the one that transmits.
        let transmits = extensions.keys().any(|name| {
            matches!(
                name.as_str(),
                "KHR_materials_transmission" | "KHR_materials_diffuse_transmission"
            ) || !name.starts_with("KHR_materials_")
        });
        if !transmits {
            ctx.emit(
                "KHR_MATERIALS_VOLUME_NO_TRANSMISSION",
                ext_pointer("KHR_materials_volume"),
                "The volume extension needs to be combined with an extension that allows light to transmit through the surface.",
            );
        }
        let thick = number(volume, "thicknessFactor", 0.0) > 0.0;
        if thick && material.get("doubleSided").and_then(Value::as_bool) == Some(true) {
            ctx.emit(
                "KHR_MATERIALS_VOLUME_DOUBLE_SIDED",
                ext_pointer("KHR_materials_volume"),
                "The volume extension should not be used with double-sided materials.",
            );
        }
    }
    if extension(material, "KHR_materials_dispersion").is_some()
        && !extensions.contains_key("KHR_materials_volume")
    {
        ctx.emit(
            "KHR_MATERIALS_DISPERSION_NO_VOLUME",
            ext_pointer("KHR_materials_dispersion"),
            "The dispersion extension needs to be combined with the volume extension.",
        );
    }
    if let Some(iridescence) = extension(material, "KHR_materials_iridescence") {
        let p = ext_pointer("KHR_materials_iridescence");
        let has_texture = iridescence.get("iridescenceThicknessTexture").is_some();
        if iridescence.get("iridescenceThicknessMinimum").is_some() && !has_texture {
            ctx.emit(
                "KHR_MATERIALS_IRIDESCENCE_THICKNESS_RANGE_WITHOUT_TEXTURE",
                member(&p, "iridescenceThicknessMinimum"),
                "Thickness minimum has no effect when a thickness texture is not defined.",
            );
        }
        let min = number(iridescence, "iridescenceThicknessMinimum", 100.0);
        let max = number(iridescence, "iridescenceThicknessMaximum", 400.0);
        if has_texture && min == max {
            ctx.emit(
                "KHR_MATERIALS_IRIDESCENCE_THICKNESS_TEXTURE_UNUSED",
                member(&p, "iridescenceThicknessTexture"),
                "Thickness texture has no effect when the thickness minimum is equal to the thickness maximum.",
            );
        }
    }
    check_texcoord_pairs(ctx, material, pointer);
}

/// Normal and anisotropy / clearcoat-normal textures should share texCoords. The Khronos
/// validator compares the raw `texCoord`; gltfmat's default profile applies the
/// KHR_texture_transform override, which is what a renderer samples.
fn check_texcoord_pairs(ctx: &mut Context, material: &Value, pointer: &str) {
    let Some(normal) = material.get("normalTexture").filter(|n| n.is_object()) else {
        return;
    };
    let khronos = ctx.is_khronos();
    let texcoord = |info: &Value| {
        if khronos {
            unsigned(info, "texCoord").unwrap_or(0)
        } else {
            effective_texcoord(info)
        }
    };
    let pairs = [
        (
            "KHR_materials_anisotropy",
            "anisotropyTexture",
            "KHR_MATERIALS_ANISOTROPY_ANISOTROPY_TEXTURE_TEXCOORD",
            "Normal and anisotropy textures should use the same texture coords.",
        ),
        (
            "KHR_materials_clearcoat",
            "clearcoatNormalTexture",
            "KHR_MATERIALS_CLEARCOAT_CLEARCOAT_NORMAL_TEXTURE_TEXCOORD",
            "Normal and clearcoat normal textures should use the same texture coords.",
        ),
    ];
    let normal_set = texcoord(normal);
    for (ext, key, code, message) in pairs {
        let Some(info) = extension(material, ext)
            .and_then(|e| e.get(key))
            .filter(|i| i.is_object())
        else {
            continue;
        };
        if texcoord(info) != normal_set {
            ctx.emit(code, format!("{pointer}/extensions/{ext}/{key}"), message);
        }
    }
}
