//! glTF 1.0: the readings of the 1.0 PBR drafts shared by check, upgrade and shade.

pub mod pbr;
