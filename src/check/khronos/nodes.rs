//! Nodes as the Khronos validator checks them: transforms (matrix with TRS, default or
//! non-decomposable matrices, non-unit rotations), what a skin or morph weights depend on,
//! the hierarchy (a second parent, loops, scene roots that are children) and skinned meshes
//! under transformed parents.

use super::accessor_usage::UNIT_TOLERANCE_VEC4;
use super::primitives::{joint_sets, mesh_morph_targets};
use crate::check::context::{elements, member, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::Array;
use crate::document::Node;
use crate::gltf::as_index;
use std::collections::{HashMap, HashSet};

/// How far a matrix may be from its TRS recomposition.
const TRS_TOLERANCE: f64 = 0.00005;

pub(super) fn check(ctx: &mut Context) {
    let nodes = ctx.items("nodes");
    let parents = parents(ctx, nodes);
    let hierarchy = Hierarchy::of(nodes, &parents);
    let mut lost = LostTransforms::default();
    for (i, pointer, node) in ctx.objects("nodes") {
        transforms(ctx, node, &pointer);
        dependencies(ctx, node, &pointer);
        if hierarchy.on_loop.get(i) == Some(&true) {
            ctx.emit(
                khronos::NODE_LOOP,
                pointer.clone(),
                "Node is a part of a node loop.",
            );
        }
        // A skin that resolves to no object (UNRESOLVED_REFERENCE) skins nothing.
        if unsigned(node, "skin").is_some_and(|s| ctx.element("skins", s).is_some()) {
            skinned_placement(ctx, nodes, &parents, &hierarchy, &mut lost, i, &pointer);
        }
    }
    for (_, pointer, scene) in ctx.objects("scenes") {
        for (k, root) in elements(scene, "nodes") {
            let index = as_index(root).map(|n| n as usize);
            if index.is_some_and(|n| parent_of(&parents, n).is_some()) {
                ctx.emit(
                    khronos::SCENE_NON_ROOT_NODE,
                    format!("{pointer}/nodes/{k}"),
                    format!("Node {} is not a root node.", index.unwrap_or_default()),
                );
            }
        }
    }
    unused_mesh_weights(ctx, nodes);
}

/// Each node's parent, walking `children` in node order; a node listed as a child more than
/// once gets the last parent that lists it. Calls `relisted(parent, k, child)` for each
/// listing after the first. Empty when no node lists a child (10^7 nodes that are all
/// roots need no list of 10^7 parents).
fn walk_parents(nodes: Array, mut relisted: impl FnMut(usize, usize, usize)) -> Vec<Option<usize>> {
    let mut parent = Vec::new();
    for (i, node) in nodes.iter().enumerate() {
        for (k, child) in elements(node, "children") {
            // A child that resolves to no object (UNRESOLVED_REFERENCE) has no parent.
            let Some(c) = as_index(child)
                .map(|c| c as usize)
                .filter(|c| *c < nodes.len() && nodes.at(*c).is_object())
            else {
                continue;
            };
            if parent.is_empty() {
                parent = vec![None; nodes.len()];
            }
            if parent[c].is_some() {
                relisted(i, k, c);
            }
            parent[c] = Some(i);
        }
    }
    parent
}

/// Each node's parent (see `walk_parents`), for every node.
pub(super) fn parent_map(nodes: Array) -> Vec<Option<usize>> {
    let parents = walk_parents(nodes, |_, _, _| {});
    if parents.is_empty() {
        return vec![None; nodes.len()];
    }
    parents
}

/// A node's parent in a list `walk_parents` made.
fn parent_of(parents: &[Option<usize>], node: usize) -> Option<usize> {
    parents.get(node).copied().flatten()
}

/// Each node's parent; a second listing as a child is NODE_PARENT_OVERRIDE.
fn parents(ctx: &mut Context, nodes: Array) -> Vec<Option<usize>> {
    let mut overrides = Vec::new();
    let parent = walk_parents(nodes, |i, k, c| overrides.push((i, k, c)));
    for (i, k, c) in overrides {
        ctx.emit(
            khronos::NODE_PARENT_OVERRIDE,
            format!("/nodes/{i}/children/{k}"),
            format!("Value overrides parent of node {c}."),
        );
    }
    parent
}

/// What each node's ancestry holds, found for all nodes in one walk (memoised, so a
/// 10^5-node chain costs 10^5 steps, not 10^10).
struct Hierarchy {
    /// Walking up from the node comes back to it.
    on_loop: Vec<bool>,
    /// Some ancestor (on a loop: some node of the loop) has a transform.
    transformed_above: Vec<bool>,
}

impl Hierarchy {
    fn of(nodes: Array, parents: &[Option<usize>]) -> Hierarchy {
        let n = parents.len();
        let mut on_loop = vec![false; n];
        let mut above: Vec<Option<bool>> = vec![None; n];
        // Where each node of the current climb is on it (u32: at most 2^24 values).
        let mut position = vec![u32::MAX; n];
        let transformed = |i: usize| has_transform(nodes.at(i));
        for start in 0..n {
            // Climb until a root, a node already known, or a node of this climb (a loop).
            let mut path = Vec::new();
            let mut at = Some(start);
            while let Some(node) = at.filter(|&a| above[a].is_none() && position[a] == u32::MAX) {
                position[node] = path.len() as u32;
                path.push(node);
                at = parents[node];
            }
            let mut known = match at {
                None => false,
                Some(a) if position[a] != u32::MAX => {
                    let cycle = path.split_off(position[a] as usize);
                    let any = cycle.iter().any(|&c| transformed(c));
                    for &c in &cycle {
                        on_loop[c] = true;
                        above[c] = Some(any);
                        position[c] = u32::MAX;
                    }
                    any
                }
                Some(a) => transformed(a) || above[a].unwrap_or(false),
            };
            // Down again: each node's answer is its parent's transform or the parent's answer.
            for &node in path.iter().rev() {
                above[node] = Some(known);
                position[node] = u32::MAX;
                known = known || transformed(node);
            }
        }
        Hierarchy {
            on_loop,
            transformed_above: above.into_iter().map(|a| a.unwrap_or(false)).collect(),
        }
    }
}

fn numbers(node: Node, key: &str, length: usize) -> Option<Vec<f64>> {
    let list = node.get(key)?.as_array()?;
    let values: Vec<f64> = list.iter().filter_map(Node::as_f64).collect();
    (values.len() == length && list.len() == length).then_some(values)
}

fn transforms(ctx: &mut Context, node: Node, pointer: &str) {
    if let Some(q) = numbers(node, "rotation", 4).filter(|q| q.iter().all(|v| v.abs() <= 1.0)) {
        let length = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        if (1.0 - length).abs() > UNIT_TOLERANCE_VEC4 {
            ctx.emit(
                khronos::ROTATION_NON_UNIT,
                member(pointer, "rotation"),
                "Rotation quaternion must be normalized.",
            );
        }
    }
    let Some(matrix) = numbers(node, "matrix", 16) else {
        return;
    };
    // The validator holds a matrix in single precision: 0.9999999776482582 is 1 there.
    let matrix: Vec<f64> = matrix.iter().map(|&v| f64::from(v as f32)).collect();
    let at = member(pointer, "matrix");
    if ["translation", "rotation", "scale"]
        .iter()
        .any(|k| node.get(k).is_some())
    {
        ctx.emit(
            khronos::NODE_MATRIX_TRS,
            at.clone(),
            "A node can have either a matrix or any combination of translation/rotation/scale (TRS) properties.",
        );
    }
    if matrix == IDENTITY {
        ctx.emit(
            khronos::NODE_MATRIX_DEFAULT,
            at,
            "Do not specify default transform matrix.",
        );
    } else if !is_trs_decomposable(&matrix) {
        ctx.emit(
            khronos::NODE_MATRIX_NON_TRS,
            at,
            "Matrix must be decomposable to TRS.",
        );
    }
}

const IDENTITY: [f64; 16] = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

/// Whether a column-major matrix is translation × rotation × scale, decided as the Khronos
/// validator decides it (its vector_math library, single-precision storage): an affine last
/// row, a non-zero determinant, then the matrix decomposed, recomposed, and the two compared
/// by their largest column sums (`absoluteError` < 5·10⁻⁵). Every value the library stores
/// is rounded to single precision, which is what makes a large scale fail; the comparison of
/// norms is what lets some shears pass.
pub(crate) fn is_trs_decomposable(m: &[f64]) -> bool {
    if m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0 {
        return false;
    }
    let det = determinant(m);
    if det == 0.0 {
        return false;
    }
    let length = |c: usize| {
        (m[4 * c] * m[4 * c] + m[4 * c + 1] * m[4 * c + 1] + m[4 * c + 2] * m[4 * c + 2]).sqrt()
    };
    let mut scale = [length(0), length(1), length(2)];
    if det < 0.0 {
        scale[0] = -scale[0];
    }
    // The rotation part: each column divided by its scale, stored.
    let mut r = [0.0; 9];
    for c in 0..3 {
        let inverse = 1.0 / scale[c];
        for row in 0..3 {
            r[3 * c + row] = single(m[4 * c + row] * inverse);
        }
    }
    let q = quaternion(&r).map(single);
    let scale = scale.map(single);
    let mut recomposed = [0.0; 16];
    recomposed[..12].copy_from_slice(&rotation_columns(q));
    recomposed[12..].copy_from_slice(&m[12..16]);
    for c in 0..3 {
        for row in 0..4 {
            recomposed[4 * c + row] = single(single(recomposed[4 * c + row]) * scale[c]);
        }
    }
    (largest_column_sum(&recomposed) - largest_column_sum(m)).abs() < TRS_TOLERANCE
}

/// A value as single-precision storage holds it.
fn single(v: f64) -> f64 {
    f64::from(v as f32)
}

/// The determinant of a column-major 4×4 matrix, expanded as vector_math expands it.
fn determinant(m: &[f64]) -> f64 {
    let d01_01 = m[0] * m[5] - m[1] * m[4];
    let d01_02 = m[0] * m[6] - m[2] * m[4];
    let d01_03 = m[0] * m[7] - m[3] * m[4];
    let d01_12 = m[1] * m[6] - m[2] * m[5];
    let d01_13 = m[1] * m[7] - m[3] * m[5];
    let d01_23 = m[2] * m[7] - m[3] * m[6];
    let d201_012 = m[8] * d01_12 - m[9] * d01_02 + m[10] * d01_01;
    let d201_013 = m[8] * d01_13 - m[9] * d01_03 + m[11] * d01_01;
    let d201_023 = m[8] * d01_23 - m[10] * d01_03 + m[11] * d01_02;
    let d201_123 = m[9] * d01_23 - m[10] * d01_13 + m[11] * d01_12;
    -d201_123 * m[12] + d201_023 * m[13] - d201_013 * m[14] + d201_012 * m[15]
}

/// The quaternion (x, y, z, w) of a column-major 3×3 rotation, as vector_math's
/// `setFromRotation` computes it.
fn quaternion(r: &[f64; 9]) -> [f64; 4] {
    let at = |row: usize, col: usize| r[3 * col + row];
    let trace = r[0] + r[4] + r[8];
    let mut q = [0.0; 4];
    if trace > 0.0 {
        let s = (trace + 1.0).sqrt();
        q[3] = s * 0.5;
        let s = 0.5 / s;
        q[0] = (r[5] - r[7]) * s;
        q[1] = (r[6] - r[2]) * s;
        q[2] = (r[1] - r[3]) * s;
    } else {
        let i = if r[0] < r[4] {
            if r[4] < r[8] {
                2
            } else {
                1
            }
        } else if r[0] < r[8] {
            2
        } else {
            0
        };
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let s = (at(i, i) - at(j, j) - at(k, k) + 1.0).sqrt();
        q[i] = s * 0.5;
        let s = 0.5 / s;
        q[3] = (at(k, j) - at(j, k)) * s;
        q[j] = (at(j, i) + at(i, j)) * s;
        q[k] = (at(k, i) + at(i, k)) * s;
    }
    q
}

/// The first three columns (with their zero fourth row) of the rotation a quaternion
/// gives, as vector_math's `setFromTranslationRotation` writes them (not normalised).
fn rotation_columns([x, y, z, w]: [f64; 4]) -> [f64; 12] {
    let (x2, y2, z2) = (x + x, y + y, z + z);
    let (xx, xy, xz) = (x * x2, x * y2, x * z2);
    let (yy, yz, zz) = (y * y2, y * z2, z * z2);
    let (wx, wy, wz) = (w * x2, w * y2, w * z2);
    [
        1.0 - (yy + zz),
        xy + wz,
        xz - wy,
        0.0,
        xy - wz,
        1.0 - (xx + zz),
        yz + wx,
        0.0,
        xz + wy,
        yz - wx,
        1.0 - (xx + yy),
        0.0,
    ]
}

/// The largest sum of absolute values over the four columns (vector_math's `infinityNorm`).
fn largest_column_sum(m: &[f64]) -> f64 {
    (0..4)
        .map(|c| m[4 * c..4 * c + 4].iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// A skin or morph weights need a mesh; weights must match its morph targets; a skin needs
/// a skinned mesh, and a skinned mesh a skin.
fn dependencies(ctx: &mut Context, node: Node, pointer: &str) {
    if node.get("mesh").is_none() {
        for key in ["skin", "weights"] {
            if node.get(key).is_some() {
                ctx.emit(
                    khronos::UNSATISFIED_DEPENDENCY,
                    member(pointer, key),
                    "Dependency failed. 'mesh' must be defined.",
                );
            }
        }
        return;
    }
    let mesh = unsigned(node, "mesh").and_then(|m| ctx.element("meshes", m));
    // An empty list of primitives (EMPTY_ENTITY) is none, as the validator reads it.
    let primitives = mesh.and_then(|m| m.get("primitives")?.as_array());
    let Some(primitives) = primitives.filter(|p| !p.is_empty()) else {
        return;
    };
    // An empty list of weights (EMPTY_ENTITY) is none too.
    let weights = node.get("weights").and_then(Node::as_array);
    if let Some(weights) = weights.filter(|w| !w.is_empty()) {
        let targets = mesh.and_then(mesh_morph_targets);
        if targets != Some(weights.len()) {
            ctx.emit(
                khronos::NODE_WEIGHTS_INVALID,
                member(pointer, "weights"),
                format!("The length of weights array ({}) does not match the number of morph targets ({}).", weights.len(), targets.unwrap_or(0)),
            );
        }
    }
    let skinned = |p: Node| {
        p.get("attributes")
            .and_then(Node::as_object)
            .is_some_and(|a| joint_sets(a) > 0)
    };
    // An unresolved skin is none, as the validator links it.
    let has_skin = unsigned(node, "skin")
        .and_then(|s| ctx.element("skins", s))
        .is_some();
    if has_skin && !primitives.iter().any(skinned) {
        ctx.emit(
            khronos::NODE_SKIN_WITH_NON_SKINNED_MESH,
            pointer,
            "Node has skin defined, but mesh has no joints data.",
        );
    }
    if !has_skin && primitives.iter().any(skinned) {
        ctx.emit(
            khronos::NODE_SKINNED_MESH_WITHOUT_SKIN,
            pointer,
            "Node uses skinned mesh, but has no skin defined.",
        );
    }
}

/// Whether a node moves what it holds: a non-identity matrix or any non-default TRS.
fn has_transform(node: Node) -> bool {
    let is =
        |key: &str, default: &[f64]| numbers(node, key, default.len()).is_none_or(|v| v == default);
    !(is("matrix", &IDENTITY)
        && is("translation", &[0.0; 3])
        && is("rotation", &[0.0, 0.0, 0.0, 1.0])
        && is("scale", &[1.0; 3]))
}

/// A skinned mesh ignores its node's and its ancestors' transforms: say so. The Khronos
/// profile follows the released validator (2.0.0-dev.3.10): a warning for every non-root
/// skinned node. The default profile reports only what is lost, a parent's transform, as
/// the next Khronos build does (NODE_SKINNED_MESH_PARENT_TRANSFORMS), and only where it is
/// lost: a transformed ancestor that is also an ancestor of every joint reaches the mesh
/// through the joints (CesiumMan, BrainStem), so nothing is lost on screen.
fn skinned_placement(
    ctx: &mut Context,
    nodes: Array,
    parents: &[Option<usize>],
    hierarchy: &Hierarchy,
    lost: &mut LostTransforms,
    i: usize,
    pointer: &str,
) {
    if has_transform(nodes.at(i)) {
        ctx.emit(
            khronos::NODE_SKINNED_MESH_LOCAL_TRANSFORMS,
            pointer,
            "Local transforms will not affect a skinned mesh.",
        );
    }
    if parent_of(parents, i).is_none() {
        return;
    }
    // The released validator's warning, and the newer builds' narrower one (the profiles
    // each report one of them: `khronos::RETIRED`, `khronos::UNRELEASED`).
    ctx.emit(
        khronos::NODE_SKINNED_MESH_NON_ROOT,
        pointer,
        "Node with a skinned mesh is not root. Parent transforms will not affect a skinned mesh.",
    );
    let skin = unsigned(nodes.at(i), "skin").map(|s| s as usize);
    let skins = ctx.items("skins");
    let mut reaches_not_through_joints = || match skin.and_then(|s| Some((s, skins.get(s)?))) {
        Some((s, skin)) => lost.above(nodes, parents, s, skin, i),
        None => true,
    };
    if hierarchy.transformed_above.get(i) == Some(&true) && reaches_not_through_joints() {
        ctx.emit(
            khronos::NODE_SKINNED_MESH_PARENT_TRANSFORMS,
            pointer,
            "Node with a skinned mesh has parent nodes with transforms. Parent transforms will not affect a skinned mesh.",
        );
    }
}

/// The nodes that are each joint or an ancestor of it, for every joint. They lie on the
/// first joint's line to its root: each further joint can only cut that line from below,
/// at the point where its own line meets it. Where a node's line meets the first line is
/// remembered for every node climbed, so the whole search is linear in the nodes.
pub(super) fn common_roots(parents: &[Option<usize>], joints: &[usize]) -> HashSet<usize> {
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

/// Per skin, the nodes that are an ancestor of every joint, and for each node climbed whether
/// a transformed node lies between it and the first of those above it: a transform there
/// moves the node but not the joints, and is lost to a skinned mesh. Each node is climbed
/// once per skin.
#[derive(Default)]
struct LostTransforms {
    per_skin: HashMap<usize, (HashSet<usize>, HashMap<usize, bool>)>,
}

impl LostTransforms {
    /// Whether a transform above `node` (skinned by `skin`, index `s`) is lost.
    fn above(
        &mut self,
        nodes: Array,
        parents: &[Option<usize>],
        s: usize,
        skin: Node,
        node: usize,
    ) -> bool {
        let (common, memo) = self.per_skin.entry(s).or_insert_with(|| {
            let joints: Vec<usize> = elements(skin, "joints")
                .filter_map(|(_, j)| {
                    as_index(j)
                        .map(|j| j as usize)
                        .filter(|j| *j < parents.len())
                })
                .collect();
            (common_roots(parents, &joints), HashMap::new())
        });
        // Climb from the parent until a node every joint hangs from, or a known answer.
        let mut climbed = Vec::new();
        let mut on_climb = HashSet::new();
        let mut at = parent_of(parents, node);
        let answer = loop {
            let Some(n) = at else { break false };
            if common.contains(&n) {
                break false;
            }
            if let Some(&known) = memo.get(&n) {
                break known;
            }
            if has_transform(nodes.at(n)) {
                break true;
            }
            if !on_climb.insert(n) {
                break false; // a loop, reported as NODE_LOOP
            }
            climbed.push(n);
            at = parent_of(parents, n);
        };
        for n in climbed {
            memo.insert(n, answer);
        }
        answer
    }
}

/// A mesh's own morph weights do nothing when every node that draws it has weights, or when
/// it has no primitives (the validator reads no weights for a node on such a mesh).
fn unused_mesh_weights(ctx: &mut Context, nodes: Array) {
    // Per mesh: the nodes that draw it, and how many of them have their own weights.
    let mut drawn_by: HashMap<usize, (usize, usize)> = HashMap::new();
    for node in nodes {
        if let Some(mesh) = unsigned(node, "mesh") {
            let entry = drawn_by.entry(mesh as usize).or_default();
            entry.0 += 1;
            entry.1 += usize::from(node.get("weights").is_some());
        }
    }
    for (m, pointer, mesh) in ctx.objects("meshes") {
        if mesh.get("weights").is_none() {
            continue;
        }
        let (users, overriding) = drawn_by.get(&m).copied().unwrap_or((0, 0));
        let primitives = mesh.get("primitives").and_then(Node::as_array);
        let drawn = primitives.is_some_and(|p| !p.is_empty());
        if users > 0 && (users == overriding || !drawn) {
            ctx.emit(
                khronos::UNUSED_MESH_WEIGHTS,
                member(&pointer, "weights"),
                "The static morph target weights are always overridden.",
            );
        }
    }
}
