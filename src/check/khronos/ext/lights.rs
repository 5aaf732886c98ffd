//! KHR_lights_punctual beyond its schema: properties a light type ignores (a `spot` of a
//! light of another type is not read at all), spot cone
//! angles in order, and node references to the root's lights (resolved, used).

use crate::check::context::{member, unsigned, Context};
use crate::diagnostic::{khronos, Diagnostic, Sink};
use crate::document::{Array, Node, Tree};

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

/// Takes out of the tree the `spot` of each light whose `type` is not "spot" (absent, of
/// no type, another): the Khronos validator reads nothing in it, and reports it as a
/// property that will not be used, here (before the schema pass).
pub(crate) fn take_unread_spots(tree: &mut Tree, sink: &mut dyn Sink) {
    let lights =
        (tree.root().get("extensions")).and_then(|e| e.get(EXTENSION)?.get("lights")?.as_array());
    let unread: Vec<String> = (lights.into_iter().flatten().enumerate())
        .filter(|(_, light)| {
            light.get("spot").is_some() && light.get("type").and_then(Node::as_str) != Some("spot")
        })
        .map(|(i, _)| format!("/extensions/{EXTENSION}/lights/{i}/spot"))
        .collect();
    for pointer in unread {
        let message = "This property should not be defined as it will not be used.";
        sink.push(Diagnostic::at(
            khronos::EXTRA_PROPERTY,
            pointer.clone(),
            message,
        ));
        tree.remove(&pointer);
    }
}

fn light_properties(ctx: &mut Context, light: Node, at: &str) {
    let kind = light.get("type").and_then(Node::as_str);
    let extra = |key: &str| member(at, key);
    // A range that is no number above zero is read as none, and is not there to be extra.
    let range = light.get("range").and_then(Node::as_f64);
    if kind == Some("directional") && range.is_some_and(|r| r > 0.0) {
        ctx.emit(
            khronos::EXTRA_PROPERTY,
            extra("range"),
            "This property should not be defined as it will not be used.",
        );
    }
    let Some(spot) = light.get("spot").filter(|_| kind == Some("spot")) else {
        return;
    };
    // An angle that is no number in its range is read as none, and compared with nothing.
    let half_turn = std::f64::consts::FRAC_PI_2;
    let angle = |key: &str, default: f64, valid: &dyn Fn(f64) -> bool| match spot.get(key) {
        None => Some(default),
        Some(value) => value.as_f64().filter(|a| valid(*a)),
    };
    let inner = angle("innerConeAngle", 0.0, &|a| (0.0..half_turn).contains(&a));
    let outer = angle("outerConeAngle", half_turn / 2.0, &|a| {
        a > 0.0 && a <= half_turn
    });
    let Some((inner, outer)) = inner.zip(outer) else {
        return;
    };
    if outer <= inner {
        ctx.emit(
            khronos::KHR_LIGHTS_PUNCTUAL_LIGHT_SPOT_ANGLES,
            member(&member(at, "spot"), "outerConeAngle"),
            format!("outerConeAngle ({outer}) is less than or equal to innerConeAngle ({inner})."),
        );
    }
}
