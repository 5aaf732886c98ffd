//! Every member of a glTF 1.0 asset, given a value of every JSON type, is upgraded or refused
//! with a message, never a panic: a stranger's file can put a number where an object belongs
//! anywhere, and 1.0 assets are read member by member, each with its own expectation.

use gltfmat::{upgrade, NoResources, UpgradeOptions};
use rayon::prelude::*;
use serde_json::{json, Value};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A 1.0 asset with one of every object type the upgrade reads, each member it converts set.
fn kitchen_sink() -> Value {
    let floats = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAIA/AAAAAAAAAAAAAAAAAACAPwAAgD8AAAAA";
    json!({
        "asset": {"version": "1.0", "generator": "test", "premultipliedAlpha": true, "profile": {"api": "WebGL", "version": "1.0.2"}},
        "extensionsUsed": ["KHR_materials_common", "KHR_materials_pbrSpecularGlossiness", "WEB3D_materials_pbr", "FRAUNHOFER_materials_pbr", "EXT_materials_pbr"],
        "extensions": {"KHR_materials_common": {"lights": {
            "sun": {"type": "directional", "directional": {"color": [1, 1, 1]}},
            "lamp": {"type": "point", "point": {"color": [1, 0.5, 0.5], "constantAttenuation": 1, "linearAttenuation": 0.1, "quadraticAttenuation": 0.01}},
            "spot": {"type": "spot", "spot": {"color": [1, 1, 1], "fallOffAngle": 0.8, "fallOffExponent": 2}},
            "sky": {"type": "ambient", "ambient": {"color": [0.1, 0.1, 0.1]}}
        }}},
        "buffers": {"b": {"uri": floats, "byteLength": 72, "type": "arraybuffer"}},
        "bufferViews": {
            "positions": {"buffer": "b", "byteOffset": 0, "byteLength": 36, "target": 34962},
            "uvs": {"buffer": "b", "byteOffset": 36, "byteLength": 24, "target": 34962},
            "times": {"buffer": "b", "byteOffset": 60, "byteLength": 8}
        },
        "accessors": {
            "pos": {"bufferView": "positions", "byteOffset": 0, "byteStride": 12, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
            "uv": {"bufferView": "uvs", "byteOffset": 0, "byteStride": 8, "componentType": 5126, "count": 3, "type": "VEC2"},
            "time": {"bufferView": "times", "byteOffset": 0, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
            "translation": {"bufferView": "positions", "byteOffset": 0, "componentType": 5126, "count": 2, "type": "VEC3"}
        },
        "images": {"img": {"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==", "name": "pixel"}},
        "samplers": {"s": {"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 33071}},
        "textures": {"t": {"source": "img", "sampler": "s", "format": 6408, "internalFormat": 6408, "target": 3553, "type": 5121}},
        "shaders": {
            "vs": {"type": 35633, "uri": "data:,void%20main()%7B%7D"},
            "fs": {"type": 35632, "uri": "data:,void%20main()%7B%7D"}
        },
        "programs": {"p": {"vertexShader": "vs", "fragmentShader": "fs", "attributes": ["a_position", "a_texcoord0"]}},
        "techniques": {"tech": {
            "program": "p",
            "attributes": {"a_position": "position", "a_texcoord0": "texcoord0"},
            "uniforms": {"u_diffuse": "diffuse", "u_shininess": "shininess", "u_transparency": "transparency"},
            "parameters": {
                "position": {"type": 35665, "semantic": "POSITION"},
                "texcoord0": {"type": 35664, "semantic": "TEXCOORD_0"},
                "diffuse": {"type": 35678},
                "emission": {"type": 35666, "value": [0.1, 0.1, 0.1, 1]},
                "shininess": {"type": 5126, "value": 20},
                "transparency": {"type": 5126, "value": 0.5},
                "modelViewMatrix": {"type": 35676, "semantic": "MODELVIEW"}
            },
            "states": {"enable": [2884, 2929, 3042], "functions": {"blendFuncSeparate": [1, 771, 1, 771], "cullFace": [1029]}}
        }},
        "materials": {
            "shaded": {"technique": "tech", "values": {"diffuse": "t", "shininess": 40, "transparency": 0.8}, "name": "shaded"},
            "common": {"extensions": {"KHR_materials_common": {"technique": "BLINN", "doubleSided": true, "transparent": true,
                "values": {"diffuse": [0.8, 0.2, 0.2, 1], "specular": [0.2, 0.2, 0.2, 1], "shininess": 10, "emission": "t", "ambient": [0, 0, 0, 1], "transparency": 0.9}}}},
            "pbr": {"extensions": {"KHR_materials_pbrSpecularGlossiness": {"diffuseFactor": [0.6, 0.5, 0.4, 1], "specularFactor": [0.2, 0.2, 0.2], "glossinessFactor": 0.75, "diffuseTexture": "t", "specularGlossinessTexture": "t"}}},
            "web3d": {"extensions": {"WEB3D_materials_pbr": {"technique": "PBR_metal_roughness", "values": {"baseColorFactor": [0.8, 0.6, 0.4, 1], "metallicFactor": 0.7, "roughnessFactor": 0.35, "baseColorTexture": "t"}}}},
            "fraunhofer": {"extensions": {"FRAUNHOFER_materials_pbr": {"materialModel": "PBR_metal_roughness", "values": {"baseColorFactor": [0.8, 0.6, 0.4, 1], "metallicFactor": 0.7, "roughnessFactor": 0.35, "metallicRoughnessTexture": "t"}}}},
            "ext": {"extensions": {"EXT_materials_pbr": {"materialModel": "PBR_specular_glossiness", "values": {"diffuseFactor": [0.6, 0.5, 0.4, 1], "specularFactor": [0.2, 0.2, 0.2], "glossinessFactor": 0.75, "specularGlossinessTexture": "t"}}}}
        },
        "meshes": {"m": {"name": "tri", "primitives": [
            {"attributes": {"POSITION": "pos", "TEXCOORD_0": "uv"}, "material": "shaded", "mode": 4},
            {"attributes": {"POSITION": "pos"}, "material": "common", "mode": 4},
            {"attributes": {"POSITION": "pos", "TEXCOORD_0": "uv"}, "material": "pbr"},
            {"attributes": {"POSITION": "pos", "TEXCOORD_0": "uv"}, "material": "web3d"},
            {"attributes": {"POSITION": "pos", "TEXCOORD_0": "uv"}, "material": "fraunhofer"},
            {"attributes": {"POSITION": "pos", "TEXCOORD_0": "uv"}, "material": "ext"}
        ]}},
        "skins": {"skin": {"bindShapeMatrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "inverseBindMatrices": "pos", "jointNames": ["j"]}},
        "cameras": {
            "persp": {"type": "perspective", "perspective": {"aspectRatio": 1.5, "yfov": 0.8, "zfar": 100, "znear": 0.1}},
            "ortho": {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "zfar": 100, "znear": 0}}
        },
        "nodes": {
            "root": {"children": ["child", "joint", "viewer", "light"], "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]},
            "child": {"meshes": ["m", "m"], "skeletons": ["joint"], "skin": "skin", "translation": [0, 1, 0], "rotation": [0, 0, 0, 1], "scale": [1, 1, 1]},
            "joint": {"jointName": "j", "children": []},
            "viewer": {"camera": "persp"},
            "light": {"extensions": {"KHR_materials_common": {"light": "lamp"}}}
        },
        "animations": {"walk": {
            "channels": [{"sampler": "move", "target": {"id": "joint", "path": "translation"}}],
            "parameters": {"TIME": "time", "translation": "translation"},
            "samplers": {"move": {"input": "TIME", "interpolation": "LINEAR", "output": "translation"}}
        }},
        "scenes": {"s": {"nodes": ["root"], "name": "scene"}},
        "scene": "s"
    })
}

/// Every JSON pointer in `value`, the root's members first.
fn pointers(value: &Value, at: String, out: &mut Vec<String>) {
    match value {
        Value::Object(map) => {
            for (key, member) in map {
                let path = format!("{at}/{}", key.replace('~', "~0").replace('/', "~1"));
                out.push(path.clone());
                pointers(member, path, out);
            }
        }
        Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                let path = format!("{at}/{i}");
                out.push(path.clone());
                pointers(item, path, out);
            }
        }
        _ => {}
    }
}

/// One value of each JSON type, the empty and the wrong-shaped containers among them.
fn every_type() -> [Value; 8] {
    [
        json!(null),
        json!(true),
        json!(-1.5),
        json!("x"),
        json!([]),
        json!([1, "a", null]),
        json!({}),
        json!({"a": [1]}),
    ]
}

/// Upgrades `asset` with the value at each pointer replaced by each type; the first panic's
/// pointer and value, if any.
fn sweep(asset: &Value) -> Vec<String> {
    let mut paths = Vec::new();
    pointers(asset, String::new(), &mut paths);
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let cases: Vec<(&String, Value)> = (paths.iter())
        .flat_map(|path| every_type().map(|replacement| (path, replacement)))
        .collect();
    let panics = (cases.par_iter())
        .filter_map(|(path, replacement)| {
            let mut mutated = asset.clone();
            *mutated.pointer_mut(path)? = replacement.clone();
            let bytes = serde_json::to_vec(&mutated).unwrap();
            let ran = catch_unwind(AssertUnwindSafe(|| {
                let _ = upgrade(bytes, &NoResources, &UpgradeOptions::default());
            }));
            ran.is_err().then(|| format!("{path} = {replacement}"))
        })
        .collect();
    std::panic::set_hook(previous);
    panics
}

#[test]
fn the_kitchen_sink_asset_upgrades_as_it_is() {
    // The sweep below means something only if the unmutated asset reaches every step.
    let bytes = serde_json::to_vec(&kitchen_sink()).unwrap();
    let upgraded = upgrade(bytes, &NoResources, &UpgradeOptions::default());
    assert!(
        upgraded.is_ok(),
        "{:?}",
        upgraded.err().map(|e| e.to_string())
    );
}

#[test]
fn every_member_of_a_1_0_asset_of_every_json_type_never_panics_the_upgrade() {
    let panics = sweep(&kitchen_sink());
    assert!(panics.is_empty(), "panicked at:\n{}", panics.join("\n"));
}
