//! Accessor data: one pass over each accessor's elements for non-finite floats, for `min` /
//! `max` that do not match the data, and for the checks its uses add (unit normals, index
//! bounds, animation inputs…, see `accessor_usage`): the Khronos ACCESSOR_* data codes.

use super::accessor_fast;
use super::accessor_usage::{self, Checker, Findings};
use super::resources::{view_bytes, view_data_in_buffer, ViewData};
use crate::check::context::{unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::Node;
use crate::gltf::accessor::{
    component_count, component_size, normalise, visit, Layout, MAX_COMPONENTS,
};
use crate::gltf::gl;
use rayon::prelude::*;
use std::borrow::Cow;

fn layout(ctx: &Context, accessor: Node, view: usize) -> Option<Layout> {
    let mut layout = packed_layout(accessor)?;
    if let Some(stride) = ctx
        .items("bufferViews")
        .get(view)
        .and_then(|v| unsigned(v, "byteStride"))
    {
        layout.stride = usize::try_from(stride).ok()?;
    }
    layout.offset = usize::try_from(crate::gltf::byte_offset(accessor)?).ok()?;
    Some(layout)
}

/// The accessor's elements packed one after the other from offset 0.
fn packed_layout(accessor: Node) -> Option<Layout> {
    let component_type = unsigned(accessor, "componentType")?;
    let size = component_size(component_type)?;
    let kind = accessor.get("type")?.as_str()?;
    // Small-component matrices have padded columns, which this pass does not walk.
    if kind.starts_with("MAT") && kind != "MAT4" && size < 4 {
        return None;
    }
    let components = component_count(kind)?;
    Some(Layout {
        component_type,
        size,
        components,
        stride: size * components,
        offset: 0,
        count: usize::try_from(unsigned(accessor, "count")?).ok()?,
    })
}

fn show(component_type: u64, v: f64) -> String {
    if component_type == gl::FLOAT || !v.is_finite() {
        super::Dart(v).to_string()
    } else {
        format!("{v}")
    }
}

pub(crate) fn check(ctx: &mut Context) {
    let mut uses = accessor_usage::checkers(ctx);
    // Accessors are independent and read-only here: scanned in parallel, reported in order.
    let mut work: Vec<Work> = ctx
        .objects("accessors")
        .filter_map(|(index, pointer, accessor)| {
            let (layout, data) = match accessor.get("sparse") {
                None => scannable(ctx, accessor).map(|(l, v)| (l, Data::View(v)))?,
                Some(_) => substituted(ctx, accessor).map(|(l, b)| (l, Data::Dense(b)))?,
            };
            let checkers = uses.remove(&index).unwrap_or_default();
            Some(Work {
                pointer,
                layout,
                data,
                accessor,
                checkers,
            })
        })
        .collect();
    // In batches, each walk with its share of what the pass may still keep: memory stays
    // bounded however many accessors alias one corrupt view, and the report does not
    // depend on the order the walks finish in.
    let mut budget = ctx.diagnostics.walk_budget();
    let reading = Reading::default();
    let mut found: Vec<Findings> = Vec::with_capacity(work.len());
    for batch in work.chunks_mut(WALKS_PER_BATCH) {
        let walks = batch.len();
        let batch_found: Vec<Findings> = (batch.par_iter_mut())
            .map(|work| scan(work, &reading, Findings::listing(budget.share(walks))))
            .collect();
        (batch_found.iter()).for_each(|findings| budget.spend(findings.listed()));
        found.extend(batch_found);
    }
    for findings in found {
        findings.report(ctx);
    }
}

/// One accessor to scan, with the checks its uses add.
struct Work<'c> {
    pointer: String,
    layout: Layout,
    data: Data<'c>,
    accessor: Node<'c>,
    checkers: Vec<Checker>,
}

/// An accessor's bytes: the part of its view it reads (read when its walk starts, so that
/// the views of a large GLB are held one walk at a time), or a sparse accessor's elements
/// with the substitution applied.
enum Data<'c> {
    View(ViewData<'c>),
    Dense(Vec<u8>),
    Walked,
}

/// The accessor's layout and the part of its view it reads, when it is plain (not sparse)
/// data that fits its view (otherwise ACCESSOR_TOO_LONG or a schema code was reported).
pub(crate) fn scannable<'c>(ctx: &'c Context, accessor: Node) -> Option<(Layout, ViewData<'c>)> {
    if accessor.get("sparse").is_some() {
        return None; // see `substituted`
    }
    in_view(ctx, accessor)
}

/// The accessor's layout and the part of its view it reads when its elements fit the view,
/// sparse or not.
fn in_view<'c>(ctx: &'c Context, accessor: Node) -> Option<(Layout, ViewData<'c>)> {
    let view = unsigned(accessor, "bufferView")? as usize;
    if view >= ctx.items("bufferViews").len() {
        return None;
    }
    let layout = layout(ctx, accessor, view)?;
    let bytes = view_data_in_buffer(ctx, view)?;
    // Every offset the walk computes is below `needed`, so once it fits, none can overflow.
    // Elements that overlap (a stride below the element size) are not walked: other passes
    // report that layout.
    let element = layout.size.checked_mul(layout.components)?;
    // Data at a total byteOffset that is no multiple of the component size is not read: the
    // validator's typed arrays cannot start there (ACCESSOR_TOTAL_OFFSET_ALIGNMENT says so).
    let view_offset = ctx
        .items("bufferViews")
        .get(view)
        .and_then(|v| unsigned(v, "byteOffset"))
        .unwrap_or(0);
    let total = view_offset.checked_add(u64::try_from(layout.offset).ok()?)?;
    if !total.is_multiple_of(u64::try_from(layout.size).ok()?) {
        return None;
    }
    let needed = layout
        .count
        .checked_sub(1)?
        .checked_mul(layout.stride)?
        .checked_add(element)?
        .checked_add(layout.offset)?;
    let part = bytes.part(0..needed)?;
    (layout.stride >= element).then_some((layout, part))
}

/// The largest dense copy made of a sparse accessor without a bufferView (its base elements
/// are zeros, and its count may claim anything).
const MAX_ZEROS: usize = 64 << 20;

/// A sparse accessor's elements with its values substituted, packed from offset 0, so that
/// the accessor-data pass checks (min, max, normalisation …) what a loader reads. None when
/// the base, the indices or the values cannot be read (each reported elsewhere).
fn substituted(ctx: &Context, accessor: Node) -> Option<(Layout, Vec<u8>)> {
    let sparse = accessor.get("sparse")?;
    let layout = packed_layout(accessor)?;
    let element = layout.size.checked_mul(layout.components)?;
    // A bufferView that names no view is none: the base elements are zeros, as the Khronos
    // validator reads an unresolved view.
    let view = unsigned(accessor, "bufferView").and_then(|v| ctx.element("bufferViews", v));
    let mut dense = match view {
        Some(_) => {
            let (base, view) = in_view(ctx, accessor)?;
            let bytes = view.read()?;
            (0..base.count)
                .flat_map(|i| {
                    let at = base.offset + i * base.stride;
                    bytes[at..at + element].iter().copied()
                })
                .collect()
        }
        None => vec![
            0u8;
            layout
                .count
                .checked_mul(element)
                .filter(|&n| n <= MAX_ZEROS)?
        ],
    };
    let values = sparse.get("values")?;
    let value_bytes = view_bytes(ctx, unsigned(values, "bufferView")? as usize)?;
    let start = usize::try_from(crate::gltf::byte_offset(values)?).ok()?;
    // More substitutions than elements (ACCESSOR_SPARSE_COUNT_OUT_OF_RANGE): the validator
    // reads no element of such an accessor.
    let sparse_count = usize::try_from(unsigned(sparse, "count")?)
        .ok()
        .filter(|&n| n <= layout.count)?;
    let length = sparse_count.checked_mul(element)?;
    let value_bytes = value_bytes.get(start..start.checked_add(length)?)?;
    let mut previous = None;
    for (index, value) in
        super::sparse::readable_indices(ctx, sparse)?.zip(value_bytes.chunks_exact(element))
    {
        // A loader merges the indices into the elements in one ascending pass: the values
        // are substituted up to the first index out of order or out of range (reported by
        // the sparse pass), and none after it, as the Khronos validator reads them.
        if index >= layout.count as u64 || previous.is_some_and(|p| index <= p) {
            break;
        }
        previous = Some(index);
        let at = usize::try_from(index)
            .ok()
            .and_then(|i| i.checked_mul(element));
        let range = at.and_then(|at| Some(at..at.checked_add(element)?));
        if let Some(slot) = range.and_then(|range| dense.get_mut(range)) {
            slot.copy_from_slice(value);
        }
    }
    Some((layout, dense))
}

/// How many accessors are walked in parallel before their findings are reported.
const WALKS_PER_BATCH: usize = 16;

/// The most bytes the walks hold at once of data read from files (a large GLB's views):
/// however many threads walk, and however many accessors alias one large view, a walk
/// waits until this much is free (or nothing else is held) before it reads.
const READ_AT_ONCE: usize = 64 << 20;

/// The bytes the walks hold of data read from files, with a wait for room.
#[derive(Default)]
struct Reading {
    held: std::sync::Mutex<usize>,
    freed: std::sync::Condvar,
}

impl Reading {
    /// Waits for room for `bytes`, and holds it until the guard is dropped.
    fn hold(&self, bytes: usize) -> Held<'_> {
        let mut held = self.held.lock().unwrap_or_else(|e| e.into_inner());
        while *held > 0 && *held + bytes > READ_AT_ONCE {
            held = self.freed.wait(held).unwrap_or_else(|e| e.into_inner());
        }
        *held += bytes;
        Held {
            reading: self,
            bytes,
        }
    }
}

/// Room held in [`Reading`] while a walk holds its bytes.
struct Held<'r> {
    reading: &'r Reading,
    bytes: usize,
}

impl Drop for Held<'_> {
    fn drop(&mut self) {
        let mut held = (self.reading.held.lock()).unwrap_or_else(|e| e.into_inner());
        *held -= self.bytes;
        self.reading.freed.notify_all();
    }
}

/// Every finding of one accessor (as many as `findings` keeps), from a single walk over its
/// elements.
fn scan(work: &mut Work, reading: &Reading, mut findings: Findings) -> Findings {
    let data = std::mem::replace(&mut work.data, Data::Walked);
    // Dropped after the bytes (declared before them).
    let _held = match &data {
        Data::View(view) if view.is_in_file() => Some(reading.hold(view.len())),
        _ => None,
    };
    let bytes = match data {
        Data::View(view) => view.read(),
        Data::Dense(bytes) => Some(Cow::Owned(bytes)),
        Data::Walked => None,
    };
    let Work {
        pointer,
        layout,
        accessor,
        checkers,
        ..
    } = work;
    let Some(bytes) = bytes else {
        findings.push((
            khronos::IO_ERROR,
            pointer.clone(),
            "The accessor's data could not be read: the file changed while it was checked.".into(),
        ));
        return findings;
    };
    let bytes = &bytes[..];
    if let Some((min, max)) = accessor_fast::bounds(layout, bytes, checkers) {
        Bounds {
            layout,
            bytes,
            pointer,
            findings: &mut findings,
        }
        .compare(*accessor, &min, &max);
        for checker in checkers.iter() {
            checker.finish(layout.count, &mut findings);
        }
        return findings;
    }
    walk_decoded(layout, bytes, *accessor, checkers, pointer, findings)
}

/// [`scan`]'s general walk: every element decoded to doubles, fed to each checker, its
/// actual bounds taken and compared with the declared ones.
fn walk_decoded(
    layout: &Layout,
    bytes: &[u8],
    accessor: Node,
    checkers: &mut [Checker],
    pointer: &str,
    mut findings: Findings,
) -> Findings {
    let n = layout.components;
    let unit = unit_scale(layout.component_type, accessor).unwrap_or(|v| v);
    let mut actual_min = [f64::INFINITY; MAX_COMPONENTS];
    let mut actual_max = [f64::NEG_INFINITY; MAX_COMPONENTS];
    let mut non_finite = false;
    visit(layout, bytes, |first, values| {
        for c in 0..n {
            // A comparison is false for NaN, so NaN never becomes a bound; infinities are
            // taken out again by the slow path.
            let (low, high) = (&mut actual_min[c], &mut actual_max[c]);
            for &v in values[c..].iter().step_by(n) {
                *low = if v < *low { v } else { *low };
                *high = if v > *high { v } else { *high };
            }
        }
        for checker in checkers.iter_mut() {
            checker.feed(first * n, values, n, unit, &mut findings);
        }
        non_finite |= values.iter().any(|v| !v.is_finite());
    });
    if non_finite {
        report_non_finite(
            layout,
            bytes,
            pointer,
            &mut actual_min,
            &mut actual_max,
            &mut findings,
        );
    }
    let mut bounds = Bounds {
        layout,
        bytes,
        pointer,
        findings: &mut findings,
    };
    bounds.compare(accessor, &actual_min[..n], &actual_max[..n]);
    for checker in checkers.iter() {
        checker.finish(layout.count * n, &mut findings);
    }
    findings
}

/// The rare second walk of an accessor holding NaN or infinities: reports each and takes
/// min/max as the validator does: an infinity makes its component's actual bound infinite,
/// and a NaN in the first element makes both of its component's bounds NaN.
fn report_non_finite(
    layout: &Layout,
    bytes: &[u8],
    pointer: &str,
    actual_min: &mut [f64; MAX_COMPONENTS],
    actual_max: &mut [f64; MAX_COMPONENTS],
    findings: &mut Findings,
) {
    *actual_min = [f64::INFINITY; MAX_COMPONENTS];
    *actual_max = [f64::NEG_INFINITY; MAX_COMPONENTS];
    let n = layout.components;
    visit(layout, bytes, |first, values| {
        for (i, c, v) in components(first, values, n) {
            // The validator starts each component's bounds at the first element and moves
            // them by comparisons, which are false for NaN: a NaN first element leaves both
            // bounds NaN (which no declared bound matches), a later NaN moves neither.
            if i == 0 {
                (actual_min[c], actual_max[c]) = (*v, *v);
            } else {
                actual_min[c] = if *v < actual_min[c] {
                    *v
                } else {
                    actual_min[c]
                };
                actual_max[c] = if *v > actual_max[c] {
                    *v
                } else {
                    actual_max[c]
                };
            }
            if v.is_finite() {
                continue;
            }
            let what = if v.is_nan() {
                "NaN"
            } else if *v > 0.0 {
                "Infinity"
            } else {
                "-Infinity"
            };
            findings.push((
                khronos::ACCESSOR_INVALID_FLOAT,
                pointer.to_string(),
                format!("Accessor element at index {} is {what}.", i * n + c),
            ));
        }
    });
}

/// (element index, component, value) for each number of a batch starting at `first`.
fn components(
    first: usize,
    values: &[f64],
    n: usize,
) -> impl Iterator<Item = (usize, usize, &f64)> {
    values
        .iter()
        .enumerate()
        .map(move |(k, v)| (first + k / n, k % n, v))
}

/// Declared `min` / `max` against the data.
struct Bounds<'w> {
    layout: &'w Layout,
    bytes: &'w [u8],
    pointer: &'w str,
    findings: &'w mut Findings,
}

impl Bounds<'_> {
    fn compare(&mut self, accessor: Node, actual_min: &[f64], actual_max: &[f64]) {
        let sides = [
            ("min", "minimum", "less than", actual_min),
            ("max", "maximum", "greater than", actual_max),
        ];
        for (key, word, relation, actual) in sides {
            let Some(declared) = self.declared(accessor, key) else {
                continue;
            };
            let is_min = key == "min";
            let t = self.layout.component_type;
            // A component of nothing but NaN has no actual bound (it stays at its start).
            let none = if is_min {
                f64::INFINITY
            } else {
                f64::NEG_INFINITY
            };
            for (c, (&declared, &actual)) in declared.iter().zip(actual).enumerate() {
                if actual == none || self.as_stored(declared) == actual {
                    continue;
                }
                let at = format!("{}/{key}/{c}", self.pointer);
                let code = if is_min {
                    khronos::ACCESSOR_MIN_MISMATCH
                } else {
                    khronos::ACCESSOR_MAX_MISMATCH
                };
                self.findings.push((code, at.clone(), format!("Declared {word} value for this component ({}) does not match actual {word} ({}).", show(t, declared), show(t, actual))));
                let outside = self.count_outside(c, self.as_stored(declared), is_min);
                if outside > 0 {
                    let code = if is_min {
                        khronos::ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND
                    } else {
                        khronos::ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND
                    };
                    let message = format!(
                        "Accessor contains {outside} element(s) {relation} declared {word} value {}.",
                        show(t, declared)
                    );
                    self.findings.push((code, at, message));
                }
            }
        }
    }

    /// A declared bound with one number per component.
    fn declared(&self, accessor: Node, key: &str) -> Option<Vec<f64>> {
        let list = accessor.get(key)?.as_array()?;
        (list.len() == self.layout.components).then(|| {
            list.iter()
                .map(|v| v.as_f64().unwrap_or(f64::NAN))
                .collect()
        })
    }

    /// A declared bound as the data's own precision sees it.
    fn as_stored(&self, v: f64) -> f64 {
        if self.layout.component_type == gl::FLOAT {
            f64::from(v as f32)
        } else {
            v
        }
    }

    /// Counts the elements past a bound: a second walk, needed only when the bound is wrong.
    fn count_outside(&self, c: usize, bound: f64, is_min: bool) -> u64 {
        let mut outside = 0;
        let n = self.layout.components;
        visit(self.layout, self.bytes, |_, values| {
            for v in values.iter().skip(c).step_by(n) {
                outside += u64::from(if is_min { *v < bound } else { *v > bound });
            }
        });
        outside
    }
}

/// What maps a stored value to the value a shader sees (the glTF normalisation rules for
/// `normalized` integers); None when they are the same (floats and plain integers).
pub(crate) fn unit_scale(component_type: u64, accessor: Node) -> Option<fn(f64) -> f64> {
    let normalized = accessor.get("normalized").and_then(Node::as_bool) == Some(true);
    normalise(component_type).filter(|_| normalized)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, Ordering};

    #[test]
    fn a_walk_waits_to_read_until_the_bytes_held_leave_room() {
        let reading = Reading::default();
        let first = reading.hold(READ_AT_ONCE / 2 + 1);
        let second_held = AtomicBool::new(false);
        std::thread::scope(|scope| {
            scope.spawn(|| {
                let _second = reading.hold(READ_AT_ONCE / 2 + 1);
                second_held.store(true, Ordering::SeqCst);
            });
            std::thread::sleep(std::time::Duration::from_millis(50));
            assert!(!second_held.load(Ordering::SeqCst), "both held at once");
            drop(first);
        });
        assert!(second_held.load(Ordering::SeqCst));
        // A walk larger than the whole allowance still reads when nothing else is held.
        let _alone = reading.hold(2 * READ_AT_ONCE);
    }
}
