//! The one specular-glossiness → metallic-roughness mapping, for the 1.0 drafts'
//! spec-gloss materials and for glTF 2.0's archived KHR_materials_pbrSpecularGlossiness:
//! metallic 0, roughness 1 − glossiness, F0 = specular through KHR_materials_specular
//! (specularColor) and KHR_materials_ior (ior 0, so that F0 is the specular colour itself),
//! base colour diffuse · (1 − specular), channel by channel. With a specular-glossiness
//! texture, base colour and roughness vary per texel and are rebaked into new textures.
//!
//! Why per channel: the source's diffuse is c_diff,c · (1 − F_c) with c_diff = diffuse ·
//! (1 − max specular) (the archived extension's text, balanced per channel as Appendix B's
//! `fresnel_mix` with an RGB Fresnel). The target's is base_c · (1 − max_c F_c)
//! (KHR_materials_specular). With ior 0, F_c = s_c + (1 − s_c)·w for the same Schlick weight
//! w, so 1 − F_c = (1 − s_c)(1 − w) and 1 − max F = (1 − max s)(1 − w): base_c = diffuse_c ·
//! (1 − s_c) makes the two equal at every angle, chromatic specular included. (The earlier
//! diffuse · (1 − max s) is the same only for an achromatic specular.)

pub use super::fit::{base_colour, Factors};
use super::fit::{TexelFits, TexelReport};
use super::rebake;
use serde_json::{json, Map, Value};
use std::sync::Arc;

/// The two textures of a spec-gloss material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    /// The diffuse colour (sRGB RGB, alpha).
    Diffuse,
    /// Specular (sRGB RGB) and glossiness (A).
    SpecularGlossiness,
}

/// The material's textures as the output asset holds them.
pub trait Textures {
    /// The textureInfo that reads the slot's texture as it is, if the material has one.
    fn info(&self, slot: Slot) -> Option<Value>;
    /// The encoded image of the slot's texture.
    fn bytes(&self, slot: Slot) -> Option<Arc<crate::document::Bytes>>;
    /// Adds a rebaked image as a new texture sampled like the slot's texture (its sampler,
    /// texture coordinates and transform); returns the textureInfo that reads it.
    fn add_rebaked(&mut self, bytes: Vec<u8>, like: Slot, name: &str) -> Value;
    /// The per-texel fits, for a source whose text can be read several ways (the 1.0
    /// drafts); `None` where the closed form is exact (the archived 2.0 extension).
    fn texel_fits(&mut self) -> Option<&mut TexelFits>;
}

/// A converted material: its `pbrMetallicRoughness`, the extensions it gains, and the
/// decisions made, for the conversion report.
pub struct Converted {
    pub pbr_metallic_roughness: Value,
    pub extensions: Map<String, Value>,
    pub decisions: Vec<String>,
}

/// Converts one material; an error says why a texture could not be rebaked.
pub fn to_metal_rough(factors: &Factors, textures: &mut dyn Textures) -> Result<Converted, String> {
    let mut decisions = Vec::new();
    let specular_texture = textures.bytes(Slot::SpecularGlossiness);
    let mut core = json!({"metallicFactor": 0.0, "roughnessFactor": 1.0 - factors.glossiness});
    if let Some(specular) = &specular_texture {
        let diffuse = textures.bytes(Slot::Diffuse);
        let fits = textures.texel_fits();
        // The two rebakes are independent: the roughness one runs on a second thread.
        let (base_colour, roughness) = std::thread::scope(|scope| {
            let roughness =
                scope.spawn(|| rebake::gloss_to_roughness(specular, factors.glossiness));
            let base_colour = rebake::spec_gloss_base_colour(
                diffuse.as_deref().map(|bytes| &bytes[..]),
                Some(specular),
                factors,
                fits,
            );
            let roughness = (roughness.join())
                .unwrap_or_else(|_| Err("the roughness rebake failed".to_string()));
            (base_colour, roughness)
        });
        // Both rebakes must succeed before either is added: a failure leaves no orphan.
        let (base_colour, roughness) = (base_colour?.0, roughness?);
        let like = if diffuse.is_some() {
            Slot::Diffuse
        } else {
            Slot::SpecularGlossiness
        };
        core["baseColorTexture"] = textures.add_rebaked(base_colour, like, "baseColor");
        core["baseColorFactor"] = json!([1.0, 1.0, 1.0, 1.0]);
        core["metallicRoughnessTexture"] =
            textures.add_rebaked(roughness, Slot::SpecularGlossiness, "roughness");
        core["roughnessFactor"] = json!(1.0);
        decisions.push("baseColor = diffuse · (1 − specular) per channel and roughness = 1 − glossiness rebaked per texel into new textures (on the finer grid of the two, each sampled bilinearly).".to_string());
        if let Some(fits) = textures.texel_fits() {
            decisions.push(texel_fit_decision(&fits.take_report()));
        }
    } else {
        let keep = factors.specular.map(|s| 1.0 - s);
        let [r, g, b, a] = factors.diffuse;
        let [br, bg, bb] = base_colour([r, g, b], factors.specular);
        core["baseColorFactor"] = json!([br, bg, bb, a]);
        if let Some(info) = textures.info(Slot::Diffuse) {
            core["baseColorTexture"] = info;
        }
        decisions.push(format!(
            "baseColorFactor = diffuse · (1 − specular) per channel = diffuse · {keep:?}."
        ));
    }
    let mut specular = json!({"specularColorFactor": factors.specular});
    if let Some(info) = textures.info(Slot::SpecularGlossiness) {
        // Its RGB is the sRGB specular colour, exactly what specularColorTexture reads.
        specular["specularColorTexture"] = info;
    }
    let mut extensions = Map::new();
    extensions.insert("KHR_materials_specular".into(), specular);
    extensions.insert("KHR_materials_ior".into(), json!({"ior": 0}));
    decisions.push("spec-gloss → metal-rough: metallic 0, F0 = specular via KHR_materials_specular (specularColor) and KHR_materials_ior (ior 0, infinite). With base colour diffuse · (1 − specular) per channel the diffuse term equals the archived extension's per-channel (1 − F) balance at every angle, chromatic specular included.".to_string());
    Ok(Converted {
        pbr_metallic_roughness: core,
        extensions,
        decisions,
    })
}

/// The conversion report's line for a rebake's per-texel fits.
fn texel_fit_decision(report: &TexelReport) -> String {
    let mut line = format!(
        "per-texel check of the rebaked base colour against the drafts' three readings: {} distinct texel values, the closed form's worst ΔE2000 {:.2}",
        report.screened, report.closed_worst
    );
    if report.above > 0 {
        line += &format!(
            "; {} above the threshold, {} of them fitted (base colour per texel, no longer exact under any one reading): worst now {:.2} as the PNG stores it",
            report.above, report.fitted, report.written_worst
        );
    }
    if report.above > report.fitted {
        line += &format!(
            " ({} kept the closed form: at most {} distinct texel values are fitted per upgrade)",
            report.above - report.fitted,
            super::fit::MAX_TEXEL_FITS
        );
    }
    if report.unscreened > 0 {
        line += &format!(
            "; {} texels kept the closed form unchecked (at most {} distinct texel values are checked per upgrade)",
            report.unscreened,
            super::fit::MAX_SCREENED_TEXELS
        );
    }
    line + "."
}

/// The extensions a converted material gains, for `extensionsUsed`.
pub const EXTENSIONS_ADDED: [&str; 2] = ["KHR_materials_specular", "KHR_materials_ior"];
