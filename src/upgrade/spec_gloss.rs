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

pub(super) use super::fit::Factors;
use super::fit::{TexelFits, TexelReport};
use super::rebake;
use crate::shade::material::SpecGlossReading;
use crate::shade::sample::{self, Sampler, Texture};
use serde_json::{json, Map, Value};
use std::sync::Arc;

/// The two textures of a spec-gloss material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Slot {
    /// The diffuse colour (sRGB RGB, alpha).
    Diffuse,
    /// Specular (sRGB RGB) and glossiness (A).
    SpecularGlossiness,
}

/// The material's textures as the output asset holds them.
pub(super) trait Textures {
    /// The textureInfo that reads the slot's texture as it is, if the material has one.
    fn info(&self, slot: Slot) -> Option<Value>;
    /// The encoded image of the slot's texture (`None`: the slot has none), or why it
    /// cannot be had.
    fn bytes(&self, slot: Slot) -> Result<Option<Arc<crate::document::Bytes>>, String>;
    /// The sampler the slot's texture is read through (LINEAR, REPEAT when it names none).
    fn sampler(&self, slot: Slot) -> Sampler;
    /// Adds a rebaked image as a new texture sampled like the slot's texture (its sampler,
    /// texture coordinates and transform); returns the textureInfo that reads it.
    fn add_rebaked(&mut self, bytes: Vec<u8>, like: Slot, name: &str) -> Value;
    /// The per-texel fits, for a source whose text can be read several ways (the 1.0
    /// drafts); `None` where the closed form is exact (the archived 2.0 extension).
    fn texel_fits(&mut self) -> Option<&mut TexelFits>;
    /// The rebakes this upgrade has made so far.
    fn rebakes(&mut self) -> &mut Rebakes;
}

/// The rebakes of one upgrade, by what they were made from: the same two images (by
/// identity: the upgrade holds each image once) with the same factors under the same
/// reading rebake to the same textures, so materials sharing a texture are rebaked once.
#[derive(Default)]
pub(super) struct Rebakes(std::collections::HashMap<RebakeKey, Rebaked>);

impl Rebakes {
    /// The images the rebakes decoded (see [`Rebaked::decoded`]).
    pub(super) fn decoded(&self) -> Vec<Texture> {
        (self.0.values())
            .flat_map(|rebaked| rebaked.decoded.iter().cloned())
            .collect()
    }
}

/// The images' addresses (0 for none), their samplers, the factors' bits and the reading.
type RebakeKey = (usize, usize, [Sampler; 2], [u64; 8], SpecGlossReading);

/// A rebake's two PNGs and its decisions (a held grid, the per-texel fits), and the images it
/// was made from, held so that their addresses (the key) cannot be taken by other images.
#[derive(Clone)]
struct Rebaked {
    base_colour: Vec<u8>,
    roughness: Vec<u8>,
    /// The factor the roughness texture is read with.
    roughness_factor: f32,
    lines: Vec<String>,
    _made_from: (
        Option<Arc<crate::document::Bytes>>,
        Arc<crate::document::Bytes>,
    ),
    /// The images decoded: held until the upgrade is done with, so that its proof, which
    /// reads the same images, shares them rather than decoding them again.
    decoded: Vec<Texture>,
}

fn rebake_key(
    factors: &Factors,
    diffuse: Option<&Arc<crate::document::Bytes>>,
    specular: &Arc<crate::document::Bytes>,
    samplers: [Sampler; 2],
) -> RebakeKey {
    let [d0, d1, d2, d3] = factors.diffuse;
    let [s0, s1, s2] = factors.specular;
    let bits = [d0, d1, d2, d3, s0, s1, s2, factors.glossiness].map(f64::to_bits);
    let address = diffuse.map_or(0, |d| Arc::as_ptr(d) as usize);
    (
        address,
        Arc::as_ptr(specular) as usize,
        samplers,
        bits,
        factors.reading,
    )
}

/// A converted material: its `pbrMetallicRoughness`, the extensions it gains, and the
/// decisions made, for the conversion report.
pub(super) struct Converted {
    pub pbr_metallic_roughness: Value,
    pub extensions: Map<String, Value>,
    pub decisions: Vec<String>,
}

/// Converts one material; an error says why a texture could not be rebaked.
pub(super) fn to_metal_rough(
    factors: &Factors,
    textures: &mut dyn Textures,
) -> Result<Converted, String> {
    let mut decisions = Vec::new();
    let specular_texture = textures.bytes(Slot::SpecularGlossiness)?;
    let mut core = json!({"metallicFactor": 0.0, "roughnessFactor": 1.0 - factors.glossiness});
    if let Some(specular) = &specular_texture {
        let diffuse = textures.bytes(Slot::Diffuse)?;
        let samplers = [Slot::Diffuse, Slot::SpecularGlossiness].map(|s| textures.sampler(s));
        let key = rebake_key(factors, diffuse.as_ref(), specular, samplers);
        let made = match textures.rebakes().0.get(&key) {
            Some(made) => made.clone(),
            None => {
                let made = rebake(factors, diffuse.as_ref(), specular, samplers, textures)?;
                textures.rebakes().0.insert(key, made.clone());
                made
            }
        };
        let like = if diffuse.is_some() {
            Slot::Diffuse
        } else {
            Slot::SpecularGlossiness
        };
        core["baseColorTexture"] = textures.add_rebaked(made.base_colour, like, "baseColor");
        core["baseColorFactor"] = json!([1.0, 1.0, 1.0, 1.0]);
        core["metallicRoughnessTexture"] =
            textures.add_rebaked(made.roughness, Slot::SpecularGlossiness, "roughness");
        core["roughnessFactor"] = json!(made.roughness_factor);
        decisions.push(format!("baseColor = {} and roughness = 1 − glossiness rebaked per texel into new textures (on the finer grid of the two, each read through its sampler).", formula(factors.reading)));
        decisions.extend(made.lines);
    } else {
        let [r, g, b, a] = factors.diffuse;
        let [br, bg, bb] = factors.base_colour([r, g, b], factors.specular);
        core["baseColorFactor"] = json!([br, bg, bb, a]);
        if let Some(info) = textures.info(Slot::Diffuse) {
            core["baseColorTexture"] = info;
        }
        let (scale, _) = factors.reading.closed_form_base([1.0; 3], factors.specular);
        decisions.push(format!(
            "baseColorFactor = {} = diffuse · {scale:?}.",
            formula(factors.reading)
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
    decisions.push(match factors.reading {
        SpecGlossReading::ArchivedExtension => "spec-gloss → metal-rough: metallic 0, F0 = specular via KHR_materials_specular (specularColor) and KHR_materials_ior (ior 0, infinite). With base colour diffuse · (1 − specular) per channel the diffuse term equals the archived extension's per-channel (1 − F) balance at every angle, chromatic specular included.".to_string(),
        reading => format!("spec-gloss → metal-rough under the drafts' reading '{}' ({}): metallic 0, F0 = specular via KHR_materials_specular (specularColor) and KHR_materials_ior (ior 0, infinite).", reading.option_name(), reading.name()),
    });
    Ok(Converted {
        pbr_metallic_roughness: core,
        extensions,
        decisions,
    })
}

/// Rebakes the base colour and roughness textures of one material (both must succeed before
/// either is added: a failure leaves no orphan).
fn rebake(
    factors: &Factors,
    diffuse: Option<&Arc<crate::document::Bytes>>,
    specular: &Arc<crate::document::Bytes>,
    samplers: [Sampler; 2],
    textures: &mut dyn Textures,
) -> Result<Rebaked, String> {
    // Each image is decoded once, both at a time; the rebakes below share the decodes. A
    // decode that fails here fails there too, and says why.
    let decoded: Vec<Texture> = std::thread::scope(|scope| {
        let specular = scope.spawn(|| sample::decode(specular));
        let diffuse = diffuse.map(|bytes| sample::decode(bytes));
        let specular = specular.join().ok();
        [diffuse, specular]
            .into_iter()
            .flatten()
            .flatten()
            .collect()
    });
    let fits = textures.texel_fits();
    // The two rebakes are independent: the roughness one runs on a second thread.
    let (base_colour, roughness) = std::thread::scope(|scope| {
        let roughness =
            scope.spawn(|| rebake::gloss_to_roughness(&specular[..], factors.glossiness));
        let base_colour = rebake::spec_gloss_base_colour(
            diffuse.map(|bytes| &bytes[..]),
            Some(&specular[..]),
            samplers,
            factors,
            fits,
        );
        let roughness =
            (roughness.join()).unwrap_or_else(|_| Err("the roughness rebake failed".to_string()));
        (base_colour, roughness)
    });
    let ((base_colour, _, held), (roughness, roughness_factor)) = (base_colour?, roughness?);
    // A rebake on a refined grid checks no texel value (each is a blend, not a stored one):
    // nothing is said of a check not made.
    let fit_line = (textures.texel_fits())
        .map(|fits| fits.take_report())
        .filter(|report| report.screened + report.unscreened > 0)
        .map(|report| texel_fit_decision(&report));
    let scaled = (roughness_factor != 1.0).then(|| format!("Roughness is stored divided by its largest value, {roughness_factor}, which the roughnessFactor multiplies back: steps of {roughness_factor}/255, not 1/255, store it nearer (a smooth surface's specular peak shows the coarser step)."));
    Ok(Rebaked {
        base_colour,
        roughness,
        roughness_factor,
        lines: held.into_iter().chain(fit_line).chain(scaled).collect(),
        _made_from: (diffuse.cloned(), Arc::clone(specular)),
        decoded,
    })
}

/// The closed-form base colour under `reading`, in words (see
/// [`SpecGlossReading::closed_form_base`]).
fn formula(reading: SpecGlossReading) -> &'static str {
    match reading {
        SpecGlossReading::ArchivedExtension | SpecGlossReading::DraftAppendix => {
            "diffuse · (1 − specular) per channel"
        }
        SpecGlossReading::DraftAppendix2016 => {
            "diffuse · (1 − specular) / (1 − max specular) per channel, at most 1"
        }
        SpecGlossReading::DraftExampleShader => {
            "diffuse (the example shader's reading has no exact 2.0 form: fitted where it matters)"
        }
    }
}

/// The conversion report's line for a rebake's per-texel fits.
fn texel_fit_decision(report: &TexelReport) -> String {
    let mut line = format!(
        "per-texel check of the rebaked base colour as the PNG stores it, under the reading converted to: {} distinct texel values, the closed form's worst ΔE2000 {:.2}",
        report.screened, report.closed_worst
    );
    if report.unseen_rounding > 0 {
        line += &format!(
            " ({} of them not evaluated in the scene: rounding moves their base colour by at most ΔE2000 {}, which shows at most {})",
            report.unseen_rounding,
            super::fit::ROUNDING_SEEN_ABOVE,
            super::fit::LEVELS_TRIED_ABOVE
        );
    }
    if report.above > 0 {
        line += &format!(
            "; {} above the threshold, {} of them fitted towards that reading (base colour per texel): worst now {:.2} as the PNG stores it",
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
pub(super) const EXTENSIONS_ADDED: [&str; 2] = ["KHR_materials_specular", "KHR_materials_ior"];
