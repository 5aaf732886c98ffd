//! Meshes and primitives: attributes renamed, accessors repacked, modes kept.

use crate::document::{Node, Object};
use crate::upgrade::builder::{pointer, Builder};
use crate::upgrade::data::{self, Role};
use crate::upgrade::{NoteKind, UpgradeError};
use serde_json::{json, Map, Value};

const NO_ATTRIBUTES: &str = "primitive without attributes dropped: it draws nothing, and glTF 2.0 requires at least one attribute.";
const NO_PRIMITIVES: &str = "mesh without (drawable) primitives dropped, and with it the nodes' reference to it: it draws nothing, and glTF 2.0 requires at least one primitive.";

impl<'s> Builder<'s, '_> {
    /// 1.0 allows a mesh without primitives and a primitive without attributes (both default
    /// to empty); 2.0 requires at least one of each. Such a primitive draws nothing and is
    /// dropped with a note, and so is a mesh left without primitives, the nodes holding it
    /// then holding no mesh (see [`Builder::mesh_index`]).
    pub(in crate::upgrade) fn meshes(&mut self) -> Result<(), UpgradeError> {
        for (position, (id, mesh)) in self.source.dictionary("meshes").into_iter().enumerate() {
            let mut out = Self::named(id, mesh);
            let mut primitives = Vec::new();
            let list = mesh.get("primitives").and_then(Node::as_array);
            for (p, primitive) in list.into_iter().flatten().enumerate() {
                let at = format!("{}/primitives/{p}", pointer("meshes", id));
                let has_attributes = (primitive.get("attributes").and_then(Node::as_object))
                    .is_some_and(|attributes| attributes.iter().next().is_some());
                if !has_attributes {
                    self.note(at, NoteKind::Dropped, NO_ATTRIBUTES);
                    continue;
                }
                primitives.push(self.primitive(primitive, &at)?);
            }
            if primitives.is_empty() {
                self.note(pointer("meshes", id), NoteKind::Dropped, NO_PRIMITIVES);
                self.dropped_meshes.push(position);
                continue;
            }
            out.insert("primitives".into(), json!(primitives));
            self.push_from("meshes", Value::Object(out), pointer("meshes", id));
        }
        Ok(())
    }

    /// The 2.0 index of 1.0 mesh `id`: its place in the dictionary less the meshes dropped
    /// before it; None for a mesh that was dropped or does not exist.
    pub(in crate::upgrade) fn mesh_index(&self, id: &str) -> Option<usize> {
        let position = self.index_of_id("meshes", id)?;
        match self.dropped_meshes.binary_search(&position) {
            Ok(_) => None,
            Err(dropped_before) => Some(position - dropped_before),
        }
    }

    pub(in crate::upgrade) fn primitive(
        &mut self,
        primitive: Node<'s>,
        at: &str,
    ) -> Result<Value, UpgradeError> {
        let mut attributes = Map::new();
        let source_attributes = primitive.get("attributes").and_then(Node::as_object);
        let tangents = match source_attributes {
            Some(source) => self.signed_tangents(source, at)?,
            None => None,
        };
        if let Some(index) = tangents {
            attributes.insert("TANGENT".into(), json!(index));
        }
        let merged = match source_attributes {
            Some(source) => self.merged_influences(source, at)?,
            None => None,
        };
        if let Some((joints, weights)) = merged {
            attributes.insert("JOINTS_0".into(), json!(joints));
            attributes.insert("WEIGHTS_0".into(), json!(weights));
        }
        for (semantic, accessor) in source_attributes.into_iter().flat_map(|a| a.iter()) {
            let Some(accessor) = accessor.as_str() else {
                continue;
            };
            if tangents.is_some() && matches!(semantic, "TANGENT" | "BINORMAL") {
                continue;
            }
            if merged.is_some() && matches!(semantic, "JOINT" | "WEIGHT" | "JOINT_0" | "WEIGHT_0") {
                continue;
            }
            let renamed = rename_semantic(semantic);
            // An attribute naming no accessor has no data to convert: it is left out and said.
            // A primitive without POSITION draws nothing, so that one is refused with its reason.
            if renamed != "POSITION" && self.source.object("accessors", accessor).is_none() {
                self.note(
                    format!("{at}/attributes/{semantic}"),
                    NoteKind::Dropped,
                    format!("attribute {semantic} names accessor '{accessor}', which does not exist: left out of the primitive."),
                );
                continue;
            }
            if renamed != semantic {
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
        if let Some(indices) = primitive.get("indices").and_then(Node::as_str) {
            out.insert(
                "indices".into(),
                json!(self.accessor(indices, Role::Indices)?),
            );
        }
        if let Some(m) = self.index_of("materials", primitive.get("material")) {
            out.insert("material".into(), json!(m));
        }
        if let Some(mode) = primitive.get("mode") {
            out.insert("mode".into(), mode.to_value());
        }
        Ok(Value::Object(out))
    }
}

impl<'s> Builder<'s, '_> {
    /// A primitive's JOINT/WEIGHT pair with every joint a vertex lists twice (with weight) merged
    /// into one entry carrying the summed weight, each vertex's weights divided by their sum as
    /// the other skinned vertices' are: the blend Σ wᵢ·M(jᵢ) is unchanged, and glTF 2.0 forbids a
    /// joint twice in one vertex. None when no vertex repeats a joint (the pair is converted as
    /// it is) or the pair is not four float weights per vertex.
    fn merged_influences(
        &mut self,
        source: Object<'s>,
        at: &str,
    ) -> Result<Option<(usize, usize)>, UpgradeError> {
        let id = |semantic: &str| source.get(semantic).and_then(Node::as_str);
        let (Some(joints_id), Some(weights_id)) = (
            id("JOINT").or(id("JOINT_0")),
            id("WEIGHT").or(id("WEIGHT_0")),
        ) else {
            return Ok(None);
        };
        if let Some(done) = self.merged_influences.get(&(joints_id, weights_id)) {
            return Ok(*done);
        }
        let merged = self.merge_influences(joints_id, weights_id, at)?;
        self.merged_influences
            .insert((joints_id, weights_id), merged);
        Ok(merged)
    }

    fn merge_influences(
        &mut self,
        joints_id: &'s str,
        weights_id: &'s str,
        at: &str,
    ) -> Result<Option<(usize, usize)>, UpgradeError> {
        let read = |id: &str| {
            data::read(self.source, id).map_err(|reason| UpgradeError::Resource {
                pointer: pointer("accessors", id),
                reason,
            })
        };
        let (joints, weights) = (read(joints_id)?, read(weights_id)?);
        let fits = joints.components == 4
            && weights.components == 4
            && weights.component_type == data::FLOAT
            && joints.count == weights.count;
        if !fits {
            return Ok(None);
        }
        let (mut j, mut w) = (joints.values(), weights.values());
        let mut merged_vertices = 0;
        for (vj, vw) in j.chunks_exact_mut(4).zip(w.chunks_exact_mut(4)) {
            if merge_repeated_joints(vj, vw) {
                merged_vertices += 1;
            }
        }
        if merged_vertices == 0 {
            return Ok(None);
        }
        let count = joints.count;
        let joint_type = match j.iter().copied().fold(0.0, f64::max) {
            m if m <= 255.0 => crate::gltf::gl::UNSIGNED_BYTE,
            _ => crate::gltf::gl::UNSIGNED_SHORT,
        };
        let packed = data::pack_values(&j, 4, joint_type, false, true, &mut self.binary);
        let joints_index = self.add_accessor(packed, "VEC4", count, Role::Joints, Some(joints_id));
        self.record_origin("accessors", joints_index, pointer("accessors", joints_id));
        let packed = data::pack_values(&w, 4, data::FLOAT, false, true, &mut self.binary);
        let weights_index =
            self.add_accessor(packed, "VEC4", count, Role::Weights, Some(weights_id));
        self.record_origin("accessors", weights_index, pointer("accessors", weights_id));
        self.note(
            format!("{at}/attributes"),
            NoteKind::Decision,
            format!("{merged_vertices} of {count} vertices list a joint twice with weight (glTF 2.0 forbids it): each repeat merged into one entry with the weights summed, which skins the same (the blend adds w·M per entry)."),
        );
        Ok(Some((joints_index, weights_index)))
    }

    /// 2.0 tangents for 1.0 VEC3 ones: VEC4 with w = ±1, the sign of dot(cross(N, T), B) with
    /// the 1.0 BINORMAL (the bitangent 2.0 rebuilds as cross(N, T) · w), or +1 without one.
    /// None when the tangents are not VEC3 (they are converted as they are).
    fn signed_tangents(
        &mut self,
        attributes: Object,
        at: &str,
    ) -> Result<Option<usize>, UpgradeError> {
        let id = |semantic: &str| attributes.get(semantic).and_then(Node::as_str);
        let Some(tangent_id) = id("TANGENT") else {
            return Ok(None);
        };
        let read = |builder: &Self, accessor: &str| {
            data::read(builder.source, accessor).map_err(|reason| UpgradeError::Resource {
                pointer: pointer("accessors", accessor),
                reason,
            })
        };
        let tangents = read(self, tangent_id)?;
        if tangents.kind != "VEC3" {
            return Ok(None);
        }
        let count = tangents.count;
        let vec3 = |builder: &Self, semantic: &str| -> Result<Option<_>, UpgradeError> {
            let Some(accessor) = id(semantic) else {
                return Ok(None);
            };
            let data = read(builder, accessor)?;
            Ok((data.kind == "VEC3" && data.count == count).then_some(data))
        };
        let (normals, binormals) = (vec3(self, "NORMAL")?, vec3(self, "BINORMAL")?);
        let mut values = Vec::with_capacity(count * 4);
        for i in 0..count {
            let t = [0, 1, 2].map(|c| tangents.get(i, c));
            let w = match (&normals, &binormals) {
                (Some(n), Some(b)) => {
                    let n = [0, 1, 2].map(|c| n.get(i, c));
                    let b = [0, 1, 2].map(|c| b.get(i, c));
                    let cross = [
                        n[1] * t[2] - n[2] * t[1],
                        n[2] * t[0] - n[0] * t[2],
                        n[0] * t[1] - n[1] * t[0],
                    ];
                    if cross[0] * b[0] + cross[1] * b[1] + cross[2] * b[2] < 0.0 {
                        -1.0
                    } else {
                        1.0
                    }
                }
                _ => 1.0,
            };
            values.extend(t);
            values.push(w);
        }
        let packed = data::pack_values(&values, 4, data::FLOAT, false, true, &mut self.binary);
        let index = self.add_accessor(
            packed,
            "VEC4",
            count,
            Role::FloatAttribute,
            Some(tangent_id),
        );
        self.record_origin("accessors", index, pointer("accessors", tangent_id));
        let how = if binormals.is_some() && normals.is_some() {
            "w = the sign of dot(cross(NORMAL, TANGENT), BINORMAL); BINORMAL dropped, as 2.0 rebuilds it from NORMAL, TANGENT and w"
        } else {
            "w = +1 (no BINORMAL and NORMAL to take the handedness from)"
        };
        self.note(
            format!("{at}/attributes/TANGENT"),
            NoteKind::Decision,
            format!("VEC3 tangents written as the VEC4 glTF 2.0 requires: {how}."),
        );
        Ok(Some(index))
    }
}

/// Merges the entries of one vertex that name the same joint with weight: the first keeps the
/// summed weight, the others become joint 0 with weight 0; the weights are then divided by
/// their sum. Whether anything was merged.
fn merge_repeated_joints(joints: &mut [f64], weights: &mut [f64]) -> bool {
    let mut merged = false;
    for a in 0..joints.len() {
        for b in a + 1..joints.len() {
            if weights[a] != 0.0 && weights[b] != 0.0 && joints[a] == joints[b] {
                weights[a] += weights[b];
                (joints[b], weights[b]) = (0.0, 0.0);
                merged = true;
            }
        }
    }
    let sum: f64 = weights.iter().sum();
    if merged && sum > 0.0 {
        weights.iter_mut().for_each(|w| *w /= sum);
    }
    merged
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
