//! An upgrade's proof: every source material that has a model of its own (a 1.0 asset's
//! PBR-draft materials, every converted material of a 2.0 asset) compared with its
//! conversion by the reference evaluator, under every reading of the source's text, the
//! worst reading kept and named.

use super::{converted_materials, Upgraded};
use crate::document::uri::ResourceLoader;
use crate::shade::pairing::{self, compare_pairs, Named, Outcome};
use crate::shade::MaterialSource;

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

/// Proves `upgraded`, made from `input` (named `name`, its files read through `loader`):
/// one outcome per converted material, the worst of its source's readings.
pub fn prove(
    input: &[u8],
    name: &str,
    loader: &dyn ResourceLoader,
    upgraded: &Upgraded,
) -> Result<Vec<Outcome>, ProofError> {
    let sources =
        pairing::load_materials(input.to_vec(), name, loader).map_err(ProofError::Source)?;
    let converted = converted_materials(upgraded).map_err(ProofError::Converted)?;
    let converted: Vec<Named> = (converted.into_iter().zip(&sources))
        .map(|(target, (name, _))| (name.clone(), Some(target)))
        .collect();
    let pairs: Vec<(usize, usize)> = (0..sources.len().min(converted.len()))
        .filter(|&i| !upgraded.is_passed_through(i))
        .map(|i| (i, i))
        .collect();
    Ok(worst_readings(&sources, &converted, &pairs))
}

/// Each pair compared under every reading of its source's text (one comparison per reading
/// for all pairs together, so that identical pairs are evaluated once); the worst reading of
/// each, named in its label.
fn worst_readings(
    sources: &[Named],
    converted: &[Named],
    pairs: &[(usize, usize)],
) -> Vec<Outcome> {
    let readings: Vec<Vec<MaterialSource>> = (sources.iter())
        .map(|(_, source)| {
            source
                .as_ref()
                .map(MaterialSource::readings)
                .unwrap_or_default()
        })
        .collect();
    let most = readings.iter().map(Vec::len).max().unwrap_or(0);
    let mut worst: std::collections::BTreeMap<usize, Outcome> = Default::default();
    for r in 0..most {
        let read: Vec<Named> = (sources.iter().zip(&readings))
            .map(|((name, _), all)| {
                let Some(reading) = all.get(r) else {
                    return (name.clone(), None);
                };
                let label = match reading.reading_name() {
                    Some(how) => format!("{name} (source read as: {how})"),
                    None => name.clone(),
                };
                (label, Some(reading.clone()))
            })
            .collect();
        for outcome in compare_pairs(&read, converted, pairs, 0) {
            let kept = worst.get(&outcome.a.0);
            if kept.is_none_or(|kept| outcome.result.max > kept.result.max) {
                worst.insert(outcome.a.0, outcome);
            }
        }
    }
    worst.into_values().collect()
}
