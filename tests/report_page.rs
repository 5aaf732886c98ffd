//! `gltfmat report`, `upgrade --report` and `compare --report`: one self-contained page.

use std::path::Path;
use std::process::Command;

fn gltfmat(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("gltfmat runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn count(html: &str, needle: &str) -> usize {
    html.matches(needle).count()
}

#[test]
fn a_report_of_the_fixtures_shows_every_file_its_findings_and_its_materials() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("report.html");
    let (status, _, stderr) = gltfmat(&["report", "fixtures", "-o", page.to_str().unwrap()]);
    assert_eq!(status, 0, "{stderr}");
    let html = std::fs::read_to_string(&page).unwrap();
    let (_, listed, _) = gltfmat(&["check", "fixtures", "--format", "jsonl"]);
    let files = listed.lines().count();
    assert!(files >= 10);
    // One summary row and one section per file.
    assert_eq!(
        count(&html, "<tr><td><a href=\"#asset-")
            + count(&html, "<tr class=\"bad\"><td><a href=\"#asset-"),
        files
    );
    assert_eq!(count(&html, "<section id=\"asset-"), files);
    // The broken material's findings, each linked to its code's explanation, given once.
    assert!(html.contains("fixtures/broken/bad-material.gltf"));
    assert!(html.contains("href=\"#code-VALUE_NOT_IN_RANGE\""));
    assert_eq!(count(&html, "<dt id=\"code-VALUE_NOT_IN_RANGE\">"), 1);
    assert!(
        html.contains("fixtures/broken/bad-material.gltf:60:11"),
        "a finding's line and column"
    );
    // Balls for assets with material findings, thumbnails of the textures they read.
    assert!(html.contains("rendered as a ball\""));
    assert!(html.contains("read by diffuseTexture\""));
    // Self-contained and script-free: every image inline, nothing fetched.
    assert!(!html.contains("<script"));
    assert!(!html.contains("src=\"http"));
    let images = count(&html, "<img ");
    assert!(images > 5);
    assert_eq!(count(&html, "<img src=\"data:image/png;base64,"), images);
    assert_eq!(count(&html, " alt=\""), images, "every image has alt text");
    // Errors first in the summary.
    let first_row = html.find("<tbody><tr").unwrap();
    assert!(html[first_row..].starts_with("<tbody><tr class=\"bad\">"));
}

#[test]
fn text_from_the_asset_is_shown_as_text() {
    let dir = tempfile::tempdir().unwrap();
    let asset = dir.path().join("hostile.gltf");
    std::fs::write(
        &asset,
        r#"{"asset": {"version": "2.0"}, "materials": [{"name": "<script>alert(1)</script>", "alphaCutoff": 0.5}]}"#,
    )
    .unwrap();
    let page = dir.path().join("r.html");
    let (status, _, stderr) = gltfmat(&[
        "report",
        asset.to_str().unwrap(),
        "-o",
        page.to_str().unwrap(),
        "--render",
        "all",
    ]);
    assert_eq!(status, 0, "{stderr}");
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(!html.contains("<script>"));
    assert!(html.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
}

#[test]
fn the_report_is_written_as_every_output_is() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("r.html");
    std::fs::write(&page, "mine").unwrap();
    let (status, _, _) = gltfmat(&["report", "fixtures/valid", "-o", page.to_str().unwrap()]);
    assert_eq!(
        status, 2,
        "an existing file is not replaced without --force"
    );
    assert_eq!(std::fs::read_to_string(&page).unwrap(), "mine");
    let (status, _, _) = gltfmat(&[
        "report",
        "fixtures/valid",
        "-o",
        "fixtures/valid/sheen-triangle.gltf",
        "--force",
    ]);
    assert_eq!(status, 2, "never over an input");
    assert!(Path::new("fixtures/valid/sheen-triangle.gltf").exists());
}

#[test]
fn upgrade_and_compare_reports_show_both_materials_side_by_side() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.gltf");
    let page = dir.path().join("upgrade.html");
    let (status, _, stderr) = gltfmat(&[
        "upgrade",
        "fixtures/spec-gloss/textured.gltf",
        "-o",
        out.to_str().unwrap(),
        "--report",
        page.to_str().unwrap(),
    ]);
    assert_eq!(status, 0, "{stderr}");
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("alt=\"source material 0") && html.contains("alt=\"compared material 0"));
    assert!(html.contains("ΔE2000 over UV"), "a heat map");
    assert!(html.contains("class=\"pair same\""));

    let page = dir.path().join("compare.html");
    gltfmat(&[
        "compare",
        "fixtures/spec-gloss/textured.gltf",
        "fixtures/spec-gloss/factors.gltf",
        "--report",
        page.to_str().unwrap(),
    ]);
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("class=\"pair different\""));
    assert!(html.contains("DIFFERENT: ΔE2000 max"));
    let (status, _, _) = gltfmat(&[
        "upgrade",
        "fixtures/spec-gloss/textured.gltf",
        "-o",
        "-",
        "--report",
        "x.html",
    ]);
    assert_eq!(status, 2, "a report needs a file output");
}

/// A 1.0 KHR_materials_common material against its upgrade: its lighting is not evaluated, so
/// the page marks the pair "not evaluated" while its emission and coverage agree, and
/// "different" once the upgrade's emission is lost.
#[test]
fn a_pair_evaluated_in_part_is_marked_not_evaluated_or_different_by_what_was_evaluated() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("common.gltf");
    std::fs::write(
        &input,
        serde_json::json!({"asset": {"version": "1.0"}, "extensionsUsed": ["KHR_materials_common"],
            "materials": {"glow": {"extensions": {"KHR_materials_common": {"technique": "LAMBERT",
                "values": {"diffuse": [0.8, 0.2, 0.1, 1.0], "emission": [0.2, 0.6, 0.1, 1.0]}}}}}})
        .to_string(),
    )
    .unwrap();
    let out = dir.path().join("out.gltf");
    let path = |p: &Path| p.to_str().unwrap().to_string();
    let (status, _, stderr) = gltfmat(&["upgrade", &path(&input), "-o", &path(&out)]);
    assert_eq!(status, 0, "{stderr}");
    let page = dir.path().join("faithful.html");
    gltfmat(&[
        "compare",
        &path(&input),
        &path(&out),
        "--report",
        &path(&page),
    ]);
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("class=\"pair not-evaluated\""), "{html}");
    let mut dimmed: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    dimmed["materials"][0]
        .as_object_mut()
        .unwrap()
        .remove("emissiveFactor");
    let dimmed_path = dir.path().join("dimmed.gltf");
    std::fs::write(&dimmed_path, dimmed.to_string()).unwrap();
    let page = dir.path().join("dimmed.html");
    gltfmat(&[
        "compare",
        &path(&input),
        &path(&dimmed_path),
        "--report",
        &path(&page),
    ]);
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("class=\"pair different\""), "{html}");
}
