//! The registry of every code gltfmat can emit: the Khronos catalogue plus gltfmat's own rules.
//! `gltfmat rules`, `gltfmat explain` and the SARIF rule list are generated from it.

pub use super::code_info::{CodeInfo, Origin};
pub use super::rules::{is_opt_in, OPT_IN_GROUPS};
use crate::diagnostic::{khronos, khronos_words, Severity};

impl CodeInfo {
    /// The code's default severity.
    pub fn severity(&self) -> Severity {
        self.code.default_severity()
    }

    /// One sentence saying what the code reports, without the message's placeholders: for
    /// headings such as SARIF's descriptions. A gltfmat rule's summary; a Khronos code's
    /// meaning in words ([`khronos_words`]).
    pub fn description(&self) -> String {
        match (self.origin, khronos_words::of(self.code.name())) {
            (Origin::Khronos, Some(words)) => words.meaning.to_string(),
            _ => self.summary.to_string(),
        }
    }

    /// The documentation as Markdown: a gltfmat rule's own; for a Khronos code, what it
    /// means, why it matters and how to fix it, the validator's message with its values left
    /// out, and how the default profile differs.
    pub fn help_markdown(&self) -> String {
        let words = khronos_words::of(self.code.name());
        let (Origin::Khronos, Some(words)) = (self.origin, words) else {
            return self.doc.to_string();
        };
        let message = without_placeholders(self.summary);
        let message = match message.chars().filter(|c| c.is_alphabetic()).count() {
            0..8 => "Its message gives the details.".to_string(),
            _ => format!(
                "Its message names the values found: \"{}\"",
                message.trim_end()
            ),
        };
        let mut help = format!(
            "**{}**\n\n{}\n\nA check of the Khronos glTF-Validator ({} group). {message} See the validator's [list of issues]({KHRONOS_ISSUES}).",
            words.meaning, words.advice, self.group,
        );
        if let Some(why) = supersession(self.code.name()) {
            help.push_str(&format!("\n\nIn gltfmat's default profile: {why}"));
        }
        help
    }
}

/// Where the Khronos validator documents its codes.
pub const KHRONOS_ISSUES: &str =
    "https://github.com/KhronosGroup/glTF-Validator/blob/main/ISSUES.md";

/// A message template with each placeholder (`%1`, `%a`, quoted or not, or a list of them)
/// replaced by "(…)".
fn without_placeholders(template: &str) -> String {
    let mut out = String::new();
    let mut chars = template.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '%' && chars.peek().is_some_and(|n| n.is_ascii_alphanumeric()) {
            chars.next();
            out.push_str("(…)");
        } else {
            out.push(c);
        }
    }
    for quoted in ["('(…)', '(…)', '(…)')", "'(…)'", "((…))"] {
        out = out.replace(quoted, "(…)");
    }
    out
}

const fn from_catalogue(entry: &khronos::Entry) -> CodeInfo {
    CodeInfo {
        code: entry.code,
        group: entry.group,
        summary: entry.template,
        doc: "",
        origin: Origin::Khronos,
        own_logic: false,
    }
}

/// Every code, Khronos ones first.
pub fn all() -> impl Iterator<Item = CodeInfo> {
    khronos::CATALOGUE
        .iter()
        .map(from_catalogue)
        .chain(super::rules::RULES.iter().map(|rule| rule.info))
}

/// The registered code named `code` (case-insensitive).
pub fn find(code: &str) -> Option<CodeInfo> {
    all().find(|info| info.code.name().eq_ignore_ascii_case(code))
}

/// Whether `group` names the group of one of gltfmat's rules (case-insensitive).
pub fn is_rule_group(group: &str) -> bool {
    super::rules::RULES
        .iter()
        .any(|rule| rule.info.group.eq_ignore_ascii_case(group))
}

/// Why the default profile reports a Khronos code differently, when it does (see
/// `check::profile`).
pub fn supersession(code: &str) -> Option<&'static str> {
    super::profile::why_different(code)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn codes_are_unique() {
        let mut seen = HashSet::new();
        for info in all() {
            assert!(
                seen.insert(info.code.name()),
                "{} is registered twice",
                info.code
            );
        }
    }

    #[test]
    fn every_gltfmat_rule_is_documented() {
        for info in all().filter(|i| i.origin == Origin::Gltfmat) {
            for heading in ["What it does", "Why", "Example"] {
                assert!(
                    info.doc.contains(heading),
                    "{} lacks '{heading}'",
                    info.code
                );
            }
        }
    }

    /// `explain`, `rules` and SARIF's rule descriptions and help all come from these two.
    #[test]
    fn every_code_is_explained_in_words_without_placeholders() {
        let placeholder = regex::Regex::new(r"%[0-9a-z]").unwrap();
        for info in all() {
            let (description, help) = (info.description(), info.help_markdown());
            for text in [&description, &help] {
                assert!(!placeholder.is_match(text), "{}: {text}", info.code);
            }
            assert!(description.len() > 20, "{}: {description}", info.code);
            assert!(
                help.len() > description.len() + 40,
                "{}: no help beyond the description",
                info.code
            );
        }
    }
}
