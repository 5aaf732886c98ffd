//! Skins as the Khronos validator checks them beyond references: the inverse bind matrices
//! accessor (format, byteStride, count) and the joint hierarchy (a common root, a skeleton
//! among the common roots).

use super::nodes::parent_map;
use super::primitives::Format;
use crate::check::context::{elements, member, unsigned, Context};
use crate::diagnostic::khronos;
use serde_json::Value;
use std::collections::HashSet;

pub fn check(ctx: &mut Context) {
    let nodes = ctx.items("nodes");
    let parents = parent_map(nodes);
    for (_, pointer, skin) in ctx.objects("skins") {
        let joints: Vec<usize> = elements(skin, "joints")
            .filter_map(|(_, j)| j.as_u64().map(|j| j as usize).filter(|j| *j < nodes.len()))
            .collect();
        inverse_binds(ctx, skin, &pointer);
        // An empty list is a schema error; the hierarchy is then not checked.
        let listed = skin
            .get("joints")
            .and_then(Value::as_array)
            .is_some_and(|j| !j.is_empty());
        if !listed {
            continue;
        }
        let roots = common_roots(&parents, &joints);
        if roots.is_empty() {
            ctx.emit(
                khronos::SKIN_NO_COMMON_ROOT,
                member(&pointer, "joints"),
                "Joints do not have a common root.",
            );
        }
        let skeleton = unsigned(skin, "skeleton").map(|s| s as usize);
        if skeleton.is_some_and(|s| s < nodes.len() && !roots.contains(&s)) {
            ctx.emit(
                khronos::SKIN_SKELETON_INVALID,
                member(&pointer, "skeleton"),
                "Skeleton node is not a common root.",
            );
        }
    }
}

/// The nodes that are each joint or an ancestor of it, for every joint. They lie on the
/// first joint's line to its root: each further joint can only cut that line from below,
/// at the point where its own line meets it. Where a node's line meets the first line is
/// remembered for every node climbed, so the whole search is linear in the nodes.
fn common_roots(parents: &[Option<usize>], joints: &[usize]) -> HashSet<usize> {
    let Some(&first) = joints.first() else {
        return HashSet::new();
    };
    // The first joint's line, bottom (the joint) to top; a loop is walked once.
    let mut on_line = vec![usize::MAX; parents.len()];
    let mut line = Vec::new();
    let mut at = Some(first);
    while let Some(node) = at.filter(|&n| on_line[n] == usize::MAX) {
        on_line[node] = line.len();
        line.push(node);
        at = parents[node];
    }
    // Where each climbed node's line meets the first line (None: it never does).
    let mut meets: Vec<Option<Option<usize>>> = vec![None; parents.len()];
    let mut lowest = 0;
    for &joint in &joints[1..] {
        let mut climbed = Vec::new();
        let mut at = Some(joint);
        let met = loop {
            let Some(node) = at else { break None };
            if on_line[node] != usize::MAX {
                break Some(on_line[node]);
            }
            if let Some(known) = meets[node] {
                break known;
            }
            // Marked before the answer is known: meeting it again on this climb means a loop
            // off the line, which never meets it.
            meets[node] = Some(None);
            climbed.push(node);
            at = parents[node];
        };
        for node in climbed {
            meets[node] = Some(met);
        }
        match met {
            Some(position) => lowest = lowest.max(position),
            None => return HashSet::new(),
        }
    }
    line[lowest..].iter().copied().collect()
}

fn inverse_binds(ctx: &mut Context, skin: &Value, pointer: &str) {
    let Some(accessor) =
        unsigned(skin, "inverseBindMatrices").and_then(|a| ctx.items("accessors").get(a as usize))
    else {
        return;
    };
    let at = member(pointer, "inverseBindMatrices");
    if ctx.has_strided_view(accessor) {
        ctx.emit(
            khronos::SKIN_IBM_ACCESSOR_WITH_BYTESTRIDE,
            at.clone(),
            "bufferView.byteStride must not be defined for buffer views used by inverse bind matrices accessors.",
        );
    }
    if !Format::of(accessor).is_plain_float("MAT4") {
        ctx.emit(
            khronos::SKIN_IBM_INVALID_FORMAT,
            at.clone(),
            "Invalid IBM accessor format. Must be MAT4 FLOAT.",
        );
    }
    let joints = skin
        .get("joints")
        .and_then(Value::as_array)
        .map_or(0, Vec::len) as u64;
    if unsigned(accessor, "count").is_some_and(|n| skin.get("joints").is_some() && n < joints) {
        ctx.emit(
            khronos::INVALID_IBM_ACCESSOR_COUNT,
            at,
            format!(
                "Accessor of count {joints} expected. Found {}.",
                unsigned(accessor, "count").unwrap_or(0)
            ),
        );
    }
}
