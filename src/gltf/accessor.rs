//! Accessor component types and element types, as glTF (1.0 and 2.0) defines them: shared by
//! the checker's accessor passes and the converter's data repacking.

pub use super::gl::{BYTE, FLOAT, SHORT, UNSIGNED_BYTE, UNSIGNED_INT, UNSIGNED_SHORT};

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

/// One little-endian component as stored (integers not normalised); `bytes` holds at least
/// `component_size(component_type)` bytes, and an unknown type reads as a float.
#[inline(always)]
pub fn decode_component(component_type: u64, bytes: &[u8]) -> f64 {
    let word = |n: usize| {
        let mut b = [0u8; 4];
        b[..n].copy_from_slice(&bytes[..n]);
        b
    };
    match component_type {
        BYTE => f64::from(bytes[0] as i8),
        UNSIGNED_BYTE => f64::from(bytes[0]),
        SHORT => f64::from(i16::from_le_bytes([bytes[0], bytes[1]])),
        UNSIGNED_SHORT => f64::from(u16::from_le_bytes([bytes[0], bytes[1]])),
        UNSIGNED_INT => f64::from(u32::from_le_bytes(word(4))),
        _ => f64::from(f32::from_le_bytes(word(4))),
    }
}

/// The glTF 2.0 normalisation of a `normalized` integer component (§3.11): the value a shader
/// sees. Floats and unnormalised integers are unchanged.
pub fn normalise(component_type: u64) -> fn(f64) -> f64 {
    match component_type {
        BYTE => |v| (v / 127.0).max(-1.0),
        UNSIGNED_BYTE => |v| v / 255.0,
        SHORT => |v| (v / 32767.0).max(-1.0),
        UNSIGNED_SHORT => |v| v / 65535.0,
        _ => |v| v,
    }
}

/// Per-component bounds of tightly packed little-endian `f32` elements of `N` components.
pub struct FloatBounds<const N: usize> {
    /// The least value of each component (+∞ when there is none).
    pub low: [f32; N],
    /// The greatest value of each component (−∞ when there is none).
    pub high: [f32; N],
    /// Whether some component is NaN (which never becomes a bound).
    pub nan: bool,
    /// Whether some element was not valid (see [`FloatBounds::of`]).
    pub rejected: bool,
}

/// Elements bounded as one piece of work: large data is bounded on all cores.
const ELEMENTS_AT_ONCE: usize = 1 << 16;

impl<const N: usize> FloatBounds<N> {
    /// The bounds of `data`, and whether `valid` rejects some element. Compared as `f32`,
    /// which is exact (every `f32` is an `f64`); compare-and-select on fixed-size arrays
    /// lets the compiler vectorise the loop.
    pub fn of(data: &[u8], valid: impl Fn(&[f32; N]) -> bool + Sync) -> Self {
        use rayon::prelude::*;
        (data.par_chunks(4 * N * ELEMENTS_AT_ONCE))
            .map(|run| Self::of_run(run, &valid))
            .reduce(Self::of_nothing, Self::with)
    }

    fn of_nothing() -> Self {
        FloatBounds {
            low: [f32::INFINITY; N],
            high: [f32::NEG_INFINITY; N],
            nan: false,
            rejected: false,
        }
    }

    fn of_run(data: &[u8], valid: impl Fn(&[f32; N]) -> bool) -> Self {
        let FloatBounds {
            mut low,
            mut high,
            mut nan,
            mut rejected,
        } = Self::of_nothing();
        for element in data.chunks_exact(4 * N) {
            let mut v = [0f32; N];
            for (value, word) in v.iter_mut().zip(element.chunks_exact(4)) {
                *value = f32::from_le_bytes(word.try_into().unwrap_or_default());
            }
            for c in 0..N {
                low[c] = if v[c] < low[c] { v[c] } else { low[c] };
                high[c] = if v[c] > high[c] { v[c] } else { high[c] };
                nan |= v[c].is_nan();
            }
            rejected |= !valid(&v);
        }
        FloatBounds {
            low,
            high,
            nan,
            rejected,
        }
    }

    /// The bounds of both.
    fn with(self, other: Self) -> Self {
        FloatBounds {
            low: std::array::from_fn(|c| self.low[c].min(other.low[c])),
            high: std::array::from_fn(|c| self.high[c].max(other.high[c])),
            nan: self.nan || other.nan,
            rejected: self.rejected || other.rejected,
        }
    }

    /// The bounds as glTF's `min` / `max` arrays.
    pub fn min_max(&self) -> (Vec<f64>, Vec<f64>) {
        (
            self.low.map(f64::from).to_vec(),
            self.high.map(f64::from).to_vec(),
        )
    }
}
