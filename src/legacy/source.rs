//! Reading a glTF 1.0 asset: JSON text or a KHR_binary_glTF GLB (version 1), its buffers, and
//! its images on demand.

use super::draft08;
use crate::document::uri::{load_uri, ResourceLoader};
use crate::document::Bytes;
use crate::document::{Node, Tree};
use serde_json::Value;
use std::borrow::Cow;
use std::cell::{OnceCell, RefCell};
use std::collections::{HashMap, HashSet};
use std::ops::Range;
use std::sync::Arc;

/// The buffer id KHR_binary_glTF gives the GLB body (and the older spelling some writers used).
const BINARY_BUFFER_IDS: &[&str] = &["binary_glTF", "KHR_binary_glTF"];

/// Why bytes are not read as a glTF 1.0 asset.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(crate) enum NotGltf1 {
    /// Another version: 2.x, or one this reader does not know.
    #[error("not a glTF 1.0 asset: {0}")]
    Version(String),
    /// Bytes that are no glTF document of any version: empty, not JSON, a JSON root that is
    /// not an object.
    #[error("{0}")]
    Unreadable(String),
    /// A GLB of version 1 (KHR_binary_glTF) whose header cannot be read: no other reader
    /// would read it.
    #[error("{0}")]
    BrokenGlb(String),
}

pub(crate) struct Source<'a> {
    /// The JSON, as the compact tree the checker reads (a `serde_json::Value` costs about ten
    /// times as much per value, and a stranger's 1.0 asset may hold millions of them).
    json: Tree,
    /// For a glTF 0.8 asset, what was read the 0.8 way (see [`draft08`]): the tree holds its
    /// 1.0 reading.
    read_as_draft_08: Option<Vec<&'static str>>,
    /// The GLB v1 body: the input's bytes, held (and shared with the output) only for a GLB;
    /// a `.gltf`'s text is let go once its tree is built.
    body: Option<Body>,
    /// External and data-URI buffers, read on first use: reading only the materials (for
    /// `--verify`) must not load the geometry.
    buffers: HashMap<String, OnceCell<Result<Arc<Bytes>, String>>>,
    /// The distinct bytes the buffers loaded (buffers naming one file share them): where
    /// each lies, and their total.
    loaded: RefCell<(HashSet<usize>, usize)>,
    pub loader: &'a dyn ResourceLoader,
}

/// A GLB v1 body and, when the file is shorter than its header declares, both lengths: a
/// view past the end then says the file was cut short rather than that the asset is wrong.
struct Body {
    file: Arc<Bytes>,
    range: Range<usize>,
    cut_short: Option<(usize, usize)>,
}

impl Body {
    fn bytes(&self) -> &[u8] {
        &self.file[self.range.clone()]
    }
}

/// Whether `bytes` declare glTF 2.x: a GLB of version 2, or JSON whose `asset.version` is
/// 2.x. Only `asset` is looked at, so this costs a scan, not a parse into values.
pub(crate) fn declares_gltf2(bytes: &[u8]) -> bool {
    if bytes.starts_with(b"glTF") {
        return bytes.get(4..8) == Some(&2u32.to_le_bytes()[..]);
    }
    #[derive(serde::Deserialize)]
    struct Head {
        asset: Option<AssetHead>,
    }
    #[derive(serde::Deserialize)]
    struct AssetHead {
        version: Option<Value>,
    }
    let head = serde_json::from_slice::<Head>(bytes).ok();
    let version = head.and_then(|h| h.asset?.version);
    version
        .as_ref()
        .and_then(Value::as_str)
        .is_some_and(|v| v.starts_with("2."))
}

/// Reads a glTF 1.0 asset. A 2.x asset is told apart by a scan, before any tree is built.
/// Bytes handed over are let go as soon as they are not needed (a `.gltf`'s once its tree is
/// built); borrowed ones are copied only for a GLB, whose body the source keeps.
pub(crate) fn read<'a>(
    bytes: Cow<'_, [u8]>,
    loader: &'a dyn ResourceLoader,
) -> Result<Source<'a>, NotGltf1> {
    read_members(bytes, loader, None)
}

/// The root members the materials and their textures are read from.
const MATERIAL_MEMBERS: &[&str] = &[
    "asset",
    "version",
    "extensionsUsed",
    "materials",
    "techniques",
    "textures",
    "images",
    "samplers",
    "bufferViews",
    "buffers",
    "shaders",
];

/// What the meshes add to [`MATERIAL_MEMBERS`], for the texels they read.
const MESH_MEMBERS: &[&str] = &["meshes", "accessors"];

/// [`read`] for reading materials only: the root members their reading needs (with `meshes`,
/// the meshes and accessors too), not the nodes and animations (10^5 of them cost a proof
/// nothing).
pub(crate) fn read_for_materials<'a>(
    bytes: Cow<'_, [u8]>,
    loader: &'a dyn ResourceLoader,
    meshes: bool,
) -> Result<Source<'a>, NotGltf1> {
    let mut keep = MATERIAL_MEMBERS.to_vec();
    if meshes {
        keep.extend(MESH_MEMBERS);
    }
    read_members(bytes, loader, Some(&keep))
}

fn read_members<'a>(
    bytes: Cow<'_, [u8]>,
    loader: &'a dyn ResourceLoader,
    keep: Option<&[&str]>,
) -> Result<Source<'a>, NotGltf1> {
    if declares_gltf2(&bytes) {
        return Err(NotGltf1::Version(IS_GLTF2.into()));
    }
    if bytes.is_empty() {
        return Err(NotGltf1::Unreadable("the file is empty".into()));
    }
    let (json_range, body) = if bytes.starts_with(b"glTF") {
        let (json, body) = split_glb_v1(&bytes)?;
        (json, Some(body))
    } else {
        (0..bytes.len(), None)
    };
    let json = match keep {
        Some(keep) => Tree::parse_members(&bytes[json_range], keep),
        None => Tree::parse(&bytes[json_range]),
    };
    let json = json.map_err(|e| NotGltf1::Unreadable(format!("invalid JSON: {e}")))?;
    let body = body.map(|(range, cut_short)| Body {
        file: Arc::new(bytes.into_owned().into()),
        range,
        cut_short,
    });
    let root = json.root();
    if !root.is_object() {
        return Err(NotGltf1::Unreadable(
            "its JSON root is not an object".into(),
        ));
    }
    check_version(root)?;
    let (json, read_as_draft_08) = match draft08::declares(root) {
        false => (json, None),
        true => {
            let (value, read) = draft08::as_1_0(root);
            let text =
                serde_json::to_vec(&value).map_err(|e| NotGltf1::Unreadable(e.to_string()))?;
            let json = Tree::parse(&text)
                .map_err(|e| NotGltf1::Unreadable(format!("invalid JSON: {e}")))?;
            (json, Some(read))
        }
    };
    let root = json.root();
    crate::document::uri::note_named_files(root, loader);
    let buffers = (root.get("buffers").and_then(Node::as_object))
        .map(|b| {
            b.keys()
                .map(|id| (id.to_string(), OnceCell::new()))
                .collect()
        })
        .unwrap_or_default();
    Ok(Source {
        json,
        read_as_draft_08,
        body,
        buffers,
        loaded: RefCell::default(),
        loader,
    })
}

/// A body's place in the file, and the declared and actual lengths when it is cut short.
type BodyPlace = (Range<usize>, Option<(usize, usize)>);

/// Header: magic, version 1, total length, content length, content format 0 (JSON). Returns
/// where the JSON and the body lie.
fn split_glb_v1(bytes: &[u8]) -> Result<(Range<usize>, BodyPlace), NotGltf1> {
    let word = |at: usize| -> Option<u32> {
        Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
    };
    let broken = |why: String| NotGltf1::BrokenGlb(format!("GLB v1: {why}"));
    let cut = || {
        broken(format!(
            "its 20-byte header is cut short ({} bytes)",
            bytes.len()
        ))
    };
    let version = word(4).ok_or_else(cut)?;
    if version != 1 {
        return Err(NotGltf1::Version(format!(
            "GLB version {version} (byte 4); only version 1 (KHR_binary_glTF) is upgraded"
        )));
    }
    let (length, content_length, format) = (
        word(8).ok_or_else(cut)? as usize,
        word(12).ok_or_else(cut)? as usize,
        word(16).ok_or_else(cut)?,
    );
    if format != 0 {
        return Err(broken(format!(
            "content format {format} (byte 16) is not JSON (0)"
        )));
    }
    let cut_short = (length > bytes.len()).then_some((length, bytes.len()));
    let length = length.min(bytes.len());
    let content_end = 20usize
        .checked_add(content_length)
        .filter(|end| *end <= length)
        .ok_or_else(|| {
            broken(format!(
                "content length {content_length} (byte 12) runs past the end of the file ({length} bytes)"
            ))
        })?;
    Ok((20..content_end, (content_end..length, cut_short)))
}

const IS_GLTF2: &str = "asset.version is 2.x: nothing to upgrade (use `gltfmat check`)";

fn check_version(root: Node) -> Result<(), NotGltf1> {
    let version =
        (root.get("asset").and_then(|a| a.get("version"))).or_else(|| root.get("version"));
    let major = match version {
        None => return Ok(()), // 1.0 assets may omit it; 2.0 ones may not.
        Some(v) if v.is_string() => v
            .as_str()
            .and_then(|s| s.split('.').next())
            .unwrap_or_default()
            .to_string(),
        Some(v) if v.is_number() => v.as_f64().map_or(String::new(), |v| (v as u64).to_string()),
        Some(other) => other.to_string(),
    };
    match major.as_str() {
        "0" | "1" => Ok(()),
        "2" => Err(NotGltf1::Version(IS_GLTF2.into())),
        other => Err(NotGltf1::Version(format!(
            "unknown asset.version '{other}'"
        ))),
    }
}

impl Source<'_> {
    /// The asset's JSON root.
    pub(crate) fn root(&self) -> Node<'_> {
        self.json.root()
    }

    /// For a glTF 0.8 asset, what was read the 0.8 way, in words; `None` for any other.
    pub(crate) fn read_as_draft_08(&self) -> Option<&[&'static str]> {
        self.read_as_draft_08.as_deref()
    }

    /// A buffer's bytes: the GLB body for KHR_binary_glTF's buffer, otherwise its `uri`, read
    /// once.
    fn buffer(&self, id: &str) -> Result<&[u8], String> {
        if let Some(body) = self.binary_body(id) {
            return Ok(body.bytes());
        }
        let cell = self
            .buffers
            .get(id)
            .ok_or_else(|| format!("buffer '{id}' does not exist"))?;
        let loaded = cell.get_or_init(|| {
            let uri = (self.root().pointer("/buffers"))
                .and_then(|buffers| buffers.get(id)?.get("uri")?.as_str());
            let bytes = uri
                .ok_or_else(|| "the buffer has no uri".to_string())
                .and_then(|uri| self.load_uri(uri))?;
            let (places, total) = &mut *self.loaded.borrow_mut();
            if places.insert(bytes.as_ptr() as usize) {
                *total += bytes.len();
            }
            Ok(bytes)
        });
        loaded.as_deref().map(|b| &b[..]).map_err(Clone::clone)
    }

    /// The GLB v1 body when `id` names KHR_binary_glTF's buffer.
    fn binary_body(&self, id: &str) -> Option<&Body> {
        self.body
            .as_ref()
            .filter(|_| BINARY_BUFFER_IDS.contains(&id))
    }

    /// The held bytes (a loaded buffer, or the GLB file) that hold `part`, and where: such
    /// bytes can go to the output by reference. None for foreign slices.
    pub(crate) fn shared(&self, part: &[u8]) -> Option<(Arc<Bytes>, Range<usize>)> {
        let start = part.as_ptr() as usize;
        let loaded = self
            .buffers
            .values()
            .filter_map(|cell| cell.get()?.as_ref().ok());
        let held = loaded.chain(self.body.as_ref().map(|body| &body.file));
        held.into_iter().find_map(|buffer| {
            let base = buffer.as_ptr() as usize;
            let inside = start >= base && start + part.len() <= base + buffer.len();
            inside.then(|| (Arc::clone(buffer), start - base..start - base + part.len()))
        })
    }

    /// How many distinct bytes of data are loaded: what the buffers read so far (a file
    /// that several buffers name, once), and a GLB's body. Kept as buffers load: the
    /// upgrade asks once an accessor.
    pub(crate) fn loaded_bytes(&self) -> usize {
        self.loaded.borrow().1 + self.body.as_ref().map_or(0, |body| body.range.len())
    }

    /// Reads a data URI or a file inside the asset's folder.
    pub(crate) fn load_uri(&self, uri: &str) -> Result<Arc<Bytes>, String> {
        load_uri(uri, self.loader)
    }

    /// A 1.0 dictionary (`accessors`, `nodes`, …) in document order.
    pub(crate) fn dictionary(&self, name: &str) -> Vec<(&str, Node<'_>)> {
        (self.root().get(name).and_then(Node::as_object))
            .map(|map| map.iter().collect())
            .unwrap_or_default()
    }

    pub(crate) fn object(&self, collection: &str, id: &str) -> Option<Node<'_>> {
        self.root().get(collection)?.get(id)
    }

    /// The sampler object texture `texture` names, if it names one that exists.
    pub(crate) fn texture_sampler(&self, texture: &str) -> Option<Node<'_>> {
        let sampler = self.object("textures", texture)?.get("sampler")?.as_str()?;
        self.object("samplers", sampler)
    }

    /// The bytes of a bufferView.
    pub(crate) fn view(&self, id: &str) -> Result<&[u8], String> {
        let view = self
            .object("bufferViews", id)
            .ok_or_else(|| format!("bufferView '{id}' does not exist"))?;
        let buffer_id = view.get("buffer").and_then(Node::as_str).unwrap_or("");
        let buffer = self.buffer(buffer_id)?;
        let offset = view.get("byteOffset").and_then(Node::as_u64).unwrap_or(0);
        let length = match view.get("byteLength").and_then(Node::as_u64) {
            Some(n) => n,
            None => (buffer.len() as u64).saturating_sub(offset),
        };
        let end = offset
            .checked_add(length)
            .filter(|end| *end <= buffer.len() as u64)
            .ok_or_else(|| self.past_the_end(id, offset, length, buffer_id, buffer.len()))?;
        Ok(&buffer[offset as usize..end as usize])
    }

    /// Why a view does not fit its buffer, with the figures a user needs to find the cause.
    fn past_the_end(
        &self,
        id: &str,
        offset: u64,
        length: u64,
        buffer_id: &str,
        has: usize,
    ) -> String {
        let cause = match self.binary_body(buffer_id).and_then(|body| body.cut_short) {
            Some((declared, actual)) => format!(
                ": the GLB file is {actual} bytes but its header declares {declared}, so it was cut \
                 short (or altered by a text-mode copy)"
            ),
            None => String::new(),
        };
        format!(
            "bufferView '{id}' (byteOffset {offset}, byteLength {length}) runs past the end of \
             buffer '{buffer_id}', which holds {has} bytes{cause}"
        )
    }

    /// The bytes of a 1.0 image: KHR_binary_glTF bufferView, data URI or file.
    pub(crate) fn image_bytes(&self, image: Node) -> Result<Arc<Bytes>, String> {
        let binary = image
            .get("extensions")
            .and_then(|e| e.get("KHR_binary_glTF"));
        if let Some(view) = binary
            .and_then(|b| b.get("bufferView"))
            .and_then(Node::as_str)
        {
            return self.view(view).map(|bytes| Arc::new(bytes.to_vec().into()));
        }
        let uri = image
            .get("uri")
            .and_then(Node::as_str)
            .ok_or("the image has no uri")?;
        self.load_uri(uri)
    }
}
