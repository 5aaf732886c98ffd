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
    CESIUM_RTC,
];

/// Cesium's relative-to-centre extension: positions are offsets from `center`.
pub(super) const CESIUM_RTC: &str = "CESIUM_RTC";

impl Builder<'_, '_> {
    /// The root CESIUM_RTC object to write, kept as it is: CesiumJS, which 3D Tiles content is
    /// made for, applies it to glTF 2.0 as to 1.0, so every vertex stays where it was. A node
    /// translation would not be the same thing there: the 3D Tiles transform order applies the
    /// centre after the glTF's y-up to z-up rotation, and 10^6 m in a float32 model matrix
    /// jitters. A centre that is not three finite numbers is dropped, and said.
    pub(in crate::upgrade) fn cesium_rtc(&mut self) -> Option<serde_json::Value> {
        let rtc = self.source.root().get("extensions")?.get(CESIUM_RTC)?;
        let pointer = format!("/extensions/{CESIUM_RTC}");
        let center: Option<Vec<f64>> = (rtc.get("center").and_then(Node::as_array))
            .filter(|c| c.len() == 3)
            .and_then(|c| c.iter().map(Node::as_f64).collect())
            .filter(|c: &Vec<f64>| c.iter().all(|v| v.is_finite()));
        let Some(center) = center else {
            self.note(
                pointer,
                NoteKind::Dropped,
                "CESIUM_RTC without a center of three numbers: dropped; the positions are written as stored, relative to no centre.",
            );
            return None;
        };
        self.note(
            pointer,
            NoteKind::Decision,
            format!(
                "CESIUM_RTC kept with its center {center:?}: positions stay offsets from it, as CesiumJS reads them in glTF 2.0 too (declared in extensionsUsed, not required: a viewer without it shows the geometry about the origin, as it showed the 1.0 asset)."
            ),
        );
        Some(serde_json::json!({"center": center}))
    }
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
