//! glTF 1.0 → glTF 2.0, including the WEB3D / KHR / FRAUNHOFER / EXT `_materials_pbr` drafts.
//!
//! The conversion reads the whole 1.0 asset (`source`), rebuilds every object in 2.0 form
//! (`builder` holds the asset under construction; `convert/` has one file per step: ids become
//! indices, the old id becomes the name), converts materials (`convert/materials`, with
//! texture rebaking in `rebake`) and assembles the output ([`output`]). Every decision and everything dropped is recorded in the conversion report.
//!
//! Vertex, index, animation and skin data are repacked: each accessor gets a bufferView of
//! its own, tightly packed except where 2.0 demands 4-byte vertex alignment. That satisfies
//! every 2.0 alignment and byteStride rule by construction and splits 1.0 views shared by
//! accessors of different strides, at the price of de-interleaving interleaved vertices.

pub(crate) mod binary;
mod builder;
mod convert;
mod data;
mod fit;
mod gltf2;
pub(crate) mod json;
mod origins;
pub mod output;
mod proof;
mod rebake;
mod references;
mod spec_gloss;

use crate::document::uri::ResourceLoader;
use crate::document::{Node, Tree};
use crate::legacy::source::{self, NotGltf1};
use crate::shade::sample::{self, MaterialSource};
pub(crate) use binary::Binary;
pub use json::{Items, Json};
pub use proof::{proof_holds, prove, ProofError};
use std::borrow::Cow;
use std::collections::HashSet;
use std::sync::Arc;

pub use crate::shade::material::SpecGlossReading;

/// How specular-glossiness materials are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SpecularGlossiness {
    /// Metal-roughness (metallic 0, roughness 1 − glossiness) with KHR_materials_specular
    /// (specularColor = specular) and KHR_materials_ior (ior 0), base colour
    /// diffuse · (1 − specular) per channel; textures rebaked per texel.
    #[default]
    MetalRough,
    /// KHR_materials_pbrSpecularGlossiness: an exact rename, for legacy viewers.
    Extension,
}

/// How the converter writes what 2.0 can express in several ways.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct UpgradeOptions {
    /// Spec-gloss materials: converted to metal-rough, or kept as the extension.
    pub specular_glossiness: SpecularGlossiness,
    /// `doubleSided` for materials whose 1.0 form says nothing about culling (PBR-extension
    /// materials with no technique). Techniques decide for themselves: no CULL_FACE in
    /// their states means double-sided.
    pub double_sided_default: bool,
    /// The reading of the 1.0 PBR drafts' specular-glossiness text a conversion is exact
    /// under and its proof judged by (default: the drafts' Appendix, which the ratified
    /// KHR_materials_pbrSpecularGlossiness kept); the other readings' distance from it is
    /// reported as the source's ambiguity.
    pub draft_reading: SpecGlossReading,
}

impl Default for UpgradeOptions {
    fn default() -> Self {
        UpgradeOptions {
            specular_glossiness: SpecularGlossiness::default(),
            double_sided_default: false,
            draft_reading: SpecGlossReading::DraftAppendix,
        }
    }
}

impl UpgradeOptions {
    /// These options converting 1.0 spec-gloss drafts under `reading` (one of
    /// [`SpecGlossReading::DRAFTS`]; the archived extension's reading is the Appendix's).
    pub fn with_draft_reading(mut self, reading: SpecGlossReading) -> Self {
        self.draft_reading = match reading {
            SpecGlossReading::ArchivedExtension => SpecGlossReading::DraftAppendix,
            draft => draft,
        };
        self
    }

    /// These options writing spec-gloss materials as `mode` says.
    pub fn with_specular_glossiness(mut self, mode: SpecularGlossiness) -> Self {
        self.specular_glossiness = mode;
        self
    }

    /// These options with `doubleSided` as the default for materials that do not say.
    pub fn with_double_sided_default(mut self, double_sided: bool) -> Self {
        self.double_sided_default = double_sided;
        self
    }
}

/// One line of the conversion report: what was decided or dropped, and where (a pointer
/// into the 1.0 input).
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// A JSON pointer into the 1.0 input.
    pub pointer: String,
    /// Decision or dropped part.
    pub kind: NoteKind,
    /// What and why, for a person. Shared by every note of the same text (an asset's 10^5
    /// alike materials give 10^5 notes and one text).
    pub text: Arc<str>,
}

/// A conversion report being written: each distinct text is held once.
#[derive(Debug, Default)]
pub(crate) struct Notes {
    list: Vec<Note>,
    texts: HashSet<Arc<str>>,
}

impl Notes {
    pub(crate) fn push(&mut self, pointer: String, kind: NoteKind, text: String) {
        let text = match self.texts.get(text.as_str()) {
            Some(shared) => Arc::clone(shared),
            None => {
                let shared: Arc<str> = text.into();
                self.texts.insert(Arc::clone(&shared));
                shared
            }
        };
        self.list.push(Note {
            pointer,
            kind,
            text,
        });
    }

    pub(crate) fn into_list(self) -> Vec<Note> {
        self.list
    }
}

/// What a note records.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NoteKind {
    /// A choice the converter made (a mapping, a default written out).
    Decision,
    /// Something of the input that has no place in the output.
    Dropped,
}

/// A glTF 2.0 asset in memory: the JSON, the binary buffer, and the images (parallel to
/// `json.images`, which carry neither `uri` nor `bufferView` until [`output`] places them).
/// It also holds the input images its spec-gloss rebakes decoded, which [`crate::prove`]
/// shares: a caller keeping many upgrades keeps those texels too.
#[derive(Debug, Clone)]
pub struct Upgraded {
    /// The glTF 2.0 JSON.
    pub json: Json,
    /// The one output buffer.
    pub binary: Binary,
    /// Images, in `images` order.
    pub images: Vec<EncodedImage>,
    /// The conversion report.
    pub report: Vec<Note>,
    /// `/collection/index` of the output → the 1.0 object it was made from.
    origins: origins::Origins,
    /// Materials passed through as they were (a 2.0 input's materials that are not
    /// converted): a proof has nothing to compare for them.
    passed_through: std::collections::BTreeSet<usize>,
    /// The reading 1.0 spec-gloss drafts were converted under: the proof judges by it.
    draft_reading: SpecGlossReading,
    /// The input images the conversion decoded, held while the asset is: its proof reads
    /// the same images and shares these decodes (see `shade::sample::decode`).
    _decoded: Vec<crate::shade::sample::Texture>,
}

impl Upgraded {
    /// The 1.0 object a place in the output was made from (a JSON pointer into the input,
    /// or a short description), for telling a user which input construct an output
    /// finding comes from.
    pub fn origin_of(&self, output_pointer: &str) -> Option<&str> {
        let mut tokens = output_pointer.split('/').skip(1);
        let collection = tokens.next()?;
        self.origins.get(collection, tokens.next()?.parse().ok()?)
    }

    /// The reading 1.0 spec-gloss draft materials were converted under.
    pub fn draft_reading(&self) -> SpecGlossReading {
        self.draft_reading
    }

    /// Whether material `index` was passed through from a 2.0 input as it was, rather than
    /// converted.
    pub fn is_passed_through(&self, index: usize) -> bool {
        self.passed_through.contains(&index)
    }

    /// The asset as one GLB file in memory (JSON chunk, then geometry and images in the BIN
    /// chunk). [`output::write_checked`] writes it to disk instead, checked and atomically.
    pub fn to_glb(&self) -> Vec<u8> {
        output::layout(self, "asset.glb").main.bytes()
    }
}

/// An image of the output, encoded.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct EncodedImage {
    /// The encoded file (shared with the output's files, which are laid out around it).
    pub bytes: Arc<crate::document::Bytes>,
    /// Its media type.
    pub mime_type: String,
    /// A file name for `.gltf` output (unique within the asset).
    pub file_name: String,
    /// The image already lies in a bufferView of the output buffer (a 2.0 input's embedded
    /// image, passed through): [`output`] leaves it there and writes no file for it.
    pub in_binary: bool,
    /// Why a 2.0 input's image could not be read (a missing file, a data URI holding no
    /// image), when it could not: its `uri` is left as the input wrote it, so the output
    /// refers to it as the input does; `bytes` is empty and no file is written for it.
    pub unread: Option<String>,
}

impl EncodedImage {
    /// Image `index` of the output, its file named after `stem` and its media type.
    pub(crate) fn new(
        bytes: impl Into<Arc<crate::document::Bytes>>,
        mime_type: String,
        index: usize,
        stem: &str,
        in_binary: bool,
    ) -> Self {
        let extension = (mime_type.rsplit('/').next())
            .filter(|e| e.chars().all(|c| c.is_ascii_alphanumeric()) && !e.is_empty())
            .unwrap_or("bin")
            .replace("jpeg", "jpg");
        let safe: String = (stem.chars())
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        EncodedImage {
            bytes: bytes.into(),
            file_name: format!("{index}-{safe}.{extension}"),
            mime_type,
            in_binary,
            unread: None,
        }
    }
}

/// Why an asset could not be upgraded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum UpgradeError {
    /// Not a glTF 1.0 asset: a 2.x asset with nothing to upgrade, or a version unknown.
    #[error("not a glTF 1.0 asset: {0}")]
    NotGltf1(String),
    /// Bytes that cannot be read as a glTF document (not JSON, a broken GLB), or a glTF 2.0
    /// asset whose JSON cannot be read: why, and where.
    #[error("{0}")]
    Unreadable(String),
    /// A resource the asset needs could not be read or decoded.
    #[error("{pointer}: {reason}")]
    Resource {
        /// Where the resource is named.
        pointer: String,
        /// Why it could not be used.
        reason: String,
    },
    /// The 1.0 asset is broken where a faithful conversion needs it whole.
    #[error("{pointer}: {reason}")]
    Invalid {
        /// Where the problem is.
        pointer: String,
        /// What is wrong.
        reason: String,
    },
}

impl From<NotGltf1> for UpgradeError {
    fn from(not: NotGltf1) -> Self {
        match not {
            NotGltf1::Version(reason) => UpgradeError::NotGltf1(reason),
            NotGltf1::Unreadable(reason) | NotGltf1::BrokenGlb(reason) => {
                UpgradeError::Unreadable(reason)
            }
        }
    }
}

/// Upgrades a glTF 1.0 asset (`.gltf` text or a KHR_binary_glTF GLB v1) to glTF 2.0, or
/// retires the archived KHR_materials_pbrSpecularGlossiness in a glTF 2.0 asset (`.gltf` or
/// `.glb`): its materials become metallic-roughness + KHR_materials_specular +
/// KHR_materials_ior, and everything else passes through unchanged. External files are read
/// through `loader` (the CLI confines it to the asset's folder).
///
/// ```
/// use gltfmat::{upgrade, NoResources, UpgradeOptions};
///
/// let gltf1 = br#"{"asset": {"version": "1.0"}, "scene": "s", "scenes": {"s": {"nodes": []}},
///   "materials": {"gold": {"extensions": {"FRAUNHOFER_materials_pbr": {
///     "materialModel": "PBR_metal_roughness",
///     "values": {"baseColorFactor": [1.0, 0.77, 0.34, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.3}}}}}}"#;
/// let upgraded = upgrade(gltf1, &NoResources, &UpgradeOptions::default()).unwrap();
/// let gold = upgraded.json.items("materials").unwrap().get(0).unwrap();
/// assert_eq!(gold["name"], "gold");
/// assert_eq!(gold["pbrMetallicRoughness"]["roughnessFactor"], 0.3);
/// assert_eq!(upgraded.json.get("asset").unwrap()["version"], "2.0");
///
/// // The output, as bytes, passes its own check.
/// let glb = upgraded.to_glb();
/// let report = gltfmat::check_bytes("gold.glb", glb, &NoResources, &Default::default());
/// assert!(!report.has_errors());
///
/// // A glTF 2.0 asset: its spec-gloss material becomes metal-rough + specular + ior.
/// let gltf2 = br#"{"asset": {"version": "2.0"},
///   "extensionsUsed": ["KHR_materials_pbrSpecularGlossiness"],
///   "materials": [{"name": "plastic", "extensions": {"KHR_materials_pbrSpecularGlossiness": {
///     "diffuseFactor": [0.8, 0.1, 0.1, 1.0], "specularFactor": [0.04, 0.04, 0.04],
///     "glossinessFactor": 0.6}}}]}"#;
/// let upgraded = upgrade(gltf2, &NoResources, &UpgradeOptions::default()).unwrap();
/// let plastic = upgraded.json.items("materials").unwrap().get(0).unwrap();
/// assert_eq!(plastic["extensions"]["KHR_materials_ior"]["ior"], 0);
/// assert_eq!(plastic["extensions"]["KHR_materials_specular"]["specularColorFactor"][0], 0.04);
/// assert!((plastic["pbrMetallicRoughness"]["roughnessFactor"].as_f64().unwrap() - 0.4).abs() < 1e-12);
/// assert!(plastic["extensions"].get("KHR_materials_pbrSpecularGlossiness").is_none());
/// ```
pub fn upgrade<'b>(
    bytes: impl Into<Cow<'b, [u8]>>,
    loader: &dyn ResourceLoader,
    options: &UpgradeOptions,
) -> Result<Upgraded, UpgradeError> {
    // Bytes handed over (a `Vec`) are let go as soon as the conversion no longer needs them;
    // borrowed ones are copied only where the output shares them (a GLB's body).
    let bytes = bytes.into();
    let mut upgraded = if source::declares_gltf2(&bytes) {
        gltf2::upgrade(bytes.into_owned(), loader, options)?
    } else {
        let source = source::read(bytes, loader)?;
        convert::run(builder::Builder::new(&source, options))?
    };
    for (asked, read) in loader.letter_case_repairs() {
        let text = format!("'{asked}' names no file; '{read}', whose name differs only in letter case, is read for it, as Windows and macOS read the name (where names are case-sensitive, as on most web servers, the input's name finds nothing: `gltfmat check` reports it).");
        upgraded.report.push(Note {
            pointer: String::new(),
            kind: NoteKind::Decision,
            text: text.into(),
        });
    }
    Ok(upgraded)
}

/// The materials of an upgraded asset as the shading evaluator samples them: one whose
/// texture cannot be decoded is not evaluated there; an error when the images together pass
/// the decoding budget.
pub(crate) fn converted_materials(upgraded: &Upgraded) -> Result<Vec<MaterialSource>, String> {
    use crate::shade::load::{prepare_materials, samplers_of, textures_of, used_images};
    // The three lists the evaluator reads, parsed into the tree every reader of glTF uses.
    let mut text = String::from("{");
    for key in ["materials", "textures", "samplers"] {
        text += &format!("\"{key}\":[");
        for (i, item) in (upgraded.json.items(key).into_iter())
            .flat_map(Items::texts)
            .enumerate()
        {
            if i > 0 {
                text.push(',');
            }
            text += item;
        }
        text += "],";
    }
    text.pop();
    text.push('}');
    let tree = Tree::parse(text.as_bytes()).map_err(|e| e.to_string())?;
    drop(text);
    let list = |key: &str| -> Vec<Node> {
        (tree.root().get(key).and_then(Node::as_array).into_iter())
            .flat_map(|a| a.iter())
            .collect()
    };
    let (materials, textures) = (list("materials"), list("textures"));
    let samplers = samplers_of(&textures, &list("samplers"));
    let needed = used_images(materials.iter().copied(), &textures);
    let encoded: Vec<sample::Wanted<&[u8]>> = upgraded
        .images
        .iter()
        .enumerate()
        .map(|(i, image)| {
            let bytes = match &image.unread {
                Some(why) => Err(why.clone()),
                None => Ok(&image.bytes[..]),
            };
            needed.contains(&i).then_some(bytes)
        })
        .collect();
    // An image the evaluator cannot decode leaves the materials that use it not evaluated,
    // as on the source's side, not the whole proof.
    let decoded = sample::decode_each_at_most(&encoded, sample::AS_STORED)?;
    let (textures, unreadable) = textures_of(&textures, &decoded);
    Ok(prepare_materials(
        materials,
        &textures,
        &samplers,
        &unreadable,
    ))
}
