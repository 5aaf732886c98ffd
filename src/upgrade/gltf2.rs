//! glTF 2.0 inputs: the archived KHR_materials_pbrSpecularGlossiness retired. Every
//! spec-gloss material becomes metallic-roughness + KHR_materials_specular +
//! KHR_materials_ior by the same mapping as the 1.0 drafts' (`spec_gloss`); everything else
//! passes through: every other object, extension and extra as it was, every buffer byte
//! unchanged and in place (a single buffer keeps every bufferView's offset; several are
//! laid end to end, 4-byte aligned, their views moved with them). Textures, images and
//! samplers that only the converted materials used, and no longer do, are not written;
//! images stored in a bufferView stay, so that no buffer byte moves.

use super::json::{Items, Json};
use super::references::{renumber_texture_members, renumber_textures, texture_indices};
use super::spec_gloss::{self, Factors, Slot};
use super::{Binary, EncodedImage, NoteKind, Notes, SpecularGlossiness, UpgradeError};
use super::{UpgradeOptions, Upgraded};
use crate::document::uri::{load_uri, ResourceLoader};
use crate::document::{self, image_header, Bytes, Container};
use crate::document::{Node, Object};
use crate::gltf::material::{
    combination, drawn_image, effective_texcoord, texture_images, texture_transform,
};
use crate::gltf::material::{Combination, SPEC_GLOSS, UNLIT};
use crate::gltf::unsigned;
use crate::shade::sample::Sampler;
use serde_json::{json, Value};
use std::collections::{BTreeSet, HashMap};
use std::ops::Range;
use std::sync::Arc;

/// Upgrades a glTF 2.0 asset: its spec-gloss materials converted, the rest passed through.
pub(super) fn upgrade(
    bytes: Vec<u8>,
    loader: &dyn ResourceLoader,
    options: &UpgradeOptions,
) -> Result<Upgraded, UpgradeError> {
    let name = if bytes.starts_with(b"glTF") {
        "input.glb"
    } else {
        "input.gltf"
    };
    let mut problems = Vec::new();
    let mut doc = document::read(bytes, name, &mut problems);
    // The input is read from its tree; the output's JSON starts as a copy of it.
    let tree = match doc.root.take() {
        Some(tree) if tree.root().is_object() => tree,
        _ => {
            let why = document::why_unreadable(&problems);
            return Err(UpgradeError::Unreadable(format!(
                "the glTF 2.0 document cannot be read: {why}"
            )));
        }
    };
    let input = tree.root();
    let root = Json::from_node(input);
    let bytes = Arc::clone(&doc.bytes);
    let glb_bin = (doc.container == Container::Glb)
        .then_some(doc.bin.clone())
        .flatten()
        .map(|bin| (&bytes, bin));
    let mut asset = Asset {
        root,
        binary: Binary::default(),
        images: Vec::new(),
        report: Notes::default(),
        rebaked: HashMap::new(),
        rebakes: Default::default(),
        texel_fits: super::fit::TexelFits::for_exact_form(),
    };
    refuse_buffers_named_inside_extensions(input)?;
    let buffers = read_buffers(input, glb_bin, loader)?;
    asset.take_images(input, &buffers, loader)?;
    asset.join_buffers(input, &buffers);
    let mut passed_through: BTreeSet<usize> = (0..list(input, "materials").count()).collect();
    if options.specular_glossiness == SpecularGlossiness::MetalRough {
        for converted in asset.convert_materials(input)? {
            passed_through.remove(&converted);
        }
    } else {
        asset.note(
            "/materials",
            NoteKind::Decision,
            "--specular-glossiness extension: spec-gloss materials are left as they are.",
        );
    }
    Ok(Upgraded {
        json: asset.root,
        binary: asset.binary,
        images: asset.images,
        report: asset.report.into_list(),
        origins: Default::default(),
        passed_through,
        draft_reading: options.draft_reading,
        _decoded: asset.rebakes.decoded(),
    })
}

/// The 2.0 asset being rewritten.
struct Asset {
    root: Json,
    binary: Binary,
    images: Vec<EncodedImage>,
    report: Notes,
    /// Rebaked textures by image bytes and sampler: materials that share their textures and
    /// factors share the rebake instead of writing one image each.
    rebaked: HashMap<(Vec<u8>, Option<u64>), usize>,
    /// The rebakes made, by what they were made from.
    rebakes: spec_gloss::Rebakes,
    /// The 8-bit levels of rebaked texels, settled by the evaluator.
    texel_fits: super::fit::TexelFits,
}

/// An input buffer's bytes: the shared file (or GLB) and the buffer's range in it.
struct Buffer {
    bytes: Arc<Bytes>,
    range: Range<usize>,
}

fn resource_error(pointer: &str, reason: impl Into<String>) -> UpgradeError {
    UpgradeError::Resource {
        pointer: pointer.to_string(),
        reason: reason.into(),
    }
}

impl Asset {
    fn note(&mut self, pointer: impl Into<String>, kind: NoteKind, text: impl Into<String>) {
        self.report.push(pointer.into(), kind, text.into());
    }

    /// The elements of the output's root array `key`, each parsed as it is reached: what
    /// the conversion wrote, read back to find what it no longer uses.
    fn written(&self, key: &str) -> impl Iterator<Item = Value> + '_ {
        self.root.items(key).into_iter().flat_map(Items::iter)
    }

    fn count(&self, key: &str) -> usize {
        self.root.items(key).map_or(0, Items::len)
    }

    /// Changes every element of root array `key` through `change`.
    fn update_all(&mut self, key: &str, change: impl FnMut(&mut Value)) {
        if let Some(items) = self.root.items_mut_if_array(key) {
            items.update_all(change);
        }
    }

    /// Lays the buffers end to end in the output buffer. A lone buffer starts at 0, so no
    /// bufferView changes; later buffers start 4-byte aligned and their views move to
    /// buffer 0 with their offsets shifted.
    fn join_buffers(&mut self, input: Node, buffers: &[Buffer]) {
        let mut starts = Vec::with_capacity(buffers.len());
        for buffer in buffers {
            starts.push(self.binary.align());
            self.binary.share(&buffer.bytes, buffer.range.clone());
        }
        if buffers.len() > 1 {
            self.update_all("bufferViews", |view| {
                let Some(buffer) = unsigned(&*view, "buffer") else {
                    return;
                };
                let Some(&start) = starts.get(buffer as usize) else {
                    return;
                };
                let offset = unsigned(&*view, "byteOffset").unwrap_or(0);
                view["buffer"] = json!(0);
                view["byteOffset"] = json!(offset + start as u64);
            });
            let joined = format!(
                "{} buffers joined into one (bufferViews moved with their bytes; no byte changed).",
                buffers.len()
            );
            self.note("/buffers", NoteKind::Decision, joined);
        }
        match list(input, "buffers").next().map(Node::to_value) {
            Some(Value::Object(mut kept)) => {
                kept.remove("uri");
                kept.insert("byteLength".into(), json!(self.binary.len()));
                self.root.insert("buffers", &json!([kept]));
            }
            _ => {
                self.root.remove("buffers");
            }
        }
    }

    /// Every image's bytes: those in a bufferView stay there; those in files or data URIs
    /// are read, to be written beside the output or into its BIN chunk.
    fn take_images(
        &mut self,
        input: Node,
        buffers: &[Buffer],
        loader: &dyn ResourceLoader,
    ) -> Result<(), UpgradeError> {
        for (i, image) in list(input, "images").enumerate() {
            let at = format!("/images/{i}");
            let uri = image.get("uri").and_then(Node::as_str);
            let (bytes, in_binary) = match uri {
                Some(uri) => match load_uri(uri, loader) {
                    // A data URI is the same wherever the output lies: one holding no image
                    // stays as it is, rather than be given a media type it does not have.
                    Ok(bytes)
                        if uri.starts_with("data:") && image_header::read(&bytes).is_err() =>
                    {
                        self.leave_unread(i, image, "its data URI holds no image".into());
                        continue;
                    }
                    Ok(bytes) => (bytes, false),
                    Err(why) => {
                        self.leave_unread(i, image, why);
                        continue;
                    }
                },
                None => {
                    let view = unsigned(image, "bufferView")
                        .and_then(|v| view_bytes(input, v as usize, buffers))
                        .ok_or_else(|| resource_error(&at, "its bufferView cannot be read"))?;
                    (Arc::new(view.to_vec().into()), true)
                }
            };
            let declared = image.get("mimeType").and_then(Node::as_str);
            let mime_type = (declared.map(str::to_string))
                .or_else(|| Some(image_header::read(&bytes).ok()?.format.mime_type().into()))
                .unwrap_or_else(|| "application/octet-stream".into());
            let name = image.get("name").and_then(Node::as_str).unwrap_or("image");
            let stem = uri.map_or_else(|| name.to_string(), file_stem);
            let encoded = EncodedImage::new(bytes, mime_type, i, &stem, in_binary);
            self.images.push(encoded);
            if let Some(images) = self.root.items_mut_if_array("images") {
                images.update(i, |image| {
                    image.as_object_mut().map(|image| image.remove("uri"));
                });
            }
        }
        Ok(())
    }

    /// An image whose file cannot be read (missing, say), or whose data URI holds no image,
    /// is left as the input has it: its `uri` kept, no file written for it. Only a
    /// conversion that reads its texels needs it, and that material is then left as
    /// spec-gloss (see [`EncodedImage::unread`]).
    fn leave_unread(&mut self, i: usize, image: Node, why: String) {
        let declared = image.get("mimeType").and_then(Node::as_str);
        let mime_type = declared.unwrap_or("application/octet-stream").to_string();
        let text = format!("{why}: the image is left as the input has it (its uri kept, no file written for it); a conversion that reads its texels leaves its material as spec-gloss.");
        self.note(format!("/images/{i}"), NoteKind::Decision, text);
        let mut kept = EncodedImage::new(Arc::new(Vec::new().into()), mime_type, i, "", false);
        kept.unread = Some(why);
        self.images.push(kept);
    }

    /// Converts every spec-gloss material that can be; returns their indices.
    fn convert_materials(&mut self, input: Node) -> Result<Vec<usize>, UpgradeError> {
        let used_before = self.used_textures();
        let mut converted = Vec::new();
        for (i, material) in list(input, "materials").enumerate() {
            if self.convert_material(input, i, material)? {
                converted.push(i);
            }
        }
        if converted.is_empty() {
            self.note("/materials", NoteKind::Decision, "no KHR_materials_pbrSpecularGlossiness material was converted: the asset passes through unchanged.");
            return Ok(converted);
        }
        self.update_extension_lists();
        let now_used = self.used_textures();
        let unused: BTreeSet<usize> = used_before.difference(&now_used).copied().collect();
        self.drop_textures(&unused);
        Ok(converted)
    }

    /// Converts material `i` if it is a spec-gloss material that can be; true when it was.
    fn convert_material(
        &mut self,
        input: Node,
        i: usize,
        material: Node,
    ) -> Result<bool, UpgradeError> {
        let at = format!("/materials/{i}/extensions/{SPEC_GLOSS}");
        let Some(extensions) = material.get("extensions").and_then(Node::as_object) else {
            return Ok(false);
        };
        let Some(block) = extensions.get(SPEC_GLOSS) else {
            return Ok(false);
        };
        if let Some(why) = why_not_converted(input, extensions, block) {
            self.note(
                &at,
                NoteKind::Decision,
                format!("left as spec-gloss: {why}"),
            );
            return Ok(false);
        }
        let factors = Factors {
            reading: crate::shade::material::SpecGlossReading::ArchivedExtension,
            diffuse: numbers(block.get("diffuseFactor"), [1.0; 4]),
            specular: numbers(block.get("specularFactor"), [1.0; 3]),
            glossiness: block
                .get("glossinessFactor")
                .and_then(Node::as_f64)
                .unwrap_or(1.0),
        };
        let mut textures = MaterialTextures {
            asset: self,
            input,
            diffuse: block.get("diffuseTexture").map(Node::to_value),
            specular_glossiness: block.get("specularGlossinessTexture").map(Node::to_value),
            material: i,
        };
        let converted = match spec_gloss::to_metal_rough(&factors, &mut textures) {
            Ok(converted) => converted,
            Err(why) => {
                // A texture gltfmat cannot decode (a broken file, a KTX2 it does not transcode): that
                // material only.
                let text = format!("left as spec-gloss: its textures cannot be rebaked: {why}");
                self.note(&at, NoteKind::Decision, text);
                return Ok(false);
            }
        };
        if material.get("pbrMetallicRoughness").is_some() {
            self.note(&at, NoteKind::Decision, "the material's own pbrMetallicRoughness (the fallback for viewers without the extension) is replaced by the conversion.");
        }
        for decision in converted.decisions {
            self.note(&at, NoteKind::Decision, decision);
        }
        let materials = self.root.items_mut("materials");
        materials.update(i, |out| {
            out["pbrMetallicRoughness"] = converted.pbr_metallic_roughness;
            if let Some(extensions) = out.get_mut("extensions").and_then(Value::as_object_mut) {
                extensions.remove(SPEC_GLOSS);
                extensions.extend(converted.extensions);
            }
        });
        Ok(true)
    }

    /// extensionsUsed gains what the conversions wrote and loses the spec-gloss extension
    /// when no material has it any more (extensionsRequired too).
    fn update_extension_lists(&mut self) {
        let still_used = self.written("materials").any(|m| {
            m.get("extensions")
                .and_then(|e| e.get(SPEC_GLOSS))
                .is_some()
        });
        let mut used: Vec<Value> = self.written("extensionsUsed").collect();
        for added in spec_gloss::EXTENSIONS_ADDED {
            if !used.iter().any(|u| u == added) {
                used.push(json!(added));
            }
        }
        if !still_used {
            used.retain(|u| u != SPEC_GLOSS);
            if let Some(mut required) = self.root.items("extensionsRequired").cloned() {
                required.retain(|_, r| r != SPEC_GLOSS);
                if required.is_empty() {
                    self.root.remove("extensionsRequired");
                } else {
                    self.root.insert_items("extensionsRequired", required);
                }
            }
        }
        self.root.insert("extensionsUsed", &Value::Array(used));
    }

    /// The textures the materials read (through any `…Texture` member's `index`).
    fn used_textures(&self) -> BTreeSet<usize> {
        let mut used = BTreeSet::new();
        for material in self.written("materials") {
            used.extend(texture_indices(&material));
        }
        used
    }

    /// Removes `textures`, then the images and samplers only they used (images in a
    /// bufferView stay: removing them would leave their bytes behind as an unused view),
    /// renumbering what refers to the rest.
    fn drop_textures(&mut self, textures: &BTreeSet<usize>) {
        let images_before = self.referenced_by_textures("source");
        let samplers_before = self.referenced_by_textures("sampler");
        let texture_map = self.remove("textures", textures);
        self.update_all("materials", |material| {
            renumber_textures(material, &texture_map)
        });
        let images_after = self.referenced_by_textures("source");
        let removable_images: BTreeSet<usize> = (images_before.difference(&images_after))
            .copied()
            .filter(|&i| self.images.get(i).is_some_and(|image| !image.in_binary))
            .collect();
        let samplers_after = self.referenced_by_textures("sampler");
        let removable_samplers: BTreeSet<usize> = samplers_before
            .difference(&samplers_after)
            .copied()
            .collect();
        let image_map = self.remove("images", &removable_images);
        let mut index = 0;
        self.images.retain(|_| {
            index += 1;
            image_map[index - 1].is_some()
        });
        let sampler_map = self.remove("samplers", &removable_samplers);
        self.update_all("textures", |texture| {
            renumber_texture_members(texture, &image_map, &sampler_map)
        });
    }

    /// The image (`source`, including extensions' sources) or sampler indices textures name.
    fn referenced_by_textures(&self, key: &str) -> BTreeSet<usize> {
        let textures = self.written("textures");
        if key == "source" {
            textures
                .flat_map(|t| texture_images(&t).collect::<Vec<_>>())
                .map(|i| i as usize)
                .collect()
        } else {
            textures
                .filter_map(|t| unsigned(&t, key))
                .map(|i| i as usize)
                .collect()
        }
    }

    /// Removes the listed objects of a collection, noting each; returns every old index's
    /// new one (None: removed).
    fn remove(&mut self, collection: &str, removed: &BTreeSet<usize>) -> Vec<Option<usize>> {
        let Some(items) = self.root.items_mut_if_array(collection) else {
            return Vec::new();
        };
        let mut map = Vec::with_capacity(items.len());
        let mut kept = 0;
        let mut dropped = Vec::new();
        items.retain(|i, item| {
            if removed.contains(&i) {
                map.push(None);
                let name = item.get("name").and_then(Value::as_str).unwrap_or("");
                dropped.push((i, name.to_string()));
                return false;
            }
            map.push(Some(kept));
            kept += 1;
            true
        });
        if kept == 0 {
            self.root.remove(collection);
        }
        for (i, name) in dropped {
            let named = match name.is_empty() {
                true => String::new(),
                false => format!(" ('{name}')"),
            };
            self.note(
                format!("/{collection}/{i}"),
                NoteKind::Dropped,
                format!("not written: only the converted spec-gloss materials used it{named}."),
            );
        }
        map
    }
}

/// The output holds one buffer, made by joining the input's; meshopt compression names
/// its compressed buffer (and an offset in it) inside each bufferView's extension, and its
/// fallback buffer holds no bytes, so such an asset of several buffers cannot be joined
/// without rewriting what the extension means. Refused, saying what to do instead.
fn refuse_buffers_named_inside_extensions(input: Node) -> Result<(), UpgradeError> {
    const NAMING_BUFFERS: [&str; 2] = ["EXT_meshopt_compression", "KHR_meshopt_compression"];
    let used = list(input, "extensionsUsed").filter_map(Node::as_str);
    let meshopt = used.into_iter().find(|name| NAMING_BUFFERS.contains(name));
    let buffers = list(input, "buffers").count();
    match meshopt {
        Some(name) if buffers > 1 => Err(UpgradeError::Invalid {
            pointer: "/extensionsUsed".into(),
            reason: format!(
                "{name} names buffers inside each bufferView's extension, and the upgrade joins the asset's {} buffers into one; decompress the asset first (for example with gltfpack without -c, or glTF-Transform), then upgrade it",
                buffers
            ),
        }),
        _ => Ok(()),
    }
}

/// Every buffer's declared bytes: read from its file or data URI, or the GLB's BIN chunk.
fn read_buffers(
    input: Node,
    glb_bin: Option<(&Arc<Bytes>, Range<usize>)>,
    loader: &dyn ResourceLoader,
) -> Result<Vec<Buffer>, UpgradeError> {
    let mut buffers = Vec::new();
    for (i, buffer) in list(input, "buffers").enumerate() {
        let at = format!("/buffers/{i}");
        let length = unsigned(buffer, "byteLength")
            .ok_or_else(|| resource_error(&at, "byteLength is missing"))?
            as usize;
        let (bytes, start) = match (buffer.get("uri").and_then(Node::as_str), &glb_bin) {
            (Some(uri), _) => {
                let bytes = load_uri(uri, loader).map_err(|e| resource_error(&at, e))?;
                (bytes, 0)
            }
            (None, Some((bytes, bin))) if i == 0 => (Arc::clone(bytes), bin.start),
            (None, _) => {
                let why = "it has no uri and is not the GLB's BIN chunk";
                return Err(resource_error(&at, why));
            }
        };
        let available = match &glb_bin {
            Some((_, bin)) if buffer.get("uri").is_none() => bin.len(),
            _ => bytes.len(),
        };
        if length > available {
            let why = format!("byteLength is {length}, but it holds {available} bytes");
            return Err(resource_error(&at, why));
        }
        buffers.push(Buffer {
            bytes,
            range: start..start + length,
        });
    }
    Ok(buffers)
}

/// The bytes of bufferView `index` of the input.
fn view_bytes<'b>(input: Node, index: usize, buffers: &'b [Buffer]) -> Option<&'b [u8]> {
    let view = input.get("bufferViews")?.as_array()?.get(index)?;
    let buffer = buffers.get(unsigned(view, "buffer")? as usize)?;
    let start = unsigned(view, "byteOffset").unwrap_or(0) as usize;
    let end = start.checked_add(unsigned(view, "byteLength")? as usize)?;
    buffer.bytes.get(buffer.range.clone())?.get(start..end)
}

/// The elements of the input's root array `key`.
fn list<'t>(input: Node<'t>, key: &str) -> impl Iterator<Item = Node<'t>> + 't {
    (input.get(key).and_then(Node::as_array).into_iter()).flat_map(|a| a.iter())
}

/// Why a spec-gloss material is not converted, if it is not: extensions its spec excludes
/// (reported, not guessed at), unlit (which shows the fallback base colour, not the
/// spec-gloss model), or two textures a per-texel rebake cannot join (read through different
/// texture coordinates, transforms or samplers).
fn why_not_converted(input: Node, extensions: Object, block: Node) -> Option<String> {
    let excluded: Vec<&str> = (extensions.keys())
        .filter(|other| combination(SPEC_GLOSS, other) == Combination::Excluded)
        .collect();
    if !excluded.is_empty() {
        return Some(format!(
            "it also has {}, which the spec-gloss extension excludes (the material is invalid; which one the author meant is not guessed).",
            excluded.join(", ")
        ));
    }
    if extensions.contains_key(UNLIT) {
        return Some(format!(
            "it is also {UNLIT}: viewers show it unlit, and its base colour must stay as written."
        ));
    }
    let (Some(diffuse), Some(specular)) = (
        block.get("diffuseTexture"),
        block.get("specularGlossinessTexture"),
    ) else {
        return None;
    };
    let mapping = |info: Node| {
        (
            effective_texcoord(info),
            texture_transform(info).map(Node::to_value),
        )
    };
    if mapping(diffuse) != mapping(specular) {
        return Some("its diffuse and specular-glossiness textures use different texture coordinates or transforms, so no texture can hold diffuse · (1 − specular).".to_string());
    }
    // One texture is read through one sampler: two textures filtered or wrapped differently
    // (NEAREST beside LINEAR, CLAMP beside REPEAT) make a product no single sampler shows.
    let sampler = |info: Node| sampler_of(input, texture_of(input, info));
    (sampler(diffuse) != sampler(specular)).then(|| {
        "its diffuse and specular-glossiness textures are read through samplers that filter or wrap differently, so no texture read through one sampler can hold diffuse · (1 − specular).".to_string()
    })
}

/// The input's texture a textureInfo names.
fn texture_of<'t>(input: Node<'t>, info: Node) -> Option<Node<'t>> {
    list(input, "textures").nth(usize::try_from(unsigned(info, "index")?).ok()?)
}

/// The sampler `texture` is read through (LINEAR, REPEAT when it names none).
fn sampler_of(input: Node, texture: Option<Node>) -> Sampler {
    let index = texture.and_then(|t| unsigned(t, "sampler"));
    Sampler::of(index.and_then(|i| list(input, "samplers").nth(usize::try_from(i).ok()?)))
}

/// A JSON array of numbers, each missing or non-numeric entry taken from `default`.
fn numbers<const N: usize>(value: Option<Node>, default: [f64; N]) -> [f64; N] {
    std::array::from_fn(|i| {
        value
            .and_then(|v| v.get(i))
            .and_then(Node::as_f64)
            .unwrap_or(default[i])
    })
}

/// The last path segment of a URI without its extension (a data URI: "image").
fn file_stem(uri: &str) -> String {
    if uri.starts_with("data:") {
        return "image".into();
    }
    let last = uri.rsplit('/').next().unwrap_or(uri);
    last.rsplit_once('.')
        .map_or(last, |(stem, _)| stem)
        .to_string()
}

/// A spec-gloss material's two textureInfos, read from and added to the 2.0 asset.
struct MaterialTextures<'a> {
    asset: &'a mut Asset,
    input: Node<'a>,
    diffuse: Option<Value>,
    specular_glossiness: Option<Value>,
    material: usize,
}

impl MaterialTextures<'_> {
    fn slot(&self, slot: Slot) -> Option<&Value> {
        match slot {
            Slot::Diffuse => self.diffuse.as_ref(),
            Slot::SpecularGlossiness => self.specular_glossiness.as_ref(),
        }
    }

    /// The input's texture the slot names.
    fn texture(&self, slot: Slot) -> Option<Node<'_>> {
        let index = unsigned(self.slot(slot)?, "index")?;
        list(self.input, "textures").nth(usize::try_from(index).ok()?)
    }
}

impl spec_gloss::Textures for MaterialTextures<'_> {
    fn info(&self, slot: Slot) -> Option<Value> {
        self.slot(slot).cloned()
    }

    fn sampler(&self, slot: Slot) -> Sampler {
        sampler_of(self.input, self.texture(slot))
    }

    fn bytes(&self, slot: Slot) -> Result<Option<Arc<crate::document::Bytes>>, String> {
        let Some(image) = self.texture(slot).and_then(drawn_image) else {
            return Ok(None);
        };
        match self.asset.images.get(image as usize) {
            Some(EncodedImage {
                unread: Some(why), ..
            }) => Err(format!("/images/{image}: {why}")),
            Some(encoded) => Ok(Some(encoded.bytes.clone())),
            None => Ok(None),
        }
    }

    /// The archived extension has one reading, which the closed form reproduces exactly.
    fn texel_fits(&mut self) -> Option<&mut super::fit::TexelFits> {
        Some(&mut self.asset.texel_fits)
    }

    fn rebakes(&mut self) -> &mut spec_gloss::Rebakes {
        &mut self.asset.rebakes
    }

    fn add_rebaked(&mut self, bytes: Vec<u8>, like: Slot, name: &str) -> Value {
        let sampler = self.texture(like).and_then(|t| unsigned(t, "sampler"));
        let mut info = self.slot(like).cloned().unwrap_or_else(|| json!({}));
        let key = (bytes, sampler);
        if let Some(&texture) = self.asset.rebaked.get(&key) {
            info["index"] = json!(texture);
            return info;
        }
        let name = format!("material {} {name}", self.material);
        let index = self.asset.count("images");
        let image = EncodedImage::new(
            Arc::new(key.0.clone().into()),
            "image/png".into(),
            index,
            &name,
            false,
        );
        self.asset.images.push(image);
        self.asset
            .root
            .items_mut("images")
            .push(&json!({"name": name}));
        let mut texture = json!({"name": name, "source": index});
        if let Some(sampler) = sampler {
            texture["sampler"] = json!(sampler);
        }
        let texture = self.asset.root.items_mut("textures").push(&texture);
        self.asset.rebaked.insert(key, texture);
        info["index"] = json!(texture);
        info
    }
}
