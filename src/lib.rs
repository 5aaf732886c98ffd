//! gltfmat: checks glTF 2.0 / GLB assets and their materials, upgrades glTF 1.0, and evaluates
//! materials with a reference shading model.
//!
//! The façade is this page: [`check_path`] / [`check_bytes`], [`upgrade()`] and its proof
//! [`prove`], [`compare`] and [`render`], their options, [`Report`] and [`Error`]. Data flows one way: bytes →
//! [`document`] → check / upgrade / shade → [`report`].
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
#![deny(unsafe_code)]

pub mod check;
pub mod diagnostic;
pub mod document;
mod error;
pub(crate) mod gltf;
pub(crate) mod legacy;
pub mod output;
pub mod page;
pub mod report;
pub mod shade;
pub mod system;
#[cfg(test)]
mod test_random;
pub mod upgrade;

pub use check::{check_bytes, check_path, CheckOptions, Profile, Report};
pub use diagnostic::{Code, Diagnostic, Finding, Findings, Location, Place, Severity};
pub use document::uri::{FolderResources, MemoryResources, NoResources, ResourceLoader};
pub use error::Error;
pub use shade::pairing::{
    compare, render, render_each, Ball, CompareOptions, Compared, Outcome, Picture, RenderOptions,
};
pub use upgrade::{prove, upgrade, ProofError, UpgradeError, UpgradeOptions, Upgraded};
