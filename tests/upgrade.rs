//! `gltfmat upgrade` and `gltfmat::upgrade`: every 1.0 asset converts to a 2.0 asset that
//! passes gltfmat's check, materials convert as documented, and files are handled safely.

mod common;
use common::{data_uri, linear_to_srgb, shared, srgb_to_linear};

use gltfmat::upgrade_output as output;
use gltfmat::{
    upgrade, FolderResources, NoResources, Severity, SpecGlossReading, SpecularGlossiness,
    UpgradeOptions, Upgraded,
};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

fn upgrade_file(path: &Path, options: &UpgradeOptions) -> Upgraded {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let loader = FolderResources::new(path.parent().unwrap());
    upgrade(&bytes, &loader, options).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Upgrades and checks the exact bytes that would be written, in both containers; the GLB
/// loads in gltf-rs (a real client) and every primitive's attributes read through it.
fn assert_upgrades_cleanly(path: &Path) {
    let upgraded = upgrade_file(path, &UpgradeOptions::default());
    let glb = upgraded.to_glb();
    let gltf = gltf::Gltf::from_slice(&glb)
        .unwrap_or_else(|e| panic!("{}: gltf-rs refuses the output: {e}", path.display()));
    let blob = gltf.blob.as_deref();
    for primitive in gltf.meshes().flat_map(|m| m.primitives()) {
        let reader = primitive.reader(|_| blob);
        assert!(reader.read_positions().is_some_and(|p| p.count() > 0));
        let _ = reader.read_indices().map(|i| i.into_u32().count());
        let _ = reader.read_tex_coords(0).map(|t| t.into_f32().count());
    }
    for name in ["out.glb", "out.gltf"] {
        let report = output::verify(&output::layout(&upgraded, name));
        assert_eq!(
            report.count(Severity::Error),
            0,
            "{} → {name}: {:?}",
            path.display(),
            report.diagnostics
        );
    }
}

#[test]
fn every_khronos_1_0_asset_upgrades_to_a_valid_2_0_asset() {
    let Some(folder) = shared("conformance/gltf-1.0-assets", "Khronos 1.0 boxes") else {
        return;
    };
    let mut count = 0;
    for entry in std::fs::read_dir(&folder).unwrap().flatten() {
        for file in std::fs::read_dir(entry.path())
            .into_iter()
            .flatten()
            .flatten()
        {
            let path = file.path();
            if matches!(
                path.extension().and_then(|e| e.to_str()),
                Some("gltf" | "glb")
            ) {
                assert_upgrades_cleanly(&path);
                count += 1;
            }
        }
    }
    assert_eq!(count, 7, "the seven Khronos 1.0 boxes");
}

#[test]
fn every_pbr_fixture_upgrades_to_a_valid_2_0_asset() {
    for name in [
        "pbr-mr-web3d.gltf",
        "pbr-sg-khr.gltf",
        "pbr-mr-textured-fraunhofer.gltf",
        "pbr-sg-textured-ext.gltf",
        "pbr-mr-textured-ext.glb",
        "pbr-sg-textured-fraunhofer.glb",
    ] {
        assert_upgrades_cleanly(&repo(&format!("fixtures/gltf1/{name}")));
    }
}

fn material(upgraded: &Upgraded) -> Value {
    upgraded.json.items("materials").unwrap().get(0).unwrap()
}

fn texture_rgba(upgraded: &Upgraded, info: &Value) -> image::RgbaImage {
    let texture = info["index"].as_u64().unwrap() as usize;
    let image = upgraded.json.to_value()["textures"][texture]["source"]
        .as_u64()
        .unwrap() as usize;
    image::load_from_memory(&upgraded.images[image].bytes)
        .unwrap()
        .to_rgba8()
}

fn fixture_png(name: &str) -> image::RgbaImage {
    image::open(repo(&format!("fixtures/gltf1/{name}")))
        .unwrap()
        .to_rgba8()
}

#[test]
fn metal_rough_moves_metallic_from_red_to_blue_texel_for_texel() {
    for fixture in ["pbr-mr-textured-fraunhofer.gltf", "pbr-mr-textured-ext.glb"] {
        let upgraded = upgrade_file(
            &repo(&format!("fixtures/gltf1/{fixture}")),
            &UpgradeOptions::default(),
        );
        let pbr = &material(&upgraded)["pbrMetallicRoughness"];
        assert_eq!(pbr["metallicFactor"], 0.7);
        assert_eq!(pbr["roughnessFactor"], 0.35);
        let rebaked = texture_rgba(&upgraded, &pbr["metallicRoughnessTexture"]);
        let source = fixture_png("metal_rough.png");
        for (x, y, texel) in source.enumerate_pixels() {
            let out = rebaked.get_pixel(x, y).0;
            assert_eq!(out[2], texel.0[0], "{fixture}: metallic at ({x}, {y})");
            assert_eq!(out[1], texel.0[1], "{fixture}: roughness at ({x}, {y})");
        }
        // The base colour texture is the original image, untouched.
        assert_eq!(
            texture_rgba(&upgraded, &pbr["baseColorTexture"]),
            fixture_png("diffuse.png")
        );
    }
}

#[test]
fn spec_gloss_factors_convert_to_the_closed_form_of_the_drafts_appendix() {
    // Diffuse (0.6, 0.5, 0.4), specular 0.2, glossiness 0.75: under the Appendix reading the
    // closed form (diffuse · (1 − specular), roughness 0.25, specularColor 0.2) is exact, and
    // is what is written; the drafts' readings differ by 7.71 here, which the proof reports
    // beside its own figure as the source's ambiguity.
    let path = repo("fixtures/gltf1/pbr-sg-khr.gltf");
    let upgraded = upgrade_file(&path, &UpgradeOptions::default());
    let m = material(&upgraded);
    let pbr = &m["pbrMetallicRoughness"];
    let base = numbers(&pbr["baseColorFactor"]);
    for (got, want) in base.iter().zip([0.6 * 0.8, 0.5 * 0.8, 0.4 * 0.8, 1.0]) {
        assert!((got - want).abs() < 1e-12, "the closed form: {base:?}");
    }
    assert!((pbr["roughnessFactor"].as_f64().unwrap() - 0.25).abs() < 1e-12);
    assert_eq!(pbr["metallicFactor"], 0.0);
    assert_eq!(m["extensions"]["KHR_materials_ior"]["ior"], 0);
    let specular = numbers(&m["extensions"]["KHR_materials_specular"]["specularColorFactor"]);
    assert_eq!(specular, [0.2, 0.2, 0.2]);
    let notes = notes(&upgraded).join("\n");
    assert!(!notes.contains("fitted:"), "{notes}");
    let loader = FolderResources::beside(&path);
    let input = std::fs::read(&path).unwrap();
    let proof = gltfmat::prove(&input, "khr.gltf", &loader, &upgraded).unwrap();
    assert!(proof[0].result.max < 0.05, "{}", proof[0].result.max);
    let ambiguity = proof[0].ambiguity.as_ref().expect("the drafts' spread");
    assert!((ambiguity.max - 7.71).abs() < 0.01, "{}", ambiguity.max);
    let used = upgraded.json.get("extensionsUsed").unwrap();
    let used = used.as_array().unwrap();
    assert!(
        used.contains(&"KHR_materials_specular".into())
            && used.contains(&"KHR_materials_ior".into())
    );
}

fn numbers(value: &serde_json::Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// The pbr-sg-khr fixture with `values` as its material's values, upgraded under `reading`,
/// and its proof.
fn upgrade_draft_values(
    values: serde_json::Value,
    reading: SpecGlossReading,
) -> (Upgraded, Vec<gltfmat::Outcome>) {
    let path = repo("fixtures/gltf1/pbr-sg-khr.gltf");
    let mut asset: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    asset["materials"]["Effect-Texture"]["extensions"]["KHR_materials_pbr"]["values"] = values;
    let bytes = asset.to_string().into_bytes();
    let loader = FolderResources::beside(&path);
    let options = UpgradeOptions::default().with_draft_reading(reading);
    let upgraded = upgrade(&bytes, &loader, &options).unwrap();
    let proof = gltfmat::prove(&bytes, "draft.gltf", &loader, &upgraded).unwrap();
    (upgraded, proof)
}

#[test]
fn each_draft_reading_converts_to_its_own_closed_form_and_its_proof_is_exact() {
    // Every achromatic factor case of the drafts' examples, and a chromatic one.
    let cases = [
        ([0.6, 0.5, 0.4], [0.2; 3], 0.75),
        ([0.6, 0.3, 0.2], [0.2; 3], 0.7),
        ([0.5, 0.4, 0.3], [0.04; 3], 0.5),
        ([0.8; 3], [0.9, 0.1, 0.1], 0.5),
    ];
    for reading in SpecGlossReading::DRAFTS {
        for (diffuse, specular, glossiness) in cases {
            let [r, g, b] = diffuse;
            let values = serde_json::json!({"diffuseFactor": [r, g, b, 1.0],
                "specularFactor": specular, "glossinessFactor": glossiness});
            let (upgraded, proof) = upgrade_draft_values(values, reading);
            let (closed, exact) = reading.closed_form_base(diffuse, specular);
            let figure = proof[0].result.max;
            let ambiguity = proof[0].ambiguity.as_ref().expect("a draft has readings");
            assert_eq!(ambiguity.read_as, reading.name());
            if exact {
                let base = numbers(&material(&upgraded)["pbrMetallicRoughness"]["baseColorFactor"]);
                for (got, want) in base.iter().zip(closed) {
                    assert!(
                        (got - want).abs() < 1e-9,
                        "{reading:?} {diffuse:?}: {base:?}"
                    );
                }
                assert!(
                    figure < 0.05,
                    "{reading:?} {diffuse:?} {specular:?}: ΔE {figure}"
                );
            } else {
                // No exact 2.0 form: the conversion moves towards this reading, and the
                // proof reports its figure under it, whatever the others say.
                let notes = notes(&upgraded).join("\n");
                assert!(notes.contains(reading.option_name()), "{notes}");
            }
        }
    }
}

#[test]
fn a_reading_with_no_exact_form_is_fitted_towards_itself_not_between_readings() {
    // The 2016 Appendix reading of a red specular over grey: base colour 0.8 · 0.9 / 0.1
    // would pass 1, so no 2.0 material draws it exactly; the fit serves that reading only.
    let values = serde_json::json!({"diffuseFactor": [0.8, 0.8, 0.8, 1.0],
        "specularFactor": [0.9, 0.1, 0.1], "glossinessFactor": 0.5});
    let (upgraded, proof) =
        upgrade_draft_values(values.clone(), SpecGlossReading::DraftAppendix2016);
    let notes = notes(&upgraded).join("\n");
    let fitted = notes
        .lines()
        .find(|l| l.contains("fitted:"))
        .unwrap_or_else(|| panic!("{notes}"));
    assert!(fitted.contains("'appendix-2016'"), "{fitted}");
    let closed_figure: f64 = fitted
        .split("from it; ")
        .next()
        .and_then(|t| t.rsplit("ΔE2000 ").next())
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{fitted}"));
    assert!(
        proof[0].result.max < closed_figure,
        "{} vs {closed_figure}",
        proof[0].result.max
    );
    // Under the Appendix the same material converts exactly, and no cyan appears.
    let (upgraded, proof) = upgrade_draft_values(values, SpecGlossReading::DraftAppendix);
    let base = numbers(&material(&upgraded)["pbrMetallicRoughness"]["baseColorFactor"]);
    assert!(
        (base[0] - 0.08).abs() < 1e-9 && (base[1] - 0.72).abs() < 1e-9,
        "{base:?}"
    );
    assert!(proof[0].result.max < 0.05, "{}", proof[0].result.max);
}

#[test]
fn texels_the_closed_form_leaves_above_the_threshold_are_fitted_and_only_those() {
    // Two texels of a 1.0 spec-gloss material read as the 2016 Appendix: a dark one its
    // closed form draws exactly, and a white one whose closed form would pass 1 (its red and
    // blue keep more of the diffuse than the green specular does). Only the white one is
    // fitted, towards that reading; the proof samples the stored 8-bit texels.
    let dir = scratch("texel-fit");
    let png = |path: &Path, pixels: [[u8; 4]; 2]| {
        let image = image::RgbaImage::from_fn(2, 1, |x, _| image::Rgba(pixels[x as usize]));
        image.save(path).unwrap();
    };
    let (dark, bright) = ([20, 18, 16, 255], [255, 255, 255, 255]);
    png(&dir.join("diffuse.png"), [dark, bright]);
    png(&dir.join("spec_gloss.png"), [[40, 200, 40, 139]; 2]);
    let source = repo("fixtures/gltf1/pbr-sg-textured-ext.gltf");
    let mut asset: Value = serde_json::from_slice(&std::fs::read(&source).unwrap()).unwrap();
    asset["materials"]["Effect-Texture"]["extensions"]["EXT_materials_pbr"]["values"] = serde_json::json!({
        "diffuseFactor": [1.0, 1.0, 1.0, 1.0], "specularFactor": [1.0, 1.0, 1.0], "glossinessFactor": 1.0,
        "diffuseTexture": "tex_diffuse", "specularGlossinessTexture": "tex_spec_gloss"});
    let path = dir.join("in.gltf");
    std::fs::copy(repo("fixtures/gltf1/box.bin"), dir.join("box.bin")).unwrap();
    std::fs::write(&path, asset.to_string()).unwrap();
    let reading = SpecGlossReading::DraftAppendix2016;
    let options = UpgradeOptions::default().with_draft_reading(reading);
    let upgraded = upgrade_file(&path, &options);
    let notes = notes(&upgraded).join("\n");
    assert!(
        notes.contains("2 distinct texel values")
            && notes.contains("1 above the threshold, 1 of them fitted towards that reading"),
        "{notes}"
    );
    let base = texture_rgba(
        &upgraded,
        &material(&upgraded)["pbrMetallicRoughness"]["baseColorTexture"],
    );
    let linear = |texel: [u8; 4], c: usize| srgb_to_linear(f64::from(texel[c]) / 255.0);
    let specular = |c: usize| srgb_to_linear([40.0, 200.0, 40.0][c] / 255.0);
    let closed_form = |texel: [u8; 4]| {
        let (base, _) =
            reading.closed_form_base([0, 1, 2].map(|c| linear(texel, c)), [0, 1, 2].map(specular));
        base.map(|b| (linear_to_srgb(b) * 255.0).round() as u8)
    };
    let stored = |x: u32| {
        let texel = base.get_pixel(x, 0).0;
        [texel[0], texel[1], texel[2]]
    };
    assert_eq!(
        stored(0),
        closed_form(dark),
        "the dark texel keeps the closed form"
    );
    assert_ne!(stored(1), closed_form(bright), "the white texel is fitted");
    let loader = FolderResources::beside(&path);
    let input = std::fs::read(&path).unwrap();
    let proof = gltfmat::prove(&input, "in.gltf", &loader, &upgraded).unwrap();
    assert!(proof[0].ambiguity.is_some());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn spec_gloss_textures_are_rebaked_per_texel() {
    let upgraded = upgrade_file(
        &repo("fixtures/gltf1/pbr-sg-textured-ext.gltf"),
        &UpgradeOptions::default(),
    );
    let m = material(&upgraded);
    let pbr = &m["pbrMetallicRoughness"];
    let base = texture_rgba(&upgraded, &pbr["baseColorTexture"]);
    let roughness = texture_rgba(&upgraded, &pbr["metallicRoughnessTexture"]);
    let (diffuse, spec_gloss) = (fixture_png("diffuse.png"), fixture_png("spec_gloss.png"));
    // The texels whose closed form is above the proof's threshold are fitted (see the next
    // test): the report says how many, and every other texel follows the formula.
    let fitted: usize = (notes(&upgraded).iter())
        .find_map(|note| {
            let (_, after) = note.split_once("above the threshold, ")?;
            after.split_once(" of them fitted")?.0.parse().ok()
        })
        .unwrap_or(0);
    let mut away_from_formula = 0;
    for (x, y, d) in diffuse.enumerate_pixels() {
        let s = spec_gloss.get_pixel(x, y).0;
        let follows = [0.6, 0.5, 0.4].iter().enumerate().all(|(c, factor)| {
            // Per channel: what the channel's specular does not take (see upgrade/spec_gloss.rs).
            let keep = 1.0 - srgb_to_linear(f64::from(s[c]) / 255.0) * 0.2;
            let linear = srgb_to_linear(f64::from(d.0[c]) / 255.0) * factor * keep;
            let want = linear_to_srgb(linear) * 255.0;
            (f64::from(base.get_pixel(x, y).0[c]) - want).abs() <= 0.51
        });
        away_from_formula += usize::from(!follows);
        let want_roughness = (1.0 - f64::from(s[3]) / 255.0 * 0.75) * 255.0;
        let got = f64::from(roughness.get_pixel(x, y).0[1]);
        assert!(
            (got - want_roughness).abs() <= 0.51,
            "roughness ({x}, {y}): {got} vs {want_roughness}"
        );
        assert_eq!(roughness.get_pixel(x, y).0[2], 0, "dielectric");
    }
    assert_eq!(
        away_from_formula, fitted,
        "only the fitted texels leave the formula"
    );
    assert!(
        fitted < 16 / 2,
        "most texels follow the formula: {fitted} fitted"
    );
    // The specular colour is the original spec-gloss texture (its RGB is the sRGB specular).
    let specular = &m["extensions"]["KHR_materials_specular"];
    assert_eq!(
        texture_rgba(&upgraded, &specular["specularColorTexture"]),
        spec_gloss
    );
}

#[test]
fn spec_gloss_extension_mode_is_an_exact_rename() {
    let options = UpgradeOptions::default().with_specular_glossiness(SpecularGlossiness::Extension);
    let upgraded = upgrade_file(
        &repo("fixtures/gltf1/pbr-sg-textured-fraunhofer.glb"),
        &options,
    );
    let sg = &material(&upgraded)["extensions"]["KHR_materials_pbrSpecularGlossiness"];
    assert_eq!(sg["diffuseFactor"], serde_json::json!([0.6, 0.5, 0.4, 1.0]));
    assert_eq!(sg["specularFactor"], serde_json::json!([0.2, 0.2, 0.2]));
    assert_eq!(sg["glossinessFactor"], 0.75);
    assert_eq!(
        texture_rgba(&upgraded, &sg["specularGlossinessTexture"]),
        fixture_png("spec_gloss.png")
    );
}

fn gltfmat(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("gltfmat runs");
    let text =
        String::from_utf8_lossy(&out.stdout).into_owned() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code().unwrap_or(-1), text)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gltfmat-upgrade-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_cli_writes_once_refuses_to_replace_and_never_touches_the_input() {
    let dir = scratch("cli");
    let input = dir.join("in.gltf");
    std::fs::copy(repo("fixtures/gltf1/pbr-mr-web3d.gltf"), &input).unwrap();
    let original = std::fs::read(&input).unwrap();
    let out = dir.join("out.gltf");
    let (code, text) = gltfmat(&[
        "upgrade",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{text}");
    assert!(out.is_file() && dir.join("out.bin").is_file(), "{text}");
    let (code, text) = gltfmat(&[
        "upgrade",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "an existing output needs --force: {text}");
    assert!(text.contains("--force"), "{text}");
    let (code, text) = gltfmat(&[
        "upgrade",
        input.to_str().unwrap(),
        "-o",
        input.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 2, "{text}");
    assert_eq!(
        std::fs::read(&input).unwrap(),
        original,
        "the input is never overwritten"
    );
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "no temporary files are left behind");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_output_that_fails_the_check_is_not_written() {
    let dir = scratch("refuse");
    // A WebP image is legal in 1.0 files seen in the wild but needs EXT_texture_webp in 2.0:
    // the converted asset fails the check, so nothing may be written.
    let webp = b"RIFF\x1a\x00\x00\x00WEBPVP8L\x0d\x00\x00\x00\x2f\x00\x00\x00\x10\x07\x10\x11\x11\x88\x88\xfe\x07\x00";
    let asset = serde_json::json!({
        "asset": {"version": "1.0"},
        "images": {"i": {"uri": "tex.webp"}},
        "samplers": {"s": {}},
        "textures": {"t": {"source": "i", "sampler": "s"}},
        "materials": {"m": {"extensions": {"EXT_materials_pbr": {"materialModel": "PBR_metal_roughness", "values": {"baseColorTexture": "t"}}}}},
        "scenes": {"s": {"nodes": []}}, "scene": "s"
    });
    std::fs::write(dir.join("in.gltf"), serde_json::to_vec(&asset).unwrap()).unwrap();
    std::fs::write(dir.join("tex.webp"), webp).unwrap();
    let out = dir.join("out.glb");
    let (code, text) = gltfmat(&[
        "upgrade",
        dir.join("in.gltf").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("nothing was written"), "{text}");
    // The refusal names the input construct the failing output object was made from.
    assert!(text.contains("was made from 1.0 /images/i"), "{text}");
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

mod verify {
    use super::*;

    /// The proof's worst ΔE2000 of the fixture's first material against its conversion,
    /// corrupted by `corrupt` first.
    fn worst_delta_e(fixture: &str, corrupt: impl FnOnce(&mut Upgraded)) -> f64 {
        let path = repo(&format!("fixtures/gltf1/{fixture}"));
        let mut upgraded = upgrade_file(&path, &UpgradeOptions::default());
        corrupt(&mut upgraded);
        let bytes = std::fs::read(&path).unwrap();
        let loader = FolderResources::new(path.parent().unwrap());
        let proof = gltfmat::prove(bytes, fixture, &loader, &upgraded).unwrap();
        proof[0].result.max
    }

    #[test]
    fn the_conversions_render_like_their_sources() {
        assert_eq!(
            worst_delta_e("pbr-mr-textured-fraunhofer.gltf", |_| {}),
            0.0
        );
        assert!(
            worst_delta_e("pbr-sg-textured-ext.gltf", |_| {}) < 1.0,
            "8-bit rebaking stays under one JND"
        );
    }

    #[test]
    fn compare_catches_metallic_left_in_red() {
        let wrong = worst_delta_e("pbr-mr-textured-fraunhofer.gltf", |upgraded| {
            let pbr = &upgraded.json.to_value()["materials"][0]["pbrMetallicRoughness"];
            let texture = pbr["metallicRoughnessTexture"]["index"].as_u64().unwrap() as usize;
            let image = upgraded.json.to_value()["textures"][texture]["source"]
                .as_u64()
                .unwrap() as usize;
            let swizzled = std::fs::read(repo("fixtures/gltf1/metal_rough.png")).unwrap();
            upgraded.images[image].bytes = std::sync::Arc::new(swizzled.into());
        });
        assert!(
            wrong > 1.0,
            "the un-swizzled texture must be caught: ΔE {wrong}"
        );
    }

    /// A 1.0 spec-gloss factor material with `specular`, upgraded with `--verify` and
    /// `options`: the proof judges under the reading converted to.
    fn verify_spec_gloss(specular: [f64; 3], options: &[&str]) -> (i32, String) {
        let dir = scratch(&format!("chromatic-{}-{}", specular[1], options.join("")));
        let mut asset: serde_json::Value =
            serde_json::from_slice(&std::fs::read(repo("fixtures/gltf1/pbr-sg-khr.gltf")).unwrap())
                .unwrap();
        asset["materials"]["Effect-Texture"]["extensions"]["KHR_materials_pbr"]["values"]
            ["specularFactor"] = specular.into();
        let input = dir.join("in.gltf");
        std::fs::write(&input, asset.to_string()).unwrap();
        let out = dir.join("out.glb");
        let mut args = vec![
            "upgrade",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--verify",
        ];
        args.extend(options);
        let result = gltfmat(&args);
        assert_eq!(
            out.exists(),
            result.0 == 0,
            "written only when the proof holds: {}",
            result.1
        );
        let _ = std::fs::remove_dir_all(&dir);
        result
    }

    fn max_delta_e(text: &str) -> f64 {
        let at = text.find("ΔE2000 max ").expect("a ΔE figure") + "ΔE2000 max ".len();
        text[at..]
            .split([',', ' '])
            .next()
            .unwrap()
            .parse()
            .unwrap()
    }

    #[test]
    fn a_chromatic_specular_passes_under_the_appendix_and_each_reading_is_chosen_by_flag() {
        // Exact under the default reading, with the drafts' spread printed beside the figure.
        let (code, text) = verify_spec_gloss([0.9, 0.1, 0.1], &[]);
        assert_eq!(code, 0, "{text}");
        assert!(max_delta_e(&text) < 0.05, "{text}");
        assert!(
            text.contains("the drafts' readings differ by up to ΔE2000"),
            "{text}"
        );
        // The 2016 reading of the same material has no exact form: refused with its figure.
        let (code, text) =
            verify_spec_gloss([0.9, 0.1, 0.1], &["--draft-reading", "appendix-2016"]);
        assert_eq!(code, 1, "{text}");
        assert!(max_delta_e(&text) > 1.0, "{text}");
        assert!(
            text.contains("source read as the 2016 drafts' Appendix"),
            "{text}"
        );
        // A dim achromatic specular is exact under both Appendix readings. The example
        // shader's diffuse is not weighed by 1 − F at all, which no 2.0 material draws: its
        // fit is close at the fixed directions and the specular peak, and the proof's dense
        // search still finds it off by more than the threshold (view 15°, light 75°).
        for reading in ["appendix", "appendix-2016"] {
            let (code, text) = verify_spec_gloss([0.02, 0.02, 0.02], &["--draft-reading", reading]);
            assert_eq!(code, 0, "{reading}: {text}");
            assert!(max_delta_e(&text) <= 1.0, "{text}");
        }
        let (code, text) =
            verify_spec_gloss([0.02, 0.02, 0.02], &["--draft-reading", "example-shader"]);
        assert_eq!(code, 1, "{text}");
        assert!(
            max_delta_e(&text) > 1.0 && text.contains("January 2017 example shader"),
            "{text}"
        );
    }

    #[test]
    fn the_cli_verifies_before_writing() {
        let dir = scratch("verify");
        let out = dir.join("out.glb");
        let (code, text) = gltfmat(&[
            "upgrade",
            "fixtures/gltf1/pbr-sg-textured-ext.gltf",
            "-o",
            out.to_str().unwrap(),
            "--verify",
        ]);
        assert_eq!(code, 0, "{text}");
        assert!(text.contains("same: ΔE2000 max"), "{text}");
        let (code, text) = gltfmat(&[
            "compare",
            "fixtures/gltf1/pbr-sg-textured-ext.gltf",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{text}");
        let (code, text) = gltfmat(&[
            "compare",
            "fixtures/gltf1/pbr-sg-khr.gltf",
            out.to_str().unwrap(),
            "--format",
            "json",
        ]);
        assert_eq!(code, 1, "a different material fails: {text}");
        assert!(text.contains("\"pass\": false"), "{text}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

mod structure {
    use super::*;
    use gltfmat::NoResources;
    use serde_json::json;

    /// A hand-written 1.0 asset exercising the structural conversions: a skinned node with
    /// two meshes, a bind shape matrix, a camera with znear 0, a blending technique without
    /// culling, and a KHR_materials_common CONSTANT material.
    fn asset() -> serde_json::Value {
        asset_weighted([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    }

    /// [`asset`] with each vertex's four WEIGHT values given (every JOINT value is 0).
    fn asset_weighted(weights: [f32; 12]) -> serde_json::Value {
        let mut data = Vec::new();
        for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
            data.extend(v.to_le_bytes()); // POSITION
        }
        for v in [
            0.0f32, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        ] {
            data.extend(v.to_le_bytes()); // JOINT (3 × VEC4)
        }
        for v in weights {
            data.extend(v.to_le_bytes()); // WEIGHT
        }
        let identity = [
            1.0f32, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ];
        identity.iter().for_each(|v| data.extend(v.to_le_bytes())); // inverse bind matrix
        let uri = data_uri("application/octet-stream", &data);
        let accessor = |offset: usize, count: usize, kind: &str| json!({"bufferView": "v", "byteOffset": offset, "componentType": 5126, "count": count, "type": kind, "min": [0], "max": [0]});
        json!({
            "asset": {"version": "1.0"},
            "buffers": {"b": {"uri": uri, "byteLength": data.len()}},
            "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": data.len()}},
            "accessors": {"pos": accessor(0, 3, "VEC3"), "joint": accessor(36, 3, "VEC4"), "weight": accessor(84, 3, "VEC4"), "ibm": accessor(132, 1, "MAT4")},
            "techniques": {"t": {"states": {"enable": [3042, 2929], "functions": {"blendFuncSeparate": [1, 771, 1, 771]}}}},
            "materials": {
                "blended": {"technique": "t", "values": {"diffuse": [1.0, 0.5, 0.25, 1.0]}},
                "flat": {"extensions": {"KHR_materials_common": {"technique": "CONSTANT", "values": {"diffuse": [0.5, 0.5, 0.5, 1.0]}}}}
            },
            "meshes": {
                "m1": {"primitives": [{"attributes": {"POSITION": "pos", "JOINT": "joint", "WEIGHT": "weight"}, "material": "blended"}]},
                "m2": {"primitives": [{"attributes": {"POSITION": "pos", "JOINT": "joint", "WEIGHT": "weight"}, "material": "flat"}]}
            },
            "skins": {"s": {"bindShapeMatrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1], "inverseBindMatrices": "ibm", "jointNames": ["j"]}},
            "cameras": {"c": {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.0, "zfar": 100.0}}},
            "nodes": {
                "root": {"children": ["joint", "skinned"], "camera": "c"},
                "joint": {"jointName": "j"},
                "skinned": {"meshes": ["m1", "m2"], "skin": "s", "skeletons": ["joint"]}
            },
            "scenes": {"s": {"nodes": ["root"]}},
            "scene": "s"
        })
    }

    fn upgraded() -> Upgraded {
        let bytes = serde_json::to_vec(&asset()).unwrap();
        upgrade(&bytes, &NoResources, &UpgradeOptions::default()).unwrap()
    }

    /// 1.0 let a vertex name a joint twice; 2.0 forbids it. Merged with the summed weight, the
    /// vertex skins the same, and both meshes sharing the pair share the merged one.
    #[test]
    fn a_joint_listed_twice_in_a_vertex_is_merged_into_one_with_the_summed_weight() {
        let halves = [0.5, 0.5, 0.0, 0.0, 0.25, 0.75, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];
        let bytes = serde_json::to_vec(&asset_weighted(halves)).unwrap();
        let up = upgrade(&bytes, &NoResources, &UpgradeOptions::default()).unwrap();
        let report =
            gltfmat::upgrade_output::verify(&gltfmat::upgrade_output::layout(&up, "out.glb"));
        assert!(!report.has_errors(), "{:?}", report.diagnostics);
        let json = up.json.to_value();
        let attributes = |mesh: usize| json["meshes"][mesh]["primitives"][0]["attributes"].clone();
        assert_eq!(
            attributes(0)["WEIGHTS_0"],
            attributes(1)["WEIGHTS_0"],
            "one merged pair"
        );
        let glb = gltf::Gltf::from_slice(&up.to_glb()).unwrap();
        let primitive = glb.meshes().next().unwrap().primitives().next().unwrap();
        let reader = primitive.reader(|_| glb.blob.as_deref());
        let weights: Vec<[f32; 4]> = reader.read_weights(0).unwrap().into_f32().collect();
        assert_eq!(weights, [[1.0, 0.0, 0.0, 0.0]; 3]);
        assert!(up
            .report
            .iter()
            .any(|n| n.text.contains("2 of 3 vertices list a joint twice")));
    }

    /// A technique's material and a KHR_materials_common one are drawn by lighting models the
    /// evaluator does not shade: the proof compares what can be read of them (emission and
    /// coverage), says their lighting is not evaluated, and holds (before, the proof said
    /// nothing of them and `compare` found no pair at all).
    #[test]
    fn the_proof_compares_lit_materials_by_emission_and_coverage() {
        let bytes = serde_json::to_vec(&asset()).unwrap();
        let up = upgrade(&bytes, &NoResources, &UpgradeOptions::default()).unwrap();
        let proof = gltfmat::prove(&bytes, "asset.gltf", &NoResources, &up).unwrap();
        let named: Vec<&str> = proof.iter().map(|o| o.a.1.as_str()).collect();
        assert_eq!(named, ["blended", "flat"]);
        for outcome in &proof {
            assert!(outcome.is_evaluated(), "{}", outcome.a.1);
            assert!(!outcome.same(1.0), "never the same: {}", outcome.a.1);
            assert!(
                outcome.only_lighting_unread(),
                "{:?}",
                outcome.not_evaluated
            );
            assert_eq!(outcome.result.max, 0.0, "{}", outcome.a.1);
        }
        assert!(gltfmat::proof_holds(&proof, 1.0));
    }

    #[test]
    fn technique_states_become_blending_and_double_sidedness() {
        let up = upgraded();
        let blended = &up.json.to_value()["materials"][0];
        assert_eq!(blended["alphaMode"], "BLEND");
        assert_eq!(blended["doubleSided"], true, "CULL_FACE is not enabled");
        let flat = &up.json.to_value()["materials"][1];
        assert!(
            flat["extensions"]["KHR_materials_unlit"].is_object(),
            "CONSTANT → unlit"
        );
        assert!(
            flat.get("doubleSided").is_none(),
            "no technique: the option's default (false)"
        );
    }

    #[test]
    fn extra_meshes_become_skinned_children_and_the_bind_shape_is_folded() {
        let up = upgraded();
        let json = up.json.to_value();
        let nodes = json["nodes"].as_array().unwrap();
        let skinned = &nodes[2];
        assert_eq!(skinned["mesh"], 0);
        let child = skinned["children"][0].as_u64().unwrap() as usize;
        assert_eq!(nodes[child]["mesh"], 1);
        assert_eq!(
            nodes[child]["skin"], skinned["skin"],
            "the extra mesh keeps the skin"
        );
        let skin = &up.json.to_value()["skins"][skinned["skin"].as_u64().unwrap() as usize];
        assert_eq!(skin["joints"], json!([1]));
        // IBM · BSM with IBM = identity is the bind shape matrix: translation x = 5.
        let accessor = &up.json.to_value()["accessors"]
            [skin["inverseBindMatrices"].as_u64().unwrap() as usize];
        let view =
            &up.json.to_value()["bufferViews"][accessor["bufferView"].as_u64().unwrap() as usize];
        let start = view["byteOffset"].as_u64().unwrap() as usize;
        let translation_x = f32::from_le_bytes(
            up.binary.to_vec()[start + 48..start + 52]
                .try_into()
                .unwrap(),
        );
        assert_eq!(translation_x, 5.0);
        let mesh = &up.json.to_value()["meshes"][0]["primitives"][0]["attributes"];
        assert!(
            mesh.get("JOINTS_0").is_some() && mesh.get("WEIGHTS_0").is_some(),
            "{mesh}"
        );
    }

    #[test]
    fn a_zero_znear_is_made_valid() {
        let up = upgraded();
        let znear = up.json.to_value()["cameras"][0]["perspective"]["znear"]
            .as_f64()
            .unwrap();
        assert!(znear > 0.0 && znear < 1.0, "{znear}");
        let report = output::verify(&output::layout(&up, "out.glb"));
        assert_eq!(report.count(Severity::Error), 0, "{:?}", report.diagnostics);
    }

    #[test]
    fn the_double_sided_option_applies_to_materials_that_say_nothing_of_culling() {
        let mut source = asset();
        // Neither a technique nor KHR_materials_common: the 1.0 default material.
        source["materials"]["plain"] = json!({});
        let bytes = serde_json::to_vec(&source).unwrap();
        let options = UpgradeOptions::default().with_double_sided_default(true);
        let up = upgrade(&bytes, &NoResources, &options).unwrap();
        let materials = &up.json.to_value()["materials"];
        assert_eq!(materials[2]["name"], "plain");
        assert_eq!(materials[2]["doubleSided"], true);
        let by_default = upgrade(&bytes, &NoResources, &UpgradeOptions::default()).unwrap();
        assert_eq!(
            by_default.json.to_value()["materials"][2].get("doubleSided"),
            None
        );
    }

    /// KHR_materials_common is used "in favor of the supplied technique": beside a technique
    /// that blends and does not cull, the extension's own `transparent` and `doubleSided`
    /// (false by default, which the option does not override) decide, in the output as in
    /// the proof.
    #[test]
    fn a_common_material_is_drawn_as_its_extension_says_not_as_its_fallback_technique() {
        let mut source = asset();
        let flat = &mut source["materials"]["flat"];
        flat["technique"] = json!("t");
        let common = |double_sided: Option<bool>| {
            let mut source = source.clone();
            if let Some(value) = double_sided {
                source["materials"]["flat"]["extensions"]["KHR_materials_common"]["doubleSided"] =
                    json!(value);
            }
            serde_json::to_vec(&source).unwrap()
        };
        let options = UpgradeOptions::default().with_double_sided_default(true);
        for (double_sided, expected) in
            [(None, None), (Some(false), None), (Some(true), Some(true))]
        {
            let bytes = common(double_sided);
            let up = upgrade(&bytes, &NoResources, &options).unwrap();
            let flat = &up.json.to_value()["materials"][1];
            assert_eq!(flat.get("alphaMode"), None, "{double_sided:?}: {flat}");
            assert_eq!(
                flat.get("doubleSided").and_then(Value::as_bool),
                expected,
                "{double_sided:?}"
            );
            let proof = gltfmat::prove(&bytes, "asset.gltf", &NoResources, &up).unwrap();
            assert!(gltfmat::proof_holds(&proof, 1.0), "{double_sided:?}");
        }
    }
}

#[test]
fn a_scene_without_nodes_upgrades_to_a_valid_scene() {
    let gltf1 =
        br#"{"asset": {"version": "1.0"}, "scene": "s", "scenes": {"s": {"nodes": ["missing"]}}}"#;
    let up = upgrade(gltf1, &NoResources, &UpgradeOptions::default()).unwrap();
    assert!(up.json.to_value()["scenes"][0].get("nodes").is_none());
    assert!(up
        .report
        .iter()
        .any(|n| n.text.contains("'missing' does not exist")));
    let report = gltfmat::check_bytes("s.glb", up.to_glb(), &NoResources, &Default::default());
    assert!(!report.has_errors(), "{:?}", report.diagnostics);
}

#[test]
fn a_gltf_output_is_indented_for_reading_unless_its_json_is_larger_than_a_person_reads() {
    let lines = |upgraded: &Upgraded| {
        let files = output::layout(upgraded, "out.gltf");
        files.main.bytes().iter().filter(|&&b| b == b'\n').count()
    };
    let small = upgrade(
        &br#"{"asset": {"version": "1.0"}, "nodes": {"a": {}}}"#[..],
        &NoResources,
        &UpgradeOptions::default(),
    )
    .unwrap();
    assert!(lines(&small) > 5, "indented: a line per member");
    // 20,000 nodes with 200-character names: over 4 MiB of JSON.
    let nodes: serde_json::Map<String, Value> = (0..20_000)
        .map(|i| {
            (
                format!("n{i}"),
                serde_json::json!({"name": format!("{i:0>200}")}),
            )
        })
        .collect();
    let large = serde_json::json!({"asset": {"version": "1.0"}, "nodes": nodes});
    let large = upgrade(
        serde_json::to_vec(&large).unwrap(),
        &NoResources,
        &UpgradeOptions::default(),
    )
    .unwrap();
    assert_eq!(
        lines(&large),
        1,
        "compact: one line and the final line break"
    );
}

/// A one-triangle 1.0 asset whose vertex attributes are the given VEC3 arrays (3 vertices
/// each), plus an animation with no channels.
fn gltf1_triangle(attributes: &[(&str, [[f32; 3]; 3])]) -> Vec<u8> {
    let mut bin = Vec::new();
    let mut accessors = serde_json::Map::new();
    let mut semantics = serde_json::Map::new();
    for (k, (semantic, vertices)) in attributes.iter().enumerate() {
        let offset = bin.len();
        bin.extend(vertices.iter().flatten().flat_map(|v| v.to_le_bytes()));
        let (low, high) = (0..3).fold(([f32::MAX; 3], [f32::MIN; 3]), |(mut l, mut h), c| {
            for v in vertices {
                l[c] = l[c].min(v[c]);
                h[c] = h[c].max(v[c]);
            }
            (l, h)
        });
        accessors.insert(
            format!("a{k}"),
            serde_json::json!({"bufferView": "v", "byteOffset": offset,
            "componentType": 5126, "count": 3, "type": "VEC3", "min": low, "max": high}),
        );
        semantics.insert(semantic.to_string(), serde_json::json!(format!("a{k}")));
    }
    let uri = data_uri("application/octet-stream", &bin);
    serde_json::to_vec(&serde_json::json!({
        "asset": {"version": "1.0"},
        "buffers": {"b": {"uri": uri, "byteLength": bin.len()}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": bin.len(), "target": 34962}},
        "accessors": accessors,
        "meshes": {"m": {"primitives": [{"attributes": semantics, "mode": 4}]}},
        "nodes": {"n": {"meshes": ["m"]}},
        "animations": {"idle": {"channels": [], "samplers": {}, "parameters": {}}},
        "scenes": {"s": {"nodes": ["n"]}},
        "scene": "s"
    }))
    .unwrap()
}

#[test]
fn vec3_tangents_get_the_handedness_of_their_binormal_and_empty_animations_are_dropped() {
    let up = [0.0, 0.0, 1.0];
    let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let asset = gltf1_triangle(&[
        ("POSITION", positions),
        ("NORMAL", [up; 3]),
        ("TANGENT", [[1.0, 0.0, 0.0]; 3]),
        // cross(N, T) = +Y; a binormal along −Y makes the frame left-handed: w = −1.
        (
            "BINORMAL",
            [[0.0, -1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 1.0, 0.0]],
        ),
    ]);
    let upgraded = upgrade(&asset, &NoResources, &UpgradeOptions::default()).unwrap();
    let attributes = &upgraded.json.to_value()["meshes"][0]["primitives"][0]["attributes"];
    assert!(attributes.get("BINORMAL").is_none() && attributes.get("_BINORMAL").is_none());
    let tangent =
        &upgraded.json.to_value()["accessors"][attributes["TANGENT"].as_u64().unwrap() as usize];
    assert_eq!(tangent["type"], "VEC4");
    assert_eq!(tangent["min"], serde_json::json!([1.0, 0.0, 0.0, -1.0]));
    assert_eq!(tangent["max"], serde_json::json!([1.0, 0.0, 0.0, 1.0]));
    assert!(
        upgraded.json.to_value().get("animations").is_none(),
        "the empty animation is dropped"
    );
    assert!(upgraded
        .report
        .iter()
        .any(|n| n.pointer == "/animations/idle" && n.text.contains("animates nothing")));
    let report = output::verify(&output::layout(&upgraded, "out.glb"));
    assert!(!report.has_errors(), "{:?}", report.diagnostics);
}

/// A 1.0 triangle (`gltf1_triangle`'s) changed by `edit`, upgraded with the default options.
fn upgraded_triangle(edit: impl FnOnce(&mut Value)) -> Result<Upgraded, gltfmat::UpgradeError> {
    let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mut asset: Value =
        serde_json::from_slice(&gltf1_triangle(&[("POSITION", positions)])).unwrap();
    edit(&mut asset);
    upgrade(
        serde_json::to_vec(&asset).unwrap(),
        &NoResources,
        &UpgradeOptions::default(),
    )
}

/// Whether the upgrade's report has a note at `pointer` saying `words`.
fn said(upgraded: &Upgraded, pointer: &str, words: &str) -> bool {
    (upgraded.report.iter()).any(|n| n.pointer == pointer && n.text.contains(words))
}

fn assert_output_checks_clean(upgraded: &Upgraded) {
    let report = output::verify(&output::layout(upgraded, "out.glb"));
    assert!(!report.has_errors(), "{:?}", report.diagnostics);
}

#[test]
fn an_attribute_or_keyframes_naming_no_accessor_are_left_out_not_the_whole_asset() {
    let dangling = |asset: &mut Value| {
        asset["meshes"]["m"]["primitives"][0]["attributes"]["NORMAL"] = "ghost".into();
        asset["animations"]["idle"] = serde_json::json!({
            "channels": [{"sampler": "s", "target": {"id": "n", "path": "translation"}}],
            "samplers": {"s": {"input": "TIME", "output": "moves"}},
            "parameters": {"TIME": "ghost", "moves": "a0"}
        });
    };
    let upgraded = upgraded_triangle(dangling).unwrap();
    let json = upgraded.json.to_value();
    let attributes = &json["meshes"][0]["primitives"][0]["attributes"];
    assert!(attributes.get("POSITION").is_some() && attributes.get("NORMAL").is_none());
    assert!(json.get("animations").is_none(), "{json}");
    let normal = "/meshes/m/primitives/0/attributes/NORMAL";
    assert!(said(
        &upgraded,
        normal,
        "names accessor 'ghost', which does not exist"
    ));
    let sampler = "/animations/idle/samplers/s";
    assert!(said(&upgraded, sampler, "do not resolve to accessors"));
    assert_output_checks_clean(&upgraded);

    // Without POSITION the primitive draws nothing: that is refused, naming the accessor.
    let refused = upgraded_triangle(|asset| {
        dangling(asset);
        asset["meshes"]["m"]["primitives"][0]["attributes"]["POSITION"] = "ghost".into();
    });
    assert!(refused.is_err_and(|e| e.to_string().contains("accessor 'ghost' does not exist")));
}

#[test]
fn meshes_and_primitives_that_draw_nothing_are_dropped_and_the_nodes_keep_the_others() {
    let upgraded = upgraded_triangle(|asset| {
        // 1.0 defaults both lists to empty; the empty meshes come first so that the kept one
        // moves.
        let triangle = asset["meshes"]["m"].clone();
        asset["meshes"] = serde_json::json!({
            "none": {"primitives": []},
            "bare": {"primitives": [{"attributes": {}}]},
            "m": triangle,
        });
        asset["nodes"] = serde_json::json!({
            "n": {"meshes": ["none", "m", "bare"]},
            "hollow": {"meshes": ["bare"]},
        });
        asset["scenes"]["s"]["nodes"] = serde_json::json!(["n", "hollow"]);
    })
    .unwrap();
    let json = upgraded.json.to_value();
    assert_eq!(json["meshes"].as_array().unwrap().len(), 1, "{json}");
    assert_eq!(json["nodes"][0]["mesh"], 0, "{json}");
    assert!(json["nodes"][0].get("children").is_none(), "{json}");
    assert!(json["nodes"][1].get("mesh").is_none(), "{json}");
    let mesh_dropped = "mesh without (drawable) primitives dropped";
    assert!(said(&upgraded, "/meshes/none", mesh_dropped));
    let bare = "/meshes/bare/primitives/0";
    assert!(said(
        &upgraded,
        bare,
        "primitive without attributes dropped"
    ));
    assert!(said(&upgraded, "/meshes/bare", mesh_dropped));
    assert_output_checks_clean(&upgraded);
}

#[test]
fn a_node_hidden_or_flattened_by_a_zero_scale_matrix_gets_a_zero_scale() {
    let hidden = [0.0; 9];
    let squashed = [0.0, 2.0, 0.0, -3.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for (columns, scale) in [(hidden, [0.0, 0.0, 0.0]), (squashed, [2.0, 3.0, 0.0])] {
        let [a, b, c, d, e, f, g, h, i] = columns;
        let upgraded = upgraded_triangle(|asset| {
            asset["nodes"]["n"]["matrix"] =
                serde_json::json!([a, b, c, 0, d, e, f, 0, g, h, i, 0, 5, 6, 7, 1]);
        })
        .unwrap();
        let node = &upgraded.json.to_value()["nodes"][0];
        assert!(node.get("matrix").is_none(), "{node}");
        assert_eq!(node["translation"], serde_json::json!([5.0, 6.0, 7.0]));
        let written: Vec<f64> = (node["scale"].as_array().unwrap().iter())
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert!(
            (0..3).all(|k| (written[k] - scale[k]).abs() < 1e-12),
            "{node}"
        );
        assert_output_checks_clean(&upgraded);
    }
}

/// Column-major T · R · S of a 2.0 node (a missing part is the identity's).
fn node_matrix(node: &Value) -> [f64; 16] {
    let list = |key: &str, default: &[f64]| -> Vec<f64> {
        (node.get(key).and_then(Value::as_array)).map_or(default.to_vec(), |a| {
            a.iter().map(|v| v.as_f64().unwrap()).collect()
        })
    };
    let (t, q, s) = (
        list("translation", &[0.0; 3]),
        list("rotation", &[0.0, 0.0, 0.0, 1.0]),
        list("scale", &[1.0; 3]),
    );
    let [x, y, z, w] = [q[0], q[1], q[2], q[3]];
    let r = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y + z * w),
            2.0 * (x * z - y * w),
        ],
        [
            2.0 * (x * y - z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z + x * w),
        ],
        [
            2.0 * (x * z + y * w),
            2.0 * (y * z - x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    let mut m = [0.0; 16];
    for c in 0..3 {
        for row in 0..3 {
            m[4 * c + row] = r[c][row] * s[c];
        }
        m[12 + c] = t[c];
    }
    m[15] = 1.0;
    m
}

#[test]
fn a_sheared_node_matrix_becomes_a_node_and_a_child_whose_product_is_that_matrix() {
    // A shear the Khronos validator's recomposition rejects (NODE_MATRIX_NON_TRS); one it lets
    // through passes the output's check and is kept as written.
    let sheared = [
        1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ];
    let upgraded = upgraded_triangle(|asset| {
        asset["nodes"]["n"]["matrix"] = serde_json::json!(sheared);
        asset["nodes"]["n"]["children"] = serde_json::json!(["leaf"]);
        asset["nodes"]["leaf"] = serde_json::json!({"meshes": ["m"]});
    })
    .unwrap();
    let json = upgraded.json.to_value();
    let (outer, inner) = (&json["nodes"][0], &json["nodes"][2]);
    assert_eq!(outer["children"], serde_json::json!([2]), "{json}");
    assert!(
        outer.get("matrix").is_none() && outer.get("mesh").is_none(),
        "{json}"
    );
    assert_eq!(inner["mesh"], 0, "{json}");
    assert_eq!(
        inner["children"],
        serde_json::json!([1]),
        "the node's own child: {json}"
    );
    let (a, b) = (node_matrix(outer), node_matrix(inner));
    for column in 0..4 {
        for row in 0..4 {
            let product: f64 = (0..4).map(|k| a[4 * k + row] * b[4 * column + k]).sum();
            let error = (product - sheared[4 * column + row]).abs();
            assert!(
                error < 1e-9,
                "{column},{row}: {product} against {}",
                sheared[4 * column + row]
            );
        }
    }
    let note = "sheared matrix written as two nodes";
    assert!(said(&upgraded, "/nodes/n", note));
    assert_output_checks_clean(&upgraded);

    // A joint's skin reads the joint node itself, so its shear is not moved to a child.
    let joint = upgraded_triangle(|asset| {
        asset["nodes"]["n"]["matrix"] = serde_json::json!(sheared);
        asset["nodes"]["n"]["jointName"] = "j".into();
    })
    .unwrap();
    let json = joint.json.to_value();
    assert_eq!(
        json["nodes"][0]["matrix"],
        serde_json::json!(sheared),
        "{json}"
    );
    assert_eq!(json["nodes"].as_array().unwrap().len(), 1, "{json}");
}

#[test]
fn quantized_positions_are_decoded_with_their_decode_matrix() {
    // Two unsigned-short positions; the matrix scales by 1/65535 and moves by (−0.5, 0, 2).
    let stored: Vec<u8> = [0u16, 0, 0, 65535, 65535, 65535]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let s = 1.0 / 65535.0;
    let matrix = [
        s, 0., 0., 0., 0., s, 0., 0., 0., 0., s, 0., -0.5, 0., 2., 1.,
    ];
    let uri = data_uri("application/octet-stream", &stored);
    let gltf1 = serde_json::json!({
        "asset": {"version": "1.0"},
        "extensionsUsed": ["WEB3D_quantized_attributes"],
        "buffers": {"b": {"uri": uri, "byteLength": 12}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": 12, "target": 34962}},
        "accessors": {"p": {"bufferView": "v", "byteOffset": 0, "componentType": 5123, "count": 2, "type": "VEC3",
            "extensions": {"WEB3D_quantized_attributes": {"decodeMatrix": matrix,
                "decodedMin": [-0.5, 0, 2], "decodedMax": [0.5, 1, 3]}}}},
        "meshes": {"m": {"primitives": [{"attributes": {"POSITION": "p"}, "mode": 0}]}},
        "nodes": {"n": {"meshes": ["m"]}},
        "scenes": {"s": {"nodes": ["n"]}},
        "scene": "s"
    });
    let upgraded = upgrade(
        serde_json::to_vec(&gltf1).unwrap(),
        &NoResources,
        &UpgradeOptions::default(),
    )
    .unwrap();
    let position = &upgraded.json.to_value()["accessors"][0];
    assert_eq!(position["componentType"], 5126);
    assert_eq!(position["min"], serde_json::json!([-0.5, 0.0, 2.0]));
    assert_eq!(position["max"], serde_json::json!([0.5, 1.0, 3.0]));
    assert!(upgraded
        .report
        .iter()
        .any(|n| n.text.contains("decodeMatrix")));
}

/// The notes of a conversion, as `kind pointer text` lines.
fn notes(upgraded: &Upgraded) -> Vec<String> {
    (upgraded.report.iter())
        .map(|n| format!("{:?} {} {}", n.kind, n.pointer, n.text))
        .collect()
}

fn upgrade_json(asset: Value) -> Upgraded {
    let bytes = serde_json::to_vec(&asset).unwrap();
    upgrade(&bytes, &NoResources, &UpgradeOptions::default()).expect("upgrades")
}

fn assert_passes_its_check(upgraded: &Upgraded) {
    let report = output::verify(&output::layout(upgraded, "out.glb"));
    assert!(!report.has_errors(), "{:?}", report.diagnostics);
}

#[test]
fn materials_common_lights_become_punctual_lights_on_their_nodes() {
    let upgraded = upgrade_json(serde_json::json!({
        "asset": {"version": "1.0"},
        "extensionsUsed": ["KHR_materials_common"],
        "extensions": {"KHR_materials_common": {"lights": {
            "sun": {"type": "directional", "directional": {"color": [1.0, 0.5, 0.0]}},
            "bulb": {"type": "point", "point": {"color": [1, 1, 1], "constantAttenuation": 0,
                "linearAttenuation": 0, "quadraticAttenuation": 0.25, "distance": 10}},
            "lamp": {"type": "spot", "spot": {"color": [1, 1, 1], "fallOffAngle": 1.2,
                "constantAttenuation": 1, "linearAttenuation": 0, "quadraticAttenuation": 0}},
            "sky": {"type": "ambient", "ambient": {"color": [0.2, 0.2, 0.2]}},
            "spare": {"type": "point", "point": {"color": [1, 0, 0]}}
        }}},
        "nodes": {
            "a": {"extensions": {"KHR_materials_common": {"light": "sun"}}},
            "b": {"extensions": {"KHR_materials_common": {"light": "bulb"}}},
            "c": {"extensions": {"KHR_materials_common": {"light": "lamp"}}},
            "d": {"extensions": {"KHR_materials_common": {"light": "sky"}}},
            "e": {"extensions": {"KHR_materials_common": {"light": "sun"}}}
        },
        "scenes": {"s": {"nodes": ["a", "b", "c", "d", "e"]}}, "scene": "s"
    }));
    let json = &upgraded.json.to_value();
    assert_eq!(
        json["extensionsUsed"],
        serde_json::json!(["KHR_lights_punctual"])
    );
    let lights = json["extensions"]["KHR_lights_punctual"]["lights"]
        .as_array()
        .unwrap();
    assert_eq!(
        lights.len(),
        3,
        "sun (shared by two nodes), bulb, lamp: {lights:?}"
    );
    let light_of =
        |node: usize| json["nodes"][node]["extensions"]["KHR_lights_punctual"]["light"].as_u64();
    assert_eq!([light_of(0), light_of(4)], [Some(0), Some(0)]);
    assert_eq!(light_of(3), None, "ambient light has no 2.0 form");
    // sRGB 0.5 → linear 0.214.
    assert_eq!(lights[0]["type"], "directional");
    assert!((lights[0]["color"][1].as_f64().unwrap() - 0.21404).abs() < 1e-4);
    // 1/(q·d²) is exactly intensity/d² with intensity 1/q.
    assert_eq!(lights[1]["intensity"], 4.0);
    assert_eq!(lights[1]["range"], 10.0);
    // The 1.0 fall-off angle is the full cone: the 2.0 outer cone is half of it.
    assert_eq!(lights[2]["spot"]["outerConeAngle"], 0.6);
    let notes = notes(&upgraded).join("\n");
    for expected in [
        "Dropped /extensions/KHR_materials_common/lights/sky ambient light",
        "Dropped /extensions/KHR_materials_common/lights/spare light placed by no node",
        "Decision /extensions/KHR_materials_common/lights/lamp attenuation 1/(1.0 + 0.0·d + 0.0·d²) has no 2.0 form",
    ] {
        assert!(notes.contains(expected), "{expected}\n in\n{notes}");
    }
    assert_passes_its_check(&upgraded);
}

#[test]
fn technique_transparency_multiplies_alpha_where_the_technique_blends() {
    let technique = |blend: bool, functions: serde_json::Value| {
        let enable = if blend { vec![2929, 3042] } else { vec![2929] };
        serde_json::json!({"parameters": {"transparency": {"type": 5126}, "diffuse": {"type": 35666}},
            "states": {"enable": enable, "functions": functions}})
    };
    let premultiplied = serde_json::json!({"blendFuncSeparate": [1, 771, 1, 771]});
    let asset = serde_json::json!({
        "asset": {"version": "1.0"},
        "techniques": {"blends": technique(true, premultiplied.clone()), "opaque": technique(false, premultiplied),
            // BLEND enabled with the specification's default functions, ONE, ZERO: the colour
            // replaces what is behind.
            "replaces": technique(true, serde_json::json!({}))},
        "materials": {
            "glass": {"technique": "blends", "values": {"diffuse": [1, 1, 1, 0.5], "transparency": 0.9,
                "emission": [0.2, 0.3, 0.4, 1]}},
            "solid": {"technique": "opaque", "values": {"diffuse": [1, 1, 1, 1], "transparency": 0.9}},
            "plate": {"technique": "replaces", "values": {"diffuse": [1, 1, 1, 0.5], "transparency": 0.9}}
        },
        "scenes": {"s": {"nodes": []}}, "scene": "s"
    });
    let upgraded = upgrade_json(asset.clone());
    // The proof reads the techniques' emission and coverage the same way: the glass adds its
    // emission whole (ONE, ONE_MINUS_SRC_ALPHA), which its conversion keeps.
    let bytes = serde_json::to_vec(&asset).unwrap();
    let proof = gltfmat::prove(&bytes, "asset.gltf", &NoResources, &upgraded).unwrap();
    assert_eq!(proof.len(), 3);
    for outcome in &proof {
        assert!(
            outcome.only_lighting_unread(),
            "{:?}",
            outcome.not_evaluated
        );
        assert!(
            outcome.result.max < 1e-6,
            "{}: {}",
            outcome.a.1,
            outcome.result.max
        );
    }
    let material = |i: usize| upgraded.json.to_value()["materials"][i].clone();
    assert_eq!(material(0)["alphaMode"], "BLEND");
    let alpha = material(0)["pbrMetallicRoughness"]["baseColorFactor"][3]
        .as_f64()
        .unwrap();
    assert!(
        (alpha - 0.45).abs() < 1e-12,
        "diffuse.a · transparency, got {alpha}"
    );
    assert_eq!(
        material(1)["alphaMode"],
        Value::Null,
        "no blending: alpha is not seen"
    );
    assert_eq!(
        material(2)["alphaMode"],
        Value::Null,
        "GL's default blend functions replace: alpha is not seen"
    );
    assert_eq!(
        material(1)["pbrMetallicRoughness"]["baseColorFactor"][3],
        1.0
    );
}

#[test]
fn unknown_extensions_are_named_and_unused_textures_are_not_written() {
    let upgraded = upgrade_file(
        &repo("fixtures/gltf1/pbr-sg-textured-fraunhofer.glb"),
        &UpgradeOptions::default(),
    );
    // The rebake replaces the diffuse texture; only what the materials read is written.
    let json = upgraded.json.to_value();
    let textures = json["textures"].as_array().unwrap();
    let images = json["images"].as_array().unwrap();
    assert_eq!(images.len(), upgraded.images.len());
    let report = gltfmat::check_bytes(
        "out.glb",
        upgraded.to_glb(),
        &NoResources,
        &Default::default(),
    );
    let unused: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code == "UNUSED_OBJECT")
        .collect();
    assert!(
        unused.is_empty(),
        "{unused:?} ({} textures)",
        textures.len()
    );
    assert!(
        notes(&upgraded)
            .iter()
            .any(|n| n.starts_with("Dropped /textures texture")),
        "{:?}",
        notes(&upgraded)
    );

    let upgraded = upgrade_json(serde_json::json!({
        "asset": {"version": "1.0"},
        "extensionsUsed": ["CESIUM_RTC", "EXT_declared_only"],
        "extensions": {"CESIUM_RTC": {"center": [1, 2, 3]}},
        "nodes": {"n": {"extensions": {"VENDOR_thing": {}}}},
        "scenes": {"s": {"nodes": ["n"]}}, "scene": "s"
    }));
    let notes = notes(&upgraded).join("\n");
    for expected in [
        "Decision /extensions/CESIUM_RTC CESIUM_RTC kept with its center [1.0, 2.0, 3.0]",
        "Dropped /extensionsUsed/1 extension EXT_declared_only (declared in extensionsUsed but used by no object)",
        "Dropped /nodes/n/extensions/VENDOR_thing extension VENDOR_thing (on 1 object(s))",
    ] {
        assert!(notes.contains(expected), "{expected}\n in\n{notes}");
    }
}

/// A 1.0 GLB whose JSON puts an image in the binary body, with the body's last `cut` bytes
/// missing from the file (its header declares them).
fn glb_v1_with_image(body: &[u8], cut: usize) -> Vec<u8> {
    let json = serde_json::to_vec(&serde_json::json!({
        "asset": {"version": "1.0"},
        "buffers": {"binary_glTF": {"uri": "data:,", "byteLength": body.len()}},
        "bufferViews": {"v": {"buffer": "binary_glTF", "byteOffset": 0, "byteLength": body.len()}},
        "images": {"i": {"uri": "data:,", "extensions": {"KHR_binary_glTF":
            {"bufferView": "v", "mimeType": "image/png", "width": 1, "height": 1}}}},
        "textures": {"t": {"source": "i"}},
        "materials": {"m": {"values": {"diffuse": "t"}}}
    }))
    .unwrap();
    let declared = (20 + json.len() + body.len()) as u32;
    let mut glb = b"glTF".to_vec();
    for word in [1, declared, json.len() as u32, 0] {
        glb.extend(u32::to_le_bytes(word));
    }
    glb.extend(json);
    glb.extend(&body[..body.len() - cut]);
    glb
}

#[test]
fn a_glb_cut_short_is_refused_naming_both_lengths() {
    let glb = glb_v1_with_image(&[7; 40], 3);
    let Err(refusal) = upgrade(&glb, &NoResources, &UpgradeOptions::default()) else {
        panic!("a view past the end of the body is refused");
    };
    let refusal = refusal.to_string();
    let (declared, actual) = (glb.len() + 3, glb.len());
    assert!(
        refusal.starts_with("/images/i: bufferView 'v'"),
        "{refusal}"
    );
    assert!(
        refusal.contains(&format!(
            "the GLB file is {actual} bytes but its header declares {declared}"
        )),
        "{refusal}"
    );
    let whole = glb_v1_with_image(&[7; 40], 0);
    let refusal = upgrade(&whole, &NoResources, &UpgradeOptions::default())
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(!refusal.contains("header declares"), "{refusal}");
}

#[test]
fn a_meshopt_asset_of_several_buffers_is_refused_saying_why() {
    // Joining the buffers would leave each extension's `buffer` pointing at the wrong bytes.
    let sg = "KHR_materials_pbrSpecularGlossiness";
    let asset = |buffers: Value| {
        serde_json::to_vec(&serde_json::json!({"asset": {"version": "2.0"},
            "extensionsUsed": ["KHR_meshopt_compression", sg],
            "buffers": buffers,
            "materials": [{"extensions": {sg: {"diffuseFactor": [0.5, 0.5, 0.5, 1]}}}]}))
        .unwrap()
    };
    let two = asset(serde_json::json!([{"uri": "data:,", "byteLength": 0}, {"byteLength": 8}]));
    let Err(refusal) = upgrade(&two, &NoResources, &UpgradeOptions::default()) else {
        panic!("a meshopt asset of two buffers is refused");
    };
    let refusal = refusal.to_string();
    assert!(
        refusal.starts_with("/extensionsUsed: KHR_meshopt_compression names buffers"),
        "{refusal}"
    );
    let one = asset(serde_json::json!([{"uri": "data:,", "byteLength": 0}]));
    assert!(upgrade(&one, &NoResources, &UpgradeOptions::default()).is_ok());
}

/// A 1.0 asset of `meshes` point meshes, mesh i drawing accessor i: `count(i)` positions
/// from byte `offset(i)` of one view of `vertices` positions.
fn gltf1_aliases(
    vertices: usize,
    meshes: usize,
    offset: impl Fn(usize) -> usize,
    count: impl Fn(usize) -> usize,
) -> Vec<u8> {
    let bin: Vec<u8> = (0..vertices)
        .flat_map(|i| [(i % 7) as f32, (i % 5) as f32, 0.0])
        .flat_map(f32::to_le_bytes)
        .collect();
    let uri = data_uri("application/octet-stream", &bin);
    let accessors: serde_json::Map<String, Value> = (0..meshes)
        .map(|i| {
            let accessor = serde_json::json!({"bufferView": "v", "byteOffset": offset(i),
                "byteStride": 12, "componentType": 5126, "count": count(i), "type": "VEC3",
                "min": [0, 0, 0], "max": [6, 4, 0]});
            (format!("a{i}"), accessor)
        })
        .collect();
    let mesh = |i: usize| serde_json::json!({"primitives": [{"attributes": {"POSITION": format!("a{i}")}, "mode": 0}]});
    serde_json::to_vec(&serde_json::json!({
        "asset": {"version": "1.0"},
        "buffers": {"b": {"uri": uri, "byteLength": bin.len()}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": bin.len(), "target": 34962}},
        "accessors": accessors,
        "meshes": (0..meshes).map(|i| (format!("m{i}"), mesh(i))).collect::<serde_json::Map<_, _>>(),
        "nodes": {"n": {"meshes": (0..meshes).map(|i| format!("m{i}")).collect::<Vec<_>>()}},
        "scenes": {"s": {"nodes": ["n"]}},
        "scene": "s"
    }))
    .unwrap()
}

#[test]
fn accessors_reading_the_same_data_share_one_copy_of_it() {
    // 200 aliases of one 120 KB view: one copy of the data, one strided bufferView.
    let (vertices, aliases) = (10_000, 200);
    let asset = gltf1_aliases(vertices, aliases, |_| 0, |_| vertices);
    let upgraded = upgrade(&asset, &NoResources, &UpgradeOptions::default()).unwrap();
    let json = upgraded.json.to_value();
    assert_eq!(upgraded.binary.len(), 12 * vertices, "one copy of the data");
    let accessors = json["accessors"].as_array().unwrap();
    assert_eq!(accessors.len(), aliases, "each 1.0 accessor keeps its own");
    assert!(accessors
        .iter()
        .all(|a| a["bufferView"] == 0 && a["count"] == vertices));
    assert_eq!(accessors[7]["name"], "a7");
    assert_eq!(
        json["bufferViews"][0]["byteStride"], 12,
        "2.0 requires it once shared"
    );
    let report = output::verify(&output::layout(&upgraded, "out.glb"));
    assert!(!report.has_errors(), "{:?}", report.diagnostics);
    // Windows of the data that each start further on are each new data: they may grow the
    // output only so far, and then the upgrade is refused at the accessor that went past.
    let vertices = 100_000;
    let asset = gltf1_aliases(vertices, 1_000, |i| 12 * i, |i| vertices - i);
    let refused = upgrade(&asset, &NoResources, &UpgradeOptions::default()).unwrap_err();
    let message = refused.to_string();
    assert!(
        message.contains("/accessors/a") && message.contains("more than 8 times"),
        "{message}"
    );
}

#[test]
fn a_file_many_buffers_name_counts_once_in_the_data_read() {
    // 100 buffers naming one 1.2 MB file, each with a window of it that starts further on:
    // the output may grow only by what one copy of the file allows.
    let vertices = 100_000;
    let file: Vec<u8> = (0..vertices)
        .flat_map(|i| [(i % 7) as f32, 1.0, 0.0])
        .flat_map(f32::to_le_bytes)
        .collect();
    let mut loader = gltfmat::MemoryResources::default();
    loader
        .files
        .insert("one.bin".into(), std::sync::Arc::new(file.clone().into()));
    let n = 100;
    let id = |kind: &str, i: usize| format!("{kind}{i}");
    let mut root = serde_json::json!({"asset": {"version": "1.0"}, "buffers": {},
        "bufferViews": {}, "accessors": {}, "meshes": {}, "scenes": {"s": {"nodes": ["n"]}},
        "scene": "s", "nodes": {"n": {"meshes": (0..n).map(|i| id("m", i)).collect::<Vec<_>>()}}});
    for i in 0..n {
        root["buffers"][id("b", i)] =
            serde_json::json!({"uri": "one.bin", "byteLength": file.len()});
        root["bufferViews"][id("v", i)] = serde_json::json!({"buffer": id("b", i),
            "byteOffset": 12 * i, "byteLength": file.len() - 12 * i, "target": 34962});
        root["accessors"][id("a", i)] = serde_json::json!({"bufferView": id("v", i),
            "componentType": 5126, "count": vertices - i, "type": "VEC3",
            "min": [0, 1, 0], "max": [6, 1, 0]});
        root["meshes"][id("m", i)] = serde_json::json!({"primitives":
            [{"attributes": {"POSITION": id("a", i)}, "mode": 0}]});
    }
    let asset = serde_json::to_vec(&root).unwrap();
    let refused = upgrade(&asset, &loader, &UpgradeOptions::default()).unwrap_err();
    let message = refused.to_string();
    let read = format!("the {} bytes of data read", file.len());
    assert!(message.contains(&read), "{message}");
}

/// The KHR draft fixture as JSON, to edit.
fn khr_fixture() -> Value {
    serde_json::from_slice(&std::fs::read(repo("fixtures/gltf1/pbr-sg-khr.gltf")).unwrap()).unwrap()
}

/// `asset` upgraded with the fixture's folder for its resources and the default options.
fn upgrade_beside_fixture(asset: &Value) -> Result<Upgraded, gltfmat::UpgradeError> {
    let loader = FolderResources::beside(&repo("fixtures/gltf1/pbr-sg-khr.gltf"));
    upgrade(
        asset.to_string().as_bytes(),
        &loader,
        &UpgradeOptions::default(),
    )
}

#[test]
fn a_scene_listing_a_root_again_lists_it_once_and_says_so() {
    let mut asset = khr_fixture();
    asset["scenes"]["defaultScene"]["nodes"] = serde_json::json!(["node_3", "node_3", "node_3"]);
    let upgraded = upgrade_beside_fixture(&asset).expect("repaired, not refused");
    let scenes = upgraded.json.get("scenes").unwrap();
    assert_eq!(scenes[0]["nodes"].as_array().unwrap().len(), 1);
    assert!(notes(&upgraded)
        .iter()
        .any(|n| n.contains("listed more than once: listed once")));
    let files = output::layout(&upgraded, "out.glb");
    assert!(!output::verify(&files).has_errors());
}

#[test]
fn an_image_no_texture_samples_is_left_out_when_it_cannot_be_read() {
    let mut asset = khr_fixture();
    asset["images"]["orphan"] = serde_json::json!({"uri": "missing.png"});
    let upgraded = upgrade_beside_fixture(&asset).expect("nothing samples the missing image");
    assert!(notes(&upgraded)
        .iter()
        .any(|n| n.contains("sampled by no texture: left out")));
    // A sampled image that cannot be read still refuses the upgrade: a texture would be lost.
    asset["textures"] = serde_json::json!({"t": {"source": "orphan"}});
    assert!(upgrade_beside_fixture(&asset).is_err());
}

#[test]
fn a_material_that_is_no_object_is_refused_and_another_version_is_said() {
    let mut asset = khr_fixture();
    asset["asset"]["version"] = "1.1".into();
    let upgraded = upgrade_beside_fixture(&asset).unwrap();
    assert!(notes(&upgraded)
        .iter()
        .any(|n| n.contains("asset.version is '1.1', not 1.0")));
    asset["materials"]["meta"] = "a string".into();
    let refused = upgrade_beside_fixture(&asset).err().map(|e| e.to_string());
    assert_eq!(
        refused.as_deref(),
        Some("/materials/meta: the material is not an object, so it says nothing to convert")
    );
}

#[test]
fn the_1_0_default_material_is_its_displayed_grey_linearised() {
    let mut asset = khr_fixture();
    asset["materials"]["plain"] = serde_json::json!({"name": "plain"});
    let upgraded = upgrade_beside_fixture(&asset).unwrap();
    let materials = upgraded.json.get("materials").unwrap();
    let plain = (materials.as_array().unwrap().iter())
        .find(|m| m["name"] == "plain")
        .unwrap();
    let grey = plain["pbrMetallicRoughness"]["baseColorFactor"][0]
        .as_f64()
        .unwrap();
    assert!((grey - srgb_to_linear(0.5)).abs() < 1e-12, "{grey}");
    assert!(plain["extensions"]["KHR_materials_unlit"].is_object());
}

#[test]
fn a_large_scale_node_matrix_is_written_as_the_same_translation_rotation_and_scale() {
    // Written as a 2.0 matrix it would fail the output's check; as TRS it is the same transform.
    let m = common::LARGE_SCALE_MATRIX;
    let as_2_0 = serde_json::json!({"asset": {"version": "2.0"}, "nodes": [{"matrix": m}],
        "scenes": [{"nodes": [0]}], "scene": 0});
    let check = gltfmat::check_bytes(
        "m.gltf",
        as_2_0.to_string(),
        &NoResources,
        &Default::default(),
    );
    assert!(check
        .diagnostics
        .iter()
        .any(|d| d.code.name() == "NODE_MATRIX_NON_TRS"));

    let gltf1 = serde_json::json!({"asset": {"version": "1.0"}, "scene": "s",
        "scenes": {"s": {"nodes": ["n"]}}, "nodes": {"n": {"matrix": m}}});
    let upgraded = upgrade(
        gltf1.to_string().as_bytes(),
        &NoResources,
        &UpgradeOptions::default(),
    )
    .unwrap();
    let node = upgraded.json.items("nodes").unwrap().get(0).unwrap();
    assert!(node.get("matrix").is_none(), "{node}");
    assert!(upgraded
        .report
        .iter()
        .any(|n| n.text.contains("matrix written as translation")));
    let glb = upgraded.to_glb();
    let output = gltfmat::check_bytes("out.glb", glb.clone(), &NoResources, &Default::default());
    assert!(!output.has_errors(), "{:?}", output.diagnostics);
    // A real client's T · R · S gives the 1.0 matrix back (to its single precision).
    let client = gltf::Gltf::from_slice(&glb).unwrap();
    let matrix = client.nodes().next().unwrap().transform().matrix();
    for c in 0..4 {
        for row in 0..4 {
            let (got, want) = (f64::from(matrix[c][row]), m[4 * c + row]);
            assert!(
                (got - want).abs() <= 1e-6 * want.abs().max(1000.0),
                "column {c} row {row}: {got} ≠ {want}"
            );
        }
    }
}

#[test]
fn khr_materials_common_values_in_the_early_type_value_form_are_read() {
    let converted = |values: serde_json::Value| {
        let gltf1 = serde_json::json!({"asset": {"version": "1.0"}, "scene": "s",
            "scenes": {"s": {"nodes": []}}, "extensionsUsed": ["KHR_materials_common"],
            "materials": {"m": {"extensions": {"KHR_materials_common": {"technique": "BLINN", "values": values}}}}});
        let upgraded = upgrade(
            gltf1.to_string().as_bytes(),
            &NoResources,
            &UpgradeOptions::default(),
        )
        .unwrap();
        let early = upgraded
            .report
            .iter()
            .any(|n| n.text.contains("early {type, value} form"));
        (material(&upgraded), early)
    };
    let (plain, said) =
        converted(serde_json::json!({"diffuse": [0.5, 0.25, 1.0, 1.0], "shininess": 50.0}));
    assert!(!said);
    let (typed, said) = converted(serde_json::json!({
        "diffuse": {"type": 35666, "value": [0.5, 0.25, 1.0, 1.0]},
        "shininess": {"type": 5126, "value": 50.0}}));
    assert!(said, "the reading is said");
    assert_eq!(typed["pbrMetallicRoughness"], plain["pbrMetallicRoughness"]);
    assert!(
        numbers(&typed["pbrMetallicRoughness"]["baseColorFactor"])[0] < 0.5,
        "linearised"
    );
    assert!(
        typed["pbrMetallicRoughness"]["roughnessFactor"]
            .as_f64()
            .unwrap()
            < 1.0,
        "from shininess"
    );
}

/// 3D Tiles' glTF 1.0 conventions (Cesium): a NORMAL of two signed bytes is an octahedron
/// encoding, decoded to unit floats; CESIUM_RTC is kept, so positions stay offsets from it.
#[test]
fn cesium_oct_encoded_normals_are_decoded_and_cesium_rtc_is_kept() {
    let positions: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    // Stored as the city tiles store them; their shader decodes v / 127, then folds the lower
    // half: (100, 100) lies past |x| + |y| = 1, so its z is negative.
    let encoded: [[i8; 2]; 4] = [[0, 0], [127, 0], [0, -127], [100, 100]];
    let mut bin: Vec<u8> = positions
        .iter()
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    bin.extend(encoded.iter().flatten().map(|&v| v as u8));
    let uri = data_uri("application/octet-stream", &bin);
    let center = [
        1_214_939.908_552_622_4,
        -4_736_421.803_714_806,
        4_081_493.671_397_794_5,
    ];
    let gltf1 = serde_json::json!({
        "asset": {"version": "1.0"},
        "extensionsUsed": ["CESIUM_RTC"],
        "extensions": {"CESIUM_RTC": {"center": center}},
        "buffers": {"b": {"uri": uri, "byteLength": bin.len()}},
        "bufferViews": {
            "p": {"buffer": "b", "byteOffset": 0, "byteLength": 48, "target": 34962},
            "n": {"buffer": "b", "byteOffset": 48, "byteLength": 8, "target": 34962}},
        "accessors": {
            "position": {"bufferView": "p", "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]},
            "normal": {"bufferView": "n", "byteOffset": 0, "byteStride": 2, "componentType": 5120, "count": 4, "type": "VEC2"}},
        "meshes": {"m": {"primitives": [{"attributes": {"POSITION": "position", "NORMAL": "normal"}, "mode": 0}]}},
        "nodes": {"node": {"meshes": ["m"]}},
        "scenes": {"s": {"nodes": ["node"]}},
        "scene": "s"
    });
    let upgraded = upgrade_json(gltf1);
    assert_passes_its_check(&upgraded);
    let json = upgraded.json.to_value();
    assert_eq!(
        json["extensions"]["CESIUM_RTC"]["center"],
        serde_json::json!(center)
    );
    assert!(json["extensionsUsed"]
        .as_array()
        .unwrap()
        .contains(&"CESIUM_RTC".into()));
    assert!(
        notes(&upgraded).iter().any(|n| n.contains("octahedron")),
        "{:?}",
        notes(&upgraded)
    );
    let glb = gltf::Gltf::from_slice(&upgraded.to_glb()).unwrap();
    let primitive = glb.meshes().next().unwrap().primitives().next().unwrap();
    let reader = primitive.reader(|_| glb.blob.as_deref());
    let read_positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    assert_eq!(
        read_positions, positions,
        "positions stay offsets from the kept centre"
    );
    let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
    let folded = {
        let (x, y): (f64, f64) = (1.0 - 100.0 / 127.0, 1.0 - 100.0 / 127.0);
        let z: f64 = 1.0 - 200.0 / 127.0;
        let length = (x * x + y * y + z * z).sqrt();
        [x / length, y / length, z / length]
    };
    let expected = [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], folded];
    for (got, want) in normals.iter().zip(expected) {
        for c in 0..3 {
            assert!(
                (f64::from(got[c]) - want[c]).abs() < 1e-6,
                "{normals:?} against {expected:?}"
            );
        }
    }
}

/// A 2.0 spec-gloss texture of one near-grey value: rounding each channel of its rebaked
/// base colour to the nearest 8-bit level turns its hue in the proof's scene; the rebake
/// takes the neighbouring levels the evaluator sees nearer, says it checked the texels, and
/// the proof stays well under the threshold.
#[test]
fn a_2_0_rebake_takes_the_8_bit_levels_the_evaluator_sees_nearest() {
    let asset = flat_spec_gloss_asset([42, 45, 42], 0.1, 0.6);
    let upgraded = upgrade(&asset, &NoResources, &UpgradeOptions::default()).unwrap();
    assert!(
        (upgraded.report.iter()).any(|n| n.text.contains("per-texel check of the rebaked")),
        "{:?}",
        notes(&upgraded)
    );
    let max = only_proof_max(&asset, &upgraded);
    assert!(max < 0.5, "{max}");
}

/// A 2.0 spec-gloss asset of one material whose two 4² textures are flat: a diffuse of
/// `diffuse` (sRGB levels) and a specular-glossiness texture of full white, scaled by a grey
/// `specular` factor and `glossiness`.
fn flat_spec_gloss_asset(diffuse: [u8; 3], specular: f64, glossiness: f64) -> Vec<u8> {
    let diffuse = image::RgbImage::from_pixel(4, 4, image::Rgb(diffuse));
    let spec_gloss = image::RgbaImage::from_pixel(4, 4, image::Rgba([255; 4]));
    let sg = "KHR_materials_pbrSpecularGlossiness";
    serde_json::to_vec(&serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": [sg],
        "images": [embedded_png(diffuse.into()), embedded_png(spec_gloss.into())],
        "textures": [{"source": 0}, {"source": 1}],
        "materials": [{"extensions": {sg: {"diffuseTexture": {"index": 0},
            "specularGlossinessTexture": {"index": 1}, "specularFactor": [specular, specular, specular],
            "glossinessFactor": glossiness}}}],
    }))
    .unwrap()
}

/// The proof's largest ΔE2000 for an asset of one material and its upgrade.
fn only_proof_max(asset: &[u8], upgraded: &Upgraded) -> f64 {
    let proof = gltfmat::prove(asset, "asset.gltf", &NoResources, upgraded).unwrap();
    let [outcome] = &proof[..] else {
        panic!("one material");
    };
    outcome.result.max
}

/// An image entry holding `image` as a PNG data URI.
fn embedded_png(image: image::DynamicImage) -> serde_json::Value {
    let mut bytes = Vec::new();
    (image.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    ))
    .unwrap();
    serde_json::json!({"uri": data_uri("image/png", &bytes)})
}

/// A smooth surface's roughness (glossiness 0.95 → 0.05) lies between two 8-bit levels, and
/// its specular peak shows the step (ΔE 1.7): the rebake stores it scaled by its largest
/// value, which the roughnessFactor carries, and the conversion proves faithful.
#[test]
fn a_smooth_rebaked_roughness_is_stored_on_its_own_scale() {
    let asset = flat_spec_gloss_asset([128, 128, 128], 0.04, 0.95);
    let upgraded = upgrade(&asset, &NoResources, &UpgradeOptions::default()).unwrap();
    let json = upgraded.json.to_value();
    let factor = json["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"].as_f64();
    assert!((factor.unwrap() - 0.05).abs() < 1e-6, "{factor:?}");
    assert!(
        (upgraded.report.iter()).any(|n| n
            .text
            .contains("stored divided by its largest value, 0.05,")),
        "{:?}",
        notes(&upgraded)
    );
    let max = only_proof_max(&asset, &upgraded);
    assert!(max < 0.5, "{max}");
}

#[test]
fn a_common_materials_transparency_is_written_as_blend_and_said() {
    let common = |transparent: bool, values: Value| {
        serde_json::json!({"extensions": {"KHR_materials_common": {
            "technique": "LAMBERT", "transparent": transparent, "values": values}}})
    };
    let upgraded = upgrade_json(serde_json::json!({
        "asset": {"version": "1.0"},
        "extensionsUsed": ["KHR_materials_common"],
        "materials": {
            "glass": common(true, serde_json::json!({"diffuse": [1, 0, 0, 0.5], "transparency": 0.5})),
            "veil": common(false, serde_json::json!({"diffuse": [1, 1, 1, 1], "transparency": 0.25})),
            "solid": common(false, serde_json::json!({"diffuse": [1, 1, 1, 0.5]})),
            "ghost": common(true, serde_json::json!({"diffuse": [1, 1, 1, 1], "transparency": 0}))
        },
        "scenes": {"s": {"nodes": []}}, "scene": "s"
    }));
    let json = upgraded.json.to_value();
    let alpha =
        |i: usize| json["materials"][i]["pbrMetallicRoughness"]["baseColorFactor"][3].as_f64();
    assert_eq!(json["materials"][0]["alphaMode"], "BLEND");
    assert_eq!(alpha(0), Some(0.25), "diffuse alpha times transparency");
    assert_eq!(json["materials"][1]["alphaMode"], "BLEND");
    assert_eq!(alpha(1), Some(0.25));
    assert_eq!(
        json["materials"][2]["alphaMode"],
        Value::Null,
        "opaque unless it says"
    );
    let notes = notes(&upgraded).join("\n");
    for expected in [
        "Decision /materials/glass KHR_materials_common transparent, transparency 0.5 → alphaMode BLEND, the base colour's alpha the diffuse alpha times the transparency (0.25).",
        "Decision /materials/veil KHR_materials_common transparency 0.25 → alphaMode BLEND, the base colour's alpha the diffuse alpha times the transparency (0.25).",
        "Decision /materials/ghost KHR_materials_common transparent, transparency 0 → alphaMode BLEND, the base colour's alpha the diffuse alpha times the transparency (0): the surface is not seen.",
    ] {
        assert!(notes.contains(expected), "{expected}\n in\n{notes}");
    }
    assert!(
        !notes.contains("/materials/solid KHR_materials_common"),
        "{notes}"
    );
    assert_passes_its_check(&upgraded);
}

#[test]
fn a_gltf_0_8_asset_is_read_as_the_1_0_it_became() {
    let floats = |values: &[f32]| {
        values
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>()
    };
    // A line (two vertices), two keyframe times, and two keyframes turning about z by 0 and π.
    let mut stored = floats(&[0., 0., 0., 1., 0., 0.]);
    stored.extend(floats(&[0., 1.]));
    stored.extend(floats(&[0., 0., 1., 0., 0., 0., 2., std::f32::consts::PI]));
    let uri = data_uri("application/octet-stream", &stored);
    let gltf08 = serde_json::json!({
        "asset": {"version": 0.8, "profile": "WebGL 1.0.2"},
        "buffers": {"b": {"uri": uri, "byteLength": 64, "type": "arraybuffer"}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": 24, "target": 34962},
                        "k": {"buffer": "b", "byteOffset": 24, "byteLength": 40}},
        "accessors": {
            "p": {"bufferView": "v", "byteOffset": 0, "byteStride": 12, "componentType": 5126, "count": 2,
                  "type": "VEC3", "min": [0, 0, 0], "max": [1, 0, 0]},
            "t": {"bufferView": "k", "byteOffset": 0, "componentType": 5126, "count": 2, "type": "SCALAR"},
            "r": {"bufferView": "k", "byteOffset": 8, "componentType": 5126, "count": 2, "type": "VEC4"}},
        "materials": {"red": {"instanceTechnique": {"technique": "phong",
            "values": {"diffuse": [0.8, 0, 0, 1], "shininess": 256}}}},
        "techniques": {"phong": {"parameters": {"diffuse": {"type": 35666}, "shininess": {"type": 5126}},
            "pass": "defaultPass", "passes": {"defaultPass": {
                "instanceProgram": {"program": "prog"}, "states": {"enable": [2884, 2929]}}}}},
        "meshes": {"m": {"primitives": [{"attributes": {"POSITION": "p"}, "material": "red", "primitive": 1}]}},
        "nodes": {"n": {"meshes": ["m"], "rotation": [0, 2, 0, std::f64::consts::FRAC_PI_2]}},
        "animations": {"spin": {"channels": [{"sampler": "s", "target": {"id": "n", "path": "rotation"}}],
            "parameters": {"TIME": "t", "rotation": "r"},
            "samplers": {"s": {"input": "TIME", "output": "rotation", "interpolation": "LINEAR"}}}},
        "scenes": {"s": {"nodes": ["n"]}}, "scene": "s"
    });
    let upgraded = upgrade_json(gltf08);
    let json = upgraded.json.to_value();
    let material = &json["materials"][0];
    let red = material["pbrMetallicRoughness"]["baseColorFactor"][0]
        .as_f64()
        .unwrap();
    assert!(
        (red - 0.6038).abs() < 1e-3,
        "the instanceTechnique's diffuse, linearised: {red}"
    );
    assert_eq!(
        material["doubleSided"],
        Value::Null,
        "the pass's states cull back faces"
    );
    assert_eq!(
        json["meshes"][0]["primitives"][0]["mode"], 1,
        "`primitive` is the mode"
    );
    let half = std::f64::consts::FRAC_1_SQRT_2;
    let rotation = numbers(&json["nodes"][0]["rotation"]);
    assert!(
        rotation
            .iter()
            .zip([0., half, 0., half])
            .all(|(a, b)| (a - b).abs() < 1e-12),
        "{rotation:?}"
    );
    // The keyframes, read back from the output buffer: (0, 0, 0, 1) and (0, 0, 1, ~0).
    let output = &json["accessors"][json["animations"][0]["samplers"][0]["output"]
        .as_u64()
        .unwrap() as usize];
    let view = &json["bufferViews"][output["bufferView"].as_u64().unwrap() as usize];
    let start = (view["byteOffset"].as_u64().unwrap_or(0)
        + output["byteOffset"].as_u64().unwrap_or(0)) as usize;
    let binary = upgraded.binary.to_vec();
    let keyframes: Vec<f32> = (binary[start..start + 32].chunks_exact(4))
        .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
        .collect();
    let expected = [0., 0., 0., 1., 0., 0., 1., 0.];
    assert!(
        keyframes
            .iter()
            .zip(expected)
            .all(|(a, b)| (a - b).abs() < 1e-6),
        "{keyframes:?}"
    );
    let notes = notes(&upgraded).join("\n");
    for read in [
        "instanceTechnique",
        "`primitive` as its mode",
        "node rotations",
        "a technique's pass",
        "rotation keyframes",
    ] {
        assert!(notes.contains(read), "{read} not said in\n{notes}");
    }
    assert_passes_its_check(&upgraded);
}

#[test]
fn an_image_in_a_format_2_0_does_not_carry_is_named_and_left_out_only_when_nothing_samples_it() {
    let ktx1 = b"\xABKTX 11\xBB\r\n\x1A\n\x01\x02\x03\x04";
    let uri = data_uri("image/ktx", ktx1);
    let asset = |sampled: bool| {
        let textures = match sampled {
            true => serde_json::json!({"t": {"source": "i"}}),
            false => serde_json::json!({}),
        };
        serde_json::json!({"asset": {"version": "1.0"}, "images": {"i": {"uri": uri}},
            "textures": textures, "scenes": {"s": {"nodes": []}}, "scene": "s"})
    };
    let bytes = serde_json::to_vec(&asset(true)).unwrap();
    let refused = upgrade(&bytes, &NoResources, &UpgradeOptions::default()).unwrap_err();
    let refusal = refused.to_string();
    assert!(
        refusal.starts_with("/images/i: a KTX (version 1) image, which glTF 2.0 does not carry"),
        "{refusal}"
    );
    let upgraded = upgrade_json(asset(false));
    assert_eq!(upgraded.json.to_value().get("images"), None);
    let notes = notes(&upgraded).join("\n");
    assert!(notes.contains("Dropped /images/i a KTX (version 1) image, which glTF 2.0 does not carry and sampled by no texture: left out."), "{notes}");
}

/// A file with nothing to read says why and where, in each command that reads it: the
/// first error its reading found (a GLB chunk's byte, a JSON line and column), never a bare
/// "cannot be read".
#[test]
fn an_unreadable_file_is_refused_with_why_and_where_by_every_command() {
    let dir = scratch("unreadable");
    let mut empty_json_chunk = common::glb(b"{}", None);
    empty_json_chunk.truncate(20);
    empty_json_chunk[8..12].copy_from_slice(&20u32.to_le_bytes());
    empty_json_chunk[12..16].copy_from_slice(&0u32.to_le_bytes());
    let mut v1_past_its_end = b"glTF".to_vec();
    for word in [1u32, 22, 80, 0] {
        v1_past_its_end.extend_from_slice(&word.to_le_bytes());
    }
    v1_past_its_end.extend_from_slice(b"{}");
    // Each case with what every command's message holds (one of the texts, where the
    // commands word it differently).
    let cases: [(&str, &[u8], &[&str]); 5] = [
        (
            "chunk.glb",
            &empty_json_chunk,
            &["(GLB_EMPTY_CHUNK at byte 12)"],
        ),
        (
            "v1.glb",
            &v1_past_its_end,
            &["content length 80 (byte 12) runs past the end"],
        ),
        (
            "broken.gltf",
            br#"{"asset": {"version": "2.0"}, "materials": [}"#,
            &["line 1 column 45", "line 1, column 45"],
        ),
        ("array.gltf", b"[1, 2]", &["its JSON root is not an object"]),
        (
            "empty.glb",
            b"",
            &[
                "the file is empty",
                "GLB_UNEXPECTED_END_OF_HEADER at byte 0",
            ],
        ),
    ];
    for (name, bytes, why) in cases {
        let input = dir.join(name);
        std::fs::write(&input, bytes).unwrap();
        let input = input.to_str().unwrap();
        let out = dir.join("out.glb");
        let picture = dir.join("out.png");
        for args in [
            vec!["upgrade", input, "-o", out.to_str().unwrap()],
            vec!["compare", input, input],
            vec!["render", input, "-o", picture.to_str().unwrap()],
        ] {
            let (code, text) = gltfmat(&args);
            assert_ne!(code, 0, "{args:?}: {text}");
            assert!(why.iter().any(|why| text.contains(why)), "{args:?}: {text}");
            assert!(!text.contains("not a glTF 1.0 asset"), "{args:?}: {text}");
        }
        assert!(!out.exists() && !picture.exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A 1.0 PBR-draft material whose texture cannot be had (here a texture with no image, as
/// KHR_compressed_texture writes them) is not evaluated, named with the texture and why;
/// the asset's other materials still are.
#[test]
fn a_draft_material_whose_texture_cannot_be_had_alone_is_not_evaluated() {
    let dir = scratch("draft-texture");
    let fixtures = repo("fixtures/gltf1");
    for file in [
        "pbr-sg-textured-ext.gltf",
        "diffuse.png",
        "spec_gloss.png",
        "box.bin",
    ] {
        std::fs::copy(fixtures.join(file), dir.join(file)).unwrap();
    }
    let input = dir.join("pbr-sg-textured-ext.gltf");
    let mut asset: Value = serde_json::from_slice(&std::fs::read(&input).unwrap()).unwrap();
    let mut compressed = asset["materials"]["Effect-Texture"].clone();
    compressed["extensions"]["EXT_materials_pbr"]["values"]["diffuseTexture"] = "packed".into();
    asset["materials"]["Packed"] = compressed;
    asset["textures"]["packed"] = serde_json::json!({"sampler": "sampler_0"});
    std::fs::write(&input, serde_json::to_vec(&asset).unwrap()).unwrap();
    let input = input.to_str().unwrap();
    let (code, text) = gltfmat(&["compare", input, input, "--format", "json"]);
    assert_eq!(code, 1, "{text}");
    let pairs: Value = serde_json::from_str(&text).unwrap();
    let by_name = |name: &str| {
        let pairs = pairs.as_array().unwrap().iter();
        pairs
            .clone()
            .find(|p| p["aName"] == name)
            .cloned()
            .unwrap_or_else(|| panic!("{text}"))
    };
    let (whole, packed) = (by_name("Effect-Texture"), by_name("Packed"));
    assert_eq!(
        (whole["evaluated"].clone(), whole["pass"].clone()),
        (true.into(), true.into()),
        "{text}"
    );
    assert_eq!(packed["evaluated"], true, "{text}");
    assert_eq!(packed["pass"], false, "{text}");
    let unread = packed["notEvaluated"].to_string();
    assert!(
        unread.contains("texture 'packed'") && unread.contains("names no image"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Bounds JSON cannot hold are not written: a 1.0 accessor holding an infinite texture
/// coordinate is refused for that value, traced to its source accessor, not for bounds
/// the converter wrote as `null`.
#[test]
fn an_infinite_value_in_a_1_0_accessor_is_refused_for_itself_not_for_null_bounds() {
    let dir = scratch("infinite");
    let floats: Vec<f32> = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .into_iter()
        .chain([0.0, 0.0, f32::INFINITY, 0.0, 0.0, 1.0])
        .collect();
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let asset = serde_json::json!({
        "asset": {"version": "1.0"},
        "buffers": {"b": {"uri": data_uri("application/octet-stream", &bytes), "byteLength": bytes.len()}},
        "bufferViews": {"v": {"buffer": "b", "byteLength": bytes.len(), "target": 34962}},
        "accessors": {
            "position": {"bufferView": "v", "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]},
            "uv": {"bufferView": "v", "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC2"}},
        "materials": {"m": {"extensions": {"KHR_materials_pbr": {"technique": "PBR_metal_roughness",
            "values": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}}}},
        "meshes": {"mesh": {"primitives": [{"attributes": {"POSITION": "position", "TEXCOORD_0": "uv"},
            "material": "m", "mode": 4}]}},
        "nodes": {"n": {"meshes": ["mesh"]}},
        "scenes": {"s": {"nodes": ["n"]}}, "scene": "s"
    });
    let input = dir.join("in.gltf");
    std::fs::write(&input, serde_json::to_vec(&asset).unwrap()).unwrap();
    let out = dir.join("out.glb");
    let (code, text) = gltfmat(&[
        "upgrade",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("ACCESSOR_INVALID_FLOAT"), "{text}");
    assert!(text.contains("was made from 1.0 /accessors/uv"), "{text}");
    assert!(
        !text.contains("ARRAY_TYPE_MISMATCH") && !text.contains("null"),
        "{text}"
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// An asset made on a case-insensitive system names its buffer `box.bin` beside a file
/// `Box.bin`: the upgrade reads that one file, as the author's system did, and says so in
/// a decision line; `check` still reports the name, which finds nothing where names are
/// case-sensitive.
#[test]
fn a_file_named_in_another_letter_case_is_read_by_the_upgrade_and_reported_by_the_check() {
    let dir = scratch("letter-case");
    let fixtures = repo("fixtures/gltf1");
    std::fs::copy(
        fixtures.join("pbr-sg-textured-ext.gltf"),
        dir.join("in.gltf"),
    )
    .unwrap();
    for image in ["diffuse.png", "spec_gloss.png"] {
        std::fs::copy(fixtures.join(image), dir.join(image)).unwrap();
    }
    std::fs::copy(fixtures.join("box.bin"), dir.join("Box.bin")).unwrap();
    if dir.join("box.bin").exists() {
        return; // a case-insensitive file system finds the name itself
    }
    let input = dir.join("in.gltf");
    let input = input.to_str().unwrap();
    let out = dir.join("out.glb");
    let (code, text) = gltfmat(&["upgrade", input, "-o", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("decision / 'box.bin' names no file; 'Box.bin', whose name differs only in letter case, is read for it"),
        "{text}"
    );
    assert!(out.exists());
    // A glTF 2.0 input the same: read by the upgrade, reported by the check.
    let spec_gloss = repo("fixtures/spec-gloss");
    std::fs::copy(spec_gloss.join("factors.gltf"), dir.join("in2.gltf")).unwrap();
    std::fs::copy(spec_gloss.join("quad.bin"), dir.join("Quad.bin")).unwrap();
    let input = dir.join("in2.gltf");
    let input = input.to_str().unwrap();
    let out = dir.join("out2.glb");
    let (code, text) = gltfmat(&["upgrade", input, "-o", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("'quad.bin' names no file; 'Quad.bin'"),
        "{text}"
    );
    let (code, text) = gltfmat(&["check", input]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("quad.bin: no such file; Quad.bin differs only in letter case"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// An image stored in a bufferView whose buffer cannot be read leaves its material not
/// evaluated, and says which buffer and why, not only that the view cannot be read.
#[test]
fn an_image_in_a_buffer_that_cannot_be_read_names_the_buffer_and_why() {
    let dir = scratch("image-buffer");
    let asset = serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "gone.bin", "byteLength": 64}],
        "bufferViews": [{"buffer": 0, "byteLength": 64}],
        "images": [{"bufferView": 0, "mimeType": "image/png"}],
        "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    });
    let input = dir.join("in.gltf");
    std::fs::write(&input, serde_json::to_vec(&asset).unwrap()).unwrap();
    let input = input.to_str().unwrap();
    let (code, text) = gltfmat(&["compare", input, input, "--format", "json"]);
    assert_eq!(code, 1, "{text}");
    let pairs: Value = serde_json::from_str(&text).unwrap();
    let unread = pairs[0]["notEvaluated"].to_string();
    assert!(
        unread.contains("image 0: buffer 0: gone.bin: no such file"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The textured Fraunhofer box with its 24 texture coordinates replaced by `uvs` (a data-URI
/// buffer of its own) and its diffuse image by `diffuse`, in `dir`.
fn box_1_0_with(dir: &Path, name: &str, uvs: [f32; 2], diffuse: &image::RgbImage) {
    use base64::Engine;
    let mut asset: Value = serde_json::from_slice(
        &std::fs::read(repo("fixtures/gltf1/pbr-mr-textured-fraunhofer.gltf")).unwrap(),
    )
    .unwrap();
    // Every vertex in a small square at `uvs`, 0.15 a side: the three texture corners
    // around it never read.
    let corners = [[0.0, 0.0], [0.15, 0.0], [0.15, 0.15], [0.0, 0.15]];
    let data: Vec<u8> = (0..24)
        .flat_map(|i| {
            let [du, dv] = corners[i % 4];
            [uvs[0] + du, uvs[1] + dv]
        })
        .flat_map(f32::to_le_bytes)
        .collect();
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&data)
    );
    asset["buffers"]["uvs"] = serde_json::json!({"byteLength": data.len(), "uri": uri});
    asset["bufferViews"]["uvs"] =
        serde_json::json!({"buffer": "uvs", "byteOffset": 0, "byteLength": data.len()});
    asset["accessors"]["accessor_27"] = serde_json::json!({"bufferView": "uvs", "byteOffset": 0,
        "componentType": 5126, "count": 24, "type": "VEC2"});
    for file in ["box.bin", "metal_rough.png"] {
        std::fs::copy(repo(&format!("fixtures/gltf1/{file}")), dir.join(file)).unwrap();
    }
    let image = format!("{name}.png");
    diffuse.save(dir.join(&image)).unwrap();
    asset["images"]["diffuse"]["uri"] = serde_json::json!(image);
    std::fs::write(dir.join(name), asset.to_string()).unwrap();
}

/// A glTF 1.0 asset's meshes are read as a 2.0 asset's: the comparison samples the texels its
/// triangles read, through TEXCOORD_0.
#[test]
fn a_1_0_asset_is_compared_where_its_mesh_lies() {
    let folder = tempfile::tempdir().unwrap();
    let dir = folder.path();
    let plain = image::RgbImage::from_pixel(16, 16, image::Rgb([200, 150, 90]));
    // The same image, but for the texture's lower right quarter.
    let changed = image::RgbImage::from_fn(16, 16, |x, y| match x >= 8 && y >= 8 {
        true => image::Rgb([30, 60, 220]),
        false => image::Rgb([200, 150, 90]),
    });
    box_1_0_with(dir, "source.gltf", [0.1, 0.1], &plain);
    box_1_0_with(dir, "off.gltf", [0.1, 0.1], &changed);
    box_1_0_with(dir, "on.gltf", [0.7, 0.7], &changed);
    let compared = |b: &str| {
        let options = gltfmat::CompareOptions::default();
        let mut outcomes = gltfmat::compare(dir.join("source.gltf"), dir.join(b), &options)
            .unwrap()
            .outcomes;
        outcomes.remove(0).result
    };
    let off = compared("off.gltf");
    assert_eq!(off.max, 0.0, "{off:?}");
    assert!(
        matches!(off.area, gltfmat::Area::Mesh { texels } if texels < 16 * 16 / 4),
        "{:?}",
        off.area
    );
    assert!(compared("on.gltf").max > 1.0);
}
