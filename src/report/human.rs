//! Human output: `path:line:col: severity[CODE]: message`, then the source line with a caret.
//! Errors come first, then warnings, each in file order; infos and hints, which real
//! exporters' files carry by the dozen, are counted in the summary unless asked for.

use super::{location_suffix, printable, Positions, Style};
use crate::check::{Finding, Place, Report, Severity};
use crate::document::json::LineIndex;
use crate::document::Container;
use std::borrow::Borrow;
use std::io::Write;

fn paint(text: &str, code: &str, colour: bool) -> String {
    if colour {
        format!("\x1b[{code}m{text}\x1b[0m")
    } else {
        text.to_string()
    }
}

fn severity_colour(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "1;31",
        Severity::Warning => "1;33",
        Severity::Info => "1;36",
        Severity::Hint => "1;32",
    }
}

/// Whether a finding of `severity` gets its own lines.
fn listed(severity: Severity, style: &Style) -> bool {
    style.all_findings || matches!(severity, Severity::Error | Severity::Warning)
}

/// Each report's findings and summary as it comes, then the total over all of them. In a list
/// (a folder), a file with nothing listed prints nothing unless `verbose`: a folder of clean
/// files is one line, as ruff and clippy print it.
pub(super) fn write<R: Borrow<Report>>(
    reports: impl Iterator<Item = R>,
    style: &Style,
    out: &mut dyn Write,
) -> std::io::Result<()> {
    let mut total = Total::default();
    for report in reports {
        let report = report.borrow();
        let quiet = style.list
            && !style.verbose
            && !report.diagnostics.iter().any(|d| listed(d.severity, style));
        if !quiet {
            write_one(report, style, out)?;
        }
        total.add(report);
    }
    if total.files > 1 || (style.list && total.files == 1) {
        out.write_all(total.line().as_bytes())?;
    }
    Ok(())
}

/// How many findings of one code a file shows in full before the rest are counted in one
/// line (unless `--all-findings`): an asset's 2,098 non-increasing animation inputs are one
/// mistake, and four lines each would bury every other finding.
pub(super) const SHOWN_PER_CODE: usize = 3;

/// One report's findings, each written as it is rendered (10^6 of them are never one string).
fn write_one(report: &Report, style: &Style, out: &mut dyn Write) -> std::io::Result<()> {
    let positions = Positions::of_those(report, |d| listed(d.severity, style));
    // Per code, in the order codes first come: how many were shown and hidden, and the first
    // distinct places of the hidden ones (one more than are named, to know whether to say so).
    let mut per_code: Vec<Grouped> = Vec::new();
    for d in in_reading_order(report, &positions, style) {
        let code = d.code.name();
        let at = match per_code.iter().position(|g| g.code == code) {
            Some(at) => at,
            None => {
                per_code.push(Grouped {
                    code,
                    ..Grouped::default()
                });
                per_code.len() - 1
            }
        };
        let group = &mut per_code[at];
        if style.all_findings || group.shown < SHOWN_PER_CODE {
            group.shown += 1;
            out.write_all(finding(report, &positions, &d, style.colour).as_bytes())?;
            continue;
        }
        group.hidden += 1;
        if group.places.len() <= SHOWN_PER_CODE {
            let place = place(report, &positions, &d);
            if !group.places.contains(&place) {
                group.places.push(place);
            }
        }
    }
    for group in per_code.iter().filter(|g| g.hidden > 0) {
        let named = &group.places[..group.places.len().min(SHOWN_PER_CODE)];
        let more = if group.places.len() > SHOWN_PER_CODE {
            ", …"
        } else {
            ""
        };
        writeln!(
            out,
            "{}: {} more {} finding(s), at {}{more} (--all-findings lists them)",
            printable(&report.uri),
            group.hidden,
            group.code,
            named.join(", "),
        )?;
    }
    out.write_all(summary(report, style).as_bytes())
}

/// The findings of one code in one file's human report.
#[derive(Default)]
struct Grouped<'r> {
    code: &'r str,
    shown: usize,
    hidden: usize,
    /// The first distinct places of the hidden ones, at most one more than are named.
    places: Vec<String>,
}

/// Where a finding is, shortly: its line and column, or its pointer or byte.
fn place(report: &Report, positions: &Positions, d: &Finding) -> String {
    match (positions.line_col(d), d.location) {
        (Some((l, c)), _) if report.document.container != Container::Glb => format!("{l}:{c}"),
        (_, Place::Pointer(p)) => printable(p).into_owned(),
        (_, Place::Offset(o)) => format!("byte {o}"),
    }
}

/// The listed findings by severity, then place in the text; findings without a place in the
/// text (GLB container offsets, the whole file) after those that have one, in report order.
/// Sorted as one 128-bit key each (severity, whether placed, byte offset — which orders as
/// line and column do — and index), each finding read again as it is written.
fn in_reading_order<'r>(
    report: &'r Report,
    positions: &Positions,
    style: &Style,
) -> impl Iterator<Item = Finding<'r>> {
    let mut order: Vec<u128> = (report.diagnostics.iter())
        .filter(|d| listed(d.severity, style))
        .map(|d| {
            let at = positions.span(&d).map(|s| s.start as u64);
            (d.severity as u128) << 100
                | u128::from(at.is_none()) << 96
                | u128::from(at.unwrap_or(0) as u32) << 64
                | d.index as u128
        })
        .collect();
    order.sort_unstable();
    (order.into_iter()).filter_map(|key| report.diagnostics.get(key as u64 as usize))
}

fn finding(report: &Report, positions: &Positions, d: &Finding, colour: bool) -> String {
    let span = positions.span(d);
    let line_col = span.as_ref().map(|s| positions.lines.line_col(s.start));
    let position = match line_col {
        Some((l, c)) => format!("{}:{l}:{c}", printable(&report.uri)),
        None => printable(&report.uri).into_owned(),
    };
    let label = paint(
        &format!("{}[{}]", d.severity.name(), d.code),
        severity_colour(d.severity),
        colour,
    );
    let told = format!(
        "{}{}{}",
        d.message,
        location_suffix(d),
        image_named(report, d)
    );
    let mut out = format!("{position}: {label}: {}\n", printable(&told));
    if let (Some(range), Some((line, _))) = (span, line_col) {
        let byte = (report.document.container == Container::Glb
            && matches!(d.location, Place::Pointer(_)))
        .then(|| positions.text_start + range.start);
        out.push_str(&notes(positions.shown_at(d), byte));
        out.push_str(&snippet(&positions.lines, line, range.start, colour));
    } else if let Place::Offset(offset) = d.location {
        out.push_str(&hex_snippet(
            &report.document.bytes,
            offset as usize,
            colour,
        ));
    }
    out
}

/// For a finding on an image (`/images/N…`), the image's URI or name, which says more than
/// its index to a person looking at the asset's files; a data URI is shown by its media type.
fn image_named(report: &Report, d: &Finding) -> String {
    let Place::Pointer(pointer) = d.location else {
        return String::new();
    };
    let Some(index) = (pointer.strip_prefix("/images/"))
        .and_then(|rest| rest.split('/').next())
        .filter(|i| i.bytes().all(|b| b.is_ascii_digit()))
    else {
        return String::new();
    };
    let image = (report.document.root.as_ref())
        .and_then(|tree| tree.root().pointer(&format!("/images/{index}")));
    let text = |key: &str| image.and_then(|i| i.get(key)).and_then(|v| v.as_str());
    match (text("uri"), text("name")) {
        (Some(uri), _) if uri.starts_with("data:") => {
            let media = uri[5..].split([';', ',']).next().unwrap_or_default();
            format!(" [image {index}: an embedded {media}]")
        }
        (Some(uri), _) => format!(" [image {index}: {uri}]"),
        (None, Some(name)) => format!(" [image {index}: '{name}']"),
        (None, None) => String::new(),
    }
}

/// Bytes shown on each side of an offset in a binary container.
const HEX_WINDOW: usize = 8;

/// The file's bytes around `offset` (a GLB header or chunk finding), in hex with their
/// printable characters, and a caret under the byte.
fn hex_snippet(bytes: &[u8], offset: usize, colour: bool) -> String {
    let from = offset.saturating_sub(HEX_WINDOW).min(bytes.len());
    let to = (offset + HEX_WINDOW).min(bytes.len());
    let shown = &bytes[from..to];
    let hex: Vec<String> = shown.iter().map(|b| format!("{b:02x}")).collect();
    let text: String = (shown.iter())
        .map(|&b| if b.is_ascii_graphic() { b as char } else { '.' })
        .collect();
    let gutter = format!("{from:>8} | ");
    let caret_at = 3 * (offset.min(to) - from);
    format!(
        "{gutter}{}  {text}\n{}| {}{}\n",
        hex.join(" "),
        " ".repeat(gutter.len() - 2),
        " ".repeat(caret_at),
        paint("^", "1;31", colour)
    )
}

/// Where a finding is shown when that needs saying: at an enclosing value (its own member
/// is not written), and at which byte of a GLB.
fn notes(shown_at: Option<&str>, byte: Option<usize>) -> String {
    let mut out = String::new();
    if let Some(ancestor) = shown_at {
        let ancestor = if ancestor.is_empty() { "/" } else { ancestor };
        out.push_str(&format!(
            "      = not written (its default applies); shown at {ancestor}\n"
        ));
    }
    if let Some(byte) = byte {
        out.push_str(&format!("      = byte {byte} of the file (JSON chunk)\n"));
    }
    out
}

/// Characters of a long line shown on each side of the column.
const WINDOW: usize = 60;

/// Line `line_no`, which holds `offset`, with a caret under the column. A long line (minified
/// JSON, a GLB's JSON chunk) is cut to a window around the column; tabs before the column are
/// repeated under it, so the caret lands where the terminal draws the character.
fn snippet(lines: &LineIndex, line_no: usize, offset: usize, colour: bool) -> String {
    let line = lines.line(line_no);
    let at = offset
        .saturating_sub(lines.line_start(line_no))
        .min(line.len());
    // Only a window of bytes around the column is decoded: a minified file is one line, and
    // decoding all of it for each finding made reports quadratic in the file's size.
    // A character is at most 4 bytes. The window is snapped to character starts, but never
    // past the column (invalid UTF-8 has no starts).
    let reach = 4 * WINDOW;
    let from_byte = char_boundary(line, at.saturating_sub(reach)).min(at);
    let to_byte = char_boundary(line, (at + reach).min(line.len())).max(at);
    let before: Vec<char> = String::from_utf8_lossy(&line[from_byte..at])
        .chars()
        .collect();
    let after_text = String::from_utf8_lossy(&line[at..to_byte]);
    let after_text = if to_byte == line.len() {
        after_text.trim_end()
    } else {
        &after_text
    };
    let after: Vec<char> = after_text.chars().collect();
    let shown_before = &before[before.len().saturating_sub(WINDOW)..];
    let shown_after = &after[..after.len().min(WINDOW)];
    let lead = if from_byte > 0 || shown_before.len() < before.len() {
        "…"
    } else {
        ""
    };
    let tail = if to_byte < line.len() || shown_after.len() < after.len() {
        "…"
    } else {
        ""
    };
    // The file's own bytes, shown as text may be shown (see `printable`); the caret's pad is
    // as wide as what is shown before it.
    let shown_char = |&c: &char| printable(c.encode_utf8(&mut [0; 4])).into_owned();
    let shown: String = shown_before
        .iter()
        .chain(shown_after)
        .map(shown_char)
        .collect();
    let pad: String = (shown_before.iter())
        .map(|c| match c {
            '\t' => "\t".to_string(),
            _ => " ".repeat(shown_char(c).chars().count()),
        })
        .collect();
    let gutter = format!("{line_no:>5} | ");
    let blank = " ".repeat(gutter.len() - 2);
    format!(
        "{gutter}{lead}{shown}{tail}\n{blank}| {}{pad}{}\n",
        " ".repeat(lead.chars().count()),
        paint("^", "1;31", colour)
    )
}

/// The nearest UTF-8 character start at or after `at` (so a window never splits a character).
fn char_boundary(bytes: &[u8], mut at: usize) -> usize {
    while at < bytes.len() && (bytes[at] & 0b1100_0000) == 0b1000_0000 {
        at += 1;
    }
    at
}

fn summary(report: &Report, style: &Style) -> String {
    let hidden = [Severity::Info, Severity::Hint]
        .iter()
        .any(|&s| !listed(s, style) && report.count(s) > 0);
    format!(
        "{}: {} error(s), {} warning(s), {} info(s), {} hint(s){}{}\n",
        printable(&report.uri),
        report.count(Severity::Error),
        report.count(Severity::Warning),
        report.count(Severity::Info),
        report.count(Severity::Hint),
        if hidden {
            " (infos and hints not listed: --all-findings lists them)"
        } else {
            ""
        },
        if report.truncated { " (truncated)" } else { "" }
    )
}

/// What the closing line of several reports counts.
#[derive(Default)]
struct Total {
    files: usize,
    with_errors: usize,
    counts: [usize; 4],
}

const SEVERITIES: [Severity; 4] = [
    Severity::Error,
    Severity::Warning,
    Severity::Info,
    Severity::Hint,
];

impl Total {
    fn add(&mut self, report: &Report) {
        self.files += 1;
        self.with_errors += usize::from(report.has_errors());
        for (count, severity) in self.counts.iter_mut().zip(SEVERITIES) {
            *count += report.count(severity);
        }
    }

    fn line(&self) -> String {
        let [errors, warnings, infos, hints] = self.counts;
        format!(
            "{} file(s) checked, {} with errors: {errors} error(s), {warnings} warning(s), {infos} info(s), {hints} hint(s)\n",
            self.files, self.with_errors,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_snippet_of_invalid_utf8_keeps_its_caret_at_the_column() {
        // Continuation bytes with no character start: the window cannot snap past the column.
        let text = b"\x80\x80\x80abc";
        for offset in 0..text.len() {
            let lines = LineIndex::new(text);
            let shown = snippet(&lines, lines.line_col(offset).0, offset, false);
            assert_eq!(shown.lines().count(), 2, "{shown}");
            assert!(shown.lines().nth(1).unwrap().ends_with('^'), "{shown}");
        }
    }
    use crate::check::{check_bytes, CheckOptions};
    use crate::diagnostic::khronos;
    use crate::document::uri::NoResources;

    /// The report of `text` with exactly `findings` (code, pointer), replacing what the check
    /// found, so that each case shows one rendering rule.
    fn report_with(text: &str, findings: &[(crate::diagnostic::Code, &str)]) -> Report {
        let mut report = check_bytes(
            "a.gltf",
            text.as_bytes().to_vec(),
            &NoResources,
            &CheckOptions::default(),
        );
        report.diagnostics = (findings.iter())
            .map(|(code, pointer)| crate::check::Diagnostic::at(*code, *pointer, "m."))
            .collect();
        report
    }

    fn plain(report: &Report, all: bool) -> String {
        let mut out = Vec::new();
        write_one(report, &Style::new(false).with_all_findings(all), &mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn errors_come_first_then_warnings_each_in_file_order() {
        let text = "{\n\"asset\": {\"version\": \"2.0\"},\n\"nodes\": [{}, {}]\n}";
        let report = report_with(
            text,
            &[
                (khronos::NODE_SKINNED_MESH_LOCAL_TRANSFORMS, "/nodes/1"),
                (khronos::NODE_SKINNED_MESH_LOCAL_TRANSFORMS, "/nodes/0"),
                (khronos::UNDEFINED_PROPERTY, "/asset"),
                (khronos::UNDEFINED_PROPERTY, "/nodes"),
            ],
        );
        let out = plain(&report, false);
        let heads: Vec<&str> = (out.lines())
            .filter(|l| l.contains("]: m."))
            .map(|l| l.split(": ").next().unwrap())
            .collect();
        // UNDEFINED_PROPERTY is an error, the other a warning; a finding is placed at its
        // member's name.
        assert_eq!(
            heads,
            ["a.gltf:2:1", "a.gltf:3:1", "a.gltf:3:11", "a.gltf:3:15"]
        );
    }

    #[test]
    fn infos_and_hints_are_counted_not_listed_unless_asked() {
        let text = r#"{"asset": {"version": "2.0"}, "nodes": [{}]}"#;
        let report = report_with(text, &[(khronos::NODE_EMPTY, "/nodes/0")]);
        assert!(!plain(&report, false).contains("NODE_EMPTY"));
        assert!(plain(&report, true).contains("info[NODE_EMPTY]"));
    }

    #[test]
    fn a_member_that_is_not_written_is_shown_at_its_nearest_enclosing_value() {
        let text = "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"materials\": [{\"pbrMetallicRoughness\": {}}]\n}";
        let report = report_with(
            text,
            &[(
                khronos::UNDEFINED_PROPERTY,
                "/materials/0/pbrMetallicRoughness/baseColorFactor",
            )],
        );
        let out = plain(&report, false);
        assert!(out.starts_with("a.gltf:3:18: "), "{out}");
        assert!(
            out.contains(
                "not written (its default applies); shown at /materials/0/pbrMetallicRoughness"
            ),
            "{out}"
        );
    }

    #[test]
    fn the_caret_follows_tabs_and_long_lines_are_windowed() {
        let text = "{\n\t\t\"asset\": {\"version\": \"2.0\"}\n}";
        let out = plain(
            &report_with(text, &[(khronos::UNDEFINED_PROPERTY, "/asset")]),
            false,
        );
        assert!(out.contains("\n      | \t\t^"), "{out}");

        let padding = format!("\"{}\"", "x".repeat(500));
        let text =
            format!(r#"{{"extras": {padding}, "asset": {{"version": "2.0"}}, "more": {padding}}}"#);
        let out = plain(
            &report_with(&text, &[(khronos::UNDEFINED_PROPERTY, "/asset")]),
            false,
        );
        let lines: Vec<&str> = out.lines().collect();
        assert!(
            lines[1].starts_with("    1 | …") && lines[1].ends_with('…'),
            "{out}"
        );
        let caret = lines[2].find('^').unwrap();
        let under: String = lines[1].chars().skip(caret).take(7).collect();
        assert_eq!(under, "\"asset\"", "{out}");
    }

    #[test]
    fn a_finding_at_a_byte_of_a_glb_shows_the_bytes_around_it() {
        let mut glb = b"glTF".to_vec();
        glb.extend_from_slice(&2u32.to_le_bytes());
        glb.extend_from_slice(&100u32.to_le_bytes());
        let report = check_bytes("a.glb", glb, &NoResources, &CheckOptions::default());
        let out = plain(&report, false);
        let lines: Vec<&str> = out.lines().collect();
        assert!(
            lines[0].starts_with("a.glb: error[GLB_LENGTH_MISMATCH]: ")
                && lines[0].ends_with("(byte 12)"),
            "{out}"
        );
        assert_eq!(
            lines[1], "       4 | 02 00 00 00 64 00 00 00  ....d...",
            "{out}"
        );
        assert_eq!(lines[2], "         |                         ^", "{out}");
    }
}
