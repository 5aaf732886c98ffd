//! SARIF 2.1.0, with every registered code as a rule carrying its documentation.

use super::{location_suffix, Positions};
use crate::check::{registry, Diagnostic, Location, Report, Severity};
use serde_json::{json, Value};

pub fn render(reports: &[Report]) -> String {
    let rules: Vec<Value> = registry::all()
        .map(|info| {
            let help = if info.doc.is_empty() {
                info.summary
            } else {
                info.doc
            };
            json!({
                "id": info.code,
                "shortDescription": {"text": info.summary},
                "fullDescription": {"text": help},
                "help": {"text": help, "markdown": help},
                "defaultConfiguration": {"level": level(info.severity())},
                "properties": {"group": info.group},
            })
        })
        .collect();
    let log = Log {
        schema: "https://json.schemastore.org/sarif-2.1.0.json",
        version: "2.1.0",
        runs: [Run {
            tool: json!({"driver": {
                "name": "gltfmat",
                "version": env!("CARGO_PKG_VERSION"),
                "informationUri": "https://github.com/gltfmat/gltfmat",
                "rules": rules,
            }}),
            results: Results(reports),
        }],
    };
    serde_json::to_string_pretty(&log).unwrap_or_default() + "\n"
}

/// The log, serialised as it is walked: each result is built, written and dropped in turn,
/// so 10^5 results never exist as one JSON tree (ten times the size of their text).
#[derive(serde::Serialize)]
struct Log<'r> {
    #[serde(rename = "$schema")]
    schema: &'static str,
    version: &'static str,
    runs: [Run<'r>; 1],
}

#[derive(serde::Serialize)]
struct Run<'r> {
    tool: Value,
    results: Results<'r>,
}

struct Results<'r>(&'r [Report]);

impl serde::Serialize for Results<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let mut sequence = serializer.serialize_seq(None)?;
        for report in self.0 {
            let positions = Positions::of(report);
            for d in &report.diagnostics {
                sequence.serialize_element(&result(report, &positions, d))?;
            }
        }
        sequence.end()
    }
}

fn level(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Info | Severity::Hint => "note",
    }
}

/// One SARIF result.
fn result(report: &Report, positions: &Positions, d: &Diagnostic) -> Value {
    let mut region = json!({});
    if let Some((line, column)) = positions.line_col(d) {
        region = json!({"startLine": line, "startColumn": column});
    } else if let Location::Offset(offset) = d.location {
        region = json!({"byteOffset": offset});
    }
    let mut physical = json!({"artifactLocation": {"uri": report.uri}});
    if region.as_object().is_some_and(|r| !r.is_empty()) {
        physical["region"] = region;
    }
    let mut result = json!({
        "ruleId": d.code,
        "level": level(d.severity),
        "message": {"text": format!("{}{}", d.message, location_suffix(d))},
        "locations": [{"physicalLocation": physical}],
    });
    if let Location::Pointer(p) = &d.location {
        result["locations"][0]["logicalLocations"] =
            json!([{"fullyQualifiedName": p, "kind": "member"}]);
    }
    result
}
