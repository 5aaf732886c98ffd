//! glTF's own vocabulary, written once: GL enums, accessor component types and decoding,
//! colour transfer functions, texture slots. No I/O and no diagnostics.

pub mod accessor;
pub mod color;
pub mod gl;
pub(crate) mod material;

use serde_json::Value;

/// The top-level arrays of a glTF 2.0 document whose elements are objects of their own.
pub const COLLECTIONS: &[&str] = &[
    "accessors",
    "animations",
    "buffers",
    "bufferViews",
    "cameras",
    "images",
    "materials",
    "meshes",
    "nodes",
    "samplers",
    "scenes",
    "skins",
    "textures",
];

/// A non-negative integer member (an index or a count), also when written as a float (`1.0`),
/// as glTF's JSON allows.
pub fn unsigned(object: &Value, key: &str) -> Option<u64> {
    as_index(object.get(key)?)
}

/// A `byteOffset`: 0 when absent, `None` when present but not a non-negative integer (the
/// Khronos validator then reads no data through it).
pub fn byte_offset(object: &Value) -> Option<u64> {
    object.get("byteOffset").map_or(Some(0), as_index)
}

/// A JSON value read as a glTF index: a non-negative integer, also when written as a float.
/// An integer beyond 2^64 (`1e300`) reads as `u64::MAX`: as for the Khronos validator, it is
/// an integer, and no index, offset or length that large fits anything.
pub fn as_index(value: &Value) -> Option<u64> {
    value.as_u64().or_else(|| {
        value
            .as_f64()
            .filter(|f| f.fract() == 0.0 && *f >= 0.0)
            // A saturating cast: every integer from 2^64 up becomes u64::MAX.
            .map(|f| f as u64)
    })
}
