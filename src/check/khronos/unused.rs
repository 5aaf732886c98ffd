//! UNUSED_OBJECT: objects nothing refers to (the Khronos notion: referenced by any object,
//! used or not; scenes and animations are roots and never unused).

use crate::check::context::Context;
use crate::diagnostic::khronos;

const COLLECTIONS: &[&str] = &[
    "accessors",
    "buffers",
    "bufferViews",
    "cameras",
    "images",
    "materials",
    "meshes",
    "nodes",
    "samplers",
    "skins",
    "textures",
];

pub fn check(ctx: &mut Context) {
    for collection in COLLECTIONS {
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
        .map_or(0, Vec::len);
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
