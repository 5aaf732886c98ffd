//! A KTX2 image laid out in a way KHR_texture_basisu does not allow.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::document::image_header::{
    ImageInfo, Ktx2Layout, Transfer, KHR_DF_MODEL_ETC1S, KHR_DF_MODEL_UASTC,
};

pub(super) const RULE: Rule = Rule::new(
    "KTX2_LAYOUT_INVALID",
    Severity::Error,
    "channels",
    "A KTX2 image is not the 2D Basis Universal texture (ETC1S with BasisLZ, or UASTC) KHR_texture_basisu allows.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a KTX2 image a texture reads through KHR_texture_basisu whose header or data format
descriptor breaks that extension's layout: a `vkFormat` other than 0 (not Basis Universal), a colour model other than ETC1S or
UASTC, ETC1S without BasisLZ supercompression or UASTC with a scheme other than none or
Zstandard, a channel layout other than RGB, RGBA, Red or Red-Green, a Red or Red-Green texture
encoded sRGB, or a texture that is not 2D (depth, array layers, cube faces). One finding per
image, naming every reason.

## Why
KHR_texture_basisu: \"this extension allows two Basis Universal formats: ETC1S with BasisLZ
and UASTC with optional Zstandard compression\", each with the DFD channels it lists; \"Red
… and Red-Green textures MUST NOT be encoded with the sRGB transfer function\"; and the image
\"MUST be of 2D type\". A viewer implementing the extension transcodes only those; anything
else is a texture it cannot show.

## Example
A texture's KHR_texture_basisu `source` naming a KTX2 in `VK_FORMAT_R8G8B8A8_SRGB`.
";

fn check(ctx: &mut Context) {
    let basisu = super::basisu_images(ctx);
    let found: Vec<(usize, Vec<String>)> = (ctx.images.iter().enumerate())
        .filter(|(i, _)| basisu.contains(i))
        .filter_map(|(i, info)| {
            let reasons = info.as_ref().map(reasons).unwrap_or_default();
            (!reasons.is_empty()).then_some((i, reasons))
        })
        .collect();
    for (index, reasons) in found {
        ctx.emit(
            RULE.code(),
            format!("/images/{index}"),
            format!(
                "Image {index} is a KTX2 that KHR_texture_basisu does not allow: {}.",
                reasons.join("; ")
            ),
        );
    }
}

/// Why a KTX2 image breaks the extension's layout (none for other formats and valid ones).
fn reasons(info: &ImageInfo) -> Vec<String> {
    let Some(layout) = &info.ktx2 else {
        return Vec::new();
    };
    let mut reasons = Vec::new();
    if layout.vk_format != 0 {
        reasons.push(format!(
            "its vkFormat is {}, not 0 (Basis Universal)",
            layout.vk_format
        ));
    } else if let Some(model) = layout.model {
        reasons.extend(model_reasons(layout, model, info.transfer));
    }
    if !layout.is_2d() {
        reasons.push(format!(
            "it is not 2D (depth {}, {} layers, {} faces)",
            layout.depth, layout.layers, layout.faces
        ));
    }
    reasons
}

/// The supercompression, channel and transfer reasons for a Basis Universal colour model.
fn model_reasons(layout: &Ktx2Layout, model: u8, transfer: Option<Transfer>) -> Vec<String> {
    let ids = layout.channel_ids.as_slice();
    // (scheme allowed, RGB/RGBA layouts, Red/Red-Green layouts) per the extension's lists.
    let (scheme_ok, colour, data) = match model {
        KHR_DF_MODEL_ETC1S => (
            layout.supercompression == 1,
            matches!(ids, [0] | [0, 15]),
            matches!(ids, [3] | [3, 4]),
        ),
        KHR_DF_MODEL_UASTC => (
            matches!(layout.supercompression, 0 | 2),
            matches!(ids, [0] | [3]),
            matches!(ids, [4] | [6]),
        ),
        other => {
            return vec![format!(
                "its colour model is {other}, neither ETC1S (163) nor UASTC (166)"
            )]
        }
    };
    let name = if model == KHR_DF_MODEL_ETC1S {
        "ETC1S"
    } else {
        "UASTC"
    };
    let mut reasons = Vec::new();
    if !scheme_ok {
        reasons.push(format!(
            "{name} with supercompression scheme {}",
            layout.supercompression
        ));
    }
    if !colour && !data {
        reasons.push(format!(
            "{name} with channels {ids:?}, not an RGB, RGBA, Red or Red-Green layout"
        ));
    }
    if data && transfer == Some(Transfer::Srgb) {
        reasons.push("a Red or Red-Green texture encoded sRGB".into());
    }
    reasons
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::document::image_header::{read, Channels, ImageFormat};

    fn layout(supercompression: u32, model: u8, ids: &[u8], transfer: Transfer) -> ImageInfo {
        ImageInfo {
            format: ImageFormat::Ktx2,
            width: 8,
            height: 8,
            channels: Channels::Unknown,
            bits: 8,
            transfer: Some(transfer),
            animated: false,
            custom_primaries: false,
            non_square_pixels: false,
            ktx2: Some(Ktx2Layout {
                vk_format: 0,
                supercompression,
                depth: 0,
                layers: 0,
                faces: 1,
                levels: 4,
                first_level_uncompressed: 0,
                model: Some(model),
                channel_ids: ids.to_vec(),
            }),
        }
    }

    #[test]
    fn each_broken_sentence_is_a_reason_and_the_allowed_layouts_have_none() {
        let (etc1s, uastc) = (KHR_DF_MODEL_ETC1S, KHR_DF_MODEL_UASTC);
        for allowed in [
            layout(1, etc1s, &[0, 15], Transfer::Srgb),
            layout(1, etc1s, &[3, 4], Transfer::Linear),
            layout(2, uastc, &[3], Transfer::Srgb),
            layout(0, uastc, &[6], Transfer::Linear),
        ] {
            assert_eq!(reasons(&allowed), Vec::<String>::new(), "{allowed:?}");
        }
        let broken = [
            (
                layout(2, etc1s, &[0], Transfer::Srgb),
                "supercompression scheme 2",
            ),
            (
                layout(1, uastc, &[0], Transfer::Srgb),
                "supercompression scheme 1",
            ),
            (layout(2, uastc, &[5], Transfer::Linear), "channels [5]"),
            (
                layout(2, uastc, &[4], Transfer::Srgb),
                "Red or Red-Green texture encoded sRGB",
            ),
            (layout(1, 170, &[0], Transfer::Srgb), "colour model is 170"),
        ];
        for (info, reason) in broken {
            let found = reasons(&info).join("; ");
            assert!(found.contains(reason), "{reason}: {found}");
        }
        let mut cube = layout(1, etc1s, &[0], Transfer::Srgb);
        cube.ktx2.as_mut().unwrap().faces = 6;
        assert!(reasons(&cube).join("").contains("not 2D"));
        let fixture = read(include_bytes!("../../../fixtures/ktx2/normal-uastc.ktx2")).unwrap();
        assert_eq!(reasons(&fixture), Vec::<String>::new());
    }
}
