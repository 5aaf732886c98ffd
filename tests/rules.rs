//! gltfmat's material rules as a specification: each case is a fixture (a clean base asset
//! changed by a JSON merge patch, with images generated here so that what they contain is
//! visible in the test) and the complete list of issues it must produce. Near-misses must
//! not trigger their rule (they list nothing else either, but for a Khronos info the setting
//! they need brings). Every rule has at least one firing case and one near-miss.

mod common;

use common::{chunk, data_uri};
use gltfmat::registry::{self, Origin};
use gltfmat::{check_bytes, CheckOptions, FolderResources, NoResources, Place};
use image::{DynamicImage, GrayImage, ImageFormat, RgbImage, RgbaImage};
use serde_json::{json, Value};
use std::collections::BTreeSet;
use std::io::Cursor;

// ---------------------------------------------------------------- fixtures

/// A one-triangle asset with NORMAL, TEXCOORD_0/1 (tangent data in the buffer, bound by `with_tangents`) and a plain dielectric material:
/// it has no issue at all (checked by `the_base_fixture_is_clean`).
fn base() -> Value {
    asset(false)
}

fn asset(tangents: bool) -> Value {
    let mut data = Vec::new();
    let mut put = |values: &[f32]| values.iter().for_each(|v| data.extend(v.to_le_bytes()));
    put(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]); // POSITION, 0
    put(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0]); // NORMAL, 36
    put(&[1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0]); // TANGENT, 72
    put(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]); // TEXCOORD, 120
    let uri = data_uri("application/octet-stream", &data);
    // One bufferView per accessor: tightly packed attributes may not share a view.
    // (offset, length) of POSITION, NORMAL, TEXCOORD and TANGENT, which only some cases use.
    let spans = [(0, 36), (36, 36), (120, 24), (72, 48)];
    let views: Vec<Value> = spans[..if tangents { 4 } else { 3 }]
        .iter()
        .map(|(offset, length)| json!({"buffer": 0, "byteOffset": offset, "byteLength": length, "target": 34962}))
        .collect();
    let view_at = |offset: usize| spans.iter().position(|(o, _)| *o == offset).unwrap();
    let accessor = |offset: usize, kind: &str| json!({"bufferView": view_at(offset), "componentType": 5126, "count": 3, "type": kind});
    let mut position = accessor(0, "VEC3");
    position["min"] = json!([0.0, 0.0, 0.0]);
    position["max"] = json!([1.0, 1.0, 0.0]);
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": attributes(tangents), "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0}}],
        "accessors": if tangents {
            json!([position, accessor(36, "VEC3"), accessor(120, "VEC2"), accessor(72, "VEC4")])
        } else {
            json!([position, accessor(36, "VEC3"), accessor(120, "VEC2")])
        },
        "bufferViews": views,
        "buffers": [{"uri": uri, "byteLength": data.len()}]
    })
}

fn attributes(tangents: bool) -> Value {
    let mut attributes = json!({"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TEXCOORD_1": 2});
    if tangents {
        attributes["TANGENT"] = json!(3);
    }
    attributes
}

/// The base asset with TANGENT on its primitive.
fn with_tangents() -> Value {
    let full = asset(true);
    json!({"meshes": full["meshes"], "accessors": full["accessors"], "bufferViews": full["bufferViews"]})
}

/// The base asset with TANGENT, whose only image is a small KTX2 file in a bufferView, sampled
/// through KHR_texture_basisu.
fn ktx2_image() -> Value {
    ktx2_images(&[common::ktx2()])
}

/// The base asset with TANGENT, whose images are `files` of `fixtures/ktx2`, each sampled
/// through KHR_texture_basisu by the texture of the same index.
fn ktx2_fixtures(files: &[&str]) -> Value {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/ktx2");
    let bytes: Vec<Vec<u8>> = (files.iter())
        .map(|f| std::fs::read(folder.join(f)).unwrap())
        .collect();
    ktx2_images(&bytes)
}

/// A patch of [`ktx2_images`]'s asset: its first texture reads its KTX2 through an extension
/// other than KHR_texture_basisu (Magnum's KHR_texture_ktx draft), whose layout rules do not
/// bind it. gltfmat does not know that extension (UNSUPPORTED_EXTENSION), so the image counts
/// as unused, and its mimeType as one core glTF does not list.
fn through_another_extension() -> Value {
    json!({"extensionsUsed": ["KHR_texture_ktx"],
        "textures": [{"sampler": 0, "extensions": {"KHR_texture_ktx": {"source": 0}}}]})
}

/// The base asset with TANGENT, whose images are KTX2 `files` in one buffer (a data URI), each
/// sampled through KHR_texture_basisu by the texture of the same index.
fn ktx2_images(files: &[Vec<u8>]) -> Value {
    let ktx2: Vec<u8> = files.concat();
    let full = asset(true);
    let mut views = full["bufferViews"].as_array().unwrap().clone();
    let first_view = views.len();
    let mut offset = 0;
    for file in files {
        views.push(json!({"buffer": 1, "byteOffset": offset, "byteLength": file.len()}));
        offset += file.len();
    }
    let mut buffers = full["buffers"].as_array().unwrap().clone();
    buffers.push(
        json!({"uri": data_uri("application/octet-stream", &ktx2), "byteLength": ktx2.len()}),
    );
    let images: Vec<Value> = (0..files.len())
        .map(|i| json!({"bufferView": first_view + i, "mimeType": "image/ktx2"}))
        .collect();
    // Sampled without mipmaps (minFilter LINEAR): each case is about its own rule, and a
    // one-level KTX2 under a mipmap filter is KTX2_MIPMAPS_MISSING's.
    let textures: Vec<Value> = (0..files.len())
        .map(|i| json!({"sampler": 0, "extensions": {"KHR_texture_basisu": {"source": i}}}))
        .collect();
    json!({"meshes": full["meshes"], "accessors": full["accessors"], "bufferViews": views, "buffers": buffers,
        "images": images, "textures": textures, "samplers": [{"minFilter": 9729}],
        "extensionsUsed": ["KHR_texture_basisu"]})
}

/// A KTX2 fixture whose header word at `at` claims `value` (levelCount at 40, pixelWidth
/// at 20): header rules judge what the header says.
fn fixture_claiming(file: &str, at: usize, value: u32) -> Vec<u8> {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/ktx2");
    let mut bytes = std::fs::read(folder.join(file)).unwrap();
    bytes[at..at + 4].copy_from_slice(&value.to_le_bytes());
    bytes
}

/// A KTX2 fixture whose level data ends early (its header and index intact).
fn truncated_fixture(file: &str) -> Vec<u8> {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/ktx2");
    let mut bytes = std::fs::read(folder.join(file)).unwrap();
    bytes.truncate(bytes.len() - 64);
    bytes
}

/// RFC 7386 JSON merge patch.
fn merge(target: &mut Value, patch: &Value) {
    match (target, patch) {
        (Value::Object(target), Value::Object(patch)) => {
            for (key, value) in patch {
                if value.is_null() {
                    target.remove(key);
                } else {
                    merge(target.entry(key.clone()).or_insert(Value::Null), value);
                }
            }
        }
        (target, patch) => *target = patch.clone(),
    }
}

fn encode(image: DynamicImage, format: ImageFormat) -> Vec<u8> {
    let mut bytes = Vec::new();
    image
        .write_to(&mut Cursor::new(&mut bytes), format)
        .expect("encodes");
    bytes
}

fn png(image: impl Into<DynamicImage>) -> Vec<u8> {
    encode(image.into(), ImageFormat::Png)
}

fn rgb(colour: [u8; 3]) -> Vec<u8> {
    png(RgbImage::from_pixel(4, 4, image::Rgb(colour)))
}

fn rgba(colour: [u8; 4]) -> Vec<u8> {
    png(RgbaImage::from_pixel(4, 4, image::Rgba(colour)))
}

fn grey(level: u8) -> Vec<u8> {
    png(GrayImage::from_pixel(4, 4, image::Luma([level])))
}

/// A `size`² RGBA image of `fill` with the texels `at` set to `odd`.
fn rgba_with_some(size: u32, fill: [u8; 4], odd: [u8; 4], at: &[(u32, u32)]) -> Vec<u8> {
    png(RgbaImage::from_fn(size, size, |x, y| {
        image::Rgba(if at.contains(&(x, y)) { odd } else { fill })
    }))
}

/// Nine texels of a 16² image about (0.7, 0.7): beyond u + v = 1.3, far from the base
/// triangle (u + v ≤ 1) and from the edges that the REPEAT filter blends into it.
fn gutter() -> Vec<(u32, u32)> {
    patch_3x3(10, 10)
}

fn patch_3x3(x: u32, y: u32) -> Vec<(u32, u32)> {
    (x..x + 3)
        .flat_map(|x| (y..y + 3).map(move |y| (x, y)))
        .collect()
}

/// A 4×4 RGBA image of `fill` with texel (1, 2) set to `odd`.
fn rgba_with_one(fill: [u8; 4], odd: [u8; 4]) -> Vec<u8> {
    png(RgbaImage::from_fn(4, 4, |x, y| {
        image::Rgba(if (x, y) == (1, 2) { odd } else { fill })
    }))
}

fn jpeg(colour: [u8; 3]) -> Vec<u8> {
    encode(
        RgbImage::from_pixel(4, 4, image::Rgb(colour)).into(),
        ImageFormat::Jpeg,
    )
}

/// A PNG with an extra ancillary chunk right after IHDR.
fn tagged(png: Vec<u8>, kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let after_ihdr = 8 + 25;
    let mut out = png[..after_ihdr].to_vec();
    out.extend(chunk(kind, data));
    out.extend(&png[after_ihdr..]);
    out
}

fn linear_tagged(png: Vec<u8>) -> Vec<u8> {
    tagged(png, b"gAMA", &100_000u32.to_be_bytes())
}

fn srgb_tagged(png: Vec<u8>) -> Vec<u8> {
    tagged(png, b"sRGB", &[0])
}

/// A PNG whose compressed pixel data is damaged (the header is intact).
fn corrupt_png() -> Vec<u8> {
    let mut bytes = rgb([10, 20, 30]);
    let idat = bytes.windows(4).position(|w| w == b"IDAT").expect("IDAT");
    for byte in &mut bytes[idat + 4..idat + 12] {
        *byte ^= 0xA5;
    }
    bytes
}

/// A valid PNG header claiming 32768 × 32768 RGBA texels, with no pixel data behind it.
fn huge_png_header() -> Vec<u8> {
    let mut ihdr = 32_768u32.to_be_bytes().to_vec();
    ihdr.extend(32_768u32.to_be_bytes());
    ihdr.extend([8, 6, 0, 0, 0]);
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    out.extend(chunk(b"IHDR", &ihdr));
    out.extend(chunk(b"IDAT", &[0x78, 0x9c]));
    out.extend(chunk(b"IEND", &[]));
    out
}

// ---------------------------------------------------------------- running

struct Case {
    name: &'static str,
    /// For a near-miss: the rule it must not trigger.
    silent_for: Option<&'static str>,
    document: Value,
    deep: bool,
    expected: Vec<(&'static str, String)>,
}

/// A case on the base asset: `material` replaces material 0, `images[i]` becomes texture i.
fn case(name: &'static str, material: Value, images: Vec<Vec<u8>>) -> Case {
    let mut document = base();
    document["materials"] = json!([material]);
    if !images.is_empty() {
        let mime = |bytes: &[u8]| {
            if bytes.starts_with(&[0xFF, 0xD8]) {
                "image/jpeg"
            } else {
                "image/png"
            }
        };
        document["images"] = images
            .iter()
            .map(|bytes| json!({"uri": data_uri(mime(bytes), bytes)}))
            .collect();
        document["textures"] = (0..images.len()).map(|i| json!({"source": i})).collect();
    }
    Case {
        name,
        silent_for: None,
        document,
        deep: false,
        expected: Vec::new(),
    }
}

/// A case that looks like `code`'s fixture but must not trigger it.
fn near_miss(
    code: &'static str,
    name: &'static str,
    material: Value,
    images: Vec<Vec<u8>>,
) -> Case {
    let mut near_miss = case(name, material, images);
    near_miss.silent_for = Some(code);
    near_miss
}

impl Case {
    fn patch(mut self, patch: Value) -> Case {
        merge(&mut self.document, &patch);
        self
    }

    fn deep(mut self) -> Case {
        self.deep = true;
        self
    }

    /// Adds an animation that takes the number at `pointer` from 0 to 1 in one second
    /// (KHR_animation_pointer), its keys in a buffer of their own.
    fn animated(mut self, pointer: &str) -> Case {
        let keys: Vec<u8> = [0.0f32, 1.0, 0.0, 1.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let push = |document: &mut Value, collection: &str, item: Value| {
            let items = document[collection]
                .as_array_mut()
                .expect("the base has it");
            items.push(item);
            items.len() - 1
        };
        let buffer = push(
            &mut self.document,
            "buffers",
            json!({"uri": data_uri("application/octet-stream", &keys), "byteLength": 16}),
        );
        let mut accessor = |offset: usize| {
            let view = push(
                &mut self.document,
                "bufferViews",
                json!({"buffer": buffer, "byteOffset": offset, "byteLength": 8}),
            );
            push(
                &mut self.document,
                "accessors",
                json!({"bufferView": view, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0.0], "max": [1.0]}),
            )
        };
        let (input, output) = (accessor(0), accessor(8));
        self.document["animations"] = json!([{
            "channels": [{"sampler": 0, "target": {"path": "pointer", "extensions": {"KHR_animation_pointer": {"pointer": pointer}}}}],
            "samplers": [{"input": input, "output": output}]
        }]);
        self
    }

    /// Adds a KHR_interactivity graph whose one `op` node writes through `template` with
    /// the input `values`. The Khronos validator does not know the extension (first of the
    /// sorted declared names).
    fn in_graph(mut self, op: &str, template: &str, values: Value) -> Case {
        self.document["extensions"] = json!({"KHR_interactivity": {"graph": 0, "graphs": [{
            "types": [{"signature": "float"}, {"signature": "int"}],
            "declarations": [{"op": "event/onStart"}, {"op": op}],
            "nodes": [
                {"declaration": 0, "flows": {"out": {"node": 1, "socket": "in"}}},
                {"declaration": 1, "configuration": {"pointer": {"value": [template]}, "type": {"value": [0]}},
                 "values": values}]}]}});
        self.expect("UNSUPPORTED_EXTENSION", "/extensionsUsed/0")
    }

    fn expect(mut self, code: &'static str, pointer: &str) -> Case {
        self.expected.push((code, pointer.to_string()));
        self
    }

    /// Declares every extension the document uses, so that no case is about that.
    fn declared(mut self) -> Value {
        let mut names = BTreeSet::new();
        collect_extension_names(&self.document, &mut names);
        if !names.is_empty() {
            self.document["extensionsUsed"] = json!(names);
        }
        self.document
    }
}

fn collect_extension_names(value: &Value, names: &mut BTreeSet<String>) {
    match value {
        Value::Object(map) => {
            for (key, child) in map {
                if key == "extensions" {
                    names.extend(
                        child
                            .as_object()
                            .into_iter()
                            .flat_map(|e| e.keys().cloned()),
                    );
                }
                collect_extension_names(child, names);
            }
        }
        Value::Array(items) => items.iter().for_each(|v| collect_extension_names(v, names)),
        _ => {}
    }
}

/// Every issue found, as (code, pointer), with each severity checked against the registry.
/// `groups` are the opt-in rule groups run besides the default ones.
fn issues(
    uri: &str,
    bytes: Vec<u8>,
    deep: bool,
    groups: Vec<String>,
    folder: Option<&str>,
) -> Vec<(String, String)> {
    let options = CheckOptions::default()
        .with_deep(deep)
        .with_enabled_groups(groups);
    let report = match folder {
        Some(folder) => check_bytes(uri, bytes, &FolderResources::new(folder), &options),
        None => check_bytes(uri, bytes, &NoResources, &options),
    };
    // The base primitive carries two UV sets for the cases that need them; which of them a
    // case leaves unused is not what these tests are about.
    let unused_uv_set = |d: &gltfmat::Finding| {
        d.code == "UNUSED_OBJECT"
            && matches!(d.location, Place::Pointer(p) if p.contains("/attributes/TEXCOORD_"))
    };
    let mut found: Vec<_> = report
        .diagnostics
        .iter()
        .filter(|d| !unused_uv_set(d))
        .map(|d| {
            assert_eq!(
                d.severity,
                d.code.default_severity(),
                "{uri}: {} has its registered severity",
                d.code
            );
            let at = match d.location {
                Place::Pointer(p) => p.to_string(),
                Place::Offset(o) => format!("@{o}"),
            };
            (d.code.to_string(), at)
        })
        .collect();
    found.sort();
    found
}

/// The opt-in groups of the codes a case is about: a case about a plausibility rule runs
/// that group, every other case runs the default profile as users get it.
fn opt_in_groups<'c>(codes: impl Iterator<Item = &'c str>) -> Vec<String> {
    codes
        .filter_map(registry::find)
        .filter(|info| registry::is_opt_in(info.group))
        .map(|info| info.group.to_string())
        .collect()
}

fn run(case: Case) -> Vec<String> {
    let (name, deep) = (case.name, case.deep);
    let about = case.expected.iter().map(|(c, _)| *c).chain(case.silent_for);
    let groups = opt_in_groups(about);
    let mut expected: Vec<_> = case
        .expected
        .iter()
        .map(|(c, p)| (c.to_string(), p.clone()))
        .collect();
    expected.sort();
    let text = serde_json::to_vec_pretty(&case.declared()).expect("serialises");
    let found = issues(name, text, deep, groups, None);
    assert_eq!(found, expected, "case `{name}`");
    expected.into_iter().map(|(code, _)| code).collect()
}

const M0: &str = "/materials/0";

fn at(suffix: &str) -> String {
    format!("{M0}{suffix}")
}

fn opaque_grey() -> Value {
    json!({"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0})
}

fn material(extra: Value) -> Value {
    let mut m = json!({"pbrMetallicRoughness": opaque_grey()});
    merge(&mut m, &extra);
    m
}

fn visible_sheen() -> Value {
    json!({"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5})
}

fn spec_gloss() -> Value {
    json!({"diffuseFactor": [0.5, 0.5, 0.5, 1.0], "specularFactor": [0.04, 0.04, 0.04]})
}

// ---------------------------------------------------------------- the cases

fn cases() -> Vec<Case> {
    let ext = |name: &str, body: Value| json!({"extensions": {name: body}});
    let sheen_p = "/extensions/KHR_materials_sheen";
    vec![
        // -- JSON text
        near_miss("JSON_DUPLICATE_KEY", "the same key in two sibling objects", json!({"name": "a",
            "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0}}), vec![])
            .patch(json!({"nodes": [{"mesh": 0, "name": "a"}]})),
        // -- resources
        case("an image file with no folder to read it from", json!({"occlusionTexture": {"index": 0},
            "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0}}), vec![])
            .patch(json!({"images": [{"uri": "occlusion.png"}], "textures": [{"source": 0}]}))
            .expect("EXTERNAL_RESOURCE_NOT_READ", "/images/0/uri"),
        // -- exclusions
        case("specgloss + sheen", material(json!({"extensions": {
            "KHR_materials_pbrSpecularGlossiness": spec_gloss(), "KHR_materials_sheen": visible_sheen()}})), vec![])
            .expect("MATERIAL_EXTENSION_EXCLUDED", &at(sheen_p)),
        case("unlit + emissive_strength", material(json!({"emissiveFactor": [1.0, 1.0, 1.0], "extensions": {
            "KHR_materials_unlit": {}, "KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}})), vec![])
            .expect("MATERIAL_EXTENSION_EXCLUDED", &at("/extensions/KHR_materials_emissive_strength")),
        near_miss("MATERIAL_EXTENSION_EXCLUDED", "specgloss + emissive_strength is allowed", material(json!({"emissiveFactor": [1.0, 1.0, 1.0], "extensions": {
            "KHR_materials_pbrSpecularGlossiness": spec_gloss(), "KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}})), vec![]),
        near_miss("MATERIAL_EXTENSION_EXCLUDED", "sheen + clearcoat is allowed", material(json!({"extensions": {
            "KHR_materials_sheen": visible_sheen(), "KHR_materials_clearcoat": {"clearcoatFactor": 1.0}}})), vec![]),
        case("unknown vendor extension keeps the Khronos warning", material(json!({"extensions": {
            "KHR_materials_unlit": {}, "VENDOR_materials_glow": {}}})), vec![])
            .expect("MULTIPLE_EXTENSIONS", &at("/extensions/KHR_materials_unlit"))
            .expect("UNSUPPORTED_EXTENSION", "/extensionsUsed/1"),
        // -- tangent space
        case("a tangent no material extension reads is unused", material(json!({})), vec![]).patch(with_tangents())
            .expect("UNUSED_MESH_TANGENT", "/meshes/0/primitives/0/attributes/TANGENT"),
        case("a tangent and a texture an unknown extension may read are not called unused", material(ext("KHR_materials_coat",
            json!({"coatFactor": 1.0, "coatNormalTexture": {"index": 0}}))), vec![rgb([128, 128, 255])]).patch(with_tangents())
            .expect("UNSUPPORTED_EXTENSION", "/extensionsUsed/0"),
        case("an unknown extension's binding that names no texture is not reported", material(ext("KHR_materials_coat",
            json!({"coatFactor": 1.0, "coatNormalTexture": {"index": 5}}))), vec![rgb([128, 128, 255])])
            .expect("UNSUPPORTED_EXTENSION", "/extensionsUsed/0")
            .expect("UNUSED_OBJECT", "/textures/0"),
        case("an unknown extension's member not named as a binding uses no texture", material(ext("KHR_materials_coat",
            json!({"coatFactor": 1.0, "coatMap": {"index": 0}}))), vec![rgb([128, 128, 255])])
            .expect("UNSUPPORTED_EXTENSION", "/extensionsUsed/0")
            .expect("UNUSED_OBJECT", "/textures/0"),
        case("anisotropy without texture or tangents", material(ext("KHR_materials_anisotropy", json!({"anisotropyStrength": 0.5}))), vec![])
            .expect("ANISOTROPY_NO_TANGENT_SPACE", "/meshes/0/primitives/0/material"),
        near_miss("ANISOTROPY_NO_TANGENT_SPACE", "anisotropy with tangents (they are used)", material(ext("KHR_materials_anisotropy", json!({"anisotropyStrength": 0.5}))), vec![]).patch(with_tangents()),
        near_miss("ANISOTROPY_NO_TANGENT_SPACE", "anisotropy with a normal texture is the Khronos warning", material(json!({"normalTexture": {"index": 0},
            "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.5}}})), vec![rgb([128, 128, 255])])
            .expect("MESH_PRIMITIVE_GENERATED_TANGENT_SPACE", "/meshes/0/primitives/0/material"),
        case("anisotropy texCoord differs once the transform override applies", material(json!({"normalTexture": {"index": 0},
            "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.5, "anisotropyTexture": {"index": 1,
                "extensions": {"KHR_texture_transform": {"texCoord": 1}}}}}})), vec![rgb([128, 128, 255]), rgb([255, 128, 255])]).patch(with_tangents())
            .expect("KHR_MATERIALS_ANISOTROPY_ANISOTROPY_TEXTURE_TEXCOORD", &at("/extensions/KHR_materials_anisotropy/anisotropyTexture")),
        case("clearcoat normal texCoord differs once the transform override applies", material(json!({"normalTexture": {"index": 0},
            "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatNormalTexture": {"index": 0, "texCoord": 0,
                "extensions": {"KHR_texture_transform": {"texCoord": 1}}}}}})), vec![rgb([128, 128, 255])]).patch(with_tangents())
            .expect("KHR_MATERIALS_CLEARCOAT_CLEARCOAT_NORMAL_TEXTURE_TEXCOORD", &at("/extensions/KHR_materials_clearcoat/clearcoatNormalTexture")),
        // -- channels
        case("sheen roughness from an RGB image", material(ext("KHR_materials_sheen", json!({"sheenColorFactor": [1.0, 1.0, 1.0],
            "sheenRoughnessFactor": 0.5, "sheenRoughnessTexture": {"index": 0}}))), vec![rgb([9, 9, 9])])
            .expect("TEXTURE_ALPHA_MISSING", &at("/extensions/KHR_materials_sheen/sheenRoughnessTexture")),
        near_miss("TEXTURE_ALPHA_MISSING", "sheen roughness from an RGBA image", material(ext("KHR_materials_sheen", json!({"sheenColorFactor": [1.0, 1.0, 1.0],
            "sheenRoughnessFactor": 0.5, "sheenRoughnessTexture": {"index": 0}}))), vec![rgba_with_one([9, 9, 9, 128], [9, 9, 9, 64])]),
        case("blended base colour from an RGB image", json!({"alphaMode": "BLEND",
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![rgb([128, 128, 128])])
            .expect("TEXTURE_ALPHA_MISSING", &at("/pbrMetallicRoughness/baseColorTexture")),
        near_miss("TEXTURE_ALPHA_MISSING", "opaque base colour from an RGB image", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![rgb([128, 128, 128])]),
        near_miss("TEXTURE_ALPHA_MISSING", "blended base colour whose factor carries the alpha", json!({"alphaMode": "BLEND",
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [1.0, 1.0, 1.0, 0.41], "metallicFactor": 0.0}}), vec![rgb([128, 128, 128])]),
        case("metallic-roughness from a greyscale image", json!({
            "pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0}, "baseColorFactor": [0.5, 0.5, 0.5, 1.0]}}), vec![grey(200)])
            .expect("TEXTURE_GREYSCALE_PACKED", &at("/pbrMetallicRoughness/metallicRoughnessTexture")),
        near_miss("TEXTURE_GREYSCALE_PACKED", "a grey specular colour is an untinted specular", material(ext("KHR_materials_specular",
            json!({"specularColorTexture": {"index": 0}}))), vec![grey(200)]),
        case("normal map stored as JPEG", material(json!({"normalTexture": {"index": 0}})), vec![jpeg([128, 128, 255])]).patch(with_tangents())
            .expect("TEXTURE_LOSSY_DIRECTION", &at("/normalTexture")),
        near_miss("TEXTURE_LOSSY_DIRECTION", "base colour stored as JPEG", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![jpeg([128, 128, 128])]),
        // -- colour space
        case("one image as base colour and occlusion", json!({"occlusionTexture": {"index": 0},
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![rgb([128, 128, 128])])
            .expect("IMAGE_COLOR_SPACE_CONFLICT", "/images/0"),
        case("one image as base colour, occlusion and metallic-roughness, with --deep", json!({"occlusionTexture": {"index": 0},
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 0}, "metallicFactor": 0.0}}),
            vec![rgb([128, 128, 128])]).deep()
            .expect("IMAGE_COLOR_SPACE_CONFLICT", "/images/0"),
        near_miss("IMAGE_COLOR_SPACE_CONFLICT", "a black-and-white image reads the same as sRGB colour and as linear data",
            json!({"occlusionTexture": {"index": 0}, "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}),
            vec![rgba_with_one([0, 0, 0, 255], [255, 255, 255, 255])]),
        near_miss("IMAGE_COLOR_SPACE_CONFLICT", "base colour RGB and sheen roughness alpha share an image", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0},
            "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5,
                "sheenRoughnessTexture": {"index": 0}}}}), vec![rgba_with_one([128, 128, 128, 100], [128, 128, 128, 90])]),
        case("linear-tagged PNG as base colour", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![linear_tagged(rgb([128, 128, 128]))])
            .expect("IMAGE_LINEAR_IN_SRGB_SLOT", &at("/pbrMetallicRoughness/baseColorTexture")),
        near_miss("IMAGE_LINEAR_IN_SRGB_SLOT", "linear-tagged PNG as occlusion", material(json!({"occlusionTexture": {"index": 0}})),
            vec![linear_tagged(rgb([128, 128, 128]))]),
        case("sRGB-tagged PNG as occlusion", material(json!({"occlusionTexture": {"index": 0}})), vec![srgb_tagged(rgb([128, 128, 128]))])
            .expect("IMAGE_SRGB_IN_LINEAR_SLOT", &at("/occlusionTexture")),
        near_miss("IMAGE_SRGB_IN_LINEAR_SLOT", "sRGB-tagged PNG as base colour", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![srgb_tagged(rgb([128, 128, 128]))]),
        // -- settings that do nothing
        case("sheen texture with the default zero colour", material(ext("KHR_materials_sheen",
            json!({"sheenRoughnessFactor": 0.5, "sheenColorTexture": {"index": 0}}))), vec![rgb([200, 200, 200])])
            .expect("SHEEN_TEXTURE_DISABLED", &at("/extensions/KHR_materials_sheen/sheenColorTexture")),
        case("a sheen object holding only a texture (no factor at all)", material(ext("KHR_materials_sheen",
            json!({"sheenColorTexture": {"index": 0}}))), vec![rgb([200, 200, 200])])
            .expect("SHEEN_TEXTURE_DISABLED", &at("/extensions/KHR_materials_sheen/sheenColorTexture")),
        near_miss("SHEEN_TEXTURE_DISABLED", "sheen texture with a colour", material(ext("KHR_materials_sheen",
            json!({"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.5, "sheenColorTexture": {"index": 0}}))), vec![rgb([200, 200, 200])]),
        case("visible sheen with the default roughness", material(ext("KHR_materials_sheen", json!({"sheenColorFactor": [1.0, 1.0, 1.0]}))), vec![])
            .expect("SHEEN_ZERO_ROUGHNESS", &at(sheen_p)),
        case("visible sheen with roughness 0 written out", material(ext("KHR_materials_sheen",
            json!({"sheenColorFactor": [1.0, 1.0, 1.0], "sheenRoughnessFactor": 0.0}))), vec![])
            .expect("SHEEN_ZERO_ROUGHNESS", &at("/extensions/KHR_materials_sheen/sheenRoughnessFactor")),
        near_miss("SHEEN_ZERO_ROUGHNESS", "invisible sheen with roughness 0", material(ext("KHR_materials_sheen", json!({"sheenRoughnessFactor": 0.0}))), vec![]),
        // A factor an animation raises (KHR_animation_pointer) is not zero throughout.
        near_miss("SHEEN_TEXTURE_DISABLED", "sheen texture whose zero colour is animated", material(ext("KHR_materials_sheen",
            json!({"sheenRoughnessFactor": 0.5, "sheenColorTexture": {"index": 0}}))), vec![rgb([200, 200, 200])])
            .animated("/materials/0/extensions/KHR_materials_sheen/sheenColorFactor")
            .expect("INCOMPLETE_EXTENSION_SUPPORT", "/animations/0/channels/0/target/extensions/KHR_animation_pointer"),
        near_miss("SHEEN_ZERO_ROUGHNESS", "visible sheen whose zero roughness is animated", material(ext("KHR_materials_sheen",
            json!({"sheenColorFactor": [1.0, 1.0, 1.0]}))), vec![])
            .animated("/materials/0/extensions/KHR_materials_sheen/sheenRoughnessFactor")
            .expect("INCOMPLETE_EXTENSION_SUPPORT", "/animations/0/channels/0/target/extensions/KHR_animation_pointer"),
        near_miss("ANISOTROPY_TEXTURE_ZERO_STRENGTH", "anisotropy texture whose zero strength is animated", material(ext("KHR_materials_anisotropy",
            json!({"anisotropyTexture": {"index": 0}}))), vec![rgb([255, 128, 255])]).patch(with_tangents())
            .animated("/materials/0/extensions/KHR_materials_anisotropy/anisotropyStrength")
            .expect("INCOMPLETE_EXTENSION_SUPPORT", "/animations/0/channels/0/target/extensions/KHR_animation_pointer"),
        near_miss("LAYER_TEXTURE_DISABLED", "clearcoat texture whose zero factor is animated", material(ext("KHR_materials_clearcoat",
            json!({"clearcoatTexture": {"index": 0}}))), vec![rgb([200, 0, 0])])
            .animated("/materials/0/extensions/KHR_materials_clearcoat/clearcoatFactor")
            .expect("INCOMPLETE_EXTENSION_SUPPORT", "/animations/0/channels/0/target/extensions/KHR_animation_pointer"),
        near_miss("DISPERSION_THIN_WALLED", "dispersion through a volume whose zero thickness is animated", material(json!({"extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 1.0},
            "KHR_materials_volume": {}, "KHR_materials_dispersion": {"dispersion": 0.3}}})), vec![])
            .animated("/materials/0/extensions/KHR_materials_volume/thicknessFactor")
            .expect("INCOMPLETE_EXTENSION_SUPPORT", "/animations/0/channels/0/target/extensions/KHR_animation_pointer"),
        // A factor an interactivity graph sets (KHR_interactivity) is not zero throughout,
        // whichever material its template's parameter names at runtime.
        near_miss("LAYER_TEXTURE_DISABLED", "clearcoat texture whose zero factor a graph sets", material(ext("KHR_materials_clearcoat",
            json!({"clearcoatTexture": {"index": 0}}))), vec![rgb([200, 0, 0])])
            .in_graph("pointer/set", "/materials/[m]/extensions/KHR_materials_clearcoat/clearcoatFactor",
                json!({"m": {"type": 1, "value": [0]}, "value": {"type": 0, "value": [1.0]}})),
        near_miss("LAYER_TEXTURE_DISABLED", "clearcoat texture whose zero factor a graph moves, on a material chosen at runtime",
            material(ext("KHR_materials_clearcoat", json!({"clearcoatTexture": {"index": 0}}))), vec![rgb([200, 0, 0])])
            .in_graph("pointer/interpolate", "/materials/{m}/extensions/KHR_materials_clearcoat/clearcoatFactor",
                json!({"m": {"node": 0, "socket": "index"}, "value": {"type": 0, "value": [1.0]}})),
        case("clearcoat texture whose zero factor a graph sets on another material", material(ext("KHR_materials_clearcoat",
            json!({"clearcoatTexture": {"index": 0}}))), vec![rgb([200, 0, 0])])
            .in_graph("pointer/set", "/materials/[m]/extensions/KHR_materials_clearcoat/clearcoatFactor",
                json!({"m": {"type": 1, "value": [1]}, "value": {"type": 0, "value": [1.0]}}))
            .expect("LAYER_TEXTURE_DISABLED", &at("/extensions/KHR_materials_clearcoat/clearcoatTexture")),
        case("clearcoat texture whose zero factor a graph only reads", material(ext("KHR_materials_clearcoat",
            json!({"clearcoatTexture": {"index": 0}}))), vec![rgb([200, 0, 0])])
            .in_graph("pointer/get", "/materials/0/extensions/KHR_materials_clearcoat/clearcoatFactor", json!({}))
            .expect("LAYER_TEXTURE_DISABLED", &at("/extensions/KHR_materials_clearcoat/clearcoatTexture")),
        case("anisotropy texture with the default zero strength", material(ext("KHR_materials_anisotropy",
            json!({"anisotropyTexture": {"index": 0}}))), vec![rgb([255, 128, 255])]).patch(with_tangents())
            .expect("ANISOTROPY_TEXTURE_ZERO_STRENGTH", &at("/extensions/KHR_materials_anisotropy/anisotropyTexture")),
        near_miss("ANISOTROPY_TEXTURE_ZERO_STRENGTH", "anisotropy texture with a strength", material(ext("KHR_materials_anisotropy",
            json!({"anisotropyStrength": 0.5, "anisotropyTexture": {"index": 0}}))), vec![rgb([255, 128, 255])]).patch(with_tangents()),
        case("unlit material with a normal texture", material(json!({"normalTexture": {"index": 0},
            "extensions": {"KHR_materials_unlit": {}}})), vec![rgb([128, 128, 255])]).patch(with_tangents())
            .expect("UNLIT_IGNORED_TEXTURE", &at("/normalTexture")),
        near_miss("UNLIT_IGNORED_TEXTURE", "unlit material with a base colour texture", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0},
            "extensions": {"KHR_materials_unlit": {}}}), vec![rgb([128, 128, 128])]),
        case("ior on a material left at the default metallic 1", json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0]},
            "extensions": {"KHR_materials_ior": {"ior": 1.45}}}), vec![])
            .expect("SPECULAR_ON_METAL", &at("/extensions/KHR_materials_ior")),
        case("ior on a material without pbrMetallicRoughness (metallic 1 by default)",
            json!({"extensions": {"KHR_materials_ior": {"ior": 1.45}}}), vec![])
            .expect("SPECULAR_ON_METAL", &at("/extensions/KHR_materials_ior")),
        near_miss("SPECULAR_ON_METAL", "ior on a material whose metallicFactor is animated from 0 to 1",
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0]}, "extensions": {"KHR_materials_ior": {"ior": 1.45}}}), vec![])
            .animated("/materials/0/pbrMetallicRoughness/metallicFactor")
            .expect("INCOMPLETE_EXTENSION_SUPPORT", "/animations/0/channels/0/target/extensions/KHR_animation_pointer"),
        near_miss("SPECULAR_ON_METAL", "ior on a dielectric", material(ext("KHR_materials_ior", json!({"ior": 1.45}))), vec![]),
        case("glass that omits metallicFactor (so 1)", json!({"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1.0]},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.76}}}), vec![])
            .expect("TRANSMISSION_ON_METAL", &at("/extensions/KHR_materials_transmission/transmissionFactor")),
        near_miss("TRANSMISSION_ON_METAL", "glass with metallicFactor 0", material(ext("KHR_materials_transmission",
            json!({"transmissionFactor": 0.76}))), vec![]),
        // As TransmissionTest's "…Metal" spheres: the factor is left at 1 and a texture sets the metal.
        near_miss("TRANSMISSION_ON_METAL", "glass whose metallic comes from a texture", json!({
            "pbrMetallicRoughness": {"roughnessFactor": 0.0, "metallicRoughnessTexture": {"index": 0}},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}}}), vec![rgb([0, 0, 0])]),
        // As DiffuseTransmissionTest's "ColorTexture 0.0" row.
        case("diffuse transmission colour texture with the factor left at 0", material(ext("KHR_materials_diffuse_transmission",
            json!({"diffuseTransmissionColorTexture": {"index": 0}}))), vec![rgb([200, 0, 0])])
            .expect("LAYER_TEXTURE_DISABLED", &at("/extensions/KHR_materials_diffuse_transmission/diffuseTransmissionColorTexture")),
        case("clearcoat texture with the factor left at 0", material(ext("KHR_materials_clearcoat",
            json!({"clearcoatTexture": {"index": 0}}))), vec![rgb([200, 0, 0])])
            .expect("LAYER_TEXTURE_DISABLED", &at("/extensions/KHR_materials_clearcoat/clearcoatTexture")),
        near_miss("LAYER_TEXTURE_DISABLED", "clearcoat texture with a factor", material(ext("KHR_materials_clearcoat",
            json!({"clearcoatFactor": 1.0, "clearcoatTexture": {"index": 0}}))), vec![rgb([200, 0, 0])]),
        case("thickness texture on a thin-walled volume", material(json!({"extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 1.0},
            "KHR_materials_volume": {"thicknessTexture": {"index": 0}}}})), vec![rgb([0, 200, 0])])
            .expect("LAYER_TEXTURE_DISABLED", &at("/extensions/KHR_materials_volume/thicknessTexture")),
        case("dispersion on a thin-walled volume", material(json!({"extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 1.0},
            "KHR_materials_volume": {}, "KHR_materials_dispersion": {"dispersion": 0.3}}})), vec![])
            .expect("DISPERSION_THIN_WALLED", &at("/extensions/KHR_materials_dispersion")),
        near_miss("DISPERSION_THIN_WALLED", "dispersion through a volume of some thickness", material(json!({"extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 1.0},
            "KHR_materials_volume": {"thicknessFactor": 0.5}, "KHR_materials_dispersion": {"dispersion": 0.3}}})), vec![]),
        // -- pixels (--deep)
        case("anisotropy texel with no direction", material(ext("KHR_materials_anisotropy",
            json!({"anisotropyStrength": 0.5, "anisotropyTexture": {"index": 0}}))),
            vec![rgba_with_one([255, 128, 255, 255], [128, 128, 255, 255])]).patch(with_tangents()).deep()
            .expect("ANISOTROPY_DIRECTION_UNDEFINED", &at("/extensions/KHR_materials_anisotropy/anisotropyTexture")),
        near_miss("ANISOTROPY_DIRECTION_UNDEFINED", "no direction where the strength is zero", material(ext("KHR_materials_anisotropy",
            json!({"anisotropyStrength": 0.5, "anisotropyTexture": {"index": 0}}))),
            vec![rgba_with_one([255, 128, 255, 255], [128, 128, 0, 255])]).patch(with_tangents()).deep(),
        case("a normal texel pointing into the surface", material(json!({"normalTexture": {"index": 0}})),
            vec![rgba_with_one([128, 128, 255, 255], [128, 128, 100, 255])]).patch(with_tangents()).deep()
            .expect("NORMAL_TEXEL_BELOW_SURFACE", &at("/normalTexture")),
        near_miss("NORMAL_TEXEL_BELOW_SURFACE", "tilted unit normals", material(json!({"normalTexture": {"index": 0}})),
            vec![rgba_with_one([128, 128, 255, 255], [218, 128, 218, 255])]).patch(with_tangents()).deep(),
        near_miss("NORMAL_TEXEL_BELOW_SURFACE", "normals longer than 1, as a renderer normalises them", material(json!({"normalTexture": {"index": 0}})),
            vec![rgba_with_one([189, 188, 254, 255], [128, 128, 255, 255])]).patch(with_tangents()).deep(),
        // The triangle's UVs cover u + v ≤ 1: the texels about (0.7, 0.7) are a gutter nothing samples.
        near_miss("NORMAL_TEXEL_BELOW_SURFACE", "texels into the surface only where the mesh's UVs never reach", material(json!({"normalTexture": {"index": 0}})),
            vec![rgba_with_some(16, [128, 128, 255, 255], [128, 128, 0, 255], &gutter())]).patch(with_tangents()).deep(),
        case("the same texels read through a transform that brings them under the triangle",
            material(json!({"normalTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.6, 0.6]}}}})),
            vec![rgba_with_some(16, [128, 128, 255, 255], [128, 128, 0, 255], &gutter())])
            .patch(with_tangents()).patch(json!({"extensionsUsed": ["KHR_texture_transform"]})).deep()
            .expect("NORMAL_TEXEL_BELOW_SURFACE", &at("/normalTexture")),
        near_miss("NORMAL_TEXEL_BELOW_SURFACE", "one texel into the surface among the 2,000 a mesh samples", material(json!({"normalTexture": {"index": 0}})),
            vec![rgba_with_some(64, [128, 128, 255, 255], [128, 128, 0, 255], &[(10, 10)])]).patch(with_tangents()).deep(),
        case("a patch of 9 texels into the surface among the 2,000 a mesh samples", material(json!({"normalTexture": {"index": 0}})),
            vec![rgba_with_some(64, [128, 128, 255, 255], [128, 128, 0, 255], &patch_3x3(10, 10))]).patch(with_tangents()).deep()
            .expect("NORMAL_TEXEL_BELOW_SURFACE", &at("/normalTexture")),
        case("constant alpha read as sheen roughness", material(ext("KHR_materials_sheen", json!({"sheenColorFactor": [1.0, 1.0, 1.0],
            "sheenRoughnessFactor": 0.5, "sheenRoughnessTexture": {"index": 0}}))), vec![rgba([9, 9, 9, 200])]).deep()
            .expect("TEXTURE_ALPHA_CONSTANT", &at("/extensions/KHR_materials_sheen/sheenRoughnessTexture")),
        near_miss("TEXTURE_ALPHA_CONSTANT", "sheen roughness alpha that varies", material(ext("KHR_materials_sheen", json!({"sheenColorFactor": [1.0, 1.0, 1.0],
            "sheenRoughnessFactor": 0.5, "sheenRoughnessTexture": {"index": 0}}))), vec![rgba_with_one([9, 9, 9, 200], [9, 9, 9, 199])]).deep(),
        near_miss("PBR_BASE_COLOR_RANGE", "mid-grey base colour texture", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![rgb([128, 128, 128])]).deep(),
        case("damaged PNG data", material(json!({"normalTexture": {"index": 0}})), vec![corrupt_png()]).patch(with_tangents()).deep()
            .expect("IMAGE_UNDECODABLE", "/images/0"),
        near_miss("IMAGE_UNDECODABLE", "damaged PNG data without --deep", material(json!({"normalTexture": {"index": 0}})), vec![corrupt_png()]).patch(with_tangents()),
        case("a KTX2 normal map in a plain Vulkan format, which gltfmat does not transcode", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_image()).deep()
            .expect("IMAGE_NOT_DECODED", "/images/0")
            .expect("KTX2_LAYOUT_INVALID", "/images/0"),
        near_miss("KTX2_LAYOUT_INVALID", "a UASTC (Zstandard) and an ETC1S (BasisLZ) KTX2, each 2D with an allowed channel layout",
            material(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "normalTexture": {"index": 1}})), vec![])
            .patch(ktx2_fixtures(&["base-etc1s.ktx2", "normal-uastc.ktx2"])),
        near_miss("IMAGE_NOT_DECODED", "a Basis Universal (UASTC) KTX2 normal map, transcoded", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_fixtures(&["normal-uastc.ktx2"])).deep(),
        case("a KTX2 normal map whose texels point into the surface, read through ETC1S", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_fixtures(&["inward-normal-etc1s.ktx2"])).deep()
            .expect("NORMAL_TEXEL_BELOW_SURFACE", &at("/normalTexture")),
        case("a Basis Universal KTX2 whose data is cut short", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_images(&[truncated_fixture("normal-uastc.ktx2")])).deep()
            .expect("IMAGE_UNDECODABLE", "/images/0"),
        case("a KTX2 normal map declared sRGB", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_fixtures(&["normal-etc1s-srgb.ktx2"]))
            .expect("KTX2_TRANSFER_MISMATCH", &at("/normalTexture")),
        case("a KTX2 base colour declared linear", material(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "normalTexture": {"index": 1}})), vec![])
            .patch(ktx2_fixtures(&["normal-uastc.ktx2", "normal-uastc.ktx2"]))
            .expect("KTX2_TRANSFER_MISMATCH", &at("/pbrMetallicRoughness/baseColorTexture")),
        case("a one-level KTX2 minified through mipmaps", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_images(&[fixture_claiming("normal-uastc.ktx2", 40, 1)])).patch(json!({"samplers": [{"minFilter": 9987}]}))
            .expect("KTX2_MIPMAPS_MISSING", "/textures/0"),
        case("a one-level KTX2 with no sampler", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_images(&[fixture_claiming("normal-uastc.ktx2", 40, 1)]))
            .patch(json!({"textures": [{"extensions": {"KHR_texture_basisu": {"source": 0}}}], "samplers": null}))
            .expect("KTX2_MIPMAPS_MISSING", "/textures/0"),
        near_miss("KTX2_MIPMAPS_MISSING", "a KTX2 with its full mip chain, minified through mipmaps", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_fixtures(&["normal-uastc.ktx2"])).patch(json!({"samplers": [{"minFilter": 9987}]})),
        case("a KTX2 of 6 texels' width", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_images(&[fixture_claiming("normal-uastc.ktx2", 20, 6)]))
            .expect("KTX2_DIMENSIONS_NOT_MULTIPLE_OF_4", "/images/0"),
        near_miss("KTX2_DIMENSIONS_NOT_MULTIPLE_OF_4", "a KTX2 of 8 texels' width", material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_images(&[fixture_claiming("normal-uastc.ktx2", 20, 8)])),
        near_miss("KTX2_DIMENSIONS_NOT_MULTIPLE_OF_4", "a KTX2 of 6 texels' width read through another extension than KHR_texture_basisu",
            material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_images(&[fixture_claiming("normal-uastc.ktx2", 20, 6)])).patch(through_another_extension())
            .expect("UNSUPPORTED_EXTENSION", "/extensionsUsed/0").expect("UNUSED_OBJECT", "/images/0")
            .expect("VALUE_NOT_IN_LIST", "/images/0/mimeType"),
        near_miss("KTX2_LAYOUT_INVALID", "a KTX2 in a plain Vulkan format read through another extension than KHR_texture_basisu",
            material(json!({"normalTexture": {"index": 0}})), vec![])
            .patch(ktx2_image()).patch(through_another_extension())
            .expect("UNSUPPORTED_EXTENSION", "/extensionsUsed/0").expect("UNUSED_OBJECT", "/images/0")
            .expect("VALUE_NOT_IN_LIST", "/images/0/mimeType"),
        near_miss("KTX2_TRANSFER_MISMATCH", "an sRGB KTX2 base colour and a linear KTX2 normal map",
            material(json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "normalTexture": {"index": 1}})), vec![])
            .patch(ktx2_fixtures(&["base-uastc.ktx2", "normal-uastc.ktx2"])),
        case("PNG claiming 32768² texels", material(json!({"normalTexture": {"index": 0}})), vec![huge_png_header()]).patch(with_tangents()).deep()
            .expect("IMAGE_DECODE_LIMIT", "/images/0"),
        // -- plausibility
        case("charcoal-black dielectric", json!({"pbrMetallicRoughness": {"baseColorFactor": [0.005, 0.005, 0.005, 1.0], "metallicFactor": 0.0}}), vec![])
            .expect("PBR_BASE_COLOR_RANGE", &at("/pbrMetallicRoughness/baseColorFactor")),
        near_miss("PBR_BASE_COLOR_RANGE", "black metal", json!({"pbrMetallicRoughness": {"baseColorFactor": [0.005, 0.005, 0.005, 1.0]}}), vec![]),
        case("base colour texture mostly too dark", json!({
            "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}), vec![rgb([10, 10, 10])]).deep()
            .expect("PBR_BASE_COLOR_RANGE", &at("/pbrMetallicRoughness/baseColorTexture")),
        case("half-metal factor", json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.5}}), vec![])
            .expect("PBR_METALLIC_MIXED", &at("/pbrMetallicRoughness/metallicFactor")),
        case("half-metal texture", json!({"pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0},
            "baseColorFactor": [0.5, 0.5, 0.5, 1.0]}}), vec![rgb([0, 128, 128])]).deep()
            .expect("PBR_METALLIC_MIXED", &at("/pbrMetallicRoughness/metallicRoughnessTexture")),
        near_miss("PBR_METALLIC_MIXED", "metal/dielectric texture", json!({"pbrMetallicRoughness": {"metallicRoughnessTexture": {"index": 0},
            "baseColorFactor": [0.5, 0.5, 0.5, 1.0]}}), vec![rgba_with_one([0, 128, 255, 255], [0, 128, 0, 255])]).deep(),
        near_miss("PBR_BASE_COLOR_RANGE", "clear glass: white base colour, full transmission", json!({
            "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}}}), vec![]),
        near_miss("PBR_BASE_COLOR_RANGE", "the default base colour, not written", json!({
            "pbrMetallicRoughness": {"metallicFactor": 0.0}}), vec![]),
        near_miss("PBR_METALLIC_MIXED", "0.1 as float32 is a dielectric", json!({
            "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.100000001490116}}), vec![]),
    ]
}

#[test]
fn the_base_fixture_is_clean() {
    let text = serde_json::to_vec(&base()).unwrap();
    let every_group = registry::OPT_IN_GROUPS
        .iter()
        .map(|g| g.to_string())
        .collect();
    assert_eq!(issues("base", text, true, every_group, None), Vec::new());
}

/// The pointers, sorted, of the findings of `code` when `text` is checked in `profile`.
fn pointers_of(code: &str, text: &[u8], profile: gltfmat::Profile) -> Vec<String> {
    let options = CheckOptions::default().with_profile(profile);
    let report = check_bytes("asset.gltf", text.to_vec(), &NoResources, &options);
    let mut pointers: Vec<String> = (report.diagnostics.iter())
        .filter(|d| d.code == code)
        .filter_map(|d| match d.location {
            Place::Pointer(p) => Some(p.to_string()),
            Place::Offset(_) => None,
        })
        .collect();
    pointers.sort();
    pointers
}

/// A texture bound inside an extension gltfmat does not read (KHR_materials_coat, a draft)
/// reads its texCoord set: the default profile does not call that set unused; the Khronos
/// profile, which reads nothing in the extension, does, as the validator does.
#[test]
fn a_uv_set_read_inside_an_unknown_extension_is_used_in_the_default_profile_only() {
    let coat = json!({"coatFactor": 1.0, "coatTexture": {"index": 0, "texCoord": 1}});
    let case = case(
        "coat on TEXCOORD_1",
        material(json!({"extensions": {"KHR_materials_coat": coat}})),
        vec![rgb([200, 200, 200])],
    );
    let text = serde_json::to_vec(&case.declared()).unwrap();
    let unused_sets = |profile| pointers_of("UNUSED_OBJECT", &text, profile);
    let set = |n: u32| format!("/meshes/0/primitives/0/attributes/TEXCOORD_{n}");
    assert_eq!(unused_sets(gltfmat::Profile::Default), vec![set(0)]);
    assert_eq!(
        unused_sets(gltfmat::Profile::Khronos),
        vec![set(0), set(1), "/textures/0".to_string()]
    );
}

/// An attribute semantic named after a declared extension, `<extension>:<name>`, is that
/// extension's (KHR_gaussian_splatting names its attributes so) in the default profile, in
/// attributes and morph targets alike; the Khronos profile calls it invalid, as the released
/// validator does. An undeclared prefix, an empty name and a bare name stay invalid.
#[test]
fn attribute_semantics_named_after_a_declared_extension_are_its_own_in_the_default_profile() {
    let mut asset = base();
    asset["extensionsUsed"] = json!(["KHR_gaussian_splatting"]);
    let primitive = &mut asset["meshes"][0]["primitives"][0];
    for name in [
        "KHR_gaussian_splatting:SCALE",
        "KHR_gaussian_splatting:",
        "EXT_undeclared:SCALE",
        "SCALE",
    ] {
        primitive["attributes"][name] = json!(0);
    }
    primitive["targets"] = json!([{"KHR_gaussian_splatting:SCALE": 0, "EXT_undeclared:SCALE": 0}]);
    let text = serde_json::to_vec(&asset).unwrap();
    let invalid = |profile| -> Vec<String> {
        (pointers_of("MESH_PRIMITIVE_INVALID_ATTRIBUTE", &text, profile).iter())
            .map(|p| p.trim_start_matches("/meshes/0/primitives/0/").to_string())
            .collect()
    };
    let undeclared = [
        "attributes/EXT_undeclared:SCALE",
        "attributes/KHR_gaussian_splatting:",
        "attributes/SCALE",
        "targets/0/EXT_undeclared:SCALE",
    ];
    assert_eq!(invalid(gltfmat::Profile::Default), undeclared);
    let mut every = undeclared.to_vec();
    every.extend([
        "attributes/KHR_gaussian_splatting:SCALE",
        "targets/0/KHR_gaussian_splatting:SCALE",
    ]);
    every.sort();
    assert_eq!(invalid(gltfmat::Profile::Khronos), every);
}

/// Diffuse 1 and specular 1 (the defaults) cannot reflect more than they receive: the
/// extension scales diffuse by (1 − max specular). No rule, opt-in ones included, says so.
#[test]
fn a_specular_glossiness_material_at_its_defaults_is_not_a_finding() {
    let spec_gloss = json!({"extensions": {"KHR_materials_pbrSpecularGlossiness": {}}});
    let case = case("spec-gloss defaults", material(spec_gloss), vec![]);
    let text = serde_json::to_vec(&case.declared()).unwrap();
    let every_group = registry::OPT_IN_GROUPS
        .iter()
        .map(|g| g.to_string())
        .collect();
    assert_eq!(
        issues("spec-gloss defaults", text, true, every_group, None),
        Vec::new()
    );
}

#[test]
fn every_rule_case_reports_exactly_its_issues() {
    let failures: Vec<String> = cases()
        .into_iter()
        .filter_map(|case| {
            let name = case.name;
            std::panic::catch_unwind(|| run(case))
                .err()
                .map(|_| name.to_string())
        })
        .collect();
    assert!(failures.is_empty(), "failing cases: {failures:#?}");
}

/// Cases kept as files: the ones about the document text or the file system.
fn file_cases() -> Vec<(&'static str, Vec<(&'static str, &'static str)>)> {
    vec![
        (
            "fixtures/broken/duplicate-key.gltf",
            vec![("JSON_DUPLICATE_KEY", "/materials/0/doubleSided")],
        ),
        (
            "fixtures/broken/parent-dir-uri.gltf",
            vec![("URI_OUTSIDE_ASSET_FOLDER", "/buffers/0/uri")],
        ),
        (
            "fixtures/gltf1/pbr-metal-rough-bad.gltf",
            vec![
                ("GLTF_1_0_ASSET", "/asset/version"),
                (
                    "VALUE_NOT_IN_RANGE",
                    "/materials/gold/extensions/FRAUNHOFER_materials_pbr/values/metallicFactor",
                ),
                (
                    "UNRESOLVED_REFERENCE",
                    "/materials/gold/extensions/FRAUNHOFER_materials_pbr/values/baseColorTexture",
                ),
                (
                    "GLTF_1_0_PBR_MATERIAL",
                    "/materials/gold/extensions/FRAUNHOFER_materials_pbr",
                ),
            ],
        ),
    ]
}

#[test]
fn file_fixtures_report_exactly_their_issues() {
    for (path, expected) in file_cases() {
        let full = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
        let bytes = std::fs::read(&full).unwrap_or_else(|e| panic!("{path}: {e}"));
        let folder = full.parent().unwrap().to_str().unwrap().to_string();
        let found: Vec<_> = issues(path, bytes, false, Vec::new(), Some(&folder))
            .into_iter()
            .filter(|(code, _)| {
                registry::find(code).is_some_and(|i| i.origin == Origin::Gltfmat)
                    || expected.iter().any(|(c, _)| c == code)
            })
            .collect();
        let mut expected: Vec<_> = expected
            .iter()
            .map(|(c, p)| (c.to_string(), p.to_string()))
            .collect();
        expected.sort();
        assert_eq!(found, expected, "{path}");
    }
}

#[test]
fn every_rule_has_a_firing_fixture_and_a_near_miss() {
    let mut fired: BTreeSet<String> = cases().into_iter().flat_map(run).collect();
    fired.extend(
        file_cases()
            .into_iter()
            .flat_map(|(_, e)| e.into_iter().map(|(c, _)| c.to_string())),
    );
    let near_misses: BTreeSet<_> = cases().iter().filter_map(|c| c.silent_for).collect();
    for rule in registry::all().filter(|i| i.origin == Origin::Gltfmat) {
        let code = rule.code.name();
        assert!(
            fired.contains(code),
            "{code} has no fixture that triggers it"
        );
        let has_logic = rule.own_logic;
        assert!(
            !has_logic || near_misses.contains(code),
            "{code} has no near-miss fixture"
        );
    }
}

/// A skinned node under a transformed parent: the transform is lost only where it does not
/// also reach every joint (a rig's root transform moves the joints, and so the mesh).
#[test]
fn a_parent_transform_is_reported_lost_only_where_it_does_not_reach_the_joints() {
    let asset = |mesh_parent_reaches_joints: bool| {
        // 0 Z_UP (rotated) → 1 Armature → {2 skinned mesh node, 3 joint → 4 joint}; or the
        // mesh node under 5, a moved sibling of the armature.
        let mut nodes = vec![
            json!({"children": [1], "rotation": [0.6, 0, 0, 0.8]}),
            json!({"children": [2, 3], "translation": [1, 0, 0]}),
            json!({"mesh": 0, "skin": 0}),
            json!({"children": [4], "translation": [0, 1, 0]}),
            json!({"translation": [0, 1, 0]}),
        ];
        if !mesh_parent_reaches_joints {
            nodes[1] = json!({"children": [3], "translation": [1, 0, 0]});
            nodes[0] = json!({"children": [1, 5], "rotation": [0.6, 0, 0, 0.8]});
            nodes.push(json!({"children": [2], "scale": [2, 2, 2]}));
        }
        let report = check_bytes(
            "rig.gltf",
            serde_json::to_vec(&json!({"asset": {"version": "2.0"}, "nodes": nodes,
                "meshes": [{"primitives": [{"attributes": {}}]}],
                "skins": [{"joints": [3, 4]}], "scenes": [{"nodes": [0]}], "scene": 0}))
            .unwrap(),
            &NoResources,
            &CheckOptions::default(),
        );
        (report.diagnostics.iter())
            .filter(|d| d.code.name() == "NODE_SKINNED_MESH_PARENT_TRANSFORMS")
            .map(|d| d.pointer().unwrap_or_default().to_string())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        asset(true),
        Vec::<String>::new(),
        "the rig's transforms reach the joints"
    );
    assert_eq!(
        asset(false),
        ["/nodes/2"],
        "a moved sibling of the armature is lost"
    );
}
