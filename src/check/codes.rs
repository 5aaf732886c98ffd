//! The registry of every code gltfmat can emit: the Khronos catalogue plus gltfmat's own rules.
//! `gltfmat rules`, `gltfmat explain` and the SARIF rule list are generated from it.

pub use super::diagnostic::Severity;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    /// A Khronos glTF-Validator code, emitted with the same meaning.
    Khronos,
    /// A gltfmat rule (not emitted in `--profile khronos`).
    Gltfmat,
}

#[derive(Debug, Clone, Copy)]
pub struct CodeInfo {
    pub code: &'static str,
    pub severity: Severity,
    pub group: &'static str,
    /// One line: the Khronos message template, or the rule's summary.
    pub summary: &'static str,
    /// The full documentation (What it does / Why / Example), for gltfmat rules.
    pub doc: &'static str,
    pub origin: Origin,
}

/// Every code, Khronos ones first.
pub fn all() -> impl Iterator<Item = &'static CodeInfo> {
    super::khronos_codes::KHRONOS_CODES
        .iter()
        .chain(super::rules::RULES.iter().map(|rule| &rule.info))
}

pub fn find(code: &str) -> Option<&'static CodeInfo> {
    all().find(|info| info.code.eq_ignore_ascii_case(code))
}

/// The registered default severity; an unregistered code is a programming error that the
/// registry test catches, and reports as an error meanwhile.
pub fn default_severity(code: &str) -> Severity {
    find(code).map_or(Severity::Error, |info| info.severity)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    #[test]
    fn codes_are_unique() {
        let mut seen = HashSet::new();
        for info in all() {
            assert!(seen.insert(info.code), "{} is registered twice", info.code);
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

    #[test]
    fn every_code_used_in_the_source_is_registered() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
        let mut stack = vec![std::path::PathBuf::from(root)];
        let mut missing = Vec::new();
        while let Some(path) = stack.pop() {
            if path.is_dir() {
                stack.extend(std::fs::read_dir(&path).unwrap().map(|e| e.unwrap().path()));
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            for piece in text.split('"').skip(1).step_by(2) {
                let looks_like_code = piece.len() > 6
                    && piece.contains('_')
                    && piece
                        .chars()
                        .all(|c| c.is_ascii_uppercase() || c == '_' || c.is_ascii_digit())
                    && !piece.starts_with("KHR_")
                    && !piece.starts_with("EXT_")
                    && !piece.starts_with("TEXCOORD_")
                    && !piece.starts_with("JOINTS_")
                    && !piece.starts_with("WEIGHTS_")
                    && !piece.starts_with("COLOR_")
                    && !piece.starts_with('_') // application-specific attribute names
                    && !matches!(
                        piece,
                        "ARRAY_BUFFER"
                            | "ELEMENT_ARRAY_BUFFER"
                            | "NO_COLOR"
                            | "CARGO_MANIFEST_DIR"
                            | "CARGO_PKG_VERSION"
                            | "MIRRORED_REPEAT"
                            | "CLAMP_TO_EDGE"
                            | "TRIANGLE_STRIP"
                            | "TRIANGLE_FAN"
                            | "LINE_LOOP"
                            | "LINE_STRIP"
                            | "UNSIGNED_BYTE"
                            | "UNSIGNED_SHORT"
                            | "UNSIGNED_INT"
                            | "GITHUB_ACTIONS"
                            | "FRAUNHOFER_materials_pbr"
                            | "WEB3D_materials_pbr"
                    );
                if looks_like_code && find(piece).is_none() {
                    missing.push(format!("{}: {piece}", path.display()));
                }
            }
        }
        assert!(missing.is_empty(), "unregistered codes: {missing:#?}");
    }
}
