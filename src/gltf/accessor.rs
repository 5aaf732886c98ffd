//! Accessor component types and element types, as glTF (1.0 and 2.0) defines them: shared by
//! the checker's accessor passes and the converter's data repacking.

use std::ops::Range;

pub(crate) use super::gl::{BYTE, FLOAT, SHORT, UNSIGNED_BYTE, UNSIGNED_INT, UNSIGNED_SHORT};

/// An element's length when packed and the length of its data, in bytes, for a `type` of
/// components `component_size` bytes long (an unknown `type` has none). Matrix columns
/// start on 4-byte boundaries (glTF 2.0 §3.6.2.4): a matrix of 1- or 2-byte components is
/// padded after each column, and its data ends with its last column, before the padding.
pub(crate) fn element_lengths(kind: &str, component_size: usize) -> (u64, u64) {
    match (kind, component_size) {
        ("MAT2", 1) => (8, 6),
        ("MAT3", 1) => (12, 11),
        ("MAT3", 2) => (24, 22),
        _ => {
            let size = (component_count(kind).unwrap_or(0) * component_size) as u64;
            (size, size)
        }
    }
}

/// Bytes per component of a `componentType`.
pub(crate) fn component_size(component_type: u64) -> Option<usize> {
    match component_type {
        BYTE | UNSIGNED_BYTE => Some(1),
        SHORT | UNSIGNED_SHORT => Some(2),
        UNSIGNED_INT | FLOAT => Some(4),
        _ => None,
    }
}

/// Components per element of a `type` (`"VEC3"` → 3).
pub(crate) fn component_count(kind: &str) -> Option<usize> {
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
pub(crate) fn decode_component(component_type: u64, bytes: &[u8]) -> f64 {
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

/// The glTF 2.0 normalisation of a `normalized` integer component (§3.11): what makes a
/// stored value the value a shader sees. None for the types whose values are not changed
/// (floats, unsigned ints), so that callers pay no call per value for them.
pub(crate) fn normalise(component_type: u64) -> Option<fn(f64) -> f64> {
    match component_type {
        BYTE => Some(|v| (v / 127.0).max(-1.0)),
        UNSIGNED_BYTE => Some(|v| v / 255.0),
        SHORT => Some(|v| (v / 32767.0).max(-1.0)),
        UNSIGNED_SHORT => Some(|v| v / 65535.0),
        _ => None,
    }
}

/// Where an accessor's elements lie in its bytes (from `offset`, `stride` apart), and how each
/// is stored (`components` of `size` bytes as `component_type`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Layout {
    pub component_type: u64,
    pub size: usize,
    pub components: usize,
    pub stride: usize,
    pub offset: usize,
    pub count: usize,
}

/// The most components an element has (MAT4).
pub(crate) const MAX_COMPONENTS: usize = 16;
/// Elements decoded per batch: small enough for L1, large enough that each check's
/// dispatch is paid once per batch rather than once per element; a multiple of 3 so that
/// triangles rarely straddle batches.
const BATCH: usize = 240;

/// Calls `f(first element index, values)` for consecutive batches of elements, `values`
/// holding `components` numbers per element, as stored (integers not normalised); stops
/// at the first batch whose bytes `bytes` does not hold.
pub(crate) fn visit(layout: &Layout, bytes: &[u8], mut f: impl FnMut(usize, &[f64])) {
    let n = layout.components.clamp(1, MAX_COMPONENTS);
    let mut values = [0.0; BATCH * MAX_COMPONENTS];
    let mut first = 0;
    while first < layout.count {
        let k = BATCH.min(layout.count - first);
        if !decode(layout, bytes, first, &mut values[..k * n]) {
            return;
        }
        f(first, &values[..k * n]);
        first += k;
    }
}

/// Decodes the elements from `first` on that `out` has room for (`components` numbers
/// each, as stored: integers not normalised); false when `bytes` does not hold them all.
/// Dispatching on the component type once, outside the loop, keeps the inner loop a plain
/// load: the check and the upgrade run this over every byte of large assets.
pub(crate) fn decode(layout: &Layout, bytes: &[u8], first: usize, out: &mut [f64]) -> bool {
    match layout.component_type {
        BYTE => decode_as::<BYTE, 1>(layout, bytes, first, out),
        UNSIGNED_BYTE => decode_as::<UNSIGNED_BYTE, 1>(layout, bytes, first, out),
        SHORT => decode_as::<SHORT, 2>(layout, bytes, first, out),
        UNSIGNED_SHORT => decode_as::<UNSIGNED_SHORT, 2>(layout, bytes, first, out),
        UNSIGNED_INT => decode_as::<UNSIGNED_INT, 4>(layout, bytes, first, out),
        _ => decode_as::<FLOAT, 4>(layout, bytes, first, out),
    }
}

/// [`decode`] for one component type, decoded by [`decode_component`] with the type a
/// constant, so that the match on it is resolved at compile time.
fn decode_as<const TYPE: u64, const SIZE: usize>(
    layout: &Layout,
    bytes: &[u8],
    first: usize,
    out: &mut [f64],
) -> bool {
    let decode =
        |raw: &[u8]| decode_component(TYPE, &<[u8; SIZE]>::try_from(raw).unwrap_or([0; SIZE]));
    let n = layout.components.clamp(1, MAX_COMPONENTS);
    let element_size = SIZE * n;
    let start_of = |element: usize| {
        let start = element
            .checked_mul(layout.stride)?
            .checked_add(layout.offset)?;
        Some(start..start.checked_add(element_size)?)
    };
    if layout.stride == element_size {
        // Tightly packed: one run of bytes, decoded in a loop the compiler can vectorise.
        let count = out.len() / n;
        let end = |at: Range<usize>| at.start.checked_add(count * element_size);
        let run = start_of(first).and_then(|at| bytes.get(at.start..end(at)?));
        let Some(run) = run else {
            return false;
        };
        for (value, raw) in out.iter_mut().zip(run.chunks_exact(SIZE)) {
            *value = decode(raw);
        }
        return true;
    }
    for (e, values) in out.chunks_exact_mut(n).enumerate() {
        let Some(element) = start_of(first + e).and_then(|at| bytes.get(at)) else {
            return false;
        };
        for (value, raw) in values.iter_mut().zip(element.chunks_exact(SIZE)) {
            *value = decode(raw);
        }
    }
    true
}

/// Per-component bounds of tightly packed little-endian `f32` elements of `N` components.
pub(crate) struct FloatBounds<const N: usize> {
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
    pub(crate) fn of(data: &[u8], valid: impl Fn(&[f32; N]) -> bool + Sync) -> Self {
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
    pub(crate) fn min_max(&self) -> (Vec<f64>, Vec<f64>) {
        (
            self.low.map(f64::from).to_vec(),
            self.high.map(f64::from).to_vec(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unsigned shorts, two a vertex, 6 bytes apart after a 2-byte offset (padding = 0xFFFF).
    fn strided() -> (Layout, Vec<u8>) {
        let words: [u16; 10] = [0xFFFF, 1, 2, 0xFFFF, 3, 4, 0xFFFF, 5, 6, 0xFFFF];
        let layout = Layout {
            component_type: UNSIGNED_SHORT,
            size: 2,
            components: 2,
            stride: 6,
            offset: 2,
            count: 3,
        };
        (layout, words.iter().flat_map(|w| w.to_le_bytes()).collect())
    }

    #[test]
    fn elements_are_decoded_from_any_one_on_whether_packed_or_strided() {
        let (layout, bytes) = strided();
        let mut out = [0.0; 4];
        assert!(decode(&layout, &bytes, 1, &mut out));
        assert_eq!(out, [3.0, 4.0, 5.0, 6.0]);
        let floats: Vec<u8> = [1.5f32, -2.0, 0.25]
            .iter()
            .flat_map(|f| f.to_le_bytes())
            .collect();
        let packed = Layout {
            component_type: FLOAT,
            size: 4,
            components: 1,
            stride: 4,
            offset: 0,
            count: 3,
        };
        let mut out = [0.0; 2];
        assert!(decode(&packed, &floats, 1, &mut out));
        assert_eq!(out, [-2.0, 0.25]);
    }

    #[test]
    fn elements_past_the_bytes_are_not_decoded_and_a_walk_stops_there() {
        let (layout, bytes) = strided();
        let mut out = [0.0; 4];
        assert!(
            !decode(&layout, &bytes[..14], 1, &mut out),
            "the last element is cut"
        );
        assert!(
            !decode(&layout, &bytes, usize::MAX / 2, &mut out),
            "no overflow"
        );
        let mut seen = Vec::new();
        visit(&layout, &bytes, |first, values| {
            seen.push((first, values.to_vec()))
        });
        assert_eq!(seen, vec![(0, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0])]);
        let mut seen = 0;
        visit(&layout, &bytes[..14], |_, _| seen += 1);
        assert_eq!(seen, 0, "a batch that is not all there is not given");
    }
}
