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

/// A grey dielectric with `extra` members merged in (and into its extensions).
fn grey(extra: Value) -> Value {
    let mut m = pbr([0.5; 3], 0.0, 0.5);
    for (key, value) in extra.as_object().into_iter().flatten() {
        m[key] = value.clone();
    }
    m
}

/// The pairs whole-material inputs make: the first of each is the grey dielectric.
fn whole_material_changes() -> Vec<(&'static str, &'static str, Value, Vec<[u8; 3]>)> {
    let mut blended = grey(json!({"alphaMode": "BLEND"}));
    blended["pbrMetallicRoughness"]["baseColorFactor"][3] = json!(0.2);
    vec![
        ("base-colour alpha 0.2, BLEND", "coverage", blended, vec![]),
        (
            "emission 1 at strength 10",
            "emission",
            grey(json!({"emissiveFactor": [1.0, 1.0, 1.0],
                "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 10.0}}})),
            vec![],
        ),
        (
            "a tilted normal map",
            "normal",
            grey(json!({"normalTexture": {"index": 0}})),
            vec![[230, 128, 180]],
        ),
        (
            "a clearcoat of roughness 0.05",
            "clearcoat",
            grey(json!({"extensions": {"KHR_materials_clearcoat":
                {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}})),
            vec![],
        ),
        (
            "transmission 1",
            "transmission",
            grey(
                json!({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}}}),
            ),
            vec![],
        ),
        (
            "occlusion texels of 40",
            "occlusion",
            grey(json!({"occlusionTexture": {"index": 0}})),
            vec![[40, 40, 40]],
        ),
        (
            "diffuse transmission 1",
            "diffuse transmission",
            grey(json!({"extensions": {"KHR_materials_diffuse_transmission":
                {"diffuseTransmissionFactor": 1.0}}})),
            vec![],
        ),
        (
            "an iridescent film",
            "iridescence",
            grey(json!({"extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1.0}}})),
            vec![],
        ),
        (
            "alpha 0.4 masked at the default cutoff",
            "coverage",
            {
                let mut m = grey(json!({"alphaMode": "MASK"}));
                m["pbrMetallicRoughness"]["baseColorFactor"][3] = json!(0.4);
                m
            },
            vec![],
        ),
    ]
}

#[test]
fn every_whole_material_input_that_changes_the_picture_is_caught_and_named() {
    let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
    let reference = material(grey(json!({})), &[]);
    for (change, input, json, textures) in whole_material_changes() {
        let changed = material(json, &textures);
        let result = compare(&shader, &reference, &changed, 4);
        println!(
            "caught: {change}: ΔE {:.2}, mostly {:?}",
            result.max, result.dominant
        );
        assert!(
            result.max > 1.0,
            "{change}: ΔE {} is not caught",
            result.max
        );
        assert_eq!(result.dominant, Some(input), "{change}");
    }
}

/// Layers whose own inputs change, each against the same layer otherwise.
#[test]
fn a_changed_layer_is_caught() {
    let coat = |roughness: f64| {
        grey(json!({"extensions": {"KHR_materials_clearcoat":
            {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": roughness}}}))
    };
    let volume = |colour: [f64; 3]| {
        grey(
            json!({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
            "KHR_materials_volume": {"thicknessFactor": 1.0, "attenuationDistance": 1.0,
                "attenuationColor": colour}}}),
        )
    };
    let film = |thickness: f64| {
        grey(json!({"extensions": {"KHR_materials_iridescence":
            {"iridescenceFactor": 1.0, "iridescenceThicknessMaximum": thickness}}}))
    };
    let strength = |s: f64| {
        grey(json!({"emissiveFactor": [0.2, 0.1, 0.05],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": s}}}))
    };
    let cutoff = |cutoff: f64| {
        let mut m = grey(json!({"alphaMode": "MASK", "alphaCutoff": cutoff}));
        m["pbrMetallicRoughness"]["baseColorFactor"][3] = json!(0.4);
        m
    };
    let cases = [
        ("clearcoat roughness 0.1 read as 0.4", coat(0.1), coat(0.4)),
        (
            "attenuation colour lost",
            volume([0.5, 0.2, 0.2]),
            volume([1.0, 1.0, 1.0]),
        ),
        (
            "emissive strength 4 read as 1",
            strength(4.0),
            strength(1.0),
        ),
        ("alpha cutoff 0.5 read as 0.3", cutoff(0.5), cutoff(0.3)),
        (
            "film thickness 400 nm read as 300",
            film(400.0),
            film(300.0),
        ),
    ];
    for (change, a, b) in cases {
        let delta_e = worst(&material(a, &[]), &material(b, &[]));
        println!("caught: {change}: ΔE {delta_e:.2}");
        assert!(delta_e > 1.0, "{change}: ΔE {delta_e} is not caught");
    }
}

#[test]
fn whole_material_differences_nobody_can_see_pass() {
    let defaults = material(grey(json!({})), &[]);
    let explicit = material(
        grey(
            json!({"alphaMode": "OPAQUE", "alphaCutoff": 0.5, "emissiveFactor": [0.0, 0.0, 0.0],
            "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.0},
                "KHR_materials_transmission": {"transmissionFactor": 0.0},
                "KHR_materials_emissive_strength": {"emissiveStrength": 1.0},
                "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.0},
                "KHR_materials_volume": {"thicknessFactor": 0.0}}}),
        ),
        &[],
    );
    let flat_maps = material(
        grey(json!({"normalTexture": {"index": 0}, "occlusionTexture": {"index": 1}})),
        &[[128, 128, 255], [255, 255, 255]],
    );
    let emission = |level: f64| {
        material(
            grey(json!({"emissiveFactor": [srgb_to_linear(level / 255.0), 0.1, 0.1]})),
            &[],
        )
    };
    let alpha = |a: f64| {
        let mut m = grey(json!({"alphaMode": "BLEND"}));
        m["pbrMetallicRoughness"]["baseColorFactor"][3] = json!(a);
        material(m, &[])
    };
    let cases = [
        (
            "explicit defaults of every layer",
            worst(&defaults, &explicit),
        ),
        (
            "a flat normal map and a white occlusion map",
            worst(&defaults, &flat_maps),
        ),
        (
            "half an 8-bit step of emission",
            worst(&emission(100.0), &emission(100.5)),
        ),
        (
            "half an 8-bit step of alpha",
            worst(&alpha(0.5), &alpha(0.5 + 0.5 / 255.0)),
        ),
    ];
    for (difference, delta_e) in cases {
        println!("passes: {difference}: ΔE {delta_e:.2}");
        assert!(delta_e < 1.0, "{difference}: ΔE {delta_e} should pass");
    }
}

/// The specular peak: two smooth lobes of different widths differ just off the mirror
/// direction, which the fixed directions never meet.
#[test]
fn smooth_lobes_of_different_widths_are_told_apart_and_equal_ones_are_not() {
    let gold = |roughness: f64| material(pbr([1.0, 0.78, 0.34], 1.0, roughness), &[]);
    let dielectric = |roughness: f64| material(pbr([0.3, 0.3, 0.6], 0.0, roughness), &[]);
    for (pair, delta_e) in [
        (
            "gold mirror against roughness 0.05",
            worst(&gold(0.0), &gold(0.05)),
        ),
        (
            "dielectric roughness 0.10 against 0.15",
            worst(&dielectric(0.1), &dielectric(0.15)),
        ),
    ] {
        println!("caught: {pair}: ΔE {delta_e:.2}");
        assert!(delta_e > 5.0, "{pair}: ΔE {delta_e}");
    }
    let control = worst(&gold(0.3), &gold(0.3 + 0.5 / 255.0));
    assert!(
        control < 1.0,
        "half an 8-bit step of roughness: ΔE {control}"
    );
}

/// A sharp 2² base colour read through `sampler` (a glTF sampler object).
fn sampled(sampler: Value) -> MaterialSource {
    use crate::document::Tree;
    use crate::shade::sample::{Sampler, TextureSet};
    let image = image::RgbImage::from_fn(2, 2, |x, y| match (x + y) % 2 {
        0 => image::Rgb([240, 230, 220]),
        _ => image::Rgb([20, 30, 40]),
    });
    let textures = [Some(crate::shade::sample::texture_of(image))];
    let mut m = pbr([1.0; 3], 0.0, 0.5);
    m["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
    let (m, sampler) = (Tree::of(&m), Tree::of(&sampler));
    let textures = TextureSet {
        images: &textures,
        samplers: &[Sampler::of(Some(sampler.root()))],
        ..TextureSet::default()
    };
    MaterialSource::gltf2_sampled(m.root(), &textures)
}

#[test]
fn the_sampler_a_texture_is_read_through_is_seen() {
    let linear = sampled(json!({}));
    let cases = [
        (
            "magnified NEAREST against LINEAR",
            sampled(json!({"magFilter": 9728})),
        ),
        (
            "CLAMP_TO_EDGE against REPEAT",
            sampled(json!({"wrapS": 33071, "wrapT": 33071})),
        ),
        (
            "MIRRORED_REPEAT against REPEAT",
            sampled(json!({"wrapS": 33648})),
        ),
    ];
    for (change, other) in cases {
        let delta_e = worst(&linear, &other);
        println!("caught: {change}: ΔE {delta_e:.2}");
        assert!(delta_e > 1.0, "{change}: ΔE {delta_e}");
    }
    let explicit =
        sampled(json!({"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}));
    assert_eq!(
        worst(&linear, &explicit),
        0.0,
        "explicit default sampler values"
    );
}
