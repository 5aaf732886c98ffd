//! What the registry holds for each code. The rules' table is written in these terms, and
//! the registry (which reads that table) gives them their methods: kept apart from both so
//! that neither imports the other's file back.

use crate::diagnostic::Code;

/// Who defines a code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    /// A Khronos glTF-Validator code, emitted with the same meaning.
    Khronos,
    /// A gltfmat rule (not emitted in `--profile khronos`).
    Gltfmat,
}

/// What the registry knows of one code.
#[derive(Debug, Clone, Copy)]
pub struct CodeInfo {
    /// The code and its default severity.
    pub code: Code,
    /// The Khronos group, or the gltfmat rule group (`materials`, `plausibility`, …).
    pub group: &'static str,
    /// One line: the Khronos message template, or the rule's summary.
    pub summary: &'static str,
    /// The full documentation (What it does / Why / Example), for gltfmat rules.
    pub doc: &'static str,
    /// Who defines it.
    pub origin: Origin,
    /// A gltfmat rule with checks of its own (not only emitted by a core pass, like
    /// JSON_DUPLICATE_KEY by the JSON reader).
    pub own_logic: bool,
}
