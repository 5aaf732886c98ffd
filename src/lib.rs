//! gltfmat: checks glTF 2.0 / GLB assets and their materials, upgrades glTF 1.0, and evaluates
//! materials with a reference shading model.
//!
//! ```
//! use gltfmat::check::{check_bytes, CheckOptions};
//! use gltfmat::document::uri::NoResources;
//!
//! let json = br#"{"asset": {"version": "2.0"}, "materials": [{"alphaCutoff": 0.5}]}"#;
//! let report = check_bytes("inline.gltf", json.to_vec(), &NoResources, &CheckOptions::default());
//! assert!(report.diagnostics.iter().any(|d| d.code == "MATERIAL_ALPHA_CUTOFF_INVALID_MODE"));
//! assert!(!report.has_errors());
//! ```

pub mod check;
pub mod color;
pub mod document;
pub mod legacy_pbr;
pub mod report;
pub mod shade;
pub mod upgrade;

pub use check::{check_bytes, CheckOptions, Profile, Report};
