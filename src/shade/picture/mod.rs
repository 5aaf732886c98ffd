//! Pictures of materials: balls under a sky, contact sheets, heat maps, and their labels.

pub(crate) mod label;
pub(crate) mod render;
