//! gltfmat's own rules, one per file, all registered in [`RULES`]. Each file's doc comment
//! (What it does / Why / Example) is the rule's documentation for `gltfmat rules`,
//! `gltfmat explain` and SARIF.

mod duplicate_key;
pub mod gltf1;
mod outside_folder;

use super::codes::{CodeInfo, Origin, Severity};
use super::context::Context;

pub struct Rule {
    pub info: CodeInfo,
    /// Runs the rule on a document; `None` for codes emitted by the core passes.
    pub run: Option<fn(&mut Context)>,
}

const fn rule(
    code: &'static str,
    severity: Severity,
    group: &'static str,
    summary: &'static str,
    doc: &'static str,
    run: Option<fn(&mut Context)>,
) -> Rule {
    Rule {
        info: CodeInfo {
            code,
            severity,
            group,
            summary,
            doc,
            origin: Origin::Gltfmat,
        },
        run,
    }
}

pub static RULES: &[Rule] = &[
    rule(
        "JSON_DUPLICATE_KEY",
        Severity::Warning,
        "json",
        "A key appears twice in one JSON object; engines disagree on which value wins.",
        duplicate_key::DOC,
        Some(duplicate_key::check),
    ),
    rule(
        "URI_OUTSIDE_ASSET_FOLDER",
        Severity::Error,
        "resources",
        "A URI resolves outside the asset's folder (absolute path, `..` escape or symlink) and was not read.",
        outside_folder::DOC,
        None,
    ),
    rule(
        "GLTF_1_0_ASSET",
        Severity::Error,
        "gltf1",
        "The asset is glTF 1.0: run `gltfmat upgrade` to convert it to glTF 2.0.",
        gltf1::DOC,
        None,
    ),
];

/// Runs every rule with a `run` function, unless its group is disabled.
pub fn run_all(ctx: &mut Context) {
    for rule in RULES {
        if ctx
            .options
            .disabled_groups
            .iter()
            .any(|g| g == rule.info.group)
        {
            continue;
        }
        if let Some(run) = rule.run {
            run(ctx);
        }
    }
}
