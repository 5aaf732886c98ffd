//! Conformance against the Khronos glTF-Validator corpus (../shared/conformance): for each case,
//! `--profile khronos` must give the same multiset of (code, pointer or offset, severity) and
//! the same per-severity counts as the expected `.report.json`.
//!
//! The check-core folders must pass every case; the other folders are printed, not required.

use gltfmat::check::codes::{self, Origin};
use gltfmat::check::rules::SUPERSESSIONS;
use gltfmat::check::{check_bytes, CheckOptions, Location, Profile};
use gltfmat::document::uri::FolderResources;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

const REQUIRED: &[&str] = &[
    "base/data/json",
    "base/data/glb",
    "base/data/asset",
    "base/data/root",
    "base/data/buffer",
    "base/data/buffer_view",
    "base/data/accessor_data",
    "base/data/mesh_data",
    "base/data/animation_data",
    "base/data/skin_data",
    "base/data/mesh",
    "base/data/scene",
    "base/data/image",
    "base/data/texture",
    "base/data/sampler",
    "base/data/material",
    "ext/KHR_materials_anisotropy",
    "ext/KHR_materials_clearcoat",
    "ext/KHR_materials_dispersion",
    "ext/KHR_materials_emissive_strength",
    "ext/KHR_materials_ior",
    "ext/KHR_materials_iridescence",
    "ext/KHR_materials_pbrSpecularGlossiness",
    "ext/KHR_materials_sheen",
    "ext/KHR_materials_specular",
    "ext/KHR_materials_transmission",
    "ext/KHR_materials_unlit",
    "ext/KHR_materials_variants",
    "ext/KHR_materials_volume",
    "ext/KHR_texture_transform",
    "ext/EXT_texture_webp",
];

fn corpus() -> PathBuf {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/conformance/khronos-glTF-Validator/test");
    assert!(
        path.is_dir(),
        "\n\n*** ../shared/conformance is MISSING ({}).\n*** The conformance test needs the Khronos corpus beside the checkout.\n",
        path.display()
    );
    path
}

fn cases(folder: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![folder.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = entry.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.to_string_lossy().ends_with(".report.json") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

type Key = (String, String, u64);

fn expected(report: &Value) -> BTreeMap<Key, usize> {
    let mut map = BTreeMap::new();
    for m in report["issues"]["messages"].as_array().unwrap() {
        let location = m.get("pointer").map_or_else(
            || format!("@{}", m["offset"]),
            |p| p.as_str().unwrap().to_string(),
        );
        *map.entry((
            m["code"].as_str().unwrap().to_string(),
            location,
            m["severity"].as_u64().unwrap(),
        ))
        .or_insert(0) += 1;
    }
    map
}

fn asset_of(report_path: &Path) -> PathBuf {
    PathBuf::from(
        report_path
            .to_string_lossy()
            .trim_end_matches(".report.json"),
    )
}

/// The multiset of (code, location, severity) gltfmat reports for an asset.
fn diagnose(asset: &Path, profile: Profile) -> BTreeMap<Key, usize> {
    let options = CheckOptions {
        profile,
        ..Default::default()
    };
    let loader = FolderResources::new(asset.parent().unwrap());
    let report = check_bytes(
        &asset.to_string_lossy(),
        std::fs::read(asset).unwrap(),
        &loader,
        &options,
    );
    let mut found = BTreeMap::new();
    for d in &report.diagnostics {
        let location = match &d.location {
            Location::Pointer(p) => p.clone(),
            Location::Offset(o) => format!("@{o}"),
        };
        *found
            .entry((d.code.to_string(), location, d.severity as u64))
            .or_insert(0) += 1;
    }
    found
}

/// Runs one case; returns a description of the difference, or None when it matches.
fn run_case(report_path: &Path) -> Option<String> {
    let asset = asset_of(report_path);
    let expected_report: Value =
        serde_json::from_slice(&std::fs::read(report_path).unwrap()).unwrap();
    let actual = diagnose(&asset, Profile::Khronos);
    let want = expected(&expected_report);
    if want == actual {
        return None;
    }
    let missing: Vec<_> = want
        .iter()
        .filter(|(k, n)| actual.get(*k) != Some(n))
        .collect();
    let extra: Vec<_> = actual
        .iter()
        .filter(|(k, n)| want.get(*k) != Some(n))
        .collect();
    Some(format!(
        "{}\n    missing {missing:?}\n    extra   {extra:?}",
        asset.display()
    ))
}

#[test]
fn khronos_profile_matches_the_khronos_corpus() {
    let root = corpus();
    let mut folders: Vec<String> = Vec::new();
    for group in ["base/data", "ext"] {
        let mut names: Vec<String> = std::fs::read_dir(root.join(group))
            .unwrap()
            .flatten()
            .filter(|e| e.path().is_dir())
            .map(|e| format!("{group}/{}", e.file_name().to_string_lossy()))
            .collect();
        names.sort();
        folders.extend(names);
    }
    // CONFORMANCE_SHOW=base/data/mesh prints the differences of one report-only folder.
    let show_folder = std::env::var("CONFORMANCE_SHOW").ok();
    let mut required_failures = Vec::new();
    let (mut total_pass, mut total_fail) = (0, 0);
    for folder in &folders {
        let required = REQUIRED.contains(&folder.as_str());
        let (mut pass, mut fail) = (0, 0);
        for case in cases(&root.join(folder)) {
            match run_case(&case) {
                None => pass += 1,
                Some(diff) => {
                    fail += 1;
                    if required {
                        required_failures.push(diff);
                    } else if show_folder.as_deref() == Some(folder.as_str()) {
                        println!("{diff}");
                    }
                }
            }
        }
        total_pass += pass;
        total_fail += fail;
        let tag = if required { "required" } else { "report only" };
        println!("{folder:<45} {pass} passed, {fail} failed ({tag})");
    }
    println!("corpus total: {total_pass} passed, {total_fail} failed");
    assert!(
        required_failures.is_empty(),
        "required conformance cases differ:\n{}",
        required_failures.join("\n")
    );
}

fn all_folders(root: &Path) -> Vec<PathBuf> {
    ["base/data", "ext"]
        .iter()
        .flat_map(|group| std::fs::read_dir(root.join(group)).unwrap().flatten())
        .map(|e| e.path())
        .filter(|p| p.is_dir())
        .collect()
}

/// The default profile differs from the Khronos profile only by gltfmat's own rules and by
/// the documented supersessions; and on the corpus's valid assets (no expected error or
/// warning) gltfmat's rules stay silent. Every difference is printed.
#[test]
fn default_profile_differs_only_by_documented_rules() {
    let root = corpus();
    let mut undocumented = Vec::new();
    let mut noisy_on_valid = Vec::new();
    let mut differences = 0;
    for folder in all_folders(&root) {
        for report_path in cases(&folder) {
            let asset = asset_of(&report_path);
            let khronos = diagnose(&asset, Profile::Khronos);
            let default = diagnose(&asset, Profile::Default);
            let expected_report: Value =
                serde_json::from_slice(&std::fs::read(&report_path).unwrap()).unwrap();
            let valid = ["numErrors", "numWarnings"]
                .iter()
                .all(|k| expected_report["issues"][k].as_u64() == Some(0));
            let gltf1 = default.keys().any(|k| k.0 == "GLTF_1_0_ASSET");
            let keys: std::collections::BTreeSet<_> =
                khronos.keys().chain(default.keys()).collect();
            for key in keys {
                let (k, d) = (khronos.get(key), default.get(key));
                if k == d {
                    continue;
                }
                differences += 1;
                let code = key.0.as_str();
                let origin = codes::find(code).map(|i| i.origin);
                let why = if origin == Some(Origin::Gltfmat) {
                    if valid {
                        noisy_on_valid.push(format!("{}: {key:?}", asset.display()));
                    }
                    "gltfmat rule".to_string()
                } else if let Some((_, why)) = SUPERSESSIONS
                    .iter()
                    .find(|(c, _)| *c == code || (gltf1 && *c == "GLTF_1_0_ASSET"))
                {
                    format!("supersession: {why}")
                } else {
                    undocumented.push(format!(
                        "{}: {key:?} khronos={k:?} default={d:?}",
                        asset.display()
                    ));
                    "UNDOCUMENTED".to_string()
                };
                let rel = asset
                    .strip_prefix(&root)
                    .unwrap_or(&asset)
                    .display()
                    .to_string();
                println!(
                    "{rel}: {key:?} khronos×{} default×{} — {why}",
                    k.unwrap_or(&0),
                    d.unwrap_or(&0)
                );
            }
        }
    }
    println!("{differences} difference(s) between the default and Khronos profiles");
    assert!(
        undocumented.is_empty(),
        "undocumented differences:\n{}",
        undocumented.join("\n")
    );
    assert!(
        noisy_on_valid.is_empty(),
        "gltfmat rules fire on valid corpus assets:\n{}",
        noisy_on_valid.join("\n")
    );
}
