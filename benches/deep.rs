//! `cargo bench --bench deep`: time of `check --deep` per 4096² texture.
//!
//! Generates (in a temporary folder) an asset with a 4096² normal map, a 4096² anisotropy
//! map and a 4096² base colour, all PNG with varied content so compression is realistic,
//! then prints the best of three runs of the full check with pixel rules, per texture.

use gltfmat::FolderResources;
use gltfmat::{check_bytes, CheckOptions};
use image::{ImageFormat, RgbImage, RgbaImage};
use std::time::Instant;

const SIZE: u32 = 4096;

fn main() {
    let folder = std::env::temp_dir().join(format!("gltfmat-bench-deep-{}", std::process::id()));
    std::fs::create_dir_all(&folder).expect("temp folder");
    let wave = |x: u32, y: u32| (x as f32 * 0.013).sin() * (y as f32 * 0.007).cos() * 0.5 + 0.5;
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let t = wave(x, y) * 0.6 - 0.3;
        let z = (1.0 - t * t).sqrt();
        image::Rgb([(t * 127.5 + 128.0) as u8, 128, (z * 127.5 + 128.0) as u8])
    })
    .save_with_format(folder.join("normal.png"), ImageFormat::Png)
    .expect("normal map");
    RgbaImage::from_fn(SIZE, SIZE, |x, y| {
        let angle = wave(x, y) * std::f32::consts::TAU;
        image::Rgba([
            (angle.cos() * 127.0 + 128.0) as u8,
            (angle.sin() * 127.0 + 128.0) as u8,
            255,
            255,
        ])
    })
    .save_with_format(folder.join("anisotropy.png"), ImageFormat::Png)
    .expect("anisotropy map");
    RgbImage::from_fn(SIZE, SIZE, |x, y| {
        let v = (wave(x, y) * 180.0 + 40.0) as u8;
        image::Rgb([v, v / 2 + 60, 90])
    })
    .save_with_format(folder.join("base.png"), ImageFormat::Png)
    .expect("base colour");
    let asset = serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_anisotropy"],
        "images": [{"uri": "normal.png"}, {"uri": "anisotropy.png"}, {"uri": "base.png"}],
        "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
        "materials": [{
            "normalTexture": {"index": 0},
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 2}, "metallicFactor": 0.0},
            "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8, "anisotropyTexture": {"index": 1}}}
        }]
    });
    let bytes = serde_json::to_vec(&asset).expect("json");
    let loader = FolderResources::new(&folder);
    let options = CheckOptions::default().with_deep(true);
    for groups in [
        vec!["pixels".to_string(), "plausibility".to_string()],
        vec!["plausibility".to_string()],
        vec!["pixels".to_string()],
    ] {
        let options = CheckOptions::default()
            .with_deep(true)
            .with_disabled_groups(groups.clone());
        let start = Instant::now();
        check_bytes("bench.gltf", bytes.clone(), &loader, &options);
        println!(
            "breakdown: with groups {groups:?} disabled: {:.3} s",
            start.elapsed().as_secs_f64()
        );
    }
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        let start = Instant::now();
        let report = check_bytes("bench.gltf", bytes.clone(), &loader, &options);
        best = best.min(start.elapsed().as_secs_f64());
        assert!(report
            .diagnostics
            .iter()
            .all(|d| d.code != "IMAGE_UNDECODABLE"));
    }
    let textures = 3.0;
    println!(
        "check --deep, three {SIZE}x{SIZE} PNG textures: {best:.3} s in all, {:.3} s per texture (best of 3)",
        best / textures
    );
    let _ = std::fs::remove_dir_all(&folder);
}
