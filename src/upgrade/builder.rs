//! The 2.0 asset under construction, shared by every conversion step in `convert/`: 1.0 ids
//! become indices (the id becomes the name when there is none), collections are appended to,
//! data is repacked into one binary, and every decision is noted.

use super::binary::Binary;
use super::data::{self, Role};
use super::json::{Items, Json};
use super::origins::Origins;
use super::{EncodedImage, NoteKind, Notes, UpgradeError, UpgradeOptions, Upgraded};
use crate::document::Node;
use crate::gltf::gl::{ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER};
use crate::legacy::source::Source;
use serde_json::{json, Map, Value};
use std::collections::HashMap;

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

/// The 2.0 asset under construction: collections by name, the 1.0 id → 2.0 index maps, the
/// output binary and the conversion report.
pub(super) struct Builder<'s, 'a> {
    pub(in crate::upgrade) source: &'s Source<'a>,
    pub(in crate::upgrade) options: &'s UpgradeOptions,
    pub(in crate::upgrade) arrays: HashMap<&'static str, Items>,
    /// The bufferView each accessor was written with (its origin is the view's too).
    accessor_views: Vec<usize>,
    pub(in crate::upgrade) images: Vec<EncodedImage>,
    pub(in crate::upgrade) binary: Binary,
    pub(in crate::upgrade) packed_accessors: HashMap<(&'s str, Role), usize>,
    /// JOINT/WEIGHT accessor pairs with repeated joints merged, by their 1.0 ids: primitives
    /// sharing a pair share the merged one.
    pub(in crate::upgrade) merged_influences: HashMap<(&'s str, &'s str), Option<(usize, usize)>>,
    /// Data repacked so far, with its bufferView, by what makes it the same.
    repacked: HashMap<SameData, (data::Packed, usize)>,
    pub(in crate::upgrade) report: Notes,
    /// `/collection/index` of the output → the 1.0 object it was made from.
    pub(in crate::upgrade) origins: Origins,
    /// 1.0 light id → its KHR_lights_punctual index (None: it has no 2.0 form).
    pub(in crate::upgrade) lights: HashMap<String, Option<usize>>,
    /// The factor fits of spec-gloss materials made so far.
    pub(in crate::upgrade) fits: super::fit::Fits,
    /// The per-texel fits of textured spec-gloss materials made so far.
    pub(in crate::upgrade) texel_fits: super::fit::TexelFits,
    /// The spec-gloss rebakes made so far, by what they were made from.
    pub(in crate::upgrade) rebakes: super::spec_gloss::Rebakes,
    /// The textures rebakes were added as, by their PNG and the 1.0 texture they are
    /// sampled like: an image rebaked alike for several materials is written once.
    pub(in crate::upgrade) rebaked: HashMap<(Vec<u8>, Option<String>), usize>,
    /// Dictionary places, ascending, of the 1.0 meshes left out as drawing nothing.
    pub(in crate::upgrade) dropped_meshes: Vec<usize>,
}

/// How much the converted binary may outgrow the data read: `.0` times it plus `.1` bytes.
/// Conversion legitimately grows data up to fourfold (8-bit texture coordinates and
/// quantized 8-bit attributes become floats), and one accessor may serve two roles.
const GROWTH_BOUND: (usize, usize) = (8, 64 << 20);

/// What makes two accessors' repacked data the same: the same bytes (by where they lie in
/// the loaded input, whichever view names them), read the same way, for the same role and
/// decoded alike.
#[derive(PartialEq, Eq, Hash)]
struct SameData {
    place: (usize, usize, usize),
    count: usize,
    component_type: u64,
    kind: String,
    role: Role,
    quantization: Option<String>,
}

impl SameData {
    fn of(input: &data::Accessor, role: Role, quantization: Option<Node>) -> Self {
        SameData {
            place: input.place(),
            count: input.count,
            component_type: input.component_type,
            kind: input.kind.clone(),
            role,
            quantization: quantization.map(|q| q.to_string()),
        }
    }
}

/// `/collection/id` with the id escaped as a JSON pointer token.
pub(super) fn pointer(collection: &str, id: &str) -> String {
    format!("/{collection}/{}", crate::document::json::escape_token(id))
}

/// A 1.0 list of ids.
pub(super) fn id_list(value: Option<Node>) -> Vec<String> {
    (value.and_then(Node::as_array).into_iter())
        .flat_map(|a| a.iter())
        .filter_map(Node::as_str)
        .map(str::to_string)
        .collect()
}

impl<'s, 'a> Builder<'s, 'a> {
    pub(super) fn new(source: &'s Source<'a>, options: &'s UpgradeOptions) -> Self {
        Builder {
            source,
            options,
            arrays: HashMap::new(),
            accessor_views: Vec::new(),
            images: Vec::new(),
            binary: Binary::default(),
            packed_accessors: HashMap::new(),
            merged_influences: HashMap::new(),
            repacked: HashMap::new(),
            report: Notes::default(),
            lights: HashMap::new(),
            fits: super::fit::Fits::new(options.draft_reading),
            texel_fits: super::fit::TexelFits::new(options.draft_reading),
            rebakes: Default::default(),
            rebaked: HashMap::new(),
            origins: Origins::default(),
            dropped_meshes: Vec::new(),
        }
    }

    pub(super) fn note(
        &mut self,
        pointer: impl Into<String>,
        kind: NoteKind,
        text: impl Into<String>,
    ) {
        self.report.push(pointer.into(), kind, text.into());
    }

    /// The 2.0 index of a 1.0 id in a mapped collection.
    pub(super) fn index_of(&self, collection: &'static str, id: Option<Node>) -> Option<usize> {
        self.index_of_id(collection, id?.as_str()?)
    }

    /// [`Builder::index_of`] for an id at hand: the id's place in its dictionary, which
    /// is where the step made its object (the source tree finds it without a map of ids).
    pub(super) fn index_of_id(&self, collection: &'static str, id: &str) -> Option<usize> {
        debug_assert!(MAPPED.contains(&collection));
        let dictionary = self.source.root().get(collection)?.as_object()?;
        dictionary.position(id)
    }

    pub(in crate::upgrade) fn push(&mut self, collection: &'static str, value: Value) -> usize {
        self.arrays.entry(collection).or_default().push(&value)
    }

    /// [`Builder::push`], remembering the 1.0 object the value was made from.
    pub(in crate::upgrade) fn push_from(
        &mut self,
        collection: &'static str,
        value: Value,
        origin: String,
    ) -> usize {
        let index = self.push(collection, value);
        self.record_origin(collection, index, origin);
        index
    }

    pub(in crate::upgrade) fn record_origin(
        &mut self,
        collection: &'static str,
        index: usize,
        origin: String,
    ) {
        // An accessor's bufferView is its own: it comes from the same 1.0 accessor.
        let view = (collection == "accessors")
            .then(|| self.accessor_views.get(index))
            .flatten();
        if let Some(&view) = view {
            self.origins.record("bufferViews", view, &origin);
        }
        self.origins.record(collection, index, &origin);
    }

    pub(in crate::upgrade) fn named(id: &str, object: Node) -> Map<String, Value> {
        let mut out = Map::new();
        let name = object.get("name").and_then(Node::as_str).unwrap_or(id);
        out.insert("name".into(), json!(name));
        if let Some(extras) = object.get("extras") {
            out.insert("extras".into(), extras.to_value());
        }
        out
    }

    /// Adds an image (and returns its index); `stem` names its file in `.gltf` output.
    pub(super) fn add_image(
        &mut self,
        json: Map<String, Value>,
        bytes: impl Into<std::sync::Arc<crate::document::Bytes>>,
        mime_type: String,
        stem: &str,
    ) -> usize {
        let image = EncodedImage::new(bytes, mime_type, self.images.len(), stem, false);
        self.images.push(image);
        self.push("images", Value::Object(json))
    }

    /// A texture reading `image` with the sampler of 1.0 texture `like` (for rebaked images).
    pub(super) fn add_texture(&mut self, image: usize, like: Option<usize>, name: String) -> usize {
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
    pub(super) fn texture_image(&self, texture: usize) -> Option<&EncodedImage> {
        let source = self
            .arrays
            .get("textures")?
            .get(texture)?
            .get("source")?
            .as_u64()?;
        self.images.get(source as usize)
    }

    /// Repacks a 1.0 accessor for a role (once per role) and returns its 2.0 index. An
    /// accessor reading the same bytes the same way as one repacked before (aliases of one
    /// view) gets its own 2.0 accessor over that one's bufferView: a stranger's 10^3 aliases
    /// of a 1 MB view must not become a 1 GB output.
    pub(in crate::upgrade) fn accessor(
        &mut self,
        id: &'s str,
        role: Role,
    ) -> Result<usize, UpgradeError> {
        if let Some(&i) = self.packed_accessors.get(&(id, role)) {
            return Ok(i);
        }
        let at = pointer("accessors", id);
        let input = data::read(self.source, id).map_err(|reason| UpgradeError::Resource {
            pointer: at.clone(),
            reason,
        })?;
        let quantization = (self.source.object("accessors", id))
            .and_then(|a| a.get("extensions"))
            .and_then(|e| e.get("WEB3D_quantized_attributes"));
        let same = SameData::of(&input, role, quantization);
        let (packed, view) = match self.repacked.get(&same) {
            Some((packed, view)) => (packed.clone(), Some(*view)),
            None => (self.repack(&input, role, quantization, &at)?, None),
        };
        let octahedral = data::is_octahedral(&input, role);
        let (kind, components) = match octahedral {
            true => ("VEC3".to_string(), 3),
            false => (input.kind.clone(), input.components),
        };
        if let (Some(view), true) = (view, role.is_vertex()) {
            self.declare_stride(view, &packed, components);
        }
        if octahedral {
            self.note(
                &at,
                NoteKind::Decision,
                format!(
                    "NORMAL of two {} components read as an octahedron encoding (Cesium's 3D Tiles convention: the only one for two-component normals) and decoded to the unit float VEC3 glTF 2.0 requires.",
                    match input.component_type {
                        crate::gltf::gl::BYTE | crate::gltf::gl::SHORT => "signed",
                        _ => "unsigned",
                    }
                ),
            );
        }
        if quantization.is_some() {
            self.note(
                &at,
                NoteKind::Decision,
                "WEB3D_quantized_attributes decoded with its decodeMatrix to floats (glTF 2.0 core has no decode matrix).",
            );
        }
        if let Some(from) = packed.converted_from.filter(|_| !octahedral) {
            self.note(
                &at,
                NoteKind::Decision,
                format!(
                    "componentType {from} → {} as glTF 2.0 requires for {role:?}.",
                    packed.component_type
                ),
            );
        }
        if let Some(changed) = packed.renormalised {
            self.note(
                &at,
                NoteKind::Decision,
                format!(
                    "skin weights renormalised: {} of {} vertices' weights did not sum to 1 (lowest sum {:.3}); each was divided by its sum, which draws what the 1.0 shaders drew (their perspective divide removed the same factor).",
                    changed.vertices, input.count, changed.lowest
                ),
            );
        }
        let count = input.count;
        let view = view.unwrap_or_else(|| self.add_view(&packed, role));
        self.repacked
            .entry(same)
            .or_insert_with(|| (packed.clone(), view));
        let index = self.add_accessor_over(view, packed, &kind, count, Some(id));
        self.record_origin("accessors", index, at);
        self.packed_accessors.insert((id, role), index);
        Ok(index)
    }

    /// Appends an accessor's data to the binary, repacked for `role` (decoded first when it
    /// is quantized); refused once the binary outgrows what the input can legitimately
    /// become (see [`GROWTH_BOUND`]).
    fn repack(
        &mut self,
        input: &data::Accessor,
        role: Role,
        quantization: Option<Node>,
        at: &str,
    ) -> Result<data::Packed, UpgradeError> {
        if let Some(decoded) = data::oct_decoded(input, role) {
            let mut packed =
                data::pack_values(&decoded, 3, data::FLOAT, false, true, &mut self.binary);
            packed.converted_from = Some(input.component_type);
            return Ok(packed);
        }
        let packed = match data::dequantized(input, quantization) {
            None => data::pack(input, role, &mut self.binary),
            Some(decoded) => {
                let decoded = decoded.map_err(|reason| UpgradeError::Invalid {
                    pointer: format!("{at}/extensions/WEB3D_quantized_attributes"),
                    reason,
                })?;
                let mut packed = data::pack_values(
                    &decoded,
                    input.components,
                    data::FLOAT,
                    false,
                    role.is_vertex(),
                    &mut self.binary,
                );
                packed.converted_from = Some(input.component_type);
                packed
            }
        };
        let read = self.source.loaded_bytes();
        let bound = GROWTH_BOUND.0 * read + GROWTH_BOUND.1;
        if self.binary.len() > bound {
            return Err(UpgradeError::Invalid {
                pointer: at.to_string(),
                reason: format!("the converted data has grown to {} bytes, more than {} times the {read} bytes of data read (plus {} MiB): accessors over overlapping parts of the same data repeat it; refused rather than written", self.binary.len(), GROWTH_BOUND.0, GROWTH_BOUND.1 >> 20),
            });
        }
        Ok(packed)
    }

    /// Adds packed data (already in the binary) as one bufferView and one accessor.
    pub(in crate::upgrade) fn add_accessor(
        &mut self,
        packed: data::Packed,
        kind: &str,
        count: usize,
        role: Role,
        name: Option<&str>,
    ) -> usize {
        let view = self.add_view(&packed, role);
        self.add_accessor_over(view, packed, kind, count, name)
    }

    /// Adds the bufferView of packed data (already in the binary).
    fn add_view(&mut self, packed: &data::Packed, role: Role) -> usize {
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
        self.push("bufferViews", view)
    }

    /// Gives vertex bufferView `view` its byteStride, which 2.0 requires once a second
    /// accessor reads it.
    fn declare_stride(&mut self, view: usize, packed: &data::Packed, components: usize) {
        let size = crate::gltf::accessor::component_size(packed.component_type).unwrap_or(4);
        let stride = packed.byte_stride.unwrap_or(size * components);
        let views = self.arrays.entry("bufferViews").or_default();
        views.update(view, |view| {
            view["byteStride"] = json!(stride);
        });
    }

    /// Adds an accessor of packed data in bufferView `view`.
    fn add_accessor_over(
        &mut self,
        view: usize,
        packed: data::Packed,
        kind: &str,
        count: usize,
        name: Option<&str>,
    ) -> usize {
        let mut accessor = json!({
            "bufferView": view,
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
        self.accessor_views.push(view);
        self.push("accessors", accessor)
    }

    /// The finished asset; `extensions_used` comes from the conversions, `extensions` holds
    /// the root extension objects they made (the lights are added here).
    pub(super) fn finish(
        mut self,
        extensions_used: Vec<String>,
        mut extensions: serde_json::Map<String, Value>,
    ) -> Upgraded {
        let mut root = Json::default();
        let source_asset = self.source.root().get("asset");
        let mut asset = json!({"version": "2.0", "generator": concat!("gltfmat ", env!("CARGO_PKG_VERSION"), " upgrade")});
        if let Some(copyright) = source_asset.and_then(|a| a.get("copyright")) {
            asset["copyright"] = copyright.to_value();
        }
        root.insert("asset", &asset);
        if !extensions_used.is_empty() {
            root.insert("extensionsUsed", &json!(extensions_used));
        }
        if let Some(lights) = self.arrays.remove("lights") {
            let lights = Value::Array(lights.iter().collect());
            extensions.insert("KHR_lights_punctual".into(), json!({"lights": lights}));
        }
        if !extensions.is_empty() {
            root.insert("extensions", &Value::Object(extensions));
        }
        if let Some(scene) = self.index_of("scenes", self.source.root().get("scene")) {
            root.insert("scene", &json!(scene));
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
                root.insert_items(collection, items);
            }
        }
        Upgraded {
            json: root,
            binary: self.binary,
            images: self.images,
            report: self.report.into_list(),
            origins: self.origins,
            passed_through: Default::default(),
            draft_reading: self.options.draft_reading,
            _decoded: self.rebakes.decoded(),
        }
    }
}
