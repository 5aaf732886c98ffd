//! 1.0 materials → 2.0: the PBR drafts, KHR_materials_common, technique values, technique
//! render states, and the 1.0 default material.

use crate::document::Node;
use crate::gltf::color::srgb_to_linear;
use crate::legacy::blend::{self, technique_blend, Blend};
use crate::legacy::pbr::{self, LegacyPbr, Model};
use crate::shade::sample::Sampler;
use crate::upgrade::builder::{pointer, Builder};
use crate::upgrade::fit;
use crate::upgrade::json::Items;
use crate::upgrade::rebake;
use crate::upgrade::spec_gloss::{self, Slot};
use crate::upgrade::{NoteKind, SpecularGlossiness, UpgradeError};
use serde_json::{json, Map, Value};
use std::sync::Arc;

pub(crate) fn convert(
    builder: &mut Builder,
    id: &str,
    material: Node,
) -> Result<Value, UpgradeError> {
    let at = pointer("materials", id);
    // Nothing says what a material that is no object draws: it is refused, not invented.
    if !material.is_object() {
        return Err(UpgradeError::Invalid {
            pointer: at,
            reason: "the material is not an object, so it says nothing to convert".into(),
        });
    }
    let name = material.get("name").and_then(Node::as_str).unwrap_or(id);
    let mut out = Map::new();
    out.insert("name".into(), json!(name));
    apply_technique_states(builder, material, &at, &mut out);
    if let Some((extension, block)) = pbr::find(material) {
        match pbr::parse(extension, block) {
            Some(pbr) => convert_pbr(builder, &pbr, &at, &mut out)?,
            None => builder.note(
                &at,
                NoteKind::Dropped,
                format!("{extension} names an unknown model; default material written."),
            ),
        }
    } else if let Some(common) = material
        .get("extensions")
        .and_then(|e| e.get("KHR_materials_common"))
    {
        convert_common(builder, common, &at, &mut out);
    } else if material.get("technique").is_some() {
        convert_technique_values(builder, material, &at, &mut out);
    } else {
        // The 1.0 default material: constant emission of 50% grey, written to the framebuffer
        // as it is (1.0 shaders did no colour management): 0.5 as the display encodes it,
        // which a 2.0 linear factor is once linearised.
        let grey = crate::gltf::color::srgb_to_linear(0.5);
        out.insert(
            "pbrMetallicRoughness".into(),
            json!({"baseColorFactor": [grey, grey, grey, 1.0], "metallicFactor": 0.0}),
        );
        out.insert("extensions".into(), json!({"KHR_materials_unlit": {}}));
        builder.note(
            &at,
            NoteKind::Decision,
            "no technique: the 1.0 default material (50% grey as displayed, so baseColorFactor 0.214 linear, unlit).",
        );
    }
    Ok(Value::Object(out))
}

/// A technique's states decide blending, unless KHR_materials_common (used "in favor of the
/// supplied technique") says how it blends; culling is decided as the evaluator reads it
/// ([`blend::double_sided`]), and where the material says nothing, by the option.
fn apply_technique_states(
    builder: &mut Builder,
    material: Node,
    at: &str,
    out: &mut Map<String, Value>,
) {
    let common = (material.get("extensions")).and_then(|e| e.get("KHR_materials_common"));
    let technique = (material.get("technique").and_then(Node::as_str))
        .and_then(|t| builder.source.object("techniques", t))
        .filter(|_| common.is_none());
    // BLEND enabled with GL's default functions (ONE, ZERO) replaces what is behind.
    if technique.is_some_and(|t| technique_blend(t).is_some()) {
        out.insert("alphaMode".into(), json!("BLEND"));
    }
    let double_sided = blend::double_sided(builder.source, material)
        .unwrap_or(builder.options.double_sided_default);
    if double_sided {
        out.insert("doubleSided".into(), json!(true));
        builder.note(
            at,
            NoteKind::Decision,
            "doubleSided: culling is not enabled.",
        );
    }
}

/// `{index}` for a 1.0 texture id, if it resolves.
fn texture_info(builder: &Builder, id: Option<&str>) -> Option<Value> {
    let index = builder.index_of_id("textures", id?)?;
    Some(json!({"index": index}))
}

fn texture_bytes(builder: &Builder, id: Option<&str>) -> Option<Arc<crate::document::Bytes>> {
    let index = builder.index_of_id("textures", id?)?;
    Some(builder.texture_image(index)?.bytes.clone())
}

/// Adds a rebaked PNG as a new image + texture sampled like 1.0 texture `like`.
fn add_rebaked(builder: &mut Builder, bytes: Vec<u8>, like: Option<&str>, name: &str) -> Value {
    let key = (bytes, like.map(str::to_string));
    if let Some(&texture) = builder.rebaked.get(&key) {
        return json!({"index": texture});
    }
    let bytes = key.0.clone();
    let mut image = Map::new();
    image.insert("name".into(), json!(name));
    let image = builder.add_image(image, Arc::new(bytes.into()), "image/png".into(), name);
    let like = like.and_then(|id| builder.index_of_id("textures", id));
    let texture = builder.add_texture(image, like, name.to_string());
    builder.rebaked.insert(key, texture);
    json!({"index": texture})
}

fn rebake_error(at: &str, reason: String) -> UpgradeError {
    UpgradeError::Resource {
        pointer: at.to_string(),
        reason: format!("texture cannot be rebaked: {reason}"),
    }
}

fn convert_pbr(
    builder: &mut Builder,
    pbr: &LegacyPbr,
    at: &str,
    out: &mut Map<String, Value>,
) -> Result<(), UpgradeError> {
    let block = format!("{at}/extensions/{}", pbr.extension);
    for key in &pbr.unknown_keys {
        builder.note(
            &block,
            NoteKind::Dropped,
            format!("value '{key}' is not part of the {:?} model.", pbr.model),
        );
    }
    if pbr.model_source == pbr::ModelSource::Inferred {
        builder.note(
            &block,
            NoteKind::Decision,
            format!(
                "no technique/materialModel: {:?} inferred from the value names.",
                pbr.model
            ),
        );
    }
    match (pbr.model, builder.options.specular_glossiness) {
        (Model::MetalRoughness, _) => metal_rough(builder, pbr, &block, out)?,
        (Model::SpecularGlossiness, SpecularGlossiness::MetalRough) => {
            spec_gloss_as_metal_rough(builder, pbr, &block, out)?
        }
        (Model::SpecularGlossiness, SpecularGlossiness::Extension) => {
            spec_gloss_extension(builder, pbr, &block, out)
        }
    }
    let translucent_texture = pbr
        .colour_texture
        .as_deref()
        .and_then(|t| texture_bytes(builder, Some(t)))
        .is_some_and(|b| rebake::has_translucent_texels(&b));
    if pbr.colour[3] < 1.0 || translucent_texture {
        out.insert("alphaMode".into(), json!("BLEND"));
        builder.note(
            &block,
            NoteKind::Decision,
            "opacity below 1: alphaMode BLEND.",
        );
    }
    Ok(())
}

fn metal_rough(
    builder: &mut Builder,
    pbr: &LegacyPbr,
    block: &str,
    out: &mut Map<String, Value>,
) -> Result<(), UpgradeError> {
    let mut core = json!({
        "baseColorFactor": pbr.colour,
        "metallicFactor": pbr.metallic,
        "roughnessFactor": pbr.roughness,
    });
    if let Some(info) = texture_info(builder, pbr.colour_texture.as_deref()) {
        core["baseColorTexture"] = info;
    }
    if let Some(bytes) = texture_bytes(builder, pbr.data_texture.as_deref()) {
        let rebaked = rebake::metal_rough_swizzle(&bytes).map_err(|e| rebake_error(block, e))?;
        core["metallicRoughnessTexture"] = add_rebaked(
            builder,
            rebaked,
            pbr.data_texture.as_deref(),
            "metallicRoughness",
        );
        builder.note(block, NoteKind::Decision, "metallicRoughnessTexture rebaked: metallic moved from R (1.0 draft) to B (2.0); the original image is kept for its other uses.");
    }
    out.insert("pbrMetallicRoughness".into(), core);
    Ok(())
}

fn spec_gloss_as_metal_rough(
    builder: &mut Builder,
    pbr: &LegacyPbr,
    block: &str,
    out: &mut Map<String, Value>,
) -> Result<(), UpgradeError> {
    let factors = spec_gloss::Factors {
        reading: builder.options.draft_reading,
        diffuse: pbr.colour,
        specular: pbr.specular,
        glossiness: pbr.glossiness,
    };
    let mut textures = DraftTextures { builder, pbr };
    let mut converted =
        spec_gloss::to_metal_rough(&factors, &mut textures).map_err(|e| rebake_error(block, e))?;
    if pbr.colour_texture.is_none() && pbr.data_texture.is_none() {
        let decision = fit_factors(&mut builder.fits, pbr, &mut converted);
        converted.decisions.push(decision);
    }
    for decision in converted.decisions {
        builder.note(block, NoteKind::Decision, decision);
    }
    out.insert(
        "pbrMetallicRoughness".into(),
        converted.pbr_metallic_roughness,
    );
    out.insert("extensions".into(), Value::Object(converted.extensions));
    Ok(())
}

/// A factor-only draft spec-gloss material: the closed form's ΔE under the reading converted
/// to, and where it is above the proof's threshold (a reading with no exact 2.0 form) the
/// factors fitted towards that reading written instead (see `upgrade::fit`). Returns the
/// decision naming both figures.
fn fit_factors(
    fits: &mut fit::Fits,
    pbr: &LegacyPbr,
    converted: &mut spec_gloss::Converted,
) -> String {
    let [r, g, b, alpha] = pbr.colour;
    let reading = fits.reading();
    let closed = fit::Target {
        base_colour: reading.closed_form_base([r, g, b], pbr.specular).0,
        roughness: 1.0 - pbr.glossiness,
        specular_colour: pbr.specular,
    };
    let Some(outcome) = fits.fit([r, g, b], pbr.specular, pbr.glossiness, closed) else {
        return format!(
            "closed form kept, not fitted: more than {} distinct spec-gloss materials (the fits' time is bounded).",
            fit::MAX_DISTINCT_FITS
        );
    };
    let Some((target, figure)) = outcome.fitted else {
        return format!(
            "closed form kept: ΔE2000 {:.2} under the reading '{}'.",
            outcome.closed_form,
            reading.option_name()
        );
    };
    let [br, bg, bb] = target.base_colour;
    let core = &mut converted.pbr_metallic_roughness;
    core["baseColorFactor"] = json!([br, bg, bb, alpha]);
    core["roughnessFactor"] = json!(target.roughness);
    if let Some(specular) = converted.extensions.get_mut("KHR_materials_specular") {
        specular["specularColorFactor"] = json!(target.specular_colour);
    }
    format!(
        "fitted: no 2.0 material draws the reading '{}' exactly, and the closed form is ΔE2000 {:.2} from it; the factors were fitted towards it, {figure:.2} (baseColor {:.4?}, roughness {:.4}, specularColor {:.4?}).",
        reading.option_name(), outcome.closed_form, target.base_colour, target.roughness, target.specular_colour
    )
}

/// A 1.0 draft material's two textures, by their 1.0 ids, as the builder holds them.
struct DraftTextures<'b, 'p, 's, 'a> {
    builder: &'b mut Builder<'s, 'a>,
    pbr: &'p LegacyPbr,
}

impl DraftTextures<'_, '_, '_, '_> {
    fn id(&self, slot: Slot) -> Option<&str> {
        match slot {
            Slot::Diffuse => self.pbr.colour_texture.as_deref(),
            Slot::SpecularGlossiness => self.pbr.data_texture.as_deref(),
        }
    }
}

impl spec_gloss::Textures for DraftTextures<'_, '_, '_, '_> {
    fn info(&self, slot: Slot) -> Option<Value> {
        texture_info(self.builder, self.id(slot))
    }

    fn bytes(&self, slot: Slot) -> Result<Option<Arc<crate::document::Bytes>>, String> {
        Ok(texture_bytes(self.builder, self.id(slot)))
    }

    fn sampler(&self, slot: Slot) -> Sampler {
        Sampler::of(
            self.id(slot)
                .and_then(|id| self.builder.source.texture_sampler(id)),
        )
    }

    fn add_rebaked(&mut self, bytes: Vec<u8>, like: Slot, name: &str) -> Value {
        let like = self.id(like).map(str::to_string);
        add_rebaked(self.builder, bytes, like.as_deref(), name)
    }

    fn texel_fits(&mut self) -> Option<&mut fit::TexelFits> {
        Some(&mut self.builder.texel_fits)
    }

    fn rebakes(&mut self) -> &mut spec_gloss::Rebakes {
        &mut self.builder.rebakes
    }
}

fn spec_gloss_extension(
    builder: &mut Builder,
    pbr: &LegacyPbr,
    block: &str,
    out: &mut Map<String, Value>,
) {
    let mut ext = json!({
        "diffuseFactor": pbr.colour,
        "specularFactor": pbr.specular,
        "glossinessFactor": pbr.glossiness,
    });
    let mut fallback = json!({"baseColorFactor": pbr.colour, "metallicFactor": 0.0, "roughnessFactor": 1.0 - pbr.glossiness});
    if let Some(info) = texture_info(builder, pbr.colour_texture.as_deref()) {
        ext["diffuseTexture"] = info.clone();
        fallback["baseColorTexture"] = info;
    }
    if let Some(info) = texture_info(builder, pbr.data_texture.as_deref()) {
        ext["specularGlossinessTexture"] = info;
    }
    out.insert("pbrMetallicRoughness".into(), fallback);
    out.insert(
        "extensions".into(),
        json!({"KHR_materials_pbrSpecularGlossiness": ext}),
    );
    builder.note(block, NoteKind::Decision, "spec-gloss written as KHR_materials_pbrSpecularGlossiness (exact rename) with a metal-rough fallback (diffuse as base colour, metallic 0).");
}

/// An sRGB colour value of a 1.0 shading model, made linear (1.0 shaders wrote it directly
/// to an sRGB framebuffer).
pub(super) fn linear_colour(value: &Value) -> Option<[f64; 4]> {
    let list = value.as_array()?;
    let c = |i: usize, default: f64| list.get(i).and_then(Value::as_f64).unwrap_or(default);
    Some([
        srgb_to_linear(c(0, 0.0)),
        srgb_to_linear(c(1, 0.0)),
        srgb_to_linear(c(2, 0.0)),
        c(3, 1.0),
    ])
}

/// Blinn-Phong shininess n → roughness, through α = sqrt(2 / (n + 2)) and roughness = sqrt(α).
fn roughness_from_shininess(shininess: f64) -> f64 {
    (2.0 / (shininess.max(0.0) + 2.0)).sqrt().sqrt()
}

/// Shared by KHR_materials_common and technique values: diffuse (colour or texture),
/// emission, shininess.
fn lit_material(builder: &mut Builder, values: &Value, at: &str, out: &mut Map<String, Value>) {
    let mut core = json!({"metallicFactor": 0.0});
    let diffuse = values.get("diffuse").or_else(|| values.get("u_diffuse"));
    match diffuse {
        Some(Value::String(texture)) => {
            if let Some(info) = texture_info(builder, Some(texture)) {
                core["baseColorTexture"] = info;
            }
        }
        Some(colour) => {
            if let Some(c) = linear_colour(colour) {
                core["baseColorFactor"] = json!(c);
            }
        }
        None => {}
    }
    match values.get("emission") {
        Some(Value::String(texture)) => {
            if let Some(info) = texture_info(builder, Some(texture)) {
                out.insert("emissiveTexture".into(), info);
                out.insert("emissiveFactor".into(), json!([1.0, 1.0, 1.0]));
            }
        }
        Some(colour) => {
            if let Some([r, g, b, _]) =
                linear_colour(colour).filter(|c| c[..3].iter().any(|v| *v > 0.0))
            {
                out.insert("emissiveFactor".into(), json!([r, g, b]));
            }
        }
        None => {}
    }
    let shininess = values.get("shininess").and_then(Value::as_f64);
    core["roughnessFactor"] = json!(shininess.map_or(1.0, roughness_from_shininess));
    out.insert("pbrMetallicRoughness".into(), core);
    builder.note(at, NoteKind::Decision, "diffuse → base colour (linearised), emission → emissive (linearised), shininess → roughness sqrt(sqrt(2/(n+2))), metallic 0; specular and ambient are not carried over.");
}

fn convert_common(builder: &mut Builder, common: Node, at: &str, out: &mut Map<String, Value>) {
    let technique = common
        .get("technique")
        .and_then(Node::as_str)
        .unwrap_or("BLINN");
    let mut values = common
        .get("values")
        .map_or_else(|| json!({}), Node::to_value);
    if unwrap_typed_values(&mut values) {
        builder.note(
            at,
            NoteKind::Decision,
            "KHR_materials_common values in the early {type, value} form read by their value.",
        );
    }
    if technique == "CONSTANT" {
        constant_material(builder, &values, at, out);
    } else {
        lit_material(builder, &values, at, out);
    }
    let transparency = values
        .get("transparency")
        .and_then(Value::as_f64)
        .unwrap_or(1.0);
    let transparent = common
        .get("transparent")
        .and_then(Node::as_bool)
        .unwrap_or(false);
    if transparent || transparency < 1.0 {
        out.insert("alphaMode".into(), json!("BLEND"));
        scale_alpha(out, transparency);
        let why = match (transparent, transparency < 1.0) {
            (true, true) => format!("transparent, transparency {transparency}"),
            (true, false) => "transparent".to_string(),
            (false, _) => format!("transparency {transparency}"),
        };
        let alpha = out
            .get("pbrMetallicRoughness")
            .map(|c| &c["baseColorFactor"][3]);
        let alpha = alpha.and_then(Value::as_f64).unwrap_or(transparency);
        let unseen = if alpha <= 0.0 {
            ": the surface is not seen"
        } else {
            ""
        };
        let text = format!("KHR_materials_common {why} → alphaMode BLEND, the base colour's alpha the diffuse alpha times the transparency ({alpha}){unseen}.");
        builder.note(at, NoteKind::Decision, text);
        // The implementation note's blend functions: ONE, ONE_MINUS_SRC_ALPHA.
        keep_emission_whole(builder, at, out);
    }
}

/// Replaces each value written in the extension's early form, `{"type": GL type, "value": v}`,
/// by `v`; true when any was.
fn unwrap_typed_values(values: &mut Value) -> bool {
    let mut any = false;
    for value in values
        .as_object_mut()
        .into_iter()
        .flat_map(|m| m.values_mut())
    {
        let typed = value
            .as_object()
            .filter(|o| o.contains_key("type"))
            .and_then(|o| o.get("value"));
        if let Some(inner) = typed.cloned() {
            *value = inner;
            any = true;
        }
    }
    any
}

/// Technique values by name (material values over the technique's parameter defaults, which
/// gltf-pipeline ignores).
fn convert_technique_values(
    builder: &mut Builder,
    material: Node,
    at: &str,
    out: &mut Map<String, Value>,
) {
    let mut values = Map::new();
    let technique = material
        .get("technique")
        .and_then(Node::as_str)
        .and_then(|t| builder.source.object("techniques", t));
    if let Some(parameters) = technique
        .and_then(|t| t.get("parameters"))
        .and_then(Node::as_object)
    {
        for (name, parameter) in parameters.iter() {
            if let Some(value) = parameter.get("value") {
                values.insert(name.to_string(), value.to_value());
            }
        }
    }
    if let Some(own) = material.get("values").and_then(Node::as_object) {
        values.extend(
            own.iter()
                .map(|(name, value)| (name.to_string(), value.to_value())),
        );
    }
    let transparency = values.get("transparency").and_then(Value::as_f64);
    let premultiplied = technique.and_then(technique_blend) == Some(Blend::Premultiplied);
    lit_material(builder, &Value::Object(values), at, out);
    // COLLADA2GLTF's shaders write alpha = diffuse.a · u_transparency; it matters only where
    // the technique blends.
    if let Some(opacity) = transparency.filter(|t| *t < 1.0) {
        if out.get("alphaMode") == Some(&json!("BLEND")) {
            scale_alpha(out, opacity);
            builder.note(at, NoteKind::Decision, format!("technique value transparency {opacity} multiplied into the base colour's alpha (BLEND). The 1.0 shaders blended premultiplied (ONE, ONE_MINUS_SRC_ALPHA) without scaling the colour by it; 2.0 blends straight alpha, so the surface's own colour is scaled too."));
        }
    }
    if premultiplied && out.get("alphaMode") == Some(&json!("BLEND")) {
        keep_emission_whole(builder, at, out);
    }
}

/// KHR_materials_common CONSTANT: "color = <emission> + <ambient> * al", the emission
/// (colour or texture) becoming an unlit material's colour; diffuse, which the model does not
/// read, is not carried over.
fn constant_material(
    builder: &mut Builder,
    values: &Value,
    at: &str,
    out: &mut Map<String, Value>,
) {
    let mut core = json!({"metallicFactor": 0.0, "baseColorFactor": [0.0, 0.0, 0.0, 1.0]});
    match values.get("emission") {
        Some(Value::String(texture)) => {
            if let Some(info) = texture_info(builder, Some(texture)) {
                core["baseColorTexture"] = info;
                core["baseColorFactor"] = json!([1.0, 1.0, 1.0, 1.0]);
            }
        }
        Some(colour) => {
            if let Some([r, g, b, _]) = linear_colour(colour) {
                core["baseColorFactor"] = json!([r, g, b, 1.0]);
            }
        }
        None => {}
    }
    out.insert("pbrMetallicRoughness".into(), core);
    out.insert("extensions".into(), json!({"KHR_materials_unlit": {}}));
    builder.note(
        at,
        NoteKind::Decision,
        "KHR_materials_common CONSTANT → KHR_materials_unlit, its emission (linearised) the colour; ambient is not carried over.",
    );
}

/// A 1.0 material blended with ONE, ONE_MINUS_SRC_ALPHA adds its emission whole; 2.0's BLEND
/// weighs the colour by alpha. With one alpha for the whole material (no texture's), the
/// emission (an unlit material's colour) is divided by it, above 1 through
/// KHR_materials_emissive_strength; otherwise the difference is said.
fn keep_emission_whole(builder: &mut Builder, at: &str, out: &mut Map<String, Value>) {
    let core = out.get("pbrMetallicRoughness");
    let alpha = (core.and_then(|c| c["baseColorFactor"][3].as_f64())).unwrap_or(1.0);
    let textured = core.is_some_and(|c| c.get("baseColorTexture").is_some());
    let unlit = out
        .get("extensions")
        .is_some_and(|e| e.get("KHR_materials_unlit").is_some());
    let emission: Option<[f64; 3]> = match unlit {
        true => core.and_then(|c| rgb_of(&c["baseColorFactor"])),
        false => out.get("emissiveFactor").and_then(rgb_of),
    };
    let Some(emission) = emission.filter(|e| e.iter().any(|c| *c > 0.0) && alpha < 1.0) else {
        return;
    };
    if textured || alpha <= 0.0 {
        let why = if textured {
            "the diffuse texture's alpha varies"
        } else {
            "the opacity is 0"
        };
        builder.note(at, NoteKind::Decision, format!("emission under BLEND is weighed by alpha in 2.0 where 1.0 added it whole (ONE, ONE_MINUS_SRC_ALPHA), and {why}: it shows dimmer."));
        return;
    }
    let whole = emission.map(|c| c / alpha);
    let most = whole.iter().copied().fold(0.0, f64::max);
    if unlit {
        if most > 1.0 {
            builder.note(at, NoteKind::Decision, format!("the unlit colour under BLEND is weighed by alpha {alpha} in 2.0 where 1.0 added it whole, and divided by it would pass 1: it shows dimmer."));
            return;
        }
        if let Some(core) = out.get_mut("pbrMetallicRoughness") {
            core["baseColorFactor"] = json!([whole[0], whole[1], whole[2], alpha]);
        }
    } else if most > 1.0 {
        out.insert("emissiveFactor".into(), json!(whole.map(|c| c / most)));
        let extensions = out.entry("extensions").or_insert_with(|| json!({}));
        extensions["KHR_materials_emissive_strength"] = json!({"emissiveStrength": most});
    } else {
        out.insert("emissiveFactor".into(), json!(whole));
    }
    builder.note(at, NoteKind::Decision, format!("emission divided by the opacity {alpha}: 1.0 added it whole under its blend (ONE, ONE_MINUS_SRC_ALPHA), 2.0's BLEND weighs it by alpha."));
}

fn rgb_of(value: &Value) -> Option<[f64; 3]> {
    let c = |i: usize| value.get(i).and_then(Value::as_f64);
    Some([c(0)?, c(1)?, c(2)?])
}

/// Multiplies the base colour's alpha by `opacity` (over a white factor when none is written).
fn scale_alpha(out: &mut Map<String, Value>, opacity: f64) {
    if let Some(core) = out.get_mut("pbrMetallicRoughness") {
        let alpha = core["baseColorFactor"][3].as_f64().unwrap_or(1.0);
        if core.get("baseColorFactor").is_none() {
            core["baseColorFactor"] = json!([1.0, 1.0, 1.0, 1.0]);
        }
        core["baseColorFactor"][3] = json!(alpha * opacity);
    }
}

/// The KHR extensions the converted materials use.
pub(crate) fn extensions_used(materials: Option<&Items>) -> Vec<String> {
    let mut used: Vec<String> = (materials.into_iter().flat_map(Items::iter))
        .flat_map(|material| match material.get("extensions") {
            Some(Value::Object(extensions)) => extensions.keys().cloned().collect(),
            _ => Vec::new(),
        })
        .collect();
    used.sort();
    used.dedup();
    used
}
