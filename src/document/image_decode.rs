//! Decoding image pixels within fixed limits, whatever the header claims: one bound for the
//! checker's pixel rules, the converter's rebaking and the shading evaluator.

use image::{DynamicImage, ImageReader, Limits};
use std::io::Cursor;

/// Largest width or height decoded.
pub const MAX_DIMENSION: u32 = 16384;
/// Largest decoder allocation: an 8192² RGBA16 image.
pub const MAX_ALLOC: u64 = 512 * 1024 * 1024;

/// Why an image was not decoded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DecodeError {
    /// Larger than the limits above.
    #[error("larger than the decoding limits ({MAX_DIMENSION}² texels, {} MiB)", MAX_ALLOC >> 20)]
    Limit,
    /// Not decodable: the reason.
    #[error("{0}")]
    Invalid(String),
}

pub fn decode(bytes: &[u8]) -> Result<DynamicImage, DecodeError> {
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
