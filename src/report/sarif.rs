//! SARIF 2.1.0, with every registered code as a rule carrying its documentation.

use super::{location_suffix, Positions};
use crate::check::{registry, Finding, Place, Report, Severity};
use crate::document::Container;
use percent_encoding::{utf8_percent_encode, AsciiSet, NON_ALPHANUMERIC};
use serde_json::{json, Value};
use std::borrow::Borrow;
use std::cell::RefCell;

pub(super) fn write<R: Borrow<Report>>(
    reports: impl Iterator<Item = R>,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    let rules: Vec<Value> = registry::all().map(rule).collect();
    let root = SourceRoot::current();
    let mut tool = json!({"driver": {
        "name": "gltfmat",
        "version": env!("CARGO_PKG_VERSION"),
        "rules": rules,
    }});
    if let Some(home) = option_env!("CARGO_PKG_REPOSITORY").filter(|r| !r.is_empty()) {
        tool["driver"]["informationUri"] = json!(home);
    }
    let log = Log {
        schema: "https://json.schemastore.org/sarif-2.1.0.json",
        version: "2.1.0",
        runs: [Run {
            tool,
            original_uri_base_ids: root.base_ids(),
            results: Results(RefCell::new(Some(reports)), &root),
        }],
    };
    serde_json::to_writer_pretty(&mut *out, &log)?;
    out.write_all(b"\n")
}

/// One rule: a sentence for the alert's heading (never a message template), the full
/// documentation as help.
fn rule(info: registry::CodeInfo) -> Value {
    let description = info.description();
    let help = info.help_markdown();
    let mut rule = json!({
        "id": info.code,
        "shortDescription": {"text": description},
        "fullDescription": {"text": description},
        "help": {"text": help, "markdown": help},
        "defaultConfiguration": {"level": level(info.severity())},
        "properties": {"group": info.group},
    });
    if info.origin == registry::Origin::Khronos {
        rule["helpUri"] = json!(registry::KHRONOS_ISSUES);
    }
    rule
}

/// The folder result paths are relative to (`%SRCROOT%`): the current one, where a CI job
/// checks out the repository.
struct SourceRoot {
    folder: Option<std::path::PathBuf>,
}

/// Characters kept as they are in a URI path; the rest is percent-encoded.
const PATH_SEGMENT: &AsciiSet = &NON_ALPHANUMERIC
    .remove(b'-')
    .remove(b'.')
    .remove(b'_')
    .remove(b'~')
    .remove(b'/');

impl SourceRoot {
    /// The repository the working folder is in (the nearest folder above it holding `.git`),
    /// or the working folder: code scanning places results by paths from the repository's
    /// root, wherever in it the check ran.
    fn current() -> SourceRoot {
        let here = std::env::current_dir().ok();
        let repository = (here.as_deref())
            .and_then(|here| here.ancestors().find(|folder| folder.join(".git").exists()))
            .map(std::path::Path::to_path_buf);
        SourceRoot {
            folder: repository.or(here),
        }
    }

    fn base_ids(&self) -> Value {
        match self.folder.as_deref().and_then(|f| f.to_str()) {
            Some(folder) => {
                let folder = folder.trim_end_matches('/');
                json!({"%SRCROOT%": {"uri": format!("file://{}/", encode(folder))}})
            }
            None => json!({}),
        }
    }

    /// An artifact location: relative to `%SRCROOT%` when the file is inside it, an absolute
    /// `file://` URI otherwise; each path segment percent-encoded (`a 100%.gltf` →
    /// `a%20100%25.gltf`).
    fn artifact(&self, path: &str) -> Value {
        let file = std::path::Path::new(path);
        // Resolved as the working folder is (`..` and links followed), so that a file named
        // through `../` is still found inside the root.
        let absolute = (std::fs::canonicalize(file).or_else(|_| std::path::absolute(file)))
            .unwrap_or_else(|_| file.to_path_buf());
        let inside = (self.folder.as_deref()).and_then(|root| absolute.strip_prefix(root).ok());
        match inside.and_then(|relative| relative.to_str()) {
            Some(relative) => json!({"uri": encode(relative), "uriBaseId": "%SRCROOT%"}),
            None => match absolute.to_str() {
                Some(absolute) if absolute.starts_with('/') => {
                    json!({"uri": format!("file://{}", encode(absolute))})
                }
                _ => json!({"uri": encode(path)}),
            },
        }
    }
}

fn encode(path: &str) -> String {
    utf8_percent_encode(path, PATH_SEGMENT).to_string()
}

/// The log, serialised as it is walked: each result is built, written and dropped in turn,
/// so 10^5 results never exist as one JSON tree (ten times the size of their text).
#[derive(serde::Serialize)]
#[serde(bound(serialize = "Results<'r, I>: serde::Serialize"))]
struct Log<'r, I> {
    #[serde(rename = "$schema")]
    schema: &'static str,
    version: &'static str,
    runs: [Run<'r, I>; 1],
}

#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
#[serde(bound(serialize = "Results<'r, I>: serde::Serialize"))]
struct Run<'r, I> {
    tool: Value,
    original_uri_base_ids: Value,
    results: Results<'r, I>,
}

/// The results of every report, taken from the iterator as they are written (once).
struct Results<'r, I>(RefCell<Option<I>>, &'r SourceRoot);

impl<R: Borrow<Report>, I: Iterator<Item = R>> serde::Serialize for Results<'_, I> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let mut sequence = serializer.serialize_seq(None)?;
        for report in self.0.borrow_mut().take().into_iter().flatten() {
            let report = report.borrow();
            let occurrences = occurrences(report);
            let positions = Positions::of(report);
            let artifact = self.1.artifact(&report.uri);
            for (d, occurrence) in report.diagnostics.iter().zip(occurrences) {
                let identity = [report.uri.as_str(), d.code.name(), &place(&d), d.message];
                let found = result(report, &positions, &artifact, &d, identity, occurrence);
                sequence.serialize_element(&found)?;
            }
        }
        sequence.end()
    }
}

/// How many findings with the same (file, code, place, message) come before each one: two
/// distinct findings of one code at one pointer get distinct fingerprints, the same run after
/// run. Identities are compared by hash (two of one hash only number each other's
/// occurrences on: their fingerprints stay distinct), sorted rather than counted in a map, so
/// 10^6 findings cost sixteen bytes each while this runs and four after.
fn occurrences(report: &Report) -> Vec<u32> {
    let mut by_identity: Vec<(u64, u32)> = (report.diagnostics.iter())
        .map(|d| {
            let identity = [report.uri.as_str(), d.code.name(), &place(&d), d.message];
            (fnv(&identity), d.index as u32)
        })
        .collect();
    by_identity.sort_unstable();
    let mut occurrences = vec![0; by_identity.len()];
    for (at, &(hash, index)) in by_identity.iter().enumerate() {
        if at > 0 && by_identity[at - 1].0 == hash {
            occurrences[index as usize] = occurrences[by_identity[at - 1].1 as usize] + 1;
        }
    }
    occurrences
}

fn level(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Info | Severity::Hint => "note",
    }
}

/// Where a finding is, as its fingerprint names it: its JSON pointer or `@offset`.
fn place<'f>(d: &Finding<'f>) -> std::borrow::Cow<'f, str> {
    match d.location {
        Place::Pointer(p) => p.into(),
        Place::Offset(o) => format!("@{o}").into(),
    }
}

/// One SARIF result. Every result has a `startLine`, as GitHub code scanning requires of a
/// result placed in a file: a .gltf's by line and column, a GLB's the first line (its JSON
/// chunk is one line of a binary file) with the byte region kept, and so is a finding the text
/// cannot place. The fingerprint names the finding by file, code, JSON pointer, message and
/// how many alike came before it, so an alert keeps its identity when lines move and two
/// findings never share one.
fn result<'r>(
    report: &Report,
    positions: &Positions,
    artifact: &'r Value,
    d: &Finding<'r>,
    identity: [&str; 4],
    occurrence: u32,
) -> SarifResult<'r> {
    let glb = report.document.container == Container::Glb;
    let first_line = Region::line(1);
    let region = match (d.location, positions.span(d)) {
        (Place::Offset(offset), _) => Region {
            byte_offset: Some(offset),
            ..first_line
        },
        (Place::Pointer(_), Some(span)) if glb => Region {
            byte_offset: Some((positions.text_start + span.start) as u64),
            byte_length: Some(span.len().max(1)),
            ..first_line
        },
        (Place::Pointer(_), Some(span)) => {
            let (line, column) = positions.lines.line_col(span.start);
            Region {
                start_column: Some(column),
                ..Region::line(line)
            }
        }
        (Place::Pointer(_), None) => first_line,
    };
    let occurrence = occurrence.to_string();
    let [uri, code, place, message] = identity;
    let logical = match d.location {
        Place::Pointer(p) => Some([LogicalLocation {
            fully_qualified_name: p,
            kind: "member",
        }]),
        Place::Offset(_) => None,
    };
    SarifResult {
        rule_id: d.code.name(),
        level: level(d.severity),
        message: Text {
            text: format!("{}{}", d.message, location_suffix(d)),
        },
        locations: [SarifLocation {
            physical_location: PhysicalLocation {
                artifact_location: artifact,
                region,
            },
            logical_locations: logical,
        }],
        partial_fingerprints: Fingerprints {
            gltfmat_v2: fingerprint(&[uri, code, place, message, &occurrence]),
        },
    }
}

#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
struct SarifResult<'r> {
    rule_id: &'static str,
    level: &'static str,
    message: Text,
    locations: [SarifLocation<'r>; 1],
    partial_fingerprints: Fingerprints,
}

#[derive(serde::Serialize)]
struct Text {
    text: String,
}

#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
struct SarifLocation<'r> {
    physical_location: PhysicalLocation<'r>,
    #[serde(skip_serializing_if = "Option::is_none")]
    logical_locations: Option<[LogicalLocation<'r>; 1]>,
}

#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
struct PhysicalLocation<'r> {
    artifact_location: &'r Value,
    region: Region,
}

#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
struct Region {
    start_line: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    start_column: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    byte_offset: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    byte_length: Option<usize>,
}

impl Region {
    fn line(line: usize) -> Region {
        Region {
            start_line: line,
            start_column: None,
            byte_offset: None,
            byte_length: None,
        }
    }
}

#[derive(serde::Serialize)]
#[serde(rename_all = "camelCase")]
struct LogicalLocation<'r> {
    fully_qualified_name: &'r str,
    kind: &'static str,
}

#[derive(serde::Serialize)]
struct Fingerprints {
    #[serde(rename = "gltfmat/v2")]
    gltfmat_v2: String,
}

/// FNV-1a over the parts (each followed by a 0 byte), as 16 hex digits: stable across runs,
/// platforms and versions, which a std hasher does not promise.
fn fingerprint(parts: &[&str]) -> String {
    format!("{:016x}", fnv(parts))
}

/// FNV-1a over the parts, each followed by a 0 byte.
fn fnv(parts: &[&str]) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in parts.iter().flat_map(|p| p.bytes().chain([0])) {
        hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
    }
    hash
}
