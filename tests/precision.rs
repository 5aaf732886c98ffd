//! The default profile is precise on files real exporters wrote: every finding `check` makes on
//! ../shared/real-world/gltf2 (default profile, and with `--deep`) is listed in
//! tests/expected/real-world-findings.tsv with the reason it is a real problem. A finding not
//! listed fails the test, and so does a listed one no longer found: the list is the complete
//! expectation, not an allowance.

mod common;
use common::shared;

use gltfmat::{check_bytes, CheckOptions, FolderResources, Place};
use std::collections::BTreeMap;
use std::path::Path;

const EXPECTATION: &str = include_str!("expected/real-world-findings.tsv");

/// (file below real-world/gltf2, code, pointer or @offset) → how many times.
type Findings = BTreeMap<(String, String, String), usize>;

/// The listed findings for a run with or without `--deep`, each entry's reason checked to be
/// there.
fn listed(deep: bool) -> Findings {
    let mut findings = Findings::new();
    for (number, line) in EXPECTATION.lines().enumerate() {
        if line.starts_with('#') || line.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split('\t').collect();
        let [file, code, location, when, why] = fields[..] else {
            panic!(
                "line {}: expected 5 tab-separated fields: {line}",
                number + 1
            );
        };
        assert!(
            why.trim().len() > 10,
            "line {}: no reason given: {line}",
            number + 1
        );
        let applies = match when {
            "always" => true,
            "deep" => deep,
            "shallow" => !deep,
            other => panic!("line {}: unknown 'when' {other}", number + 1),
        };
        if applies {
            *findings
                .entry((file.into(), code.into(), location.into()))
                .or_default() += 1;
        }
    }
    findings
}

fn found(root: &Path, deep: bool) -> Findings {
    let list = std::fs::read_to_string(root.join("list.txt")).unwrap();
    let options = CheckOptions::default().with_deep(deep);
    let mut findings = Findings::new();
    for name in list.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let path = root.join(name);
        let loader = FolderResources::beside(&path);
        let bytes = std::fs::read(&path).unwrap();
        let report = check_bytes(name, bytes, &loader, &options);
        for d in &report.diagnostics {
            let location = match d.location {
                Place::Pointer(p) => p.to_string(),
                Place::Offset(o) => format!("@{o}"),
            };
            *findings
                .entry((name.to_string(), d.code.to_string(), location))
                .or_default() += 1;
        }
    }
    findings
}

/// What one side has more of than the other, one line per entry.
fn surplus(more: &Findings, less: &Findings) -> Vec<String> {
    more.iter()
        .filter(|(key, n)| less.get(*key).unwrap_or(&0) < n)
        .map(|((file, code, at), n)| format!("{file}\t{code}\t{at}\t×{n}"))
        .collect()
}

fn compare(deep: bool) {
    let Some(root) = shared("real-world/gltf2", "default-profile precision") else {
        return;
    };
    let (expected, actual) = (listed(deep), found(&root, deep));
    let unlisted = surplus(&actual, &expected);
    let gone = surplus(&expected, &actual);
    assert!(
        unlisted.is_empty() && gone.is_empty(),
        "--deep {deep}: {} finding(s) not in tests/expected/real-world-findings.tsv (each needs a reason it is a real problem, or is a false positive to fix):\n{}\n\n{} listed finding(s) no longer made (take them off the list):\n{}",
        unlisted.len(),
        unlisted.join("\n"),
        gone.len(),
        gone.join("\n")
    );
    let total: usize = actual.values().sum();
    assert!(
        total > 500,
        "only {total} findings: is the corpus complete?"
    );
    println!("--deep {deep}: {total} findings, each listed with its reason");
}

#[test]
fn every_default_profile_finding_on_real_exporters_files_is_listed_with_its_reason() {
    compare(false);
}

#[test]
fn every_deep_finding_on_real_exporters_files_is_listed_with_its_reason() {
    compare(true);
}

/// The Khronos sample models (CesiumMan, RiggedSimple, RiggedFigure, Monster, VC … as
/// ../shared/real-world keeps them, in glTF 1.0) upgraded to 2.0 GLBs: with and without
/// `--deep`, the default profile reports nothing of its own on them, only what the Khronos
/// profile reports (skinned meshes under transformed ancestors, textures, animations: a
/// false report here fails well-made assets).
#[test]
fn the_default_profile_adds_nothing_on_the_khronos_sample_models_upgraded() {
    use gltfmat::NoResources;
    use gltfmat::Profile;
    use gltfmat::{upgrade, UpgradeOptions};
    let Some(root) = shared("real-world/gltf1/sample-models", "sample-model precision") else {
        return;
    };
    let mut models = 0;
    for model in std::fs::read_dir(&root).unwrap() {
        let folder = model.unwrap().path().join("glTF");
        let Some(source) = (std::fs::read_dir(&folder).into_iter().flatten())
            .filter_map(Result::ok)
            .map(|e| e.path())
            .find(|p| p.extension().is_some_and(|e| e == "gltf"))
        else {
            continue;
        };
        let bytes = std::fs::read(&source).unwrap();
        let loader = FolderResources::beside(&source);
        let Ok(upgraded) = upgrade(&bytes, &loader, &UpgradeOptions::default()) else {
            continue;
        };
        let glb = upgraded.to_glb();
        for deep in [false, true] {
            let findings = |profile| {
                let options = CheckOptions::default()
                    .with_deep(deep)
                    .with_profile(profile);
                let report = check_bytes("model.glb", glb.clone(), &NoResources, &options);
                let mut codes: Vec<String> = (report.diagnostics.iter())
                    .map(|d| format!("{} {:?}", d.code, d.location))
                    .collect();
                codes.sort();
                codes
            };
            let (default, khronos) = (findings(Profile::Default), findings(Profile::Khronos));
            let own: Vec<&String> = default.iter().filter(|f| !khronos.contains(f)).collect();
            assert!(
                own.is_empty(),
                "{} (--deep {deep}): {own:?}",
                source.display()
            );
        }
        models += 1;
    }
    assert!(models >= 10, "only {models} sample models upgraded");
}
