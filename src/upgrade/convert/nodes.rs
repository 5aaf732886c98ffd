//! Nodes and skins: per-instance skins, bindShapeMatrix folded into the inverse bind matrices, transforms copied.

use crate::document::Node;
use crate::shade::brdf::{cross, dot, normalize};
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
            let transform = copy_transform(node, &mut out);
            if transform == Transform::Decomposed {
                self.note(
                    pointer("nodes", id),
                    NoteKind::Decision,
                    "matrix written as translation, rotation and scale: a glTF 2.0 reader recomposing it in single precision (the Khronos validator) would not find it decomposable.",
                );
            }
            if let Some(camera) = self.index_of("cameras", node.get("camera")) {
                out.insert("camera".into(), json!(camera));
            }
            let skin = self.skin_instance(id, node)?;
            let meshes: Vec<usize> = id_list(node.get("meshes"))
                .iter()
                .filter_map(|m| self.mesh_index(m))
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
            if let Transform::Sheared(inner_rotation) = transform {
                let inner = sheared_content(&mut out, id, inner_rotation);
                out.insert("children".into(), json!([nodes.len() + extra_nodes.len()]));
                extra_nodes.push((inner, format!("{}/matrix", pointer("nodes", id))));
                self.note(
                    pointer("nodes", id),
                    NoteKind::Decision,
                    format!("sheared matrix written as two nodes (2.0 node transforms cannot shear): this one's translation, rotation and scale, then a child \"{id}-unsheared\" turning by a second rotation and holding what the node held; together the same transform."),
                );
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

/// How a node's transform was written.
#[derive(PartialEq)]
enum Transform {
    /// As the 1.0 node had it (or none: an identity matrix is left out).
    AsWritten,
    /// Its matrix as translation, rotation and scale.
    Decomposed,
    /// Its sheared matrix as translation, rotation and scale, and a child turning by this
    /// rotation (x, y, z, w), which is to hold the node's content.
    Sheared([f64; 4]),
}

/// The matrix, or translation/rotation/scale, of a 1.0 node. A matrix that is a rotation and
/// a scale but that a single-precision reader cannot recompose (a large scale) is written as
/// its translation, rotation and scale, which describe the same transform: 2.0 requires a
/// node matrix to be decomposable, and the output must pass its own check.
fn copy_transform(node: Node, out: &mut Map<String, Value>) -> Transform {
    match matrix(node.get("matrix")) {
        Some(m) if m != IDENTITY => {
            let single: Vec<f64> = m.iter().map(|&v| f64::from(v as f32)).collect();
            // A joint's skin reads the node itself: its shear cannot move to a child.
            let parts = match (crate::check::is_trs_decomposable(&single), decomposed(&m)) {
                (false, Some(parts)) => Some((parts, None)),
                (false, None) if node.get("jointName").is_none() => {
                    unsheared(&m).map(|(t, r, s, inner)| ((t, r, s), Some(inner)))
                }
                _ => None,
            };
            match parts {
                Some(((translation, rotation, scale), inner)) => {
                    out.insert("translation".into(), json!(translation));
                    out.insert("rotation".into(), json!(rotation));
                    out.insert("scale".into(), json!(scale));
                    return inner.map_or(Transform::Decomposed, Transform::Sheared);
                }
                None => {
                    out.insert("matrix".into(), json!(m));
                }
            }
        }
        _ => {
            for key in ["translation", "rotation", "scale"] {
                if let Some(v) = node.get(key) {
                    out.insert(key.into(), v.to_value());
                }
            }
        }
    }
    Transform::AsWritten
}

/// A column-major affine matrix as translation, unit rotation quaternion (x, y, z, w) and
/// scale, when its 3×3 part is a rotation times a scale (columns orthogonal to within 10⁻⁹
/// of their lengths); `None` for a shear or a projection. A column of length zero (a node
/// flattened or hidden by a zero scale, which 1.0 writes as a matrix and 2.0 cannot decompose)
/// gets scale 0 along an axis completing the others to a rotation.
#[allow(clippy::type_complexity)]
fn decomposed(m: &[f64; 16]) -> Option<([f64; 3], [f64; 4], [f64; 3])> {
    let columns = linear_part(m)?;
    let mut scale = columns.map(|c| dot(c, c).sqrt());
    if scale.iter().any(|s| !s.is_finite()) {
        return None;
    }
    let unit = [0, 1, 2].map(|c| (scale[c] > 0.0).then(|| columns[c].map(|v| v / scale[c])));
    let orthogonal = (0..3).all(|a| {
        ((a + 1)..3).all(|b| match (unit[a], unit[b]) {
            (Some(u), Some(v)) => dot(u, v).abs() < 1e-9,
            _ => true,
        })
    });
    if !orthogonal {
        return None;
    }
    let mut r = completed(unit);
    if dot(cross(r[0], r[1]), r[2]) < 0.0 {
        // A mirror: the negative scale goes on x, as readers decompose it.
        scale[0] = -scale[0];
        r[0] = r[0].map(|v| -v);
    }
    Some(([m[12], m[13], m[14]], quaternion_of(r), scale))
}

/// The 3×3 part's columns of a column-major affine matrix; None for a projection.
fn linear_part(m: &[f64; 16]) -> Option<[[f64; 3]; 3]> {
    let affine = m[3] == 0.0 && m[7] == 0.0 && m[11] == 0.0 && m[15] == 1.0;
    affine.then(|| [0, 1, 2].map(|c| [m[4 * c], m[4 * c + 1], m[4 * c + 2]]))
}

/// Orthonormal columns with the missing ones (None) filled in to make a right-handed basis:
/// each as the cross product of the next two, or any unit vector orthogonal to the one given.
fn completed(unit: [Option<[f64; 3]>; 3]) -> [[f64; 3]; 3] {
    let given: Vec<usize> = (0..3).filter(|&c| unit[c].is_some()).collect();
    match given.as_slice() {
        [_, _, _] => unit.map(|c| c.unwrap_or_default()),
        [] => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        [only] => {
            let u = unit[*only].unwrap_or_default();
            // The axis u is least along is never parallel to it.
            let least = (0..3)
                .min_by(|&a, &b| u[a].abs().total_cmp(&u[b].abs()))
                .unwrap_or(0);
            let mut axis = [0.0; 3];
            axis[least] = 1.0;
            let v = normalize(cross(u, axis));
            let mut r = [[0.0; 3]; 3];
            r[*only] = u;
            r[(only + 1) % 3] = v;
            r[(only + 2) % 3] = cross(u, v);
            r
        }
        [_, _] => {
            let missing = (0..3).find(|&c| unit[c].is_none()).unwrap_or(2);
            let mut r = unit.map(|c| c.unwrap_or_default());
            r[missing] = cross(r[(missing + 1) % 3], r[(missing + 2) % 3]);
            r
        }
        _ => unreachable!("at most three columns"),
    }
}

/// What a sheared node held (mesh, camera, skin, children, extensions, extras), moved out of
/// `out` into the child node that turns by `rotation` beneath it.
fn sheared_content(out: &mut Map<String, Value>, id: &str, rotation: [f64; 4]) -> Value {
    let mut inner = Map::new();
    inner.insert("name".into(), json!(format!("{id}-unsheared")));
    inner.insert("rotation".into(), json!(rotation));
    let moved: Vec<String> = (out.keys())
        .filter(|k| !matches!(k.as_str(), "name" | "translation" | "rotation" | "scale"))
        .cloned()
        .collect();
    for key in moved {
        if let Some(value) = out.remove(&key) {
            inner.insert(key, value);
        }
    }
    Value::Object(inner)
}

/// A column-major affine matrix whose 3×3 part shears, as T · R₁ · S · R₂: translation, the
/// outer rotation and the scale (one node's), and the inner rotation (its child's), all
/// quaternions (x, y, z, w). This is the singular value decomposition of the 3×3 part, with
/// both rotations proper (a mirror is a negative scale on x). None for a projection, or when
/// the parts do not recompose the matrix to within 10⁻⁹ of its largest entry.
#[allow(clippy::type_complexity)]
fn unsheared(m: &[f64; 16]) -> Option<([f64; 3], [f64; 4], [f64; 3], [f64; 4])> {
    let a = linear_part(m)?;
    let largest = a.iter().flatten().fold(0.0f64, |l, v| l.max(v.abs()));
    if !largest.is_finite() || largest == 0.0 {
        return None;
    }
    let gram = [0, 1, 2].map(|i| [0, 1, 2].map(|j| dot(a[i], a[j])));
    let (squares, mut v) = symmetric_eigen(gram);
    if dot(cross(v[0], v[1]), v[2]) < 0.0 {
        v[2] = v[2].map(|x| -x);
    }
    let mut scale = squares.map(|s| s.max(0.0).sqrt());
    let smallest = scale.iter().fold(0.0f64, |l, &s| l.max(s)) * 1e-12;
    // Uᵢ = A·Vᵢ / σᵢ; a zero σ leaves its column to complete the rotation.
    let u = [0, 1, 2].map(|i| {
        let image = [0, 1, 2].map(|row| (0..3).map(|c| a[c][row] * v[i][c]).sum::<f64>());
        (scale[i] > smallest).then(|| image.map(|x| x / scale[i]))
    });
    let mut outer = completed(u);
    if dot(cross(outer[0], outer[1]), outer[2]) < 0.0 {
        scale[0] = -scale[0];
        outer[0] = outer[0].map(|x| -x);
    }
    let transposed = [0, 1, 2].map(|c| [v[0][c], v[1][c], v[2][c]]);
    let error = (0..3)
        .flat_map(|c| (0..3).map(move |row| (c, row)))
        .map(|(c, row)| {
            let back: f64 = (0..3)
                .map(|i| outer[i][row] * scale[i] * transposed[c][i])
                .sum();
            (back - a[c][row]).abs()
        })
        .fold(0.0, f64::max);
    (error <= 1e-9 * largest).then(|| {
        let translation = [m[12], m[13], m[14]];
        (
            translation,
            quaternion_of(outer),
            scale,
            quaternion_of(transposed),
        )
    })
}

/// The eigenvalues of a symmetric 3×3 matrix (rows of columns; it is its own transpose) and
/// their unit eigenvectors (columns), by cyclic Jacobi rotations until the off-diagonal part
/// vanishes against the diagonal.
fn symmetric_eigen(mut s: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..64 {
        let off = s[0][1] * s[0][1] + s[0][2] * s[0][2] + s[1][2] * s[1][2];
        let diagonal = s[0][0] * s[0][0] + s[1][1] * s[1][1] + s[2][2] * s[2][2];
        if off <= f64::EPSILON * f64::EPSILON * diagonal {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if s[p][q] == 0.0 {
                continue;
            }
            let theta = (s[q][q] - s[p][p]) / (2.0 * s[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let c = 1.0 / (t * t + 1.0).sqrt();
            let sine = t * c;
            let turn = |x: f64, y: f64| (c * x - sine * y, sine * x + c * y);
            for row in s.iter_mut() {
                (row[p], row[q]) = turn(row[p], row[q]);
            }
            for m in [&mut s, &mut v] {
                let (row_p, row_q) = (m[p], m[q]);
                m[p] = [0, 1, 2].map(|k| turn(row_p[k], row_q[k]).0);
                m[q] = [0, 1, 2].map(|k| turn(row_p[k], row_q[k]).1);
            }
        }
    }
    ([s[0][0], s[1][1], s[2][2]], v)
}

/// The unit quaternion (x, y, z, w) of a rotation given by its columns.
fn quaternion_of(r: [[f64; 3]; 3]) -> [f64; 4] {
    let at = |row: usize, col: usize| r[col][row];
    let trace = at(0, 0) + at(1, 1) + at(2, 2);
    let q = if trace > 0.0 {
        let s = (trace + 1.0).sqrt() * 2.0;
        [
            (at(2, 1) - at(1, 2)) / s,
            (at(0, 2) - at(2, 0)) / s,
            (at(1, 0) - at(0, 1)) / s,
            s / 4.0,
        ]
    } else if at(0, 0) > at(1, 1) && at(0, 0) > at(2, 2) {
        let s = (1.0 + at(0, 0) - at(1, 1) - at(2, 2)).sqrt() * 2.0;
        [
            s / 4.0,
            (at(0, 1) + at(1, 0)) / s,
            (at(0, 2) + at(2, 0)) / s,
            (at(2, 1) - at(1, 2)) / s,
        ]
    } else if at(1, 1) > at(2, 2) {
        let s = (1.0 + at(1, 1) - at(0, 0) - at(2, 2)).sqrt() * 2.0;
        [
            (at(0, 1) + at(1, 0)) / s,
            s / 4.0,
            (at(1, 2) + at(2, 1)) / s,
            (at(0, 2) - at(2, 0)) / s,
        ]
    } else {
        let s = (1.0 + at(2, 2) - at(0, 0) - at(1, 1)).sqrt() * 2.0;
        [
            (at(0, 2) + at(2, 0)) / s,
            (at(1, 2) + at(2, 1)) / s,
            s / 4.0,
            (at(1, 0) - at(0, 1)) / s,
        ]
    };
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    q.map(|v| v / n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// T · R · S of a decomposition, column-major.
    fn recomposed((t, [x, y, z, w], s): ([f64; 3], [f64; 4], [f64; 3])) -> [f64; 16] {
        let r = [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y + z * w),
                2.0 * (x * z - y * w),
            ],
            [
                2.0 * (x * y - z * w),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z + x * w),
            ],
            [
                2.0 * (x * z + y * w),
                2.0 * (y * z - x * w),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ];
        let mut m = IDENTITY;
        for c in 0..3 {
            for row in 0..3 {
                m[4 * c + row] = r[c][row] * s[c];
            }
            m[12 + c] = t[c];
        }
        m
    }

    #[test]
    fn a_rotation_and_scale_matrix_decomposes_to_the_same_transform_zero_scales_included_and_a_shear_does_not(
    ) {
        let (c, s) = (0.3f64.cos(), 0.3f64.sin());
        for (scale, mirror) in [(1.0, 1.0), (1000.0, 1.0), (2500.0, -1.0), (0.001, 1.0)] {
            let m = [
                c * scale * mirror,
                s * scale * mirror,
                0.0,
                0.0,
                -s * scale,
                c * scale,
                0.0,
                0.0,
                0.0,
                0.0,
                3.0 * scale,
                0.0,
                5.0,
                -6.0,
                7.0,
                1.0,
            ];
            let parts = decomposed(&m).expect("a rotation and a scale");
            let back = recomposed(parts);
            let error = (0..16).map(|i| (back[i] - m[i]).abs()).fold(0.0, f64::max);
            assert!(error < 1e-9 * scale.max(1.0), "{scale} {mirror}: {error}");
        }
        // A zero scale on every axis, on one, and on two (a node hidden, flattened, squashed
        // to a line along a turned axis).
        let zero_scaled = |columns: [[f64; 3]; 3]| {
            let mut m = IDENTITY;
            for (c, column) in columns.iter().enumerate() {
                m[4 * c..4 * c + 3].copy_from_slice(column);
            }
            m[12] = 4.0;
            m
        };
        for m in [
            zero_scaled([[0.0; 3]; 3]),
            zero_scaled([[c, s, 0.0], [-s, c, 0.0], [0.0; 3]]),
            zero_scaled([[0.0; 3], [-2.0 * s, 2.0 * c, 0.0], [0.0; 3]]),
        ] {
            let parts = decomposed(&m).expect("a rotation and a zero scale");
            let back = recomposed(parts);
            let error = (0..16).map(|i| (back[i] - m[i]).abs()).fold(0.0, f64::max);
            assert!(error < 1e-12, "{m:?} → {parts:?}: {error}");
            let [x, y, z, w] = parts.1;
            assert!(
                (x * x + y * y + z * z + w * w - 1.0).abs() < 1e-12,
                "{parts:?}"
            );
        }
        let mut shear = IDENTITY;
        shear[4] = 0.5;
        assert!(decomposed(&shear).is_none());
        assert!(unsheared(&shear).is_some());
        let mut projection = IDENTITY;
        projection[3] = 0.1;
        assert!(decomposed(&projection).is_none());
    }

    #[test]
    fn a_sheared_matrix_is_two_rotations_and_a_scale_that_recompose_it() {
        let (c, s) = (0.7f64.cos(), 0.7f64.sin());
        let turned = [
            c, s, 0.0, 0.0, -s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ];
        let mut shear = IDENTITY;
        (shear[4], shear[8], shear[9]) = (0.5, -0.25, 2.0);
        let mut mirrored = IDENTITY;
        mirrored[5] = -3.0;
        let mut flattened_shear = shear;
        flattened_shear[10] = 0.0;
        flattened_shear[8] = 0.0;
        flattened_shear[9] = 0.0;
        for (name, mut m) in [
            ("shear", shear),
            ("turned shear", multiply(&turned, &shear)),
            (
                "mirrored shear",
                multiply(&mirrored, &multiply(&shear, &turned)),
            ),
            ("flattened shear", flattened_shear),
        ] {
            (m[12], m[13], m[14]) = (1.0, -2.0, 3.0);
            let (t, outer, scale, inner) = unsheared(&m).expect(name);
            let back = multiply(
                &recomposed((t, outer, scale)),
                &recomposed(([0.0; 3], inner, [1.0; 3])),
            );
            let error = (0..16).map(|i| (back[i] - m[i]).abs()).fold(0.0, f64::max);
            assert!(error < 1e-12, "{name}: {m:?} → {back:?}: {error}");
            for q in [outer, inner] {
                let length: f64 = q.iter().map(|x| x * x).sum();
                assert!((length - 1.0).abs() < 1e-12, "{name}: {q:?}");
            }
        }
        let mut projection = shear;
        projection[3] = 0.1;
        assert!(unsheared(&projection).is_none());
    }

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
