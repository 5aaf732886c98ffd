//! The gltfmat codes a Khronos parity pass emits itself, because the finding is made where the
//! pass resolves a URI. Their rules (`rules/outside_folder.rs`, `rules/resource_not_read.rs`)
//! document them; the codes live here so that the passes name them without importing the
//! rules, which read what the passes found.

use crate::diagnostic::{Code, Severity};

/// A URI that resolves outside the asset's folder, refused unread.
pub(super) const URI_OUTSIDE_ASSET_FOLDER: Code =
    Code::new("URI_OUTSIDE_ASSET_FOLDER", Severity::Error);

/// A relative URI of an asset given without a folder to resolve it in.
pub(super) const EXTERNAL_RESOURCE_NOT_READ: Code =
    Code::new("EXTERNAL_RESOURCE_NOT_READ", Severity::Info);
