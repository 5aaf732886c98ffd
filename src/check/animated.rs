//! The members a document's own behaviour changes while it plays: what it writes of them is
//! not their value throughout, so a rule that calls a setting useless asks here first.
//!
//! Two extensions change members at runtime: KHR_animation_pointer (an animation channel
//! targets a JSON pointer) and KHR_interactivity (a graph's `pointer/set` and
//! `pointer/interpolate` write through a pointer template, whose `[int]` and `{ref}`
//! parameters are the node's input values). A parameter given as a literal number is
//! resolved; one wired to another node's output may take any value at runtime. Every graph
//! counts, not only the one the extension runs by default: another may be run by an
//! implementation's choice, and a rule that stays silent there loses nothing true.

use super::context::Context;
use crate::document::Node;
use std::borrow::Cow;
use std::collections::HashSet;

/// The members changed at runtime (see the module documentation).
pub(crate) struct Animated<'t> {
    /// Pointers known in full.
    pointers: HashSet<Cow<'t, str>>,
    /// Members (their path below a material) of any material: a template whose only
    /// parameter known at runtime is the material.
    of_any_material: HashSet<String>,
    /// Other templates that may name a material's member, each path segment `None` where
    /// any value may stand; at most [`MAX_TEMPLATES`] of them, past which every material
    /// member counts as changed (a graph that writes so many is read as writing anything).
    templates: HashSet<Vec<Option<String>>>,
    any_member: bool,
}

/// The most pointer templates with several runtime parameters compared with each member.
const MAX_TEMPLATES: usize = 256;

impl<'t> Animated<'t> {
    /// The document's changed members, computed once per document (the rules share them).
    pub(crate) fn of(ctx: &Context<'t>) -> std::sync::Arc<Animated<'t>> {
        let root = ctx.root;
        (ctx.animated)
            .get_or_init(|| std::sync::Arc::new(Animated::read(root)))
            .clone()
    }

    fn read(root: Node<'t>) -> Animated<'t> {
        let mut animated = Animated {
            pointers: animation_pointers(root).map(Cow::Borrowed).collect(),
            of_any_material: HashSet::new(),
            templates: HashSet::new(),
            any_member: false,
        };
        for (template, values) in graph_pointers(root) {
            animated.add(resolved(template, values));
        }
        animated
    }

    fn add(&mut self, segments: Vec<Option<String>>) {
        let joined = |segments: &[Option<String>]| -> Option<String> {
            let known: Vec<&String> = segments.iter().map(Option::as_ref).collect::<Option<_>>()?;
            Some(known.iter().map(|s| format!("/{s}")).collect())
        };
        if let Some(pointer) = joined(&segments) {
            self.pointers.insert(Cow::Owned(pointer));
            return;
        }
        let collection = segments.first().and_then(Option::as_deref);
        if !matches!(collection, Some("materials") | None) {
            return;
        }
        if let (Some("materials"), Some(None), Some(member)) = (
            collection,
            segments.get(1),
            segments.get(2..).and_then(joined),
        ) {
            self.of_any_material
                .insert(member.trim_start_matches('/').to_string());
        } else if self.templates.len() < MAX_TEMPLATES {
            self.templates.insert(segments);
        } else {
            self.any_member = true;
        }
    }

    /// Whether `member` (its path below the material) of material `material` is changed at
    /// runtime.
    pub(crate) fn material_member(&self, material: usize, member: &str) -> bool {
        if self.any_member || self.of_any_material.contains(member) {
            return true;
        }
        if self.pointers.is_empty() && self.templates.is_empty() {
            return false;
        }
        let pointer = format!("/materials/{material}/{member}");
        self.pointers.contains(pointer.as_str()) || {
            let segments: Vec<&str> = pointer.split('/').skip(1).collect();
            (self.templates.iter()).any(|template| {
                template.len() == segments.len()
                    && (template.iter().zip(&segments))
                        .all(|(t, s)| t.as_deref().is_none_or(|t| t == *s))
            })
        }
    }
}

/// Every JSON pointer an animation channel targets through KHR_animation_pointer.
fn animation_pointers(root: Node<'_>) -> impl Iterator<Item = &str> {
    let channels = (root.get("animations").and_then(Node::as_array).into_iter())
        .flatten()
        .filter_map(|animation| animation.get("channels")?.as_array())
        .flatten();
    channels.filter_map(|channel| {
        let extension = channel.get("target")?.get("extensions")?;
        extension
            .get("KHR_animation_pointer")?
            .get("pointer")?
            .as_str()
    })
}

/// Each pointer template a KHR_interactivity graph writes through, with the node's input
/// values.
fn graph_pointers(root: Node<'_>) -> Vec<(&str, Option<Node<'_>>)> {
    let graphs = (root.get("extensions"))
        .and_then(|e| e.get("KHR_interactivity")?.get("graphs")?.as_array());
    let mut found = Vec::new();
    for graph in graphs.into_iter().flatten() {
        let declarations = graph.get("declarations").and_then(Node::as_array);
        let op = |node: Node| {
            let declaration = declarations?.get(node.get("declaration")?.as_u64()? as usize)?;
            declaration.get("op")?.as_str()
        };
        let nodes = graph.get("nodes").and_then(Node::as_array);
        for node in nodes.into_iter().flatten() {
            if !matches!(op(node), Some("pointer/set" | "pointer/interpolate")) {
                continue;
            }
            let template = (node.get("configuration")).and_then(|c| {
                c.get("pointer")?
                    .get("value")?
                    .as_array()?
                    .first()?
                    .as_str()
            });
            if let Some(template) = template {
                found.push((template, node.get("values")));
            }
        }
    }
    found
}

/// A pointer template's path segments: a literal one unescaped (`[[` is `[`), a parameter
/// (`[name]` or `{name}`, the whole segment) the literal number its input value holds, or
/// `None` where the value comes from another node.
fn resolved(template: &str, values: Option<Node>) -> Vec<Option<String>> {
    fn parameter(segment: &str) -> Option<&str> {
        let inner = (segment.strip_prefix('[').and_then(|s| s.strip_suffix(']')))
            .or_else(|| segment.strip_prefix('{').and_then(|s| s.strip_suffix('}')))?;
        let escaped = ["[", "]", "{", "}"].iter().any(|b| inner.contains(b));
        (!escaped && !inner.is_empty()).then_some(inner)
    }
    let literal = |name: &str| {
        let value = values?.get(name)?.get("value")?.as_array()?.first()?;
        value.as_u64().map(|n| n.to_string())
    };
    (template.split('/').skip(1))
        .map(|segment| match parameter(segment) {
            Some(name) => literal(name),
            None => Some(
                (segment.replace("[[", "[").replace("]]", "]"))
                    .replace("{{", "{")
                    .replace("}}", "}"),
            ),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::Tree;

    fn segments(template: &str, values: &str) -> Vec<Option<String>> {
        let tree = Tree::parse(values.as_bytes()).expect("valid JSON");
        resolved(template, Some(tree.root()))
    }

    #[test]
    fn a_template_takes_its_literal_parameters_and_unescapes_its_brackets() {
        let known = |s: &[&str]| s.iter().map(|s| Some(s.to_string())).collect::<Vec<_>>();
        assert_eq!(
            segments("/materials/[m]/extras/{{x}}", r#"{"m": {"value": [3]}}"#),
            known(&["materials", "3", "extras", "{x}"])
        );
        assert_eq!(
            segments("/nodes/{n}/[[w]]", r#"{"n": {"type": 1, "value": [0]}}"#),
            known(&["nodes", "0", "[w]"])
        );
    }

    #[test]
    fn a_parameter_wired_to_another_node_or_not_a_count_stands_for_any_value() {
        let any = vec![
            Some("materials".to_string()),
            None,
            Some("alphaCutoff".to_string()),
        ];
        for values in [
            r#"{"m": {"node": 2, "socket": "out"}}"#,
            r#"{"m": {"value": [-1]}}"#,
            "{}",
        ] {
            assert_eq!(
                segments("/materials/{m}/alphaCutoff", values),
                any,
                "{values}"
            );
        }
    }
}
