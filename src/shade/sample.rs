//! Material sampling: the BRDF inputs of a material at a texture coordinate. Textures are
//! decoded once, sampled bilinearly with repeat wrapping, decoded from sRGB or kept linear
//! per slot, and KHR_texture_transform is applied. Both glTF 2.0 materials and glTF 1.0
//! PBR-draft materials (their own model) are sampled.

use super::brdf::V3;
use super::material::Inputs;
use crate::color::srgb_to_linear;
use crate::legacy_pbr::{LegacyPbr, Model};
use image::Rgba32FImage;
use serde_json::Value;
use std::sync::Arc;

/// A decoded texture (stored values, 0..1; transfer functions are applied per slot).
pub type Texture = Arc<Rgba32FImage>;

pub fn decode(bytes: &[u8]) -> Option<Texture> {
    crate::document::image_decode::decode(bytes)
        .ok()
        .map(|i| Arc::new(i.to_rgba32f()))
}

/// Bilinear sample with repeat wrapping, texel centres at (i + ½) / size.
pub fn bilinear(texture: &Rgba32FImage, [u, v]: [f64; 2]) -> [f64; 4] {
    let (w, h) = (
        texture.width().max(1) as i64,
        texture.height().max(1) as i64,
    );
    let x = u * w as f64 - 0.5;
    let y = v * h as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |i: i64, j: i64| {
        let p = texture
            .get_pixel(i.rem_euclid(w) as u32, j.rem_euclid(h) as u32)
            .0;
        p.map(f64::from)
    };
    let (x0, y0) = (x0 as i64, y0 as i64);
    let mut out = [0.0; 4];
    for (c, value) in out.iter_mut().enumerate() {
        let top = texel(x0, y0)[c] * (1.0 - fx) + texel(x0 + 1, y0)[c] * fx;
        let bottom = texel(x0, y0 + 1)[c] * (1.0 - fx) + texel(x0 + 1, y0 + 1)[c] * fx;
        *value = top * (1.0 - fy) + bottom * fy;
    }
    out
}

/// A textureInfo of a 2.0 material: its texture and its UV transform.
#[derive(Clone)]
struct Binding {
    texture: Texture,
    texcoord: u64,
    /// 2×3 affine matrix from KHR_texture_transform (identity when absent).
    transform: [f64; 6],
}

impl Binding {
    fn sample(&self, uvs: &[[f64; 2]]) -> [f64; 4] {
        let [u, v] = uvs
            .get(self.texcoord as usize)
            .copied()
            .unwrap_or([0.0, 0.0]);
        let t = self.transform;
        bilinear(
            &self.texture,
            [t[0] * u + t[1] * v + t[2], t[3] * u + t[4] * v + t[5]],
        )
    }
}

fn transform_of(info: &Value) -> ([f64; 6], Option<u64>) {
    let Some(t) = info
        .get("extensions")
        .and_then(|e| e.get("KHR_texture_transform"))
    else {
        return ([1.0, 0.0, 0.0, 0.0, 1.0, 0.0], None);
    };
    let pair = |key: &str, default: [f64; 2]| {
        t.get(key).and_then(Value::as_array).map_or(default, |a| {
            [0, 1].map(|i| a.get(i).and_then(Value::as_f64).unwrap_or(default[i]))
        })
    };
    let [ox, oy] = pair("offset", [0.0, 0.0]);
    let [sx, sy] = pair("scale", [1.0, 1.0]);
    let r = t.get("rotation").and_then(Value::as_f64).unwrap_or(0.0);
    let (s, c) = r.sin_cos();
    // T · R · S as in the KHR_texture_transform README.
    let matrix = [c * sx, s * sy, ox, -s * sx, c * sy, oy];
    (matrix, t.get("texCoord").and_then(Value::as_u64))
}

/// What a material is made of, ready to be sampled.
#[derive(Clone)]
pub enum MaterialSource {
    /// A glTF 2.0 material with its textures (by texture index).
    Gltf2 {
        material: Value,
        textures: Vec<Option<Texture>>,
    },
    /// A glTF 1.0 PBR-draft material with its two textures.
    Legacy {
        pbr: LegacyPbr,
        colour: Option<Texture>,
        data: Option<Texture>,
    },
}

fn colour3(value: Option<&Value>, default: V3) -> V3 {
    value.and_then(Value::as_array).map_or(default, |a| {
        [0, 1, 2].map(|i| a.get(i).and_then(Value::as_f64).unwrap_or(default[i]))
    })
}

fn number(object: Option<&Value>, key: &str, default: f64) -> f64 {
    object
        .and_then(|o| o.get(key))
        .and_then(Value::as_f64)
        .unwrap_or(default)
}

fn srgb3(t: [f64; 4]) -> V3 {
    [t[0], t[1], t[2]].map(srgb_to_linear)
}

impl MaterialSource {
    /// The highest texture resolution involved (for the comparison grid).
    pub fn max_resolution(&self) -> u32 {
        let textures: Vec<&Texture> = match self {
            MaterialSource::Gltf2 { textures, .. } => textures.iter().flatten().collect(),
            MaterialSource::Legacy { colour, data, .. } => colour.iter().chain(data).collect(),
        };
        textures
            .iter()
            .map(|t| t.width().max(t.height()))
            .max()
            .unwrap_or(1)
    }

    /// The BRDF inputs at texture coordinates `uvs` (one pair per TEXCOORD set).
    pub fn inputs_at(&self, uvs: &[[f64; 2]]) -> Inputs {
        match self {
            MaterialSource::Gltf2 { material, textures } => gltf2_inputs(material, textures, uvs),
            MaterialSource::Legacy { pbr, colour, data } => {
                legacy_inputs(pbr, colour.as_deref(), data.as_deref(), uvs[0])
            }
        }
    }
}

fn gltf2_inputs(material: &Value, textures: &[Option<Texture>], uvs: &[[f64; 2]]) -> Inputs {
    let bind = |info: Option<&Value>| -> Option<Binding> {
        let info = info?;
        let texture = textures
            .get(info.get("index")?.as_u64()? as usize)?
            .clone()?;
        let (transform, override_set) = transform_of(info);
        let texcoord = override_set.or_else(|| info.get("texCoord").and_then(Value::as_u64));
        Some(Binding {
            texture,
            texcoord: texcoord.unwrap_or(0),
            transform,
        })
    };
    let sample = |info: Option<&Value>| bind(info).map(|b| b.sample(uvs));
    let extension = |name: &str| material.get("extensions").and_then(|e| e.get(name));
    let mut m = Inputs::default();
    if let Some(sg) = extension("KHR_materials_pbrSpecularGlossiness") {
        let mut diffuse = colour3(sg.get("diffuseFactor"), [1.0; 3]);
        if let Some(t) = sample(sg.get("diffuseTexture")) {
            let d = srgb3(t);
            diffuse = [0, 1, 2].map(|i| diffuse[i] * d[i]);
        }
        let mut specular = colour3(sg.get("specularFactor"), [1.0; 3]);
        let mut gloss = number(Some(sg), "glossinessFactor", 1.0);
        if let Some(t) = sample(sg.get("specularGlossinessTexture")) {
            let s = srgb3(t);
            specular = [0, 1, 2].map(|i| specular[i] * s[i]);
            gloss *= t[3];
        }
        return Inputs::specular_glossiness(diffuse, specular, gloss);
    }
    let pbr = material.get("pbrMetallicRoughness");
    m.base_color = colour3(pbr.and_then(|p| p.get("baseColorFactor")), [1.0; 3]);
    if let Some(t) = sample(pbr.and_then(|p| p.get("baseColorTexture"))) {
        let c = srgb3(t);
        m.base_color = [0, 1, 2].map(|i| m.base_color[i] * c[i]);
    }
    m.metallic = number(pbr, "metallicFactor", 1.0);
    m.roughness = number(pbr, "roughnessFactor", 1.0);
    if let Some(t) = sample(pbr.and_then(|p| p.get("metallicRoughnessTexture"))) {
        m.roughness *= t[1];
        m.metallic *= t[2];
    }
    m.unlit = extension("KHR_materials_unlit").is_some();
    if let Some(ior) = extension("KHR_materials_ior") {
        m.ior = number(Some(ior), "ior", 1.5);
    }
    if let Some(s) = extension("KHR_materials_specular") {
        m.specular = number(Some(s), "specularFactor", 1.0);
        if let Some(t) = sample(s.get("specularTexture")) {
            m.specular *= t[3];
        }
        m.specular_color = colour3(s.get("specularColorFactor"), [1.0; 3]);
        if let Some(t) = sample(s.get("specularColorTexture")) {
            let c = srgb3(t);
            m.specular_color = [0, 1, 2].map(|i| m.specular_color[i] * c[i]);
        }
    }
    if let Some(s) = extension("KHR_materials_sheen") {
        m.sheen_color = colour3(s.get("sheenColorFactor"), [0.0; 3]);
        if let Some(t) = sample(s.get("sheenColorTexture")) {
            let c = srgb3(t);
            m.sheen_color = [0, 1, 2].map(|i| m.sheen_color[i] * c[i]);
        }
        m.sheen_roughness = number(Some(s), "sheenRoughnessFactor", 0.0);
        if let Some(t) = sample(s.get("sheenRoughnessTexture")) {
            m.sheen_roughness *= t[3];
        }
    }
    if let Some(a) = extension("KHR_materials_anisotropy") {
        m.anisotropy_strength = number(Some(a), "anisotropyStrength", 0.0);
        m.anisotropy_angle = number(Some(a), "anisotropyRotation", 0.0);
        if let Some(t) = sample(a.get("anisotropyTexture")) {
            let (x, y) = (2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0);
            m.anisotropy_angle += y.atan2(x);
            m.anisotropy_strength *= t[2];
        }
    }
    m
}

/// The 1.0 drafts' own model: metal-rough with metallic in R and roughness in G of the data
/// texture; spec-gloss with sRGB diffuse and specular, glossiness in A (2017 draft).
fn legacy_inputs(
    pbr: &LegacyPbr,
    colour: Option<&Rgba32FImage>,
    data: Option<&Rgba32FImage>,
    uv: [f64; 2],
) -> Inputs {
    let colour_texel = colour.map(|t| bilinear(t, uv));
    let data_texel = data.map(|t| bilinear(t, uv));
    let mut rgb = [pbr.colour[0], pbr.colour[1], pbr.colour[2]];
    if let Some(t) = colour_texel {
        let c = srgb3(t);
        rgb = [0, 1, 2].map(|i| rgb[i] * c[i]);
    }
    match pbr.model {
        Model::MetalRoughness => {
            let (mut metallic, mut roughness) = (pbr.metallic, pbr.roughness);
            if let Some(t) = data_texel {
                metallic *= t[0];
                roughness *= t[1];
            }
            Inputs {
                base_color: rgb,
                metallic,
                roughness,
                ..Inputs::default()
            }
        }
        Model::SpecularGlossiness => {
            let (mut specular, mut gloss) = (pbr.specular, pbr.glossiness);
            if let Some(t) = data_texel {
                let s = srgb3(t);
                specular = [0, 1, 2].map(|i| specular[i] * s[i]);
                gloss *= t[3];
            }
            Inputs::specular_glossiness(rgb, specular, gloss)
        }
    }
}
