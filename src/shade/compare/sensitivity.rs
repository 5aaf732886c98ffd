//! What `compare` (and so every upgrade's proof) catches and what it lets pass: mistakes a
//! converter makes are caught (ΔE2000 above one JND), differences nobody can see are not.

use super::compare;
use crate::gltf::color::srgb_to_linear;
use crate::shade::brdf::SheenVisibility;
use crate::shade::material::Shader;
use crate::shade::sample::{decode_all, solid_png, MaterialSource, Texture};
use crate::shade::sheen_table::SheenTable;
use serde_json::{json, Value};

/// A material with texture `i` being `textures[i]`.
fn material(json: Value, textures: &[[u8; 3]]) -> MaterialSource {
    let encoded: Vec<_> = textures.iter().map(|t| Some(Ok(solid_png(*t)))).collect();
    let decoded: Vec<Option<Texture>> = decode_all(&encoded).unwrap();
    MaterialSource::gltf2(&json, &decoded)
}

fn worst(a: &MaterialSource, b: &MaterialSource) -> f64 {
    let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
    compare(&shader, a, b, 4).max
}

fn pbr(base: [f64; 3], metallic: f64, roughness: f64) -> Value {
    json!({"pbrMetallicRoughness": {"baseColorFactor": [base[0], base[1], base[2], 1.0],
        "metallicFactor": metallic, "roughnessFactor": roughness}})
}

#[test]
fn the_mistakes_a_converter_makes_are_caught() {
    let base = [0.5, 0.3, 0.2];
    let reference = material(pbr(base, 0.0, 0.5), &[]);
    let textured_mr = |texel| {
        let mut m = pbr([0.8, 0.6, 0.4], 1.0, 1.0);
        m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = json!({"index": 0});
        material(m, &[texel])
    };
    let srgb_texture = |texel| {
        let mut m = pbr([1.0; 3], 0.0, 0.5);
        m["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
        material(m, &[texel])
    };
    // Linear 0.2158 is sRGB level 128; a converter that forgot the encoding writes 55.
    let level = (srgb_to_linear(128.0 / 255.0) * 255.0).round() as u8;
    let spec_gloss = material(
        json!({"extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseFactor": [0.6, 0.5, 0.4, 1.0], "specularFactor": [0.3, 0.3, 0.3], "glossinessFactor": 0.5}}}),
        &[],
    );
    let with_base = |base: [f64; 3]| {
        let mut m = pbr(base, 0.0, 0.5);
        m["extensions"] = json!({"KHR_materials_specular": {"specularColorFactor": [0.3, 0.3, 0.3]},
            "KHR_materials_ior": {"ior": 0}});
        material(m, &[])
    };
    let anisotropic = |rotation: f64| {
        let mut m = pbr(base, 0.0, 0.3);
        m["extensions"] = json!({"KHR_materials_anisotropy": {"anisotropyStrength": 0.8, "anisotropyRotation": rotation}});
        material(m, &[])
    };
    let sheen = |roughness: f64| {
        let mut m = pbr(base, 0.0, 0.5);
        m["extensions"] = json!({"KHR_materials_sheen": {"sheenColorFactor": [0.2, 0.2, 0.2], "sheenRoughnessFactor": roughness}});
        material(m, &[])
    };
    let cases = [
        (
            "anisotropy direction turned by 90°",
            worst(&anisotropic(0.0), &anisotropic(std::f64::consts::FRAC_PI_2)),
        ),
        (
            "sheen roughness 0.3 read as 0.25",
            worst(&sheen(0.3), &sheen(0.25)),
        ),
        (
            "base colour 5% darker",
            worst(
                &reference,
                &material(pbr(base.map(|c| c * 0.95), 0.0, 0.5), &[]),
            ),
        ),
        (
            "roughness + 0.05",
            worst(&reference, &material(pbr(base, 0.0, 0.55), &[])),
        ),
        (
            "roughness − 0.05",
            worst(&reference, &material(pbr(base, 0.0, 0.45), &[])),
        ),
        (
            "metallic and roughness swapped R/B in the texture",
            worst(&textured_mr([0, 100, 255]), &textured_mr([255, 100, 0])),
        ),
        (
            "a linear value stored where sRGB is read",
            worst(&srgb_texture([128; 3]), &srgb_texture([level; 3])),
        ),
        (
            "spec-gloss base colour = diffuse (no 1 − specular)",
            worst(&spec_gloss, &with_base([0.6, 0.5, 0.4])),
        ),
    ];
    for (mistake, delta_e) in cases {
        println!("caught: {mistake}: ΔE {delta_e:.2}");
        assert!(delta_e > 1.0, "{mistake}: ΔE {delta_e} is not caught");
    }
    // The same spec-gloss converted as gltfmat converts it passes: the table's rows above
    // fail for their mistake, not for the comparison's own noise.
    let exact = worst(&spec_gloss, &with_base([0.6 * 0.7, 0.5 * 0.7, 0.4 * 0.7]));
    assert!(exact < 1e-6, "ΔE {exact}");
}

#[test]
fn differences_nobody_can_see_pass() {
    let defaults = material(json!({}), &[]);
    let explicit = material(pbr([1.0; 3], 1.0, 1.0), &[]);
    let ior = |ior: f64| {
        let mut m = pbr([0.4, 0.5, 0.6], 0.0, 0.4);
        m["extensions"] = json!({"KHR_materials_specular": {"specularColorFactor": [0.05, 0.05, 0.05]},
            "KHR_materials_ior": {"ior": ior}});
        material(m, &[])
    };
    let level = |l: f64| material(pbr([srgb_to_linear(l / 255.0); 3], 0.0, 0.5), &[]);
    let cases = [
        ("explicit defaults", worst(&defaults, &explicit)),
        ("ior 0 against ior 1e9", worst(&ior(0.0), &ior(1e9))),
        (
            "half an 8-bit step of base colour",
            worst(&level(100.0), &level(100.5)),
        ),
    ];
    for (difference, delta_e) in cases {
        println!("passes: {difference}: ΔE {delta_e:.2}");
        assert!(delta_e < 1.0, "{difference}: ΔE {delta_e} should pass");
    }
}
