//! The reference shading evaluator: f64 BRDFs written from the specification equations,
//! sheen albedo tables computed by quadrature, and (in later work) renders and comparisons.

pub mod brdf;
pub mod compare;
pub(crate) mod delta_e;
pub(crate) mod elementary;
pub(crate) mod label;
pub(crate) mod lanes;
pub(crate) mod load;
pub mod material;
pub mod pairing;
pub(crate) mod quadrature;
pub mod render;
pub(crate) mod sample;
pub mod tone;

pub use sample::MaterialSource;
pub mod sheen_table;
