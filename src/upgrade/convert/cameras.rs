//! Cameras (znear 0 fixed), scenes, and the 1.0 collections glTF 2.0 has no place for.

use crate::document::Node;
use crate::upgrade::builder::{id_list, pointer, Builder};
use crate::upgrade::NoteKind;
use serde_json::{json, Value};

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn cameras(&mut self) {
        for (id, camera) in self.source.dictionary("cameras") {
            let mut out = Self::named(id, camera);
            let kind = camera
                .get("type")
                .and_then(Node::as_str)
                .unwrap_or("perspective");
            out.insert("type".into(), json!(kind));
            let mut projection = match camera.get(kind) {
                Some(given) if given.is_object() => given.to_value(),
                Some(_) => {
                    // Read as absent, as 2.0's schema reads a member of the wrong type.
                    let at = format!("{}/{kind}", pointer("cameras", id));
                    self.note(
                        &at,
                        NoteKind::Dropped,
                        format!("'{kind}' is not an object: its projection is made anew."),
                    );
                    json!({})
                }
                None => json!({}),
            };
            if kind == "perspective" {
                self.fix_perspective(&mut projection, id);
            }
            out.insert(kind.into(), projection);
            self.push_from("cameras", Value::Object(out), pointer("cameras", id));
        }
    }

    /// 2.0 needs znear > 0, yfov > 0 and (when given) aspectRatio > 0.
    pub(in crate::upgrade) fn fix_perspective(&mut self, projection: &mut Value, id: &str) {
        let at = pointer("cameras", id);
        let get = |projection: &Value, key: &str| projection.get(key).and_then(Value::as_f64);
        if get(projection, "aspectRatio").is_some_and(|a| a <= 0.0) {
            projection.as_object_mut().map(|p| p.remove("aspectRatio"));
            self.note(
                &at,
                NoteKind::Dropped,
                "aspectRatio 0 removed (the viewport's ratio is used).",
            );
        }
        if get(projection, "yfov").is_none_or(|y| y <= 0.0) {
            projection["yfov"] = json!(1.0);
            self.note(
                &at,
                NoteKind::Decision,
                "yfov 0 or missing set to 1.0 radian.",
            );
        }
        if get(projection, "znear").is_none_or(|z| z <= 0.0) {
            let znear = get(projection, "zfar").map_or(0.01, |far| (far * 1e-4).max(1e-6));
            projection["znear"] = json!(znear);
            self.note(
                &at,
                NoteKind::Decision,
                format!("znear 0 is invalid in 2.0; set to {znear} (zfar / 10000, or 0.01)."),
            );
        }
    }

    pub(in crate::upgrade) fn scenes(&mut self) {
        for (id, scene) in self.source.dictionary("scenes") {
            let mut out = Self::named(id, scene);
            let at = pointer("scenes", id);
            let mut nodes = Vec::new();
            let mut listed = std::collections::HashSet::new();
            for node in id_list(scene.get("nodes")) {
                match self.index_of_id("nodes", &node) {
                    // A root listed again draws nothing more (one node, one place): 2.0
                    // forbids the repeat, so it is listed once.
                    Some(index) if !listed.insert(index) => self.note(
                        format!("{at}/nodes"),
                        NoteKind::Decision,
                        format!("node '{node}' is listed more than once: listed once (it is drawn once either way)."),
                    ),
                    Some(index) => nodes.push(index),
                    None => self.note(
                        format!("{at}/nodes"),
                        NoteKind::Dropped,
                        format!("node '{node}' does not exist: left out of the scene."),
                    ),
                }
            }
            if nodes.is_empty() {
                // 2.0 forbids an empty `nodes` array; a scene without the member is valid.
                self.note(
                    &at,
                    NoteKind::Decision,
                    "the scene has no nodes: written without a `nodes` array (2.0 forbids an empty one).",
                );
            } else {
                out.insert("nodes".into(), json!(nodes));
            }
            self.push_from("scenes", Value::Object(out), pointer("scenes", id));
        }
    }

    pub(in crate::upgrade) fn dropped_collections(&mut self) {
        for collection in ["techniques", "programs", "shaders"] {
            let count = self.source.dictionary(collection).len();
            if count > 0 {
                self.note(
                    format!("/{collection}"),
                    NoteKind::Dropped,
                    format!("{count} {collection} dropped: glTF 2.0 materials are not shader programs (their files were not read)."),
                );
            }
        }
    }
}
