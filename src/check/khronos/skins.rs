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

/// The nodes that are each joint or an ancestor of it, for every joint.
fn common_roots(parents: &[Option<usize>], joints: &[usize]) -> HashSet<usize> {
    let lineage = |joint: usize| {
        let mut line = HashSet::new();
        let mut at = Some(joint);
        while let Some(node) = at.filter(|n| line.insert(*n)) {
            at = parents[node];
        }
        line
    };
    let mut lines = joints.iter().map(|j| lineage(*j));
    let first = lines.next().unwrap_or_default();
    lines.fold(first, |common, line| {
        common.intersection(&line).copied().collect()
    })
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
    if !Format::of(accessor).is_some_and(|f| f.is_plain_float("MAT4")) {
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
