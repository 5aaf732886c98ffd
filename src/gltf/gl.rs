//! The OpenGL enum values glTF (1.0 and 2.0) stores as numbers, in one place.

/// `componentType` values.
pub const BYTE: u64 = 5120;
pub const UNSIGNED_BYTE: u64 = 5121;
pub const SHORT: u64 = 5122;
pub const UNSIGNED_SHORT: u64 = 5123;
pub const UNSIGNED_INT: u64 = 5125;
pub const FLOAT: u64 = 5126;

/// `bufferView.target` values.
pub const ARRAY_BUFFER: u64 = 34962;
pub const ELEMENT_ARRAY_BUFFER: u64 = 34963;

/// Sampler filters and wrap modes.
pub const LINEAR: u64 = 9729;
pub const NEAREST_MIPMAP_LINEAR: u64 = 9986;
pub const REPEAT: u64 = 10497;

/// glTF 1.0 technique states (`technique.states.enable`).
pub const BLEND: u64 = 3042;
pub const CULL_FACE: u64 = 2884;
