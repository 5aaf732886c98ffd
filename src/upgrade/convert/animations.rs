//! Animations: channels and samplers re-indexed, accessors repacked.

use crate::document::Node;
use crate::legacy::draft08;
use crate::upgrade::builder::{pointer, Builder};
use crate::upgrade::data::{self, Role};
use crate::upgrade::{NoteKind, UpgradeError};
use serde_json::{json, Value};
use std::collections::{HashMap, HashSet};

/// 1.0 allows an animation without channels; 2.0 requires one, and such an animation moves
/// nothing, so it is dropped with this note.
const NO_CHANNELS: &str = "animation without (resolvable) channels dropped: it animates nothing, and glTF 2.0 requires at least one channel.";

impl Builder<'_, '_> {
    pub(in crate::upgrade) fn animations(&mut self) -> Result<(), UpgradeError> {
        for (id, animation) in self.source.dictionary("animations") {
            let at = pointer("animations", id);
            let has_channels = (animation.get("channels").and_then(Node::as_array))
                .is_some_and(|channels| !channels.is_empty());
            if !has_channels {
                self.note(&at, NoteKind::Dropped, NO_CHANNELS);
                continue;
            }
            let mut out = Self::named(id, animation);
            let parameters = animation.get("parameters");
            let turned_by_axis_and_angle = self.axis_and_angle_samplers(animation);
            let mut sampler_index = HashMap::new();
            let mut samplers = Vec::new();
            let source_samplers = animation.get("samplers").and_then(Node::as_object);
            for (sampler_id, sampler) in source_samplers.into_iter().flat_map(|s| s.iter()) {
                let accessor_of = |key: &str| {
                    let parameter = sampler.get(key).and_then(Node::as_str)?;
                    let accessor = parameters?.get(parameter)?.as_str()?;
                    self.source.object("accessors", accessor).map(|_| accessor)
                };
                let (Some(input), Some(output)) = (accessor_of("input"), accessor_of("output"))
                else {
                    self.note(
                        format!("{at}/samplers/{sampler_id}"),
                        NoteKind::Dropped,
                        "sampler whose parameters do not resolve to accessors dropped.",
                    );
                    continue;
                };
                let interpolation = sampler
                    .get("interpolation")
                    .map(Node::to_value)
                    .unwrap_or(json!("LINEAR"));
                let input = self.accessor(input, Role::Data)?;
                let output = match turned_by_axis_and_angle.contains(sampler_id) {
                    true => self.quaternion_keyframes(output)?,
                    false => self.accessor(output, Role::Data)?,
                };
                sampler_index.insert(sampler_id, samplers.len());
                samplers.push(
                    json!({"input": input, "output": output, "interpolation": interpolation}),
                );
            }
            let mut channels = Vec::new();
            for channel in animation
                .get("channels")
                .and_then(Node::as_array)
                .into_iter()
                .flat_map(|channels| channels.iter())
            {
                let sampler = channel
                    .get("sampler")
                    .and_then(Node::as_str)
                    .and_then(|s| sampler_index.get(s));
                let target = channel.get("target");
                let node = self.index_of("nodes", target.and_then(|t| t.get("id")));
                let path = target.and_then(|t| t.get("path")).map(Node::to_value);
                match (sampler, node, path) {
                    (Some(s), Some(n), Some(p)) => {
                        channels.push(json!({"sampler": s, "target": {"node": n, "path": p}}))
                    }
                    _ => self.note(
                        &at,
                        NoteKind::Dropped,
                        "channel with an unresolved sampler or target dropped.",
                    ),
                }
            }
            if channels.is_empty() {
                self.note(&at, NoteKind::Dropped, NO_CHANNELS);
                continue;
            }
            out.insert("samplers".into(), json!(samplers));
            out.insert("channels".into(), json!(channels));
            self.push_from("animations", Value::Object(out), pointer("animations", id));
        }
        Ok(())
    }

    /// The samplers whose keyframes turn a node by axis and angle: those of a glTF 0.8
    /// asset's rotation channels (1.0 writes quaternions).
    fn axis_and_angle_samplers<'n>(&self, animation: Node<'n>) -> HashSet<&'n str> {
        if self.source.read_as_draft_08().is_none() {
            return HashSet::new();
        }
        let channels = animation.get("channels").and_then(Node::as_array);
        (channels.into_iter().flat_map(|c| c.iter()))
            .filter(|c| c.pointer("/target/path").and_then(Node::as_str) == Some("rotation"))
            .filter_map(|c| c.get("sampler")?.as_str())
            .collect()
    }

    /// A 0.8 rotation sampler's keyframes (axis and angle) as the quaternions 2.0 reads.
    fn quaternion_keyframes(&mut self, id: &str) -> Result<usize, UpgradeError> {
        let at = pointer("accessors", id);
        let input = data::read(self.source, id).map_err(|reason| UpgradeError::Resource {
            pointer: at.clone(),
            reason,
        })?;
        if input.components != 4 {
            return Err(UpgradeError::Resource {
                pointer: at,
                reason: format!(
                    "a glTF 0.8 rotation keyframe has 4 components (axis and angle), not {}",
                    input.components
                ),
            });
        }
        let turned: Vec<f64> = (input.values().chunks_exact(4))
            .flat_map(|k| draft08::quaternion([k[0], k[1], k[2], k[3]]))
            .collect();
        let count = turned.len() / 4;
        let packed = data::pack_values(&turned, 4, data::FLOAT, false, false, &mut self.binary);
        let index = self.add_accessor(packed, "VEC4", count, Role::Data, Some(id));
        self.record_origin("accessors", index, at);
        Ok(index)
    }
}
