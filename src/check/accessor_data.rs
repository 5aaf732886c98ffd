//! Accessor data: one pass over each accessor's elements for non-finite floats and for
//! `min` / `max` that do not match the data (the Khronos ACCESSOR_* data codes).

use super::context::{unsigned, Context};
use super::resources::view_bytes;
use crate::document::accessor_types::{component_count, component_size};
use rayon::prelude::*;
use serde_json::Value;

/// Calls `f(element, component, value)` for every component, values as stored (integers
/// not normalised). Dispatching on the component type once, outside the loop, keeps the
/// inner loop a plain load: this pass runs over every byte of large assets.
fn visit(layout: &Layout, bytes: &[u8], f: impl FnMut(usize, usize, f64)) {
    match layout.component_type {
        5120 => walk::<1>(layout, bytes, |b| f64::from(b[0] as i8), f),
        5121 => walk::<1>(layout, bytes, |b| f64::from(b[0]), f),
        5122 => walk::<2>(layout, bytes, |b| f64::from(i16::from_le_bytes(b)), f),
        5123 => walk::<2>(layout, bytes, |b| f64::from(u16::from_le_bytes(b)), f),
        5125 => walk::<4>(layout, bytes, |b| f64::from(u32::from_le_bytes(b)), f),
        _ => walk::<4>(layout, bytes, |b| f64::from(f32::from_le_bytes(b)), f),
    }
}

fn walk<const SIZE: usize>(
    layout: &Layout,
    bytes: &[u8],
    decode: impl Fn([u8; SIZE]) -> f64,
    mut f: impl FnMut(usize, usize, f64),
) {
    let element_size = SIZE * layout.components;
    for i in 0..layout.count {
        let start = layout.offset + i * layout.stride;
        let Some(element) = bytes.get(start..start + element_size) else {
            return;
        };
        for (c, raw) in element.chunks_exact(SIZE).enumerate() {
            let mut word = [0u8; SIZE];
            word.copy_from_slice(raw);
            f(i, c, decode(word));
        }
    }
}

struct Layout {
    component_type: u64,
    size: usize,
    components: usize,
    stride: usize,
    offset: usize,
    count: usize,
}

fn layout(ctx: &Context, accessor: &Value, view: usize) -> Option<Layout> {
    let component_type = unsigned(accessor, "componentType")?;
    let size = component_size(component_type)?;
    let kind = accessor.get("type")?.as_str()?;
    // Small-component matrices have padded columns, which this pass does not walk.
    if kind.starts_with("MAT") && kind != "MAT4" && size < 4 {
        return None;
    }
    let components = component_count(kind)?;
    let element = size * components;
    let stride = unsigned(&ctx.items("bufferViews")[view], "byteStride").unwrap_or(element as u64);
    Some(Layout {
        component_type,
        size,
        components,
        stride: usize::try_from(stride).ok()?,
        offset: usize::try_from(unsigned(accessor, "byteOffset").unwrap_or(0)).ok()?,
        count: usize::try_from(unsigned(accessor, "count")?).ok()?,
    })
}

fn show(component_type: u64, v: f64) -> String {
    if component_type == 5126 {
        format!("{v:?}")
    } else {
        format!("{v}")
    }
}

pub fn check(ctx: &mut Context) {
    // Accessors are independent and read-only here: scanned in parallel, reported in order.
    let work: Vec<(String, Layout, &[u8], &Value)> = ctx
        .objects("accessors")
        .into_iter()
        .filter_map(|(_, pointer, accessor)| {
            let (layout, bytes) = scannable(ctx, accessor)?;
            Some((pointer, layout, bytes, accessor))
        })
        .collect();
    let findings: Vec<Vec<Finding>> = work
        .par_iter()
        .map(|(_, layout, bytes, accessor)| scan(layout, bytes, accessor))
        .collect();
    let pointers: Vec<String> = work.into_iter().map(|(pointer, ..)| pointer).collect();
    for (pointer, found) in pointers.iter().zip(findings) {
        for (code, suffix, message) in found {
            ctx.emit(code, format!("{pointer}{suffix}"), message);
        }
    }
}

type Finding = (&'static str, String, String);

/// The accessor's layout and its view's bytes, when it is plain (not sparse) data that fits
/// its view (otherwise ACCESSOR_TOO_LONG or a schema code was reported).
fn scannable<'c>(ctx: &'c Context, accessor: &Value) -> Option<(Layout, &'c [u8])> {
    if accessor.get("sparse").is_some() {
        return None; // sparse substitution is not applied by this pass
    }
    let view = unsigned(accessor, "bufferView")? as usize;
    if view >= ctx.items("bufferViews").len() {
        return None;
    }
    let layout = layout(ctx, accessor, view)?;
    let bytes = view_bytes(ctx, view)?;
    let needed = layout
        .count
        .checked_sub(1)
        .and_then(|n| n.checked_mul(layout.stride))
        .and_then(|n| n.checked_add(layout.size * layout.components + layout.offset));
    (layout.count > 0 && needed.is_some_and(|n| n <= bytes.len())).then_some((layout, bytes))
}

/// Returns (code, pointer suffix, message) for every finding of one accessor.
fn scan(layout: &Layout, bytes: &[u8], accessor: &Value) -> Vec<Finding> {
    let n = layout.components;
    let mut actual_min = vec![f64::INFINITY; n];
    let mut actual_max = vec![f64::NEG_INFINITY; n];
    let declared = |key: &str| -> Option<Vec<f64>> {
        let list = accessor.get(key)?.as_array()?;
        (list.len() == n).then(|| {
            list.iter()
                .map(|v| v.as_f64().unwrap_or(f64::NAN))
                .collect()
        })
    };
    let is_float = layout.component_type == 5126;
    // Declared bounds as the data's own precision sees them.
    let as_stored = |v: f64| if is_float { f64::from(v as f32) } else { v };
    let (declared_min, declared_max) = (declared("min"), declared("max"));
    let mut below = vec![0u64; n];
    let mut above = vec![0u64; n];
    let mut findings = Vec::new();
    let lowest: Vec<f64> = declared_min
        .as_ref()
        .map_or(vec![f64::NEG_INFINITY; n], |m| {
            m.iter().map(|v| as_stored(*v)).collect()
        });
    let highest: Vec<f64> = declared_max.as_ref().map_or(vec![f64::INFINITY; n], |m| {
        m.iter().map(|v| as_stored(*v)).collect()
    });
    visit(layout, bytes, |i, c, v| {
        if !v.is_finite() {
            let what = if v.is_nan() {
                "NaN"
            } else if v > 0.0 {
                "Infinity"
            } else {
                "-Infinity"
            };
            findings.push((
                "ACCESSOR_INVALID_FLOAT",
                String::new(),
                format!("Accessor element at index {} is {what}.", i * n + c),
            ));
            return;
        }
        actual_min[c] = actual_min[c].min(v);
        actual_max[c] = actual_max[c].max(v);
        below[c] += u64::from(v < lowest[c]);
        above[c] += u64::from(v > highest[c]);
    });
    let t = layout.component_type;
    let bounds = [
        (
            "min",
            "minimum",
            "less than",
            &declared_min,
            &actual_min,
            &below,
            "ACCESSOR_MIN_MISMATCH",
            "ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND",
        ),
        (
            "max",
            "maximum",
            "greater than",
            &declared_max,
            &actual_max,
            &above,
            "ACCESSOR_MAX_MISMATCH",
            "ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND",
        ),
    ];
    for (key, word, relation, declared, actual, outside, mismatch, out_of_bound) in bounds {
        let Some(declared) = declared else { continue };
        for c in 0..n {
            if actual[c].is_finite() && as_stored(declared[c]) != actual[c] {
                findings.push((mismatch, format!("/{key}/{c}"), format!("Declared {word} value for this component ({}) does not match actual {word} ({}).", show(t, declared[c]), show(t, actual[c]))));
            }
            if outside[c] > 0 {
                findings.push((
                    out_of_bound,
                    format!("/{key}/{c}"),
                    format!(
                        "Accessor contains {} element(s) {relation} declared {word} value {}.",
                        outside[c],
                        show(t, declared[c])
                    ),
                ));
            }
        }
    }
    findings
}
