//! The glTF 1.0 PBR material drafts (2016–2017): WEB3D_materials_pbr and its later names
//! KHR_materials_pbr, FRAUNHOFER_materials_pbr and EXT_materials_pbr. One reading of the
//! drafts, shared by `check` (which validates the blocks), `upgrade` (which converts them)
//! and the shading evaluator (which renders the source model).
//!
//! Accepted spellings, from the draft history (see converter-anchors.md §0):
//! - the model in `technique` (July 2016) or `materialModel` (September 2016 on), values
//!   `PBR_metal_roughness` / `PBR_specular_glossiness`, matched loosely (case, separators,
//!   `metallic` for `metal`); when both are missing, the model is inferred from the values;
//! - value keys `baseColorFactor` … `specularGlossinessTexture`, and the early bare stems
//!   `base`, `albedo`, `metallic`, `roughness`, `diffuse`, `specular`, `glossiness`, where a
//!   string is a texture id and a number or array a factor.

use crate::document::Node;

/// The four names of the extension, newest last.
pub(crate) const EXTENSION_NAMES: &[&str] = &[
    "WEB3D_materials_pbr",
    "KHR_materials_pbr",
    "FRAUNHOFER_materials_pbr",
    "EXT_materials_pbr",
];

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Model {
    MetalRoughness,
    SpecularGlossiness,
}

/// Where the model came from, for the conversion report.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ModelSource {
    /// `technique` or `materialModel` named it.
    Declared,
    /// Neither member was present: inferred from the value names.
    Inferred,
}

/// A parsed PBR block, factors defaulted as the drafts say.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LegacyPbr {
    pub extension: &'static str,
    pub model: Model,
    pub model_source: ModelSource,
    /// Metal-rough: base colour RGBA; spec-gloss: diffuse RGBA (linear).
    pub colour: [f64; 4],
    /// Metal-rough: (metallic, roughness); spec-gloss: unused (1, 1).
    pub metallic: f64,
    pub roughness: f64,
    /// Spec-gloss: specular RGB and glossiness.
    pub specular: [f64; 3],
    pub glossiness: f64,
    /// Metal-rough: base colour; spec-gloss: diffuse.
    pub colour_texture: Option<String>,
    /// Metal-rough: metallic (R) + roughness (G); spec-gloss: specular (RGB) + glossiness (A).
    pub data_texture: Option<String>,
    /// Value keys that were not understood.
    pub unknown_keys: Vec<String>,
}

/// The PBR block of a 1.0 material, if it has one: (extension name, object).
pub(crate) fn find<'t>(material: Node<'t>) -> Option<(&'static str, Node<'t>)> {
    let extensions = material.get("extensions")?;
    EXTENSION_NAMES
        .iter()
        .find_map(|name| Some((*name, extensions.get(*name).filter(|e| e.is_object())?)))
}

/// Reads a model name as the drafts spelled it.
pub(crate) fn model_from_name(name: &str) -> Option<Model> {
    let flat: String = name
        .chars()
        .filter(char::is_ascii_alphanumeric)
        .collect::<String>()
        .to_ascii_lowercase();
    if flat.contains("gloss") || flat.contains("specular") {
        Some(Model::SpecularGlossiness)
    } else if flat.contains("metal") || flat.contains("rough") {
        Some(Model::MetalRoughness)
    } else {
        None
    }
}

/// The declared model name, from `materialModel` or `technique`.
pub(crate) fn declared_model<'t>(block: Node<'t>) -> Option<&'t str> {
    ["materialModel", "technique"]
        .iter()
        .find_map(|key| block.get(*key).and_then(Node::as_str))
}

/// What a value key means: its canonical stem, and whether the value is a texture.
fn stem(key: &str) -> &str {
    let bare = key
        .strip_suffix("Factor")
        .or_else(|| key.strip_suffix("Texture"))
        .unwrap_or(key);
    match bare {
        "base" | "albedo" => "baseColor",
        other => other,
    }
}

fn model_of_stem(stem: &str) -> Option<Model> {
    match stem {
        "baseColor" | "metallic" | "roughness" | "metallicRoughness" => Some(Model::MetalRoughness),
        "diffuse" | "specular" | "glossiness" | "specularGlossiness" => {
            Some(Model::SpecularGlossiness)
        }
        _ => None,
    }
}

/// Parses a PBR block; `None` when no model can be declared or inferred.
pub(crate) fn parse(extension: &'static str, block: Node) -> Option<LegacyPbr> {
    let values = block.get("values").and_then(Node::as_object);
    let entries: Vec<(&str, Node)> = values.into_iter().flat_map(|v| v.iter()).collect();
    let (model, model_source) = match declared_model(block).and_then(model_from_name) {
        Some(model) => (model, ModelSource::Declared),
        None if declared_model(block).is_some() => return None,
        None => (
            entries.iter().find_map(|(k, _)| model_of_stem(stem(k)))?,
            ModelSource::Inferred,
        ),
    };
    let mut pbr = LegacyPbr {
        extension,
        model,
        model_source,
        colour: [1.0; 4],
        metallic: 1.0,
        roughness: 1.0,
        specular: [1.0; 3],
        glossiness: 1.0,
        colour_texture: None,
        data_texture: None,
        unknown_keys: Vec::new(),
    };
    for (key, value) in entries {
        if !pbr.apply(stem(key), value) {
            pbr.unknown_keys.push(key.to_string());
        }
    }
    Some(pbr)
}

impl LegacyPbr {
    /// Stores one value; false when the key does not belong to the model or is mistyped.
    fn apply(&mut self, stem: &str, value: Node) -> bool {
        let texture = value.as_str().map(str::to_string);
        let scalar = value.as_f64();
        let colour_stem = match self.model {
            Model::MetalRoughness => "baseColor",
            Model::SpecularGlossiness => "diffuse",
        };
        let data_stem = match self.model {
            Model::MetalRoughness => "metallicRoughness",
            Model::SpecularGlossiness => "specularGlossiness",
        };
        match (self.model, stem) {
            (_, s) if s == colour_stem && texture.is_some() => self.colour_texture = texture,
            (_, s) if s == colour_stem => return fill(&mut self.colour, value),
            (_, s) if s == data_stem && texture.is_some() => self.data_texture = texture,
            (Model::MetalRoughness, "metallic") if scalar.is_some() => {
                self.metallic = scalar.unwrap_or(1.0)
            }
            (Model::MetalRoughness, "roughness") if scalar.is_some() => {
                self.roughness = scalar.unwrap_or(1.0)
            }
            (Model::SpecularGlossiness, "specular") => return fill(&mut self.specular, value),
            (Model::SpecularGlossiness, "glossiness") if scalar.is_some() => {
                self.glossiness = scalar.unwrap_or(1.0)
            }
            _ => return false,
        }
        true
    }
}

/// Copies a numeric array into `target` (missing trailing components keep their default).
fn fill<const N: usize>(target: &mut [f64; N], value: Node) -> bool {
    let Some(list) = value.as_array() else {
        return false;
    };
    for (slot, item) in target.iter_mut().zip(list.iter()) {
        match item.as_f64() {
            Some(v) => *slot = v,
            None => return false,
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::Tree;
    use serde_json::json;

    fn tree(value: serde_json::Value) -> Tree {
        Tree::of(&value)
    }

    #[test]
    fn every_draft_spelling_reads_the_same_material() {
        let canonical = tree(json!({"materialModel": "PBR_metal_roughness",
            "values": {"baseColorFactor": [0.5, 0.4, 0.3, 1], "metallicFactor": 0, "roughnessFactor": 0.2,
                       "baseColorTexture": "tex"}}));
        let july = tree(json!({"technique": "PBR_metal_roughness",
            "values": {"baseColorFactor": [0.5, 0.4, 0.3, 1], "metallicFactor": 0, "roughnessFactor": 0.2,
                       "baseColorTexture": "tex"}}));
        let early = tree(
            json!({"values": {"base": [0.5, 0.4, 0.3, 1], "metallic": 0, "roughness": 0.2, "albedo": "tex"}}),
        );
        let a = parse("EXT_materials_pbr", canonical.root()).unwrap();
        let b = parse("EXT_materials_pbr", july.root()).unwrap();
        let c = parse("EXT_materials_pbr", early.root()).unwrap();
        assert_eq!(a, b);
        assert_eq!(c.model_source, ModelSource::Inferred);
        assert_eq!(
            (c.colour, c.metallic, c.roughness),
            (a.colour, a.metallic, a.roughness)
        );
        assert_eq!(c.colour_texture.as_deref(), Some("tex"));
    }

    #[test]
    fn defaults_and_unknown_keys_follow_the_drafts() {
        let sg = parse(
            "KHR_materials_pbr",
            tree(json!({"technique": "PBR_specular_glossiness",
            "values": {"glossinessFactor": 0.25, "sheen": 1}}))
            .root(),
        )
        .unwrap();
        assert_eq!(sg.model, Model::SpecularGlossiness);
        assert_eq!(
            (sg.colour, sg.specular, sg.glossiness),
            ([1.0; 4], [1.0; 3], 0.25)
        );
        assert_eq!(sg.unknown_keys, vec!["sheen".to_string()]);
        assert!(parse(
            "KHR_materials_pbr",
            tree(json!({"technique": "PHONG"})).root()
        )
        .is_none());
        assert_eq!(
            model_from_name("pbr-Metallic-Roughness"),
            Some(Model::MetalRoughness)
        );
    }
}
