//! Reading the materials of a glTF 2.0 file (`.gltf` or `.glb`) for the evaluator.

use super::sample::{self, MaterialSource, Texture, TextureSet};
use super::surface;
use super::views::Views;
use crate::document::uri::{load_uri, ResourceLoader};
use crate::document::{self, Bytes, Node};
use crate::gltf::material::drawn_image;
use std::collections::HashMap;
use std::sync::Arc;

/// An image's encoded bytes: its own file or data URI, or a buffer view of the document.
enum Encoded<'a> {
    Loaded(Arc<Bytes>),
    View(&'a [u8]),
}

impl std::ops::Deref for Encoded<'_> {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        match self {
            Encoded::Loaded(bytes) => bytes,
            Encoded::View(view) => view,
        }
    }
}

/// The images the materials sample (through their textureInfo objects, the only objects
/// in a material with an `index`): the others, such as originals a converter kept, are not
/// decoded.
pub(crate) fn used_images<'t>(
    materials: impl IntoIterator<Item = Node<'t>>,
    textures: &[Node],
) -> std::collections::BTreeSet<usize> {
    fn texture_indices(value: Node, out: &mut Vec<u64>) {
        if let Some(object) = value.as_object() {
            out.extend(object.get("index").and_then(Node::as_u64));
            object.values().for_each(|v| texture_indices(v, out));
        } else if let Some(items) = value.as_array() {
            items.iter().for_each(|v| texture_indices(v, out));
        }
    }
    let mut indices = Vec::new();
    (materials.into_iter()).for_each(|m| texture_indices(m, &mut indices));
    indices
        .into_iter()
        .filter_map(|t| textures.get(t as usize))
        .filter_map(|&texture| texture_source(texture))
        .map(|source| source as usize)
        .collect()
}

/// A texture's image: the one a viewer draws (see [`drawn_image`]).
pub(crate) fn texture_source(texture: Node) -> Option<u64> {
    drawn_image(texture)
}

/// An asset's materials by name, and the surface points of each (see [`gltf2_materials`]).
pub(crate) type MaterialsOn = (Vec<(String, MaterialSource)>, Vec<surface::Surface>);

/// Every material of a glTF 2.0 asset with its decoded textures (no finer than `finest`, see
/// [`sample::decode_each_at_most`]), and the material names; with `surfaces`, also the points
/// on its meshes where each material's texCoord sets differ (see [`surface::surface_points`]).
pub(crate) fn gltf2_materials(
    bytes: Vec<u8>,
    name: &str,
    loader: &dyn ResourceLoader,
    finest: u32,
    surfaces: bool,
) -> Result<MaterialsOn, String> {
    // Only the materials are read here; problems with the file are `check`'s to report,
    // but one that leaves nothing to read is said.
    let mut problems = Vec::new();
    let doc = document::read(bytes, name, &mut problems);
    let root = match doc.root.as_ref().map(|tree| tree.root()) {
        Some(root) if root.is_object() => root,
        _ => {
            let why = document::why_unreadable(&problems);
            return Err(format!("not a readable glTF document: {why}"));
        }
    };
    crate::document::uri::note_named_files(root, loader);
    let nodes =
        |key: &str| (root.get(key).and_then(Node::as_array).into_iter()).flat_map(|a| a.iter());
    let list = |key: &str| -> Vec<Node> { nodes(key).collect() };
    let views = Views::of(&doc, loader);
    let images = list("images");
    let view_bytes = |index: u64| views.read(index);
    let textures = list("textures");
    let samplers = samplers_of(&textures, &list("samplers"));
    let needed = used_images(nodes("materials"), &textures);
    let encoded: Vec<sample::Wanted<Encoded>> = images
        .iter()
        .enumerate()
        .map(|(i, image)| (i, image.get("uri").and_then(Node::as_str)))
        .map(|(i, uri)| match (needed.contains(&i), uri) {
            (false, _) => None,
            (true, Some(uri)) => Some(load_uri(uri, loader).map(Encoded::Loaded)),
            (true, None) => Some(
                (images[i].get("bufferView").and_then(Node::as_u64))
                    .ok_or_else(|| "it has neither a uri nor a bufferView".to_string())
                    .and_then(view_bytes)
                    .map(Encoded::View),
            ),
        })
        .collect();
    // An image that cannot be read or decoded (a format the evaluator does not decode, a
    // broken file) leaves the materials that use it not evaluated, not the whole asset.
    let decoded = sample::decode_each_at_most(&encoded, finest)?;
    let (textures, unreadable) = textures_of(&textures, &decoded);
    let names = nodes("materials").enumerate().map(|(i, material)| {
        (material.get("name").and_then(Node::as_str)).map_or_else(|| i.to_string(), str::to_string)
    });
    let prepared = prepare_materials(nodes("materials"), &textures, &samplers, &unreadable);
    let points = if surfaces {
        surface::surface_points(&surface::Gltf2Meshes::of(root, &views))
    } else {
        Vec::new()
    };
    Ok((names.zip(prepared).collect(), points))
}

/// Each texture's decoded image (by texture index), and why its image could not be had, from
/// the images decoded each on its own (see [`sample::decode_each_at_most`]).
pub(crate) fn textures_of(
    textures: &[Node],
    decoded: &[Result<Option<Texture>, String>],
) -> (Vec<Option<Texture>>, Vec<Option<String>>) {
    let each: Vec<Result<Option<Texture>, String>> = (textures.iter())
        .map(|texture| {
            let Some(image) = texture_source(*texture) else {
                return Ok(None);
            };
            match decoded.get(image as usize) {
                Some(Err(why)) => Err(format!("image {image}: {why}")),
                Some(Ok(texture)) => Ok(texture.clone()),
                None => Ok(None),
            }
        })
        .collect();
    let unreadable = each.iter().map(|t| t.clone().err()).collect();
    (
        each.into_iter().map(|t| t.ok().flatten()).collect(),
        unreadable,
    )
}

/// The sampler each texture (by index) reads its image through.
pub(crate) fn samplers_of(textures: &[Node], samplers: &[Node]) -> Vec<sample::Sampler> {
    (textures.iter())
        .map(|texture| {
            let index = texture.get("sampler").and_then(Node::as_u64);
            let sampler = index.and_then(|i| samplers.get(usize::try_from(i).ok()?));
            sample::Sampler::of(sampler.copied())
        })
        .collect()
}

/// Each material prepared for the evaluator with the document's textures, their samplers and
/// why a texture's image could not be had (by texture index). An asset's copies of one material share one prepared source, so 10^5
/// alike materials are prepared, held and compared once; copies that name different textures
/// of the same image and sampler are copies too (the evaluator reads the image, not the
/// texture object).
pub(crate) fn prepare_materials<'t>(
    materials: impl IntoIterator<Item = Node<'t>>,
    textures: &[Option<Texture>],
    samplers: &[sample::Sampler],
    unreadable: &[Option<String>],
) -> Vec<MaterialSource> {
    let first_alike = first_alike_textures(textures, samplers);
    let set = TextureSet {
        images: textures,
        samplers,
        unreadable,
        first_alike: &first_alike,
    };
    let mut prepared: HashMap<String, MaterialSource> = HashMap::new();
    (materials.into_iter())
        .map(|material| {
            (prepared.entry(sample::shading_text(material, &first_alike)))
                .or_insert_with(|| MaterialSource::gltf2_sampled(material, &set))
                .clone()
        })
        .collect()
}

/// For each texture index, the first index whose texture is the same decoded image read
/// through the same sampler.
fn first_alike_textures(textures: &[Option<Texture>], samplers: &[sample::Sampler]) -> Vec<usize> {
    type Key = (*const sample::TextureImage, sample::Sampler);
    let mut first: HashMap<Key, usize> = HashMap::new();
    (textures.iter().enumerate())
        .map(|(i, texture)| match texture {
            Some(texture) => {
                let sampler = samplers.get(i).copied().unwrap_or_default();
                *first.entry((Arc::as_ptr(texture), sampler)).or_insert(i)
            }
            None => i,
        })
        .collect()
}
