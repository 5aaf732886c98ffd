//! Real glTF 1.0 assets (../shared/real-world/gltf1: COLLADA2GLTF sample models in every
//! variant, the PBR draft's hammer) upgrade faithfully and load in a real 2.0 client.
//!
//! The source side is read here, independently of the converter, from the 1.0 text: node
//! hierarchy, accessors, skins (IBM · bindShapeMatrix, weights divided by their sum as the 1.0
//! shaders' perspective divide did). The output side is read by gltf-rs, a real client: every
//! accessor must read through its readers. Compared: every primitive's world-space bind-pose
//! bounding box, the animation channels (node, path, key count, time range), each skin's joint
//! count, the cameras and the image bytes, to 1e-4 relative.

mod common;
use common::shared;

use gltfmat::upgrade_output as output;
use gltfmat::{upgrade, FolderResources, UpgradeOptions};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

type Matrix = [f64; 16];
const IDENTITY: Matrix = [
    1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.,
];

/// Column-major a · b.
fn multiply(a: &Matrix, b: &Matrix) -> Matrix {
    let mut out = [0.0; 16];
    for column in 0..4 {
        for row in 0..4 {
            out[column * 4 + row] = (0..4).map(|k| a[k * 4 + row] * b[column * 4 + k]).sum();
        }
    }
    out
}

fn transform(m: &Matrix, p: [f64; 3]) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (row, value) in out.iter_mut().enumerate() {
        *value = m[row] * p[0] + m[4 + row] * p[1] + m[8 + row] * p[2] + m[12 + row];
    }
    out
}

/// A node's local matrix from `matrix` or translation / rotation (x, y, z, w) / scale.
fn local(matrix: Option<Matrix>, t: [f64; 3], r: [f64; 4], s: [f64; 3]) -> Matrix {
    if let Some(m) = matrix {
        return m;
    }
    let [x, y, z, w] = r;
    let rotation = [
        1. - 2. * (y * y + z * z),
        2. * (x * y + z * w),
        2. * (x * z - y * w),
        0.,
        2. * (x * y - z * w),
        1. - 2. * (x * x + z * z),
        2. * (y * z + x * w),
        0.,
        2. * (x * z + y * w),
        2. * (y * z - x * w),
        1. - 2. * (x * x + y * y),
        0.,
        0.,
        0.,
        0.,
        1.,
    ];
    let mut scaled = rotation;
    for column in 0..3 {
        for row in 0..3 {
            scaled[column * 4 + row] *= s[column];
        }
    }
    scaled[12..15].copy_from_slice(&t);
    scaled
}

/// What must survive the upgrade, keyed by names both sides share (1.0 ids become names).
#[derive(Debug, Default)]
struct Summary {
    /// (mesh name, primitive index) → each instance's world bounding box, sorted.
    boxes: BTreeMap<(String, usize), Vec<[f64; 6]>>,
    /// (node name, path, key count, first time, last time), sorted.
    channels: Vec<(String, String, usize, f64, f64)>,
    /// skin name → joint counts of its instances, sorted.
    joints: BTreeMap<String, Vec<usize>>,
    /// camera name → its type and parameters (znear left out: 0 is made valid on purpose).
    cameras: BTreeMap<String, Vec<f64>>,
    /// image name → its bytes.
    images: BTreeMap<String, Vec<u8>>,
}

fn bounds(points: impl Iterator<Item = [f64; 3]>) -> [f64; 6] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
        -f64::INFINITY,
        -f64::INFINITY,
        -f64::INFINITY,
    ];
    for p in points {
        for k in 0..3 {
            b[k] = b[k].min(p[k]);
            b[k + 3] = b[k + 3].max(p[k]);
        }
    }
    b
}

/// Weighted joint matrices applied to a point. A 1.0 shader's perspective divide removed the
/// weight sum (`divide`); a 2.0 client takes xyz as they are.
fn skinned(
    p: [f64; 3],
    joints: &[usize],
    weights: &[f64],
    matrices: &[Matrix],
    divide: bool,
) -> [f64; 3] {
    let mut sum = [0.0; 4];
    for (&j, &w) in joints.iter().zip(weights) {
        if w == 0.0 {
            continue;
        }
        let q = transform(&matrices[j], p);
        for k in 0..4 {
            sum[k] += w * q[k];
        }
    }
    let total: f64 = if divide { weights.iter().sum() } else { 1.0 };
    [sum[0] / total, sum[1] / total, sum[2] / total]
}

mod gltf1 {
    //! Just enough of glTF 1.0 to compute the summary, written from the 1.0 specification.
    use super::*;
    use base64::Engine;

    pub struct Asset {
        pub json: Value,
        buffers: BTreeMap<String, Vec<u8>>,
        folder: PathBuf,
    }

    pub fn read(path: &Path) -> Asset {
        let bytes = std::fs::read(path).unwrap();
        let folder = path.parent().unwrap().to_path_buf();
        let (json, body) = if bytes.starts_with(b"glTF") {
            let length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
            (
                serde_json::from_slice(&bytes[20..20 + length]).unwrap(),
                bytes[20 + length..].to_vec(),
            )
        } else {
            (serde_json::from_slice(&bytes).unwrap(), Vec::new())
        };
        let mut asset = Asset {
            json,
            buffers: BTreeMap::new(),
            folder,
        };
        let buffers: Vec<(String, Value)> = asset.dictionary("buffers");
        for (id, buffer) in buffers {
            let data = if id == "binary_glTF" {
                body.clone()
            } else {
                asset.uri(buffer["uri"].as_str().unwrap())
            };
            asset.buffers.insert(id, data);
        }
        asset
    }

    impl Asset {
        pub fn dictionary(&self, name: &str) -> Vec<(String, Value)> {
            (self.json[name].as_object().into_iter().flatten())
                .map(|(k, v)| (k.clone(), v.clone()))
                .collect()
        }

        pub fn name_of(&self, collection: &str, id: &str) -> String {
            self.json[collection][id]["name"]
                .as_str()
                .unwrap_or(id)
                .to_string()
        }

        pub fn uri(&self, uri: &str) -> Vec<u8> {
            match uri.strip_prefix("data:") {
                Some(data) => {
                    let (_, encoded) = data.split_once(";base64,").unwrap();
                    base64::engine::general_purpose::STANDARD
                        .decode(encoded)
                        .unwrap()
                }
                None => std::fs::read(self.folder.join(uri))
                    .or_else(|_| std::fs::read(self.in_another_letter_case(uri)))
                    .unwrap(),
            }
        }

        /// The file beside `uri`'s whose name differs from it only in letter case (as an
        /// asset made on Windows or macOS may name it).
        fn in_another_letter_case(&self, uri: &str) -> std::path::PathBuf {
            let wanted = self.folder.join(uri);
            let folder = wanted.parent().unwrap();
            let name = wanted.file_name().unwrap().to_string_lossy().to_lowercase();
            let entries = std::fs::read_dir(folder).unwrap().flatten();
            let mut alike =
                entries.filter(|e| e.file_name().to_string_lossy().to_lowercase() == name);
            alike.next().map(|e| e.path()).unwrap_or(wanted)
        }

        pub fn image_bytes(&self, image: &Value) -> Vec<u8> {
            match image["extensions"]["KHR_binary_glTF"]["bufferView"].as_str() {
                Some(view) => self.view(view).to_vec(),
                None => self.uri(image["uri"].as_str().unwrap()),
            }
        }

        fn view(&self, id: &str) -> &[u8] {
            let view = &self.json["bufferViews"][id];
            let buffer = &self.buffers[view["buffer"].as_str().unwrap()];
            let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
            let length = view["byteLength"]
                .as_u64()
                .map_or(buffer.len() - offset, |l| l as usize);
            &buffer[offset..offset + length]
        }

        /// An accessor's elements as f64 components.
        pub fn accessor(&self, id: &str) -> Vec<Vec<f64>> {
            let accessor = &self.json["accessors"][id];
            let components = match accessor["type"].as_str().unwrap() {
                "SCALAR" => 1,
                "VEC2" => 2,
                "VEC3" => 3,
                "VEC4" | "MAT2" => 4,
                "MAT3" => 9,
                _ => 16,
            };
            let kind = accessor["componentType"].as_u64().unwrap();
            let size = match kind {
                5120 | 5121 => 1,
                5122 | 5123 => 2,
                _ => 4,
            };
            let stride = match accessor["byteStride"].as_u64().unwrap_or(0) as usize {
                0 => size * components,
                s => s,
            };
            let data = self.view(accessor["bufferView"].as_str().unwrap());
            let offset = accessor["byteOffset"].as_u64().unwrap_or(0) as usize;
            (0..accessor["count"].as_u64().unwrap() as usize)
                .map(|i| {
                    (0..components)
                        .map(|c| {
                            let at = offset + i * stride + c * size;
                            let b = &data[at..at + size];
                            match kind {
                                5120 => b[0] as i8 as f64,
                                5121 => b[0] as f64,
                                5122 => i16::from_le_bytes([b[0], b[1]]) as f64,
                                5123 => u16::from_le_bytes([b[0], b[1]]) as f64,
                                5125 => u32::from_le_bytes(b.try_into().unwrap()) as f64,
                                _ => f32::from_le_bytes(b.try_into().unwrap()) as f64,
                            }
                        })
                        .collect()
                })
                .collect()
        }

        fn matrix(value: &Value) -> Option<Matrix> {
            let list: Vec<f64> = value.as_array()?.iter().filter_map(Value::as_f64).collect();
            list.try_into().ok()
        }

        /// Every node's world matrix.
        pub fn world(&self) -> BTreeMap<String, Matrix> {
            let nodes = self.dictionary("nodes");
            let mut parent = BTreeMap::new();
            for (id, node) in &nodes {
                for child in node["children"].as_array().into_iter().flatten() {
                    parent.insert(child.as_str().unwrap().to_string(), id.clone());
                }
            }
            let local_of = |node: &Value| {
                let v = |key: &str, default: &[f64]| -> Vec<f64> {
                    node[key].as_array().map_or(default.to_vec(), |a| {
                        a.iter().map(|x| x.as_f64().unwrap()).collect()
                    })
                };
                let (t, r, s) = (
                    v("translation", &[0.; 3]),
                    v("rotation", &[0., 0., 0., 1.]),
                    v("scale", &[1.; 3]),
                );
                local(
                    Self::matrix(&node["matrix"]),
                    t.try_into().unwrap(),
                    r.try_into().unwrap(),
                    s.try_into().unwrap(),
                )
            };
            let mut world = BTreeMap::new();
            for (id, _) in &nodes {
                let mut m = IDENTITY;
                let mut at = Some(id.clone());
                while let Some(node) = at {
                    m = multiply(&local_of(&self.json["nodes"][&node]), &m);
                    at = parent.get(&node).cloned();
                }
                world.insert(id.clone(), m);
            }
            world
        }

        /// The node a jointName names under the skeleton roots (1.0 scopes joint names by them).
        fn joint(&self, skeletons: &[String], name: &str) -> String {
            let mut stack: Vec<String> = skeletons.to_vec();
            while let Some(id) = stack.pop() {
                let node = &self.json["nodes"][&id];
                if node["jointName"].as_str() == Some(name) {
                    return id;
                }
                stack.extend(
                    node["children"]
                        .as_array()
                        .into_iter()
                        .flatten()
                        .map(|c| c.as_str().unwrap().to_string()),
                );
            }
            panic!("joint {name} not found")
        }

        /// Each node's skin matrices: W(joint) · IBM · bindShapeMatrix.
        pub fn skin_matrices(
            &self,
            node: &Value,
            world: &BTreeMap<String, Matrix>,
        ) -> Option<(String, Vec<Matrix>)> {
            let skin_id = node["skin"].as_str()?;
            let skin = &self.json["skins"][skin_id];
            let skeletons: Vec<String> = node["skeletons"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s.as_str().unwrap().to_string())
                .collect();
            let bind_shape = Self::matrix(&skin["bindShapeMatrix"]).unwrap_or(IDENTITY);
            let ibms = self.accessor(skin["inverseBindMatrices"].as_str().unwrap());
            let names = skin["jointNames"].as_array().unwrap();
            let matrices = names
                .iter()
                .zip(ibms)
                .map(|(name, ibm)| {
                    let joint = self.joint(&skeletons, name.as_str().unwrap());
                    let ibm: Matrix = ibm.try_into().unwrap();
                    multiply(&world[&joint], &multiply(&ibm, &bind_shape))
                })
                .collect();
            Some((self.name_of("skins", skin_id), matrices))
        }
    }

    pub fn summary(asset: &Asset) -> Summary {
        let mut summary = Summary::default();
        let world = asset.world();
        for (id, node) in asset.dictionary("nodes") {
            let skin = asset.skin_matrices(&node, &world);
            if let Some((name, matrices)) = &skin {
                summary
                    .joints
                    .entry(name.clone())
                    .or_default()
                    .push(matrices.len());
            }
            for mesh in node["meshes"].as_array().into_iter().flatten() {
                let mesh = mesh.as_str().unwrap();
                let primitives = asset.json["meshes"][mesh]["primitives"].as_array().unwrap();
                for (p, primitive) in primitives.iter().enumerate() {
                    let attribute = |name: &str| {
                        primitive["attributes"][name]
                            .as_str()
                            .map(|a| asset.accessor(a))
                    };
                    let positions = attribute("POSITION").unwrap();
                    let points: Vec<[f64; 3]> =
                        match (&skin, attribute("JOINT"), attribute("WEIGHT")) {
                            (Some((_, matrices)), Some(joints), Some(weights)) => positions
                                .iter()
                                .zip(joints.iter().zip(&weights))
                                .filter(|(_, (_, w))| w.iter().sum::<f64>() > 0.0)
                                .map(|(v, (j, w))| {
                                    let j: Vec<usize> = j.iter().map(|x| *x as usize).collect();
                                    skinned([v[0], v[1], v[2]], &j, w, matrices, true)
                                })
                                .collect(),
                            _ => positions
                                .iter()
                                .map(|v| {
                                    let q = transform(&world[&id], [v[0], v[1], v[2]]);
                                    [q[0], q[1], q[2]]
                                })
                                .collect(),
                        };
                    let key = (asset.name_of("meshes", mesh), p);
                    summary
                        .boxes
                        .entry(key)
                        .or_default()
                        .push(bounds(points.into_iter()));
                }
            }
        }
        for (_, animation) in asset.dictionary("animations") {
            for channel in animation["channels"].as_array().into_iter().flatten() {
                let sampler = &animation["samplers"][channel["sampler"].as_str().unwrap()];
                let input = animation["parameters"][sampler["input"].as_str().unwrap()]
                    .as_str()
                    .unwrap();
                let times: Vec<f64> = asset.accessor(input).into_iter().map(|t| t[0]).collect();
                let target = &channel["target"];
                summary.channels.push((
                    asset.name_of("nodes", target["id"].as_str().unwrap()),
                    target["path"].as_str().unwrap().to_string(),
                    times.len(),
                    times[0],
                    *times.last().unwrap(),
                ));
            }
        }
        for (id, camera) in asset.dictionary("cameras") {
            let kind = camera["type"].as_str().unwrap();
            let p = &camera[kind];
            let values = match kind {
                "perspective" => ["yfov", "aspectRatio", "zfar"]
                    .map(|k| p[k].as_f64().unwrap_or(-1.0))
                    .to_vec(),
                _ => ["xmag", "ymag", "zfar"]
                    .map(|k| p[k].as_f64().unwrap_or(-1.0))
                    .to_vec(),
            };
            summary
                .cameras
                .insert(asset.name_of("cameras", &id), values);
        }
        for (id, image) in asset.dictionary("images") {
            summary
                .images
                .insert(asset.name_of("images", &id), asset.image_bytes(&image));
        }
        summary
    }
}

/// The output read by gltf-rs: every accessor through its readers.
fn gltf2_summary(
    document: &gltf::Document,
    buffer: &[u8],
    images: &BTreeMap<usize, Vec<u8>>,
) -> Summary {
    let mut summary = Summary::default();
    let data = |b: gltf::Buffer| (b.index() == 0).then_some(buffer);
    let mut world = vec![IDENTITY; document.nodes().len()];
    fn walk(node: gltf::Node, parent: &Matrix, world: &mut [Matrix]) {
        let m = multiply(parent, &bytemuck_matrix(node.transform().matrix()));
        world[node.index()] = m;
        for child in node.children() {
            walk(child, &m, world);
        }
    }
    let children: std::collections::HashSet<usize> = document
        .nodes()
        .flat_map(|n| n.children().map(|c| c.index()))
        .collect();
    for root in document.nodes().filter(|n| !children.contains(&n.index())) {
        walk(root, &IDENTITY, &mut world);
    }
    for node in document.nodes() {
        let matrices: Option<Vec<Matrix>> = node.skin().map(|skin| {
            let ibms: Vec<[[f32; 4]; 4]> = skin
                .reader(data)
                .read_inverse_bind_matrices()
                .unwrap()
                .collect();
            let name = skin.name().unwrap().to_string();
            summary
                .joints
                .entry(name)
                .or_default()
                .push(skin.joints().count());
            skin.joints()
                .zip(ibms)
                .map(|(joint, ibm)| multiply(&world[joint.index()], &bytemuck_matrix(ibm)))
                .collect()
        });
        let Some(mesh) = node.mesh() else { continue };
        for (p, primitive) in mesh.primitives().enumerate() {
            let reader = primitive.reader(data);
            let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            // Every attribute and the indices must read.
            let _ = reader.read_indices().map(|i| i.into_u32().count());
            let _ = reader.read_normals().map(Iterator::count);
            let _ = reader.read_tangents().map(Iterator::count);
            let _ = reader.read_tex_coords(0).map(|t| t.into_f32().count());
            let _ = reader.read_colors(0).map(|c| c.into_rgba_f32().count());
            let point = |v: [f32; 3]| v.map(f64::from);
            let points: Vec<[f64; 3]> =
                match (&matrices, reader.read_joints(0), reader.read_weights(0)) {
                    (Some(matrices), Some(joints), Some(weights)) => positions
                        .iter()
                        .zip(joints.into_u16().zip(weights.into_f32()))
                        .map(|(v, (j, w))| {
                            let j = j.map(usize::from);
                            skinned(point(*v), &j, &w.map(f64::from), matrices, false)
                        })
                        .collect(),
                    _ => positions
                        .iter()
                        .map(|v| {
                            let q = transform(&world[node.index()], point(*v));
                            [q[0], q[1], q[2]]
                        })
                        .collect(),
                };
            let key = (mesh.name().unwrap().to_string(), p);
            summary
                .boxes
                .entry(key)
                .or_default()
                .push(bounds(points.into_iter()));
        }
    }
    for animation in document.animations() {
        for channel in animation.channels() {
            let reader = channel.reader(data);
            let times: Vec<f32> = reader.read_inputs().unwrap().collect();
            let _ = reader.read_outputs().map(|o| match o {
                gltf::animation::util::ReadOutputs::Translations(t) => t.count(),
                gltf::animation::util::ReadOutputs::Rotations(r) => r.into_f32().count(),
                gltf::animation::util::ReadOutputs::Scales(s) => s.count(),
                gltf::animation::util::ReadOutputs::MorphTargetWeights(w) => w.into_f32().count(),
            });
            let target = channel.target();
            let path = match target.property() {
                gltf::animation::Property::Translation => "translation",
                gltf::animation::Property::Rotation => "rotation",
                gltf::animation::Property::Scale => "scale",
                gltf::animation::Property::MorphTargetWeights => "weights",
            };
            summary.channels.push((
                target.node().name().unwrap().to_string(),
                path.to_string(),
                times.len(),
                f64::from(times[0]),
                f64::from(*times.last().unwrap()),
            ));
        }
    }
    for camera in document.cameras() {
        let values = match camera.projection() {
            gltf::camera::Projection::Perspective(p) => {
                vec![
                    f64::from(p.yfov()),
                    p.aspect_ratio().map_or(-1.0, f64::from),
                    p.zfar().map_or(-1.0, f64::from),
                ]
            }
            gltf::camera::Projection::Orthographic(o) => vec![
                f64::from(o.xmag()),
                f64::from(o.ymag()),
                f64::from(o.zfar()),
            ],
        };
        summary
            .cameras
            .insert(camera.name().unwrap().to_string(), values);
    }
    for image in document.images() {
        if let Some(bytes) = images.get(&image.index()) {
            summary
                .images
                .insert(image.name().unwrap().to_string(), bytes.clone());
        }
    }
    summary
}

fn bytemuck_matrix(m: [[f32; 4]; 4]) -> Matrix {
    let mut out = [0.0; 16];
    for (c, column) in m.iter().enumerate() {
        for (r, value) in column.iter().enumerate() {
            out[c * 4 + r] = f64::from(*value);
        }
    }
    out
}

/// a ≈ b to 1e-4 relative to the larger magnitude (and to `scale` for coordinates near 0).
fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-4 * a.abs().max(b.abs()).max(scale)
}

fn assert_faithful(path: &Path, source: &Summary, output: &Summary) {
    let at = path.display();
    let scale = (source.boxes.values().flatten().flatten()).fold(1e-6_f64, |m, v| m.max(v.abs()));
    assert_eq!(
        source.boxes.keys().collect::<Vec<_>>(),
        output.boxes.keys().collect::<Vec<_>>(),
        "{at}: primitives"
    );
    for (key, boxes) in &source.boxes {
        let mut ours = boxes.clone();
        let mut theirs = output.boxes[key].clone();
        for list in [&mut ours, &mut theirs] {
            list.sort_by(|a, b| a.partial_cmp(b).unwrap());
        }
        assert_eq!(ours.len(), theirs.len(), "{at}: instances of {key:?}");
        for (a, b) in ours.iter().zip(&theirs) {
            assert!(
                a.iter().zip(b).all(|(x, y)| close(*x, *y, scale)),
                "{at}: {key:?} box {a:?} became {b:?}"
            );
        }
    }
    let mut channels = [source.channels.clone(), output.channels.clone()];
    for list in &mut channels {
        list.sort_by(|a, b| a.partial_cmp(b).unwrap());
    }
    assert_eq!(
        channels[0].len(),
        channels[1].len(),
        "{at}: animation channels"
    );
    for (a, b) in channels[0].iter().zip(&channels[1]) {
        assert!(
            a.0 == b.0 && a.1 == b.1 && a.2 == b.2 && close(a.3, b.3, 1.0) && close(a.4, b.4, 1.0),
            "{at}: channel {a:?} became {b:?}"
        );
    }
    assert_eq!(source.joints, output.joints, "{at}: joint counts");
    assert_eq!(
        source.cameras.keys().collect::<Vec<_>>(),
        output.cameras.keys().collect::<Vec<_>>(),
        "{at}: cameras"
    );
    for (name, values) in &source.cameras {
        let converted = &output.cameras[name];
        assert!(
            values
                .iter()
                .zip(converted)
                .all(|(a, b)| close(*a, *b, 1e-6)),
            "{at}: camera {name} {values:?} became {converted:?}"
        );
    }
    for (name, bytes) in &source.images {
        assert!(
            output.images.get(name) == Some(bytes),
            "{at}: image {name} changed or lost"
        );
    }
}

#[test]
fn real_gltf1_assets_upgrade_faithfully_and_load_in_gltf_rs() {
    let Some(folder) = shared("real-world/gltf1", "real-world 1.0 faithfulness") else {
        return;
    };
    let mut inputs: Vec<PathBuf> = Vec::new();
    let mut stack = vec![folder];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            match path.extension().and_then(|e| e.to_str()) {
                _ if path.is_dir() => stack.push(path),
                Some("gltf" | "glb") => inputs.push(path),
                _ => {}
            }
        }
    }
    inputs.sort();
    let mut checked = 0;
    for path in &inputs {
        let bytes = std::fs::read(path).unwrap();
        // As the CLI converts: one asset names its buffer in another letter case than its
        // file's (BoxWithoutIndices, glTF-MaterialsCommon).
        let loader = FolderResources::new(path.parent().unwrap()).repairing_letter_case();
        let upgraded = upgrade(&bytes, &loader, &UpgradeOptions::default())
            .unwrap_or_else(|e| panic!("{} refused: {e}", path.display()));
        let source = gltf1::summary(&gltf1::read(path));
        for name in ["out.glb", "out.gltf"] {
            let files = output::layout(&upgraded, name);
            let main = files.main.bytes();
            let side: BTreeMap<String, Vec<u8>> = files
                .side
                .iter()
                .map(|f| (f.name.clone(), f.bytes()))
                .collect();
            let gltf = gltf::Gltf::from_slice(&main)
                .unwrap_or_else(|e| panic!("{} → {name}: gltf-rs: {e}", path.display()));
            let buffer: Vec<u8> = match gltf.blob.clone() {
                Some(blob) => blob,
                None => gltf
                    .buffers()
                    .next()
                    .map_or_else(Vec::new, |b| match b.source() {
                        gltf::buffer::Source::Uri(uri) => side[uri].clone(),
                        gltf::buffer::Source::Bin => unreachable!("a .gltf has no BIN chunk"),
                    }),
            };
            let images: BTreeMap<usize, Vec<u8>> = gltf
                .images()
                .map(|image| {
                    let bytes = match image.source() {
                        gltf::image::Source::Uri { uri, .. } => side[uri].clone(),
                        gltf::image::Source::View { view, .. } => {
                            buffer[view.offset()..view.offset() + view.length()].to_vec()
                        }
                    };
                    (image.index(), bytes)
                })
                .collect();
            let output = gltf2_summary(&gltf.document, &buffer, &images);
            assert_faithful(&path.join(name), &source, &output);
        }
        checked += 1;
    }
    assert!(checked >= 50, "only {checked} inputs checked");
}

#[test]
fn the_pbr_drafts_hammer_upgrades_under_each_extension_name() {
    let Some(folder) = shared(
        "real-world/gltf1/fraunhofer-hammer",
        "the PBR draft's hammer",
    ) else {
        return;
    };
    // The draft's example gives the hammer its spec-gloss material in code (index.html):
    // here it is written into the asset, under each of the draft's four names.
    let mut asset: Value =
        serde_json::from_slice(&std::fs::read(folder.join("hammer.gltf")).unwrap()).unwrap();
    asset["images"]["image_specular"] = serde_json::json!({"uri": "specular.jpg"});
    let sampler = asset["textures"]["texture_diffuse"]["sampler"].clone();
    asset["textures"]["texture_specular"] = serde_json::json!({"source": "image_specular", "sampler": sampler,
        "format": 6407, "internalFormat": 6407, "target": 3553, "type": 5121});
    let scratch = tempfile::tempdir().unwrap();
    for file in ["buffer_0.bin", "diffuse.jpeg", "specular.jpg"] {
        std::fs::copy(folder.join(file), scratch.path().join(file)).unwrap();
    }
    for name in [
        "WEB3D_materials_pbr",
        "KHR_materials_pbr",
        "FRAUNHOFER_materials_pbr",
        "EXT_materials_pbr",
    ] {
        let material = &mut asset["materials"]["material_hammermat"];
        material["extensions"] = serde_json::json!({name: {"materialModel": "PBR_specular_glossiness", "values": {
            "diffuseFactor": [1, 1, 1, 1], "diffuseTexture": "texture_diffuse",
            "specularFactor": [1, 1, 1], "glossinessFactor": 0.6,
            "specularGlossinessTexture": "texture_specular"}}});
        let path = scratch.path().join(format!("{name}.gltf"));
        std::fs::write(&path, serde_json::to_vec(&asset).unwrap()).unwrap();
        let upgraded = upgrade(
            std::fs::read(&path).unwrap(),
            &FolderResources::new(scratch.path()),
            &UpgradeOptions::default(),
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        for container in ["out.glb", "out.gltf"] {
            let report = output::verify(&output::layout(&upgraded, container));
            assert!(
                !report.has_errors(),
                "{name} → {container}: {:?}",
                report.diagnostics
            );
        }
        let material = &upgraded.json.to_value()["materials"][0];
        assert!(
            material["extensions"]["KHR_materials_specular"]["specularColorTexture"].is_object(),
            "{name}: {material}"
        );
        let glb = upgraded.to_glb();
        assert!(
            gltf::Gltf::from_slice(&glb).is_ok(),
            "{name}: gltf-rs loads it"
        );
    }
}
