//! `gltfmat rules` and `gltfmat explain CODE`: generated from the registry.

use crate::common::{Failure, Outcome};
use gltfmat::check::registry;
use std::io::Write;
use std::process::ExitCode;

/// Writes text to stdout; a closed pipe (`| head`) is not an error.
pub fn print(text: &str) {
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

pub fn list() -> Outcome {
    let mut out = String::new();
    for info in registry::all() {
        out.push_str(&format!(
            "{:<58} {:<8} {}\n",
            info.code,
            info.severity().name(),
            info.summary
        ));
    }
    print(&out);
    Ok(ExitCode::SUCCESS)
}

pub fn explain(code: &str) -> Outcome {
    let info = registry::find(code)
        .ok_or_else(|| Failure::usage(format!("unknown code '{code}' (see `gltfmat rules`)")))?;
    let body = if info.doc.is_empty() {
        info.summary
    } else {
        info.doc
    };
    print(&format!(
        "# {} ({}, {})\n\n{}\n",
        info.code,
        info.severity().name(),
        info.group,
        body
    ));
    Ok(ExitCode::SUCCESS)
}
