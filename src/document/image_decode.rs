//! Decoding image pixels within fixed limits, whatever the header claims: one bound for the
//! checker's pixel rules, the converter's rebaking and the shading evaluator.

use image::{DynamicImage, ImageReader, Limits};
use std::io::Cursor;

/// Largest width or height decoded.
pub(crate) const MAX_DIMENSION: u32 = 16384;
/// Largest decoder allocation: an 8192² RGBA16 image.
pub(crate) const MAX_ALLOC: u64 = 512 * 1024 * 1024;

/// Why an image was not decoded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(crate) enum DecodeError {
    /// Larger than the limits above.
    #[error("larger than the decoding limits ({MAX_DIMENSION}² texels, {} MiB)", MAX_ALLOC >> 20)]
    Limit,
    /// Not decodable: the reason.
    #[error("{0}")]
    Invalid(String),
    /// A valid image in an encoding gltfmat does not transcode (a KTX2 that is not Basis
    /// Universal LDR): which one.
    #[error("{0}")]
    NotTranscoded(String),
}

pub(crate) fn decode(bytes: &[u8]) -> Result<DynamicImage, DecodeError> {
    if bytes.starts_with(super::image_header::KTX2_MAGIC) {
        return decode_ktx2(bytes);
    }
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_DIMENSION);
    limits.max_image_height = Some(MAX_DIMENSION);
    limits.max_alloc = Some(MAX_ALLOC);
    let mut reader = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| DecodeError::Invalid(e.to_string()))?;
    reader.limits(limits);
    reader.decode().map_err(|e| match e {
        image::ImageError::Limits(_) => DecodeError::Limit,
        other => DecodeError::Invalid(other.to_string()),
    })
}

/// A KTX2 image's first level as 8-bit RGBA, transcoded from Basis Universal (ETC1S or UASTC,
/// with or without Zstandard) to uncompressed texels: what its blocks hold, as a viewer's
/// uncompressed fallback samples it. The stored encoding is kept (an sRGB texture stays
/// sRGB-encoded, as a PNG's texels do), and channels the file lacks read as the transcoder
/// fills them (RGB → alpha 1; RRR → grey).
fn decode_ktx2(bytes: &[u8]) -> Result<DynamicImage, DecodeError> {
    use basisu::{DecodeFlags, TargetFormat, Transcoder};
    let header = super::image_header::read(bytes).ok();
    let layout = (header.as_ref().and_then(|info| info.ktx2.as_ref()))
        .ok_or_else(|| DecodeError::Invalid("its KTX2 header ends early".into()))?;
    // vkFormat 0 (VK_FORMAT_UNDEFINED) is how KTX2 marks a Basis Universal payload; any other
    // is a plain GPU format, which KHR_texture_basisu does not allow.
    if layout.vk_format != 0 {
        return Err(DecodeError::NotTranscoded(format!(
            "a KTX2 texture in Vulkan format {}, not Basis Universal",
            layout.vk_format
        )));
    }
    check_ktx2_sizes(
        layout,
        header.as_ref().map_or((0, 0), |i| (i.width, i.height)),
    )?;
    let transcoder = Transcoder::new(bytes).map_err(|e| {
        DecodeError::Invalid(format!("not a readable Basis Universal KTX2 ({e:?})"))
    })?;
    if !transcoder.supports(TargetFormat::Rgba32) {
        return Err(DecodeError::NotTranscoded(format!(
            "a KTX2 texture in {:?}, which has no 8-bit form",
            transcoder.source_format()
        )));
    }
    let (width, height) = transcoder.base_dimensions();
    let bytes_needed = u64::from(width) * u64::from(height) * 4;
    if width > MAX_DIMENSION || height > MAX_DIMENSION || bytes_needed > MAX_ALLOC {
        return Err(DecodeError::Limit);
    }
    let texels =
        (transcoder.transcode(0, TargetFormat::Rgba32, DecodeFlags::NONE)).map_err(|e| {
            DecodeError::Invalid(format!(
                "its Basis Universal data cannot be transcoded ({e:?})"
            ))
        })?;
    image::RgbaImage::from_raw(width, height, texels)
        .map(DynamicImage::ImageRgba8)
        .ok_or_else(|| DecodeError::Invalid("its first level is smaller than its size".into()))
}

/// What a KTX2's header and first level entry claim, held to what glTF allows and its size
/// can hold, before the transcoder allocates by them: a 2D texture (KHR_texture_basisu: "MUST
/// be of 2D type"), and a Zstandard level no larger uncompressed than UASTC's 16 bytes per
/// 4×4 block of its texels (what a valid one is exactly). A stranger's file claiming a
/// terabyte is refused here, not allocated.
fn check_ktx2_sizes(
    layout: &super::image_header::Ktx2Layout,
    (width, height): (u32, u32),
) -> Result<(), DecodeError> {
    if !layout.is_2d() {
        return Err(DecodeError::Invalid(format!(
            "a KTX2 texture of depth {}, {} layers and {} faces is not the 2D texture KHR_texture_basisu requires",
            layout.depth, layout.layers, layout.faces
        )));
    }
    const ZSTANDARD: u32 = 2;
    let most = u64::from(width.div_ceil(4)) * u64::from(height.div_ceil(4)) * 16;
    let claimed = layout.first_level_uncompressed;
    if layout.supercompression == ZSTANDARD && claimed > most {
        return Err(DecodeError::Invalid(format!(
            "its first level claims {claimed} bytes uncompressed, more than the {most} its {width}×{height} texels hold"
        )));
    }
    Ok(())
}
