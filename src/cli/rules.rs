//! `gltfmat rules` and `gltfmat explain CODE`: generated from the registry.

use crate::common::{Failure, Outcome};
use gltfmat::registry;
use std::process::ExitCode;

/// How `gltfmat rules` prints the list.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ListFormat {
    /// Aligned columns: code, severity, group (`*` for an opt-in group), origin, description.
    Table,
    /// One JSON array of objects with the same fields and the documentation.
    Json,
}

pub fn list(format: ListFormat) -> Outcome {
    let out = match format {
        ListFormat::Table => table(),
        ListFormat::Json => {
            let entries: Vec<serde_json::Value> = registry::all().map(entry).collect();
            serde_json::to_string_pretty(&entries).unwrap_or_default() + "\n"
        }
    };
    out!("{}", &out);
    Ok(ExitCode::SUCCESS)
}

fn origin(info: &registry::CodeInfo) -> &'static str {
    match info.origin {
        registry::Origin::Khronos => "khronos",
        registry::Origin::Gltfmat => "gltfmat",
    }
}

/// The width the table keeps to: a 100-column terminal.
const WIDTH: usize = 100;

/// A line of code, severity, group (`*` for an opt-in group) and origin per code, then its
/// description wrapped beneath it, within [`WIDTH`] columns.
fn table() -> String {
    let mut out = format!(
        "{:<58} {:<8} {:<15} {}\n",
        "CODE", "SEVERITY", "GROUP", "ORIGIN"
    );
    for info in registry::all() {
        let group = if registry::is_opt_in(info.group) {
            format!("{}*", info.group)
        } else {
            info.group.to_string()
        };
        out.push_str(&format!(
            "{:<58} {:<8} {:<15} {}\n",
            info.code.name(),
            info.severity().name(),
            group,
            origin(&info),
        ));
        out.push_str(&wrapped(&info.description(), "    "));
    }
    out.push_str("\n* opt-in group: runs only with --enable-group\n");
    out
}

/// `text` in lines of at most [`WIDTH`] columns, each starting with `indent` (a word longer
/// than a line gets a line of its own).
fn wrapped(text: &str, indent: &str) -> String {
    let mut out = String::new();
    let mut line = String::from(indent);
    for word in text.split_whitespace() {
        let width = line.chars().count();
        if width > indent.len() && width + 1 + word.chars().count() > WIDTH {
            out.push_str(line.trim_end());
            out.push('\n');
            line = String::from(indent);
        }
        if line.len() > indent.len() {
            line.push(' ');
        }
        line.push_str(word);
    }
    out.push_str(line.trim_end());
    out.push('\n');
    out
}

fn entry(info: registry::CodeInfo) -> serde_json::Value {
    serde_json::json!({
        "code": info.code,
        "severity": info.severity().name(),
        "group": info.group,
        "optIn": registry::is_opt_in(info.group),
        "origin": origin(&info),
        "description": info.description(),
        "messageTemplate": (info.origin == registry::Origin::Khronos).then_some(info.summary),
        "documentation": info.help_markdown(),
    })
}

pub fn explain(code: &str) -> Outcome {
    let info = registry::find(code)
        .ok_or_else(|| Failure::usage(format!("unknown code '{code}' (see `gltfmat rules`)")))?;
    outln!(
        "# {} ({}, {})\n\n{}",
        info.code,
        info.severity().name(),
        info.group,
        info.help_markdown()
    );
    Ok(ExitCode::SUCCESS)
}
