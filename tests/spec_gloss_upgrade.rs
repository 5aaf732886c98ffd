//! `upgrade` of glTF 2.0 assets that use the archived KHR_materials_pbrSpecularGlossiness:
//! every spec-gloss material becomes metal-rough + KHR_materials_specular +
//! KHR_materials_ior, everything else passes through, and the proof can fail.

mod common;

use common::{linear_to_srgb, srgb_to_linear};

use gltfmat::upgrade_output as output;
use gltfmat::{prove, upgrade, FolderResources, NoResources, UpgradeOptions, Upgraded};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

const SPEC_GLOSS: &str = "KHR_materials_pbrSpecularGlossiness";

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/spec-gloss")
        .join(name)
}

fn upgrade_path(path: &Path, options: &UpgradeOptions) -> Upgraded {
    let bytes = std::fs::read(path).unwrap();
    let loader = FolderResources::new(path.parent().unwrap());
    upgrade(&bytes, &loader, options).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The JSON of an input (.gltf or the JSON chunk of a .glb).
fn input_json(path: &Path) -> Value {
    let bytes = std::fs::read(path).unwrap();
    if bytes.starts_with(b"glTF") {
        let length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        serde_json::from_slice(&bytes[20..20 + length]).unwrap()
    } else {
        serde_json::from_slice(&bytes).unwrap()
    }
}

/// The bytes of every bufferView of an input, read here from its buffers.
fn input_views(path: &Path, json: &Value) -> Vec<Vec<u8>> {
    let bytes = std::fs::read(path).unwrap();
    let buffers: Vec<Vec<u8>> = json["buffers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|buffer| match buffer["uri"].as_str() {
            Some(uri) => std::fs::read(path.parent().unwrap().join(uri)).unwrap(),
            None => {
                let json_length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
                bytes[20 + json_length + 8..].to_vec()
            }
        })
        .collect();
    views_of(json, &buffers)
}

fn views_of(json: &Value, buffers: &[Vec<u8>]) -> Vec<Vec<u8>> {
    let views = json["bufferViews"].as_array().cloned().unwrap_or_default();
    views
        .iter()
        .map(|view| {
            let buffer = &buffers[view["buffer"].as_u64().unwrap() as usize];
            let start = view["byteOffset"].as_u64().unwrap_or(0) as usize;
            buffer[start..start + view["byteLength"].as_u64().unwrap() as usize].to_vec()
        })
        .collect()
}

/// The 2.0 spec-gloss assets: the fixtures, and Blender's in ../shared when it is there.
fn spec_gloss_assets(test: &str) -> Vec<PathBuf> {
    let mut assets: Vec<PathBuf> = [
        "factors.gltf",
        "chromatic.gltf",
        "textured.gltf",
        "mixed.glb",
        "transform.gltf",
    ]
    .into_iter()
    .map(fixture)
    .collect();
    if let Some(blender) = common::shared("real-world/gltf2/blender-io", test) {
        for name in ["04_sphere_specular_glossiness", "14_emission_strength"] {
            assets.push(blender.join(name).join(format!("{name}.gltf")));
        }
    }
    assets
}

#[test]
fn every_spec_gloss_asset_converts_to_an_asset_that_passes_its_check() {
    for path in spec_gloss_assets("every_spec_gloss_asset_converts") {
        let upgraded = upgrade_path(&path, &UpgradeOptions::default());
        for name in ["out.glb", "out.gltf"] {
            let report = output::verify(&output::layout(&upgraded, name));
            assert!(
                !report.has_errors(),
                "{} as {name}: {:?}",
                path.display(),
                report.diagnostics
            );
        }
        let left = notes_saying(&upgraded, "left as spec-gloss");
        for (i, material) in upgraded.json.to_value()["materials"]
            .as_array()
            .unwrap()
            .iter()
            .enumerate()
        {
            let still = material["extensions"].get(SPEC_GLOSS).is_some();
            let reported = left
                .iter()
                .any(|p| p.starts_with(&format!("/materials/{i}/")));
            assert_eq!(
                still,
                reported,
                "{} material {i}: kept only when reported",
                path.display()
            );
        }
    }
}

fn notes_saying(upgraded: &Upgraded, text: &str) -> Vec<String> {
    (upgraded.report.iter())
        .filter(|n| n.text.contains(text))
        .map(|n| n.pointer.clone())
        .collect()
}

#[test]
fn everything_but_the_materials_passes_through_unchanged() {
    for path in spec_gloss_assets("everything_but_the_materials_passes_through") {
        let before = input_json(&path);
        let upgraded = upgrade_path(&path, &UpgradeOptions::default());
        let after = &upgraded.json.to_value();
        let material_side = [
            "materials",
            "textures",
            "images",
            "samplers",
            "buffers",
            "extensionsUsed",
            "extensionsRequired",
        ];
        for (key, value) in before.as_object().unwrap() {
            if !material_side.contains(&key.as_str()) {
                assert_eq!(&after[key], value, "{}: /{key} changed", path.display());
            }
        }
        let binary = upgraded.binary.to_vec();
        assert_eq!(
            views_of(after, &[binary]),
            input_views(&path, &before),
            "{}: a bufferView's bytes changed",
            path.display()
        );
        assert_eq!(
            after["buffers"][0]["byteLength"],
            before["buffers"][0]["byteLength"]
        );
        // Members of a converted material other than its PBR parameters are kept; a texture
        // they read may be renumbered (textures only the conversion used are not written),
        // but it reads the same image.
        let image_bytes = upgraded_image_bytes(&upgraded);
        let source_images = input_image_bytes(&path, &before);
        for (old, new) in before["materials"]
            .as_array()
            .unwrap()
            .iter()
            .zip(after["materials"].as_array().unwrap())
        {
            for (key, value) in old.as_object().unwrap() {
                if key == "extensions" || key == "pbrMetallicRoughness" {
                    continue;
                }
                let (mut value, mut kept) = (value.clone(), new[key].clone());
                if let (Some(i), Some(j)) = (value["index"].as_u64(), kept["index"].as_u64()) {
                    assert_eq!(
                        source_images(i),
                        image_bytes(j),
                        "{}: {key} reads another image",
                        path.display()
                    );
                    value["index"] = json!(0);
                    kept["index"] = json!(0);
                }
                assert_eq!(kept, value, "{}: material member {key}", path.display());
            }
        }
    }
}

/// The image bytes texture `index` of an input reads.
fn input_image_bytes<'a>(path: &'a Path, json: &'a Value) -> impl Fn(u64) -> Vec<u8> + 'a {
    let views = input_views(path, json);
    move |texture| {
        let image = &json["images"][json["textures"][texture as usize]["source"]
            .as_u64()
            .unwrap() as usize];
        match image["uri"].as_str() {
            Some(uri) => std::fs::read(path.parent().unwrap().join(uri)).unwrap(),
            None => views[image["bufferView"].as_u64().unwrap() as usize].clone(),
        }
    }
}

/// The image bytes texture `index` of an upgraded asset reads.
fn upgraded_image_bytes(upgraded: &Upgraded) -> impl Fn(u64) -> Vec<u8> + '_ {
    move |texture| {
        let source = upgraded.json.to_value()["textures"][texture as usize]["source"]
            .as_u64()
            .unwrap();
        upgraded.images[source as usize].bytes.to_vec()
    }
}

/// The worst ΔE2000 of each material of `path` against its conversion, as the upgrade's proof
/// finds it (every texel centre of the finest texture, the corners between them, the mesh).
fn delta_e(path: &Path, upgraded: &Upgraded) -> Vec<f64> {
    let loader = FolderResources::new(path.parent().unwrap());
    let bytes = std::fs::read(path).unwrap();
    let name = path.to_string_lossy();
    let proof = prove(bytes, &name, &loader, upgraded).unwrap();
    proof.into_iter().map(|o| o.result.max).collect()
}

#[test]
fn conversions_prove_and_the_proof_catches_a_naive_one() {
    for name in [
        "factors.gltf",
        "chromatic.gltf",
        "textured.gltf",
        "transform.gltf",
    ] {
        let path = fixture(name);
        let upgraded = upgrade_path(&path, &UpgradeOptions::default());
        for (i, worst) in delta_e(&path, &upgraded).into_iter().enumerate() {
            assert!(worst < 1.0, "{name} material {i}: ΔE {worst}");
        }
    }
    // Specular (0.9, 0.1, 0.1): the source balances its diffuse per channel (1 − F_c), the
    // target by 1 − max F. diffuse · (1 − max specular), exact only for an achromatic
    // specular, is caught, and so is the diffuse taken as it is (glTF-Transform's mapping);
    // a proof that evaluated the source by the target's model would find 0 for both.
    let path = fixture("chromatic.gltf");
    let diffuse = [0.2, 0.6, 0.3];
    for (mapping, base) in [
        ("1 − max specular", diffuse.map(|d| d * (1.0 - 0.9))),
        ("diffuse as it is", diffuse),
    ] {
        let mut upgraded = upgrade_path(&path, &UpgradeOptions::default());
        upgraded.json.items_mut("materials").update(0, |material| {
            material["pbrMetallicRoughness"]["baseColorFactor"] =
                json!([base[0], base[1], base[2], 1.0]);
        });
        let worst = delta_e(&path, &upgraded)[0];
        assert!(worst > 1.0, "{mapping}: ΔE {worst}");
    }
}

#[test]
fn mixed_resolutions_render_like_their_source_at_the_inputs_texel_centres_and_corners() {
    // mixed.glb: an 8×8 diffuse with a 4×4 spec-gloss texture, and the reverse. The rebakes
    // lie on an odd multiple of the 8×8 grid, so the proof's grid holds the inputs' texel
    // centres and corners, where the rebakes must agree with the conversion of the inputs.
    let path = fixture("mixed.glb");
    let upgraded = upgrade_path(&path, &UpgradeOptions::default());
    for (i, worst) in delta_e(&path, &upgraded).into_iter().enumerate() {
        assert!(
            worst < 1.0,
            "material {i}: ΔE {worst} at the texel centres and corners"
        );
    }
}

/// Bilinear sample of an 8-bit sRGB image with repeat wrapping: RGB decoded to linear texel
/// by texel before they are mixed (as a GPU filters an sRGB texture), alpha as stored; 0..1.
fn bilinear(image: &image::RgbaImage, u: f64, v: f64) -> [f64; 4] {
    let (w, h) = (image.width() as i64, image.height() as i64);
    let (x, y) = (u * w as f64 - 0.5, v * h as f64 - 0.5);
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |i: i64, j: i64| {
        image
            .get_pixel(i.rem_euclid(w) as u32, j.rem_euclid(h) as u32)
            .0
    };
    let (a, b, c, d) = (
        at(x0 as i64, y0 as i64),
        at(x0 as i64 + 1, y0 as i64),
        at(x0 as i64, y0 as i64 + 1),
        at(x0 as i64 + 1, y0 as i64 + 1),
    );
    std::array::from_fn(|k| {
        let level = |p: [u8; 4]| match k {
            3 => f64::from(p[k]) / 255.0,
            _ => srgb_to_linear(f64::from(p[k]) / 255.0),
        };
        let top = level(a) * (1.0 - fx) + level(b) * fx;
        let bottom = level(c) * (1.0 - fx) + level(d) * fx;
        top * (1.0 - fy) + bottom * fy
    })
}

fn image_of(upgraded: &Upgraded, info: &Value) -> image::RgbaImage {
    let texture = info["index"].as_u64().unwrap() as usize;
    let source = upgraded.json.to_value()["textures"][texture]["source"]
        .as_u64()
        .unwrap() as usize;
    image::load_from_memory(&upgraded.images[source].bytes)
        .unwrap()
        .to_rgba8()
}

#[test]
fn rebaked_texels_follow_the_formula() {
    // Source images by texture index, decoded from the input asset itself.
    for (name, material) in [("textured.gltf", 0), ("mixed.glb", 0), ("mixed.glb", 1)] {
        let path = fixture(name);
        let before = input_json(&path);
        let image_bytes = input_image_bytes(&path, &before);
        let source_image = |slot: &str| -> image::RgbaImage {
            let block = &before["materials"][material]["extensions"][SPEC_GLOSS];
            let bytes = image_bytes(block[slot]["index"].as_u64().unwrap());
            image::load_from_memory(&bytes).unwrap().to_rgba8()
        };
        let block = &before["materials"][material]["extensions"][SPEC_GLOSS];
        let factor = |key: &str, i: usize, default: f64| block[key][i].as_f64().unwrap_or(default);
        let (diffuse, specular) = (
            source_image("diffuseTexture"),
            source_image("specularGlossinessTexture"),
        );
        let upgraded = upgrade_path(&path, &UpgradeOptions::default());
        let pbr = &upgraded.json.to_value()["materials"][material]["pbrMetallicRoughness"];
        let base = image_of(&upgraded, &pbr["baseColorTexture"]);
        let roughness = image_of(&upgraded, &pbr["metallicRoughnessTexture"]);
        let finer = (
            diffuse.width().max(specular.width()),
            diffuse.height().max(specular.height()),
        );
        // The finer grid, or an odd multiple of it where the product is not linear enough
        // between texel centres, which a decision line says.
        let scale = base.width() / finer.0;
        assert_eq!(
            base.dimensions(),
            (finer.0 * scale, finer.1 * scale),
            "{name}"
        );
        assert_eq!(scale % 2, 1, "{name}: an odd multiple ({scale})");
        let said = notes_saying(&upgraded, &format!("rebaked at {scale}× its inputs' grid"));
        assert_eq!(said.is_empty(), scale == 1, "{name}: {said:?}");
        for (x, y, texel) in base.enumerate_pixels() {
            let (u, v) = (
                (x as f64 + 0.5) / base.width() as f64,
                (y as f64 + 0.5) / base.height() as f64,
            );
            let (d, s) = (bilinear(&diffuse, u, v), bilinear(&specular, u, v));
            for (c, &diffuse) in d.iter().enumerate().take(3) {
                let keep = 1.0 - s[c] * factor("specularFactor", c, 1.0);
                let expected =
                    linear_to_srgb(diffuse * factor("diffuseFactor", c, 1.0) * keep) * 255.0;
                assert!(
                    (f64::from(texel.0[c]) - expected).abs() <= 0.5 + 1e-9,
                    "{name} material {material} texel ({x}, {y}) channel {c}: {} vs {expected}",
                    texel.0[c]
                );
            }
            assert!(
                (f64::from(texel.0[3]) - d[3] * 255.0 * factor("diffuseFactor", 3, 1.0)).abs()
                    <= 0.5 + 1e-9
            );
        }
        // Stored on the scale of the roughnessFactor: within half a step of that scale.
        let scale = pbr["roughnessFactor"].as_f64().unwrap();
        for (x, y, texel) in roughness.enumerate_pixels() {
            let gloss = f64::from(specular.get_pixel(x, y).0[3]) / 255.0
                * block["glossinessFactor"].as_f64().unwrap_or(1.0);
            assert!(
                (scale * f64::from(texel.0[1]) - (1.0 - gloss) * 255.0).abs() <= 0.5 * scale + 1e-6,
                "{name} roughness ({x}, {y}) on the scale {scale}"
            );
            assert_eq!(texel.0[2], 0, "dielectric: metallic 0");
        }
    }
}

fn upgrade_json(asset: Value) -> Upgraded {
    upgrade(
        asset.to_string().as_bytes(),
        &NoResources,
        &UpgradeOptions::default(),
    )
    .unwrap()
}

#[test]
fn a_material_with_an_excluded_extension_or_unlit_is_reported_not_converted() {
    let sg = json!({"diffuseFactor": [0.5, 0.5, 0.5, 1], "specularFactor": [0.1, 0.1, 0.1]});
    let upgraded = upgrade_json(json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": [SPEC_GLOSS, "KHR_materials_sheen", "KHR_materials_unlit", "KHR_materials_emissive_strength"],
        "materials": [
            {"extensions": {SPEC_GLOSS: sg, "KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1]}}},
            {"extensions": {SPEC_GLOSS: sg, "KHR_materials_unlit": {}}},
            {"extensions": {SPEC_GLOSS: sg, "KHR_materials_emissive_strength": {"emissiveStrength": 2}}},
        ]
    }));
    let materials = &upgraded.json.to_value()["materials"];
    assert!(materials[0]["extensions"].get(SPEC_GLOSS).is_some());
    assert!(materials[1]["extensions"].get(SPEC_GLOSS).is_some());
    let left = notes_saying(&upgraded, "left as spec-gloss");
    assert_eq!(left.len(), 2, "{:?}", upgraded.report);
    assert!(upgraded.report.iter().any(|n| n
        .text
        .contains("KHR_materials_sheen, which the spec-gloss extension excludes")));
    // emissive_strength is allowed with spec-gloss: that material is converted and keeps it.
    assert!(materials[2]["extensions"].get(SPEC_GLOSS).is_none());
    assert_eq!(
        materials[2]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"],
        2
    );
    let used = upgraded.json.get("extensionsUsed").unwrap();
    let used: Vec<&str> = used
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .collect();
    assert!(
        used.contains(&SPEC_GLOSS),
        "still used by materials 0 and 1"
    );
    assert!(used.contains(&"KHR_materials_specular") && used.contains(&"KHR_materials_ior"));
}

#[test]
fn the_extension_leaves_the_extension_lists_when_no_material_uses_it() {
    let upgraded = upgrade_json(json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": [SPEC_GLOSS],
        "extensionsRequired": [SPEC_GLOSS],
        "materials": [{"extensions": {SPEC_GLOSS: {"glossinessFactor": 0.5}}}]
    }));
    assert_eq!(
        upgraded.json.to_value()["extensionsUsed"],
        json!(["KHR_materials_specular", "KHR_materials_ior"])
    );
    assert!(upgraded.json.to_value().get("extensionsRequired").is_none());
    assert_eq!(
        upgraded.json.to_value()["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"],
        0.5
    );
}

#[test]
fn extension_mode_leaves_a_2_0_asset_as_it_was() {
    let path = fixture("textured.gltf");
    let options =
        UpgradeOptions::default().with_specular_glossiness(gltfmat::SpecularGlossiness::Extension);
    let upgraded = upgrade_path(&path, &options);
    let before = input_json(&path);
    assert_eq!(upgraded.json.to_value()["materials"], before["materials"]);
    assert_eq!(upgraded.json.to_value()["textures"], before["textures"]);
}

#[test]
fn several_buffers_are_joined_and_their_views_move_with_their_bytes() {
    use base64::Engine;
    let data = |bytes: &[u8]| {
        format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(bytes)
        )
    };
    let upgraded = upgrade_json(json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": data(&[1, 2, 3]), "byteLength": 3}, {"uri": data(&[9, 8, 7, 6]), "byteLength": 4, "name": "second"}],
        "bufferViews": [{"buffer": 0, "byteLength": 3}, {"buffer": 1, "byteOffset": 1, "byteLength": 3}]
    }));
    let binary = upgraded.binary.to_vec();
    assert_eq!(
        views_of(&upgraded.json.to_value(), &[binary]),
        vec![vec![1, 2, 3], vec![8, 7, 6]]
    );
    assert_eq!(
        upgraded.json.to_value()["buffers"]
            .as_array()
            .unwrap()
            .len(),
        1
    );
}

/// Runs the CLI; its exit status, stdout and stderr.
fn gltfmat(args: &[&str]) -> (i32, Vec<u8>, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(args)
        .output()
        .expect("gltfmat runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (out.status.code().unwrap_or(-1), out.stdout, stderr)
}

#[test]
fn every_upgrade_proves_itself_and_verify_makes_a_failed_proof_refuse() {
    let dir = std::env::temp_dir().join(format!("gltfmat-sg-cli-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // mixed.glb's sharp 8×8 textures are rebaked on a finer grid, which leaves a difference
    // between texel centres below the default threshold and above 0.2: the proof fails there.
    let input = fixture("mixed.glb");
    let input = input.to_str().unwrap();
    let out = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let strict = ["--threshold", "0.2"];
    let (code, stdout, _) = gltfmat(&["upgrade", input, "-o", &out("d.glb")]);
    assert_eq!(code, 0);
    let stdout = String::from_utf8_lossy(&stdout);
    assert!(!stdout.contains("DIFFERENT"), "{stdout}");

    // The proof's figures are printed, and a failure is a warning.
    let (code, stdout, _) =
        gltfmat(&[&["upgrade", input, "-o", &out("a.glb")][..], &strict].concat());
    let stdout = String::from_utf8_lossy(&stdout);
    assert_eq!(code, 0, "{stdout}");
    assert!(
        stdout.contains("proof: material 1 (fine spec-gloss)") && stdout.contains("DIFFERENT"),
        "{stdout}"
    );
    assert!(stdout.contains(
        "warning: the proof does not show that every converted material renders like its source"
    ));

    // --verify refuses it; nothing is written.
    let (code, stdout, _) = gltfmat(
        &[
            &["upgrade", input, "-o", &out("b.glb"), "--verify"][..],
            &strict,
        ]
        .concat(),
    );
    assert_eq!(code, 1, "{}", String::from_utf8_lossy(&stdout));
    assert!(!dir.join("b.glb").exists());

    // --no-verify skips it.
    let (code, stdout, _) = gltfmat(&["upgrade", input, "-o", &out("c.glb"), "--no-verify"]);
    assert_eq!(code, 0);
    assert!(!String::from_utf8_lossy(&stdout).contains("proof:"));

    // With the asset on stdout, the proof goes to stderr and stdout is the GLB alone.
    let (code, stdout, stderr) = gltfmat(&[&["upgrade", input, "-o", "-"][..], &strict].concat());
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("proof: material 1"), "{stderr}");
    assert!(stdout.starts_with(b"glTF"));
    let length = u32::from_le_bytes(stdout[8..12].try_into().unwrap()) as usize;
    assert_eq!(length, stdout.len(), "nothing but the GLB on stdout");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn materials_sharing_textures_and_factors_share_their_rebakes() {
    let path = fixture("textured.gltf");
    let mut asset = input_json(&path);
    let material = asset["materials"][0].clone();
    asset["materials"] = json!([material.clone(), material]);
    let loader = FolderResources::new(path.parent().unwrap());
    let upgraded = upgrade(
        asset.to_string().as_bytes(),
        &loader,
        &UpgradeOptions::default(),
    )
    .unwrap();
    let pbr = |i: usize| upgraded.json.to_value()["materials"][i]["pbrMetallicRoughness"].clone();
    assert_eq!(pbr(0), pbr(1), "the same textures");
    // The spec-gloss image (now the specular colour) and the normal map, plus one base
    // colour and one roughness rebake (the diffuse image is no longer used).
    assert_eq!(
        upgraded.images.len(),
        4,
        "{:?}",
        upgraded.json.to_value()["images"]
    );
}

#[test]
fn a_material_whose_texture_cannot_be_decoded_is_left_and_reported() {
    use base64::Engine;
    let broken = base64::engine::general_purpose::STANDARD.encode(b"\x89PNG not really");
    let upgraded = upgrade_json(json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": [SPEC_GLOSS],
        "images": [{"uri": format!("data:image/png;base64,{broken}")}],
        "textures": [{"source": 0}],
        "materials": [
            {"extensions": {SPEC_GLOSS: {"specularGlossinessTexture": {"index": 0}}}},
            {"extensions": {SPEC_GLOSS: {"glossinessFactor": 0.5}}}
        ]
    }));
    let left = notes_saying(&upgraded, "cannot be rebaked");
    assert_eq!(left, vec![format!("/materials/0/extensions/{SPEC_GLOSS}")]);
    assert!(upgraded.json.to_value()["materials"][0]["extensions"]
        .get(SPEC_GLOSS)
        .is_some());
    assert!(upgraded.json.to_value()["materials"][1]["extensions"]
        .get(SPEC_GLOSS)
        .is_none());
    assert_eq!(upgraded.images.len(), 1, "no rebake was added");
}

/// A 2.0 input with errors of its own that have nothing to do with its materials: the
/// materials are converted and the output written with those errors passed through (and
/// said); `--strict` refuses it.
#[test]
fn errors_the_input_had_are_passed_through_and_only_strict_refuses_them() {
    let folder = tempfile::tempdir().unwrap();
    let mut asset = input_json(&fixture("factors.gltf"));
    asset["nodes"][0]["children"] = json!([]); // an error of the input's own
    let source = fixture("factors.gltf");
    for file in std::fs::read_dir(source.parent().unwrap())
        .unwrap()
        .flatten()
    {
        if file.path().extension().is_some_and(|e| e == "bin") {
            std::fs::copy(file.path(), folder.path().join(file.file_name())).unwrap();
        }
    }
    std::fs::write(folder.path().join("in.gltf"), asset.to_string()).unwrap();
    let run = |extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["upgrade", "in.gltf", "-o", "out.gltf", "--force"])
            .args(extra)
            .current_dir(folder.path())
            .output()
            .unwrap()
    };
    let passed = run(&[]);
    let stdout = String::from_utf8_lossy(&passed.stdout);
    assert_eq!(
        passed.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&passed.stderr)
    );
    assert!(
        stdout.contains("the input has 1 error(s) of its own"),
        "{stdout}"
    );
    assert!(
        stdout.contains("(the input's own, passed through)"),
        "{stdout}"
    );
    let written: Value =
        serde_json::from_slice(&std::fs::read(folder.path().join("out.gltf")).unwrap()).unwrap();
    assert!(written["materials"][0]["extensions"]["KHR_materials_specular"].is_object());
    std::fs::remove_file(folder.path().join("out.gltf")).unwrap();
    let strict = run(&["--strict"]);
    assert_eq!(strict.status.code(), Some(1));
    assert!(!folder.path().join("out.gltf").exists());
}

#[test]
fn a_material_the_evaluator_cannot_show_is_not_evaluated_and_verify_refuses_it() {
    // factors.gltf with an extension no evaluator knows on its material: the conversion
    // carries it, the proof cannot show it, so it proves nothing and --verify writes nothing.
    let dir = std::env::temp_dir().join(format!("gltfmat-sg-unknown-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut asset = input_json(&fixture("factors.gltf"));
    asset["materials"][0]["extensions"]["VENDOR_materials_glow"] = json!({"glow": 1.0});
    let used = asset["extensionsUsed"].as_array_mut().unwrap();
    used.push(json!("VENDOR_materials_glow"));
    for (key, value) in asset["buffers"].as_array().unwrap().iter().enumerate() {
        if let Some(uri) = value["uri"].as_str().filter(|u| !u.starts_with("data:")) {
            let from = fixture("factors.gltf").parent().unwrap().join(uri);
            std::fs::copy(from, dir.join(uri)).unwrap_or_else(|e| panic!("buffer {key}: {e}"));
        }
    }
    let input = dir.join("in.gltf");
    std::fs::write(&input, asset.to_string()).unwrap();
    let out = dir.join("out.glb");
    let (code, stdout, stderr) = gltfmat(&[
        "upgrade",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--verify",
    ]);
    let stdout = String::from_utf8_lossy(&stdout);
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(
        stdout.contains("NOT EVALUATED (first: VENDOR_materials_glow"),
        "{stdout}"
    );
    assert!(!out.exists(), "nothing is written");
    let _ = std::fs::remove_dir_all(&dir);
}

/// mixed.glb (8×8 diffuse over 4×4 spec-gloss, and the reverse) with its one sampler, or
/// its textures' samplers, replaced.
fn mixed_with(samplers: Value, texture_samplers: [u64; 4]) -> Vec<u8> {
    let glb = std::fs::read(fixture("mixed.glb")).unwrap();
    let length = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let mut json: Value = serde_json::from_slice(&glb[20..20 + length]).unwrap();
    let bin = &glb[20 + length + 8..];
    json["samplers"] = samplers;
    for (texture, sampler) in texture_samplers.into_iter().enumerate() {
        json["textures"][texture]["sampler"] = json!(sampler);
    }
    common::glb(json.to_string().as_bytes(), Some(bin))
}

#[test]
fn textures_are_rebaked_as_their_samplers_read_them() {
    // The coarser texture of each material is read at the finer one's texel centres: through
    // NEAREST it is its nearest texel, not a blend of four; by a texture's edge CLAMP and
    // MIRRORED_REPEAT read the edge texel, not the opposite side's.
    for sampler in [
        json!({"magFilter": 9728}),
        json!({"wrapS": 33071, "wrapT": 33071}),
        json!({"magFilter": 9728, "wrapS": 33648, "wrapT": 33071}),
    ] {
        let bytes = mixed_with(json!([sampler]), [0; 4]);
        let upgraded = upgrade(&bytes, &NoResources, &UpgradeOptions::default()).unwrap();
        let proof = prove(bytes, "mixed.glb", &NoResources, &upgraded).unwrap();
        assert_eq!(proof.len(), 2);
        for outcome in proof {
            assert!(outcome.result.max < 1.0, "{sampler}: {outcome:?}");
        }
    }
}

#[test]
fn a_material_whose_two_textures_are_read_through_different_samplers_is_left() {
    // Material 0 reads NEAREST and LINEAR; material 1 two samplers that say the same.
    let samplers = json!([{"magFilter": 9728}, {}, {"magFilter": 9729, "wrapS": 10497}]);
    let bytes = mixed_with(samplers, [0, 1, 1, 2]);
    let upgraded = upgrade(&bytes, &NoResources, &UpgradeOptions::default()).unwrap();
    let materials = &upgraded.json.to_value()["materials"];
    assert!(materials[0]["extensions"].get(SPEC_GLOSS).is_some());
    assert!(materials[1]["extensions"].get(SPEC_GLOSS).is_none());
    let left = notes_saying(&upgraded, "samplers that filter or wrap differently");
    assert_eq!(left.len(), 1, "{:?}", upgraded.report);
}

#[test]
fn an_image_the_evaluator_cannot_decode_leaves_only_its_materials_unproved() {
    use base64::Engine;
    // Material 0 converts; material 1, passed through, reads an image that decodes to
    // nothing (a PNG cut short after its signature).
    let broken = base64::engine::general_purpose::STANDARD.encode(b"\x89PNG\r\n\x1a\n");
    let asset = json!({"asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "images": [{"uri": format!("data:image/png;base64,{broken}")}],
        "textures": [{"source": 0}],
        "materials": [
            {"extensions": {"KHR_materials_pbrSpecularGlossiness": {
                "diffuseFactor": [0.5, 0.4, 0.3, 1.0], "glossinessFactor": 0.4}}},
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]});
    let bytes = serde_json::to_vec(&asset).unwrap();
    let upgraded = upgrade(&bytes[..], &NoResources, &UpgradeOptions::default()).unwrap();
    let proof = prove(&bytes[..], "asset.gltf", &NoResources, &upgraded).unwrap();
    assert_eq!(proof.len(), 1, "the converted material only");
    assert!(proof[0].is_evaluated(), "{:?}", proof[0].result);
    assert!(gltfmat::proof_holds(&proof, 1.0));
}

/// An image file that cannot be read (here missing), or a data URI holding no image, is an
/// error of the input's own: the upgrade leaves it as the input has it (its `uri` kept, no
/// file written), converts every material that does not read its texels, and leaves as
/// spec-gloss, with the reason, one that does; the output is written with that error passed
/// through.
#[test]
fn a_missing_image_is_left_as_it_was_and_only_a_conversion_reading_it_is_left() {
    let folder = tempfile::tempdir().unwrap();
    for file in [
        "textured.gltf",
        "diffuse16.png",
        "specgloss16.png",
        "normal.png",
        "quad.bin",
    ] {
        std::fs::copy(fixture(file), folder.path().join(file)).unwrap();
    }
    let mut asset = input_json(&fixture("textured.gltf"));
    asset["images"]
        .as_array_mut()
        .unwrap()
        .push(json!({"uri": "missing.png"}));
    asset["textures"]
        .as_array_mut()
        .unwrap()
        .push(json!({"source": 3}));
    let plain =
        json!({"name": "plain", "pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}});
    asset["materials"].as_array_mut().unwrap().push(plain);
    let run = |asset: &Value| {
        std::fs::write(folder.path().join("in.gltf"), asset.to_string()).unwrap();
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["upgrade", "in.gltf", "-o", "out.gltf", "--force"])
            .current_dir(folder.path())
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout).into_owned()
            + &String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{text}");
        let written = std::fs::read(folder.path().join("out.gltf")).unwrap();
        (serde_json::from_slice::<Value>(&written).unwrap(), text)
    };
    let (written, text) = run(&asset);
    assert!(
        text.contains("decision /images/3 missing.png: no such file"),
        "{text}"
    );
    assert!(
        written["materials"][0]["extensions"]
            .get(SPEC_GLOSS)
            .is_none(),
        "{text}"
    );
    let kept = written["images"].as_array().unwrap().iter();
    assert_eq!(
        kept.filter(|image| image["uri"] == "missing.png").count(),
        1,
        "{text}"
    );
    assert!(!folder.path().join("missing.png").exists());
    // A data URI that holds no image is the same wherever the output lies: it stays as it
    // is, rather than be written with a media type it does not have.
    let garbage = "data:application/octet-stream;base64,Z2FyYmFnZQ==";
    let mut with_garbage = asset.clone();
    with_garbage["images"][3]["uri"] = json!(garbage);
    let (written, text) = run(&with_garbage);
    assert!(
        text.contains("decision /images/3 its data URI holds no image"),
        "{text}"
    );
    let kept = written["images"].as_array().unwrap().iter();
    assert_eq!(
        kept.filter(|image| image["uri"] == garbage).count(),
        1,
        "{text}"
    );
    // The spec-gloss material's diffuse texture reads the missing image: it is left.
    asset["textures"][0]["source"] = json!(3);
    let (written, text) = run(&asset);
    assert!(
        written["materials"][0]["extensions"]
            .get(SPEC_GLOSS)
            .is_some(),
        "{text}"
    );
    assert!(
        text.contains("left as spec-gloss: its textures cannot be rebaked: /images/3: missing.png: no such file"),
        "{text}"
    );
}
