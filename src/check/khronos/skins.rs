//! Skins as the Khronos validator checks them beyond references: the inverse bind matrices
//! accessor (format, byteStride, count) and the joint hierarchy (a common root, a skeleton
//! among the common roots).

use super::nodes::{common_roots, parent_map};
use super::primitives::Format;
use crate::check::context::{elements, member, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::{Array, Node};
use crate::gltf::as_index;
use std::collections::HashMap;

pub(super) fn check(ctx: &mut Context) {
    let nodes = ctx.items("nodes");
    let parents = parent_map(nodes);
    // Each skin's topmost common root (a node without a parent), where its joints have one.
    let mut tops = HashMap::new();
    for (s, pointer, skin) in ctx.objects("skins") {
        // Joints that resolve (to a node that is an object), as the validator links them.
        let joints: Vec<usize> = elements(skin, "joints")
            .filter_map(|(_, j)| as_index(j).filter(|&j| ctx.element("nodes", j).is_some()))
            .map(|j| j as usize)
            .collect();
        inverse_binds(ctx, skin, &pointer);
        // A missing, empty or mistyped list is a schema error; the joints then have no
        // common root, which is not said again (a skeleton is still not one).
        let listed = skin
            .get("joints")
            .and_then(Node::as_array)
            .is_some_and(|j| !j.is_empty());
        let counted = if ctx.options.profile.refills_emptied_common_roots() {
            after_last_reset(&parents, &joints)
        } else {
            &joints[..]
        };
        let roots = match listed {
            true => common_roots(&parents, counted),
            false => Default::default(),
        };
        if let Some(&top) = roots.iter().find(|&&r| parents[r].is_none()) {
            tops.insert(s, top);
        }
        if listed && roots.is_empty() {
            ctx.emit(
                khronos::SKIN_NO_COMMON_ROOT,
                member(&pointer, "joints"),
                "Joints do not have a common root.",
            );
        }
        // A skeleton that names no node (or an element that is no object) is unresolved,
        // nothing more.
        let skeleton = unsigned(skin, "skeleton").filter(|&s| ctx.element("nodes", s).is_some());
        if skeleton.is_some_and(|s| !roots.contains(&(s as usize))) {
            ctx.emit(
                khronos::SKIN_SKELETON_INVALID,
                member(&pointer, "skeleton"),
                "Skeleton node is not a common root.",
            );
        }
    }
    skinned_nodes_in_scenes(ctx, &parents, &tops);
}

/// A skinned node shown by a scene that does not show its joints' topmost common root
/// (NODE_SKIN_NO_SCENE): the scenes that show a node are those listing it or an ancestor.
fn skinned_nodes_in_scenes(
    ctx: &mut Context,
    parents: &[Option<usize>],
    tops: &HashMap<usize, usize>,
) {
    if tops.is_empty() {
        return;
    }
    let mut listing: HashMap<usize, Vec<usize>> = HashMap::new();
    for (s, _, scene) in ctx.objects("scenes") {
        for (_, node) in elements(scene, "nodes") {
            if let Some(node) = as_index(node).and_then(|n| usize::try_from(n).ok()) {
                listing.entry(node).or_default().push(s);
            }
        }
    }
    let skinned: Vec<(usize, usize)> = (ctx.objects("nodes"))
        .filter_map(|(i, _, node)| {
            let skin = unsigned(node, "skin").filter(|&s| ctx.element("skins", s).is_some())?;
            Some((i, *tops.get(&(skin as usize))?))
        })
        .collect();
    // Each skinned node climbs its line once; a hostile tree of 10^5 skinned nodes in a
    // line of 10^5 is bounded by the budget (what is left unclimbed is not reported).
    let mut budget = CLIMB_BUDGET;
    for (i, top) in skinned {
        let empty = Vec::new();
        let shows_top = listing.get(&top).unwrap_or(&empty);
        let mut at = Some(i);
        let mut climbed = 0;
        let mut unshown = false;
        while let Some(node) = at.filter(|_| climbed <= parents.len() && budget > 0) {
            let scenes = listing.get(&node).map_or(&[][..], Vec::as_slice);
            if scenes.iter().any(|scene| !shows_top.contains(scene)) {
                unshown = true;
                break;
            }
            (at, climbed, budget) = (parents[node], climbed + 1, budget - 1);
        }
        if unshown {
            ctx.emit(
                khronos::NODE_SKIN_NO_SCENE,
                format!("/nodes/{i}"),
                "A node with a skinned mesh is used in a scene that does not contain joint nodes.",
            );
        }
    }
}

/// How many steps up their lines [`skinned_nodes_in_scenes`] takes in all.
const CLIMB_BUDGET: usize = 10_000_000;

/// The joints whose lines the Khronos validator intersects in the end. It refills an emptied
/// intersection with the next joint's line, so only the joints after the last one that
/// emptied it count, and none when the last joint emptied it. A joint empties it when its
/// line never meets the lines so far: it lies in another tree.
fn after_last_reset<'j>(parents: &[Option<usize>], joints: &'j [usize]) -> &'j [usize] {
    let mut roots = Roots::new(parents);
    let mut start = 0;
    let mut at = 1;
    while at < joints.len() {
        if roots.of(joints[at]) == roots.of(joints[start]) {
            at += 1;
        } else if at + 1 == joints.len() {
            return &[];
        } else {
            (start, at) = (at + 1, at + 2);
        }
    }
    &joints[start.min(joints.len())..]
}

/// The top of each node's line (for a line ending in a loop, the loop's least node), found
/// once per node.
struct Roots<'p> {
    parents: &'p [Option<usize>],
    known: Vec<Option<usize>>,
}

impl<'p> Roots<'p> {
    fn new(parents: &'p [Option<usize>]) -> Self {
        Roots {
            parents,
            known: vec![None; parents.len()],
        }
    }

    fn of(&mut self, node: usize) -> usize {
        let mut on_climb = HashMap::new();
        let mut climb = Vec::new();
        let mut at = node;
        let root = loop {
            if let Some(root) = self.known[at] {
                break root;
            }
            if let Some(&from) = on_climb.get(&at) {
                break climb[from..].iter().copied().min().unwrap_or(at);
            }
            on_climb.insert(at, climb.len());
            climb.push(at);
            match self.parents[at] {
                Some(parent) if parent < self.parents.len() => at = parent,
                _ => break at,
            }
        };
        for node in climb {
            self.known[node] = Some(root);
        }
        root
    }
}

fn inverse_binds(ctx: &mut Context, skin: Node, pointer: &str) {
    let Some(accessor) =
        unsigned(skin, "inverseBindMatrices").and_then(|a| ctx.element("accessors", a))
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
        .and_then(Node::as_array)
        .map_or(0, Array::len) as u64;
    // A missing or invalid count is the validator's -1: fewer than any joints.
    let count = unsigned(accessor, "count");
    // An empty list of joints (EMPTY_ENTITY) is none: no count is expected.
    if joints > 0 && count.is_none_or(|n| n < joints) {
        let found = count.map_or("-1".to_string(), |n| n.to_string());
        ctx.emit(
            khronos::INVALID_IBM_ACCESSOR_COUNT,
            at,
            format!("Accessor of count {joints} expected. Found {found}."),
        );
    }
}
