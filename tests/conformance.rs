//! Conformance against the Khronos glTF-Validator corpus (../shared/conformance): for each case,
//! `--profile khronos` must give the same multiset of (code, pointer or offset, severity) and
//! the same per-severity counts as the expected `.report.json`.
//!
//! Every case must match, except the known differences listed below with their reason;
//! each case listed by name must still differ, so that the list shrinks as gltfmat catches
//! up (in a listed folder, cases that already match are counted as passing).

mod common;
use common::shared;

use gltfmat::registry::{self, Origin};
use gltfmat::{check_bytes, CheckOptions, FolderResources, Place, Profile};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Cases (or whole folders) where gltfmat's report still differs from the Khronos one, and why.
const KNOWN_DIFFERENCES: &[(&str, &str)] = &[
    (
        "base/data/node/infinite_transform.gltf",
        "numbers beyond f64 (1e400) are INVALID_JSON here, VALUE_NOT_IN_RANGE in Khronos",
    ),
    (
        "base/data/camera/infinite_znear.gltf",
        "numbers beyond f64 (1e400) are INVALID_JSON here, VALUE_NOT_IN_RANGE in Khronos",
    ),
    (
        "base/data/skin/ignored_parent_transform.gltf",
        "release skew: the corpus comes from the build after 2.0.0-dev.3.10, where NODE_SKINNED_MESH_NON_ROOT is info and NODE_SKINNED_MESH_PARENT_TRANSFORMS new; --profile khronos follows the released validator users compare with",
    ),
    (
        "ext/KHR_node_visibility",
        "release skew: the corpus comes from the build after 2.0.0-dev.3.10, which knows KHR_node_visibility; the released validator reports it UNSUPPORTED_EXTENSION, and --profile khronos follows the release",
    ),
];

/// The listing a case falls under (its own name, or its folder's) and the reason.
fn known_difference(case: &str) -> Option<(&'static str, &'static str)> {
    KNOWN_DIFFERENCES
        .iter()
        .find(|(prefix, _)| case.starts_with(prefix))
        .copied()
}

fn corpus() -> Option<PathBuf> {
    shared("conformance/khronos-glTF-Validator/test", "conformance")
}

fn cases(folder: &Path) -> Vec<PathBuf> {
    files_below(folder, |p| p.to_string_lossy().ends_with(".report.json"))
}

/// Every file below `folder` that `keep` accepts, sorted.
fn files_below(folder: &Path, keep: impl Fn(&Path) -> bool) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![folder.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = entry.path();
            if p.is_dir() {
                stack.push(p);
            } else if keep(&p) {
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
    let options = CheckOptions::default().with_profile(profile);
    let loader = FolderResources::new(asset.parent().unwrap());
    let report = check_bytes(
        &asset.to_string_lossy(),
        std::fs::read(asset).unwrap(),
        &loader,
        &options,
    );
    let mut found = BTreeMap::new();
    for d in &report.diagnostics {
        let location = match d.location {
            Place::Pointer(p) => p.to_string(),
            Place::Offset(o) => format!("@{o}"),
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
    let Some(root) = corpus() else { return };
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
    let mut unexpected = Vec::new();
    let mut known_but_matching = Vec::new();
    let (mut total_pass, mut total_fail) = (0, 0);
    for folder in &folders {
        let (mut pass, mut fail) = (0, 0);
        for case in cases(&root.join(folder)) {
            let name = case
                .strip_prefix(&root)
                .unwrap_or(&case)
                .to_string_lossy()
                .trim_end_matches(".report.json")
                .to_string();
            match (run_case(&case), known_difference(&name)) {
                (None, None) => pass += 1,
                (None, Some((listed, _))) => {
                    pass += 1;
                    if !listed.ends_with('/') {
                        known_but_matching.push(name);
                    }
                }
                (Some(_), Some((_, why))) => {
                    fail += 1;
                    println!("known difference: {name} ({why})");
                }
                (Some(diff), None) => {
                    fail += 1;
                    unexpected.push(diff);
                }
            }
        }
        total_pass += pass;
        total_fail += fail;
        println!("{folder:<45} {pass} passed, {fail} known differences");
    }
    println!("corpus total: {total_pass} passed, {total_fail} known differences");
    assert!(
        unexpected.is_empty(),
        "conformance cases differ:\n{}",
        unexpected.join("\n")
    );
    assert!(
        known_but_matching.is_empty(),
        "these cases now match: take them off KNOWN_DIFFERENCES: {known_but_matching:?}"
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

/// gltfmat findings on corpus assets the Khronos validator calls valid, each a real problem
/// the Khronos validator does not look for: (asset below the corpus, code, pointer, why).
const REAL_PROBLEMS_IN_VALID_CORPUS_ASSETS: &[(&str, &str, &str, &str)] = &[
    (
        "ext/KHR_materials_variants/data/primitive/valid.gltf",
        "SHEEN_TEXTURE_DISABLED",
        "/materials/1/extensions/KHR_materials_sheen/sheenColorTexture",
        "the sheen object holds only a texture: multiplied by the default sheenColorFactor [0, 0, 0], the layer is off",
    ),
    (
        "ext/KHR_materials_transmission/data/material/valid.gltf",
        "TRANSMISSION_ON_METAL",
        "/materials/0/extensions/KHR_materials_transmission/transmissionFactor",
        METAL_BY_DEFAULT,
    ),
    (
        "ext/KHR_materials_specular/data/material/valid.gltf",
        "SPECULAR_ON_METAL",
        "/materials/0/extensions/KHR_materials_specular",
        METAL_BY_DEFAULT,
    ),
    (
        "ext/KHR_materials_specular/data/material/valid.gltf",
        "SPECULAR_ON_METAL",
        "/materials/1/extensions/KHR_materials_specular",
        METAL_BY_DEFAULT,
    ),
    (
        "ext/KHR_materials_ior/data/material/valid.gltf",
        "SPECULAR_ON_METAL",
        "/materials/0/extensions/KHR_materials_ior",
        METAL_BY_DEFAULT,
    ),
    (
        "ext/KHR_materials_ior/data/material/valid.gltf",
        "SPECULAR_ON_METAL",
        "/materials/1/extensions/KHR_materials_ior",
        METAL_BY_DEFAULT,
    ),
    (
        "ext/KHR_materials_ior/data/material/valid.gltf",
        "SPECULAR_ON_METAL",
        "/materials/2/extensions/KHR_materials_ior",
        METAL_BY_DEFAULT,
    ),
];

const METAL_BY_DEFAULT: &str = "no pbrMetallicRoughness: metallicFactor is its default 1, a metal, whose Fresnel the extension does not change";

/// The default profile differs from the Khronos profile only by gltfmat's own rules and by
/// the documented supersessions; and on the corpus's valid assets (no expected error or
/// warning) gltfmat's rules stay silent, except for the listed real problems. Every
/// difference is printed.
#[test]
fn default_profile_differs_only_by_documented_rules() {
    let Some(root) = corpus() else { return };
    let mut undocumented = Vec::new();
    let mut noisy_on_valid = Vec::new();
    let mut listed_found = std::collections::BTreeSet::new();
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
                let origin = registry::find(code).map(|i| i.origin);
                let rel = asset
                    .strip_prefix(&root)
                    .unwrap_or(&asset)
                    .display()
                    .to_string();
                let why = if origin == Some(Origin::Gltfmat) {
                    let listed = REAL_PROBLEMS_IN_VALID_CORPUS_ASSETS
                        .iter()
                        .find(|(a, c, p, _)| rel.ends_with(a) && *c == code && *p == key.1);
                    match (valid, listed) {
                        (true, Some(entry)) => {
                            listed_found.insert((entry.0, entry.2));
                        }
                        (true, None) => noisy_on_valid.push(format!("{rel}: {key:?}")),
                        (false, _) => {}
                    }
                    "gltfmat rule".to_string()
                } else if let Some(why) = registry::supersession(code).or_else(|| {
                    gltf1
                        .then(|| registry::supersession("GLTF_1_0_ASSET"))
                        .flatten()
                }) {
                    format!("supersession: {why}")
                } else {
                    undocumented.push(format!(
                        "{}: {key:?} khronos={k:?} default={d:?}",
                        asset.display()
                    ));
                    "UNDOCUMENTED".to_string()
                };
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
    let gone: Vec<_> = REAL_PROBLEMS_IN_VALID_CORPUS_ASSETS
        .iter()
        .filter(|entry| !listed_found.contains(&(entry.0, entry.2)))
        .collect();
    assert!(
        gone.is_empty(),
        "listed real problems no longer found: {gone:?}"
    );
}

/// Real exporters' files (../shared/real-world/gltf2) whose released-validator report
/// (2.0.0-dev.3.10, the npm package users compare with) gltfmat does not reproduce, and why.
const REAL_WORLD_DIFFERENCES: &[(&str, &str)] = &[];

#[test]
fn khronos_profile_matches_the_released_validator_on_real_exporters_files() {
    let Some(root) = shared("real-world/gltf2", "real-world parity") else {
        return;
    };
    let list = std::fs::read_to_string(root.join("list.txt")).unwrap();
    let mut unexpected = Vec::new();
    let mut listed_but_matching = Vec::new();
    let mut matching = 0;
    for name in list.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let report = root.join(format!("{name}.report.json"));
        let known = REAL_WORLD_DIFFERENCES.iter().any(|(case, _)| *case == name);
        match (run_case(&report), known) {
            (None, false) => matching += 1,
            (None, true) => listed_but_matching.push(name.to_string()),
            (Some(difference), false) => unexpected.push(difference),
            (Some(_), true) => {}
        }
    }
    assert!(
        unexpected.is_empty(),
        "{} real-world files differ from the released validator:\n{}",
        unexpected.len(),
        unexpected.join("\n")
    );
    assert!(
        listed_but_matching.is_empty(),
        "listed as different but now matching (remove them from the list): {listed_but_matching:?}"
    );
    assert!(matching > 100, "only {matching} real-world files compared");
}

/// Real skinned 1.0 assets (COLLADA2GLTF's CesiumMan, Monster, RiggedFigure, RiggedSimple in
/// every variant): all but RiggedSimple store weights that sum to as little as 0.18, and each
/// upgrades, its weights renormalised where needed, to an asset that passes the output check.
#[test]
fn real_skinned_gltf1_assets_upgrade_with_renormalised_weights() {
    let Some(models) = shared("real-world/gltf1/sample-models", "real skinned 1.0 assets") else {
        return;
    };
    let (mut upgraded, mut renormalised_count) = (0, 0);
    for model in ["CesiumMan", "Monster", "RiggedFigure", "RiggedSimple"] {
        for path in assets_below(&models.join(model)) {
            let bytes = std::fs::read(&path).unwrap();
            let loader = FolderResources::beside(&path);
            let result = gltfmat::upgrade(&bytes, &loader, &gltfmat::UpgradeOptions::default())
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let renormalised = result
                .report
                .iter()
                .any(|n| n.text.starts_with("skin weights renormalised"));
            renormalised_count += usize::from(renormalised);
            let files = gltfmat::upgrade_output::layout(&result, "out.glb");
            let report = gltfmat::upgrade_output::verify(&files);
            assert!(
                !report.has_errors(),
                "{}: {:?}",
                path.display(),
                report.diagnostics.first()
            );
            upgraded += 1;
        }
    }
    assert!(upgraded >= 16, "{upgraded} assets");
    // CesiumMan, Monster and RiggedFigure (12 inputs) were refused before renormalising.
    assert!(
        renormalised_count >= 12,
        "{renormalised_count} renormalised"
    );
}

fn assets_below(folder: &Path) -> Vec<PathBuf> {
    files_below(folder, |p| {
        let extension = p.extension().and_then(|e| e.to_str()).unwrap_or_default();
        extension.eq_ignore_ascii_case("gltf") || extension.eq_ignore_ascii_case("glb")
    })
}
