//! A KTX2 image whose width or height is not a multiple of 4.

use super::{Rule, Run};
use crate::check::context::Context;
use crate::diagnostic::Severity;
use crate::document::image_header::ImageFormat;

pub(super) const RULE: Rule = Rule::new(
    "KTX2_DIMENSIONS_NOT_MULTIPLE_OF_4",
    Severity::Error,
    "channels",
    "A KTX2 image's width or height is not a multiple of 4.",
    DOC,
    Run::document(check),
);

const DOC: &str = "\
## What it does
Reports a KTX2 image a texture reads through KHR_texture_basisu whose `pixelWidth` or
`pixelHeight` is not a multiple of 4.

## Why
KHR_texture_basisu: \"`pixelWidth` and `pixelHeight` MUST be multiples of 4.\" Basis Universal
transcodes to GPU block formats of 4×4 texels; on some of them (WebGL's compressed formats)
an image whose base level is not made of whole blocks is refused, and the texture is missing.
Resize or pad the source image before encoding.

## Example
A 250×250 KTX2 image bound through KHR_texture_basisu.
";

fn check(ctx: &mut Context) {
    let basisu = super::basisu_images(ctx);
    let sizes: Vec<(usize, u32, u32)> = (ctx.images.iter().enumerate())
        .filter(|(i, _)| basisu.contains(i))
        .filter_map(|(i, info)| Some((i, info.as_ref()?)))
        .filter(|(_, info)| info.format == ImageFormat::Ktx2)
        .filter(|(_, info)| info.width % 4 != 0 || info.height % 4 != 0)
        .map(|(i, info)| (i, info.width, info.height))
        .collect();
    for (index, width, height) in sizes {
        ctx.emit(
            RULE.code(),
            format!("/images/{index}"),
            format!("Image {index} is a KTX2 of {width}×{height} texels, not whole 4×4 blocks."),
        );
    }
}
