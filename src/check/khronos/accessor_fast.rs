//! Fast paths of the accessor-data pass for the bulk of real data: tightly packed floats
//! that no use checks element by element (positions, texture coordinates), scalar index
//! buffers, and unsigned integer vectors no use checks (joints, colours). They compute the
//! same min/max in the data's own type with loops the compiler vectorises. Whenever
//! something would be reported element by element (a non-finite float, an index out of range
//! or equal to the restart value) they decline, and the general walk runs and reports it.

use super::accessor_usage::{is_unit_length, Checker};
use crate::gltf::accessor::{FloatBounds, Layout};
use crate::gltf::gl;
use rayon::prelude::*;

/// Elements (indices: triangles) bounded as one piece of work: large buffers are read on
/// all cores.
const ELEMENTS_AT_ONCE: usize = 1 << 16;

/// min/max per component, or None when the general walk is needed.
pub(super) fn bounds(
    layout: &Layout,
    bytes: &[u8],
    checkers: &mut [Checker],
) -> Option<(Vec<f64>, Vec<f64>)> {
    let element = layout.size * layout.components;
    let end = layout
        .count
        .checked_mul(element)?
        .checked_add(layout.offset)?;
    if layout.stride != element || layout.components == 0 {
        return None;
    }
    let data = bytes.get(layout.offset..end)?;
    match (layout.component_type, layout.components) {
        (gl::FLOAT, n @ 1..=4) if checkers.is_empty() => floats(n, data),
        (gl::FLOAT, 3) if checkers.iter().all(Checker::wants_unit_vectors_only) => {
            float_bounds::<3>(data, unit_vector)
        }
        (gl::UNSIGNED_BYTE, 1) => indices::<1>(data, checkers),
        (gl::UNSIGNED_SHORT, 1) => indices::<2>(data, checkers),
        (gl::UNSIGNED_INT, 1) => indices::<4>(data, checkers),
        (gl::UNSIGNED_BYTE | gl::UNSIGNED_SHORT, n @ 2..=4) if checkers.is_empty() => {
            unsigned(layout.size, n, data)
        }
        _ => None,
    }
}

fn floats(n: usize, data: &[u8]) -> Option<(Vec<f64>, Vec<f64>)> {
    match n {
        1 => float_bounds::<1>(data, |_| true),
        2 => float_bounds::<2>(data, |_| true),
        3 => float_bounds::<3>(data, |_| true),
        _ => float_bounds::<4>(data, |_| true),
    }
}

fn unit_vector(v: &[f32; 3]) -> bool {
    let [x, y, z] = v.map(f64::from);
    is_unit_length((x * x + y * y + z * z).sqrt())
}

/// min/max of `N`-component float elements. Declines on NaN, an infinity, or an element
/// that `valid` rejects.
fn float_bounds<const N: usize>(
    data: &[u8],
    valid: impl Fn(&[f32; N]) -> bool + Sync,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let bounds = FloatBounds::<N>::of(data, valid);
    let finite = bounds.low.iter().chain(&bounds.high).all(|v| v.is_finite());
    (finite && !bounds.nan && !bounds.rejected).then(|| bounds.min_max())
}

/// [`unsigned_bounds`] for the component size and count.
fn unsigned(size: usize, n: usize, data: &[u8]) -> Option<(Vec<f64>, Vec<f64>)> {
    match (size, n) {
        (1, 2) => Some(unsigned_bounds::<1, 2>(data)),
        (1, 3) => Some(unsigned_bounds::<1, 3>(data)),
        (1, _) => Some(unsigned_bounds::<1, 4>(data)),
        (_, 2) => Some(unsigned_bounds::<2, 2>(data)),
        (_, 3) => Some(unsigned_bounds::<2, 3>(data)),
        _ => Some(unsigned_bounds::<2, 4>(data)),
    }
}

/// min/max of `N`-component unsigned elements of `SIZE`-byte components (joints, colours,
/// texture coordinates stored as integers): every value is finite, so this never declines.
fn unsigned_bounds<const SIZE: usize, const N: usize>(data: &[u8]) -> (Vec<f64>, Vec<f64>) {
    let (low, high) = (data.par_chunks(SIZE * N * ELEMENTS_AT_ONCE))
        .map(|run| {
            let (mut low, mut high) = ([u16::MAX; N], [0u16; N]);
            for element in run.chunks_exact(SIZE * N) {
                for (c, word) in element.chunks_exact(SIZE).enumerate() {
                    let v = match SIZE {
                        1 => u16::from(word[0]),
                        _ => u16::from_le_bytes([word[0], word[1]]),
                    };
                    low[c] = low[c].min(v);
                    high[c] = high[c].max(v);
                }
            }
            (low, high)
        })
        .reduce(
            || ([u16::MAX; N], [0; N]),
            |a, b| {
                let low = std::array::from_fn(|c| a.0[c].min(b.0[c]));
                (low, std::array::from_fn(|c| a.1[c].max(b.1[c])))
            },
        );
    (low.map(f64::from).to_vec(), high.map(f64::from).to_vec())
}

/// min/max of a scalar unsigned index buffer and its degenerate triangles, handed to its
/// index checkers. Declines when an index is out of range or the restart value.
fn indices<const SIZE: usize>(
    data: &[u8],
    checkers: &mut [Checker],
) -> Option<(Vec<f64>, Vec<f64>)> {
    let value = |word: &[u8]| {
        let mut le = [0u8; 4];
        le[..SIZE].copy_from_slice(word);
        u32::from_le_bytes(le)
    };
    // Runs of whole triangles, on all cores, each read once for its bounds and its
    // degenerate triangles (the words after the last whole triangle only for the bounds).
    let (low, high, degenerate) = (data.par_chunks(3 * SIZE * ELEMENTS_AT_ONCE))
        .map(|run| {
            let (mut low, mut high, mut degenerate) = (u32::MAX, 0u32, 0u64);
            let triangles = run.chunks_exact(3 * SIZE);
            let rest = triangles.remainder();
            for triangle in triangles {
                let (a, b, c) = (
                    value(&triangle[..SIZE]),
                    value(&triangle[SIZE..2 * SIZE]),
                    value(&triangle[2 * SIZE..]),
                );
                low = low.min(a).min(b).min(c);
                high = high.max(a).max(b).max(c);
                degenerate += u64::from(a == b || b == c || c == a);
            }
            for word in rest.chunks_exact(SIZE) {
                low = low.min(value(word));
                high = high.max(value(word));
            }
            (low, high, degenerate)
        })
        .reduce(
            || (u32::MAX, 0, 0),
            |a, b| (a.0.min(b.0), a.1.max(b.1), a.2 + b.2),
        );
    let clean = checkers
        .iter_mut()
        .all(|checker| checker.accept_index_summary(f64::from(high), degenerate));
    clean.then(|| (vec![f64::from(low)], vec![f64::from(high)]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsigned_bounds_over_many_runs_are_those_of_one_loop() {
        // Three runs and a bit; each component's extremes lie in a different run.
        let elements = 3 * ELEMENTS_AT_ONCE + 5;
        let value = |i: usize, c: usize| ((i * (c + 3) + c * ELEMENTS_AT_ONCE) % 60_001) as u16;
        let data: Vec<u8> = (0..elements)
            .flat_map(|i| (0..3).map(move |c| value(i, c)))
            .flat_map(u16::to_le_bytes)
            .collect();
        let low: Vec<f64> = (0..3)
            .map(|c| (0..elements).map(|i| value(i, c)).min().unwrap().into())
            .collect();
        let high: Vec<f64> = (0..3)
            .map(|c| (0..elements).map(|i| value(i, c)).max().unwrap().into())
            .collect();
        assert_eq!(unsigned_bounds::<2, 3>(&data), (low, high));
        let bytes: Vec<u8> = data.iter().step_by(2).copied().collect();
        let (low, high) = unsigned_bounds::<1, 2>(&bytes[..2 * elements]);
        let expected = |pick: fn(std::slice::Iter<u8>) -> Option<&u8>, c: usize| {
            let column: Vec<u8> = bytes[..2 * elements]
                .iter()
                .skip(c)
                .step_by(2)
                .copied()
                .collect();
            f64::from(*pick(column.iter()).unwrap())
        };
        assert_eq!(low, [expected(|i| i.min(), 0), expected(|i| i.min(), 1)]);
        assert_eq!(high, [expected(|i| i.max(), 0), expected(|i| i.max(), 1)]);
    }
}
