//! Nodes and skins: per-instance skins, bindShapeMatrix folded into the inverse bind matrices, transforms copied.

use crate::document::Node;
use crate::upgrade::builder::{id_list, pointer, Builder};
use crate::upgrade::data;
use crate::upgrade::data::Role;
use crate::upgrade::{NoteKind, UpgradeError};
use serde_json::{json, Map, Value};
use std::collections::{HashMap, HashSet};

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn nodes(&mut self) -> Result<(), UpgradeError> {
        let nodes = self.source.dictionary("nodes");
        let mut extra_nodes = Vec::new();
        for &(id, node) in &nodes {
            let mut out = Self::named(id, node);
            let mut children: Vec<Value> = id_list(node.get("children"))
                .iter()
                .filter_map(|c| self.index_of_id("nodes", c))
                .map(|i| json!(i))
                .collect();
            copy_transform(node, &mut out);
            if let Some(camera) = self.index_of("cameras", node.get("camera")) {
                out.insert("camera".into(), json!(camera));
            }
            let skin = self.skin_instance(id, node)?;
            let meshes: Vec<usize> = id_list(node.get("meshes"))
                .iter()
                .filter_map(|m| self.index_of_id("meshes", m))
                .collect();
            for (k, mesh) in meshes.iter().enumerate() {
                if k == 0 {
                    out.insert("mesh".into(), json!(mesh));
                    if let Some(skin) = skin {
                        out.insert("skin".into(), json!(skin));
                    }
                    continue;
                }
                // 2.0 nodes hold one mesh: the others become children (keeping the skin).
                let mut child = json!({"name": format!("{id}-mesh{k}"), "mesh": mesh});
                let origin = format!("{}/meshes/{k}", pointer("nodes", id));
                if let Some(skin) = skin {
                    child["skin"] = json!(skin);
                }
                children.push(json!(nodes.len() + extra_nodes.len()));
                extra_nodes.push((child, origin));
            }
            if meshes.len() > 1 {
                self.note(
                    pointer("nodes", id),
                    NoteKind::Decision,
                    format!("{} meshes split into child nodes.", meshes.len()),
                );
            }
            if !children.is_empty() {
                out.insert("children".into(), json!(children));
            }
            if let Some(light) = self.node_light(&pointer("nodes", id), node) {
                let placed = json!({super::lights::PUNCTUAL: {"light": light}});
                out.insert("extensions".into(), placed);
            }
            // Pushed as made (a node's index is its place in the dictionary): 10^5 nodes
            // are never all held as values at once.
            self.push_from("nodes", Value::Object(out), pointer("nodes", id));
        }
        for (node, origin) in extra_nodes {
            self.push_from("nodes", node, origin);
        }
        Ok(())
    }

    /// The 2.0 skin for a node instancing a 1.0 skin with its `skeletons` (one 2.0 skin per
    /// instance, as 2.0 joints are absolute node indices).
    pub(in crate::upgrade) fn skin_instance(
        &mut self,
        id: &str,
        node: Node,
    ) -> Result<Option<usize>, UpgradeError> {
        let Some(skin_id) = node.get("skin").and_then(Node::as_str) else {
            return Ok(None);
        };
        let Some(skin) = self.source.object("skins", skin_id) else {
            self.note(
                pointer("nodes", id),
                NoteKind::Dropped,
                format!("skin '{skin_id}' does not exist."),
            );
            return Ok(None);
        };
        let skeletons = id_list(node.get("skeletons"));
        let by_name = self.joints_by_name(id, &skeletons)?;
        let mut joints = Vec::new();
        for (k, name) in id_list(skin.get("jointNames")).iter().enumerate() {
            let Some(&joint) = by_name.get(name) else {
                // Dropping the name would shift every later joint: vertices would follow
                // the wrong bones.
                return Err(UpgradeError::Invalid {
                    pointer: format!("{}/jointNames/{k}", pointer("skins", skin_id)),
                    reason: format!(
                        "joint name '{name}' names no node under the skeletons of node '{id}'"
                    ),
                });
            };
            joints.push(joint);
        }
        let mut out = Self::named(skin_id, skin);
        out.insert("joints".into(), json!(joints));
        if let Some(root) = skeletons.first().and_then(|s| self.index_of_id("nodes", s)) {
            out.insert("skeleton".into(), json!(root));
        }
        let matrices = self.inverse_bind_matrices(skin_id, skin, joints.len())?;
        out.insert("inverseBindMatrices".into(), json!(matrices));
        let origin = format!(
            "{} (instanced by {})",
            pointer("skins", skin_id),
            pointer("nodes", id)
        );
        Ok(Some(self.push_from("skins", Value::Object(out), origin)))
    }

    /// Every `jointName` in the skeleton subtrees (1.0 scopes joint names by them), or among
    /// all nodes when the instance names no skeleton, to its 2.0 node index: one walk for
    /// all the skin's names. Where two nodes share a name, the one met first wins. A
    /// skeleton or child id that names no node is an error: the joints below it are unknown.
    fn joints_by_name(
        &self,
        id: &str,
        skeletons: &[String],
    ) -> Result<HashMap<String, usize>, UpgradeError> {
        let mut stack: Vec<(String, String)> = if skeletons.is_empty() {
            (self.source.dictionary("nodes").iter())
                .map(|(node, _)| (node.to_string(), String::new()))
                .collect()
        } else {
            let from = format!("{}/skeletons", pointer("nodes", id));
            skeletons
                .iter()
                .map(|s| (s.clone(), from.clone()))
                .collect()
        };
        let (mut found, mut seen) = (HashMap::new(), HashSet::new());
        while let Some((node_id, named_at)) = stack.pop() {
            if !seen.insert(node_id.clone()) {
                continue;
            }
            let Some(node) = self.source.object("nodes", &node_id) else {
                return Err(UpgradeError::Invalid {
                    pointer: named_at,
                    reason: format!("node '{node_id}' does not exist, so the skin's joints below it cannot be found"),
                });
            };
            if let (Some(name), Some(index)) = (
                node.get("jointName").and_then(Node::as_str),
                self.index_of_id("nodes", &node_id),
            ) {
                found.entry(name.to_string()).or_insert(index);
            }
            if !skeletons.is_empty() {
                let children_at = format!("{}/children", pointer("nodes", &node_id));
                stack.extend(
                    id_list(node.get("children"))
                        .into_iter()
                        .map(|c| (c, children_at.clone())),
                );
            }
        }
        Ok(found)
    }

    /// Inverse bind matrices with the bind shape matrix folded in: IBMᵢ · BSM, so that the
    /// 2.0 skinning (which has no bind shape matrix) deforms the vertices the same way.
    pub(in crate::upgrade) fn inverse_bind_matrices(
        &mut self,
        skin_id: &str,
        skin: Node,
        joints: usize,
    ) -> Result<usize, UpgradeError> {
        let bind_shape = matrix(skin.get("bindShapeMatrix")).unwrap_or(IDENTITY);
        let source_matrices = match skin.get("inverseBindMatrices").and_then(Node::as_str) {
            Some(id) => data::read(self.source, id)
                .map_err(|reason| UpgradeError::Resource {
                    pointer: pointer("skins", skin_id),
                    reason,
                })?
                .values(),
            None => IDENTITY.repeat(joints),
        };
        if bind_shape != IDENTITY {
            self.note(
                pointer("skins", skin_id),
                NoteKind::Decision,
                "bindShapeMatrix folded into inverseBindMatrices (IBM · BSM).",
            );
        }
        let folded: Vec<f64> = source_matrices
            .chunks_exact(16)
            .flat_map(|m| multiply(m, &bind_shape))
            .collect();
        let count = folded.len() / 16;
        let packed = data::pack_values(&folded, 16, data::FLOAT, false, false, &mut self.binary);
        let index = self.add_accessor(packed, "MAT4", count, Role::Data, Some(skin_id));
        let origin = format!("{}/inverseBindMatrices", pointer("skins", skin_id));
        self.record_origin("accessors", index, origin);
        Ok(index)
    }
}

const IDENTITY: [f64; 16] = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

fn matrix(value: Option<Node>) -> Option<[f64; 16]> {
    let list = value?.as_array()?;
    let mut m = [0.0; 16];
    if list.len() != 16 {
        return None;
    }
    for (slot, v) in m.iter_mut().zip(list.iter()) {
        *slot = v.as_f64()?;
    }
    Some(m)
}

/// Column-major 4×4 product a · b.
fn multiply(a: &[f64], b: &[f64; 16]) -> [f64; 16] {
    let mut out = [0.0; 16];
    for column in 0..4 {
        for row in 0..4 {
            out[column * 4 + row] = (0..4).map(|k| a[k * 4 + row] * b[column * 4 + k]).sum();
        }
    }
    out
}

/// matrix or translation/rotation/scale; an identity matrix is left out.
fn copy_transform(node: Node, out: &mut Map<String, Value>) {
    match matrix(node.get("matrix")) {
        Some(m) if m != IDENTITY => {
            out.insert("matrix".into(), json!(m));
        }
        _ => {
            for key in ["translation", "rotation", "scale"] {
                if let Some(v) = node.get(key) {
                    out.insert(key.into(), v.to_value());
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bind_shape_is_folded_on_the_right() {
        let mut translate = IDENTITY;
        translate[12] = 2.0; // x + 2
        let mut scale = IDENTITY;
        scale[0] = 3.0; // x · 3
        let folded = multiply(&scale, &translate);
        // (IBM · BSM) applied to x = 1: first BSM (x + 2 = 3), then IBM (· 3 = 9).
        assert_eq!(folded[0] * 1.0 + folded[12], 9.0);
    }
}
