//! The conversion steps, in the order their indices depend on each other: samplers and images
//! before textures, textures before materials, accessors (repacked on first use) with the
//! meshes, nodes before skins and animations, scenes last.

mod animations;
mod cameras;
mod extensions;
mod images;
mod lights;
pub(super) mod materials;
mod meshes;
mod nodes;
mod unused;

use super::builder::{self, Builder};
use super::{UpgradeError, Upgraded};

/// An `asset.version` other than 1.0: a 0.8 asset is read as the 1.0 it became (see
/// [`draft08`](crate::legacy::draft08)), and the report names what was read the 0.8 way; any
/// other (0.x, a 1.1 draft) is converted by the 1.0 text, and the report says that what the
/// draft changed is not read rather than convert it silently.
fn note_version(builder: &mut Builder) {
    if let Some(read) = builder.source.read_as_draft_08() {
        let read = match read.is_empty() {
            true => "nothing in it is written the 0.8 way".to_string(),
            false => read.join("; "),
        };
        let why = format!(
            "asset.version is 0.8: read as the glTF 1.0 it became ({read}), then converted as 1.0."
        );
        builder.note("/asset/version", super::NoteKind::Decision, why);
        return;
    }
    let root = builder.source.root();
    let version = (root.get("asset").and_then(|a| a.get("version"))).map(|v| {
        v.as_str()
            .map_or_else(|| v.to_value().to_string(), str::to_string)
    });
    if let Some(version) = version.filter(|v| !matches!(v.as_str(), "1.0" | "1" | "1.0.0")) {
        builder.note(
            "/asset/version",
            super::NoteKind::Decision,
            format!("asset.version is '{version}', not 1.0: converted as glTF 1.0; what that version changed from 1.0 is not read, so compare the output with the viewer the asset was made for."),
        );
    }
}

/// Runs every step on `builder` and finishes the asset.
pub(super) fn run(mut builder: Builder) -> Result<Upgraded, UpgradeError> {
    note_version(&mut builder);
    builder.samplers();
    builder.images()?;
    builder.textures();
    for (id, material) in builder.source.dictionary("materials") {
        let converted = materials::convert(&mut builder, id, material)?;
        builder.push_from("materials", converted, builder::pointer("materials", id));
    }
    builder.meshes()?;
    builder.cameras();
    builder.nodes()?;
    builder.unplaced_lights();
    builder.animations()?;
    builder.scenes();
    builder.dropped_collections();
    builder.unconverted_extensions();
    builder.drop_unused_textures();
    let mut used = materials::extensions_used(builder.arrays.get("materials"));
    if builder.arrays.contains_key("lights") {
        used.push(lights::PUNCTUAL.to_string());
    }
    let mut root_extensions = serde_json::Map::new();
    if let Some(rtc) = builder.cesium_rtc() {
        used.push(extensions::CESIUM_RTC.to_string());
        root_extensions.insert(extensions::CESIUM_RTC.to_string(), rtc);
    }
    used.sort();
    Ok(builder.finish(used, root_extensions))
}
