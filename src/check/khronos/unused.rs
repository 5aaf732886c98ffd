//! UNUSED_OBJECT: objects nothing refers to (the Khronos notion: referenced by any object,
//! used or not; scenes and animations are roots and never unused).

use crate::check::context::Context;
use crate::diagnostic::khronos;
use crate::document::Array;

/// Animations and scenes are used by being there; everything else by being referenced.
fn may_be_unused(collection: &str) -> bool {
    !matches!(collection, "animations" | "scenes")
}

pub(super) fn check(ctx: &mut Context) {
    for collection in crate::gltf::COLLECTIONS.iter().filter(|c| may_be_unused(c)) {
        for (i, pointer, _) in ctx.objects(collection) {
            if !ctx.is_used(collection, i) {
                ctx.emit(
                    khronos::UNUSED_OBJECT,
                    pointer,
                    "This object may be unused.",
                );
            }
        }
    }
    let variants = ctx
        .root
        .get("extensions")
        .and_then(|e| e.get("KHR_materials_variants"))
        .and_then(|v| v.get("variants"))
        .and_then(|v| v.as_array())
        .map_or(0, Array::len);
    for i in 0..variants {
        if !ctx.is_used("variants", i) {
            ctx.emit(
                khronos::UNUSED_OBJECT,
                format!("/extensions/KHR_materials_variants/variants/{i}"),
                "This object may be unused.",
            );
        }
    }
}
