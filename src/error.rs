//! The façade's error type.

use std::path::PathBuf;

/// Why `check_path`, `compare` or `render` could not read an asset or use it. Problems *in*
/// an asset are not errors: they are diagnostics in the check's report. The upgrade has
/// errors of its own (`UpgradeError`, `ProofError`, `WriteError`).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A file could not be read (missing, not a regular file, too large, or unreadable).
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: crate::document::file::FileError,
    },
    /// The asset holds nothing the operation can use (no materials to compare, …).
    #[error("{}: {reason}", path.display())]
    Unusable {
        /// The asset.
        path: PathBuf,
        /// Why.
        reason: String,
    },
}
