//! State shared by the passes: the document, found diagnostics, which objects are referenced,
//! and what earlier passes learned (buffer data, image headers, material needs).

use super::collector::Collector;
use super::{CheckOptions, Diagnostic};
use crate::diagnostic::Sink;
use crate::diagnostic::{khronos, Code};
use crate::document::image_header::ImageInfo;
use crate::document::json::escape_token;
use crate::document::uri::ResourceLoader;
use crate::document::Array;
use crate::document::Node;
use crate::document::{BufferData, Bytes, Document};
use crate::gltf::material::{texture_images, TEXTURE_SLOTS};
use crate::gltf::material::{Channels, TextureSlot};
use std::collections::{HashMap, HashSet};

/// A resource as listed in the report's `info.resources`.
#[derive(Debug, Clone, Default)]
pub struct ResourceInfo {
    /// Where the resource is declared (`/buffers/0`, `/images/2`).
    pub pointer: String,
    /// `external`, `data-uri`, `glb` or `buffer-view`, as in the Khronos report.
    pub storage: &'static str,
    /// Its media type, when known.
    pub mime_type: Option<String>,
    /// Its length in bytes, when read.
    pub byte_length: Option<usize>,
    /// Its URI, for external files.
    pub uri: Option<String>,
    /// The image header, for images.
    pub image: Option<ImageInfo>,
}

/// The report's `info` section.
#[derive(Debug, Clone, Default)]
pub struct AssetInfo {
    /// `asset.version`.
    pub version: Option<String>,
    /// `asset.minVersion`.
    pub min_version: Option<String>,
    /// `asset.generator`.
    pub generator: Option<String>,
    /// `extensionsUsed`.
    pub extensions_used: Vec<String>,
    /// `extensionsRequired`.
    pub extensions_required: Vec<String>,
    /// Every buffer and image.
    pub resources: Vec<ResourceInfo>,
    /// Object counts (`drawCallCount`, `totalTriangleCount`, …) as the Khronos report has them.
    pub counts: Vec<(&'static str, u64)>,
}

/// What a material demands of the primitives that use it.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct MaterialNeeds {
    /// Each texture binding with the texCoord set it reads.
    pub texcoords: Vec<TexcoordNeed>,
    /// A normal, clearcoat-normal or anisotropy texture needs a tangent space.
    pub needs_tangent: bool,
    /// The material has a normal texture, from which a runtime can generate tangents.
    pub can_generate_tangent: bool,
    /// gltfmat: the material uses KHR_materials_anisotropy (with or without a texture).
    pub anisotropy: bool,
    /// Default profile: the material carries an extension the profile does not read, whose
    /// need of a tangent space is unknown.
    pub unread_extension: bool,
    /// Default profile: the texCoord sets below 64 that the texture bindings inside such
    /// extensions read, a bit each (counted as used, never required of a primitive). A mask,
    /// not a list: the needs are copied for every primitive drawing the material, and an
    /// extension may hold any number of bindings.
    pub unread_sets: u64,
}

/// A texture binding's texCoord set. Its pointer is made only for a finding: 10^5
/// materials hold no pointer strings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TexcoordNeed {
    /// The binding's slot, an index into [`TEXTURE_SLOTS`].
    pub slot: usize,
    /// The set comes from the binding's KHR_texture_transform (which the Khronos validator
    /// checks under its own pointer), not from the binding itself.
    pub from_transform: bool,
    pub set: u64,
}

impl TexcoordNeed {
    /// Pointer to the binding (or its KHR_texture_transform) in material `material`.
    pub(crate) fn binding(&self, material: usize) -> String {
        let transform = if self.from_transform {
            "/extensions/KHR_texture_transform"
        } else {
            ""
        };
        let slot = TEXTURE_SLOTS[self.slot].pointer();
        format!("/materials/{material}{slot}{transform}")
    }
}

/// What a profile reports of a finding as it is emitted (`check::profile::Filters`), asked
/// through this trait so that the passes' context does not depend on the profiles' rules.
pub(crate) trait Reporting {
    /// The finding as the profile reports it, or `None` when it does not.
    fn report(&self, ctx: &Context, diagnostic: Diagnostic) -> Option<Diagnostic>;
}

pub(crate) struct Context<'a> {
    pub root: Node<'a>,
    pub document: &'a Document,
    pub loader: &'a dyn ResourceLoader,
    pub options: &'a CheckOptions,
    pub diagnostics: Collector<'a>,
    /// What the profile reports of what the passes emit.
    reporting: &'a dyn Reporting,
    used: HashSet<(&'static str, usize)>,
    /// Bytes of each buffer, where they could be read (the GLB BIN chunk is borrowed).
    pub buffers: Vec<Option<BufferData<'a>>>,
    /// Header of each image, where it could be read.
    pub images: Vec<Option<ImageInfo>>,
    /// Encoded bytes of each image, kept for gltfmat's rules (not in the Khronos profile).
    pub image_bytes: Vec<Option<std::sync::Arc<Bytes>>>,
    /// By material index, for the materials that demand anything (a million empty
    /// materials keep no entry).
    pub material_needs: HashMap<usize, MaterialNeeds>,
    /// Every texture binding, computed on first use (see `materials::slot_uses`).
    pub slot_uses: std::sync::OnceLock<std::sync::Arc<[SlotUse<'a>]>>,
    /// The members changed at runtime, computed on first use (see `Animated::of`).
    pub animated: std::sync::OnceLock<std::sync::Arc<super::animated::Animated<'a>>>,
    pub resources: Vec<ResourceInfo>,
    /// Extension objects no `extensionsUsed` declares, taken out of the document before the
    /// passes (the Khronos validator reads nothing of them); the extensions pass reports them.
    pub undeclared_extensions: super::khronos::Undeclared,
    /// Each material's extension names as written, where the profile counts them so (see
    /// `khronos::extensions_as_written`), by material index.
    pub extensions_as_written: HashMap<usize, Vec<String>>,
    /// The images with an extension object as written, where the profile leaves them unread
    /// (see `khronos::images_with_extensions`).
    pub images_left_to_extensions: HashSet<usize>,
    /// Where the profile reports link findings the validator names by a path it did not
    /// unwind (see `khronos::LinkPath`); none when they are at their own pointers.
    pub link_path: Option<super::khronos::LinkPath>,
    /// The buffer or image data URI where the profile stops reading the document, as the
    /// Khronos validator stops (see `khronos::stops_at_data_uri`).
    pub stopped_at: Option<(&'static str, usize)>,
    extensions_used: std::sync::OnceLock<HashSet<&'a str>>,
}

impl<'a> Context<'a> {
    pub(crate) fn new(
        root: Node<'a>,
        document: &'a Document,
        loader: &'a dyn ResourceLoader,
        options: &'a CheckOptions,
        diagnostics: Collector<'a>,
        reporting: &'a dyn Reporting,
    ) -> Self {
        Context {
            root,
            document,
            loader,
            options,
            diagnostics,
            reporting,
            used: HashSet::new(),
            buffers: Vec::new(),
            images: Vec::new(),
            image_bytes: Vec::new(),
            material_needs: HashMap::new(),
            slot_uses: std::sync::OnceLock::new(),
            animated: std::sync::OnceLock::new(),
            resources: Vec::new(),
            undeclared_extensions: Default::default(),
            extensions_as_written: Default::default(),
            images_left_to_extensions: Default::default(),
            stopped_at: None,
            link_path: None,
            extensions_used: std::sync::OnceLock::new(),
        }
    }

    /// Reports a finding, as the profile reports it (see `check::profile`).
    pub(crate) fn emit(
        &mut self,
        code: Code,
        pointer: impl Into<String>,
        message: impl Into<std::borrow::Cow<'static, str>>,
    ) {
        let found = Diagnostic::at(code, self.link_pointer(code, pointer.into()), message);
        if let Some(reported) = self.reporting.report(self, found) {
            self.diagnostics.push(reported);
        }
    }

    /// The pointer a finding of `code` found at `pointer` is reported at.
    fn link_pointer(&self, code: Code, pointer: String) -> String {
        (self.link_path.as_ref())
            .and_then(|path| path.rewrite(code, &pointer))
            .unwrap_or(pointer)
    }

    /// Counts `n` findings of `code` at `pointer` that a pass does not list (it keeps a
    /// bounded number of one walk's findings): the report's counts stay complete.
    pub(crate) fn count_unlisted(&mut self, code: Code, pointer: impl Into<String>, n: u64) {
        let found = Diagnostic::at(code, self.link_pointer(code, pointer.into()), String::new());
        if let Some(reported) = self.reporting.report(self, found) {
            self.diagnostics.count_unlisted(&reported, n);
        }
    }

    /// The elements of a top-level array, or nothing when it is missing or not an array.
    pub(crate) fn items(&self, collection: &str) -> Array<'a> {
        self.root
            .get(collection)
            .and_then(Node::as_array)
            .unwrap_or_else(|| Array::empty(self.root))
    }

    /// Whether an accessor's bufferView declares a byteStride (false when it has no view).
    pub(crate) fn has_strided_view(&self, accessor: Node) -> bool {
        unsigned(accessor, "bufferView")
            .and_then(|v| self.items("bufferViews").get(v as usize))
            .is_some_and(|v| v.get("byteStride").is_some())
    }

    /// Object elements of a top-level array, with their index and pointer.
    pub(crate) fn objects(
        &self,
        collection: &'static str,
    ) -> impl Iterator<Item = (usize, String, Node<'a>)> + 'a {
        // It borrows the document, not the context, so a pass can emit while it walks; and
        // each pointer is made as its object is reached (a million materials once took a
        // list of a million pointers per pass).
        self.items(collection)
            .iter()
            .enumerate()
            .filter(|(_, v)| v.is_object())
            .map(move |(i, v)| (i, format!("/{collection}/{i}"), v))
    }

    /// Resolves `object[key]` as an index into `collection`, marking the target used.
    /// A missing or mistyped member gives `None` silently (the schema pass reported it).
    pub(crate) fn reference(
        &mut self,
        object: Node,
        key: &str,
        pointer: &str,
        collection: &'static str,
    ) -> Option<usize> {
        let value = object.get(key)?;
        self.reference_value(value, &member(pointer, key), collection)
    }

    /// Resolves an index value at `pointer` into `collection`, marking the target used.
    pub(crate) fn reference_value(
        &mut self,
        value: Node,
        pointer: &str,
        collection: &'static str,
    ) -> Option<usize> {
        let index = self.resolve(value, pointer, collection)?;
        self.used.insert((collection, index));
        Some(index)
    }

    /// Resolves an index value at `pointer` into `collection`, reporting one that names
    /// nothing, without marking the target used (as for a skin's skeleton: the Khronos
    /// validator counts no node used for being one).
    pub(crate) fn resolve(
        &mut self,
        value: Node,
        pointer: &str,
        collection: &'static str,
    ) -> Option<usize> {
        // A whole number too large for an index (1e29) resolves to nothing, like any other
        // index past the end, and so does an element that is no object (the schema pass
        // reported it; the Khronos validator reads it as missing); other values are the
        // schema pass's to report.
        let whole = value.as_f64().is_some_and(|f| f.fract() == 0.0 && f >= 0.0);
        let index = as_index(value).filter(|&i| self.element(collection, i).is_some());
        let Some(index) = index else {
            if whole {
                self.emit(
                    khronos::UNRESOLVED_REFERENCE,
                    pointer,
                    // The number as written: an index beyond u64 must not print as a saturated one.
                    format!("Unresolved reference: {value}."),
                );
            }
            return None;
        };
        Some(index as usize)
    }

    /// The element at `index` of a top-level collection, when it is an object: what a
    /// reference can resolve to (an element of another type is read as missing).
    pub(crate) fn element(&self, collection: &str, index: u64) -> Option<Node<'a>> {
        let element = self.items(collection).get(usize::try_from(index).ok()?)?;
        element.is_object().then_some(element)
    }

    pub(crate) fn mark_used(&mut self, collection: &'static str, index: usize) {
        self.used.insert((collection, index));
    }

    pub(crate) fn is_used(&self, collection: &'static str, index: usize) -> bool {
        self.used.contains(&(collection, index))
    }

    /// Whether `extensionsUsed` names `extension`: a set built once, since an asset may
    /// declare 10^5 names and hold as many extension objects.
    pub(crate) fn uses_extension(&self, extension: &str) -> bool {
        let used = self.extensions_used.get_or_init(|| {
            (self.items("extensionsUsed").iter())
                .filter_map(Node::as_str)
                .collect()
        });
        used.contains(extension)
    }

    pub(crate) fn info(&self) -> AssetInfo {
        let asset = self.root.get("asset");
        let text = |key: &str| {
            asset
                .and_then(|a| a.get(key))
                .and_then(Node::as_str)
                .map(str::to_string)
        };
        let strings = |key: &str| {
            self.root
                .get(key)
                .and_then(Node::as_array)
                .map(|a| {
                    a.iter()
                        .filter_map(|v| v.as_str().map(str::to_string))
                        .collect()
                })
                .unwrap_or_default()
        };
        let count = |key: &str| self.items(key).len() as u64;
        AssetInfo {
            version: text("version"),
            min_version: text("minVersion"),
            generator: text("generator"),
            extensions_used: strings("extensionsUsed"),
            extensions_required: strings("extensionsRequired"),
            resources: self.resources.clone(),
            counts: vec![
                ("animationCount", count("animations")),
                ("materialCount", count("materials")),
                ("hasMorphTargets", 0),
                ("hasSkins", u64::from(count("skins") > 0)),
                ("hasTextures", u64::from(count("textures") > 0)),
                (
                    "hasDefaultScene",
                    u64::from(self.root.get("scene").is_some()),
                ),
            ],
        }
    }
}

/// `pointer/key`, with the key escaped.
pub(crate) fn member(pointer: &str, key: &str) -> String {
    format!("{pointer}/{}", escape_token(key))
}

/// The elements of an array member with their indices; nothing when missing or mistyped
/// (the schema pass reports that).
pub(crate) fn elements<'v>(object: Node<'v>, key: &str) -> impl Iterator<Item = (usize, Node<'v>)> {
    object
        .get(key)
        .and_then(Node::as_array)
        .into_iter()
        .flatten()
        .enumerate()
}

/// A number member, falling back to `default` when missing or mistyped.
pub(crate) fn number(object: Node, key: &str, default: f64) -> f64 {
    object.get(key).and_then(Node::as_f64).unwrap_or(default)
}

pub(crate) use crate::gltf::{as_index, unsigned};

/// A material's extension object by name.
pub(crate) fn extension<'v>(material: Node<'v>, name: &str) -> Option<Node<'v>> {
    material
        .get("extensions")?
        .get(name)
        .filter(|v| v.is_object())
}

/// One texture bound to one slot of one material. Small and allocation-free: an asset
/// may hold 10^5 of them, and its pointer and images are made when asked for.
#[derive(Clone)]
pub(crate) struct SlotUse<'a> {
    pub material: Node<'a>,
    /// The material's index.
    pub material_index: usize,
    pub slot: &'static TextureSlot,
    /// The texture object it binds.
    pub texture: Node<'a>,
    /// How many images the asset has (a source past them samples nothing).
    pub image_count: usize,
}

impl SlotUse<'_> {
    /// Pointer to the textureInfo.
    pub(crate) fn pointer(&self) -> String {
        format!("/materials/{}{}", self.material_index, self.slot.pointer())
    }

    /// Images the texture may sample: `source` and any extension's `source` (WebP, KTX2 …).
    pub(crate) fn images(&self) -> impl Iterator<Item = usize> + '_ {
        (texture_images(self.texture))
            .filter(|&i| i < self.image_count as u64)
            .map(|i| i as usize)
    }

    /// The channels this use reads: (sRGB, linear).
    pub(crate) fn reads(&self) -> (Channels, Channels) {
        self.slot.reads(self.material)
    }

    /// A member of the slot's extension object (or of the material for core slots).
    pub(crate) fn extension_number(&self, key: &str, default: f64) -> f64 {
        self.slot
            .extension
            .and_then(|name| extension(self.material, name))
            .map_or(default, |ext| number(ext, key, default))
    }
}
