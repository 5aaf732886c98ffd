//! Decoding textures for the pixel rules (`--deep`), within fixed limits, and the counting
//! helper those rules share.

use crate::check::context::Context;
use crate::document::image_decode::{self, DecodeError};
use crate::gltf::coverage::Seen;
use image::DynamicImage;

/// A decoded image.
pub(crate) struct Texels {
    image: DynamicImage,
}

/// A decoded image as one texture binding samples it: where the binding's meshes are known,
/// only the texels they read are visited.
pub(crate) struct Sampled<'t> {
    texels: &'t Texels,
    seen: Option<&'t Seen>,
}

/// The share of the texels a mesh samples below which a defect found in a few texels is not
/// reported: one in a thousand. Fewer are isolated texels (compression noise, seams) that the
/// bilinear filter and the mip chain average with their neighbours; a real defect — a wrong map,
/// a flipped channel, a painted patch — covers far more.
pub(crate) const VISIBLE_SHARE: f64 = 0.001;

/// How many texels matched a predicate, with the first one as an example.
pub(crate) struct Tally {
    pub count: u64,
    pub total: u64,
    pub example: Option<(u32, u32, [f32; 4])>,
    /// Whether `total` counts only the texels a mesh samples.
    pub of_seen: bool,
}

/// Decodes image `index`, reporting IMAGE_UNDECODABLE or IMAGE_DECODE_LIMIT on failure, and
/// IMAGE_NOT_DECODED for a valid image in an encoding gltfmat does not transcode.
pub(crate) fn decode(ctx: &mut Context, index: usize) -> Option<Texels> {
    let (code, message) = match image_decode::decode(encoded(ctx, index)?) {
        Ok(image) => return Some(Texels { image }),
        Err(error @ DecodeError::Limit) => (
            crate::check::rules::decode_limit::RULE.code(),
            format!("Image is {error}; its pixel rules were skipped."),
        ),
        Err(DecodeError::NotTranscoded(what)) => (
            crate::check::rules::not_decoded::RULE.code(),
            format!("Image is {what}, whose texels gltfmat does not transcode; its pixel rules did not run."),
        ),
        Err(error) => (
            crate::check::rules::undecodable::RULE.code(),
            format!("Image data cannot be decoded: {error}."),
        ),
    };
    ctx.emit(code, format!("/images/{index}"), message);
    None
}

/// Decodes image `index` without reporting a failure: for a document rule that only looks
/// closer when it can (the pixel rules report what cannot be decoded).
pub(crate) fn decode_quietly(ctx: &Context, index: usize) -> Option<Texels> {
    let image = image_decode::decode(encoded(ctx, index)?).ok()?;
    Some(Texels { image })
}

/// The encoded bytes of image `index`, when they were read.
fn encoded<'c>(ctx: &'c Context, index: usize) -> Option<&'c [u8]> {
    ctx.image_bytes
        .get(index)?
        .as_deref()
        .map(|bytes| &bytes[..])
}

impl Texels {
    pub(crate) fn has_alpha(&self) -> bool {
        self.image.color().has_alpha()
    }

    /// Width and height in texels.
    pub(crate) fn size(&self) -> (u32, u32) {
        (self.image.width(), self.image.height())
    }

    /// This image as a binding samples it (`seen` None: every texel).
    pub(crate) fn as_seen<'t>(&'t self, seen: Option<&'t Seen>) -> Sampled<'t> {
        Sampled { texels: self, seen }
    }

    /// Calls `f(x, y, rgba)` for every texel, channels normalised to 0..1; greyscale is
    /// expanded to RGB and a missing alpha reads 1, as a renderer samples it.
    pub(crate) fn visit(&self, mut f: impl FnMut(u32, u32, [f32; 4])) {
        let width = self.image.width() as usize;
        if width == 0 {
            return;
        }
        match &self.image {
            DynamicImage::ImageLuma8(_)
            | DynamicImage::ImageLumaA8(_)
            | DynamicImage::ImageRgb8(_)
            | DynamicImage::ImageRgba8(_) => {
                let channels = usize::from(self.image.color().channel_count());
                let unit: [f32; 256] = std::array::from_fn(|v| v as f32 / 255.0);
                let rows = self.image.as_bytes().chunks_exact(width * channels);
                for (y, row) in rows.enumerate() {
                    for (x, t) in row.chunks_exact(channels).enumerate() {
                        let c = |i: usize| unit[usize::from(t[i])];
                        let rgba = match channels {
                            1 => [c(0), c(0), c(0), 1.0],
                            2 => [c(0), c(0), c(0), c(1)],
                            3 => [c(0), c(1), c(2), 1.0],
                            _ => [c(0), c(1), c(2), c(3)],
                        };
                        f(x as u32, y as u32, rgba);
                    }
                }
            }
            _ => {
                let wide = self.image.to_rgba32f();
                for (x, y, texel) in wide.enumerate_pixels() {
                    f(x, y, texel.0);
                }
            }
        }
    }

    /// Counts the texels for which `matches` holds.
    pub(crate) fn tally(&self, matches: impl FnMut([f32; 4]) -> bool) -> Tally {
        self.as_seen(None).tally(matches)
    }
}

impl Sampled<'_> {
    pub(crate) fn has_alpha(&self) -> bool {
        self.texels.has_alpha()
    }

    /// [`Texels::visit`] over the texels the binding samples.
    pub(crate) fn visit(&self, mut f: impl FnMut(u32, u32, [f32; 4])) {
        match self.seen {
            None => self.texels.visit(f),
            Some(seen) => self.texels.visit(|x, y, rgba| {
                if seen.contains(x, y) {
                    f(x, y, rgba)
                }
            }),
        }
    }

    /// Counts the sampled texels for which `matches` holds.
    pub(crate) fn tally(&self, mut matches: impl FnMut([f32; 4]) -> bool) -> Tally {
        let mut tally = Tally {
            count: 0,
            total: 0,
            example: None,
            of_seen: self.seen.is_some(),
        };
        self.visit(|x, y, rgba| {
            tally.total += 1;
            if matches(rgba) {
                tally.count += 1;
                tally.example.get_or_insert((x, y, rgba));
            }
        });
        tally
    }
}

impl Tally {
    pub(crate) fn fraction(&self) -> f64 {
        self.count as f64 / self.total.max(1) as f64
    }

    /// Whether the matching texels are enough to be seen: at least [`VISIBLE_SHARE`] of those
    /// counted, and at least one.
    pub(crate) fn visible(&self) -> bool {
        self.count > 0 && self.fraction() >= VISIBLE_SHARE
    }

    /// "3 of 16 texels (18.8%), e.g. texel (2, 0) = RGBA 8-bit (128, 128, 255, 255)".
    pub(crate) fn describe(&self) -> String {
        let example = self.example.map_or(String::new(), |(x, y, rgba)| {
            let [r, g, b, a] = rgba.map(|c| (c * 255.0).round() as u32);
            format!(", e.g. texel ({x}, {y}) = RGBA 8-bit ({r}, {g}, {b}, {a})")
        });
        format!(
            "{} of {} texels{} ({:.1}%){example}",
            self.count,
            self.total,
            if self.of_seen {
                " the meshes sample"
            } else {
                ""
            },
            100.0 * self.fraction()
        )
    }
}
