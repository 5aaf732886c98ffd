//! The reference shading evaluator: f64 BRDFs written from the specification equations,
//! sheen albedo tables computed by quadrature, materials sampled from their textures, and
//! what is built on them: comparisons (ΔE2000 on what a viewer shows) and pictures.
//!
//! - `eval/`: the equations. BRDF lobes, material inputs and their readings, the lanes the
//!   lobes are evaluated on, elementary functions, quadrature and the sheen table.
//! - `sources/`: a material's inputs at a texture coordinate (decoding, sampling, loading a
//!   glTF 2.0 asset's or a 1.0 asset's PBR-draft materials).
//! - `compare.rs`, `delta_e.rs`, `tone.rs`: the figure of merit.
//! - `picture/`: material balls, contact sheets and their labels.
//! - `pairing.rs`: whole assets' materials paired and compared or rendered.
//!
//! The modules keep their paths under `shade::` (re-exported below), so callers name
//! `shade::brdf` wherever the file lives.

mod eval;
mod picture;
mod sources;

pub(crate) mod compare;
pub(crate) mod delta_e;
pub(crate) mod pairing;
pub(crate) mod tone;

pub(crate) use eval::{appearance, brdf, iridescence, material, sheen_table};
pub(crate) use eval::{elementary, lanes};
pub(crate) use picture::render;
pub(crate) use sources::{legacy, load, sample, surface};
