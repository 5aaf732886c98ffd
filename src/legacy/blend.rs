//! How a glTF 1.0 material blends and culls, read from its technique's states and
//! KHR_materials_common.

use crate::document::tree::Node;
use crate::gltf::gl::{BLEND, CULL_FACE};
use crate::legacy::source::Source;

/// How a 1.0 material's colour meets what is behind it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Blend {
    /// Source factor ONE: the colour is added whole, the background kept by 1 − alpha
    /// (premultiplied colour, KHR_materials_common's implementation note).
    Premultiplied,
    /// Source factor SRC_ALPHA: the colour weighed by alpha, as glTF 2.0's BLEND.
    Straight,
}

/// How `technique` blends: `None` without BLEND enabled, or with blend functions whose
/// source factor is neither ONE nor SRC_ALPHA; without blend functions, GL's own (ONE,
/// ZERO, the specification's default) add the colour whole and keep nothing behind, which
/// is no blend either.
pub(crate) fn technique_blend(technique: Node) -> Option<Blend> {
    const ONE: u64 = 1;
    const SRC_ALPHA: u64 = 770;
    let states = technique.get("states")?;
    let enabled = states.get("enable").and_then(Node::as_array)?;
    if !enabled.iter().any(|e| e.as_u64() == Some(BLEND)) {
        return None;
    }
    let functions = states.get("functions");
    let pair = functions.and_then(|f| f.get("blendFuncSeparate"));
    match pair.and_then(|f| f.get(0usize)).and_then(Node::as_u64) {
        Some(ONE) => Some(Blend::Premultiplied),
        Some(SRC_ALPHA) => Some(Blend::Straight),
        _ => None,
    }
}

/// Whether a 1.0 material draws both sides, where it says: KHR_materials_common's
/// `doubleSided` (false by default; a runtime may use the extension "in favor of the supplied
/// technique"), else its technique's states. `None` where nothing says (no technique, or one
/// that names nothing).
pub(crate) fn double_sided(source: &Source, material: Node) -> Option<bool> {
    let common = (material.get("extensions")).and_then(|e| e.get("KHR_materials_common"));
    if let Some(common) = common {
        return Some(common.get("doubleSided").and_then(Node::as_bool) == Some(true));
    }
    let technique = material.get("technique").and_then(Node::as_str)?;
    Some(!technique_culls(source.object("techniques", technique)?))
}

/// Whether `technique` culls back faces: its states enable CULL_FACE (1.0 states default to
/// nothing enabled, so a technique that does not enable it draws both sides).
fn technique_culls(technique: Node) -> bool {
    let states = technique.get("states");
    let enabled = states
        .and_then(|s| s.get("enable"))
        .and_then(Node::as_array);
    enabled.is_some_and(|e| e.iter().any(|e| e.as_u64() == Some(CULL_FACE)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::tree::Tree;

    fn blend_of(technique: &str) -> Option<Blend> {
        let tree = Tree::parse(technique.as_bytes()).unwrap();
        technique_blend(tree.root())
    }

    #[test]
    fn a_technique_blends_as_its_enabled_state_and_source_factor_say() {
        let with = |functions: &str| {
            blend_of(&format!(
                r#"{{"states": {{"enable": [2884, 3042]{functions}}}}}"#
            ))
        };
        assert_eq!(
            with(r#", "functions": {"blendFuncSeparate": [1, 771, 1, 771]}"#),
            Some(Blend::Premultiplied)
        );
        assert_eq!(
            with(r#", "functions": {"blendFuncSeparate": [770, 771, 1, 771]}"#),
            Some(Blend::Straight)
        );
        assert_eq!(with(""), None, "GL's default ONE, ZERO blends nothing");
        assert_eq!(
            blend_of(
                r#"{"states": {"enable": [2884], "functions": {"blendFuncSeparate": [1, 771, 1, 771]}}}"#
            ),
            None,
            "functions without BLEND enabled"
        );
        assert_eq!(blend_of(r#"{"states": "none"}"#), None);
    }

    #[test]
    fn a_technique_culls_only_when_its_states_enable_cull_face() {
        let culls =
            |technique: &str| technique_culls(Tree::parse(technique.as_bytes()).unwrap().root());
        assert!(culls(r#"{"states": {"enable": [2929, 2884]}}"#));
        assert!(!culls(r#"{"states": {"enable": [2929]}}"#));
        assert!(!culls(r#"{"states": {}}"#), "nothing enabled by default");
        assert!(!culls(r#"{}"#));
    }
}
