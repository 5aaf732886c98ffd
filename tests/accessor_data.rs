//! Accessor data checked by use: a clean skinned, animated triangle, and one byte-level
//! defect at a time, each reported with its Khronos code at the pointer that uses the data.

use base64::Engine;
use gltfmat::{check_bytes, CheckOptions, NoResources, Place, Profile};
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
                let at = match d.location {
                    Place::Pointer(p) => p.to_string(),
                    Place::Offset(o) => format!("@{o}"),
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

/// A triangle list over `vertices` positions whose x is the distance from the middle vertex
/// (least there, greatest at the ends), with `normals` of the given length, its indices
/// degenerate at `degenerate` triangles, and the bounds `declared` (min x, max x).
fn large_mesh(vertices: usize, degenerate: &[usize], normal_z: f32, declared: [f32; 2]) -> Value {
    let middle = (vertices / 2) as f32;
    let positions: Vec<u8> = (0..vertices)
        .flat_map(|i| [(i as f32 - middle).abs(), 1.0, 0.0])
        .flat_map(f32::to_le_bytes)
        .collect();
    let normals: Vec<u8> = (0..vertices)
        .flat_map(|_| [0.0, 0.0, normal_z])
        .flat_map(f32::to_le_bytes)
        .collect();
    let indices: Vec<u8> = (0..vertices as u32 - 2)
        .flat_map(|t| match degenerate.contains(&(t as usize)) {
            true => [t, t, t + 2],
            false => [t, t + 1, t + 2],
        })
        .flat_map(u32::to_le_bytes)
        .collect();
    let buffer = [positions.clone(), normals.clone(), indices.clone()].concat();
    let data = base64::engine::general_purpose::STANDARD.encode(&buffer);
    let view = |offset: usize, length: usize, target: u32| serde_json::json!({"buffer": 0, "byteOffset": offset, "byteLength": length, "target": target});
    serde_json::json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": buffer.len(), "uri": format!("data:application/octet-stream;base64,{data}")}],
        "bufferViews": [view(0, positions.len(), 34962), view(positions.len(), normals.len(), 34962),
            view(positions.len() + normals.len(), indices.len(), 34963)],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": vertices, "type": "VEC3",
             "min": [declared[0], 1.0, 0.0], "max": [declared[1], 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5126, "count": vertices, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": 3 * (vertices - 2), "type": "SCALAR"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0
    })
}

#[test]
fn large_data_read_in_parallel_runs_is_bounded_and_counted_as_one_walk_would() {
    // 300 000 vertices and triangles: several runs of 65 536 elements each, bounded on
    // different cores; the least x lies in a middle run, the greatest in the first.
    let vertices = 300_000;
    let middle = (vertices / 2) as f32;
    let clean = large_mesh(vertices, &[], 1.0, [0.0, middle]);
    assert_eq!(findings(&clean), vec![]);
    let spread = [3, 70_000, 140_000, vertices - 3];
    let report = |gltf: &Value| {
        let bytes = serde_json::to_vec(gltf).unwrap();
        check_bytes("large.gltf", bytes, &NoResources, &CheckOptions::default())
    };
    let degenerate = report(&large_mesh(vertices, &spread, 1.0, [0.0, middle]));
    let messages: Vec<&str> = (degenerate.diagnostics.iter())
        .filter(|d| d.code == "ACCESSOR_INDEX_TRIANGLE_DEGENERATE")
        .map(|d| d.message)
        .collect();
    assert_eq!(
        messages,
        [format!(
            "Indices accessor contains 4 degenerate triangles (out of {}).",
            vertices - 2
        )]
    );
    let wrong_bounds = report(&large_mesh(vertices, &[], 1.0, [1.0, middle - 1.0]));
    let actual: Vec<String> = (wrong_bounds.diagnostics.iter())
        .filter(|d| d.code.to_string().starts_with("ACCESSOR_M"))
        .map(|d| d.message.to_string())
        .collect();
    assert_eq!(actual.len(), 2, "{actual:?}");
    assert!(actual[0].contains("actual minimum (0.0)"), "{}", actual[0]);
    assert!(
        actual[1].contains(&format!("actual maximum ({middle:?})")),
        "{}",
        actual[1]
    );
    // A non-unit normal in a late run is found, whichever core reads it.
    let long_normals = report(&large_mesh(vertices, &[], 2.0, [0.0, middle]));
    assert!(long_normals
        .diagnostics
        .iter()
        .any(|d| d.code == "ACCESSOR_VECTOR3_NON_UNIT"));
}

#[test]
fn declared_bounds_of_integer_joints_are_held_against_the_data() {
    // The joints are (0,1,0,0), (0,1,0,0), (1,0,0,0): component 1 reaches 1, declared 0.
    let mut gltf = fixture();
    gltf["accessors"][2]["min"] = serde_json::json!([0, 0, 0, 0]);
    gltf["accessors"][2]["max"] = serde_json::json!([1, 0, 0, 0]);
    assert_eq!(
        findings(&gltf),
        vec![
            (
                "ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND".to_string(),
                "/accessors/2/max/1".to_string()
            ),
            (
                "ACCESSOR_MAX_MISMATCH".to_string(),
                "/accessors/2/max/1".to_string()
            ),
        ]
    );
    let bytes = serde_json::to_vec(&gltf).unwrap();
    let report = check_bytes("case.gltf", bytes, &NoResources, &CheckOptions::default());
    let messages: Vec<&str> = report.diagnostics.iter().map(|d| d.message).collect();
    assert!(
        messages.contains(
            &"Declared maximum value for this component (0) does not match actual maximum (1)."
        ),
        "{messages:?}"
    );
    assert!(
        messages.contains(&"Accessor contains 2 element(s) greater than declared maximum value 0."),
        "{messages:?}"
    );
    // Declared right, nothing is said.
    gltf["accessors"][2]["max"] = serde_json::json!([1, 1, 0, 0]);
    assert_eq!(findings(&gltf), vec![]);
}
