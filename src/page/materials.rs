//! A checked asset's materials on the page: each one's ball, its parameters, and its texture
//! slots with a thumbnail of each image, the channels the slot reads, their colour space and
//! the findings that concern it.

use super::html::{anchor_of, escape, png_data_uri};
use crate::check::Report;
use crate::document::uri::{load_uri, FolderResources, NoResources, ResourceLoader};
use crate::document::{Container, Node};
use crate::gltf::material::{drawn_image, Channels, TEXTURE_SLOTS};
use crate::shade::pairing::{render_each, Ball};
use crate::shade::sample::{decode_each_at_most, Wanted};
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;

/// At most this many materials of one asset are shown (the rest are counted): a page stays
/// small whatever the asset holds.
const MATERIALS_SHOWN: usize = 64;
/// Parameters shown of a material's JSON, in characters.
const PARAMETERS_SHOWN: usize = 2000;

/// The asset's material cards: balls only when `draw` and the asset is a file.
pub(super) fn cards(
    report: &Report,
    path: Option<&Path>,
    groups: &BTreeMap<String, Vec<usize>>,
    draw: bool,
    ball: u32,
    thumbnail: u32,
) -> String {
    let Some(tree) = report.document.root.as_ref() else {
        return String::new();
    };
    let root = tree.root();
    let items = |key: &str| root.get(key).and_then(Node::as_array);
    let Some(materials) = items("materials").filter(|m| !m.is_empty()) else {
        return String::new();
    };
    let balls: Vec<Ball> = match (draw, path) {
        (true, Some(path)) => render_each(path, ball, MATERIALS_SHOWN).unwrap_or_default(),
        _ => Vec::new(),
    };
    let folder: Box<dyn ResourceLoader> = match path {
        Some(path) => Box::new(FolderResources::beside(path)),
        None => Box::new(NoResources),
    };
    let mut images = Thumbnails {
        report,
        loader: folder.as_ref(),
        size: thumbnail,
        made: HashMap::new(),
    };
    let mut out = String::from("<h3>Materials</h3>");
    for (index, material) in materials.iter().enumerate().take(MATERIALS_SHOWN) {
        out += &card(
            index,
            material,
            balls.get(index),
            groups,
            &report.uri,
            &mut images,
            root,
        );
    }
    if materials.len() > MATERIALS_SHOWN {
        let _ = write!(
            out,
            "<p>… and {} more materials.</p>",
            materials.len() - MATERIALS_SHOWN
        );
    }
    out
}

#[allow(clippy::too_many_arguments)]
fn card(
    index: usize,
    material: Node,
    ball: Option<&Ball>,
    groups: &BTreeMap<String, Vec<usize>>,
    uri: &str,
    images: &mut Thumbnails,
    root: Node,
) -> String {
    let name = material
        .get("name")
        .and_then(Node::as_str)
        .map_or_else(|| index.to_string(), str::to_string);
    let picture = ball_figure(index, &name, ball);
    let group = format!("materials/{index}");
    let said = groups.get(&group).map_or(0, Vec::len);
    let findings_link = match said {
        0 => String::new(),
        n => format!(
            " · <a href=\"#{}\">{n} finding(s)</a>",
            anchor_of(uri, &group)
        ),
    };
    let parameters = shown_parameters(material);
    let mut slots = String::new();
    for slot in TEXTURE_SLOTS {
        let Some(info) = slot.lookup(material) else {
            continue;
        };
        let texture = info.get("index").and_then(Node::as_u64);
        let texture_node = texture.and_then(|t| root.get("textures")?.as_array()?.get(t as usize));
        let image = texture_node.and_then(drawn_image);
        let (srgb, linear) = slot.reads(material);
        let space = match (srgb, linear) {
            (0, _) => format!("{} as data (linear)", channel_names(linear)),
            (_, 0) => format!("{} as sRGB colour", channel_names(srgb)),
            _ => format!(
                "{} as sRGB colour, {} as data",
                channel_names(srgb),
                channel_names(linear)
            ),
        };
        let slot_pointer = format!("/materials/{index}{}", slot.pointer());
        let concerns = slot_concerns(images.report, groups, &group, &slot_pointer, texture, image);
        let thumb = match image {
            Some(i) => images.of(i as usize, slot.key),
            None => "no image".into(),
        };
        let _ = write!(
            slots,
            "<tr><th scope=\"row\">{}</th><td>{thumb}</td><td>texture {} → image {}, texCoord {}</td><td>{}</td><td>{concerns}</td></tr>",
            slot.key,
            texture.map_or("?".into(), |t| t.to_string()),
            image.map_or("?".into(), |i| i.to_string()),
            crate::gltf::material::effective_texcoord(info),
            escape(&space)
        );
    }
    let slots = match slots.is_empty() {
        true => "<p>No textures.</p>".to_string(),
        false => format!("<table><thead><tr><th scope=\"col\">slot</th><th scope=\"col\">image</th><th scope=\"col\">reads</th><th scope=\"col\">channels</th><th scope=\"col\">findings</th></tr></thead><tbody>{slots}</tbody></table>"),
    };
    format!(
        "<div class=\"material\">{picture}<div><h4>material {index}: {}{findings_link}</h4>{slots}<details><summary>parameters</summary><pre>{}</pre></details></div></div>",
        escape(&name),
        escape(&parameters)
    )
}

/// The material's ball, or why it is not drawn (nothing without a ball).
fn ball_figure(index: usize, name: &str, ball: Option<&Ball>) -> String {
    match ball {
        Some(Ball {
            image: Some(image),
            not_drawn,
            ..
        }) => {
            let missing = match not_drawn.is_empty() {
                true => String::new(),
                false => format!("<br>not drawn: {}", escape(&not_drawn.join("; "))),
            };
            format!(
                "<figure><img src=\"{}\" width=\"{w}\" height=\"{w}\" alt=\"material {index} ({}) rendered as a ball\"><figcaption>rendered{missing}</figcaption></figure>",
                png_data_uri(image),
                escape(name),
                w = image.width()
            )
        }
        Some(Ball { not_drawn, .. }) => format!(
            "<figure><figcaption>not drawn: {}</figcaption></figure>",
            escape(&not_drawn.join("; "))
        ),
        None => String::new(),
    }
}

/// The material's JSON, pretty-printed, cut at [`PARAMETERS_SHOWN`] characters.
fn shown_parameters(material: Node) -> String {
    let mut parameters = serde_json::to_string_pretty(&material).unwrap_or_default();
    if parameters.len() > PARAMETERS_SHOWN {
        let cut = (0..=PARAMETERS_SHOWN)
            .rev()
            .find(|&i| parameters.is_char_boundary(i))
            .unwrap_or(0);
        parameters.truncate(cut);
        parameters += "\n…";
    }
    parameters
}

/// Links to the codes of the findings that concern a texture slot: those of the material
/// (`group`) at the slot's pointer or under it, and those of its texture and image.
fn slot_concerns(
    report: &Report,
    groups: &BTreeMap<String, Vec<usize>>,
    group: &str,
    slot_pointer: &str,
    texture: Option<u64>,
    image: Option<u64>,
) -> String {
    let mut concerns: Vec<String> = Vec::new();
    let findings_of = |key: &str| -> Vec<usize> { groups.get(key).cloned().unwrap_or_default() };
    for i in findings_of(group) {
        let finding = report.diagnostics.get(i);
        if let Some(p) = finding.and_then(|f| f.pointer()) {
            if p.starts_with(slot_pointer) {
                concerns.extend(finding.map(|f| f.code.name().to_string()));
            }
        }
    }
    let keys = [
        texture.map(|t| format!("textures/{t}")),
        image.map(|i| format!("images/{i}")),
    ];
    for key in keys.into_iter().flatten() {
        concerns.extend(
            (findings_of(&key).iter())
                .filter_map(|&i| report.diagnostics.get(i))
                .map(|f| f.code.name().to_string()),
        );
    }
    concerns.sort();
    concerns.dedup();
    (concerns.iter())
        .map(|c| format!("<a class=\"code\" href=\"#code-{c}\">{c}</a>"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn channel_names(channels: Channels) -> String {
    ["R", "G", "B", "A"]
        .iter()
        .enumerate()
        .filter(|(bit, _)| channels & (1 << bit) != 0)
        .map(|(_, name)| *name)
        .collect()
}

/// Each image's thumbnail, made once however many slots show it.
struct Thumbnails<'r> {
    report: &'r Report,
    loader: &'r dyn ResourceLoader,
    size: u32,
    made: HashMap<usize, String>,
}

impl Thumbnails<'_> {
    fn of(&mut self, image: usize, slot: &str) -> String {
        if let Some(made) = self.made.get(&image) {
            return made.clone();
        }
        let html = match self.decode(image) {
            Ok(thumbnail) => {
                // Shown at the thumbnail's size whatever the image's: a 4² image is not a dot.
                let (w, h) = (thumbnail.width(), thumbnail.height());
                let scale = f64::from(self.size) / f64::from(w.max(h));
                let shown = |n: u32| ((f64::from(n) * scale).round() as u32).max(1);
                format!(
                    "<img src=\"{}\" width=\"{}\" height=\"{}\" class=\"pixelated\" alt=\"image {image}, as the file stores it, read by {slot}\">",
                    png_data_uri(&thumbnail),
                    shown(w),
                    shown(h)
                )
            }
            Err(why) => format!("no preview: {}", escape(&why)),
        };
        self.made.insert(image, html.clone());
        html
    }

    /// The image decoded no finer than the thumbnail needs (the evaluator's bounded decoding).
    fn decode(&self, image: usize) -> Result<image::RgbaImage, String> {
        let bytes = self.bytes(image)?;
        let wanted: [Wanted<Arc<crate::document::Bytes>>; 1] = [Some(Ok(bytes))];
        let decoded = decode_each_at_most(&wanted, self.size)?;
        match decoded.into_iter().next() {
            Some(Ok(Some(texture))) => Ok(texture.thumbnail(self.size)),
            Some(Err(why)) => Err(why),
            _ => Err("not decoded".into()),
        }
    }

    /// An image's encoded bytes: its URI (a data URI or a file in the asset's folder), or its
    /// bufferView in the GLB's BIN chunk or in a buffer file.
    fn bytes(&self, image: usize) -> Result<Arc<crate::document::Bytes>, String> {
        let doc = &self.report.document;
        let root = doc.root.as_ref().ok_or("no JSON")?.root();
        let at = |key: &str, i: u64| {
            root.get(key)
                .and_then(Node::as_array)
                .and_then(|a| a.get(i as usize))
        };
        let node = at("images", image as u64).ok_or("no such image")?;
        if let Some(uri) = node.get("uri").and_then(Node::as_str) {
            return load_uri(uri, self.loader);
        }
        let view = node
            .get("bufferView")
            .and_then(Node::as_u64)
            .and_then(|v| at("bufferViews", v))
            .ok_or("no bufferView")?;
        let buffer = view
            .get("buffer")
            .and_then(Node::as_u64)
            .ok_or("no buffer")?;
        let start = view.get("byteOffset").and_then(Node::as_u64).unwrap_or(0) as usize;
        let end = start
            .checked_add(
                view.get("byteLength")
                    .and_then(Node::as_u64)
                    .ok_or("no byteLength")? as usize,
            )
            .ok_or("too long")?;
        let buffer_uri = at("buffers", buffer)
            .and_then(|b| b.get("uri"))
            .and_then(Node::as_str);
        let data: Arc<crate::document::Bytes> = match buffer_uri {
            Some(uri) => load_uri(uri, self.loader)?,
            None if buffer == 0 && doc.container == Container::Glb => {
                let bin = doc.bin().ok_or("the BIN chunk is not held in memory")?;
                return bin
                    .get(start..end)
                    .map(|b| Arc::new(b.to_vec().into()))
                    .ok_or_else(|| "outside the BIN chunk".into());
            }
            None => return Err("its buffer has no data".into()),
        };
        data.get(start..end)
            .map(|b| Arc::new(b.to_vec().into()))
            .ok_or_else(|| "outside its buffer".into())
    }
}
