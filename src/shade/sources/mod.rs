//! A material's inputs at a texture coordinate: textures decoded and sampled, glTF 2.0
//! and glTF 1.0 materials loaded from their asset.

pub(crate) mod legacy;
pub(crate) mod load;
pub(crate) mod sample;
pub(crate) mod surface;
mod views;
