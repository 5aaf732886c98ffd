//! The `gltfmat` binary, end to end, on the bundled fixtures.

mod common;
use common::gltfmat;

use std::path::Path;
use std::process::Command;

#[test]
fn a_valid_asset_passes_in_both_containers() {
    for file in [
        "fixtures/valid/sheen-triangle.gltf",
        "fixtures/valid/sheen-triangle.glb",
    ] {
        let (code, out) = gltfmat(&["check", file]);
        assert_eq!(code, 0, "{file}: {out}");
        assert!(out.contains("0 error(s), 0 warning(s)"), "{out}");
    }
}

#[test]
fn hostile_inputs_get_a_diagnostic_and_exit_1() {
    let cases = [
        (
            "fixtures/broken/truncated.glb",
            "GLB_UNEXPECTED_END_OF_CHUNK_DATA",
        ),
        ("fixtures/broken/claims-4gib.glb", "GLB_CHUNK_TOO_BIG"),
        ("fixtures/broken/deep-nesting.gltf", "INVALID_JSON"),
        (
            "fixtures/broken/parent-dir-uri.gltf",
            "URI_OUTSIDE_ASSET_FOLDER",
        ),
        (
            "fixtures/broken/absolute-uri.gltf",
            "URI_OUTSIDE_ASSET_FOLDER",
        ),
        ("fixtures/broken/bad-material.gltf", "VALUE_NOT_IN_RANGE"),
    ];
    for (file, expected) in cases {
        let (code, out) = gltfmat(&["check", file]);
        assert_eq!(code, 1, "{file}: {out}");
        assert!(
            out.contains(expected),
            "{file} should report {expected}:\n{out}"
        );
    }
}

#[test]
fn khronos_profile_words_a_refused_path_as_io_error() {
    let (code, out) = gltfmat(&[
        "check",
        "--profile",
        "khronos",
        "fixtures/broken/parent-dir-uri.gltf",
    ]);
    assert_eq!(code, 1);
    assert!(
        out.contains("IO_ERROR") && !out.contains("URI_OUTSIDE_ASSET_FOLDER"),
        "{out}"
    );
}

#[test]
fn human_output_has_line_col_and_a_snippet() {
    let (code, out) = gltfmat(&["check", "fixtures/broken/duplicate-key.gltf"]);
    assert_eq!(code, 0, "a duplicate key is a warning: {out}");
    assert!(
        out.contains("fixtures/broken/duplicate-key.gltf:41:7: warning[JSON_DUPLICATE_KEY]"),
        "{out}"
    );
    assert!(
        out.contains("\"doubleSided\": false"),
        "snippet missing: {out}"
    );
}

#[test]
fn json_output_is_a_khronos_report() {
    let (_, out) = gltfmat(&[
        "check",
        "--format",
        "json",
        "fixtures/broken/bad-material.gltf",
    ]);
    let report: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(report["mimeType"], "model/gltf+json");
    assert_eq!(report["issues"]["numErrors"], 2);
    let pointers: Vec<&str> = report["issues"]["messages"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|m| m["pointer"].as_str())
        .collect();
    assert!(
        pointers.contains(&"/materials/0/extensions/KHR_materials_sheen/sheenRoughnessFactor"),
        "{pointers:?}"
    );
}

#[test]
fn json_is_an_object_for_one_file_argument_and_an_array_for_a_folder_or_several() {
    let json_of = |args: &[&str]| {
        let (_, out) = gltfmat(&[&["check", "--format", "json"], args].concat());
        serde_json::from_str::<serde_json::Value>(&out).unwrap()
    };
    let one_file = json_of(&["fixtures/valid/sheen-triangle.gltf"]);
    assert_eq!(one_file["mimeType"], "model/gltf+json", "{one_file}");

    let files = [
        "fixtures/valid/sheen-triangle.gltf",
        "fixtures/broken/truncated.glb",
    ];
    assert_eq!(json_of(&files).as_array().map(Vec::len), Some(2));

    // The shape must not depend on how many assets a folder happened to hold.
    let folder = tempfile::tempdir().unwrap();
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join(files[0]),
        folder.path().join("only.gltf"),
    )
    .unwrap();
    let walked = json_of(&[folder.path().to_str().unwrap()]);
    assert_eq!(walked.as_array().map(Vec::len), Some(1), "{walked}");

    let (_, out) = gltfmat(&["check", "--format", "jsonl", files[0], files[1]]);
    assert_eq!(out.lines().count(), 2);
    assert!(out
        .lines()
        .all(|l| serde_json::from_str::<serde_json::Value>(l).is_ok()));
}

#[test]
fn sarif_and_github_formats() {
    let (_, out) = gltfmat(&[
        "check",
        "--format",
        "sarif",
        "fixtures/broken/bad-material.gltf",
    ]);
    let log: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(log["version"], "2.1.0");
    let result = &log["runs"][0]["results"][0];
    assert!(
        result["locations"][0]["physicalLocation"]["region"]["startLine"]
            .as_u64()
            .is_some()
    );
    let (_, out) = gltfmat(&[
        "check",
        "--format",
        "github",
        "fixtures/broken/bad-material.gltf",
    ]);
    assert!(
        out.lines()
            .all(|l| l.starts_with("::error file=fixtures/broken/bad-material.gltf,line=")),
        "{out}"
    );
}

#[test]
fn options_filter_and_override() {
    let file = "fixtures/broken/bad-material.gltf";
    let (code, out) = gltfmat(&[
        "check",
        "--ignore",
        "UNRESOLVED_REFERENCE",
        "--severity",
        "VALUE_NOT_IN_RANGE=warning",
        file,
    ]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("warning[VALUE_NOT_IN_RANGE]") && !out.contains("UNRESOLVED_REFERENCE"),
        "{out}"
    );
    let (_, out) = gltfmat(&["check", "--format", "json", "--max-issues", "1", file]);
    let report: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(report["issues"]["truncated"], true);
    assert_eq!(report["issues"]["messages"].as_array().unwrap().len(), 1);
}

/// A resource that cannot be read is named in its IO_ERROR, with the reason: a folder the
/// operating system refuses to read as a file, a name no file can hold.
#[test]
fn an_unreadable_resource_is_named_with_the_reason() {
    let folder = tempfile::tempdir().unwrap();
    std::fs::create_dir(folder.path().join("data")).unwrap();
    let asset = folder.path().join("a.gltf");
    let text = r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"data","byteLength":4}],
        "images":[{"uri":"x%00.png"}]}"#;
    std::fs::write(&asset, text).unwrap();
    let (code, out) = gltfmat(&["check", asset.to_str().unwrap()]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.contains("Could not read resource: data: not a regular file (a folder)."),
        "{out}"
    );
    assert!(
        out.contains("Could not read resource 'x%00.png': it decodes to a NUL byte"),
        "{out}"
    );
}

#[test]
fn an_asset_without_materials_is_said_to_have_none_when_drawn_or_compared() {
    let folder = tempfile::tempdir().unwrap();
    let asset = folder.path().join("bare.gltf");
    std::fs::write(&asset, r#"{"asset":{"version":"2.0"},"meshes":[]}"#).unwrap();
    let asset = asset.to_str().unwrap();
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(args)
            .current_dir(folder.path())
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let (code, stderr) = run(&["render", asset, "--all"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("has no materials to render"), "{stderr}");
    let (code, stderr) = run(&["compare", asset, asset]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("an asset without materials"), "{stderr}");
}

#[test]
fn usage_errors_exit_2() {
    assert_eq!(gltfmat(&["check", "fixtures/no-such-file.gltf"]).0, 2);
    assert_eq!(
        gltfmat(&["check", "--ignore", "NOT_A_CODE", "fixtures/valid"]).0,
        2
    );
    // An output folder that is not there is named before anything is converted.
    let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(["upgrade", "fixtures/gltf1/pbr-mr-textured-fraunhofer.gltf"])
        .args(["-o", "fixtures/no-such-folder/out.glb"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("the output folder fixtures/no-such-folder does not exist"),
        "{stderr}"
    );
}

#[test]
fn a_folder_is_walked_and_fails_on_one_broken_asset() {
    let (code, out) = gltfmat(&["check", "fixtures"]);
    assert_eq!(code, 1);
    // A file with nothing to list prints nothing; one with findings its summary; the run
    // one total line.
    assert!(out.contains("fixtures/broken/truncated.glb:"), "{out}");
    assert!(!out.contains("fixtures/valid/sheen-triangle.glb:"), "{out}");
    assert!(
        out.lines().last().unwrap().contains("file(s) checked"),
        "{out}"
    );
    let (_, verbose) = gltfmat(&["check", "fixtures", "--verbose"]);
    assert!(
        verbose.contains("fixtures/valid/sheen-triangle.glb:"),
        "{verbose}"
    );
    // A folder of clean files is one line.
    let clean = tempfile::tempdir().unwrap();
    for name in ["a.gltf", "b.gltf", "c.gltf"] {
        std::fs::copy(
            "fixtures/valid/sheen-triangle.gltf",
            clean.path().join(name),
        )
        .unwrap();
    }
    let (code, out) = gltfmat(&["check", clean.path().to_str().unwrap()]);
    assert_eq!(code, 0, "{out}");
    assert_eq!(out.lines().count(), 1, "{out}");
}

#[test]
fn rules_lists_every_code_once_and_explain_shows_docs() {
    let (code, out) = gltfmat(&["rules"]);
    assert_eq!(code, 0);
    // A line per code, its description wrapped beneath it (indented), within 100 columns.
    assert!(out.lines().all(|l| l.chars().count() <= 100), "{out}");
    let codes: Vec<&str> = (out.lines())
        .filter(|l| !l.starts_with(' '))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    let unique: std::collections::HashSet<_> = codes.iter().collect();
    assert_eq!(codes.len(), unique.len());
    assert!(codes.contains(&"JSON_DUPLICATE_KEY") && codes.contains(&"GLB_INVALID_MAGIC"));
    let (code, out) = gltfmat(&["explain", "URI_OUTSIDE_ASSET_FOLDER"]);
    assert_eq!(code, 0);
    assert!(out.contains("## Why"), "{out}");
    // A Khronos code the default profile reports differently says so.
    let (code, out) = gltfmat(&["explain", "UNUSED_MESH_TANGENT"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("In gltfmat's default profile: Not reported on anisotropy"),
        "{out}"
    );
}

/// Names in capitals joined by underscores that the docs use and that are not codes: GL enums,
/// vertex attributes, environment variables, a 1.0 extension named in capitals and one table of
/// the source.
const DOC_NAMES_NOT_CODES: &[&str] = &[
    "CLAMP_TO_EDGE",
    "MIRRORED_REPEAT",
    "CULL_FACE",
    "SRC_ALPHA",
    "ONE_MINUS_SRC_ALPHA",
    "COLOR_0",
    "TEXCOORD_0",
    "TEXCOORD_1",
    "NO_COLOR",
    "CLICOLOR_FORCE",
    "FORCE_COLOR",
    "CARGO_INCREMENTAL",
    "GLTFMAT_SHARED",
    "CESIUM_RTC",
    "TEXTURE_SLOTS",
];

#[test]
fn the_docs_name_only_codes_that_exist() {
    let (code, out) = gltfmat(&["rules", "--format", "json"]);
    assert_eq!(code, 0, "{out}");
    let rules: Vec<serde_json::Value> = serde_json::from_str(&out).unwrap();
    let codes: std::collections::HashSet<&str> =
        rules.iter().map(|r| r["code"].as_str().unwrap()).collect();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages = vec![root.join("README.md"), root.join("ARCHITECTURE.md")];
    for entry in std::fs::read_dir(root.join("docs")).unwrap() {
        pages.push(entry.unwrap().path());
    }
    let mut unknown = Vec::new();
    for page in pages
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
    {
        let text = std::fs::read_to_string(page).unwrap();
        let words = text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'));
        for word in words {
            let code_shaped = word.contains('_')
                && word.starts_with(|c: char| c.is_ascii_uppercase())
                && !word.ends_with('_')
                && word
                    .chars()
                    .all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_');
            if code_shaped && !codes.contains(word) && !DOC_NAMES_NOT_CODES.contains(&word) {
                unknown.push(format!("{}: {word}", page.display()));
            }
        }
    }
    assert!(
        unknown.is_empty(),
        "names in the docs that are no code of `gltfmat rules` (rename them, or list a \
         non-code name in DOC_NAMES_NOT_CODES): {unknown:?}"
    );
}

#[test]
fn lut_sheen_writes_the_table_the_evaluator_uses() {
    let (code, out) = gltfmat(&["lut", "sheen", "--size", "4", "--visibility", "ashikhmin"]);
    assert_eq!(code, 0, "{out}");
    let rows: Vec<Vec<f64>> = out
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 4);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), 4);
        for (j, value) in row.iter().enumerate() {
            let (mu, roughness) = ((j as f64 + 0.5) / 4.0, (i as f64 + 0.5) / 4.0);
            let exact =
                gltfmat::SheenTable::albedo(gltfmat::SheenVisibility::Ashikhmin, mu, roughness);
            assert!(
                (value - exact).abs() < 1e-6,
                "E({mu}, {roughness}) = {value} vs {exact}"
            );
        }
    }
}

#[test]
fn sarif_output_validates_against_the_sarif_2_1_0_schema() {
    let schema: serde_json::Value = serde_json::from_slice(
        &std::fs::read(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("fixtures/sarif/sarif-2.1.0.schema.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let validator = jsonschema::options()
        .should_validate_formats(true)
        .build(&schema)
        .expect("the SARIF schema compiles");
    let (code, out) = gltfmat(&[
        "check",
        "--format",
        "sarif",
        "fixtures/broken/bad-material.gltf",
        "fixtures/broken/duplicate-key.gltf",
        "fixtures/valid/sheen-triangle.glb",
    ]);
    assert_eq!(code, 1, "{out}");
    let sarif: serde_json::Value = serde_json::from_str(&out).expect("SARIF is JSON");
    let errors: Vec<String> = validator
        .iter_errors(&sarif)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect();
    assert!(
        errors.is_empty(),
        "SARIF schema violations:\n{}",
        errors.join("\n")
    );
    assert!(sarif["runs"][0]["results"]
        .as_array()
        .is_some_and(|r| !r.is_empty()));
}

#[test]
fn render_compare_heatmap_and_lut_png_write_readable_images() {
    let dir = std::env::temp_dir().join(format!("gltfmat-cli-images-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let (code, out) = gltfmat(&[
        "render",
        "fixtures/valid/sheen-triangle.gltf",
        "--size",
        "64",
        "-o",
        &path("ball.png"),
    ]);
    assert_eq!(code, 0, "{out}");
    let (code, out) = gltfmat(&[
        "compare",
        "fixtures/valid/sheen-triangle.gltf",
        "fixtures/valid/sheen-triangle.glb",
        "--grid",
        "16",
        "--heatmap",
        &path("heat.png"),
    ]);
    assert_eq!(code, 0, "the same material in both containers: {out}");
    let (code, out) = gltfmat(&[
        "lut",
        "sheen",
        "--size",
        "4",
        "--format",
        "png",
        "-o",
        &path("lut.png"),
    ]);
    assert_eq!(code, 0, "{out}");
    for (name, size) in [("ball.png", 64), ("heat.png", 16), ("lut.png", 4)] {
        let image = image::open(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((image.width(), image.height()), (size, size), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `check` of a fixture with warnings, with `env` set (and nothing else of the caller's
/// colour settings): whether its output holds ANSI colour.
fn coloured(args: &[&str], env: &[(&str, &str)]) -> bool {
    let mut command = Command::new(env!("CARGO_BIN_EXE_gltfmat"));
    command
        .args(["check", "fixtures/broken/duplicate-key.gltf"])
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"));
    for name in [
        "NO_COLOR",
        "CLICOLOR",
        "CLICOLOR_FORCE",
        "FORCE_COLOR",
        "TERM",
        "CI",
    ] {
        command.env_remove(name);
    }
    command.envs(env.iter().copied());
    let out = command.output().expect("gltfmat runs");
    String::from_utf8_lossy(&out.stdout).contains("\x1b[")
}

#[test]
fn colour_follows_the_conventions_and_color_overrides_them() {
    // Piped output is plain unless forced.
    assert!(!coloured(&[], &[]));
    assert!(!coloured(&[], &[("NO_COLOR", "")]));
    assert!(coloured(&[], &[("CLICOLOR_FORCE", "1")]));
    assert!(coloured(&[], &[("FORCE_COLOR", "1")]));
    assert!(!coloured(&[], &[("FORCE_COLOR", "0")]));
    // NO_COLOR, when not empty, wins over the forcing variables; --color over everything.
    assert!(!coloured(
        &[],
        &[("CLICOLOR_FORCE", "1"), ("NO_COLOR", "1")]
    ));
    assert!(!coloured(&[], &[("FORCE_COLOR", "1"), ("NO_COLOR", "1")]));
    assert!(coloured(&["--color", "always"], &[("NO_COLOR", "1")]));
    assert!(!coloured(&["--color", "never"], &[("CLICOLOR_FORCE", "1")]));
}

#[test]
fn each_file_is_checked_with_the_nearest_gltfmat_toml_above_it() {
    let root = tempfile::tempdir().unwrap();
    let asset = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/broken/duplicate-key.gltf"),
    )
    .unwrap();
    for folder in ["quiet", "loud"] {
        std::fs::create_dir(root.path().join(folder)).unwrap();
        std::fs::write(root.path().join(folder).join("a.gltf"), &asset).unwrap();
    }
    std::fs::write(
        root.path().join("quiet/gltfmat.toml"),
        "ignore = [\"JSON_DUPLICATE_KEY\"]\n",
    )
    .unwrap();
    let gltfmat = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(args)
            .current_dir(root.path())
            .output()
            .unwrap()
    };
    let out = gltfmat(&["check", "quiet", "loud", "--format", "jsonl"]);
    let reports: Vec<serde_json::Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let duplicate_keys = |report: &serde_json::Value| {
        (report["issues"]["messages"].as_array().unwrap().iter())
            .filter(|m| m["code"] == "JSON_DUPLICATE_KEY")
            .count()
    };
    assert_eq!(reports.len(), 2);
    assert_eq!(
        duplicate_keys(&reports[0]),
        0,
        "quiet/gltfmat.toml applies to quiet/a.gltf"
    );
    assert_eq!(duplicate_keys(&reports[1]), 1, "and not to loud/a.gltf");

    // A gate over uploads reads none: the upload's own gltfmat.toml silences nothing.
    let isolated = gltfmat(&["check", "quiet", "--format", "jsonl", "--isolated"]);
    let report: serde_json::Value = serde_json::from_slice(&isolated.stdout).unwrap();
    assert_eq!(
        duplicate_keys(&report),
        1,
        "--isolated reads no gltfmat.toml"
    );

    // A config that is not TOML (a planted link to a secret, say) is named by line and
    // column, its text never printed.
    std::fs::write(
        root.path().join("loud/gltfmat.toml"),
        "ignore = []\ntoken s3cr3t\n",
    )
    .unwrap();
    let refused = gltfmat(&["check", "loud"]);
    let said = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{said}");
    assert!(said.contains("gltfmat.toml: line 2, column 7"), "{said}");
    assert!(!said.contains("s3cr3t"), "{said}");
}

#[test]
fn sarif_shows_well_in_code_scanning() {
    let root = tempfile::tempdir().unwrap();
    let folder = root.path().join("we,ird:dir");
    std::fs::create_dir(&folder).unwrap();
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    std::fs::copy(
        fixtures.join("broken/bad-material.gltf"),
        folder.join("a 100%.gltf"),
    )
    .unwrap();
    std::fs::copy(
        fixtures.join("broken/duplicate-key.gltf"),
        folder.join("b.glb.gltf"),
    )
    .unwrap();
    let glb = std::fs::read(fixtures.join("valid/sheen-triangle.glb")).unwrap();
    // A valid GLB still has infos and hints: those are placed by byte in the file.
    std::fs::write(root.path().join("t.glb"), &glb).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(["check", "--format", "sarif", "we,ird:dir", "t.glb"])
        .current_dir(root.path())
        .output()
        .unwrap();
    let log: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let run = &log["runs"][0];
    // Headings are sentences, not message templates; help says more than the heading.
    for rule in run["tool"]["driver"]["rules"].as_array().unwrap() {
        let heading = rule["shortDescription"]["text"].as_str().unwrap();
        assert!(!heading.contains('%'), "{}: {heading}", rule["id"]);
        assert_ne!(
            rule["help"]["text"].as_str().unwrap(),
            heading,
            "{}",
            rule["id"]
        );
    }
    assert!(run["tool"]["driver"]["informationUri"]
        .as_str()
        .is_none_or(|u| !u.contains("OWNER")));
    let base = run["originalUriBaseIds"]["%SRCROOT%"]["uri"]
        .as_str()
        .unwrap();
    assert!(
        base.starts_with("file:///") && base.ends_with('/'),
        "{base}"
    );
    let results = run["results"].as_array().unwrap();
    assert!(!results.is_empty());
    let mut fingerprints = std::collections::HashSet::new();
    for result in results {
        let location = &result["locations"][0]["physicalLocation"];
        assert_eq!(location["artifactLocation"]["uriBaseId"], "%SRCROOT%");
        let uri = location["artifactLocation"]["uri"].as_str().unwrap();
        assert!(
            [
                "we%2Cird%3Adir/a%20100%25.gltf",
                "we%2Cird%3Adir/b.glb.gltf",
                "t.glb"
            ]
            .contains(&uri),
            "{uri}"
        );
        let fingerprint = result["partialFingerprints"]["gltfmat/v2"]
            .as_str()
            .unwrap();
        fingerprints.insert((
            uri.to_string(),
            fingerprint.to_string(),
            result["ruleId"].to_string(),
        ));
        if uri == "t.glb" {
            assert!(
                location["region"]["byteOffset"].as_u64().is_some(),
                "{location}"
            );
            assert_eq!(location["region"]["startLine"], 1, "{location}");
        } else {
            assert!(
                location["region"]["startLine"].as_u64().is_some(),
                "{location}"
            );
        }
    }
    assert!(results
        .iter()
        .any(|r| r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "t.glb"));
    // An unrelated line inserted above every finding moves them, not their fingerprints.
    let fingerprints_of = |log: &serde_json::Value| -> Vec<(String, String)> {
        let mut found: Vec<_> = (log["runs"][0]["results"].as_array().unwrap().iter())
            .map(|r| {
                (
                    r["ruleId"].to_string(),
                    r["partialFingerprints"]["gltfmat/v2"].to_string(),
                )
            })
            .collect();
        found.sort();
        found
    };
    let sarif_of = |file: &str| -> serde_json::Value {
        let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["check", "--format", "sarif", file])
            .current_dir(root.path())
            .output()
            .unwrap();
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let before = sarif_of("we,ird:dir/a 100%.gltf");
    let text = std::fs::read_to_string(folder.join("a 100%.gltf")).unwrap();
    std::fs::write(folder.join("a 100%.gltf"), format!("\n\n{text}")).unwrap();
    let after = sarif_of("we,ird:dir/a 100%.gltf");
    let line = |log: &serde_json::Value| {
        log["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["region"]["startLine"]
            .as_u64()
    };
    assert_eq!(line(&after), line(&before).map(|l| l + 2));
    assert_eq!(fingerprints_of(&before), fingerprints_of(&after));
    // Two findings share a fingerprint only when they share file, code and place.
    assert!(
        fingerprints.len() * 10 >= results.len() * 9,
        "{} of {}",
        fingerprints.len(),
        results.len()
    );
}

#[test]
fn fail_on_sets_the_least_severity_that_fails() {
    // duplicate-key.gltf has a warning and no error.
    let fixture = "fixtures/broken/duplicate-key.gltf";
    assert_eq!(gltfmat(&["check", fixture]).0, 0);
    assert_eq!(gltfmat(&["check", "--fail-on", "warning", fixture]).0, 1);
    assert_eq!(
        gltfmat(&[
            "check",
            "--fail-on",
            "never",
            "fixtures/broken/bad-material.gltf"
        ])
        .0,
        0
    );
    assert_eq!(
        gltfmat(&[
            "check",
            "--fail-on",
            "error",
            "fixtures/broken/bad-material.gltf"
        ])
        .0,
        1
    );
}

#[test]
fn stdin_filename_names_the_input_and_finds_its_resources() {
    // sheen-triangle.gltf with its buffer moved out of the data URI into a.bin.
    let folder = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/valid/sheen-triangle.gltf"),
    )
    .unwrap();
    let mut document: serde_json::Value = serde_json::from_str(&text).unwrap();
    let uri = document["buffers"][0]["uri"].as_str().unwrap().to_string();
    let data = base64::Engine::decode(
        &base64::engine::general_purpose::STANDARD,
        uri.split(',').nth(1).unwrap(),
    )
    .unwrap();
    let data_length = data.len() as u64;
    std::fs::write(folder.path().join("a.bin"), data).unwrap();
    document["buffers"][0]["uri"] = "a.bin".into();
    let name = folder.path().join("a.gltf");
    let name = name.to_str().unwrap();
    let run = |args: &[&str]| {
        let mut child = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(args)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        use std::io::Write;
        child
            .stdin
            .take()
            .unwrap()
            .write_all(document.to_string().as_bytes())
            .unwrap();
        let out = child.wait_with_output().unwrap();
        let report = serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap();
        (report, String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (named, notes) = run(&["check", "--format", "json", "--stdin-filename", name, "-"]);
    assert_eq!(named["uri"], name);
    assert_eq!(named["issues"]["numErrors"], 0, "{named}");
    let read = &named["info"]["resources"][0];
    assert_eq!(
        (&read["storage"], &read["byteLength"]),
        (&"external".into(), &data_length.into())
    );
    assert_eq!(notes, "");
    // Without a name there is no folder: the finding says what was not checked.
    let (anonymous, _) = run(&["check", "--format", "json", "-"]);
    assert_eq!(anonymous["uri"], "-");
    let messages = anonymous["issues"]["messages"].as_array().unwrap();
    assert!(
        messages
            .iter()
            .any(|m| m["code"] == "EXTERNAL_RESOURCE_NOT_READ" && m["pointer"] == "/buffers/0/uri"),
        "{anonymous}"
    );
}

#[test]
fn rules_as_json_completions_and_the_manual_page() {
    let (code, out) = gltfmat(&["rules", "--format", "json"]);
    assert_eq!(code, 0);
    let rules: Vec<serde_json::Value> = serde_json::from_str(&out).unwrap();
    let plausibility = rules
        .iter()
        .find(|r| r["code"] == "PBR_BASE_COLOR_RANGE")
        .unwrap();
    assert_eq!(plausibility["optIn"], true);
    assert!(rules
        .iter()
        .all(|r| r["description"].as_str().is_some_and(|d| !d.contains('%'))));
    let (code, out) = gltfmat(&["completions", "bash"]);
    assert_eq!(code, 0);
    assert!(out.contains("--enable-group"), "{out}");
    let (code, out) = gltfmat(&["man"]);
    assert_eq!(code, 0);
    assert!(
        out.starts_with(".ie") && out.contains(".TH gltfmat 1"),
        "{out}"
    );
}

/// A glTF 2.0 asset of `count` spec-gloss materials, each named, all alike.
fn alike_spec_gloss_materials(count: usize) -> String {
    let material = |i: usize| {
        serde_json::json!({"name": format!("m{i}"), "extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseFactor": [0.5, 0.4, 0.3, 1.0], "specularFactor": [0.1, 0.1, 0.1], "glossinessFactor": 0.6}}})
    };
    serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "materials": (0..count).map(material).collect::<Vec<_>>(),
    })
    .to_string()
}

#[test]
fn alike_notes_and_proofs_make_one_line_naming_where_they_apply() {
    let folder = tempfile::tempdir().unwrap();
    let input = folder.path().join("alike.gltf");
    std::fs::write(&input, alike_spec_gloss_materials(500)).unwrap();
    let output = folder.path().join("out.gltf");
    let (code, out) = gltfmat(&[
        "upgrade",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
        "--no-verify",
    ]);
    assert_eq!(code, 0, "{out}");
    let decisions: Vec<&str> = out.lines().filter(|l| l.starts_with("decision")).collect();
    // Two decisions per material, each the same for all 500: two lines, not 1,000.
    assert_eq!(decisions.len(), 2, "{out}");
    let first = "/materials/0/extensions/KHR_materials_pbrSpecularGlossiness";
    assert!(
        decisions
            .iter()
            .all(|l| l.contains(first) && l.contains(" and 497 more ")),
        "{out}"
    );
    // The proof compares the 500 alike pairs once, and says so in one line.
    let (code, out) = gltfmat(&[
        "upgrade",
        input.to_str().unwrap(),
        "-o",
        output.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(code, 0, "{out}");
    let proofs: Vec<&str> = out.lines().filter(|l| l.starts_with("proof:")).collect();
    assert_eq!(proofs.len(), 1, "{out}");
    assert!(
        proofs[0].starts_with("proof: material 0 (m0) ↔ 0 (m0), material 1 (m1)")
            && proofs[0].contains(" and 497 more: same: "),
        "{out}"
    );
}

#[test]
fn a_reader_that_goes_away_ends_no_command_in_a_panic() {
    let folder = tempfile::tempdir().unwrap();
    let input = folder.path().join("alike.gltf");
    // Named materials: one proof line each, far more than a pipe holds.
    std::fs::write(&input, alike_spec_gloss_materials(3000)).unwrap();
    let output = folder.path().join("out.glb");
    let mut child = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(["upgrade", input.to_str().unwrap(), "-o"])
        .arg(&output)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // `| head -0`: the reader is gone before the first line.
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(output.is_file(), "the upgrade still writes its output");
}

#[test]
fn a_2_0_input_with_errors_of_its_own_is_written_saying_so_and_refused_with_strict() {
    let folder = tempfile::tempdir().unwrap();
    let input = folder.path().join("broken.gltf");
    // A spec-gloss material to convert, and a node whose mesh does not exist: an error the
    // upgrade passes through.
    let asset = r#"{"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "materials": [{"extensions": {"KHR_materials_pbrSpecularGlossiness": {"glossinessFactor": 0.5}}}],
        "nodes": [{"mesh": 7}], "scenes": [{"nodes": [0]}], "scene": 0}"#;
    std::fs::write(&input, asset).unwrap();
    let output = folder.path().join("out.glb");
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["upgrade", input.to_str().unwrap(), "-o"])
            .arg(&output)
            .args(extra)
            .output()
            .unwrap()
    };
    let out = run(&[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("the input has 1 error(s) of its own"),
        "{stdout}"
    );
    assert!(output.exists());
    std::fs::remove_file(&output).unwrap();
    let out = run(&["--strict"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("glTF 2.0 with 1 error(s) of its own"),
        "{stderr}"
    );
    assert!(!output.exists());
}

/// GitHub code scanning's documented rules for an uploaded SARIF, over every real exporter's
/// file and the Khronos corpus: every result placed in a file has a `startLine`, no two
/// results share a fingerprint, and files inside the repository are named relative to it.
#[test]
fn sarif_of_whole_corpora_meets_github_code_scanning_rules() {
    for (relative, name) in [
        ("real-world/gltf2", "sarif_real_world"),
        (
            "conformance/khronos-glTF-Validator/test",
            "sarif_conformance",
        ),
    ] {
        let Some(folder) = common::shared(relative, name) else {
            continue;
        };
        let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["check", "--format", "sarif", "--all-findings"])
            .arg(&folder)
            .current_dir(folder.parent().unwrap())
            .output()
            .unwrap();
        let log: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let results = log["runs"][0]["results"].as_array().unwrap();
        assert!(results.len() > 100, "{relative}: {} results", results.len());
        let mut fingerprints = std::collections::HashSet::new();
        for result in results {
            let location = &result["locations"][0]["physicalLocation"];
            assert!(
                location["region"]["startLine"]
                    .as_u64()
                    .is_some_and(|l| l >= 1),
                "{relative}: no startLine: {result}"
            );
            assert_eq!(
                location["artifactLocation"]["uriBaseId"], "%SRCROOT%",
                "{result}"
            );
            let uri = location["artifactLocation"]["uri"].as_str().unwrap();
            assert!(!uri.starts_with("..") && !uri.starts_with('/'), "{uri}");
            let fingerprint = (uri.to_string(), result["partialFingerprints"].to_string());
            assert!(
                fingerprints.insert(fingerprint),
                "{relative}: a shared fingerprint: {result}"
            );
        }
    }
}

/// `--format github` annotates errors and warnings (infos and hints only with
/// `--all-findings`), at most ten per file, and counts the rest in one notice: GitHub shows
/// ten annotations of a kind per step, and the errors must be among them.
#[test]
fn github_annotations_are_the_errors_first_and_bounded_per_file() {
    let folder = tempfile::tempdir().unwrap();
    let nodes: Vec<_> = (0..30)
        .map(|_| serde_json::json!({"rotation": [1, 1, 1, 1]}))
        .collect();
    let asset = serde_json::json!({"asset": {"version": "2.0"}, "nodes": nodes});
    std::fs::write(folder.path().join("n.gltf"), asset.to_string()).unwrap();
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["check", "--format", "github", "n.gltf"])
            .args(extra)
            .current_dir(folder.path())
            .output()
            .unwrap();
        String::from_utf8(out.stdout).unwrap()
    };
    let out = run(&[]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 11, "{out}");
    assert!(
        lines[..10]
            .iter()
            .all(|l| l.starts_with("::error file=n.gltf")),
        "{out}"
    );
    assert!(
        lines[10].starts_with(
            "::notice file=n.gltf::20 more finding(s) not annotated (20 error(s), 0 warning(s))"
        ),
        "{out}"
    );
    // With --all-findings the infos count too, still after the errors.
    let out = run(&["--all-findings"]);
    assert!(
        out.lines().take(10).all(|l| l.starts_with("::error")),
        "{out}"
    );
    assert!(
        out.contains("more finding(s) not annotated (20 error(s)"),
        "{out}"
    );
}

/// An asset with 2,098 findings of one code prints a few of them and one line counting the
/// rest; `--all-findings` prints every one.
#[test]
fn many_findings_of_one_code_are_grouped_in_human_output() {
    use base64::Engine;
    let n = 2098;
    let mut bytes: Vec<u8> = (0..n).flat_map(|_| 1f32.to_le_bytes()).collect();
    bytes.extend(vec![0u8; 12 * n]);
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    );
    let asset = serde_json::json!({"asset": {"version": "2.0"}, "nodes": [{}],
        "buffers": [{"uri": uri, "byteLength": bytes.len()}],
        "bufferViews": [{"buffer": 0, "byteLength": 4 * n}, {"buffer": 0, "byteOffset": 4 * n, "byteLength": 12 * n}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "SCALAR", "min": [1], "max": [1]},
                      {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"}],
        "animations": [{"channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
                        "samplers": [{"input": 0, "output": 1}]}],
        "scenes": [{"nodes": [0]}], "scene": 0});
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("anim.gltf");
    std::fs::write(&path, serde_json::to_string_pretty(&asset).unwrap()).unwrap();
    let run = |extra: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["check", "--color", "never"])
            .arg(&path)
            .args(extra)
            .output()
            .unwrap();
        String::from_utf8(out.stdout).unwrap()
    };
    let out = run(&[]);
    assert!(out.lines().count() < 50, "{} lines", out.lines().count());
    assert!(
        out.contains("2094 more ACCESSOR_ANIMATION_INPUT_NON_INCREASING finding(s)"),
        "{out}"
    );
    let all = run(&["--all-findings"]);
    let listed = all
        .matches("error[ACCESSOR_ANIMATION_INPUT_NON_INCREASING]")
        .count();
    assert_eq!(listed, n - 1, "every one with --all-findings");
}

/// The README's Actions recipe as the action runs it, from the repository's root:
/// `--exclude assets/third-party/` leaves that folder out of `check assets/`.
#[test]
fn the_readme_actions_recipe_excludes_what_it_says() {
    let repository = tempfile::tempdir().unwrap();
    let root = repository.path();
    std::fs::create_dir(root.join(".git")).unwrap();
    for (folder, fixture) in [
        ("assets/third-party", "broken/bad-material.gltf"),
        ("assets/mine", "valid/sheen-triangle.gltf"),
    ] {
        std::fs::create_dir_all(root.join(folder)).unwrap();
        let from = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fixtures")
            .join(fixture);
        std::fs::copy(from, root.join(folder).join("a.gltf")).unwrap();
    }
    let run = |format: &str| {
        Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["check", "--quiet", "--format", format])
            .args(["--exclude", "assets/third-party/", "assets/"])
            .current_dir(root)
            .output()
            .unwrap()
    };
    let sarif = run("sarif");
    assert_eq!(
        sarif.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&sarif.stderr)
    );
    let text = String::from_utf8(sarif.stdout).unwrap();
    assert!(!text.contains("third-party"), "{text}");
    let github = run("github");
    assert_eq!(github.status.code(), Some(0));
    assert!(!String::from_utf8_lossy(&github.stdout).contains("third-party"));
}

/// `asset` (a glTF 2.0 JSON with one material, `material`) written into `dir` as `name`.
fn one_material(dir: &Path, name: &str, material: serde_json::Value, images: serde_json::Value) {
    let mut asset = serde_json::json!({"asset": {"version": "2.0"}, "materials": [material]});
    if let Some(images) = images.as_array().filter(|i| !i.is_empty()) {
        asset["images"] = images.clone().into();
        asset["textures"] = (0..images.len())
            .map(|i| serde_json::json!({"source": i}))
            .collect();
    }
    let used: Vec<String> = (material_extensions(&asset["materials"][0]).into_iter()).collect();
    if !used.is_empty() {
        asset["extensionsUsed"] = used.into();
    }
    std::fs::write(dir.join(name), asset.to_string()).unwrap();
}

fn material_extensions(material: &serde_json::Value) -> Vec<String> {
    (material["extensions"].as_object().into_iter())
        .flat_map(|e| e.keys().cloned())
        .collect()
}

/// A data URI of a 2×2 PNG of one colour.
fn png_uri(texel: [u8; 3]) -> String {
    use base64::Engine;
    let image = image::RgbImage::from_pixel(2, 2, image::Rgb(texel));
    let mut png = Vec::new();
    (image::DynamicImage::ImageRgb8(image))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(png)
    )
}

/// The pairs a viewer draws differently that a slice of the material called the same: each
/// is DIFFERENT, named by the input that dominates it, and each layer renders a different
/// ball. An extension the evaluator does not model is NOT EVALUATED, never the same.
#[test]
fn compare_tells_every_layer_of_a_material_apart_and_names_it() {
    let dir = std::env::temp_dir().join(format!("gltfmat-layers-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let grey = serde_json::json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0],
        "metallicFactor": 0.0, "roughnessFactor": 0.5}});
    let with = |extra: serde_json::Value| {
        let mut m = grey.clone();
        for (key, value) in extra.as_object().into_iter().flatten() {
            m[key] = value.clone();
        }
        m
    };
    one_material(&dir, "grey.gltf", grey.clone(), serde_json::json!([]));
    let mut blended = with(serde_json::json!({"alphaMode": "BLEND"}));
    blended["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.2.into();
    let pairs = [
        ("blend", "coverage", blended, None),
        (
            "emission",
            "emission",
            with(serde_json::json!({"emissiveFactor": [1.0, 1.0, 1.0],
                "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 10.0}}})),
            None,
        ),
        (
            "normal",
            "normal",
            with(serde_json::json!({"normalTexture": {"index": 0}})),
            Some([230, 128, 180]),
        ),
        (
            "clearcoat",
            "clearcoat",
            with(serde_json::json!({"extensions": {"KHR_materials_clearcoat":
                {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}})),
            None,
        ),
        (
            "transmission",
            "transmission",
            with(
                serde_json::json!({"extensions": {"KHR_materials_transmission":
                {"transmissionFactor": 1.0}}}),
            ),
            None,
        ),
        (
            "occlusion",
            "occlusion",
            with(serde_json::json!({"occlusionTexture": {"index": 0}})),
            Some([40, 40, 40]),
        ),
        (
            "iridescence",
            "iridescence",
            with(
                serde_json::json!({"extensions": {"KHR_materials_iridescence":
                {"iridescenceFactor": 1.0}}}),
            ),
            None,
        ),
    ];
    let render = |name: &str| {
        let out = dir.join(format!("{name}.png"));
        let (code, text) = gltfmat(&[
            "render",
            dir.join(format!("{name}.gltf")).to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--size",
            "32",
            "--force",
        ]);
        assert_eq!(code, 0, "{text}");
        image::open(out).unwrap().to_rgb8()
    };
    let plain = render("grey");
    for (name, input, material, texel) in pairs {
        let images = match texel {
            Some(texel) => serde_json::json!([{"uri": png_uri(texel)}]),
            None => serde_json::json!([]),
        };
        one_material(&dir, &format!("{name}.gltf"), material, images);
        let (code, text) = gltfmat(&[
            "compare",
            dir.join("grey.gltf").to_str().unwrap(),
            dir.join(format!("{name}.gltf")).to_str().unwrap(),
        ]);
        assert_eq!(code, 1, "{name}: {text}");
        assert!(
            text.contains("DIFFERENT") && text.contains(&format!("(mostly {input})")),
            "{name}: {text}"
        );
        assert_ne!(render(name), plain, "{name} renders like the plain ball");
    }
    // Dispersion is not modelled (its fringes need a structured background): not evaluated,
    // exit 1, even against itself, and render says what it left out.
    let dispersive = with(serde_json::json!({"extensions": {
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_volume": {"thicknessFactor": 1.0},
        "KHR_materials_dispersion": {"dispersion": 5.0}}}));
    one_material(&dir, "dispersive.gltf", dispersive, serde_json::json!([]));
    let (code, text) = gltfmat(&[
        "compare",
        dir.join("dispersive.gltf").to_str().unwrap(),
        dir.join("dispersive.gltf").to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("NOT EVALUATED (first: KHR_materials_dispersion"),
        "{text}"
    );
    let (code, text) = gltfmat(&[
        "render",
        dir.join("dispersive.gltf").to_str().unwrap(),
        "-o",
        dir.join("dispersive.png").to_str().unwrap(),
        "--force",
        "--size",
        "16",
    ]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("not drawn: KHR_materials_dispersion"),
        "{text}"
    );
    // An image the evaluator cannot decode leaves its material not evaluated, not the asset.
    let ktx2 =
        with(serde_json::json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}));
    one_material(
        &dir,
        "ktx2.gltf",
        ktx2,
        serde_json::json!([{"uri": "data:image/ktx2;base64,q0tUWCAyMLsNChoK"}]),
    );
    let (code, text) = gltfmat(&[
        "compare",
        dir.join("grey.gltf").to_str().unwrap(),
        dir.join("ktx2.gltf").to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("NOT EVALUATED (second: baseColorTexture"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_shards_of_a_walk_cover_every_file_exactly_once() {
    let uris = |args: &[&str]| -> Vec<String> {
        let (_, out) = gltfmat(&[&["check", "fixtures", "--format", "jsonl"], args].concat());
        (out.lines())
            .map(|line| {
                serde_json::from_str::<serde_json::Value>(line).unwrap()["uri"]
                    .as_str()
                    .unwrap()
                    .to_string()
            })
            .collect()
    };
    let whole = uris(&[]);
    assert!(whole.len() >= 10, "{whole:?}");
    for n in [2, 3, 5] {
        let mut union: Vec<String> = (1..=n)
            .flat_map(|k| uris(&["--shard", &format!("{k}/{n}")]))
            .collect();
        assert!((1..=n).all(|k| uris(&["--shard", &format!("{k}/{n}")]).len() < whole.len()));
        union.sort();
        let mut expected = whole.clone();
        expected.sort();
        assert_eq!(union, expected, "{n} shards");
    }
    let (status, _) = gltfmat(&["check", "fixtures", "--shard", "4/3"]);
    assert_eq!(status, 2);
}

#[test]
fn man_writes_one_page_per_subcommand_and_replaces_none_without_force() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().to_str().unwrap();
    let (status, _) = gltfmat(&["man", "--dir", folder]);
    assert_eq!(status, 0);
    for sub in [
        "check", "upgrade", "render", "compare", "report", "rules", "explain",
    ] {
        let page = std::fs::read_to_string(dir.path().join(format!("gltfmat-{sub}.1"))).unwrap();
        assert!(
            page.contains(&format!("gltfmat\\-{sub}")),
            "{sub}'s page names itself"
        );
    }
    let check = std::fs::read_to_string(dir.path().join("gltfmat-check.1")).unwrap();
    assert!(
        check.contains("shard") && check.contains("exclude"),
        "options documented"
    );
    let main = std::fs::read_to_string(dir.path().join("gltfmat.1")).unwrap();
    assert!(
        main.contains("gltfmat\\-check(1)"),
        "the main page names the subcommands' pages"
    );
    let (status, _) = gltfmat(&["man", "--dir", folder]);
    assert_eq!(status, 2, "existing pages are not replaced without --force");
    let (status, _) = gltfmat(&["man", "--dir", folder, "--force"]);
    assert_eq!(status, 0);
}

/// On a real terminal (util-linux `script`), a folder check's screen holds the report's lines
/// whole: the progress bar is not drawn into them. With the report sent to a file, the bar may
/// show on the terminal, and the file holds no trace of it.
#[test]
fn the_progress_bar_never_breaks_a_report_line() {
    if Command::new("script").arg("--version").output().is_err() {
        eprintln!("SKIPPED LOUDLY: util-linux `script` is needed for a real terminal");
        assert!(std::env::var_os("CI").is_none(), "script is missing in CI");
        return;
    }
    let exe = env!("CARGO_BIN_EXE_gltfmat");
    let on_screen = |command: String| -> String {
        let out = Command::new("script")
            .args(["-qec", &command, "/dev/null"])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .env_remove("CI")
            .output()
            .expect("script runs");
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let screen = on_screen(format!("{exe} check fixtures --color never"));
    assert!(
        screen.contains("error[") && screen.lines().count() > 5,
        "{screen}"
    );
    for line in screen.split("\r\n") {
        assert!(
            !line.contains('\r') && !line.contains('\x1b'),
            "a line broken by a redraw: {line:?}"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("report.txt");
    on_screen(format!(
        "{exe} check fixtures --color never > {}",
        file.display()
    ));
    let report = std::fs::read_to_string(&file).unwrap();
    assert!(report.contains("error[") && !report.contains('\r') && !report.contains('\x1b'));
}

#[test]
fn explain_puts_every_code_in_words() {
    let (_, listed) = gltfmat(&["rules", "--format", "json"]);
    let rules: Vec<serde_json::Value> = serde_json::from_str(&listed).unwrap();
    assert!(rules.len() > 190);
    for rule in &rules {
        let code = rule["code"].as_str().unwrap();
        let (status, text) = gltfmat(&["explain", code]);
        assert_eq!(status, 0, "{code}");
        assert!(!regex_like_placeholder(&text), "{code}: {text}");
        assert!(text.lines().count() >= 3, "{code}: {text}");
    }
}

/// A message template's placeholder: `%` and a digit or a lower-case letter.
fn regex_like_placeholder(text: &str) -> bool {
    text.as_bytes()
        .windows(2)
        .any(|w| w[0] == b'%' && (w[1].is_ascii_digit() || w[1].is_ascii_lowercase()))
}

/// One triangle whose two texCoord sets read different parts of a texture split red | blue,
/// drawn with `material`.
fn two_set_triangle(dir: &Path, name: &str, material: serde_json::Value) {
    use base64::Engine;
    let mut data = Vec::new();
    let floats: [&[f32]; 3] = [
        &[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], // POSITION
        &[0.0, 0.0, 1.0, 0.0, 0.0, 1.0],                // TEXCOORD_0: the red half, mostly
        &[1.0, 1.0, 0.6, 1.0, 1.0, 0.6],                // TEXCOORD_1: the blue half only
    ];
    for values in floats {
        values.iter().for_each(|v| data.extend(v.to_le_bytes()));
    }
    let texture = image::RgbImage::from_fn(4, 4, |x, _| {
        image::Rgb(if x < 2 { [200, 30, 30] } else { [30, 60, 220] })
    });
    let mut png = Vec::new();
    (image::DynamicImage::ImageRgb8(texture))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let base64 = |bytes: &[u8]| base64::engine::general_purpose::STANDARD.encode(bytes);
    let asset = serde_json::json!({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2}, "material": 0}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 24},
            {"buffer": 0, "byteOffset": 60, "byteLength": 24}],
        "buffers": [{"byteLength": data.len(), "uri": format!("data:application/octet-stream;base64,{}", base64(&data))}],
        "images": [{"uri": format!("data:image/png;base64,{}", base64(&png))}],
        "textures": [{"source": 0}],
        "materials": [material]
    });
    std::fs::write(dir.join(name), asset.to_string()).unwrap();
}

/// A texture read through texCoord 1 instead of 0 is a different picture wherever the mesh's
/// sets differ: compare reads each slot through its own set at points on the mesh, says where,
/// and still calls the same material the same.
#[test]
fn compare_reads_each_texture_through_its_own_texcoord_set_on_the_mesh() {
    let dir = std::env::temp_dir().join(format!("gltfmat-texcoords-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let through = |set: u32| {
        serde_json::json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": set},
            "metallicFactor": 0.0, "roughnessFactor": 0.5}})
    };
    two_set_triangle(&dir, "set0.gltf", through(0));
    two_set_triangle(&dir, "set1.gltf", through(1));
    two_set_triangle(&dir, "set0-again.gltf", through(0));
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (code, text) = gltfmat(&["compare", &path("set0.gltf"), &path("set1.gltf")]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("DIFFERENT")
            && text.contains("(mostly base colour)")
            && text.contains("on the mesh, TEXCOORD_1"),
        "{text}"
    );
    let (code, text) = gltfmat(&["compare", &path("set0.gltf"), &path("set0-again.gltf")]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("same: ΔE2000 max 0.0000"), "{text}");
    // TEXCOORD_1 without a bufferView (zeros, as compressed data reads before decoding): the
    // mesh cannot be read, so texCoord 1 is not evaluated, never called the same.
    let unread = std::fs::read_to_string(dir.join("set1.gltf")).unwrap();
    let mut unread: serde_json::Value = serde_json::from_str(&unread).unwrap();
    unread["accessors"][2]
        .as_object_mut()
        .unwrap()
        .remove("bufferView");
    std::fs::write(dir.join("unread.gltf"), unread.to_string()).unwrap();
    let (code, text) = gltfmat(&["compare", &path("set0.gltf"), &path("unread.gltf")]);
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("NOT EVALUATED") && text.contains("texCoord sets on the mesh"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A triangle at `uvs` (TEXCOORD_0) drawn with a base colour texture whose lower half is red
/// or, `changed`, blue; without a mesh when `uvs` is None.
fn half_changed_asset(dir: &Path, name: &str, uvs: Option<[f32; 6]>, changed: bool) {
    use base64::Engine;
    let base64 = |bytes: &[u8]| base64::engine::general_purpose::STANDARD.encode(bytes);
    let texture = image::RgbImage::from_fn(16, 16, |_, y| match (y < 8, changed) {
        (true, _) => image::Rgb([200, 200, 40]),
        (false, false) => image::Rgb([200, 30, 30]),
        (false, true) => image::Rgb([30, 60, 220]),
    });
    let mut png = Vec::new();
    (image::DynamicImage::ImageRgb8(texture))
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let mut asset = serde_json::json!({
        "asset": {"version": "2.0"},
        "images": [{"uri": format!("data:image/png;base64,{}", base64(&png))}],
        "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
            "metallicFactor": 0.0, "roughnessFactor": 0.5}}]
    });
    if let Some(uvs) = uvs {
        let mut data = Vec::new();
        let position = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        for v in position.iter().chain(&uvs) {
            data.extend(v.to_le_bytes());
        }
        let more = serde_json::json!({
            "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
            "bufferViews": [
                {"buffer": 0, "byteOffset": 0, "byteLength": 36},
                {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
            "buffers": [{"byteLength": data.len(), "uri": format!("data:application/octet-stream;base64,{}", base64(&data))}]
        });
        asset
            .as_object_mut()
            .unwrap()
            .extend(more.as_object().unwrap().clone());
    }
    std::fs::write(dir.join(name), asset.to_string()).unwrap();
}

/// `compare` looks where a viewer can look: on the second asset's mesh. A texture changed only
/// where no triangle reads it renders the same; changed under the triangles, DIFFERENT; with
/// no mesh, the whole UV square is compared, and each says which it sampled.
#[test]
fn compare_samples_the_grid_where_the_second_assets_mesh_lies() {
    let folder = tempfile::tempdir().unwrap();
    let dir = folder.path();
    let upper = [0.1, 0.05, 0.9, 0.05, 0.5, 0.4];
    let lower = [0.1, 0.7, 0.9, 0.7, 0.5, 0.95];
    half_changed_asset(dir, "lower.gltf", Some(lower), false);
    half_changed_asset(dir, "upper-changed.gltf", Some(upper), true);
    half_changed_asset(dir, "lower-changed.gltf", Some(lower), true);
    half_changed_asset(dir, "no-mesh-changed.gltf", None, true);
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let compare = |b: &str| gltfmat(&["compare", &path("lower.gltf"), &path(b)]);
    // The first asset's mesh lies on the changed half: the second's is the one looked at.
    let (code, text) = compare("upper-changed.gltf");
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("same: ΔE2000 max 0.0000")
            && text.contains("texel centres and corners on the mesh ("),
        "{text}"
    );
    let (code, text) = compare("lower-changed.gltf");
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("DIFFERENT") && text.contains("on the mesh"),
        "{text}"
    );
    let (code, text) = compare("no-mesh-changed.gltf");
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("DIFFERENT") && text.contains("over the whole UV square (no mesh draws it)"),
        "{text}"
    );
    // A mesh without texture coordinates places nothing; a material without textures has
    // nothing to place.
    let edit = |from: &str, to: &str, change: &dyn Fn(&mut serde_json::Value)| {
        let mut asset: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join(from)).unwrap()).unwrap();
        change(&mut asset);
        std::fs::write(dir.join(to), asset.to_string()).unwrap();
    };
    edit("lower-changed.gltf", "no-uvs.gltf", &|asset| {
        let attributes = &mut asset["meshes"][0]["primitives"][0]["attributes"];
        attributes.as_object_mut().unwrap().remove("TEXCOORD_0");
    });
    let (_, text) = compare("no-uvs.gltf");
    assert!(
        text.contains("over the whole UV square (a texture is read through a texCoord set its mesh does not have)"),
        "{text}"
    );
    edit("no-uvs.gltf", "untextured.gltf", &|asset| {
        asset["materials"][0]["pbrMetallicRoughness"]
            .as_object_mut()
            .unwrap()
            .remove("baseColorTexture");
    });
    let (code, text) = gltfmat(&[
        "compare",
        &path("untextured.gltf"),
        &path("untextured.gltf"),
    ]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("over the whole UV square (neither material reads a texture)"),
        "{text}"
    );
    let (_, json) = gltfmat(&[
        "compare",
        &path("lower.gltf"),
        &path("upper-changed.gltf"),
        "--format",
        "json",
    ]);
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    let outcome = &json[0];
    assert_eq!(outcome["area"]["on"], "mesh", "{json}");
    let texels = outcome["area"]["texels"].as_u64().unwrap();
    assert!(texels > 0 && texels < 16 * 8, "{texels}");
    assert!(outcome["offMesh"].as_u64().unwrap() > 16 * 8, "{json}");
}

/// A 1.0 material drawn by KHR_materials_common's lighting is proved by what can be read of
/// it, its emission and coverage: its lighting is said not to be evaluated (so `compare`
/// never calls the pair the same, exit 1), and a faithful upgrade holds under `--verify`.
/// Against an output that lost its emission or its blending, `compare` says DIFFERENT and
/// names the input; a change of the lit colour alone is not seen (the lighting is not read).
#[test]
fn a_lit_1_0_material_is_proved_by_its_emission_and_coverage() {
    let folder = tempfile::tempdir().unwrap();
    let input = folder.path().join("common.gltf");
    let common = |technique: &str, values: serde_json::Value, transparent: bool| {
        serde_json::json!({"extensions": {"KHR_materials_common": {
            "technique": technique, "transparent": transparent, "values": values}}})
    };
    let asset = serde_json::json!({
        "asset": {"version": "1.0"},
        "extensionsUsed": ["KHR_materials_common"],
        "materials": {
            "glow": common("BLINN", serde_json::json!({"diffuse": [0.8, 0.2, 0.1, 1.0],
                "emission": [0.2, 0.6, 0.1, 1.0], "shininess": 20}), false),
            "glass": common("PHONG", serde_json::json!({"diffuse": [0.3, 0.3, 0.9, 1.0],
                "transparency": 0.4}), true),
            // Blended with ONE, ONE_MINUS_SRC_ALPHA, its emission is added whole.
            "lamp": common("LAMBERT", serde_json::json!({"emission": [0.9, 0.9, 0.9, 1.0],
                "transparency": 0.3}), true),
            // The constant model's colour is its emission; diffuse does not apply.
            "sign": common("CONSTANT", serde_json::json!({"diffuse": [0.1, 0.1, 0.9, 1.0],
                "emission": [0.9, 0.5, 0.1, 1.0]}), false),
        },
    });
    std::fs::write(&input, asset.to_string()).unwrap();
    let output = folder.path().join("out.gltf");
    let (input, output) = (input.to_str().unwrap(), output.to_str().unwrap());
    let (code, out) = gltfmat(&["upgrade", input, "-o", output, "--verify"]);
    assert_eq!(code, 0, "{out}");
    let proof: Vec<&str> = out.lines().filter(|l| l.starts_with("proof:")).collect();
    assert_eq!(
        proof.len(),
        1,
        "one line for the four alike verdicts: {out}"
    );
    assert!(
        proof[0].contains("NOT EVALUATED (first: its lighting")
            && proof[0].contains("only its emission and coverage are compared")
            && proof[0].contains("of the rest: ΔE2000 max 0.0000"),
        "{out}"
    );
    let (code, out) = gltfmat(&["compare", input, output, "--format", "json"]);
    assert_eq!(code, 1, "never the same: {out}");
    let pairs: serde_json::Value = serde_json::from_str(&out).unwrap();
    for pair in pairs.as_array().unwrap() {
        assert_eq!(pair["evaluated"], true, "{out}");
        assert_eq!(pair["pass"], false, "{out}");
        assert_eq!(pair["max"], 0.0, "{out}");
    }
    let converted: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(output).unwrap()).unwrap();
    let variant = |name: &str, change: &dyn Fn(&mut serde_json::Value)| {
        let mut changed = converted.clone();
        change(&mut changed["materials"]);
        let path = folder.path().join(name);
        std::fs::write(&path, changed.to_string()).unwrap();
        let (code, out) = gltfmat(&["compare", input, path.to_str().unwrap()]);
        assert_eq!(code, 1, "{out}");
        out
    };
    let unlit = variant("no-emission.gltf", &|m| {
        m[0].as_object_mut().unwrap().remove("emissiveFactor");
    });
    assert!(
        unlit.contains("material 0 (glow) ↔ 0 (glow): DIFFERENT in what is evaluated")
            && unlit.contains("(mostly emission)"),
        "{unlit}"
    );
    let opaque = variant("opaque.gltf", &|m| {
        m[1].as_object_mut().unwrap().remove("alphaMode");
    });
    assert!(
        opaque.contains("material 1 (glass) ↔ 1 (glass): DIFFERENT in what is evaluated")
            && opaque.contains("(mostly coverage)"),
        "{opaque}"
    );
    let dimmed = variant("dimmed.gltf", &|m| {
        m[2].as_object_mut().unwrap().remove("extensions");
    });
    assert!(
        dimmed.contains("material 2 (lamp) ↔ 2 (lamp): DIFFERENT in what is evaluated"),
        "{dimmed}"
    );
    let recoloured = variant("recoloured.gltf", &|m| {
        m[0]["pbrMetallicRoughness"]["baseColorFactor"] = serde_json::json!([0.0, 1.0, 0.0, 1.0]);
        m[3]["pbrMetallicRoughness"]["baseColorFactor"] = serde_json::json!([0.0, 0.0, 1.0, 1.0]);
    });
    assert!(
        recoloured.contains("material 0 (glow) ↔ 0 (glow): NOT EVALUATED")
            && recoloured.contains("material 3 (sign) ↔ 3 (sign): DIFFERENT in what is evaluated"),
        "the lit colour is not read, the constant one is its emission: {recoloured}"
    );
}

/// A 1.0 material nothing can be read of (its technique names no technique): the proof and
/// `compare` say it is not evaluated, with no figure; `--verify` keeps the output, `compare`
/// exits 1 (not the same), not 2, and writes no heat map of nothing.
#[test]
fn a_material_without_a_model_is_said_to_be_not_evaluated_by_the_proof_and_compare() {
    let folder = tempfile::tempdir().unwrap();
    let input = folder.path().join("technique.gltf");
    let asset = serde_json::json!({
        "asset": {"version": "1.0"},
        "materials": {"lit": {"technique": "missing", "values": {"diffuse": [0.8, 0.2, 0.1, 1.0]}}},
    });
    std::fs::write(&input, asset.to_string()).unwrap();
    let output = folder.path().join("out.glb");
    let (input, output) = (input.to_str().unwrap(), output.to_str().unwrap());
    let (code, out) = gltfmat(&["upgrade", input, "-o", output, "--verify"]);
    assert_eq!(code, 0, "{out}");
    let proof: Vec<&str> = out.lines().filter(|l| l.starts_with("proof:")).collect();
    assert_eq!(proof.len(), 1, "{out}");
    assert!(
        proof[0].starts_with("proof: material 0 (lit) ↔ 0 (lit): NOT EVALUATED (first: ")
            && !proof[0].contains("ΔE2000"),
        "{out}"
    );
    let heatmap = folder.path().join("heat.png");
    let heatmap = heatmap.to_str().unwrap();
    let (code, out) = gltfmat(&[
        "compare",
        input,
        output,
        "--format",
        "json",
        "--heatmap",
        heatmap,
    ]);
    assert_eq!(code, 1, "{out}");
    let pairs: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(pairs[0]["evaluated"], false, "{out}");
    assert_eq!(pairs[0]["pass"], false, "{out}");
    assert!(!std::path::Path::new(heatmap).exists());
}

/// `render` names a material it cannot draw (no model) rather than leaving it out: alone, the
/// refusal says which and why; in a sheet, a line says it was not drawn.
#[test]
fn render_names_a_material_without_a_model() {
    let folder = tempfile::tempdir().unwrap();
    let fixture = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/gltf1");
    let mut asset: serde_json::Value =
        serde_json::from_slice(&std::fs::read(fixture.join("pbr-mr-web3d.gltf")).unwrap()).unwrap();
    std::fs::copy(fixture.join("box.bin"), folder.path().join("box.bin")).unwrap();
    let common = serde_json::json!({"extensions": {"KHR_materials_common": {
        "technique": "LAMBERT", "values": {"diffuse": [0.8, 0.2, 0.1, 1.0]}}}});
    asset["materials"]["lit"] = common.clone();
    asset["extensionsUsed"] = serde_json::json!(["WEB3D_materials_pbr", "KHR_materials_common"]);
    let mixed = folder.path().join("mixed.gltf");
    std::fs::write(&mixed, asset.to_string()).unwrap();
    let only = folder.path().join("only.gltf");
    asset["materials"] = serde_json::json!({ "lit": common });
    std::fs::write(&only, asset.to_string()).unwrap();
    let sheet = folder.path().join("sheet.png");
    let (mixed, only, sheet) = (
        mixed.to_str().unwrap(),
        only.to_str().unwrap(),
        sheet.to_str().unwrap(),
    );
    let (code, out) = gltfmat(&["render", mixed, "--all", "-o", sheet]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("material 1 'lit': not drawn: ") && out.contains("KHR_materials_common"),
        "{out}"
    );
    let refused = std::process::Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(["render", only, "-o", sheet, "--force"])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(2), "{said}");
    assert!(
        said.contains("material 0 (lit) cannot be drawn: "),
        "{said}"
    );
}

#[test]
fn upgrade_timings_name_each_stage_on_stderr_only() {
    let folder = tempfile::tempdir().unwrap();
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/spec-gloss/textured.gltf");
    let run = |extra: &[&str], output: &str| {
        let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .arg("upgrade")
            .arg(&input)
            .args(["-o", &folder.path().join(output).to_string_lossy()])
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        let line = |text: &[u8]| {
            (String::from_utf8_lossy(text).lines())
                .find(|l| l.starts_with("timings: "))
                .map(str::to_owned)
        };
        assert_eq!(line(&out.stdout), None, "stdout keeps the notes alone");
        line(&out.stderr)
    };
    let stages = |line: String| -> Vec<String> {
        (line["timings: ".len()..].split(", "))
            .map(|stage| {
                let (name, seconds) = stage.rsplit_once(' ').unwrap().0.rsplit_once(' ').unwrap();
                assert!(seconds.parse::<f64>().unwrap() >= 0.0, "{stage}");
                name.to_owned()
            })
            .collect()
    };
    let with_proof = run(&["--timings"], "a.glb").expect("a timings line");
    assert_eq!(
        stages(with_proof),
        ["conversion", "proof", "output check and write"]
    );
    let without = run(&["--timings", "--no-verify"], "b.glb").expect("a timings line");
    assert_eq!(stages(without), ["conversion", "output check and write"]);
    assert_eq!(run(&[], "c.glb"), None, "only when asked");
}

#[test]
fn compare_counts_the_corners_it_does_not_sample_in_both_formats() {
    // A spec-gloss material whose two textures are 16², read as stored on a 16² grid,
    // against itself: the corners that are blends of their centres are counted, not sampled.
    let folder = tempfile::tempdir().unwrap();
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/spec-gloss");
    for png in ["diffuse16.png", "specgloss16.png"] {
        std::fs::copy(fixtures.join(png), folder.path().join(png)).unwrap();
    }
    let asset = serde_json::json!({"asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
        "images": [{"uri": "diffuse16.png"}, {"uri": "specgloss16.png"}],
        "textures": [{"source": 0}, {"source": 1}],
        "materials": [{"extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1}}}}]});
    let input = folder.path().join("a.gltf");
    std::fs::write(&input, asset.to_string()).unwrap();
    let input = input.to_str().unwrap();
    let (_, out) = gltfmat(&["compare", input, input, "--format", "json"]);
    let pairs: serde_json::Value = serde_json::from_str(&out).unwrap();
    let pair = &pairs[0];
    let (grid, samples, blended) = (
        pair["grid"].as_u64().unwrap(),
        pair["samples"].as_u64().unwrap(),
        pair["blendedCorners"].as_u64().unwrap(),
    );
    assert_eq!(grid, 16, "{out}");
    assert!(blended > 0 && blended < grid * grid, "{out}");
    assert_eq!(
        samples,
        8 * (2 * grid * grid - blended),
        "every centre and every corner not counted as a blend, in 8 directions: {out}"
    );
    let (_, human) = gltfmat(&["compare", input, input]);
    assert!(
        human.contains(&format!(
            "({blended} corners, where both are blends of the centres around them, not sampled)"
        )),
        "{human}"
    );
}

#[test]
fn an_assets_text_never_reaches_the_terminal_as_control_characters() {
    let folder = tempfile::tempdir().unwrap();
    // A name, a key and a URI holding an escape sequence and a line break, and a raw escape
    // in the file's own bytes (invalid JSON, shown in its snippet).
    // A key's line break, in the pointer of the finding on it, must not start a workflow
    // command of its own.
    let named = r#"{"asset": {"version": "2.0"}, "extras": {"k\u001b[2J": 1},
        "k\n::error::fake": 1,
        "materials": [{"name": "evil\u001b[31m\nfake: 0 error(s)"}, {"name": "\u202Eright"}],
        "images": [{"uri": "x\u001b[31m.png"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
        "accessors": [{"componentType": 5126, "count": 1, "type": "VEC3"}]}"#;
    std::fs::write(folder.path().join("named.gltf"), named).unwrap();
    std::fs::write(folder.path().join("raw.gltf"), b"{\"asset\": \x1b[31m 1}").unwrap();
    let named = folder.path().join("named.gltf");
    let named = named.to_str().unwrap();
    let raw = folder.path().join("raw.gltf");
    let raw = raw.to_str().unwrap();
    for args in [
        &["check", named, "--all-findings"][..],
        &["check", named, "--format", "github"],
        &["check", raw],
        &["compare", named, named],
        &["render", named, "--all", "-o", "sheet.png"],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(args)
            .current_dir(folder.path())
            .output()
            .unwrap();
        let (stdout, stderr) = (&out.stdout, &out.stderr);
        let text = String::from_utf8_lossy(stdout) + String::from_utf8_lossy(stderr);
        assert!(!text.contains(['\u{1b}', '\u{202E}']), "{args:?}: {text}");
        let forged = |l: &str| l.starts_with("fake") || l.starts_with("::error::fake");
        assert!(!text.lines().any(forged), "{args:?}: {text}");
        assert!(
            text.contains("\\u{1b}"),
            "{args:?} shows the escape: {text}"
        );
    }
}

/// Meshes that share their vertex data (one accessor of 2^20 texture coordinates, drawn by
/// three meshes) are read once: three reads would pass the run's read budget and leave the
/// material's mesh unread, compared over the whole UV square.
#[test]
fn meshes_sharing_their_vertex_data_are_read_once() {
    let folder = tempfile::tempdir().unwrap();
    let dir = folder.path();
    let count = 1usize << 20;
    // Tiny triangles in the square's first tenth.
    let uvs: Vec<u8> = (0..count)
        .flat_map(|i| {
            let corner = (i % 3) as f32 * 1e-4;
            let cell = (i / 3 % 1000) as f32 * 1e-4;
            [0.01 + cell + corner, 0.01 + corner]
        })
        .flat_map(f32::to_le_bytes)
        .collect();
    std::fs::write(dir.join("uvs.bin"), &uvs).unwrap();
    let primitive =
        serde_json::json!({"primitives": [{"attributes": {"TEXCOORD_0": 0}, "material": 0}]});
    let png = dir.join("texture.png");
    image::RgbImage::from_pixel(64, 64, image::Rgb([90, 120, 200]))
        .save(&png)
        .unwrap();
    let asset = serde_json::json!({
        "asset": {"version": "2.0"},
        "meshes": [primitive, primitive, primitive],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC2"}],
        "bufferViews": [{"buffer": 0, "byteLength": uvs.len()}],
        "buffers": [{"byteLength": uvs.len(), "uri": "uvs.bin"}],
        "images": [{"uri": "texture.png"}],
        "textures": [{"source": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    });
    let path = dir.join("shared.gltf");
    std::fs::write(&path, asset.to_string()).unwrap();
    let path = path.to_str().unwrap();
    let (code, text) = gltfmat(&["compare", path, path]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("texel centres and corners on the mesh ("),
        "{text}"
    );
}
