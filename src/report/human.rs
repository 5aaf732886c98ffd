//! Human output: `path:line:col: severity[CODE]: message`, then the source line with a caret.

use super::{location_suffix, Positions};
use crate::check::{Report, Severity};
use crate::document::json::LineIndex;

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

pub fn render(reports: &[Report], colour: bool) -> String {
    let mut out = String::new();
    for report in reports {
        let positions = Positions::of(report);
        for d in &report.diagnostics {
            let position = match positions.line_col(d) {
                Some((l, c)) => format!("{}:{l}:{c}", report.uri),
                None => report.uri.clone(),
            };
            let label = paint(
                &format!("{}[{}]", d.severity.name(), d.code),
                severity_colour(d.severity),
                colour,
            );
            out.push_str(&format!(
                "{position}: {label}: {}{}\n",
                d.message,
                location_suffix(d)
            ));
            if let Some(range) = positions.span(d) {
                out.push_str(&snippet(&positions.lines, range.start, colour));
            }
        }
        out.push_str(&summary(report));
    }
    out
}

/// The source line holding `offset`, with a caret under the column.
fn snippet(lines: &LineIndex, offset: usize, colour: bool) -> String {
    let (line_no, column) = lines.line_col(offset);
    let line = lines.line(line_no);
    if line.len() > 200 {
        return String::new();
    }
    let line = String::from_utf8_lossy(line);
    let gutter = format!("{line_no:>5} | ");
    let pad: String = " ".repeat(gutter.len() - 2);
    format!(
        "{gutter}{}\n{pad}| {}{}\n",
        line.trim_end(),
        " ".repeat(column - 1),
        paint("^", "1;31", colour)
    )
}

fn summary(report: &Report) -> String {
    format!(
        "{}: {} error(s), {} warning(s), {} info(s), {} hint(s){}\n",
        report.uri,
        report.count(Severity::Error),
        report.count(Severity::Warning),
        report.count(Severity::Info),
        report.count(Severity::Hint),
        if report.truncated { " (truncated)" } else { "" }
    )
}
