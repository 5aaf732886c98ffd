//! The reference shading evaluator: f64 BRDFs written from the specification equations,
//! sheen albedo tables computed by quadrature, and (in later work) renders and comparisons.

pub mod brdf;
pub mod compare;
pub mod delta_e;
pub mod elementary;
pub mod label;
pub mod lanes;
pub mod load;
pub mod material;
pub mod pairing;
pub mod quadrature;
pub mod render;
pub mod sample;
pub mod sheen_table;
