//! The equations: BRDF lobes, material inputs, and what they are computed with.

pub(crate) mod appearance;
pub(crate) mod brdf;
pub(crate) mod elementary;
pub(crate) mod iridescence;
pub(crate) mod lanes;
pub(crate) mod material;
pub(crate) mod quadrature;
mod sheen_charlie16;
pub(crate) mod sheen_table;
