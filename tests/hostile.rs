//! Regression suite for hostile input: each case gets a diagnostic (or a clean refusal), in
//! bounded memory, and never a panic. Cases built from bytes here; the file fixtures are in
//! tests/cli.rs (truncated GLB, 4 GiB claims, 100 000-deep JSON, `..` and absolute URIs).

mod common;

use base64::Engine;
use gltfmat::{
    check_bytes, upgrade, CheckOptions, FolderResources, NoResources, Report, UpgradeOptions,
};
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
        serde_json::to_vec(&gltf1).unwrap(),
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

/// KTX2 files whose header claims what no texture of their size holds: a Zstandard level
/// of a terabyte uncompressed (the transcoder would allocate it and abort the process), and
/// a million array layers. Each is an undecodable image, at once.
#[test]
fn ktx2_bombs_are_reported_not_allocated() {
    let fixture =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/ktx2/normal-uastc.ktx2");
    let valid = std::fs::read(fixture).unwrap();
    let claiming = |at: usize, value: &[u8]| {
        let mut bytes = valid.clone();
        bytes[at..at + value.len()].copy_from_slice(value);
        bytes
    };
    let terabyte_level = claiming(80 + 16, &(1u64 << 40).to_le_bytes());
    let million_layers = claiming(32, &1_000_000u32.to_le_bytes());
    for (what, bytes) in [
        ("terabyte level", terabyte_level),
        ("million layers", million_layers),
    ] {
        let uri = format!(
            "data:image/ktx2;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(bytes)
        );
        let start = std::time::Instant::now();
        let report = check_bytes("bomb.gltf", asset_with_image(uri), &NoResources, &deep());
        assert!(
            codes(&report).contains(&"IMAGE_UNDECODABLE"),
            "{what}: {:?}",
            codes(&report)
        );
        assert!(
            start.elapsed().as_secs() < 5,
            "{what}: {:?}",
            start.elapsed()
        );
    }
}

/// Every byte of a KTX2's data format descriptor block set to 255 in turn (the fuzzer found
/// a texel block dimension of 255 panicking a descriptor parser): the header is still read,
/// with or without --deep, and nothing panics.
#[test]
fn every_descriptor_byte_at_its_extreme_is_read_without_panic() {
    let fixture =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/ktx2/normal-uastc.ktx2");
    let valid = std::fs::read(fixture).unwrap();
    let descriptor = u32::from_le_bytes(valid[48..52].try_into().unwrap()) as usize;
    for at in descriptor..descriptor + 44 {
        for value in [0u8, 255] {
            let mut bytes = valid.clone();
            bytes[at] = value;
            let uri = format!(
                "data:image/ktx2;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(bytes)
            );
            for options in [deep(), CheckOptions::default()] {
                let _ = check_bytes(
                    "dfd.gltf",
                    asset_with_image(uri.clone()),
                    &NoResources,
                    &options,
                );
            }
        }
    }
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
    // diagnostics; the data pass keeps 10 000, says how many more there were and counts them.
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
    assert_eq!(oob.len(), 10_000);
    assert!(
        oob[9_999].message.contains("90000 more findings"),
        "{}",
        oob[9_999].message
    );
    assert!(
        report.count(gltfmat::Severity::Error) >= count as usize,
        "every one counted"
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

fn check(gltf: &serde_json::Value, options: &CheckOptions) -> Report {
    check_bytes(
        "big.gltf",
        serde_json::to_vec(gltf).unwrap(),
        &NoResources,
        options,
    )
}

fn count(report: &Report, code: &str) -> usize {
    report.diagnostics.iter().filter(|d| d.code == code).count()
}

fn every_issue() -> CheckOptions {
    CheckOptions::default().with_max_issues(0)
}

/// A 1.0 skin instance whose jointNames and skeleton ids are given.
fn gltf1_skin(joint_names: &[&str], skeleton_children: &[&str]) -> Vec<u8> {
    let identity: Vec<u8> = [
        1f32, 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.,
    ]
    .iter()
    .flat_map(|v| v.to_le_bytes())
    .collect::<Vec<u8>>()
    .repeat(joint_names.len());
    let data = base64::engine::general_purpose::STANDARD.encode(&identity);
    serde_json::to_vec(&json!({
        "asset": {"version": "1.0"},
        "buffers": {"b": {"uri": format!("data:application/octet-stream;base64,{data}"), "byteLength": identity.len()}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": identity.len()}},
        "accessors": {"ibm": {"bufferView": "v", "byteOffset": 0, "componentType": 5126, "count": joint_names.len(), "type": "MAT4"}},
        "skins": {"s": {"jointNames": joint_names, "inverseBindMatrices": "ibm",
            "bindShapeMatrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}},
        "nodes": {
            "root": {"jointName": "A", "children": skeleton_children},
            "b": {"jointName": "B"},
            "instance": {"skin": "s", "skeletons": ["root"]}
        },
        "scenes": {"s": {"nodes": ["root", "instance"]}},
        "scene": "s"
    }))
    .unwrap()
}

#[test]
fn a_skin_whose_joints_cannot_all_be_found_is_refused_not_shifted() {
    let options = UpgradeOptions::default();
    let whole = upgrade(gltf1_skin(&["A", "B"], &["b"]), &NoResources, &options).unwrap();
    assert_eq!(whole.json.to_value()["skins"][0]["joints"], json!([0, 1]));

    // Finding 10: "C" names no node, so every later joint would move up one place.
    let error = upgrade(gltf1_skin(&["C", "B"], &["b"]), &NoResources, &options).unwrap_err();
    assert!(
        error.to_string().contains("/skins/s/jointNames/0"),
        "{error}"
    );
    assert!(error.to_string().contains("'C' names no node"), "{error}");

    // A child id in the skeleton that names no node hides the joints below it.
    let error = upgrade(
        gltf1_skin(&["A", "B"], &["b", "ghost"]),
        &NoResources,
        &options,
    )
    .unwrap_err();
    assert!(
        error.to_string().contains("/nodes/root/children"),
        "{error}"
    );
    assert!(
        error.to_string().contains("'ghost' does not exist"),
        "{error}"
    );
}

#[test]
fn a_hundred_thousand_node_chain_is_walked_once() {
    // Finding 11: each node used to walk to the root (10^10 steps here).
    let n = 100_000;
    let mut nodes: Vec<_> = (0..n).map(|i| json!({"children": [i + 1]})).collect();
    // The last three nodes form a loop: 99997 → 99998 → 99999 → 99997.
    nodes[n - 1] = json!({"children": [n - 3], "translation": [1, 0, 0]});
    let report = check(
        &json!({"asset": {"version": "2.0"}, "nodes": nodes, "scenes": [{"nodes": [0]}]}),
        &every_issue(),
    );
    let looped: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code == "NODE_LOOP")
        .map(|d| d.pointer().unwrap_or_default().to_string())
        .collect();
    assert_eq!(looped, ["/nodes/99997", "/nodes/99998", "/nodes/99999"]);
}

#[test]
fn common_skin_roots_are_found_for_thirty_thousand_joints() {
    let n = 30_000;
    let chain: Vec<_> = (0..n).map(|i| json!({"children": [i + 1]})).collect();
    let mut nodes = chain.clone();
    nodes.push(json!({}));
    let joints: Vec<usize> = (0..=n).collect();
    let rooted = check(
        &json!({"asset": {"version": "2.0"}, "nodes": nodes, "skins": [{"joints": joints, "skeleton": 0}]}),
        &every_issue(),
    );
    assert_eq!(count(&rooted, "SKIN_NO_COMMON_ROOT"), 0);
    assert_eq!(count(&rooted, "SKIN_SKELETON_INVALID"), 0);
    // The skeleton must be an ancestor of every joint: the chain's second node is not one
    // of the first.
    let deeper = check(
        &json!({"asset": {"version": "2.0"}, "nodes": nodes, "skins": [{"joints": joints, "skeleton": 1}]}),
        &every_issue(),
    );
    assert_eq!(count(&deeper, "SKIN_SKELETON_INVALID"), 1);
    // Two separate trees have no common root.
    let mut forest = nodes.clone();
    forest.push(json!({}));
    let split = check(
        &json!({"asset": {"version": "2.0"}, "nodes": forest, "skins": [{"joints": [n, n + 1]}]}),
        &every_issue(),
    );
    assert_eq!(count(&split, "SKIN_NO_COMMON_ROOT"), 1);
}

#[test]
fn repeated_keys_and_shared_textures_are_found_in_linear_time() {
    let n = 20_000;
    let text = format!(
        r#"{{"asset":{{"version":"2.0"}},"extras":{{{}}}}}"#,
        vec![r#""k":0"#; n].join(",")
    );
    let report = check_bytes("k.gltf", text.into_bytes(), &NoResources, &every_issue());
    // One finding for the key, with its count: 10^6 repeats must not be 10^6 findings.
    let found: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code == "JSON_DUPLICATE_KEY")
        .collect();
    assert_eq!(found.len(), 1);
    assert!(found[0]
        .message
        .contains(&format!("({n} times in this object)")));

    // Every other material reads the one image as sRGB colour, the rest as linear data: one
    // finding for the image, naming the first use of each kind and counting the rest.
    let materials: Vec<_> = (0..n)
        .map(|i| match i % 2 {
            0 => json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}),
            _ => json!({"occlusionTexture": {"index": 0}}),
        })
        .collect();
    let report = check(
        &json!({"asset": {"version": "2.0"}, "images": [{"uri": "a.png"}], "textures": [{"source": 0}], "materials": materials}),
        &every_issue(),
    );
    let conflicts: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code == "IMAGE_COLOR_SPACE_CONFLICT")
        .collect();
    assert_eq!(conflicts.len(), 1);
    assert_eq!(
        conflicts[0].message,
        format!("Image 0 is read as sRGB colour by /materials/0/pbrMetallicRoughness/baseColorTexture and as linear data by /materials/1/occlusionTexture in channel(s) R; {n} of its {n} bindings clash.")
    );
}

#[test]
fn fifty_thousand_declared_extensions_are_looked_up_not_searched() {
    // Each extension object and each required name searched the whole declared list
    // (2.5·10^9 comparisons here; 10^5 names took 65 s).
    let n = 50_000;
    let names: Vec<String> = (0..n).map(|i| format!("X_e{i}")).collect();
    let mut required = names.clone();
    required.push("X_never_used".into());
    let mut nodes: Vec<_> = (names.iter().rev())
        .map(|name| json!({"extensions": {name: {}}}))
        .collect();
    nodes.push(json!({"extensions": {"X_undeclared": {}}}));
    let report = check(
        &json!({"asset": {"version": "2.0"}, "extensionsUsed": names,
            "extensionsRequired": required, "nodes": nodes, "extras": {"extensions": {"X_u": {}}}}),
        &every_issue(),
    );
    assert_eq!(count(&report, "UNSUPPORTED_EXTENSION"), n);
    let undeclared: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code == "UNDECLARED_EXTENSION")
        .map(|d| d.pointer().unwrap_or_default().to_string())
        .collect();
    assert_eq!(undeclared, [format!("/nodes/{n}/extensions/X_undeclared")]);
    let unused: Vec<_> = (report.diagnostics.iter())
        .filter(|d| d.code == "UNUSED_EXTENSION_REQUIRED")
        .map(|d| d.pointer().unwrap_or_default().to_string())
        .collect();
    assert_eq!(unused, [format!("/extensionsRequired/{n}")]);
}

#[test]
fn channels_sharing_a_target_give_one_finding_each_not_one_per_pair() {
    // Finding 12: N channels on one target were N²/2 findings (10^8 here).
    let n = 20_000;
    let channels: Vec<_> = (0..n)
        .map(|_| json!({"sampler": 0, "target": {"node": 0, "path": "translation"}}))
        .collect();
    let report = check(
        &json!({"asset": {"version": "2.0"}, "nodes": [{}],
            "animations": [{"channels": channels, "samplers": [{"input": 0, "output": 1}]}]}),
        &every_issue(),
    );
    assert_eq!(count(&report, "ANIMATION_DUPLICATE_TARGETS"), n - 1);
}

#[test]
fn max_issues_is_held_while_collecting_with_every_count_complete() {
    // Finding 13: 10^5 findings of each kind, 10 kept.
    let n = 100_000;
    let materials: Vec<_> = (0..n).map(|_| json!({})).collect();
    let zeros = vec![0; n];
    let options = CheckOptions::default().with_max_issues(10);
    let report = check(
        &json!({"asset": {"version": "2.0"}, "materials": materials, "meshes": zeros}),
        &options,
    );
    assert_eq!(report.diagnostics.len(), 10);
    assert!(report.truncated);
    assert_eq!(
        report.count(gltfmat::Severity::Error),
        n,
        "one TYPE_MISMATCH per mesh"
    );
    let all = check(
        &json!({"asset": {"version": "2.0"}, "materials": materials, "meshes": zeros}),
        &every_issue(),
    );
    for severity in gltfmat::Severity::ALL {
        assert_eq!(report.count(severity), all.count(severity), "{severity}");
    }
    // The elements past the first chunk are reported where they are.
    assert!(all
        .diagnostics
        .iter()
        .any(|d| d.pointer() == Some(&format!("/meshes/{}", n - 1))));
}

#[test]
fn every_printed_finding_is_at_its_own_line_however_many_there_are() {
    // Finding 14: one rescan of the file per finding.
    let n = 20_000;
    let nodes: Vec<_> = (0..n).map(|_| json!({"rotation": [1, 1, 1, 1]})).collect();
    let text = serde_json::to_string_pretty(&json!({"asset": {"version": "2.0"}, "nodes": nodes}))
        .unwrap();
    let report = check_bytes(
        "r.gltf",
        text.clone().into_bytes(),
        &NoResources,
        &every_issue(),
    );
    let human = gltfmat::report::render(
        gltfmat::report::Format::Human,
        std::slice::from_ref(&report),
        // Every one listed: grouping would show three.
        &gltfmat::report::Style::new(false).with_all_findings(true),
    );
    let lines: Vec<&str> = text.lines().collect();
    let mut seen = 0;
    for line in human.lines().filter(|l| l.contains("[ROTATION_NON_UNIT]")) {
        let position = line.strip_prefix("r.gltf:").unwrap();
        let (row, rest) = position.split_once(':').unwrap();
        let row: usize = row.parse().unwrap();
        let column: usize = rest.split_once(':').unwrap().0.parse().unwrap();
        assert!(
            lines[row - 1][column - 1..].starts_with("\"rotation\""),
            "{line}"
        );
        seen += 1;
    }
    assert_eq!(seen, n);
}

#[test]
fn a_minified_file_shows_each_finding_in_a_window_of_its_one_line() {
    // Each snippet decoded the whole line: on a minified file, the whole file per finding.
    let n = 20_000;
    let nodes: Vec<_> = (0..n).map(|_| json!({"rotation": [1, 1, 1, 1]})).collect();
    let text =
        serde_json::to_string(&json!({"asset": {"version": "2.0"}, "nodes": nodes})).unwrap();
    let report = check_bytes("m.gltf", text.into_bytes(), &NoResources, &every_issue());
    let human = gltfmat::report::render(
        gltfmat::report::Format::Human,
        std::slice::from_ref(&report),
        // Every one listed: grouping would show three.
        &gltfmat::report::Style::new(false).with_all_findings(true),
    );
    let lines: Vec<&str> = human.lines().collect();
    let mut seen = 0;
    let mut rotation = false;
    for pair in lines.windows(2) {
        if pair[0].starts_with("m.gltf:") {
            rotation = pair[0].contains("[ROTATION_NON_UNIT]");
        }
        let Some((gutter, shown)) = pair[0].split_once(" | ").filter(|_| rotation) else {
            continue;
        };
        if gutter.trim().parse::<usize>().is_err() {
            continue; // not a snippet line
        }
        let caret = pair[1].find('^').expect("a caret under every snippet");
        let column = caret - pair[1].find("| ").unwrap() - 2;
        let at: String = shown.chars().skip(column).take(10).collect();
        assert_eq!(at, "\"rotation\"", "{}\n{}", pair[0], pair[1]);
        let cut = shown.starts_with('…') || shown.ends_with('…');
        assert!(cut && shown.chars().count() <= 122, "a window: {shown}");
        seen += 1;
    }
    assert_eq!(seen, n);
}

/// A PNG claiming `size`² 8-bit RGBA texels, with no pixel data.
fn png_header(size: u32) -> Vec<u8> {
    let mut header = size.to_be_bytes().to_vec();
    header.extend(size.to_be_bytes());
    header.extend([8, 6, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    for (kind, data) in [(b"IHDR", &header[..]), (b"IDAT", &[]), (b"IEND", &[])] {
        let mut typed = kind.to_vec();
        typed.extend(data);
        png.extend((data.len() as u32).to_be_bytes());
        png.extend(&typed);
        png.extend(common::crc32(&typed).to_be_bytes());
    }
    png
}

fn textured(images: &[Vec<u8>]) -> serde_json::Value {
    let uri = |png: &Vec<u8>| {
        format!(
            "data:image/png;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(png)
        )
    };
    let images: Vec<_> = images.iter().map(|png| json!({"uri": uri(png)})).collect();
    let textures: Vec<_> = (0..images.len()).map(|i| json!({"source": i})).collect();
    let materials: Vec<_> = (0..images.len())
        .map(|i| json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": i}}}))
        .collect();
    json!({"asset": {"version": "2.0"}, "images": images, "textures": textures, "materials": materials})
}

/// Renders every material of `gltf`: what the picture could not draw, or why it was refused.
fn render_all(gltf: &serde_json::Value) -> Result<Vec<String>, String> {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("t.gltf");
    std::fs::write(&path, serde_json::to_vec(gltf).unwrap()).unwrap();
    let mut options = gltfmat::RenderOptions::default();
    options.all = true;
    options.size = 8;
    gltfmat::render(&path, &options)
        .map(|picture| picture.not_drawn.concat())
        .map_err(|e| e.to_string())
}

#[test]
fn decoded_textures_are_held_to_a_budget_before_anything_is_decoded() {
    // Two headers announcing about 1 GiB each once decoded, in a file of a few hundred bytes:
    // refused from their headers by a comparison (which needs every texel), nothing
    // allocated for them. (Two identical images would be one.)
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("t.gltf");
    let gltf = textured(&[png_header(16384), png_header(16383)]);
    std::fs::write(&path, serde_json::to_vec(&gltf).unwrap()).unwrap();
    let options = gltfmat::CompareOptions::default();
    let error = gltfmat::compare(&path, &path, &options)
        .unwrap_err()
        .to_string();
    assert!(error.contains("image 0 (16384×16384)"), "{error}");
    assert!(
        error.contains("past 96 MiB, this input's budget"),
        "{error}"
    );
}

#[test]
fn a_rebake_of_a_texture_past_the_budget_is_refused_and_the_material_left_as_it_was() {
    // A flat 16384² image compresses to half a megabyte and decodes to 1 GiB: the rebake's
    // decode is held to the same budget, and the material stays spec-gloss, saying why.
    let png = png_header(16384);
    let uri = format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&png)
    );
    let gltf = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "images": [{"uri": uri}], "textures": [{"source": 0}],
        "materials": [{"extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "specularGlossinessTexture": {"index": 0}}}}]
    });
    let upgraded = upgrade_json(&gltf);
    let notes: Vec<&str> = upgraded.report.iter().map(|n| &*n.text).collect();
    assert!(
        notes
            .iter()
            .any(|n| n.contains("left as spec-gloss") && n.contains("budget")),
        "{notes:?}"
    );
}

#[test]
fn a_preview_decodes_an_interlaced_png_whole_only_within_the_budget() {
    // A preview reduces a large PNG row by row, but an interlaced one is decoded whole: that
    // decode is held to the budget too, not to the reduced size the set was judged by.
    let mut png = png_header(16384);
    png[28] = 1; // IHDR's interlace method: Adam7
    let crc_at = 8 + 8 + 13;
    let crc = common::crc32(&png[12..crc_at]);
    png[crc_at..crc_at + 4].copy_from_slice(&crc.to_be_bytes());
    // The image is not decoded; its material is drawn without it and says why.
    let not_drawn = render_all(&textured(&[png])).unwrap();
    assert!(
        not_drawn
            .iter()
            .any(|n| n.contains("image 0") && n.contains("past 96 MiB, this input's budget")),
        "{not_drawn:?}"
    );
}

#[test]
fn a_texture_that_cannot_be_decoded_is_named_not_silently_dropped() {
    // Finding 18: a header claiming 60000² (past the decoder's limits), and a truncated one.
    // The material is never shown as if untextured without a word: the picture names the
    // slot and the image, and a comparison refuses the asset or calls the pair not evaluated.
    for png in [png_header(60000), png_header(4)] {
        let gltf = textured(&[png]);
        let not_drawn = render_all(&gltf).unwrap();
        assert!(
            not_drawn.iter().any(|n| n.contains("image 0")),
            "{not_drawn:?}"
        );
        let folder = tempfile::tempdir().unwrap();
        let path = folder.path().join("t.gltf");
        std::fs::write(&path, serde_json::to_vec(&gltf).unwrap()).unwrap();
        // A comparison needs every texel: an image past the budget refuses the asset from
        // its header; one that fails to decode leaves its material not evaluated.
        match gltfmat::compare(&path, &path, &gltfmat::CompareOptions::default()) {
            Err(e) => assert!(e.to_string().contains("image 0"), "{e}"),
            Ok(compared) => assert!(
                (compared.outcomes.iter()).all(|o| !o.not_evaluated.is_empty() && !o.same(1.0)),
                "{:?}",
                compared
                    .outcomes
                    .iter()
                    .map(|o| &o.not_evaluated)
                    .collect::<Vec<_>>()
            ),
        }
    }
}

#[test]
fn numeric_options_out_of_range_are_usage_errors() {
    // Finding 19.
    let asset = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/valid/sheen-triangle.gltf"
    );
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(args)
            .output()
            .unwrap()
    };
    for args in [
        vec!["compare", asset, asset, "--threshold", "nan"],
        vec!["compare", asset, asset, "--threshold=-1"],
        vec!["compare", asset, asset, "--grid", "5000"],
        vec!["render", asset, "--size", "0"],
        vec!["render", asset, "--size", "65536"],
    ] {
        let output = run(&args);
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        assert!(
            String::from_utf8_lossy(&output.stderr).contains("invalid value"),
            "{args:?}"
        );
    }
}

#[test]
fn sparse_accessors_are_checked_and_their_values_applied() {
    // Finding 17: a count of 2^32 over 8- and 16-byte views, misaligned parts, repeated and
    // out-of-range indices, and substituted values outside the declared bounds all passed.
    let words = |values: &[u16]| {
        values
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>()
    };
    let floats = |values: &[f32]| {
        values
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>()
    };
    let mut data = floats(&[0.0; 4]);
    data.extend(words(&[1, 1, 0, 9]));
    data.extend(floats(&[5.0, 6.0, 7.0, 8.0]));
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&data)
    );
    let sparse = |count: u64, offset: u64| {
        json!({"count": count, "indices": {"bufferView": 1, "componentType": 5123, "byteOffset": offset},
            "values": {"bufferView": 2, "byteOffset": 2 * offset}})
    };
    let gltf = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": uri, "byteLength": data.len()}],
        "bufferViews": [{"buffer": 0, "byteLength": 16}, {"buffer": 0, "byteOffset": 16, "byteLength": 8},
            {"buffer": 0, "byteOffset": 24, "byteLength": 16}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "SCALAR", "min": [0], "max": [0], "sparse": sparse(4, 0)},
            {"componentType": 5126, "count": 4, "type": "SCALAR", "sparse": sparse(1 << 32, 1)}
        ]
    });
    let report = check(&gltf, &every_issue());
    let found: Vec<(&str, &str)> = (report.diagnostics.iter())
        .map(|d| (d.code.name(), d.pointer().unwrap_or_default()))
        .collect();
    for expected in [
        (
            "ACCESSOR_SPARSE_COUNT_OUT_OF_RANGE",
            "/accessors/1/sparse/count",
        ),
        (
            "ACCESSOR_OFFSET_ALIGNMENT",
            "/accessors/1/sparse/indices/byteOffset",
        ),
        (
            "ACCESSOR_TOTAL_OFFSET_ALIGNMENT",
            "/accessors/1/sparse/values",
        ),
        ("ACCESSOR_TOO_LONG", "/accessors/1/sparse/indices"),
        ("ACCESSOR_TOO_LONG", "/accessors/1/sparse/values"),
        (
            "ACCESSOR_SPARSE_INDICES_NON_INCREASING",
            "/accessors/0/sparse",
        ),
        ("ACCESSOR_SPARSE_INDEX_OOB", "/accessors/0/sparse"),
        ("ACCESSOR_MAX_MISMATCH", "/accessors/0/max/0"),
    ] {
        assert!(found.contains(&expected), "{expected:?} in {found:?}");
    }
    assert_eq!(count(&report, "ACCESSOR_SPARSE_INDICES_NON_INCREASING"), 2);
}

#[test]
fn findings_below_the_lowest_kept_severity_are_counted_not_kept() {
    // The human report lists no infos: 10^5 unused materials must not be held to be counted.
    let n = 100_000;
    let materials: Vec<_> = (0..n).map(|_| json!({})).collect();
    let gltf = json!({"asset": {"version": "2.0"}, "materials": materials, "scene": 5});
    let all = check(&gltf, &every_issue());
    assert!(
        all.count(gltfmat::Severity::Info) >= n,
        "one UNUSED_OBJECT per material"
    );
    let lean = check(
        &gltf,
        &every_issue().with_lowest_kept(gltfmat::Severity::Warning),
    );
    for severity in gltfmat::Severity::ALL {
        assert_eq!(lean.count(severity), all.count(severity), "{severity}");
    }
    assert!(!lean.truncated);
    assert!(lean
        .diagnostics
        .iter()
        .all(|d| d.severity <= gltfmat::Severity::Warning));
    assert!(lean
        .diagnostics
        .iter()
        .any(|d| d.code == "UNRESOLVED_REFERENCE"));
}

#[test]
fn data_findings_past_those_kept_per_accessor_are_still_counted() {
    // 12 000 zero normals: each is ACCESSOR_VECTOR3_NON_UNIT. One walk lists at most 10 000; the
    // report still counts every one, and the last listed says how many more there are.
    let n = 12_000;
    let data = base64::engine::general_purpose::STANDARD.encode(vec![0u8; 12 * n]);
    let gltf = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": format!("data:application/octet-stream;base64,{data}"), "byteLength": 12 * n}],
        "bufferViews": [{"buffer": 0, "byteLength": 12 * n, "target": 34962},
            {"buffer": 0, "byteLength": 12 * n, "target": 34962}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "mode": 0}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0});
    let report = check(&gltf, &every_issue());
    assert_eq!(count(&report, "ACCESSOR_VECTOR3_NON_UNIT"), 10_000);
    assert_eq!(report.count(gltfmat::Severity::Error), n);
    let last = (report.diagnostics.iter())
        .rfind(|d| d.code == "ACCESSOR_VECTOR3_NON_UNIT")
        .unwrap();
    assert!(
        last.message
            .ends_with("(2000 more findings here are not listed.)"),
        "{}",
        last.message
    );
}

#[test]
fn accessors_aliasing_one_corrupt_view_keep_a_bounded_list_and_a_complete_count() {
    // 300 NORMAL accessors over the same 1000 zero vectors: 300 000 findings from a small
    // file. One data pass lists at most 100 000 of them; the report counts them all.
    let (accessors, elements) = (300, 1000);
    let data = base64::engine::general_purpose::STANDARD.encode(vec![0u8; 12 * elements]);
    let mut list = vec![
        json!({"bufferView": 0, "componentType": 5126, "count": elements, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]}),
    ];
    list.extend((0..accessors).map(
        |_| json!({"bufferView": 0, "componentType": 5126, "count": elements, "type": "VEC3"}),
    ));
    let primitives: Vec<_> = (1..=accessors)
        .map(|i| json!({"attributes": {"POSITION": 0, "NORMAL": i}, "mode": 0}))
        .collect();
    let gltf = json!({"asset": {"version": "2.0"},
        "buffers": [{"uri": format!("data:application/octet-stream;base64,{data}"), "byteLength": 12 * elements}],
        "bufferViews": [{"buffer": 0, "byteLength": 12 * elements, "byteStride": 12, "target": 34962}],
        "accessors": list, "meshes": [{"primitives": primitives}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0});
    let report = check(&gltf, &every_issue());
    let listed = count(&report, "ACCESSOR_VECTOR3_NON_UNIT");
    assert!((90_000..=100_000).contains(&listed), "{listed} listed");
    assert_eq!(report.count(gltfmat::Severity::Error), accessors * elements);
}

#[test]
fn crossed_strip_textures_rebake_on_a_grid_held_to_the_budget_not_their_product() {
    // A diffuse 2100×1 and a spec-gloss 1×2100: their finest grid holds 2100², more than the
    // largest input or 2048²; the rebake is held to 2048² texels and says so.
    let png = |width: u32, height: u32| {
        let image = image::GrayAlphaImage::from_pixel(width, height, image::LumaA([128, 255]));
        let mut bytes = Vec::new();
        image::DynamicImage::ImageLumaA8(image)
            .write_to(
                &mut std::io::Cursor::new(&mut bytes),
                image::ImageFormat::Png,
            )
            .unwrap();
        format!(
            "data:image/png;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&bytes)
        )
    };
    let gltf = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "images": [{"uri": png(2100, 1)}, {"uri": png(1, 2100)}],
        "textures": [{"source": 0}, {"source": 1}],
        "materials": [{"extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1}}}}]
    });
    let upgraded = upgrade_json(&gltf);
    let notes: Vec<&str> = upgraded.report.iter().map(|n| &*n.text).collect();
    let held = notes
        .iter()
        .find(|n| n.contains("the rebake's grid is"))
        .unwrap_or_else(|| panic!("{notes:?}"));
    assert!(held.contains("not the 2100×2100"), "{held}");
    let largest = upgraded
        .images
        .iter()
        .filter_map(|i| image::load_from_memory(&i.bytes).ok())
        .map(|i| u64::from(i.width()) * u64::from(i.height()))
        .max()
        .unwrap();
    assert!(largest <= 1 << 22, "{largest} texels");
}

/// `gltf` upgraded with no resources and the default options.
fn upgrade_json(gltf: &serde_json::Value) -> gltfmat::Upgraded {
    upgrade(
        serde_json::to_vec(gltf).unwrap(),
        &NoResources,
        &UpgradeOptions::default(),
    )
    .unwrap()
}
