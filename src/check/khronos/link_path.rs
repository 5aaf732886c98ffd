//! Where the released Khronos validator reports what it finds after an animation channel
//! without a sampler index, for the Khronos profile to report it there too.
//!
//! The validator names each finding by a path it pushes and pops as it links the document.
//! Linking an animation's channels, it pushes each channel's index but pops it only when the
//! channel has a sampler index; the pop meant for `channels` then takes a channel index
//! instead, and so on outwards. What it reports later carries the leftover: the animation's
//! unused samplers (`/animations/2/channels/0/samplers/0`), the channels and animations after
//! it, the scenes it links next, the node checks that end the linking and the unused objects
//! after them (`/animations/nodes/0`). Findings made while reading the document (the schema's) have
//! their own, right, paths. The default profile reports every finding at its own pointer.

use crate::check::context::unsigned;
use crate::check::schema::is_collection_element;
use crate::diagnostic::{khronos, Code};
use crate::document::Node;

/// What the validator's node checks, which end its linking, report.
const NODE_CHECKS: [Code; 5] = [
    khronos::NODE_EMPTY,
    khronos::NODE_LOOP,
    khronos::NODE_SKINNED_MESH_NON_ROOT,
    khronos::NODE_SKINNED_MESH_LOCAL_TRANSFORMS,
    khronos::NODE_SKIN_NO_SCENE,
];

/// The validator's path at each animation, and what is left of it after the animations.
#[derive(Debug, Default)]
pub(crate) struct LinkPath {
    /// Per animation: the path it is linked under (`animations` and any leftover before it)
    /// and its channels without a sampler index, in order.
    animations: Vec<(Vec<String>, Vec<usize>)>,
    /// The path left when the animations are linked (empty when nothing is left over).
    residue: Vec<String>,
}

impl LinkPath {
    /// The validator's paths for `root`'s animations; none when every channel has a sampler
    /// index (the paths are then the pointers themselves).
    pub(crate) fn of(root: Node) -> Option<LinkPath> {
        let animations = root.get("animations").and_then(Node::as_array)?;
        let unsampled = |animation: Node| -> Vec<usize> {
            let Some((_, channels)) = super::animations::linked(animation) else {
                return Vec::new();
            };
            (channels.iter().enumerate())
                .filter(|(_, channel)| {
                    channel.is_object() && unsigned(*channel, "sampler").is_none()
                })
                .map(|(k, _)| k)
                .collect()
        };
        let mut path = vec!["animations".to_string()];
        let mut any = false;
        let mut each = Vec::with_capacity(animations.len());
        for (a, animation) in animations.iter().enumerate() {
            let unsampled = if animation.is_object() {
                unsampled(animation)
            } else {
                Vec::new()
            };
            each.push((path.clone(), unsampled.clone()));
            // Left after linking it: its index, `channels` and all but the last of its
            // unsampled channels, less the one pop its collection makes.
            let mut left = match unsampled.len() {
                0 => Vec::new(),
                _ => [a.to_string(), "channels".to_string()]
                    .into_iter()
                    .chain(
                        unsampled[..unsampled.len() - 1]
                            .iter()
                            .map(usize::to_string),
                    )
                    .collect(),
            };
            any |= !unsampled.is_empty();
            if !left.is_empty() {
                left.pop();
            }
            path.extend(left);
        }
        if !any {
            return None;
        }
        path.pop();
        Some(LinkPath {
            animations: each,
            residue: path,
        })
    }

    /// The pointer the validator reports a finding of `code` at, for one found at `pointer`
    /// (none when it is the same).
    pub(crate) fn rewrite(&self, code: Code, pointer: &str) -> Option<String> {
        let name = code.name();
        let linked = code == khronos::UNRESOLVED_REFERENCE
            || code == khronos::UNUSED_OBJECT
            || name.starts_with("ANIMATION_")
            || name.starts_with("ACCESSOR_ANIMATION_");
        if let Some(rest) = pointer.strip_prefix("/animations/") {
            return linked.then(|| self.in_animation(code, rest)).flatten();
        }
        let after = pointer.starts_with("/scenes/")
            && (code == khronos::UNRESOLVED_REFERENCE || code == khronos::SCENE_NON_ROOT_NODE)
            || pointer.starts_with("/nodes/") && NODE_CHECKS.contains(&code)
            || code == khronos::UNUSED_OBJECT && is_collection_element(pointer);
        (after && !self.residue.is_empty()).then(|| format!("/{}{pointer}", self.residue.join("/")))
    }

    /// `rest`: the pointer after `/animations/`.
    fn in_animation(&self, code: Code, rest: &str) -> Option<String> {
        let (index, tail) = rest.split_once('/').unwrap_or((rest, ""));
        let (path, unsampled) = self.animations.get(index.parse::<usize>().ok()?)?;
        let mut tokens: Vec<String> = path.clone();
        tokens.push(index.to_string());
        let mut parts = tail.split('/');
        match (parts.next(), parts.next()) {
            (Some("channels"), Some(k)) => {
                let k: usize = k.parse().ok()?;
                tokens.push("channels".into());
                tokens.extend(unsampled.iter().filter(|&&b| b < k).map(usize::to_string));
                tokens.push(k.to_string());
            }
            (Some("samplers"), Some(j))
                if code == khronos::UNUSED_OBJECT && !unsampled.is_empty() =>
            {
                tokens.push("channels".into());
                tokens.extend(
                    unsampled[..unsampled.len() - 1]
                        .iter()
                        .map(usize::to_string),
                );
                tokens.extend(["samplers".to_string(), j.to_string()]);
            }
            (first, second) => tokens.extend(first.into_iter().chain(second).map(str::to_string)),
        }
        tokens.extend(parts.map(str::to_string));
        let rewritten = format!("/{}", tokens.join("/"));
        (rewritten != format!("/animations/{rest}")).then_some(rewritten)
    }
}
