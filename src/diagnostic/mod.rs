//! The bottom layer: one finding is a [`Code`], a [`Severity`], a message and a [`Location`].
//! Nothing here knows the validator, the terminal or the rule registry.

mod findings;
pub mod khronos;
pub mod khronos_words;

pub use findings::{Finding, Findings, Place};
use serde::Serialize;
use std::borrow::Cow;
use std::fmt;

/// Severity levels, numbered as in the Khronos report format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Severity {
    /// The asset is invalid.
    Error = 0,
    /// The asset is valid but probably not what its author meant.
    Warning = 1,
    /// Worth knowing; nothing is wrong.
    Info = 2,
    /// A suggestion.
    Hint = 3,
}

impl Severity {
    /// Every severity, most severe first.
    pub const ALL: [Severity; 4] = [
        Severity::Error,
        Severity::Warning,
        Severity::Info,
        Severity::Hint,
    ];

    /// The lower-case name used in reports and configuration.
    pub fn name(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Info => "info",
            Severity::Hint => "hint",
        }
    }

    /// Reads a name or the Khronos number (`error`, `1`, `information`, …).
    pub fn parse(text: &str) -> Option<Severity> {
        match text.to_ascii_lowercase().as_str() {
            "error" | "0" => Some(Severity::Error),
            "warning" | "1" => Some(Severity::Warning),
            "info" | "information" | "2" => Some(Severity::Info),
            "hint" | "3" => Some(Severity::Hint),
            _ => None,
        }
    }
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An issue code with its default severity. Codes are constants ([`khronos`] and each rule's
/// `RULE.code()`), so a misspelt code is a compile error rather than a silent new code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Code {
    name: &'static str,
    severity: Severity,
}

impl Code {
    /// A code named `name` whose default severity is `severity`.
    pub const fn new(name: &'static str, severity: Severity) -> Code {
        Code { name, severity }
    }

    /// The code as reports spell it, e.g. `ACCESSOR_TOO_LONG`.
    pub const fn name(self) -> &'static str {
        self.name
    }

    /// The severity the code has unless a profile or the user overrides it.
    pub const fn default_severity(self) -> Severity {
        self.severity
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)
    }
}

impl PartialEq<&str> for Code {
    fn eq(&self, other: &&str) -> bool {
        self.name == *other
    }
}

impl PartialEq<str> for Code {
    fn eq(&self, other: &str) -> bool {
        self.name == other
    }
}

impl Serialize for Code {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name)
    }
}

/// Where a diagnostic points: a JSON pointer into the document, or a byte offset in a GLB.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Location {
    /// An RFC 6901 JSON pointer into the glTF JSON (`""` is the root).
    Pointer(String),
    /// A byte offset in the file (GLB container findings).
    Offset(u64),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Pointer(pointer) if pointer.is_empty() => f.write_str("/"),
            Location::Pointer(pointer) => f.write_str(pointer),
            Location::Offset(offset) => write!(f, "byte {offset}"),
        }
    }
}

/// One finding.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// What was found.
    pub code: Code,
    /// The code's default severity until the check's collector, the one place that decides
    /// it, stamps the severity of the code the profile reports (or the user's override).
    pub severity: Severity,
    /// A sentence for a person: most are fixed texts, held without a copy of their own
    /// (a file of 10^6 alike findings holds 10^6 messages).
    pub message: Cow<'static, str>,
    /// Where it was found.
    pub location: Location,
    /// A byte offset into the JSON text when the pointer cannot say it (syntax errors).
    pub span_hint: Option<usize>,
}

impl Diagnostic {
    /// A diagnostic at `location` with the code's default severity.
    pub fn new(code: Code, location: Location, message: impl Into<Cow<'static, str>>) -> Self {
        Diagnostic {
            code,
            severity: code.default_severity(),
            message: message.into(),
            location,
            span_hint: None,
        }
    }

    /// A diagnostic at a JSON pointer.
    pub fn at(
        code: Code,
        pointer: impl Into<String>,
        message: impl Into<Cow<'static, str>>,
    ) -> Self {
        Self::new(code, Location::Pointer(pointer.into()), message)
    }

    /// The JSON pointer, when the location is one.
    pub fn pointer(&self) -> Option<&str> {
        match &self.location {
            Location::Pointer(p) => Some(p),
            Location::Offset(_) => None,
        }
    }
}

/// Where findings go as they are made. A checker's sink may filter, count and bound them
/// (see `check`'s collector), so that memory stays bounded however many a file holds; a
/// `Vec` keeps them all.
pub trait Sink {
    /// Takes one finding.
    fn push(&mut self, diagnostic: Diagnostic);
}

impl Sink for Vec<Diagnostic> {
    fn push(&mut self, diagnostic: Diagnostic) {
        Vec::push(self, diagnostic);
    }
}
