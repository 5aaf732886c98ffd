//! Accessor data checked by use: a clean skinned, animated triangle, and one byte-level
//! defect at a time, each reported with its Khronos code at the pointer that uses the data.

use base64::Engine;
use gltfmat::check::{check_bytes, CheckOptions, Location, Profile};
use gltfmat::document::uri::NoResources;
use serde_json::Value;

const FIXTURE: &str = "fixtures/valid/skinned-animated.gltf";

fn fixture() -> Value {
    serde_json::from_slice(&std::fs::read(FIXTURE).unwrap()).unwrap()
}

/// The fixture with `f32` values written into bufferView `view` starting at element `at`.
fn with_floats(view: usize, at: usize, values: &[f32]) -> Value {
    with_bytes(
        view,
        at * 4,
        &values
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>(),
    )
}

fn with_bytes(view: usize, at: usize, bytes: &[u8]) -> Value {
    let mut gltf = fixture();
    let engine = base64::engine::general_purpose::STANDARD;
    let uri = gltf["buffers"][0]["uri"].as_str().unwrap().to_string();
    let (head, data) = uri.split_once(',').unwrap();
    let mut buffer = engine.decode(data).unwrap();
    let start = gltf["bufferViews"][view]["byteOffset"].as_u64().unwrap() as usize + at;
    buffer[start..start + bytes.len()].copy_from_slice(bytes);
    gltf["buffers"][0]["uri"] = format!("{head},{}", engine.encode(&buffer)).into();
    gltf
}

/// (code, pointer) of every finding, in both profiles (which must agree on these codes).
fn findings(gltf: &Value) -> Vec<(String, String)> {
    let run = |profile| {
        let options = CheckOptions::default().with_profile(profile);
        let bytes = serde_json::to_vec(gltf).unwrap();
        let report = check_bytes("case.gltf", bytes, &NoResources, &options);
        let mut out: Vec<(String, String)> = report
            .diagnostics
            .iter()
            .map(|d| {
                let at = match &d.location {
                    Location::Pointer(p) => p.clone(),
                    Location::Offset(o) => format!("@{o}"),
                };
                (d.code.to_string(), at)
            })
            .collect();
        out.sort();
        out
    };
    let default = run(Profile::Default);
    assert_eq!(default, run(Profile::Khronos), "the profiles disagree");
    default
}

fn one(code: &str, pointer: &str) -> Vec<(String, String)> {
    vec![(code.to_string(), pointer.to_string())]
}

const PRIMITIVE: &str = "/meshes/0/primitives/0";

#[test]
fn the_skinned_animated_fixture_is_clean() {
    assert_eq!(findings(&fixture()), vec![]);
}

#[test]
fn a_normal_of_length_two_is_not_unit() {
    let gltf = with_floats(1, 3, &[0.0, 0.0, 2.0]);
    let at = format!("{PRIMITIVE}/attributes/NORMAL");
    assert_eq!(findings(&gltf), one("ACCESSOR_VECTOR3_NON_UNIT", &at));
}

#[test]
fn an_index_past_the_last_vertex_is_out_of_bounds() {
    let gltf = with_bytes(4, 2, &3u16.to_le_bytes());
    let at = format!("{PRIMITIVE}/indices");
    assert_eq!(findings(&gltf), one("ACCESSOR_INDEX_OOB", &at));
}

#[test]
fn a_repeated_index_makes_a_degenerate_triangle() {
    let gltf = with_bytes(4, 4, &1u16.to_le_bytes());
    let at = format!("{PRIMITIVE}/indices");
    assert_eq!(
        findings(&gltf),
        one("ACCESSOR_INDEX_TRIANGLE_DEGENERATE", &at)
    );
}

#[test]
fn weights_summing_past_one_are_not_normalized() {
    let gltf = with_floats(3, 0, &[0.75, 0.5]);
    let at = format!("{PRIMITIVE}/attributes/WEIGHTS_0");
    assert_eq!(findings(&gltf), one("ACCESSOR_WEIGHTS_NON_NORMALIZED", &at));
}

#[test]
fn a_joint_past_the_skin_is_out_of_bounds() {
    // The skin has two joints: index 2 does not exist. Its weight (0.25) is then not
    // counted, so the vertex's weights no longer sum to 1 either.
    let gltf = with_bytes(2, 1, &[2]);
    let mut expected = one(
        "ACCESSOR_JOINTS_INDEX_OOB",
        &format!("{PRIMITIVE}/attributes/JOINTS_0"),
    );
    expected.extend(one(
        "ACCESSOR_WEIGHTS_NON_NORMALIZED",
        &format!("{PRIMITIVE}/attributes/WEIGHTS_0"),
    ));
    assert_eq!(findings(&gltf), expected);
}

#[test]
fn a_joint_with_zero_weight_must_be_zero() {
    // Vertex 2 has weights (1, 0, 0, 0): a non-zero joint in its second slot is a warning.
    let gltf = with_bytes(2, 9, &[1]);
    let at = format!("{PRIMITIVE}/attributes/JOINTS_0");
    assert_eq!(
        findings(&gltf),
        one("ACCESSOR_JOINTS_USED_ZERO_WEIGHT", &at)
    );
}

#[test]
fn animation_times_must_increase() {
    let mut gltf = with_floats(6, 0, &[1.0, 1.0]);
    gltf["accessors"][6]["min"] = serde_json::json!([1.0]);
    let at = "/animations/0/samplers/0/input";
    assert_eq!(
        findings(&gltf),
        one("ACCESSOR_ANIMATION_INPUT_NON_INCREASING", at)
    );
}

#[test]
fn an_animated_rotation_must_be_a_unit_quaternion() {
    let gltf = with_floats(7, 4, &[0.0, 0.0, 0.0, 2.0]);
    let at = "/animations/0/channels/0/sampler";
    assert_eq!(
        findings(&gltf),
        one(
            "ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION",
            at
        )
    );
}

#[test]
fn an_inverse_bind_matrix_must_be_affine() {
    let gltf = with_floats(5, 3, &[1.0]);
    let at = "/skins/0/inverseBindMatrices";
    assert_eq!(findings(&gltf), one("ACCESSOR_INVALID_IBM", at));
}
