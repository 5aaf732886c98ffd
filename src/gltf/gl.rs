//! The OpenGL enum values glTF (1.0 and 2.0) stores as numbers, in one place.

/// `componentType` values.
pub(crate) const BYTE: u64 = 5120;
pub(crate) const UNSIGNED_BYTE: u64 = 5121;
pub(crate) const SHORT: u64 = 5122;
pub(crate) const UNSIGNED_SHORT: u64 = 5123;
pub(crate) const UNSIGNED_INT: u64 = 5125;
pub(crate) const FLOAT: u64 = 5126;

/// The name and the range of values of an integer component type (`None` for FLOAT and
/// for what is no component type).
pub(crate) fn integer_range(component_type: u64) -> Option<(&'static str, f64, f64)> {
    match component_type {
        BYTE => Some(("BYTE", -128.0, 127.0)),
        UNSIGNED_BYTE => Some(("UNSIGNED_BYTE", 0.0, 255.0)),
        SHORT => Some(("SHORT", -32768.0, 32767.0)),
        UNSIGNED_SHORT => Some(("UNSIGNED_SHORT", 0.0, 65535.0)),
        UNSIGNED_INT => Some(("UNSIGNED_INT", 0.0, 4294967295.0)),
        _ => None,
    }
}

/// `bufferView.target` values.
pub(crate) const ARRAY_BUFFER: u64 = 34962;
pub(crate) const ELEMENT_ARRAY_BUFFER: u64 = 34963;

/// Sampler filters and wrap modes.
pub(crate) const LINEAR: u64 = 9729;
pub(crate) const NEAREST_MIPMAP_LINEAR: u64 = 9986;
pub(crate) const REPEAT: u64 = 10497;
pub(crate) const CLAMP_TO_EDGE: u64 = 33071;
pub(crate) const MIRRORED_REPEAT: u64 = 33648;

/// glTF 1.0 technique states (`technique.states.enable`).
pub(crate) const BLEND: u64 = 3042;
pub(crate) const CULL_FACE: u64 = 2884;
