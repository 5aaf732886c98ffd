//! Output formats. The checker knows nothing of terminals: each format renders a list of
//! [`Report`]s to a writer (or a string).

mod human;
mod sarif;

use crate::check::{Finding, Findings, Place, Report, Severity};
use crate::document::json;
use serde::Serialize;
use serde_json::{json, Map, Value};
use std::borrow::Borrow;
use std::cell::RefCell;
use std::io::Write;
use std::ops::Range;

/// `text` as a terminal or a CI log may show it: every control character but the tab (line
/// breaks, escape sequences, C1 controls) and every bidirectional override is written as its
/// `\u{…}` escape. Text from an asset (a name, a key, a URI, the file's own bytes) can then
/// neither move the cursor, colour or clear the screen, nor start a line that reads as
/// gltfmat's own (or as a CI log's command).
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    let shown_raw = |c: char| {
        c == '\t'
            || !(c.is_control() || matches!(c, '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}'))
    };
    if text.chars().all(shown_raw) {
        return text.into();
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        match shown_raw(c) {
            true => out.push(c),
            false => out.push_str(&format!("\\u{{{:x}}}", u32::from(c))),
        }
    }
    out.into()
}

/// An output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Format {
    /// `path:line:col: severity[CODE]: message` with a source snippet.
    Human,
    /// Khronos validation report shape: one object for one file argument, an array when the
    /// inputs form a list ([`Style::list`]).
    Json,
    /// One Khronos-shaped report per line.
    Jsonl,
    /// SARIF 2.1.0.
    Sarif,
    /// GitHub Actions workflow commands (`::error file=…`).
    Github,
}

/// How the output looks.
#[derive(Debug, Clone, Copy, Default)]
#[non_exhaustive]
pub struct Style {
    /// ANSI colours (human format).
    pub colour: bool,
    /// List infos and hints too, not only count them (human format).
    pub all_findings: bool,
    /// The inputs form a list (a folder, or several arguments), so `json` is an array even
    /// when the list holds one report: its shape must not depend on how many files a folder
    /// happened to hold.
    pub list: bool,
    /// A summary line for every file of a list, not only for those with something listed
    /// (human format).
    pub verbose: bool,
}

impl Style {
    /// Plain text, or coloured; infos and hints counted, not listed.
    pub fn new(colour: bool) -> Style {
        Style {
            colour,
            all_findings: false,
            list: false,
            verbose: false,
        }
    }

    /// This style listing infos and hints too (or not).
    pub fn with_all_findings(mut self, all: bool) -> Style {
        self.all_findings = all;
        self
    }

    /// This style summarising every file of a list (or only those with findings listed).
    pub fn with_verbose(mut self, verbose: bool) -> Style {
        self.verbose = verbose;
        self
    }

    /// This style rendering the reports as a list (or not): see [`Style::list`].
    pub fn with_list(mut self, list: bool) -> Style {
        self.list = list;
        self
    }
}

/// Renders every report in `format` as one string.
pub fn render(format: Format, reports: &[Report], options: &Style) -> String {
    let mut text = Vec::new();
    write(format, reports, options, &mut text).expect("writing to memory does not fail");
    String::from_utf8(text).expect("every format writes UTF-8")
}

/// Writes every report in `format` to `out` as it is rendered: a SARIF or JSON report of
/// 10^5 findings is never held whole in memory (`out` should be buffered).
pub fn write(
    format: Format,
    reports: &[Report],
    options: &Style,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    write_each(format, reports, options, out)
}

/// Writes each report in `format` to `out` as it comes, then what closes the output (the
/// grand total, the end of the list): reports made one after another (a folder of 10^4
/// assets) are each dropped, with their document, once written.
pub fn write_each<R: Borrow<Report>>(
    format: Format,
    reports: impl IntoIterator<Item = R>,
    options: &Style,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    let mut reports = reports.into_iter();
    match format {
        Format::Human => human::write(reports, options, out),
        Format::Json => {
            let first = reports.next();
            let second = if options.list { None } else { reports.next() };
            match (first, second) {
                (Some(one), None) if !options.list => {
                    serde_json::to_writer_pretty(&mut *out, &khronos_report(one.borrow()))?
                }
                (first, second) => {
                    let all = first.into_iter().chain(second).chain(reports);
                    serde_json::to_writer_pretty(&mut *out, &KhronosReports::new(all))?
                }
            }
            out.write_all(b"\n")
        }
        Format::Jsonl => reports.try_for_each(|r| {
            serde_json::to_writer(&mut *out, &khronos_report(r.borrow()))?;
            out.write_all(b"\n")
        }),
        Format::Sarif => sarif::write(reports, out),
        Format::Github => reports.try_for_each(|r| github(r.borrow(), options, out)),
    }
}

/// A list of Khronos-shaped reports, each built as it is written (serialising takes the
/// reports from the iterator: it is written once).
struct KhronosReports<I>(RefCell<Option<I>>);

impl<I> KhronosReports<I> {
    fn new(reports: I) -> Self {
        KhronosReports(RefCell::new(Some(reports)))
    }
}

impl<R: Borrow<Report>, I: Iterator<Item = R>> serde::Serialize for KhronosReports<I> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let mut list = serializer.serialize_seq(None)?;
        for report in self.0.borrow_mut().take().into_iter().flatten() {
            list.serialize_element(&khronos_report(report.borrow()))?;
        }
        list.end()
    }
}

/// Where a report's findings lie in its JSON text: every pointer located in one pass and
/// lines indexed once, so that rendering N findings costs one scan of the file, not N, and
/// four bytes per finding and eight per distinct pointer. A pointer to a member that is not
/// written (a default) is placed at its nearest enclosing value that is.
pub(crate) struct Positions<'r> {
    /// Each finding's place in `spans` (`UNPLACED` for one not located).
    places: Vec<u32>,
    /// Where each distinct pointer's value lies (or its nearest enclosing value's) in the
    /// text, as start and end (`NOWHERE` when not found; a text is shorter than 4 GiB).
    spans: Vec<[u32; 2]>,
    /// The pointers placed at an enclosing value: their place in `spans` and that value's
    /// pointer, in order.
    enclosing: Vec<(usize, &'r str)>,
    /// The JSON text's lines.
    pub lines: json::LineIndex<'r>,
    /// Where the JSON text starts in the file (the JSON chunk of a GLB).
    pub text_start: usize,
}

const NOWHERE: [u32; 2] = [u32::MAX, u32::MAX];
const UNPLACED: u32 = u32::MAX;

impl<'r> Positions<'r> {
    pub(crate) fn of(report: &'r Report) -> Self {
        Self::of_those(report, |_| true)
    }

    /// The positions of the findings `wanted` picks (those a format shows: a summary of
    /// 10^5 counted infos locates none of them).
    pub(crate) fn of_those(report: &'r Report, wanted: impl Fn(&Finding) -> bool) -> Self {
        let text = report.document.json_text();
        let findings = &report.diagnostics;
        let pointer = |i: u32| findings.pointer_at(i as usize).unwrap_or_default();
        let mut by_pointer: Vec<u32> = (findings.iter())
            .filter(|f| f.span_hint.is_none() && f.pointer().is_some() && wanted(f))
            .map(|f| f.index as u32)
            .collect();
        by_pointer.sort_unstable_by(|&a, &b| pointer(a).cmp(pointer(b)));
        // Each distinct pointer once (the first finding naming it stands for it), and each
        // finding's place among them.
        let mut places = vec![UNPLACED; findings.len()];
        let mut distinct: Vec<u32> = Vec::new();
        for &index in &by_pointer {
            if distinct
                .last()
                .is_none_or(|&last| pointer(last) != pointer(index))
            {
                distinct.push(index);
            }
            places[index as usize] = (distinct.len() - 1) as u32;
        }
        drop(by_pointer);
        let mut spans = vec![NOWHERE; distinct.len()];
        let mut enclosing = Vec::new();
        if report.document.root.is_some() && u32::try_from(text.len()).is_ok() {
            let at = |i: usize| pointer(distinct[i]);
            json::locate_each(text, distinct.len(), at, |i, range| {
                spans[i] = [range.start as u32, range.end as u32];
            });
            enclosing = place_at_ancestors(text, at, &mut spans);
        }
        Positions {
            places,
            spans,
            enclosing,
            lines: json::LineIndex::new(text),
            text_start: report.document.json_range.start,
        }
    }

    /// The place in `spans` of a finding of the report these positions are of.
    fn place_of(&self, finding: &Finding) -> Option<usize> {
        let place = *self.places.get(finding.index)?;
        (place != UNPLACED).then_some(place as usize)
    }

    /// Byte range in the JSON text that a finding points at, or, for a member that is not
    /// written, at its nearest enclosing value.
    pub(crate) fn span(&self, finding: &Finding) -> Option<Range<usize>> {
        if let Some(offset) = finding.span_hint {
            return Some(offset..offset);
        }
        let [start, end] = self.spans[self.place_of(finding)?];
        ([start, end] != NOWHERE).then_some(start as usize..end as usize)
    }

    /// The enclosing value a finding is shown at when its own pointer is not in the text.
    pub(crate) fn shown_at(&self, finding: &Finding) -> Option<&'r str> {
        if self.enclosing.is_empty() {
            return None;
        }
        let place = self.place_of(finding)?;
        let at = (self.enclosing)
            .binary_search_by_key(&place, |(p, _)| *p)
            .ok()?;
        Some(self.enclosing[at].1)
    }

    /// 1-based line and column of a finding, when it can be located in the source.
    pub(crate) fn line_col(&self, finding: &Finding) -> Option<(usize, usize)> {
        Some(self.lines.line_col(self.span(finding)?.start))
    }
}

/// Places each pointer not found (`NOWHERE` in `spans`) at its nearest ancestor that is
/// found, and lists those with their ancestor.
fn place_at_ancestors<'p>(
    text: &[u8],
    pointer: impl Fn(usize) -> &'p str,
    spans: &mut [[u32; 2]],
) -> Vec<(usize, &'p str)> {
    let missing: Vec<usize> = (0..spans.len()).filter(|&i| spans[i] == NOWHERE).collect();
    let ancestors = |pointer: &'p str| {
        std::iter::successors(Some(pointer), |p| p.rfind('/').map(|i| &p[..i])).skip(1)
    };
    let mut through: Vec<&str> = (missing.iter())
        .flat_map(|&i| ancestors(pointer(i)))
        .collect();
    through.sort_unstable();
    through.dedup();
    let found = json::locate_all(text, &through);
    let found_at = |ancestor: &str| found[through.binary_search(&ancestor).ok()?].clone();
    let mut enclosing = Vec::new();
    for i in missing {
        let nearest = ancestors(pointer(i)).find_map(|a| Some((a, found_at(a)?)));
        if let Some((ancestor, span)) = nearest {
            spans[i] = [span.start as u32, span.end as u32];
            enclosing.push((i, ancestor));
        }
    }
    enclosing
}

/// The annotations GitHub shows for one file: at most this many. GitHub shows ten of each kind
/// per step; a file's first errors and warnings are what a reviewer acts on.
pub const GITHUB_ANNOTATIONS_PER_FILE: usize = 10;

/// A report as GitHub Actions workflow commands: its errors and warnings (infos and hints too
/// with `all_findings`), errors first, at most [`GITHUB_ANNOTATIONS_PER_FILE`], then one
/// notice counting the rest, so the errors that matter are not drowned.
fn github(report: &Report, options: &Style, out: &mut dyn Write) -> std::io::Result<()> {
    let shown = |f: &Finding| {
        options.all_findings || matches!(f.severity, Severity::Error | Severity::Warning)
    };
    // The first annotated, most severe first then in report order, found without gathering
    // the 10^5 others: only they are located.
    let mut annotated: Vec<Finding> = Vec::new();
    for severity in Severity::ALL {
        let room = GITHUB_ANNOTATIONS_PER_FILE - annotated.len();
        let of_severity = report.diagnostics.iter().filter(|f| f.severity == severity);
        annotated.extend(of_severity.filter(shown).take(room));
    }
    let positions = Positions::of_those(report, |f| annotated.iter().any(|a| a.index == f.index));
    for f in &annotated {
        out.write_all(github_line(report, &positions, f).as_bytes())?;
    }
    let listed =
        |s: Severity| (report.diagnostics.iter()).filter(move |f| f.severity == s && shown(f));
    let rest_of = |s: Severity| {
        let annotated = annotated.iter().filter(|a| a.severity == s).count();
        listed(s).count() - annotated
    };
    let rest: usize = Severity::ALL.into_iter().map(rest_of).sum();
    if rest > 0 {
        writeln!(
            out,
            "::notice file={}::{rest} more finding(s) not annotated ({} error(s), {} warning(s)): `gltfmat check` lists them all",
            github_file(&report.uri),
            rest_of(Severity::Error),
            rest_of(Severity::Warning)
        )?;
    }
    Ok(())
}

/// A file name as a workflow command's property (its line breaks escaped by `printable`).
fn github_file(uri: &str) -> String {
    printable(uri)
        .replace('%', "%25")
        .replace(',', "%2C")
        .replace(':', "%3A")
}

fn github_line(report: &Report, positions: &Positions, d: &Finding) -> String {
    let level = match d.severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Info | Severity::Hint => "notice",
    };
    // A GLB is binary: a line and column of its JSON chunk mean nothing in a diff view.
    let glb = report.document.container == crate::document::Container::Glb;
    let position = (positions.line_col(d))
        .filter(|_| !glb)
        .map_or(String::new(), |(l, c)| format!(",line={l},col={c}"));
    // The pointer too: an asset's key may hold a line break, which would end the command.
    let message = format!("{}{}", d.message, location_suffix(d));
    format!(
        "::{level} file={}{position},title={}::{}\n",
        github_file(&report.uri),
        d.code,
        printable(&message).replace('%', "%25")
    )
}

fn location_suffix(f: &Finding) -> String {
    match f.location {
        Place::Pointer("") => String::new(),
        Place::Pointer(p) => format!(" ({p})"),
        Place::Offset(o) => format!(" (byte {o})"),
    }
}

/// Each finding's 1-based line and column in the asset's JSON text (of a GLB: in its JSON
/// chunk), in the report's order; `None` for a finding that lies in binary data.
pub fn line_columns(report: &Report) -> Vec<Option<(usize, usize)>> {
    let positions = Positions::of(report);
    (report.diagnostics.iter())
        .map(|f| positions.line_col(&f))
        .collect()
}

/// A report in the Khronos `validation.schema.json` shape.
pub fn khronos_report(report: &Report) -> KhronosReport<'_> {
    let info = &report.info;
    let mut info_map = Map::new();
    if let Some(v) = &info.version {
        info_map.insert("version".into(), json!(v));
    }
    if let Some(v) = &info.min_version {
        info_map.insert("minVersion".into(), json!(v));
    }
    if let Some(v) = &info.generator {
        info_map.insert("generator".into(), json!(v));
    }
    if !info.extensions_used.is_empty() {
        info_map.insert("extensionsUsed".into(), json!(info.extensions_used));
    }
    if !info.extensions_required.is_empty() {
        info_map.insert("extensionsRequired".into(), json!(info.extensions_required));
    }
    if !info.resources.is_empty() {
        let resources: Vec<Value> = info.resources.iter().map(resource_json).collect();
        info_map.insert("resources".into(), Value::Array(resources));
    }
    for (key, value) in &info.counts {
        let v = if key.starts_with("has") {
            json!(*value == 1)
        } else {
            json!(value)
        };
        info_map.insert((*key).into(), v);
    }
    KhronosReport {
        uri: &report.uri,
        mime_type: report.mime_type(),
        validator_version: concat!("gltfmat ", env!("CARGO_PKG_VERSION")),
        issues: Issues {
            num_errors: report.count(Severity::Error),
            num_warnings: report.count(Severity::Warning),
            num_infos: report.count(Severity::Info),
            num_hints: report.count(Severity::Hint),
            messages: Messages(&report.diagnostics),
            truncated: report.truncated,
        },
        info: report
            .document
            .root
            .is_some()
            .then_some(Value::Object(info_map)),
    }
}

/// A report in the Khronos validator's shape, written as it is serialised: its findings are
/// read from the report one at a time, never gathered into a JSON tree (which costs tens of
/// times the findings' own size).
#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
pub struct KhronosReport<'r> {
    uri: &'r str,
    mime_type: &'static str,
    validator_version: &'static str,
    issues: Issues<'r>,
    #[serde(skip_serializing_if = "Option::is_none")]
    info: Option<Value>,
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Issues<'r> {
    num_errors: usize,
    num_warnings: usize,
    num_infos: usize,
    num_hints: usize,
    messages: Messages<'r>,
    truncated: bool,
}

/// The findings, each serialised as it is reached.
struct Messages<'r>(&'r Findings);

impl Serialize for Messages<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.0.iter().map(Message::of))
    }
}

/// One finding as the Khronos validator writes it.
#[derive(Serialize)]
struct Message<'r> {
    code: &'r str,
    message: &'r str,
    severity: u8,
    #[serde(skip_serializing_if = "Option::is_none")]
    pointer: Option<&'r str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    offset: Option<u64>,
}

impl<'r> Message<'r> {
    fn of(d: Finding<'r>) -> Self {
        let (pointer, offset) = match d.location {
            Place::Pointer(p) => (Some(p), None),
            Place::Offset(o) => (None, Some(o)),
        };
        Message {
            code: d.code.name(),
            message: d.message,
            severity: d.severity as u8,
            pointer,
            offset,
        }
    }
}

fn resource_json(r: &crate::check::context::ResourceInfo) -> Value {
    let mut m = Map::new();
    m.insert("pointer".into(), json!(r.pointer));
    m.insert("storage".into(), json!(r.storage));
    if let Some(t) = &r.mime_type {
        m.insert("mimeType".into(), json!(t));
    }
    if let Some(n) = r.byte_length {
        m.insert("byteLength".into(), json!(n));
    }
    if let Some(u) = &r.uri {
        m.insert("uri".into(), json!(u));
    }
    if let Some(i) = &r.image {
        let transfer = match i.transfer {
            Some(crate::document::image_header::Transfer::Linear) => "linear",
            Some(crate::document::image_header::Transfer::Custom) => "custom",
            _ => "srgb",
        };
        m.insert(
            "image".into(),
            json!({"width": i.width, "height": i.height, "format": i.channels.name(), "primaries": "srgb", "transfer": transfer, "bits": i.bits}),
        );
    }
    Value::Object(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::{check_bytes, CheckOptions};
    use crate::document::uri::NoResources;
    use std::cell::Cell;

    /// A report that counts how many of its kind are alive.
    struct Counted<'c>(Report, &'c Cell<usize>);

    impl Drop for Counted<'_> {
        fn drop(&mut self) {
            self.1.set(self.1.get() - 1);
        }
    }

    impl Borrow<Report> for Counted<'_> {
        fn borrow(&self) -> &Report {
            &self.0
        }
    }

    #[test]
    fn each_report_is_written_and_dropped_before_the_next_is_made() {
        let text = br#"{"asset":{"version":"2.0"},"nodes":[{"rotation":[1,1,1,1]}]}"#;
        for format in [
            Format::Human,
            Format::Json,
            Format::Jsonl,
            Format::Sarif,
            Format::Github,
        ] {
            let (alive, most) = (Cell::new(0), Cell::new(0));
            let reports = (0..5).map(|i| {
                alive.set(alive.get() + 1);
                most.set(most.get().max(alive.get()));
                let report = check_bytes(
                    &format!("{i}.gltf"),
                    &text[..],
                    &NoResources,
                    &CheckOptions::default(),
                );
                Counted(report, &alive)
            });
            let mut out = Vec::new();
            write_each(
                format,
                reports,
                &Style::new(false).with_list(true),
                &mut out,
            )
            .unwrap();
            assert_eq!(most.get(), 1, "{format:?}: reports held at once");
            let text = String::from_utf8(out).unwrap();
            assert!(
                text.contains("4.gltf"),
                "{format:?}: every report written: {text}"
            );
        }
    }
}
