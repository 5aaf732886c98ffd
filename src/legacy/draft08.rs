//! glTF 0.8 (COLLADA2GLTF's output before 1.0, Cesium's early models), read as the 1.0 it
//! became. The differences are those of the 0.8 → 1.0 schema change as gltf-pipeline's
//! version update lists them: a material's `instanceTechnique`, a primitive's `primitive`,
//! rotations as axis and angle, a node's `instanceSkin`, a technique's `passes`, the root's
//! `allExtensions` and `lights`, and the version itself (on the root, or a number).
//!
//! Each is moved to its 1.0 place only where the 1.0 member is absent, and each one made is
//! named, so that the upgrade can say how the asset was read. Rotation keyframes are data:
//! the animation step converts them (see [`quaternion`]).

use crate::document::Node;
use serde_json::{json, Map, Value};

/// Whether the asset declares glTF 0.8 (`asset.version`, or the root's `version` of the
/// earliest drafts, as a string or a number).
pub(crate) fn declares(root: Node) -> bool {
    let version =
        (root.get("asset").and_then(|a| a.get("version"))).or_else(|| root.get("version"));
    match version {
        Some(v) if v.is_string() => v.as_str().is_some_and(|s| s.starts_with("0.8")),
        Some(v) => v.as_f64() == Some(0.8),
        None => false,
    }
}

/// The 1.0 reading of a 0.8 root, and what was read the 0.8 way, in words.
pub(crate) fn as_1_0(root: Node) -> (Value, Vec<&'static str>) {
    let mut root = root.to_value();
    let mut read = Vec::new();
    let Some(members) = root.as_object_mut() else {
        return (root, read);
    };
    members.remove("version");
    let asset = members.entry("asset").or_insert_with(|| json!({}));
    if let Some(asset) = asset.as_object_mut() {
        asset.insert("version".into(), json!("1.0"));
    }
    let steps: [(Step, &'static str); 7] = [
        (
            instance_techniques,
            "a material's instanceTechnique as its technique and values",
        ),
        (primitive_modes, "a primitive's `primitive` as its mode"),
        (
            node_rotations,
            "node rotations from axis and angle to quaternions",
        ),
        (
            instance_skins,
            "a node's instanceSkin as its skeletons, skin and meshes",
        ),
        (
            technique_passes,
            "a technique's pass as its program, attributes, uniforms and states",
        ),
        (all_extensions, "allExtensions as extensionsUsed"),
        (
            root_lights,
            "the root's lights as KHR_materials_common lights",
        ),
    ];
    for (step, words) in steps {
        if step(members) {
            read.push(words);
        }
    }
    if animates_rotation(members) {
        read.push("rotation keyframes from axis and angle to quaternions");
    }
    (root, read)
}

/// One change of the 0.8 → 1.0 reading, made in place; whether the asset needed it.
type Step = fn(&mut Map<String, Value>) -> bool;

/// A rotation written as axis (x, y, z) and angle (radians) as the unit quaternion glTF 1.0
/// writes (x, y, z, w); an axis of length zero turns nothing.
pub(crate) fn quaternion([x, y, z, angle]: [f64; 4]) -> [f64; 4] {
    let length = (x * x + y * y + z * z).sqrt();
    if length == 0.0 || !length.is_finite() || !angle.is_finite() {
        return [0.0, 0.0, 0.0, 1.0];
    }
    let (sin, cos) = (angle / 2.0).sin_cos();
    let s = sin / length;
    [x * s, y * s, z * s, cos]
}

/// The objects of a root dictionary (`materials`, `nodes`, …), to change in place.
fn each<'v>(
    root: &'v mut Map<String, Value>,
    key: &str,
) -> impl Iterator<Item = &'v mut Map<String, Value>> {
    (root.get_mut(key).and_then(Value::as_object_mut).into_iter())
        .flat_map(|objects| objects.values_mut())
        .filter_map(Value::as_object_mut)
}

/// Puts `value` at `key` where `object` has nothing there; whether it did.
fn keep_absent(object: &mut Map<String, Value>, key: &str, value: Option<&Value>) -> bool {
    match value {
        Some(value) if !object.contains_key(key) => {
            object.insert(key.to_string(), value.clone());
            true
        }
        _ => false,
    }
}

/// Moves the members `names` of `object`'s member `from` up into `object` where it lacks
/// them; whether it moved any.
fn lift(object: &mut Map<String, Value>, from: &str, names: &[&str]) -> bool {
    let Some(Value::Object(inner)) = object.remove(from) else {
        return false;
    };
    (names.iter()).fold(false, |any, name| {
        keep_absent(object, name, inner.get(*name)) | any
    })
}

fn instance_techniques(root: &mut Map<String, Value>) -> bool {
    let names = ["technique", "values"];
    (each(root, "materials")).fold(false, |any, m| lift(m, "instanceTechnique", &names) | any)
}

fn primitive_modes(root: &mut Map<String, Value>) -> bool {
    let mut any = false;
    for mesh in each(root, "meshes") {
        let primitives = mesh.get_mut("primitives").and_then(Value::as_array_mut);
        for primitive in primitives
            .into_iter()
            .flatten()
            .filter_map(Value::as_object_mut)
        {
            if let Some(mode) = primitive.remove("primitive") {
                if !primitive.contains_key("mode") {
                    primitive.insert("mode".into(), mode);
                    any = true;
                }
            }
        }
    }
    any
}

fn node_rotations(root: &mut Map<String, Value>) -> bool {
    let mut any = false;
    for node in each(root, "nodes") {
        let rotation = node.get("rotation").and_then(Value::as_array);
        let numbers: Option<Vec<f64>> =
            rotation.and_then(|r| r.iter().map(Value::as_f64).collect());
        if let Some(axis_angle) = numbers.and_then(|n| <[f64; 4]>::try_from(n).ok()) {
            node.insert("rotation".into(), json!(quaternion(axis_angle)));
            any = true;
        }
    }
    any
}

fn instance_skins(root: &mut Map<String, Value>) -> bool {
    let names = ["skeletons", "skin", "meshes"];
    (each(root, "nodes")).fold(false, |any, node| lift(node, "instanceSkin", &names) | any)
}

fn technique_passes(root: &mut Map<String, Value>) -> bool {
    let mut any = false;
    for technique in each(root, "techniques") {
        let Some(Value::Object(mut passes)) = technique.remove("passes") else {
            continue;
        };
        let name = technique.remove("pass");
        let name = name
            .as_ref()
            .and_then(Value::as_str)
            .unwrap_or("defaultPass");
        let Some(Value::Object(mut pass)) = passes.remove(name) else {
            continue;
        };
        if let Some(Value::Object(program)) = pass.remove("instanceProgram") {
            for key in ["attributes", "program", "uniforms"] {
                any |= keep_absent(technique, key, program.get(key));
            }
        }
        any |= keep_absent(technique, "states", pass.get("states"));
    }
    any
}

fn all_extensions(root: &mut Map<String, Value>) -> bool {
    match root.remove("allExtensions") {
        Some(used) if !root.contains_key("extensionsUsed") => {
            root.insert("extensionsUsed".into(), used);
            true
        }
        _ => false,
    }
}

fn root_lights(root: &mut Map<String, Value>) -> bool {
    let Some(lights) = root.remove("lights") else {
        return false;
    };
    let extensions = root.entry("extensions").or_insert_with(|| json!({}));
    let Some(common) = extensions
        .as_object_mut()
        .map(|e| e.entry("KHR_materials_common").or_insert_with(|| json!({})))
    else {
        return false;
    };
    let Some(common) = common.as_object_mut().filter(|c| !c.contains_key("lights")) else {
        return false;
    };
    common.insert("lights".into(), lights);
    let used = root.entry("extensionsUsed").or_insert_with(|| json!([]));
    if let Some(used) = used
        .as_array_mut()
        .filter(|u| !u.iter().any(|e| e == "KHR_materials_common"))
    {
        used.push(json!("KHR_materials_common"));
    }
    true
}

/// Whether an animation channel targets a rotation (its keyframes are axis and angle).
fn animates_rotation(root: &mut Map<String, Value>) -> bool {
    each(root, "animations").any(|animation| {
        let channels = animation.get("channels").and_then(Value::as_array);
        channels
            .into_iter()
            .flatten()
            .any(|c| c.pointer("/target/path") == Some(&json!("rotation")))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_axis_and_angle_becomes_the_unit_quaternion_turning_as_much() {
        let q = quaternion([0.0, 0.0, 2.0, std::f64::consts::PI]);
        let expected = [0.0, 0.0, 1.0, 0.0];
        assert!(
            q.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-15),
            "{q:?}"
        );
        let q = quaternion([1.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        let half = std::f64::consts::FRAC_1_SQRT_2;
        assert!(
            (q[0] - half).abs() < 1e-15 && (q[3] - half).abs() < 1e-15,
            "{q:?}"
        );
        assert_eq!(quaternion([0.0, 0.0, 0.0, 1.0]), [0.0, 0.0, 0.0, 1.0]);
    }
}
