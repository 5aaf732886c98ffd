//! A glTF 1.0 asset's PBR-draft materials, sampled by their own model.

use super::sample::{self, MaterialSource, Texture};
use crate::document::uri::ResourceLoader;
use crate::legacy::pbr;
use crate::legacy::source::{self, NotGltf1};
use crate::shade::material::SpecGlossReading;
use crate::shade::pairing::Named;
use std::collections::HashMap;

/// Why a 1.0 asset's materials cannot be sampled.
#[derive(Debug, thiserror::Error)]
pub(crate) enum LegacyMaterialsError {
    /// Not a 1.0 asset at all: the caller may read it as 2.0.
    #[error(transparent)]
    NotGltf1(#[from] NotGltf1),
    /// A texture the materials use cannot be read or decoded.
    #[error("/textures: {0}")]
    Textures(String),
}

/// The PBR-draft materials of a glTF 1.0 asset as the shading evaluator samples them (their
/// own model), in material order, with their ids; `None` for materials without a PBR block.
/// Textures no finer than `finest` (see [`sample::decode_all_at_most`]).
pub(crate) fn legacy_materials(
    bytes: &[u8],
    loader: &dyn ResourceLoader,
    finest: u32,
) -> Result<Vec<Named>, LegacyMaterialsError> {
    let source = source::read_for_materials(bytes.into(), loader)?;
    let parsed: Vec<(&str, Option<pbr::LegacyPbr>)> = source
        .dictionary("materials")
        .into_iter()
        .map(|(id, material)| {
            let pbr = pbr::find(material).and_then(|(name, block)| pbr::parse(name, block));
            (id, pbr)
        })
        .collect();
    // Every texture the materials use, decoded once and all together.
    let texture_ids: Vec<String> = parsed
        .iter()
        .filter_map(|(_, pbr)| pbr.as_ref())
        .flat_map(|pbr| [&pbr.colour_texture, &pbr.data_texture])
        .flatten()
        .cloned()
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let position: HashMap<&str, usize> = (texture_ids.iter().enumerate())
        .map(|(at, id)| (id.as_str(), at))
        .collect();
    let encoded: Vec<sample::Wanted<_>> = texture_ids
        .iter()
        .map(|id| {
            let image = (source.object("textures", id))
                .and_then(|texture| texture.get("source")?.as_str())
                .and_then(|image| source.object("images", image))
                .ok_or_else(|| format!("texture '{id}' names no image"));
            Some(image.and_then(|image| source.image_bytes(image)))
        })
        .collect();
    let decoded =
        sample::decode_all_at_most(&encoded, finest).map_err(LegacyMaterialsError::Textures)?;
    let texture = |id: &Option<String>| -> Option<Texture> {
        decoded[*position.get(id.as_deref()?)?].clone()
    };
    // 1.0 samplers use the GL enums and defaults of 2.0's (LINEAR, REPEAT).
    let sampler = |id: &Option<String>| {
        let sampler = (id.as_deref())
            .and_then(|id| source.object("textures", id)?.get("sampler")?.as_str())
            .and_then(|sampler| source.object("samplers", sampler))
            .map(|sampler| sampler.to_value());
        sample::Sampler::of(sampler.as_ref())
    };
    Ok(parsed
        .into_iter()
        .map(|(id, pbr)| {
            let sampled = pbr.map(|pbr| MaterialSource::Legacy {
                colour: texture(&pbr.colour_texture),
                data: texture(&pbr.data_texture),
                samplers: [sampler(&pbr.colour_texture), sampler(&pbr.data_texture)],
                pbr: Box::new(pbr),
                reading: SpecGlossReading::DraftAppendix,
            });
            (id.to_string(), sampled)
        })
        .collect())
}
