//! Regression suite for hostile input: each case gets a diagnostic (or a clean refusal), in
//! bounded memory, and never a panic. Cases built from bytes here; the file fixtures are in
//! tests/cli.rs (truncated GLB, 4 GiB claims, 100 000-deep JSON, `..` and absolute URIs).

mod common;

use base64::Engine;
use gltfmat::check::{check_bytes, CheckOptions, Report};
use gltfmat::document::uri::{FolderResources, NoResources};
use gltfmat::upgrade::{upgrade, UpgradeOptions};
use serde_json::json;

fn codes(report: &Report) -> Vec<&'static str> {
    report.diagnostics.iter().map(|d| d.code.name()).collect()
}

fn deep() -> CheckOptions {
    CheckOptions::default().with_deep(true)
}

#[test]
fn an_accessor_claiming_two_to_the_31_elements_is_refused_not_allocated() {
    let gltf1 = json!({
        "asset": {"version": "1.0"},
        "buffers": {"b": {"uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAA", "byteLength": 12}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": 12}},
        "accessors": {"a": {"bufferView": "v", "byteOffset": 0, "componentType": 5126, "count": 2_147_483_648u64, "type": "VEC3"}},
        "meshes": {"m": {"primitives": [{"attributes": {"POSITION": "a"}}]}},
        "scenes": {"s": {"nodes": []}}
    });
    let error = upgrade(
        &serde_json::to_vec(&gltf1).unwrap(),
        &NoResources,
        &UpgradeOptions::default(),
    )
    .expect_err("the accessor does not fit its view");
    assert!(error.to_string().contains("runs past the end"), "{error}");

    let mut gltf2 = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAA", "byteLength": 12}],
        "bufferViews": [{"buffer": 0, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 1, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]
    });
    for count in [2_147_483_648u64, u64::MAX] {
        gltf2["accessors"][0]["count"] = json!(count);
        let report = check_bytes(
            "count.gltf",
            serde_json::to_vec(&gltf2).unwrap(),
            &NoResources,
            &deep(),
        );
        let found = codes(&report);
        assert!(
            found.contains(&"ACCESSOR_TOO_LONG"),
            "count {count}: {found:?}"
        );
    }
}

/// A PNG header claiming 60000 × 60000 RGBA (14 GB decoded) behind a tiny file.
fn png_bomb() -> Vec<u8> {
    let chunk = common::chunk;
    let mut ihdr = 60_000u32.to_be_bytes().to_vec();
    ihdr.extend(60_000u32.to_be_bytes());
    ihdr.extend([8, 6, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(chunk(b"IHDR", &ihdr));
    png.extend(chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00]));
    png.extend(chunk(b"IEND", &[]));
    png
}

fn asset_with_image(uri: String) -> Vec<u8> {
    serde_json::to_vec(&json!({
        "asset": {"version": "2.0"},
        "images": [{"uri": uri}], "textures": [{"source": 0}],
        "materials": [{"normalTexture": {"index": 0}}]
    }))
    .unwrap()
}

#[test]
fn decompression_bombs_are_reported_not_decoded() {
    let uri = format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png_bomb())
    );
    let report = check_bytes("bomb.gltf", asset_with_image(uri), &NoResources, &deep());
    assert!(
        codes(&report).contains(&"IMAGE_DECODE_LIMIT"),
        "{:?}",
        codes(&report)
    );
    // A JPEG whose SOF claims 65500 × 65500.
    let mut jpeg = vec![
        0xFF, 0xD8, 0xFF, 0xC0, 0x00, 0x11, 0x08, 0xFF, 0xDC, 0xFF, 0xDC, 0x03,
    ];
    jpeg.extend([1, 0x11, 0, 2, 0x11, 0, 3, 0x11, 0, 0xFF, 0xD9]);
    let uri = format!(
        "data:image/jpeg;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(jpeg)
    );
    let report = check_bytes("bomb.gltf", asset_with_image(uri), &NoResources, &deep());
    let found = codes(&report);
    assert!(
        found.contains(&"IMAGE_DECODE_LIMIT")
            || found.contains(&"IMAGE_UNDECODABLE")
            || found.contains(&"IMAGE_DATA_INVALID"),
        "{found:?}"
    );
}

#[test]
fn a_huge_data_uri_is_checked_in_memory_proportional_to_it() {
    // 24 MB of buffer in a data URI: decoded once, no copies beyond that.
    let data = vec![0u8; 24 << 20];
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&data)
    );
    let asset = serde_json::to_vec(
        &json!({"asset": {"version": "2.0"}, "buffers": [{"uri": uri, "byteLength": data.len()}]}),
    )
    .unwrap();
    let report = check_bytes("big.gltf", asset, &NoResources, &CheckOptions::default());
    assert!(!report.has_errors(), "{:?}", codes(&report));
    assert!(codes(&report).contains(&"UNUSED_OBJECT"));
}

#[cfg(unix)]
#[test]
fn a_symlink_leaving_the_asset_folder_is_not_followed() {
    let root = std::env::temp_dir().join(format!("gltfmat-hostile-{}", std::process::id()));
    let asset_folder = root.join("asset");
    std::fs::create_dir_all(&asset_folder).unwrap();
    std::fs::write(root.join("secret.bin"), [1u8; 16]).unwrap();
    let _ = std::os::unix::fs::symlink(root.join("secret.bin"), asset_folder.join("data.bin"));
    let asset = serde_json::to_vec(
        &json!({"asset": {"version": "2.0"}, "buffers": [{"uri": "data.bin", "byteLength": 16}]}),
    )
    .unwrap();
    let report = check_bytes(
        "a.gltf",
        asset,
        &FolderResources::new(&asset_folder),
        &CheckOptions::default(),
    );
    assert!(
        codes(&report).contains(&"URI_OUTSIDE_ASSET_FOLDER"),
        "{:?}",
        codes(&report)
    );
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_corrupt_index_buffer_gives_a_bounded_list_of_findings() {
    // 100 000 indices, every one past the single vertex: one finding each would be 100 000
    // diagnostics; the data pass keeps 1000 and says how many more there were.
    let count = 100_000u32;
    let mut bin = Vec::new();
    bin.extend_from_slice(&[0u8; 12]); // one vertex at the origin
    for i in 0..count {
        bin.extend_from_slice(&(i % 60_000 + 1).to_le_bytes());
    }
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bin)
    );
    let gltf = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": uri, "byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 12, "target": 34962},
            {"buffer": 0, "byteOffset": 12, "byteLength": count * 4, "target": 34963}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 1, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]},
            {"bufferView": 1, "componentType": 5125, "count": count, "type": "SCALAR"}
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}]
    });
    let report = check_bytes(
        "oob.gltf",
        serde_json::to_vec(&gltf).unwrap(),
        &NoResources,
        &CheckOptions::default(),
    );
    let oob: Vec<_> = report
        .diagnostics
        .iter()
        .filter(|d| d.code == "ACCESSOR_INDEX_OOB")
        .collect();
    assert_eq!(oob.len(), 1000, "{:?}", codes(&report));
    assert!(
        oob[999].message.contains("99000 more findings"),
        "{}",
        oob[999].message
    );
}

#[test]
fn offsets_near_two_to_the_64_are_a_finding_not_a_wrapped_sum() {
    for (offset, stride) in [
        (18_446_744_073_709_551_612u64, None),
        (0, Some(9_223_372_036_854_775_808u64)),
    ] {
        let mut view = json!({"buffer": 0, "byteLength": 36});
        if let Some(stride) = stride {
            view["byteStride"] = json!(stride);
        }
        let gltf = json!({
            "asset": {"version": "2.0"},
            "buffers": [{"byteLength": 36, "uri": format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode([0u8; 36]))}],
            "bufferViews": [view],
            "accessors": [{"bufferView": 0, "byteOffset": offset, "componentType": 5126, "count": 3, "type": "VEC3"}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]
        });
        let bytes = serde_json::to_vec(&gltf).unwrap();
        for profile in [gltfmat::Profile::Default, gltfmat::Profile::Khronos] {
            let options = CheckOptions::default().with_profile(profile);
            let report = check_bytes("extreme.gltf", bytes.clone(), &NoResources, &options);
            assert!(
                report.has_errors(),
                "offset {offset}, stride {stride:?}: {:?}",
                codes(&report)
            );
        }
    }
}

#[test]
fn a_file_without_a_2_x_version_gets_only_the_asset_findings() {
    // The rest of the file is not judged by rules of a version it does not claim.
    for asset in [json!({}), json!({"version": "3.0"})] {
        let gltf = json!({"asset": asset, "nodes": [{"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "children": [7]}]});
        let options = CheckOptions::default().with_profile(gltfmat::Profile::Khronos);
        let report = check_bytes(
            "v.gltf",
            serde_json::to_vec(&gltf).unwrap(),
            &NoResources,
            &options,
        );
        let found = codes(&report);
        assert!(!found.is_empty(), "{asset}");
        assert!(
            report
                .diagnostics
                .iter()
                .all(|d| d.pointer().is_some_and(|p| p.starts_with("/asset"))),
            "{asset}: {found:?}"
        );
    }
}

#[test]
fn max_issues_keeps_errors_first_and_counts_everything() {
    // The schema pass emits the warning (an unknown root member) before the link pass emits
    // the error (an unresolved scene).
    let gltf = json!({"asset": {"version": "2.0"}, "unknownMember": 1, "scene": 5});
    let bytes = serde_json::to_vec(&gltf).unwrap();
    let all = check_bytes(
        "m.gltf",
        bytes.clone(),
        &NoResources,
        &CheckOptions::default(),
    );
    assert_eq!(codes(&all)[0], "UNEXPECTED_PROPERTY", "{:?}", codes(&all));
    let options = CheckOptions::default().with_max_issues(1);
    let report = check_bytes("m.gltf", bytes, &NoResources, &options);
    assert!(report.truncated);
    assert_eq!(codes(&report), ["UNRESOLVED_REFERENCE"]);
    for severity in gltfmat::Severity::ALL {
        assert_eq!(report.count(severity), all.count(severity), "{severity}");
    }
    assert!(report.has_errors());
}

#[test]
fn an_index_beyond_u64_is_unresolved_as_written_not_saturated() {
    let gltf = br#"{"asset":{"version":"2.0"},"nodes":[{"mesh":1e29}],"scenes":[{"nodes":[0]}]}"#;
    let report = check_bytes(
        "i.gltf",
        gltf.to_vec(),
        &NoResources,
        &CheckOptions::default(),
    );
    let found: Vec<_> = report
        .diagnostics
        .iter()
        .filter(|d| d.code == "UNRESOLVED_REFERENCE")
        .collect();
    assert_eq!(found.len(), 1, "{:?}", codes(&report));
    assert!(found[0].message.contains("1e+29"), "{}", found[0].message);
    assert!(!found[0].message.contains("18446744073709551615"));
}
