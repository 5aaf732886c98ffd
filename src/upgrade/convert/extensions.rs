//! 1.0 extensions the converter does not know: never dropped silently. Each is named in the
//! report, with how many objects carried it and the first of them.

use crate::document::json::escape_token;
use crate::document::Node;
use crate::legacy::pbr;
use crate::upgrade::builder::Builder;
use crate::upgrade::NoteKind;
use std::collections::BTreeMap;

/// The 1.0 extensions some conversion step reads (besides the PBR drafts), or that glTF 2.0
/// holds in its core (OES_element_index_uint: 32-bit indices).
const CONVERTED: &[&str] = &[
    "OES_element_index_uint",
    "KHR_binary_glTF",
    "KHR_materials_common",
    "WEB3D_quantized_attributes",
];

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn unconverted_extensions(&mut self) {
        let mut found: BTreeMap<String, (usize, String)> = BTreeMap::new();
        collect_extensions(self.source.root(), &mut String::new(), &mut found);
        let declared = (self.source.root().get("extensionsUsed"))
            .and_then(Node::as_array)
            .into_iter()
            .flat_map(|names| names.iter())
            .filter_map(Node::as_str)
            .enumerate();
        for (i, name) in declared {
            found
                .entry(name.to_string())
                .or_insert((0, format!("/extensionsUsed/{i}")));
        }
        let is_converted =
            |name: &str| CONVERTED.contains(&name) || pbr::EXTENSION_NAMES.contains(&name);
        for (name, (count, first)) in found.into_iter().filter(|(n, _)| !is_converted(n)) {
            let where_ = match count {
                0 => "declared in extensionsUsed but used by no object".to_string(),
                n => format!("on {n} object(s)"),
            };
            self.note(
                first,
                NoteKind::Dropped,
                format!("extension {name} ({where_}) has no glTF 2.0 conversion: dropped, and what it adds is not in the output."),
            );
        }
    }
}

/// Every `extensions` member below `value`: name → (objects carrying it, the first's pointer).
fn collect_extensions(value: Node, at: &mut String, found: &mut BTreeMap<String, (usize, String)>) {
    let length = at.len();
    if let Some(members) = value.as_object() {
        if let Some(extensions) = members.get("extensions").and_then(Node::as_object) {
            for name in extensions.keys() {
                let entry = found
                    .entry(name.to_string())
                    .or_insert((0, format!("{at}/extensions/{}", escape_token(name))));
                entry.0 += 1;
            }
        }
        for (key, member) in members.iter() {
            at.push('/');
            at.push_str(&escape_token(key));
            collect_extensions(member, at, found);
            at.truncate(length);
        }
    }
    for (i, item) in value
        .as_array()
        .into_iter()
        .flat_map(|items| items.iter())
        .enumerate()
    {
        at.push_str(&format!("/{i}"));
        collect_extensions(item, at, found);
        at.truncate(length);
    }
}
