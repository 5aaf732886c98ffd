//! KHR_lights_punctual beyond its schema: properties a light type ignores, spot cone
//! angles in order, and node references to the root's lights (resolved, used).

use crate::check::context::{member, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::{Array, Node};

const EXTENSION: &str = "KHR_lights_punctual";

pub(crate) fn check(ctx: &mut Context) {
    let root = ctx.root.get("extensions").and_then(|e| e.get(EXTENSION));
    let lights: Array = root
        .and_then(|r| r.get("lights"))
        .and_then(Node::as_array)
        .unwrap_or_else(|| Array::empty(ctx.root));
    let base = format!("/extensions/{EXTENSION}/lights");
    for (i, light) in lights.iter().enumerate() {
        light_properties(ctx, light, &format!("{base}/{i}"));
    }
    let mut used = vec![false; lights.len()];
    for (_, pointer, node) in ctx.objects("nodes") {
        let Some(extension) = node.get("extensions").and_then(|e| e.get(EXTENSION)) else {
            continue;
        };
        let at = format!("{pointer}/extensions/{EXTENSION}");
        if root.is_none() {
            ctx.emit(
                khronos::UNSATISFIED_DEPENDENCY,
                at,
                format!("Dependency failed. '/extensions/{EXTENSION}' must be defined."),
            );
            continue;
        }
        let Some(light) = unsigned(extension, "light") else {
            continue;
        };
        match used.get_mut(light as usize) {
            Some(slot) => *slot = true,
            None => ctx.emit(
                khronos::UNRESOLVED_REFERENCE,
                member(&at, "light"),
                format!("Unresolved reference: {light}."),
            ),
        }
    }
    for (i, light) in lights.iter().enumerate() {
        if light.is_object() && !used[i] {
            ctx.emit(
                khronos::UNUSED_OBJECT,
                format!("{base}/{i}"),
                "This object may be unused.",
            );
        }
    }
}

fn light_properties(ctx: &mut Context, light: Node, at: &str) {
    let kind = light.get("type").and_then(Node::as_str);
    let extra = |key: &str| member(at, key);
    if kind != Some("spot") && kind.is_some() && light.get("spot").is_some() {
        ctx.emit(
            khronos::EXTRA_PROPERTY,
            extra("spot"),
            "This property should not be defined as it will not be used.",
        );
    }
    if kind == Some("directional") && light.get("range").is_some() {
        ctx.emit(
            khronos::EXTRA_PROPERTY,
            extra("range"),
            "This property should not be defined as it will not be used.",
        );
    }
    let Some(spot) = light.get("spot").filter(|_| kind == Some("spot")) else {
        return;
    };
    let angle = |key: &str, default: f64| spot.get(key).and_then(Node::as_f64).unwrap_or(default);
    let (inner, outer) = (
        angle("innerConeAngle", 0.0),
        angle("outerConeAngle", std::f64::consts::FRAC_PI_4),
    );
    if outer <= inner {
        ctx.emit(
            khronos::KHR_LIGHTS_PUNCTUAL_LIGHT_SPOT_ANGLES,
            member(&member(at, "spot"), "outerConeAngle"),
            format!("outerConeAngle ({outer}) is less than or equal to innerConeAngle ({inner})."),
        );
    }
}
