//! The comparison against a dense reference: every point of a UV grid four times as fine as
//! the finest texture (texel centres, edges and corners), every direction of a regular grid
//! over views and lights up to the search's limit with each view's mirror direction and
//! offsets from it, and the worst found refined. Slow, and only here: it says whether the
//! fast comparison's points and its search find the maximum on materials made to hide it.

use super::refine::MAX_THETA;
use super::{compare, delta_at, Angles};
use crate::shade::brdf::SheenVisibility;
use crate::shade::material::Shader;
use crate::shade::sample::{texture_of, MaterialSource, Texture};
use crate::shade::sheen_table::SheenTable;
use serde_json::{json, Value};

fn shader() -> Shader {
    Shader::new(SheenTable::compute(2, SheenVisibility::Charlie))
}

/// The reference's directions: views every 15° (two azimuths), lights every 7.5° and 30°,
/// and each view's mirror direction with offsets from 0.05° to 4°.
fn directions() -> Vec<Angles> {
    let steps = |step: f64| {
        (0..)
            .map(move |k| k as f64 * step)
            .take_while(|t| *t <= MAX_THETA)
    };
    let mut out = Vec::new();
    for theta_v in steps(15.0) {
        for phi_v in [0.0, 90.0] {
            let view = [theta_v, phi_v];
            for theta_l in steps(7.5) {
                for k in 0..12 {
                    out.push(Angles {
                        view,
                        light: [theta_l, phi_v + 30.0 * f64::from(k)],
                    });
                }
            }
            for offset in [0.0, 0.05, 0.2, 0.5, 1.0, 2.0, 4.0] {
                for light in [
                    [theta_v + offset, phi_v + 180.0],
                    [(theta_v - offset).max(0.0), phi_v + 180.0],
                    [theta_v, phi_v + 180.0 + offset],
                ] {
                    if light[0] <= MAX_THETA {
                        out.push(Angles { view, light });
                    }
                }
            }
        }
    }
    out
}

/// The largest ΔE2000 the reference finds, refined by a pattern search from its worst.
fn reference_max(shader: &Shader, a: &MaterialSource, b: &MaterialSource, texels: u32) -> f64 {
    let fine = 4 * texels;
    let directions = directions();
    let mut worst = (0.0, None);
    for y in 0..fine {
        for x in 0..fine {
            // Quarter-texel steps from a corner: corners, edges, centres and between.
            let uv = [
                f64::from(x) / f64::from(fine),
                f64::from(y) / f64::from(fine),
            ];
            let (ia, ib) = (a.inputs_at(&[uv]), b.inputs_at(&[uv]));
            if ia == ib {
                continue;
            }
            for angles in &directions {
                let d = delta_at(shader, &ia, &ib, angles).0;
                if d > worst.0 {
                    worst = (d, Some((ia.clone(), ib.clone(), *angles)));
                }
            }
        }
    }
    let Some((ia, ib, start)) = worst.1 else {
        return 0.0;
    };
    super::refine::climb(start, |angles| delta_at(shader, &ia, &ib, angles))
        .1
         .0
}

/// A `side`² texture whose texel (x, y) is `texel(x, y)`.
fn texture(side: u32, texel: impl Fn(u32, u32) -> [u8; 4]) -> Texture {
    texture_of(image::RgbaImage::from_fn(side, side, |x, y| {
        image::Rgba(texel(x, y))
    }))
}

fn with(json: Value, textures: &[&Texture]) -> MaterialSource {
    let textures: Vec<Option<Texture>> = textures.iter().map(|t| Some((*t).clone())).collect();
    MaterialSource::gltf2(&json, &textures)
}

fn mr(base: [f64; 3], metallic: f64, roughness: f64) -> Value {
    json!({"pbrMetallicRoughness": {"baseColorFactor": [base[0], base[1], base[2], 1.0],
        "metallicFactor": metallic, "roughnessFactor": roughness}})
}

#[test]
fn the_fast_maximum_is_the_dense_references_on_materials_made_to_hide_it() {
    let shader = shader();
    let smooth = texture(8, |x, y| [(30 * x) as u8, (20 * y + 40) as u8, 120, 255]);
    let sharp = texture(8, |x, y| match (x + y) % 2 {
        0 => [250, 240, 230, 255],
        _ => [20, 30, 40, 255],
    });
    let sharp_specular = texture(8, |x, _| match x % 2 {
        0 => [230, 230, 230, 255],
        _ => [10, 10, 10, 255],
    });
    let coarse_specular = texture(4, |x, y| [(60 * x) as u8, (60 * y) as u8, 90, 200]);
    let textured = |extra: Value| {
        let mut m = mr([1.0; 3], 0.0, 0.5);
        m["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
        for (key, value) in extra.as_object().into_iter().flatten() {
            m["pbrMetallicRoughness"][key] = value.clone();
        }
        m
    };
    let spec_gloss = json!({"extensions": {"KHR_materials_pbrSpecularGlossiness": {
        "diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1}}}});
    // Each converted texel-centre by texel-centre (diffuse · (1 − specular) of the texels),
    // which is exact at the centres and not between them.
    let converted = |diffuse: &Texture, specular: &Texture| {
        let side = diffuse.width().max(specular.width());
        let at = |t: &Texture, x: u32, y: u32| {
            let uv = [
                (f64::from(x) + 0.5) / f64::from(side),
                (f64::from(y) + 0.5) / f64::from(side),
            ];
            crate::shade::sample::sampled_srgb(t, uv, Default::default())
        };
        let base = texture(side, |x, y| {
            let (d, s) = (at(diffuse, x, y), at(specular, x, y));
            let c = |k: usize| crate::gltf::color::linear_to_srgb8(d[k] * (1.0 - s[k]));
            [c(0), c(1), c(2), 255]
        });
        let specular_colour = specular.clone();
        let target = json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                "metallicFactor": 0.0, "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_specular": {"specularColorTexture": {"index": 1}},
                "KHR_materials_ior": {"ior": 0}}});
        (base, specular_colour, target)
    };
    let (sharp_base, sharp_spec, sharp_target) = converted(&sharp, &sharp_specular);
    let (mixed_base, mixed_spec, mixed_target) = converted(&smooth, &coarse_specular);
    let cases: Vec<(&str, MaterialSource, MaterialSource, u32)> = vec![
        (
            "a smooth texture, roughness 0.5 against 0.55",
            with(textured(json!({})), &[&smooth]),
            with(textured(json!({"roughnessFactor": 0.55})), &[&smooth]),
            8,
        ),
        (
            "a sharp spec-gloss converted at its texel centres",
            with(spec_gloss.clone(), &[&sharp, &sharp_specular]),
            with(sharp_target, &[&sharp_base, &sharp_spec]),
            8,
        ),
        (
            "mixed resolutions converted at the finer grid's centres",
            with(spec_gloss, &[&smooth, &coarse_specular]),
            with(mixed_target, &[&mixed_base, &mixed_spec]),
            8,
        ),
        (
            "a sharp texture moved by half a texel",
            with(textured(json!({})), &[&sharp]),
            with(
                textured(json!({"baseColorTexture": {"index": 0, "extensions":
                    {"KHR_texture_transform": {"offset": [0.0625, 0.0]}}}})),
                &[&sharp],
            ),
            8,
        ),
        (
            "a near-mirror metal, roughness 0.02 against 0.06",
            with(mr([1.0, 0.78, 0.34], 1.0, 0.02), &[]),
            with(mr([1.0, 0.78, 0.34], 1.0, 0.06), &[]),
            1,
        ),
        (
            "a near-mirror dielectric, roughness 0.08 against 0.12",
            with(mr([0.3, 0.3, 0.6], 0.0, 0.08), &[]),
            with(mr([0.3, 0.3, 0.6], 0.0, 0.12), &[]),
            1,
        ),
        (
            "half an 8-bit step of base colour (a control)",
            with(mr([0.5, 0.3, 0.2], 0.0, 0.4), &[]),
            with(mr([0.5 * 1.004, 0.3, 0.2], 0.0, 0.4), &[]),
            1,
        ),
    ];
    for (case, a, b, texels) in cases {
        let fast = compare(&shader, &a, &b, 0).max;
        let reference = reference_max(&shader, &a, &b, texels);
        println!("{case}: fast {fast:.3}, reference {reference:.3}");
        assert!(
            (fast - reference).abs() <= (0.1 * reference).max(0.5),
            "{case}: fast {fast} against the reference's {reference}"
        );
    }
}
