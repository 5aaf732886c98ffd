//! Rebuilding every 1.0 object in 2.0 form: ids become indices (the id becomes the name when
//! there is none), data is repacked, nodes, skins, animations and cameras are fixed up.

use super::binary::Binary;
use super::data::{self, Role};
use super::source::Source;
use super::{materials, EncodedImage, Note, NoteKind, UpgradeError, UpgradeOptions, Upgraded};
use crate::document::image_header;
use crate::gltf::gl::{self, ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER};
use serde_json::{json, Map, Value};
use std::collections::HashMap;

const IDENTITY: [f64; 16] = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

/// Dictionaries whose objects map one-to-one onto 2.0 arrays, in output order.
const MAPPED: &[&str] = &[
    "samplers",
    "images",
    "textures",
    "materials",
    "meshes",
    "cameras",
    "nodes",
    "animations",
    "scenes",
];

pub struct Builder<'s, 'a> {
    pub source: &'s Source<'a>,
    pub options: &'s UpgradeOptions,
    index: HashMap<(&'static str, String), usize>,
    arrays: HashMap<&'static str, Vec<Value>>,
    pub images: Vec<EncodedImage>,
    binary: Binary,
    packed_accessors: HashMap<(String, Role), usize>,
    pub report: Vec<Note>,
}

/// `/collection/id` with the id escaped as a JSON pointer token.
pub fn pointer(collection: &str, id: &str) -> String {
    format!("/{collection}/{}", crate::document::json::escape_token(id))
}

fn id_list(value: Option<&Value>) -> Vec<String> {
    value
        .and_then(Value::as_array)
        .map(|a| {
            a.iter()
                .filter_map(Value::as_str)
                .map(str::to_string)
                .collect()
        })
        .unwrap_or_default()
}

impl<'s, 'a> Builder<'s, 'a> {
    pub fn new(source: &'s Source<'a>, options: &'s UpgradeOptions) -> Self {
        let mut index = HashMap::new();
        for collection in MAPPED {
            for (i, (id, _)) in source.dictionary(collection).into_iter().enumerate() {
                index.insert((*collection, id.to_string()), i);
            }
        }
        Builder {
            source,
            options,
            index,
            arrays: HashMap::new(),
            images: Vec::new(),
            // Repacked data is about the size of the input buffers: reserve it once.
            binary: Binary::default(),
            packed_accessors: HashMap::new(),
            report: Vec::new(),
        }
    }

    pub fn note(&mut self, pointer: impl Into<String>, kind: NoteKind, text: impl Into<String>) {
        self.report.push(Note {
            pointer: pointer.into(),
            kind,
            text: text.into(),
        });
    }

    /// The 2.0 index of a 1.0 id in a mapped collection.
    pub fn index_of(&self, collection: &'static str, id: Option<&Value>) -> Option<usize> {
        let id = id?.as_str()?;
        self.index.get(&(collection, id.to_string())).copied()
    }

    fn push(&mut self, collection: &'static str, value: Value) -> usize {
        let array = self.arrays.entry(collection).or_default();
        array.push(value);
        array.len() - 1
    }

    pub fn run(&mut self) -> Result<(), UpgradeError> {
        self.samplers();
        self.images()?;
        self.textures();
        for (id, material) in self.source.dictionary("materials") {
            let converted = materials::convert(self, id, material)?;
            self.push("materials", converted);
        }
        self.meshes()?;
        self.cameras();
        self.nodes()?;
        self.animations()?;
        self.scenes();
        self.dropped_collections();
        Ok(())
    }

    fn named(id: &str, object: &Value) -> Map<String, Value> {
        let mut out = Map::new();
        let name = object.get("name").and_then(Value::as_str).unwrap_or(id);
        out.insert("name".into(), json!(name));
        if let Some(extras) = object.get("extras") {
            out.insert("extras".into(), extras.clone());
        }
        out
    }

    fn samplers(&mut self) {
        let samplers = self.source.dictionary("samplers");
        for (id, sampler) in &samplers {
            let mut out = Self::named(id, sampler);
            // 1.0 defaults, written out: 2.0 leaves missing filters to the implementation.
            for (key, default) in [
                ("magFilter", gl::LINEAR),
                ("minFilter", gl::NEAREST_MIPMAP_LINEAR),
                ("wrapS", gl::REPEAT),
                ("wrapT", gl::REPEAT),
            ] {
                let value = sampler.get(key).and_then(Value::as_u64).unwrap_or(default);
                out.insert(key.into(), json!(value));
            }
            self.push("samplers", Value::Object(out));
        }
        if !samplers.is_empty() {
            self.note(
                "/samplers",
                NoteKind::Decision,
                "1.0 sampler defaults (LINEAR / NEAREST_MIPMAP_LINEAR / REPEAT) written out explicitly.",
            );
        }
    }

    fn images(&mut self) -> Result<(), UpgradeError> {
        for (id, image) in self.source.dictionary("images") {
            let at = pointer("images", id);
            let bytes =
                self.source
                    .image_bytes(image)
                    .map_err(|reason| UpgradeError::Resource {
                        pointer: at.clone(),
                        reason,
                    })?;
            let format = image_header::read(&bytes).map_err(|e| UpgradeError::Resource {
                pointer: at.clone(),
                reason: format!("not a readable image ({e:?})"),
            })?;
            let mime_type = format.format.mime_type().to_string();
            self.add_image(Self::named(id, image), bytes, mime_type, id);
        }
        Ok(())
    }

    /// Adds an image (and returns its index); `stem` names its file in `.gltf` output.
    pub fn add_image(
        &mut self,
        json: Map<String, Value>,
        bytes: Vec<u8>,
        mime_type: String,
        stem: &str,
    ) -> usize {
        let extension = mime_type
            .rsplit('/')
            .next()
            .unwrap_or("bin")
            .replace("jpeg", "jpg");
        let safe: String = stem
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let file_name = format!("{}-{safe}.{extension}", self.images.len());
        self.images.push(EncodedImage {
            bytes,
            mime_type,
            file_name,
        });
        self.push("images", Value::Object(json))
    }

    fn textures(&mut self) {
        for (id, texture) in self.source.dictionary("textures") {
            let mut out = Self::named(id, texture);
            if let Some(i) = self.index_of("samplers", texture.get("sampler")) {
                out.insert("sampler".into(), json!(i));
            }
            if let Some(i) = self.index_of("images", texture.get("source")) {
                out.insert("source".into(), json!(i));
            }
            let format = texture
                .get("format")
                .and_then(Value::as_u64)
                .unwrap_or(6408);
            if !matches!(format, 6407 | 6408) {
                self.note(
                    pointer("textures", id),
                    NoteKind::Dropped,
                    format!("texture format {format} (ALPHA/LUMINANCE) has no 2.0 equivalent; the image is sampled as stored."),
                );
            }
            self.push("textures", Value::Object(out));
        }
    }

    /// A texture reading `image` with the sampler of 1.0 texture `like` (for rebaked images).
    pub fn add_texture(&mut self, image: usize, like: Option<usize>, name: String) -> usize {
        let mut out = Map::new();
        out.insert("name".into(), json!(name));
        let sampler =
            like.and_then(|t| self.arrays.get("textures")?.get(t)?.get("sampler").cloned());
        if let Some(sampler) = sampler {
            out.insert("sampler".into(), sampler);
        }
        out.insert("source".into(), json!(image));
        self.push("textures", Value::Object(out))
    }

    /// The image a 2.0 texture reads.
    pub fn texture_image(&self, texture: usize) -> Option<&EncodedImage> {
        let source = self
            .arrays
            .get("textures")?
            .get(texture)?
            .get("source")?
            .as_u64()?;
        self.images.get(source as usize)
    }

    /// Repacks a 1.0 accessor for a role (once per role) and returns its 2.0 index.
    fn accessor(&mut self, id: &str, role: Role) -> Result<usize, UpgradeError> {
        if let Some(&i) = self.packed_accessors.get(&(id.to_string(), role)) {
            return Ok(i);
        }
        let at = pointer("accessors", id);
        let input = data::read(self.source, id).map_err(|reason| UpgradeError::Resource {
            pointer: at.clone(),
            reason,
        })?;
        let packed = data::pack(&input, role, &mut self.binary);
        if let Some(from) = packed.converted_from {
            self.note(
                &at,
                NoteKind::Decision,
                format!(
                    "componentType {from} → {} as glTF 2.0 requires for {role:?}.",
                    packed.component_type
                ),
            );
        }
        let (kind, count) = (input.kind.clone(), input.count);
        let index = self.add_accessor(packed, &kind, count, role, Some(id));
        self.packed_accessors.insert((id.to_string(), role), index);
        Ok(index)
    }

    /// Adds packed data (already in the binary) as one bufferView and one accessor.
    fn add_accessor(
        &mut self,
        packed: data::Packed,
        kind: &str,
        count: usize,
        role: Role,
        name: Option<&str>,
    ) -> usize {
        let mut view =
            json!({"buffer": 0, "byteOffset": packed.offset, "byteLength": packed.length});
        match role {
            Role::Indices => view["target"] = json!(ELEMENT_ARRAY_BUFFER),
            Role::Data => {}
            _ => view["target"] = json!(ARRAY_BUFFER),
        }
        if let Some(stride) = packed.byte_stride {
            view["byteStride"] = json!(stride);
        }
        let view_index = self.push("bufferViews", view);
        let mut accessor = json!({
            "bufferView": view_index,
            "componentType": packed.component_type,
            "count": count,
            "type": kind,
        });
        if let Some(name) = name {
            accessor["name"] = json!(name);
        }
        if packed.normalized {
            accessor["normalized"] = json!(true);
        }
        if !packed.min.is_empty() {
            accessor["min"] = json!(packed.min);
            accessor["max"] = json!(packed.max);
        }
        self.push("accessors", accessor)
    }

    fn meshes(&mut self) -> Result<(), UpgradeError> {
        for (id, mesh) in self.source.dictionary("meshes") {
            let mut out = Self::named(id, mesh);
            let mut primitives = Vec::new();
            let list = mesh.get("primitives").and_then(Value::as_array);
            for (p, primitive) in list.into_iter().flatten().enumerate() {
                let at = format!("{}/primitives/{p}", pointer("meshes", id));
                primitives.push(self.primitive(primitive, &at)?);
            }
            out.insert("primitives".into(), json!(primitives));
            self.push("meshes", Value::Object(out));
        }
        Ok(())
    }

    fn primitive(&mut self, primitive: &Value, at: &str) -> Result<Value, UpgradeError> {
        let mut attributes = Map::new();
        let source_attributes = primitive.get("attributes").and_then(Value::as_object);
        for (semantic, accessor) in source_attributes.into_iter().flatten() {
            let Some(accessor) = accessor.as_str() else {
                continue;
            };
            let renamed = rename_semantic(semantic);
            if renamed != *semantic {
                self.note(
                    format!("{at}/attributes/{semantic}"),
                    NoteKind::Decision,
                    format!("attribute {semantic} renamed {renamed}."),
                );
            }
            let index = self.accessor(accessor, Role::of_semantic(&renamed))?;
            attributes.insert(renamed, json!(index));
        }
        let mut out = Map::new();
        out.insert("attributes".into(), Value::Object(attributes));
        if let Some(indices) = primitive.get("indices").and_then(Value::as_str) {
            out.insert(
                "indices".into(),
                json!(self.accessor(indices, Role::Indices)?),
            );
        }
        if let Some(m) = self.index_of("materials", primitive.get("material")) {
            out.insert("material".into(), json!(m));
        }
        if let Some(mode) = primitive.get("mode") {
            out.insert("mode".into(), mode.clone());
        }
        Ok(Value::Object(out))
    }

    fn cameras(&mut self) {
        for (id, camera) in self.source.dictionary("cameras") {
            let mut out = Self::named(id, camera);
            let kind = camera
                .get("type")
                .and_then(Value::as_str)
                .unwrap_or("perspective");
            out.insert("type".into(), json!(kind));
            let mut projection = camera.get(kind).cloned().unwrap_or_else(|| json!({}));
            if kind == "perspective" {
                self.fix_perspective(&mut projection, id);
            }
            out.insert(kind.into(), projection);
            self.push("cameras", Value::Object(out));
        }
    }

    /// 2.0 needs znear > 0, yfov > 0 and (when given) aspectRatio > 0.
    fn fix_perspective(&mut self, projection: &mut Value, id: &str) {
        let at = pointer("cameras", id);
        let get = |projection: &Value, key: &str| projection.get(key).and_then(Value::as_f64);
        if get(projection, "aspectRatio").is_some_and(|a| a <= 0.0) {
            projection.as_object_mut().map(|p| p.remove("aspectRatio"));
            self.note(
                &at,
                NoteKind::Dropped,
                "aspectRatio 0 removed (the viewport's ratio is used).",
            );
        }
        if get(projection, "yfov").is_none_or(|y| y <= 0.0) {
            projection["yfov"] = json!(1.0);
            self.note(
                &at,
                NoteKind::Decision,
                "yfov 0 or missing set to 1.0 radian.",
            );
        }
        if get(projection, "znear").is_none_or(|z| z <= 0.0) {
            let znear = get(projection, "zfar").map_or(0.01, |far| (far * 1e-4).max(1e-6));
            projection["znear"] = json!(znear);
            self.note(
                &at,
                NoteKind::Decision,
                format!("znear 0 is invalid in 2.0; set to {znear} (zfar / 10000, or 0.01)."),
            );
        }
    }

    fn nodes(&mut self) -> Result<(), UpgradeError> {
        let nodes = self.source.dictionary("nodes");
        let mut extra_nodes = Vec::new();
        let mut outputs = Vec::new();
        for (id, node) in &nodes {
            let mut out = Self::named(id, node);
            let mut children: Vec<Value> = id_list(node.get("children"))
                .iter()
                .filter_map(|c| self.index_of("nodes", Some(&json!(c))))
                .map(|i| json!(i))
                .collect();
            copy_transform(node, &mut out);
            if let Some(camera) = self.index_of("cameras", node.get("camera")) {
                out.insert("camera".into(), json!(camera));
            }
            let skin = self.skin_instance(id, node)?;
            let meshes: Vec<usize> = id_list(node.get("meshes"))
                .iter()
                .filter_map(|m| self.index_of("meshes", Some(&json!(m))))
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
                if let Some(skin) = skin {
                    child["skin"] = json!(skin);
                }
                children.push(json!(nodes.len() + extra_nodes.len()));
                extra_nodes.push(child);
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
            if node
                .get("extensions")
                .and_then(|e| e.get("KHR_materials_common"))
                .is_some()
            {
                self.note(
                    pointer("nodes", id),
                    NoteKind::Dropped,
                    "KHR_materials_common light dropped (no light conversion).",
                );
            }
            outputs.push(Value::Object(out));
        }
        for node in outputs.into_iter().chain(extra_nodes) {
            self.push("nodes", node);
        }
        Ok(())
    }

    /// The 2.0 skin for a node instancing a 1.0 skin with its `skeletons` (one 2.0 skin per
    /// instance, as 2.0 joints are absolute node indices).
    fn skin_instance(&mut self, id: &str, node: &Value) -> Result<Option<usize>, UpgradeError> {
        let Some(skin_id) = node.get("skin").and_then(Value::as_str) else {
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
        let joints: Vec<usize> = id_list(skin.get("jointNames"))
            .iter()
            .filter_map(|name| self.find_joint(name, &skeletons))
            .collect();
        let mut out = Self::named(skin_id, skin);
        out.insert("joints".into(), json!(joints));
        if let Some(root) = skeletons
            .first()
            .and_then(|s| self.index_of("nodes", Some(&json!(s))))
        {
            out.insert("skeleton".into(), json!(root));
        }
        let matrices = self.inverse_bind_matrices(skin_id, skin, joints.len())?;
        out.insert("inverseBindMatrices".into(), json!(matrices));
        Ok(Some(self.push("skins", Value::Object(out))))
    }

    /// The node whose `jointName` is `name`, searched in the skeleton subtrees (1.0 scopes
    /// joint names by them), or among all nodes when the instance names no skeleton.
    fn find_joint(&self, name: &str, skeletons: &[String]) -> Option<usize> {
        let mut stack: Vec<String> = if skeletons.is_empty() {
            self.source
                .dictionary("nodes")
                .iter()
                .map(|(id, _)| id.to_string())
                .collect()
        } else {
            skeletons.to_vec()
        };
        let mut seen = std::collections::HashSet::new();
        while let Some(id) = stack.pop() {
            if !seen.insert(id.clone()) {
                continue;
            }
            let node = self.source.object("nodes", &id)?;
            if node.get("jointName").and_then(Value::as_str) == Some(name) {
                return self.index_of("nodes", Some(&json!(id)));
            }
            stack.extend(id_list(node.get("children")));
        }
        None
    }

    /// Inverse bind matrices with the bind shape matrix folded in: IBMᵢ · BSM, so that the
    /// 2.0 skinning (which has no bind shape matrix) deforms the vertices the same way.
    fn inverse_bind_matrices(
        &mut self,
        skin_id: &str,
        skin: &Value,
        joints: usize,
    ) -> Result<usize, UpgradeError> {
        let bind_shape = matrix(skin.get("bindShapeMatrix")).unwrap_or(IDENTITY);
        let source_matrices = match skin.get("inverseBindMatrices").and_then(Value::as_str) {
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
        Ok(self.add_accessor(packed, "MAT4", count, Role::Data, Some(skin_id)))
    }

    fn animations(&mut self) -> Result<(), UpgradeError> {
        for (id, animation) in self.source.dictionary("animations") {
            let at = pointer("animations", id);
            let mut out = Self::named(id, animation);
            let parameters = animation.get("parameters");
            let mut sampler_index = HashMap::new();
            let mut samplers = Vec::new();
            let source_samplers = animation.get("samplers").and_then(Value::as_object);
            for (sampler_id, sampler) in source_samplers.into_iter().flatten() {
                let accessor_of = |key: &str| {
                    let parameter = sampler.get(key).and_then(Value::as_str)?;
                    parameters?.get(parameter)?.as_str().map(str::to_string)
                };
                let (Some(input), Some(output)) = (accessor_of("input"), accessor_of("output"))
                else {
                    self.note(
                        format!("{at}/samplers/{sampler_id}"),
                        NoteKind::Dropped,
                        "sampler whose parameters do not resolve dropped.",
                    );
                    continue;
                };
                let interpolation = sampler
                    .get("interpolation")
                    .cloned()
                    .unwrap_or(json!("LINEAR"));
                let (input, output) = (
                    self.accessor(&input, Role::Data)?,
                    self.accessor(&output, Role::Data)?,
                );
                sampler_index.insert(sampler_id.clone(), samplers.len());
                samplers.push(
                    json!({"input": input, "output": output, "interpolation": interpolation}),
                );
            }
            let mut channels = Vec::new();
            for channel in animation
                .get("channels")
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
            {
                let sampler = channel
                    .get("sampler")
                    .and_then(Value::as_str)
                    .and_then(|s| sampler_index.get(s));
                let target = channel.get("target");
                let node = self.index_of("nodes", target.and_then(|t| t.get("id")));
                let path = target.and_then(|t| t.get("path")).cloned();
                match (sampler, node, path) {
                    (Some(s), Some(n), Some(p)) => {
                        channels.push(json!({"sampler": s, "target": {"node": n, "path": p}}))
                    }
                    _ => self.note(
                        &at,
                        NoteKind::Dropped,
                        "channel with an unresolved sampler or target dropped.",
                    ),
                }
            }
            out.insert("samplers".into(), json!(samplers));
            out.insert("channels".into(), json!(channels));
            self.push("animations", Value::Object(out));
        }
        Ok(())
    }

    fn scenes(&mut self) {
        for (id, scene) in self.source.dictionary("scenes") {
            let mut out = Self::named(id, scene);
            let nodes: Vec<usize> = id_list(scene.get("nodes"))
                .iter()
                .filter_map(|n| self.index_of("nodes", Some(&json!(n))))
                .collect();
            out.insert("nodes".into(), json!(nodes));
            self.push("scenes", Value::Object(out));
        }
    }

    fn dropped_collections(&mut self) {
        for collection in ["techniques", "programs", "shaders"] {
            let count = self.source.dictionary(collection).len();
            if count > 0 {
                self.note(
                    format!("/{collection}"),
                    NoteKind::Dropped,
                    format!("{count} {collection} dropped: glTF 2.0 materials are not shader programs (their files were not read)."),
                );
            }
        }
    }

    pub fn finish(mut self) -> Upgraded {
        let mut root = Map::new();
        let source_asset = self.source.json.get("asset");
        let mut asset = json!({"version": "2.0", "generator": concat!("gltfmat ", env!("CARGO_PKG_VERSION"), " upgrade")});
        if let Some(copyright) = source_asset.and_then(|a| a.get("copyright")) {
            asset["copyright"] = copyright.clone();
        }
        root.insert("asset".into(), asset);
        let used =
            materials::extensions_used(self.arrays.get("materials").map_or(&[][..], Vec::as_slice));
        if !used.is_empty() {
            root.insert("extensionsUsed".into(), json!(used));
        }
        if let Some(scene) = self.index_of("scenes", self.source.json.get("scene")) {
            root.insert("scene".into(), json!(scene));
        }
        if !self.binary.is_empty() {
            self.push("buffers", json!({"byteLength": self.binary.len()}));
        }
        for collection in [
            "scenes",
            "nodes",
            "meshes",
            "materials",
            "textures",
            "images",
            "samplers",
            "skins",
            "animations",
            "cameras",
            "accessors",
            "bufferViews",
            "buffers",
        ] {
            if let Some(items) = self.arrays.remove(collection).filter(|a| !a.is_empty()) {
                root.insert(collection.into(), Value::Array(items));
            }
        }
        Upgraded {
            json: Value::Object(root),
            binary: self.binary,
            images: self.images,
            report: self.report,
        }
    }
}

/// 1.0 attribute semantics → 2.0: TEXCOORD → TEXCOORD_0, COLOR → COLOR_0, JOINT(_n) →
/// JOINTS_n, WEIGHT(_n) → WEIGHTS_n; unknown semantics get the `_` application prefix.
fn rename_semantic(semantic: &str) -> String {
    let (base, set) = match semantic.split_once('_') {
        Some((b, s)) if s.chars().all(|c| c.is_ascii_digit()) && !s.is_empty() => (b, s),
        _ => (semantic, "0"),
    };
    match base {
        "POSITION" | "NORMAL" | "TANGENT" if semantic == base => semantic.to_string(),
        "TEXCOORD" | "COLOR" => format!("{base}_{set}"),
        "JOINT" | "JOINTS" => format!("JOINTS_{set}"),
        "WEIGHT" | "WEIGHTS" => format!("WEIGHTS_{set}"),
        _ if semantic.starts_with('_') => semantic.to_string(),
        _ => format!("_{semantic}"),
    }
}

fn matrix(value: Option<&Value>) -> Option<[f64; 16]> {
    let list = value?.as_array()?;
    let mut m = [0.0; 16];
    if list.len() != 16 {
        return None;
    }
    for (slot, v) in m.iter_mut().zip(list) {
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

/// matrix or translation/rotation/scale; an identity matrix is left out.
fn copy_transform(node: &Value, out: &mut Map<String, Value>) {
    match matrix(node.get("matrix")) {
        Some(m) if m != IDENTITY => {
            out.insert("matrix".into(), json!(m));
        }
        _ => {
            for key in ["translation", "rotation", "scale"] {
                if let Some(v) = node.get(key) {
                    out.insert(key.into(), v.clone());
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn semantics_are_renamed_as_2_0_requires() {
        for (old, new) in [
            ("TEXCOORD", "TEXCOORD_0"),
            ("TEXCOORD_1", "TEXCOORD_1"),
            ("COLOR", "COLOR_0"),
            ("JOINT", "JOINTS_0"),
            ("WEIGHT", "WEIGHTS_0"),
            ("POSITION", "POSITION"),
            ("BATCHID", "_BATCHID"),
        ] {
            assert_eq!(rename_semantic(old), new);
        }
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
