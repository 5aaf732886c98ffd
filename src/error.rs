//! The façade's error type.

use std::path::PathBuf;

/// Why a façade call could not produce its result. Problems *in* an asset are not errors:
/// they are diagnostics in the [`Report`](crate::Report).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
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
