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

/// Runs every step on `builder` and finishes the asset.
pub(super) fn run(mut builder: Builder) -> Result<Upgraded, UpgradeError> {
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
        used.sort();
    }
    Ok(builder.finish(used))
}
