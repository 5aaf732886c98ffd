//! glTF's own vocabulary, written once: GL enums, accessor component types and decoding,
//! colour transfer functions, texture slots. No I/O and no diagnostics.

pub(crate) mod accessor;
pub(crate) mod color;
pub(crate) mod coverage;
pub(crate) mod gl;
pub(crate) mod material;
pub(crate) mod mesh;

use serde_json::Value;

/// The top-level arrays of a glTF 2.0 document whose elements are objects of their own, in
/// the order the Khronos validator reads them.
pub(crate) const COLLECTIONS: &[&str] = &[
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

/// A JSON value as the spec's vocabulary reads it: serde_json's tree (which the upgrade
/// rewrites and the evaluator reads) and the checker's compact one alike.
pub(crate) trait Json<'a>: Copy + 'a {
    /// The member named `key`, when this is an object.
    fn get(self, key: &str) -> Option<Self>;
    /// The number, when it is an integer from 0 to `u64::MAX` as written.
    fn as_u64(self) -> Option<u64>;
    /// Any number, as the nearest f64.
    fn as_f64(self) -> Option<f64>;
    /// The text, when this is a string.
    fn as_str(self) -> Option<&'a str>;
    /// Whether this is an object.
    fn is_object(self) -> bool;
    /// The values of an object's members (none for anything else).
    fn member_values(self) -> Box<dyn Iterator<Item = Self> + 'a>;
    /// Element `index`, when this is an array that long.
    fn item(self, index: usize) -> Option<Self>;
}

impl<'a> Json<'a> for &'a Value {
    fn get(self, key: &str) -> Option<Self> {
        Value::get(self, key)
    }

    fn as_u64(self) -> Option<u64> {
        Value::as_u64(self)
    }

    fn as_f64(self) -> Option<f64> {
        Value::as_f64(self)
    }

    fn as_str(self) -> Option<&'a str> {
        Value::as_str(self)
    }

    fn is_object(self) -> bool {
        Value::is_object(self)
    }

    fn member_values(self) -> Box<dyn Iterator<Item = Self> + 'a> {
        Box::new(
            self.as_object()
                .into_iter()
                .flat_map(|members| members.values()),
        )
    }

    fn item(self, index: usize) -> Option<Self> {
        Value::get(self, index)
    }
}

/// What an integer from 2^64 up reads as: 2^64 − 4096. A number that large is a multiple of
/// 2^12 (a double's step there), so, as `1e308` is to the Khronos validator, it is aligned to
/// every component and stride size, and it still fits nothing.
pub(crate) const BEYOND_U64: u64 = !0xFFF;

/// A non-negative integer member (an index or a count), also when written as a float (`1.0`),
/// as glTF's JSON allows.
pub(crate) fn unsigned<'a>(object: impl Json<'a>, key: &str) -> Option<u64> {
    as_index(object.get(key)?)
}

/// A `byteOffset`: 0 when absent, `None` when present but not a non-negative integer (the
/// Khronos validator then reads no data through it).
pub(crate) fn byte_offset<'a>(object: impl Json<'a>) -> Option<u64> {
    object.get("byteOffset").map_or(Some(0), as_index)
}

/// A JSON value read as a glTF index: a non-negative integer, also when written as a float.
/// An integer from 2^64 up (`1e300`) reads as [`BEYOND_U64`]: as for the Khronos validator, it
/// is an integer, and no index, offset or length that large fits anything.
pub(crate) fn as_index<'a>(value: impl Json<'a>) -> Option<u64> {
    const SAFE: u64 = 1 << 53;
    // Past 2^53 a number is read as the double it rounds to, as the validator (JavaScript)
    // reads it: 2^64 − 1 is 2^64, even, and beyond.
    let f = match value.as_u64() {
        Some(n) if n <= SAFE => return Some(n),
        _ => value.as_f64().filter(|f| f.fract() == 0.0 && *f >= 0.0)?,
    };
    Some(if f < 18_446_744_073_709_551_616.0 {
        f as u64
    } else {
        BEYOND_U64
    })
}
