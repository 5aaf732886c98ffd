//! Animations as the Khronos validator checks them beyond references: sampler input and
//! output accessors (format, bounds, byteStride, key frame counts) and channel targets
//! (matrix or skinned nodes, morph weights without targets, duplicates).

use super::primitives::{mesh_morph_targets, Format};
use crate::check::context::{elements, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::Array;
use crate::document::Node;
use std::collections::HashMap;

pub(crate) fn check(ctx: &mut Context) {
    let pointer_paths = ctx.uses_extension("KHR_animation_pointer");
    for (_, pointer, animation) in ctx.objects("animations") {
        let links = linked(animation).is_some();
        for (c, channel) in elements(animation, "channels") {
            let at = format!("{pointer}/channels/{c}/target");
            animation_pointer(ctx, channel, &at, pointer_paths, links);
        }
        let Some((samplers, channels)) = linked(animation) else {
            continue;
        };
        for (s, sampler) in samplers.iter().enumerate() {
            sampler_accessors(ctx, sampler, &format!("{pointer}/samplers/{s}"));
        }
        let mut later = later_channels_per_target(channels);
        for (c, channel) in channels.iter().enumerate() {
            let at = format!("{pointer}/channels/{c}");
            target(ctx, channel, &at);
            let sampler = unsigned(channel, "sampler").and_then(|s| samplers.get(s as usize));
            if let Some(sampler) = sampler {
                output(ctx, channel, sampler, &at);
            }
            let remaining = target_key(channel).and_then(|key| later.get_mut(&key));
            // A channel whose sampler is no index still counts for the later ones, but is
            // not itself reported, as the validator does.
            if let Some(remaining) = remaining {
                *remaining -= 1;
                if *remaining > 0 && unsigned(channel, "sampler").is_some() {
                    ctx.emit(
                        khronos::ANIMATION_DUPLICATE_TARGETS,
                        format!("{at}/target"),
                        "Animation channel has the same target as another channel.",
                    );
                }
            }
        }
    }
}

/// An animation's samplers and channels, when it has both lists and neither is empty: the
/// Khronos validator links nothing of an animation without them (its samplers' accessors stay
/// unused, its samplers and target nodes unchecked).
pub(crate) fn linked(animation: Node) -> Option<(Array, Array)> {
    let list = |key: &str| animation.get(key)?.as_array().filter(|a| !a.is_empty());
    Some((list("samplers")?, list("channels")?))
}

/// The target path `pointer` exists only with KHR_animation_pointer, which then owns the
/// target: no node (asked, as the validator asks, only of an animation it links, see
/// [`linked`], and of a node the target resolves to), and that path.
fn animation_pointer(ctx: &mut Context, channel: Node, at: &str, declared: bool, links: bool) {
    let Some(target) = channel.get("target") else {
        return;
    };
    let path = target.get("path").and_then(Node::as_str);
    if path == Some("pointer") && !declared {
        ctx.emit(
            khronos::VALUE_NOT_IN_LIST,
            format!("{at}/path"),
            "Invalid value 'pointer'. Valid values are ('translation', 'rotation', 'scale', 'weights').",
        );
    }
    let Some(extension) = target
        .get("extensions")
        .and_then(|e| e.get("KHR_animation_pointer"))
    else {
        return;
    };
    let here = format!("{at}/extensions/KHR_animation_pointer");
    if !extension.is_object() {
        return;
    }
    ctx.emit(
        khronos::INCOMPLETE_EXTENSION_SUPPORT,
        here.clone(),
        "Validation support for this extension is incomplete; the asset may have undetected issues.",
    );
    // Asked of the node the target links to: an index that resolves to nothing is
    // reported unresolved, and not again here.
    let node = target.get("node").and_then(Node::as_u64);
    if links && node.is_some_and(|n| ctx.element("nodes", n).is_some()) {
        ctx.emit(
            khronos::KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_NODE,
            here.clone(),
            "This extension requires the animation channel target node to be undefined.",
        );
    }
    // An absent or mistyped path is not 'pointer' either (the validator reads it as null).
    if path != Some("pointer") {
        let found = path.unwrap_or("null");
        ctx.emit(
            khronos::KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_PATH,
            here,
            format!("This extension requires the animation channel target path to be 'pointer'. Found '{found}' instead."),
        );
    }
}

/// (node, path) of a channel's target, when it names a node.
/// How many channels target each (node, path). A channel followed by another with its target
/// gets one finding, as the Khronos validator words it for a pair; for three or more channels
/// on one target that validator reports every later one again (N²/2 findings for N
/// channels), which gltfmat does not: one finding per repeating channel is the same news.
fn later_channels_per_target(channels: Array<'_>) -> HashMap<(u64, &str), usize> {
    let mut counts = HashMap::new();
    for key in channels.iter().filter_map(target_key) {
        *counts.entry(key).or_insert(0) += 1;
    }
    counts
}

fn target_key(channel: Node<'_>) -> Option<(u64, &str)> {
    let target = channel.get("target")?;
    Some((unsigned(target, "node")?, target.get("path")?.as_str()?))
}

fn accessor<'a>(ctx: &Context<'a>, object: Node, key: &str) -> Option<Node<'a>> {
    ctx.element("accessors", unsigned(object, key)?)
}

/// A sampler's interpolation: LINEAR when absent, none when it is not a string (the
/// validator then neither takes the default nor counts keys).
fn interpolation(sampler: Node<'_>) -> Option<&str> {
    match sampler.get("interpolation") {
        None => Some("LINEAR"),
        Some(given) => given.as_str(),
    }
}

fn sampler_accessors(ctx: &mut Context, sampler: Node, at: &str) {
    for key in ["input", "output"] {
        let Some(data) = accessor(ctx, sampler, key) else {
            continue;
        };
        if ctx.has_strided_view(data) {
            ctx.emit(
                khronos::ANIMATION_SAMPLER_ACCESSOR_WITH_BYTESTRIDE,
                format!("{at}/{key}"),
                "bufferView.byteStride must not be defined for buffer views used by animation sampler accessors.",
            );
        }
    }
    let Some(input) = accessor(ctx, sampler, "input") else {
        return;
    };
    let at = format!("{at}/input");
    if !Format::of(input).is_plain_float("SCALAR") {
        ctx.emit(
            khronos::ANIMATION_SAMPLER_INPUT_ACCESSOR_INVALID_FORMAT,
            at.clone(),
            "Invalid Animation sampler input accessor format. Must be SCALAR FLOAT.",
        );
    }
    if !Format::has_bounds(input) {
        ctx.emit(
            khronos::ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS,
            at.clone(),
            "accessor.min and accessor.max must be defined for animation input accessor.",
        );
    }
    // A count that is missing or invalid reads as none at all, as the validator reads it.
    let cubic = interpolation(sampler) == Some("CUBICSPLINE");
    if cubic && unsigned(input, "count").is_none_or(|n| n < 2) {
        ctx.emit(
            khronos::ANIMATION_SAMPLER_INPUT_ACCESSOR_TOO_FEW_ELEMENTS,
            at,
            "Animation sampler has CUBICSPLINE interpolation; input accessor must have at least 2 elements.",
        );
    }
}

/// The morph target count of the mesh a channel's node draws.
fn morph_target_count(ctx: &Context, node: Node) -> Option<usize> {
    mesh_morph_targets(ctx.element("meshes", unsigned(node, "mesh")?)?)
}

fn target(ctx: &mut Context, channel: Node, at: &str) {
    let Some(target) = channel.get("target") else {
        return;
    };
    let Some(node) = unsigned(target, "node").and_then(|n| ctx.element("nodes", n)) else {
        return;
    };
    match target.get("path").and_then(Node::as_str) {
        Some("translation" | "rotation" | "scale") => {
            if node.get("matrix").is_some() {
                ctx.emit(
                    khronos::ANIMATION_CHANNEL_TARGET_NODE_MATRIX,
                    format!("{at}/target"),
                    "Animation channel cannot target TRS properties of a node with defined matrix.",
                );
            }
            // A skin that resolves to no object skins nothing.
            if unsigned(node, "skin").is_some_and(|s| ctx.element("skins", s).is_some()) {
                ctx.emit(
                    khronos::ANIMATION_CHANNEL_TARGET_NODE_SKIN,
                    format!("{at}/target/path"),
                    "Animated TRS properties will not affect a skinned mesh.",
                );
            }
        }
        Some("weights") if morph_target_count(ctx, node).is_none() => ctx.emit(
            khronos::ANIMATION_CHANNEL_TARGET_NODE_WEIGHTS_NO_MORPHS,
            format!("{at}/target"),
            "Animation channel cannot target WEIGHTS when mesh does not have morph targets.",
        ),
        _ => {}
    }
}

/// The sampler output must suit the targeted property, with one value (three for cubic
/// splines) per key frame, times the morph target count for weights.
fn output(ctx: &mut Context, channel: Node, sampler: Node, at: &str) {
    let Some(output) = accessor(ctx, sampler, "output") else {
        return;
    };
    let Some(target) = channel.get("target") else {
        return;
    };
    let path = target.get("path").and_then(Node::as_str).unwrap_or("");
    if Format::of(output).allowed_for_animation(path) == Some(false) {
        ctx.emit(
            khronos::ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_FORMAT,
            format!("{at}/sampler"),
            format!("Invalid animation sampler output accessor format for path '{path}'."),
        );
    }
    let Some(input) = accessor(ctx, sampler, "input") else {
        return;
    };
    let (Some(keys), Some(count)) = (unsigned(input, "count"), unsigned(output, "count")) else {
        return;
    };
    let per_key = match interpolation(sampler) {
        Some("CUBICSPLINE") => 3,
        Some(_) => 1,
        None => return,
    };
    let node = unsigned(target, "node").and_then(|n| ctx.element("nodes", n));
    let values = match path {
        "weights" => node.and_then(|n| morph_target_count(ctx, n)).unwrap_or(0) as u64,
        "translation" | "rotation" | "scale" => 1,
        _ => 0,
    };
    let expected = keys * per_key * values;
    if expected != 0 && expected != count {
        ctx.emit(
            khronos::ANIMATION_SAMPLER_OUTPUT_ACCESSOR_INVALID_COUNT,
            format!("{at}/sampler"),
            format!(
                "Animation sampler output accessor of count {expected} expected. Found {count}."
            ),
        );
    }
}
