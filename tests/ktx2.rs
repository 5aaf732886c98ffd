//! KTX2 textures (KHR_texture_basisu) are read like any other image: by the checker's pixel and
//! colour-space rules, by `compare`, `render` and the proof. The fixtures in `fixtures/ktx2`
//! were encoded by Binomial's `basisu`, and each `*.basisu.png` is that tool's own (C++)
//! transcoding of a KTX2 to RGBA32: the reference gltfmat's transcoding is held to.

mod common;
use common::gltfmat;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/ktx2")
}

/// A scratch folder holding copies of every KTX2 fixture file.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gltfmat-ktx2-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for entry in std::fs::read_dir(fixtures()).unwrap() {
        let path = entry.unwrap().path();
        std::fs::copy(&path, dir.join(path.file_name().unwrap())).unwrap();
    }
    dir
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `fixture` (a KTX2 variant) with each image replaced by the reference transcoder's PNG of
/// it, as plain textures: the same texels, no KTX2.
fn reference_variant(dir: &Path, fixture: &str) -> PathBuf {
    let mut doc = read_json(&dir.join(fixture));
    for image in doc["images"].as_array_mut().unwrap() {
        let uri = image["uri"]
            .as_str()
            .unwrap()
            .replace(".ktx2", ".basisu.png");
        image["uri"] = Value::from(uri);
    }
    for texture in doc["textures"].as_array_mut().unwrap() {
        let source = texture["extensions"]["KHR_texture_basisu"]["source"].clone();
        *texture = serde_json::json!({ "source": source });
    }
    let object = doc.as_object_mut().unwrap();
    object.remove("extensionsUsed");
    object.remove("extensionsRequired");
    let out = dir.join(fixture.replace(".gltf", "-reference.gltf"));
    std::fs::write(&out, doc.to_string()).unwrap();
    out
}

fn compare_json(a: &Path, b: &Path) -> Value {
    let (_, text) = gltfmat(&[
        "compare",
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let all: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    all[0].clone()
}

#[test]
fn ktx2_textures_read_as_the_reference_transcoder_decodes_them() {
    let dir = scratch("reference");
    for fixture in ["etc1s.gltf", "uastc.gltf"] {
        let reference = reference_variant(&dir, fixture);
        let pair = compare_json(&dir.join(fixture), &reference);
        assert_eq!(
            pair["notEvaluated"],
            serde_json::json!([]),
            "{fixture}: {pair}"
        );
        assert_eq!(pair["max"], 0.0, "{fixture}: {pair}");
        assert_eq!(pair["pass"], true, "{fixture}: {pair}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Against the PNG they were encoded from, the KTX2 variants differ by exactly what their
/// texels differ by: the figure is the compression's own error, gltfmat adds none. UASTC (up
/// to 3/255 per channel here) keeps the base colour within a few ΔE where ETC1S (29.6 dB)
/// does not.
#[test]
fn a_ktx2_variant_differs_from_its_png_source_by_the_compressions_own_error() {
    let dir = scratch("source");
    let png = dir.join("png.gltf");
    let mut maxima = Vec::new();
    for fixture in ["uastc.gltf", "etc1s.gltf"] {
        let reference = reference_variant(&dir, fixture);
        let ktx2 = compare_json(&png, &dir.join(fixture));
        let texels = compare_json(&png, &reference);
        for key in ["max", "p99", "mean"] {
            let (a, b) = (ktx2[key].as_f64().unwrap(), texels[key].as_f64().unwrap());
            assert!(
                (a - b).abs() < 1e-9,
                "{fixture} {key}: {ktx2} against {texels}"
            );
        }
        assert!(ktx2["max"].as_f64().unwrap() > 0.0, "{fixture}: {ktx2}");
        maxima.push(ktx2["p99"].as_f64().unwrap());
    }
    assert!(maxima[0] < maxima[1], "UASTC p99 {maxima:?} below ETC1S's");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn render_draws_a_ktx2_material_as_its_texels() {
    let dir = scratch("render");
    let reference = reference_variant(&dir, "uastc.gltf");
    let render = |asset: &Path, out: &str| {
        let out = dir.join(out);
        let args = [
            "render",
            asset.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--size",
            "48",
        ];
        let (code, text) = gltfmat(&args);
        assert_eq!(code, 0, "{text}");
        std::fs::read(out).unwrap()
    };
    let ktx2 = render(&dir.join("uastc.gltf"), "ktx2.png");
    assert_eq!(ktx2, render(&reference, "reference.png"));
    assert_ne!(ktx2, render(&dir.join("etc1s.gltf"), "etc1s.png"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The codes `check --deep` reports for `doc` written beside the fixtures.
fn deep_codes(dir: &Path, name: &str, doc: &Value) -> Vec<String> {
    std::fs::write(dir.join(name), doc.to_string()).unwrap();
    let path = dir.join(name);
    let args = [
        "check",
        "--deep",
        "--format",
        "json",
        path.to_str().unwrap(),
    ];
    let (_, text) = gltfmat(&args);
    let report: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    (report["issues"]["messages"].as_array().unwrap().iter())
        .map(|f| f["code"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn the_pixel_and_colour_space_rules_read_ktx2_textures() {
    let dir = scratch("rules");
    let uastc = read_json(&dir.join("uastc.gltf"));
    let codes = deep_codes(&dir, "as-made.gltf", &uastc);
    assert!(
        !codes.iter().any(|c| c.starts_with("IMAGE_")),
        "a valid UASTC asset is decoded: {codes:?}"
    );
    // A normal map pointing into the surface, in ETC1S: the texel rule sees its texels; and
    // one whose data format descriptor says sRGB, which a viewer decodes as colour.
    let with_normal_map = |name: &str, file: &str| {
        let mut doc = uastc.clone();
        doc["images"][1]["uri"] = Value::from(file);
        deep_codes(&dir, name, &doc)
    };
    let inward = with_normal_map("inward.gltf", "inward-normal-etc1s.ktx2");
    let srgb = with_normal_map("srgb-normal.gltf", "normal-etc1s-srgb.ktx2");
    let has = |codes: &[String], code: &str| codes.iter().any(|c| c == code);
    assert!(has(&inward, "NORMAL_TEXEL_BELOW_SURFACE"), "{inward:?}");
    assert!(!has(&inward, "KTX2_TRANSFER_MISMATCH"), "{inward:?}");
    assert!(has(&srgb, "KTX2_TRANSFER_MISMATCH"), "{srgb:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A texture with a PNG fallback and a KTX2 through KHR_texture_basisu is drawn from the KTX2,
/// as viewers that support the extension draw it.
#[test]
fn a_texture_with_a_fallback_is_evaluated_from_its_ktx2() {
    let dir = scratch("fallback");
    let mut doc = read_json(&dir.join("etc1s.gltf"));
    let images = doc["images"].as_array_mut().unwrap();
    images.push(serde_json::json!({"uri": "base.png"}));
    doc["textures"][0]["source"] = Value::from(images.len() - 1);
    doc.as_object_mut().unwrap().remove("extensionsRequired");
    let with_fallback = dir.join("with-fallback.gltf");
    std::fs::write(&with_fallback, doc.to_string()).unwrap();
    let pair = compare_json(&dir.join("etc1s.gltf"), &with_fallback);
    assert_eq!(pair["max"], 0.0, "{pair}");
    let pair = compare_json(&dir.join("png.gltf"), &with_fallback);
    assert!(pair["p99"].as_f64().unwrap() > 1.0, "{pair}");
    std::fs::remove_dir_all(&dir).unwrap();
}
