//! Accessor component types and element types, as glTF (1.0 and 2.0) defines them: shared by
//! the checker's accessor passes and the converter's data repacking.

pub const BYTE: u64 = 5120;
pub const UNSIGNED_BYTE: u64 = 5121;
pub const SHORT: u64 = 5122;
pub const UNSIGNED_SHORT: u64 = 5123;
pub const UNSIGNED_INT: u64 = 5125;
pub const FLOAT: u64 = 5126;

/// Bytes per component of a `componentType`.
pub fn component_size(component_type: u64) -> Option<usize> {
    match component_type {
        BYTE | UNSIGNED_BYTE => Some(1),
        SHORT | UNSIGNED_SHORT => Some(2),
        UNSIGNED_INT | FLOAT => Some(4),
        _ => None,
    }
}

/// Components per element of a `type` (`"VEC3"` → 3).
pub fn component_count(kind: &str) -> Option<usize> {
    match kind {
        "SCALAR" => Some(1),
        "VEC2" => Some(2),
        "VEC3" => Some(3),
        "VEC4" | "MAT2" => Some(4),
        "MAT3" => Some(9),
        "MAT4" => Some(16),
        _ => None,
    }
}
