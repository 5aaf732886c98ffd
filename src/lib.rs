//! gltfmat: checks glTF 2.0 / GLB assets and their materials, upgrades glTF 1.0, and evaluates
//! materials with a reference shading model.
//!
//! The façade is this page: [`check_path`] / [`check_bytes`], [`upgrade()`] and its proof
//! [`prove`], [`compare`] and [`render`], their options, [`Report`] and [`Error`], and the
//! types they take and give. Four modules name what a report and an upgrade are made of:
//! [`diagnostic`] (codes and findings), [`report`] (output formats), [`registry`] (every code
//! and rule) and [`upgrade_output`] (an upgraded asset's files). Everything else is private.
//! Data flows one way: bytes → document → check / upgrade / shade → [`report`].
//!
//! Check a file (its external `.bin` and images are read from its folder):
//! ```
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let report = gltfmat::check_path("fixtures/valid/sheen-triangle.gltf", &gltfmat::CheckOptions::default())?;
//! assert!(!report.has_errors());
//! # Ok(()) }
//! ```
//!
//! Check bytes in memory:
//! ```
//! use gltfmat::{check_bytes, diagnostic::khronos, CheckOptions, NoResources};
//!
//! let json = br#"{"asset": {"version": "2.0"}, "materials": [{"alphaCutoff": 0.5}]}"#;
//! let report = check_bytes("inline.gltf", json.to_vec(), &NoResources, &CheckOptions::default());
//! assert!(report.diagnostics.iter().any(|d| d.code == khronos::MATERIAL_ALPHA_CUTOFF_INVALID_MODE));
//! assert!(!report.has_errors());
//! ```
//!
//! Upgrade a glTF 1.0 asset and prove that its materials render as before:
//! ```
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use gltfmat::{prove, upgrade, FolderResources, UpgradeOptions};
//!
//! let path = std::path::Path::new("fixtures/gltf1/pbr-mr-web3d.gltf");
//! let bytes = std::fs::read(path)?;
//! let resources = FolderResources::beside(path);
//! let upgraded = upgrade(&bytes, &resources, &UpgradeOptions::default())?;
//! let proof = prove(&bytes, "pbr-mr-web3d.gltf", &resources, &upgraded)?;
//! assert!(!proof.is_empty());
//! assert!(proof.iter().all(|outcome| outcome.result.max < 1.0));
//! # Ok(()) }
//! ```

#![warn(missing_docs)]
#![warn(unreachable_pub)]
#![deny(unsafe_code)]

mod check;
pub mod diagnostic;
mod document;
mod error;
mod gltf;
mod legacy;
mod output;
mod page;
pub mod report;
mod shade;
mod system;
#[cfg(test)]
mod test_random;
mod upgrade;

// Checking: a file or bytes in, a report out; the rules and codes it can report.
pub use check::registry;
pub use check::{check_bytes, check_path, AssetInfo, CheckOptions, Profile, Report, ResourceInfo};
pub use diagnostic::{Code, Diagnostic, Finding, Findings, Location, Place, Severity};

// Input: reading a file within bounds, and the files an asset names.
pub use document::bytes::Bytes;
pub use document::file::{read_file, read_stream, FileError, FileId, Kept, MAX_FILE_BYTES};
pub use document::uri::{
    folder_of, FolderResources, LoadError, MemoryResources, NoResources, ResourceLoader,
};
pub use error::Error;

// Upgrading and its proof; the upgraded asset's files, checked as written.
pub use upgrade::output as upgrade_output;
pub use upgrade::{
    proof_holds, prove, upgrade, Items, Json, Note, NoteKind, ProofError, SpecGlossReading,
    SpecularGlossiness, UpgradeError, UpgradeOptions, Upgraded,
};

// Comparing and drawing materials with the reference evaluator.
pub use shade::brdf::SheenVisibility;
pub use shade::compare::{Area, DEFAULT_THRESHOLD, DIRECTIONS};
pub use shade::pairing::{
    compare, render, render_each, Ball, CompareOptions, Compared, Outcome, Picture, RenderOptions,
    NO_MODEL,
};
pub use shade::render::{heatmap, png, SheetLayout, MAX_PIXELS, MAX_SIZE};
pub use shade::sheen_table::SheenTable;

// Writing outputs the one safe way, and the HTML report page.
pub use output::{exit_removing_unfinished, may_write, write_file, write_files, WriteError};
pub use page::{Page, Part, Renders};
pub use system::return_large_blocks_when_freed;
