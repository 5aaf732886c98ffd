//! Sparse accessors as the Khronos validator checks them: the sparse count against the
//! accessor's, each part (indices, values) inside its bufferView, and the indices' data,
//! strictly increasing and each below the accessor's count.

use super::resources::{fits_in_view, view_data};
use crate::check::context::{member, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::Node;
use crate::gltf::accessor::{component_count, component_size};

/// The sparse count and the placement of both parts (from the accessors pass).
pub(super) fn check_structure(ctx: &mut Context, accessor: Node, pointer: &str) {
    let Some(sparse) = accessor.get("sparse").filter(|s| s.is_object()) else {
        return;
    };
    let at = member(pointer, "sparse");
    let parts = ["indices", "values"].map(|key| (key, sparse.get(key)));
    for (key, part) in parts {
        if let Some(part) = part {
            ctx.reference(part, "bufferView", &member(&at, key), "bufferViews");
        }
    }
    let (Some(sparse_count), [(_, Some(indices)), (_, Some(values))]) =
        (unsigned(sparse, "count"), parts)
    else {
        return;
    };
    if let Some(count) = unsigned(accessor, "count").filter(|&count| sparse_count > count) {
        ctx.emit(
            khronos::ACCESSOR_SPARSE_COUNT_OUT_OF_RANGE,
            member(&at, "count"),
            format!("Sparse accessor overrides more elements ({sparse_count}) than the base accessor contains ({count})."),
        );
    }
    let index_size = unsigned(indices, "componentType").and_then(component_size);
    let value_size = unsigned(accessor, "componentType").and_then(component_size);
    let components = accessor
        .get("type")
        .and_then(Node::as_str)
        .and_then(component_count);
    let values_element = value_size.zip(components).map(|(size, n)| (size, size * n));
    for (key, part, sizes) in [
        ("indices", indices, index_size.map(|size| (size, size))),
        ("values", values, values_element),
    ] {
        // A view that is no object resolves to nothing (UNRESOLVED_REFERENCE), as one past
        // the end.
        let view = unsigned(part, "bufferView").map(|v| v as usize);
        let views = ctx.items("bufferViews");
        let Some(view) = view.filter(|&v| v < views.len() && views.at(v).is_object()) else {
            continue;
        };
        let part_at = member(&at, key);
        if ctx
            .items("bufferViews")
            .at(view)
            .get("byteStride")
            .is_some()
        {
            ctx.emit(
                khronos::BUFFER_VIEW_INVALID_BYTE_STRIDE,
                member(&part_at, "bufferView"),
                "Only buffer views with raw vertex data can have byteStride.",
            );
        }
        let Some((size, element)) = sizes else {
            continue;
        };
        let offset = unsigned(part, "byteOffset").unwrap_or(0);
        let length = (element as u64).checked_mul(sparse_count);
        fits_in_view(ctx, &part_at, view, offset, size as u64, length);
    }
}

/// The sparse indices of every accessor: strictly increasing, each naming an element the
/// accessor has (a pass after the buffers are read).
pub(super) fn check_indices(ctx: &mut Context) {
    for (_, pointer, accessor) in ctx.objects("accessors") {
        let Some(sparse) = accessor.get("sparse") else {
            continue;
        };
        let (Some(count), Some(indices)) =
            (unsigned(accessor, "count"), readable_indices(ctx, sparse))
        else {
            continue;
        };
        let at = member(&pointer, "sparse");
        let mut previous: Option<u64> = None;
        let mut findings = Vec::new();
        for (k, index) in indices.enumerate() {
            if let Some(last) = previous.filter(|&last| index <= last) {
                findings.push((
                    khronos::ACCESSOR_SPARSE_INDICES_NON_INCREASING,
                    format!("Accessor sparse indices element at index {k} is less than or equal to previous: {index} <= {last}."),
                ));
            }
            if index >= count {
                findings.push((
                    khronos::ACCESSOR_SPARSE_INDEX_OOB,
                    format!("Accessor sparse indices element at index {k} is greater than or equal to the number of accessor elements: {index} >= {count}."),
                ));
            }
            previous = Some(index);
        }
        for (code, message) in findings {
            ctx.emit(code, at.clone(), message);
        }
    }
}

/// The sparse indices, when their view holds all `sparse.count` of them.
pub(super) fn readable_indices<'c>(
    ctx: &'c Context,
    sparse: Node,
) -> Option<impl Iterator<Item = u64> + 'c> {
    let indices = sparse.get("indices")?;
    let size = unsigned(indices, "componentType").and_then(component_size)?;
    let view = view_data(ctx, unsigned(indices, "bufferView")? as usize)?;
    let start = usize::try_from(crate::gltf::byte_offset(indices)?).ok()?;
    let length = usize::try_from(unsigned(sparse, "count")?)
        .ok()?
        .checked_mul(size)?;
    let data = view.part(start..start.checked_add(length)?)?.read()?;
    Some((0..length / size).map(move |i| {
        let mut le = [0u8; 8];
        le[..size].copy_from_slice(&data[i * size..(i + 1) * size]);
        u64::from_le_bytes(le)
    }))
}
