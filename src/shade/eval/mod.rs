//! The equations: BRDF lobes, material inputs, and what they are computed with.

pub mod appearance;
pub mod brdf;
pub(crate) mod elementary;
pub mod iridescence;
pub(crate) mod lanes;
pub mod material;
pub(crate) mod quadrature;
mod sheen_charlie16;
pub mod sheen_table;
