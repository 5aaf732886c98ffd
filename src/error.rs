//! The façade's error type.

use std::path::PathBuf;

/// Why a façade call could not produce its result. Problems *in* an asset are not errors:
/// they are diagnostics in the [`Report`](crate::Report).
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
    /// The asset could not be upgraded.
    #[error(transparent)]
    Upgrade(#[from] crate::upgrade::UpgradeError),
    /// The upgraded asset could not be written.
    #[error(transparent)]
    Write(#[from] crate::upgrade::output::WriteError),
}
