//! glTF 1.0: reading a 1.0 asset (JSON or GLB v1, its buffers and images) and the readings
//! of the 1.0 PBR drafts, shared by check, upgrade and shade.

pub(crate) mod blend;
pub(crate) mod draft08;
pub(crate) mod pbr;
pub(crate) mod source;
