//! Fast paths of the accessor-data pass for the bulk of real data: tightly packed floats
//! that no use checks element by element (positions, texture coordinates), and scalar index
//! buffers. They compute the same min/max in the data's own type with loops the compiler
//! vectorises. Whenever something would be reported element by element (a non-finite float,
//! an index out of range or equal to the restart value) they decline, and the general walk
//! runs and reports it.

use super::accessor_usage::{is_unit_length, Checker};
use crate::gltf::accessor::FloatBounds;
use crate::gltf::gl;
use rayon::prelude::*;

/// Indices bounded as one piece of work, in triangles: large buffers are read on all cores.
const TRIANGLES_AT_ONCE: usize = 1 << 16;

/// Where an accessor's elements lie in its bufferView's bytes.
#[derive(Clone, Copy)]
pub(super) struct Layout {
    pub component_type: u64,
    pub size: usize,
    pub components: usize,
    pub stride: usize,
    pub offset: usize,
    pub count: usize,
}

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
    let triangles = !checkers.is_empty();
    // Runs of whole triangles, on all cores.
    let (low, high, degenerate) = (data.par_chunks(3 * SIZE * TRIANGLES_AT_ONCE))
        .map(|run| {
            let (mut low, mut high, mut degenerate) = (u32::MAX, 0u32, 0u64);
            for word in run.chunks_exact(SIZE) {
                let v = value(word);
                low = low.min(v);
                high = high.max(v);
            }
            if triangles {
                for triangle in run.chunks_exact(3 * SIZE) {
                    let (a, b, c) = (
                        value(&triangle[..SIZE]),
                        value(&triangle[SIZE..2 * SIZE]),
                        value(&triangle[2 * SIZE..]),
                    );
                    degenerate += u64::from(a == b || b == c || c == a);
                }
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
