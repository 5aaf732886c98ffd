//! Meshes and primitives: attributes renamed, accessors repacked, modes kept.

use crate::upgrade::builder::{pointer, Builder};
use crate::upgrade::data::Role;
use crate::upgrade::{NoteKind, UpgradeError};
use serde_json::{json, Map, Value};

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn meshes(&mut self) -> Result<(), UpgradeError> {
        for (id, mesh) in self.source.dictionary("meshes") {
            let mut out = Self::named(id, mesh);
            let mut primitives = Vec::new();
            let list = mesh.get("primitives").and_then(Value::as_array);
            for (p, primitive) in list.into_iter().flatten().enumerate() {
                let at = format!("{}/primitives/{p}", pointer("meshes", id));
                primitives.push(self.primitive(primitive, &at)?);
            }
            out.insert("primitives".into(), json!(primitives));
            self.push("meshes", Value::Object(out));
        }
        Ok(())
    }

    pub(in crate::upgrade) fn primitive(
        &mut self,
        primitive: &Value,
        at: &str,
    ) -> Result<Value, UpgradeError> {
        let mut attributes = Map::new();
        let source_attributes = primitive.get("attributes").and_then(Value::as_object);
        for (semantic, accessor) in source_attributes.into_iter().flatten() {
            let Some(accessor) = accessor.as_str() else {
                continue;
            };
            let renamed = rename_semantic(semantic);
            if renamed != *semantic {
                self.note(
                    format!("{at}/attributes/{semantic}"),
                    NoteKind::Decision,
                    format!("attribute {semantic} renamed {renamed}."),
                );
            }
            let index = self.accessor(accessor, Role::of_semantic(&renamed))?;
            attributes.insert(renamed, json!(index));
        }
        let mut out = Map::new();
        out.insert("attributes".into(), Value::Object(attributes));
        if let Some(indices) = primitive.get("indices").and_then(Value::as_str) {
            out.insert(
                "indices".into(),
                json!(self.accessor(indices, Role::Indices)?),
            );
        }
        if let Some(m) = self.index_of("materials", primitive.get("material")) {
            out.insert("material".into(), json!(m));
        }
        if let Some(mode) = primitive.get("mode") {
            out.insert("mode".into(), mode.clone());
        }
        Ok(Value::Object(out))
    }
}

/// 1.0 attribute semantics → 2.0: TEXCOORD → TEXCOORD_0, COLOR → COLOR_0, JOINT(_n) →
/// JOINTS_n, WEIGHT(_n) → WEIGHTS_n; unknown semantics get the `_` application prefix.
fn rename_semantic(semantic: &str) -> String {
    let (base, set) = match semantic.split_once('_') {
        Some((b, s)) if s.chars().all(|c| c.is_ascii_digit()) && !s.is_empty() => (b, s),
        _ => (semantic, "0"),
    };
    match base {
        "POSITION" | "NORMAL" | "TANGENT" if semantic == base => semantic.to_string(),
        "TEXCOORD" | "COLOR" => format!("{base}_{set}"),
        "JOINT" | "JOINTS" => format!("JOINTS_{set}"),
        "WEIGHT" | "WEIGHTS" => format!("WEIGHTS_{set}"),
        _ if semantic.starts_with('_') => semantic.to_string(),
        _ => format!("_{semantic}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn semantics_are_renamed_as_2_0_requires() {
        for (old, new) in [
            ("TEXCOORD", "TEXCOORD_0"),
            ("TEXCOORD_1", "TEXCOORD_1"),
            ("COLOR", "COLOR_0"),
            ("JOINT", "JOINTS_0"),
            ("WEIGHT", "WEIGHTS_0"),
            ("POSITION", "POSITION"),
            ("BATCHID", "_BATCHID"),
        ] {
            assert_eq!(rename_semantic(old), new);
        }
    }
}
