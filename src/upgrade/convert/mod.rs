//! The conversion steps, in the order their indices depend on each other: samplers and images
//! before textures, textures before materials, accessors (repacked on first use) with the
//! meshes, nodes before skins and animations, scenes last.

mod animations;
mod cameras;
mod images;
pub(super) mod materials;
mod meshes;
mod nodes;

use super::builder::Builder;
use super::{UpgradeError, Upgraded};

/// Runs every step on `builder` and finishes the asset.
pub(super) fn run(mut builder: Builder) -> Result<Upgraded, UpgradeError> {
    builder.samplers();
    builder.images()?;
    builder.textures();
    for (id, material) in builder.source.dictionary("materials") {
        let converted = materials::convert(&mut builder, id, material)?;
        builder.push("materials", converted);
    }
    builder.meshes()?;
    builder.cameras();
    builder.nodes()?;
    builder.animations()?;
    builder.scenes();
    builder.dropped_collections();
    let used = materials::extensions_used(
        builder
            .arrays
            .get("materials")
            .map_or(&[][..], Vec::as_slice),
    );
    Ok(builder.finish(used))
}
