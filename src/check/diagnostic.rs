//! One finding: a code, a severity, a message and where it is.

use serde::Serialize;

/// Severity levels, numbered as in the Khronos report format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Severity {
    Error = 0,
    Warning = 1,
    Info = 2,
    Hint = 3,
}

impl Severity {
    pub fn name(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Info => "info",
            Severity::Hint => "hint",
        }
    }

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

/// Where a diagnostic points: a JSON pointer into the document, or a byte offset in a GLB.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Location {
    Pointer(String),
    Offset(u64),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub code: &'static str,
    pub severity: Severity,
    pub message: String,
    pub location: Location,
    /// A byte offset into the JSON text when the pointer cannot say it (syntax errors).
    pub span_hint: Option<usize>,
}

impl Diagnostic {
    /// A diagnostic with the code's default severity from the registry.
    pub fn new(code: &'static str, location: Location, message: impl Into<String>) -> Self {
        Diagnostic {
            code,
            severity: super::codes::default_severity(code),
            message: message.into(),
            location,
            span_hint: None,
        }
    }

    pub fn at(code: &'static str, pointer: impl Into<String>, message: impl Into<String>) -> Self {
        Self::new(code, Location::Pointer(pointer.into()), message)
    }

    pub fn pointer(&self) -> Option<&str> {
        match &self.location {
            Location::Pointer(p) => Some(p),
            Location::Offset(_) => None,
        }
    }
}
