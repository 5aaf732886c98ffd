//! Cameras as the Khronos validator checks them beyond the schema: the projection object
//! the `type` names (the only one it reads, see `objects::take_unread_projections`), clip
//! planes in order, positive magnifications and a field of view below π.

use crate::check::context::{member, Context};
use crate::diagnostic::khronos;
use crate::document::Node;

pub(super) fn check(ctx: &mut Context) {
    for (_, pointer, camera) in ctx.objects("cameras") {
        // A camera holding both projections was reported before the schema pass, which took
        // out the one `type` does not name.
        let kind = camera.get("type").and_then(Node::as_str);
        for projection in ["perspective", "orthographic"] {
            if kind == Some(projection) && camera.get(projection).is_none() {
                ctx.emit(
                    khronos::UNDEFINED_PROPERTY,
                    pointer.clone(),
                    format!("Property '{projection}' must be defined."),
                );
            }
        }
        if let Some(perspective) = camera.get("perspective").filter(|p| p.is_object()) {
            projection(ctx, perspective, &member(&pointer, "perspective"), true);
        }
        if let Some(orthographic) = camera.get("orthographic").filter(|p| p.is_object()) {
            projection(ctx, orthographic, &member(&pointer, "orthographic"), false);
        }
    }
}

fn projection(ctx: &mut Context, projection: Node, at: &str, perspective: bool) {
    // A missing, mistyped or out-of-range number compares false, as NaN does (the validator
    // reads it as NaN): the schema reported it. znear, zfar and yfov must be positive; only an
    // orthographic znear may be 0.
    let number = |key: &str| (projection.get(key).and_then(Node::as_f64)).unwrap_or(f64::NAN);
    let positive = |key: &str| {
        let in_range = |v: &f64| *v > 0.0 || (*v == 0.0 && key == "znear" && !perspective);
        Some(number(key)).filter(in_range).unwrap_or(f64::NAN)
    };
    if positive("zfar") <= positive("znear") {
        ctx.emit(
            khronos::CAMERA_ZFAR_LEQUAL_ZNEAR,
            at,
            "zfar must be greater than znear.",
        );
    }
    if perspective {
        if positive("yfov") >= std::f64::consts::PI {
            ctx.emit(
                khronos::CAMERA_YFOV_GEQUAL_PI,
                at,
                "yfov should be less than Pi.",
            );
        }
        return;
    }
    for key in ["xmag", "ymag"] {
        let value = number(key);
        if value == 0.0 {
            ctx.emit(
                khronos::CAMERA_XMAG_YMAG_ZERO,
                member(at, key),
                "xmag and ymag must not be zero.",
            );
        } else if value < 0.0 {
            ctx.emit(
                khronos::CAMERA_XMAG_YMAG_NEGATIVE,
                member(at, key),
                "xmag and ymag should not be negative.",
            );
        }
    }
}
