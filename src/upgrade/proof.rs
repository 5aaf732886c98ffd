//! An upgrade's proof: every source material that has a model of its own (a 1.0 asset's
//! PBR-draft materials, every converted material of a 2.0 asset) compared with its
//! conversion by the reference evaluator, the source read as it was converted (a 1.0
//! spec-gloss draft under the upgrade's draft reading); how far the drafts' other readings
//! are from that one is given beside, as the source's own ambiguity.

use super::{converted_materials, Upgraded};
use crate::document::uri::ResourceLoader;
use crate::shade::pairing::{self, compare_pairs, Named, Outcome, TexelMap};
use crate::shade::sample::AS_STORED;

/// Why a proof could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ProofError {
    /// The input's materials cannot be evaluated (an unreadable texture, say).
    #[error("the source materials cannot be evaluated: {0}")]
    Source(String),
    /// The upgraded asset's materials cannot be evaluated.
    #[error("the converted materials cannot be evaluated: {0}")]
    Converted(String),
}

/// Proves `upgraded`, made from `input` (named `name`, its files read through `loader`; the
/// bytes are read into the proof's own tree, so a caller done with them hands them over):
/// one outcome per converted material.
pub fn prove<'b>(
    input: impl Into<std::borrow::Cow<'b, [u8]>>,
    name: &str,
    loader: &dyn ResourceLoader,
    upgraded: &Upgraded,
) -> Result<Vec<Outcome>, ProofError> {
    // Conversions keep the geometry: where texCoord sets differ, the points are the source's.
    let (sources, surfaces) =
        pairing::load_materials(input.into().into_owned(), name, loader, AS_STORED, true)
            .map_err(ProofError::Source)?;
    let reading = upgraded.draft_reading();
    let sources: Vec<Named> = (sources.into_iter())
        .map(|(name, source)| (name, source.map(|s| s.read_as(reading))))
        .collect();
    let converted = converted_materials(upgraded).map_err(ProofError::Converted)?;
    let converted: Vec<Named> = (converted.into_iter().zip(&sources))
        .map(|(target, (name, _))| (name.clone(), Some(target)))
        .collect();
    let pairs: Vec<(usize, usize)> = (0..sources.len().min(converted.len()))
        .filter(|&i| !upgraded.is_passed_through(i))
        .map(|i| (i, i))
        .collect();
    Ok(compare_pairs(
        &sources,
        &converted,
        &pairs,
        &surfaces,
        0,
        TexelMap::Dropped,
    ))
}

/// Whether a proof holds at `threshold`: every pair that was evaluated is the same. A 1.0
/// material drawn by a technique's shaders or KHR_materials_common's lighting is compared by
/// its emission and coverage alone, and holds when those are within `threshold`: its
/// conversion changes the lighting model by design, as its decision line states, and no
/// figure could judge that. A 1.0 material nothing can be read of (a technique id that
/// names nothing, an unreadable texture) is not evaluated and does not fail it. A pair
/// evaluated in part for any other reason (an input the evaluator does not model) is never
/// the same, and fails it.
pub fn proof_holds(proof: &[Outcome], threshold: f64) -> bool {
    (proof.iter())
        .filter(|o| o.is_evaluated())
        .all(|o| match o.only_lighting_unread() {
            true => o.result.max <= threshold,
            false => o.same(threshold),
        })
}
