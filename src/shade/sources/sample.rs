//! Material sampling: the BRDF inputs of a material at a texture coordinate. Textures are
//! decoded once, sampled bilinearly with repeat wrapping, decoded from sRGB or kept linear
//! per slot, and KHR_texture_transform is applied. Both glTF 2.0 materials and glTF 1.0
//! PBR-draft materials (their own model) are sampled.

use crate::document::image_header::Channels;
use crate::document::Node;
use crate::gltf::color::srgb_texel_to_linear;
use crate::gltf::material::{effective_texcoord, uv_transform};
use crate::legacy::blend::Blend;
use crate::legacy::pbr::{LegacyPbr, Model};
use crate::shade::brdf::V3;
use crate::shade::iridescence::Film;
use crate::shade::lanes::channels;
use crate::shade::material::{Inputs, SpecGlossReading};
use std::ops::Deref;
use std::sync::Arc;

/// A decoded texture, shared by the materials that bind it.
pub(crate) type Texture = Arc<TextureImage>;

/// Texels as the file stores them (its channels, 8 or 16 bits), read as RGBA values 0..1
/// (transfer functions are applied per slot). Nothing is widened when decoded: an 8192²
/// RGB PNG holds 201 MB, not the 268 MB of RGBA bytes (or 1 GiB of RGBA floats) on top of
/// the decoder's own buffer.
pub(crate) struct TextureImage {
    width: u32,
    height: u32,
    /// 1 (luminance), 2 (luminance, alpha), 3 (RGB) or 4 (RGBA).
    channels: usize,
    texels: Texels,
}

enum Texels {
    Unorm8(Vec<u8>),
    Unorm16(Vec<u16>),
    Float(Vec<f32>),
}

/// Its size and channels; the texels are too many to print.
impl std::fmt::Debug for TextureImage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        (f.debug_struct("TextureImage"))
            .field("width", &self.width)
            .field("height", &self.height)
            .field("channels", &self.channels)
            .finish_non_exhaustive()
    }
}

impl TextureImage {
    pub(crate) fn width(&self) -> u32 {
        self.width
    }

    pub(crate) fn height(&self) -> u32 {
        self.height
    }

    /// The image as the file stores it (no transfer function applied), reduced to at most
    /// `size` texels a side by taking the nearest texel: a thumbnail shows what the file holds.
    pub(crate) fn thumbnail(&self, size: u32) -> image::RgbaImage {
        let scale = (f64::from(self.width.max(self.height)) / f64::from(size.max(1))).max(1.0);
        let side = |n: u32| ((f64::from(n) / scale).round() as u32).max(1);
        image::RgbaImage::from_fn(side(self.width), side(self.height), |x, y| {
            let at = |i: u32, n: u32| (((f64::from(i) + 0.5) * scale) as i64).min(i64::from(n) - 1);
            let texel = self.decoded::<false>(at(x, self.width), at(y, self.height));
            image::Rgba(texel.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
        })
    }

    /// Clears `row[x]` wherever texel (x, y) does not hold what texel (x − 1, y) holds, as
    /// stored, and at x = 0 (no texel to its left); a row not held whole is cleared.
    fn clear_unlike_left(&self, y: u32, row: &mut [bool]) {
        // Texels as arrays of their `N` channels: compared as one value, not by a loop.
        fn clear_as<T: PartialEq, const N: usize>(raw: &[T], row: &mut [bool]) {
            let (texels, _) = raw.as_chunks::<N>();
            row[0] = false;
            for (flag, pair) in row[1..].iter_mut().zip(texels.windows(2)) {
                *flag &= pair[0] == pair[1];
            }
        }
        fn clear<T: PartialEq>(raw: &[T], n: usize, row: &mut [bool]) {
            match n {
                1 => clear_as::<T, 1>(raw, row),
                2 => clear_as::<T, 2>(raw, row),
                3 => clear_as::<T, 3>(raw, row),
                4 => clear_as::<T, 4>(raw, row),
                // No image has more channels; none would be said to repeat.
                _ => row.fill(false),
            }
        }
        let (n, width) = (self.channels, self.width as usize);
        let start = y as usize * width * n;
        let span = start..start + width * n;
        let held = match &self.texels {
            Texels::Unorm8(raw) => raw.get(span).map(|r| clear(r, n, row)),
            Texels::Unorm16(raw) => raw.get(span).map(|r| clear(r, n, row)),
            Texels::Float(raw) => raw.get(span).map(|r| clear(r, n, row)),
        };
        if held.is_none() || row.len() > width {
            row.fill(false);
        }
    }

    /// Whether it holds every texel its size says (a decoder may hand over fewer).
    fn complete(&self) -> bool {
        let wanted = self.width as usize * self.height as usize * self.channels;
        match &self.texels {
            Texels::Unorm8(raw) => raw.len() == wanted,
            Texels::Unorm16(raw) => raw.len() == wanted,
            Texels::Float(raw) => raw.len() == wanted,
        }
    }

    /// Texel (x, y) of a [`complete`](Self::complete) image as stored, its channels' bits
    /// packed into fields of at most 64 bits, handed to `push` with their widths (the same
    /// at every texel).
    #[inline(always)]
    pub(crate) fn stored_fields(&self, x: u32, y: u32, push: &mut impl FnMut(u64, u32)) {
        let n = self.channels;
        let at = (y as usize * self.width as usize + x as usize) * n;
        let bits = |per_channel: usize| (per_channel * n) as u32;
        match &self.texels {
            Texels::Unorm8(raw) => (raw.get(at..at + n).into_iter())
                .for_each(|t| push(t.iter().fold(0, |w, &c| w << 8 | u64::from(c)), bits(8))),
            Texels::Unorm16(raw) => (raw.get(at..at + n).into_iter())
                .for_each(|t| push(t.iter().fold(0, |w, &c| w << 16 | u64::from(c)), bits(16))),
            Texels::Float(raw) => (raw.get(at..at + n).into_iter().flatten())
                .for_each(|c| push(u64::from(c.to_bits()), 32)),
        }
    }

    /// Texel (x, y) as stored, its channels packed into one word, for an image of 8-bit
    /// channels with every texel held; `None` for any other.
    #[inline(always)]
    pub(crate) fn narrow_texel(&self, x: u32, y: u32) -> Option<u32> {
        let Texels::Unorm8(raw) = &self.texels else {
            return None;
        };
        let at = (y as usize * self.width as usize + x as usize) * self.channels;
        let texel = raw
            .get(at..at + self.channels)
            .filter(|_| self.complete())?;
        Some(texel.iter().fold(0, |w, &c| w << 8 | u32::from(c)))
    }

    /// Whether its texels have an alpha channel (luminance-alpha or RGBA), stored last.
    pub(crate) fn has_alpha(&self) -> bool {
        matches!(self.channels, 2 | 4)
    }

    /// Whether some 8-bit texel's alpha is below 1 (`false` without an alpha channel);
    /// `None` for texels of more than 8 bits, which this does not judge.
    pub(crate) fn has_translucent_texels(&self) -> Option<bool> {
        match &self.texels {
            _ if !self.has_alpha() => Some(false),
            Texels::Unorm8(raw) => Some(
                raw.chunks_exact(self.channels)
                    .any(|t| t[t.len() - 1] < 255),
            ),
            Texels::Unorm16(_) | Texels::Float(_) => None,
        }
    }

    /// Whether its texels have more than 8 bits (a rebake from it keeps 16 bits).
    pub(crate) fn is_wide(&self) -> bool {
        !matches!(self.texels, Texels::Unorm8(_))
    }

    /// The texel at column `x`, row `y` (inside the image), or transparent black if the
    /// texel data is short; its colour decoded from sRGB when `SRGB` (alpha is always
    /// linear), 8-bit texels through a table each.
    #[inline(always)]
    fn decoded<const SRGB: bool>(&self, x: i64, y: i64) -> [f64; 4] {
        let at = ((y * i64::from(self.width) + x) as usize) * self.channels;
        let texel = match &self.texels {
            Texels::Unorm8(raw) => {
                let unorm = unorm8_table();
                let colour = if SRGB { srgb8_table() } else { unorm };
                return (raw.get(at..at + self.channels)).map_or([0.0; 4], |p| {
                    let [r, g, b, _] = rgba(p, |&b| colour[usize::from(b)]);
                    let alpha = match p {
                        [_, a] | [_, _, _, a, ..] => unorm[usize::from(*a)],
                        _ => 1.0,
                    };
                    [r, g, b, alpha]
                });
            }
            // As the image crate's own widening (through f32), so 16-bit results do not
            // depend on where the conversion happens.
            Texels::Unorm16(raw) => (raw.get(at..at + self.channels))
                .map(|p| rgba(p, |&v| f64::from(f32::from(v) / 65535.0))),
            Texels::Float(raw) => {
                (raw.get(at..at + self.channels)).map(|p| rgba(p, |&v| f64::from(v)))
            }
        };
        let texel = texel.unwrap_or([0.0; 4]);
        if SRGB {
            let [r, g, b] = srgb3(texel);
            [r, g, b, texel[3]]
        } else {
            texel
        }
    }
}

/// One stored texel as RGBA: luminance stands for all three colours, and a texel with no
/// alpha is opaque.
#[inline(always)]
fn rgba<T>(stored: &[T], value: impl Fn(&T) -> f64) -> [f64; 4] {
    match stored {
        [l] => [value(l), value(l), value(l), 1.0],
        [l, a] => [value(l), value(l), value(l), value(a)],
        [r, g, b] => [value(r), value(g), value(b), 1.0],
        [r, g, b, a, ..] => [value(r), value(g), value(b), value(a)],
        [] => [0.0; 4],
    }
}

/// The linear value of every sRGB-encoded byte.
fn srgb8_table() -> &'static [f64; 256] {
    static TABLE: std::sync::OnceLock<[f64; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|b| srgb_texel_to_linear(b as f64 / 255.0)))
}

/// b / 255 for every byte: a lookup where sampling would divide four times per texel.
fn unorm8_table() -> &'static [f64; 256] {
    static TABLE: std::sync::OnceLock<[f64; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|b| b as f64 / 255.0))
}

/// `image` encoded as a PNG and decoded as the evaluator decodes it, for tests.
#[cfg(test)]
pub(crate) fn texture_of(image: impl Into<image::DynamicImage>) -> Texture {
    let mut png = Vec::new();
    (image.into())
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .expect("a PNG in memory");
    decode_all(&[Some(Ok(png))])
        .expect("a PNG decodes")
        .remove(0)
        .expect("one image")
}

/// A 2×2 RGB PNG of one colour, for tests that need a decoded texture.
#[cfg(test)]
pub(crate) fn solid_png(texel: [u8; 3]) -> Vec<u8> {
    let image = image::RgbImage::from_pixel(2, 2, image::Rgb(texel));
    let mut bytes = Vec::new();
    image::DynamicImage::ImageRgb8(image)
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .expect("a PNG in memory");
    bytes
}

/// Decodes one image no finer than `finest` texels a side where that saves memory (see
/// [`decode_png_reduced`]), otherwise as stored.
fn decode_at_most(bytes: &[u8], finest: u32) -> Result<Texture, String> {
    match decode_png_reduced(bytes, finest) {
        Some(reduced) => reduced.map(Arc::new),
        // Decoded whole after all (an interlaced PNG, another format): the set's budget took
        // it as reduced, so it is held to the budget on its own here.
        None => decode(bytes),
    }
}

/// A PNG larger than `finest` texels a side, read a row at a time and averaged in boxes of
/// k × k texels (k the smallest whole factor that brings it within `finest`), as stored
/// (the file's channels and bit depth; averaged in the file's encoding). The whole image is
/// never held: a preview of an 8192² texture takes the preview's texels, not 201 MB. None
/// when there is nothing to save (the image is small enough), or when the PNG is
/// interlaced or unreadable here: it is then decoded whole, which says why it is broken.
fn decode_png_reduced(bytes: &[u8], finest: u32) -> Option<Result<TextureImage, String>> {
    use crate::document::image_decode::MAX_DIMENSION;
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().ok()?;
    let info = reader.info();
    let (width, height) = (info.width, info.height);
    let too_large = width > MAX_DIMENSION || height > MAX_DIMENSION;
    if info.interlaced || too_large || width.max(height) <= finest.max(1) {
        return None;
    }
    let k = width.max(height).div_ceil(finest.max(1)) as usize;
    let (color, depth) = reader.output_color_type();
    let channels = color.samples();
    let wide = depth == png::BitDepth::Sixteen;
    let (width, height) = (width as usize, height as usize);
    let reduced_width = width.div_ceil(k);
    let mut sums = vec![0u64; reduced_width * channels];
    let mut averaged: Vec<u16> = Vec::with_capacity(reduced_width * height.div_ceil(k) * channels);
    for y in 0..height {
        let row = match reader.next_row() {
            Ok(Some(row)) => row.data(),
            Ok(None) => return Some(Err("the image data ends early".into())),
            Err(e) => return Some(Err(e.to_string())),
        };
        let sample_bytes = if wide { 2 } else { 1 };
        // One box of k texels at a time: no division per sample.
        let boxes = row
            .chunks(k * channels * sample_bytes)
            .zip(sums.chunks_mut(channels));
        for (texels, sum) in boxes {
            for texel in texels.chunks_exact(channels * sample_bytes) {
                for (c, sample) in texel.chunks_exact(sample_bytes).enumerate() {
                    sum[c] += u64::from(match sample {
                        [high, low] => u16::from_be_bytes([*high, *low]),
                        [value] => u16::from(*value),
                        _ => 0,
                    });
                }
            }
        }
        let band_ends = (y + 1) % k == 0 || y + 1 == height;
        if band_ends {
            let rows = (y % k + 1) as u64;
            for (i, sum) in sums.iter_mut().enumerate() {
                let x = i / channels;
                let columns = (width.min((x + 1) * k) - x * k) as u64;
                let texels = rows * columns;
                averaged.push(((*sum + texels / 2) / texels) as u16);
                *sum = 0;
            }
        }
    }
    let texels = match wide {
        true => Texels::Unorm16(averaged),
        false => Texels::Unorm8(averaged.into_iter().map(|v| v as u8).collect()),
    };
    Some(Ok(TextureImage {
        width: reduced_width as u32,
        height: height.div_ceil(k) as u32,
        channels,
        texels,
    }))
}

/// Decodes one image (see [`decode_each_at_most`] for a set of them), within
/// [`decode_budget`] of its bytes; an image another decode of this process still holds is
/// shared, not decoded again.
pub(crate) fn decode(bytes: &[u8]) -> Result<Texture, String> {
    within_budget(&[Some(bytes)], AS_STORED)?;
    if let Some(held) = Live::get(bytes, AS_STORED) {
        return Ok(held);
    }
    let texture = decode_whole(bytes)?;
    Live::put(bytes, AS_STORED, &texture);
    Ok(texture)
}

/// Decodes one image as stored, its size already judged.
fn decode_whole(bytes: &[u8]) -> Result<Texture, String> {
    use image::DynamicImage as Stored;
    let image = crate::document::image_decode::decode(bytes).map_err(|e| e.to_string())?;
    let (width, height) = (image.width(), image.height());
    let channels = usize::from(image.color().channel_count());
    let texels = match image {
        Stored::ImageLuma8(i) => Texels::Unorm8(i.into_raw()),
        Stored::ImageLumaA8(i) => Texels::Unorm8(i.into_raw()),
        Stored::ImageRgb8(i) => Texels::Unorm8(i.into_raw()),
        Stored::ImageRgba8(i) => Texels::Unorm8(i.into_raw()),
        Stored::ImageLuma16(i) => Texels::Unorm16(i.into_raw()),
        Stored::ImageLumaA16(i) => Texels::Unorm16(i.into_raw()),
        Stored::ImageRgb16(i) => Texels::Unorm16(i.into_raw()),
        Stored::ImageRgba16(i) => Texels::Unorm16(i.into_raw()),
        Stored::ImageRgb32F(i) => Texels::Float(i.into_raw()),
        other => {
            let texels = Texels::Float(other.into_rgba32f().into_raw());
            return Ok(Arc::new(TextureImage {
                width,
                height,
                channels: 4,
                texels,
            }));
        }
    };
    Ok(Arc::new(TextureImage {
        width,
        height,
        channels,
        texels,
    }))
}

/// The margin of the decode budget: decoded texels (as stored: the file's channels, 1 or 2
/// bytes each) may take [`DECODE_RATIO`] times the images' own bytes plus this, and never
/// more than [`DECODE_CEILING`]. However compressible a stranger makes an image (a flat
/// 16384² PNG of half a megabyte decodes to 1 GiB), a run holds in proportion to what it was
/// given; past the budget an image is refused from its header, before anything is decoded.
pub(crate) const DECODE_MARGIN: u64 = 96 << 20;

/// How many times their own bytes the images may take decoded. Real textures compress that
/// well: Khronos's ABeautifulGame holds 18 MiB of PNGs that decode to 396 MiB (22×), its
/// Sponza 40 MiB of JPEGs and PNGs that decode to 207 MiB; a flat image compresses a
/// thousandfold.
pub(crate) const DECODE_RATIO: u64 = 32;

/// The most decoded texels one set of images may take, however large its files.
pub(crate) const DECODE_CEILING: u64 = 2 << 30;

/// The decoded bytes allowed for images of `encoded` bytes in all (see [`DECODE_MARGIN`]).
pub(crate) fn decode_budget(encoded: u64) -> u64 {
    (encoded
        .saturating_mul(DECODE_RATIO)
        .saturating_add(DECODE_MARGIN))
    .min(DECODE_CEILING)
}

/// An image to decode: `None` when nothing samples it, `Some(Err(why))` when something does
/// but its bytes could not be read.
pub(crate) type Wanted<B> = Option<Result<B, String>>;

/// Decodes every wanted image as stored, for tests: an image that cannot be read or decoded
/// is an error (see [`decode_each_at_most`]).
#[cfg(test)]
pub(crate) fn decode_all<B: Deref<Target: AsRef<[u8]>> + Sync>(
    sources: &[Wanted<B>],
) -> Result<Vec<Option<Texture>>, String> {
    decode_each_at_most(sources, AS_STORED)?
        .into_iter()
        .collect()
}

/// The finest detail wanted when every texel counts (comparisons, proofs): images decoded
/// as stored.
pub(crate) const AS_STORED: u32 = u32::MAX;

/// Decodes every wanted image, one per available core (decoding a 2048² PNG takes tens of
/// milliseconds, and a comparison decodes every texture of both assets first), no finer than
/// `finest` texels a side (a preview): larger images may be decoded reduced to it (see
/// [`decode_png_reduced`]). Images with the same bytes are decoded once and shared, and the
/// decoded size of all of them together is held to [`decode_budget`] from their headers
/// before anything is decoded. Each image's failure is its own (`Err(why)` in its place,
/// for the caller to name the image): the materials that read it are not evaluated, the
/// others are. The outer error is the decoding budget's, which no set of images may pass.
pub(crate) fn decode_each_at_most<B: Deref<Target: AsRef<[u8]>> + Sync>(
    sources: &[Wanted<B>],
    finest: u32,
) -> Result<Vec<Result<Option<Texture>, String>>, String> {
    let unread: Vec<Option<String>> = (sources.iter())
        .map(|source| match source {
            Some(Err(why)) => Some(why.clone()),
            _ => None,
        })
        .collect();
    let bytes: Vec<Option<&[u8]>> = (sources.iter())
        .map(|source| match source {
            Some(Ok(bytes)) => Some((**bytes).as_ref()),
            _ => None,
        })
        .collect();
    let first_copy = first_copies(&bytes);
    let unique: Vec<Option<&[u8]>> = (bytes.iter().enumerate())
        .map(|(i, b)| b.filter(|_| first_copy[i] == i))
        .collect();
    within_budget(&unique, finest)?;
    // Images another decode of this process still holds are shared, not decoded again.
    let held: Vec<Option<Texture>> = (unique.iter())
        .map(|b| b.and_then(|b| Live::get(b, finest)))
        .collect();
    let to_decode: Vec<Option<&[u8]>> = (unique.iter().zip(&held))
        .map(|(bytes, held)| bytes.filter(|_| held.is_none()))
        .collect();
    let mut decoded = decode_in_parallel(&to_decode, finest);
    for (i, held) in held.into_iter().enumerate() {
        match (held, &decoded[i], to_decode[i]) {
            (Some(texture), _, _) => decoded[i] = Ok(Some(texture)),
            (None, Ok(Some(texture)), Some(bytes)) => Live::put(bytes, finest, texture),
            _ => {}
        }
    }
    for (i, &first) in first_copy.iter().enumerate() {
        if first != i {
            decoded[i] = decoded[first].clone();
        }
        if let Some(why) = &unread[i] {
            decoded[i] = Err(why.clone());
        }
    }
    Ok(decoded)
}

/// For each image, the index of the first image with the same bytes (itself if none).
fn first_copies(bytes: &[Option<&[u8]>]) -> Vec<usize> {
    use std::hash::{Hash, Hasher};
    let mut seen: std::collections::HashMap<u64, Vec<usize>> = Default::default();
    (bytes.iter().enumerate())
        .map(|(i, b)| {
            let Some(b) = b else { return i };
            let mut hasher = std::collections::hash_map::DefaultHasher::new();
            b.hash(&mut hasher);
            let same = seen.entry(hasher.finish()).or_default();
            let first = same.iter().copied().find(|&j| bytes[j] == Some(b));
            first.unwrap_or_else(|| {
                same.push(i);
                i
            })
        })
        .collect()
}

/// Refuses the set when the decoded texels their headers announce (a PNG wider than
/// `finest` as it is reduced while decoded) pass [`decode_budget`] of their bytes.
fn within_budget(unique: &[Option<&[u8]>], finest: u32) -> Result<(), String> {
    let encoded: u64 = unique.iter().flatten().map(|b| b.len() as u64).sum();
    let budget = decode_budget(encoded);
    let mut total = 0u64;
    for (i, bytes) in unique.iter().enumerate() {
        let Some(bytes) = bytes else { continue };
        total = total.saturating_add(decoded_size(bytes, finest));
        if total > budget {
            let size = crate::document::image_header::read(bytes)
                .map(|info| format!(" ({}×{})", info.width, info.height))
                .unwrap_or_default();
            return Err(format!(
                "image {i}{size} would take the decoded textures past {} MiB, this input's budget ({DECODE_RATIO} times its images' {} KiB plus {} MiB, at most {} MiB)",
                budget >> 20,
                encoded >> 10,
                DECODE_MARGIN >> 20,
                DECODE_CEILING >> 20
            ));
        }
    }
    Ok(())
}

/// The bytes an image takes once decoded, from its header (as stored: its channels at 1 or 2
/// bytes, 4 when unknown); a PNG wider than `finest` as it is reduced. 0 when the header
/// cannot be read: decoding says why.
fn decoded_size(bytes: &[u8], finest: u32) -> u64 {
    let Ok(info) = crate::document::image_header::read(bytes) else {
        return 0;
    };
    // A KTX2 is transcoded to 8-bit RGBA whatever channels it holds.
    let channels = match info.format {
        crate::document::image_header::ImageFormat::Ktx2 => Channels::Rgba,
        _ => info.channels,
    };
    let per_texel = match channels {
        Channels::Luminance => 1,
        Channels::LuminanceAlpha => 2,
        Channels::Rgb => 3,
        Channels::Rgba | Channels::Unknown => 4,
    } * if info.bits > 8 { 2 } else { 1 };
    let (mut width, mut height) = (u64::from(info.width), u64::from(info.height));
    let longest = width.max(height);
    if bytes.starts_with(b"\x89PNG") && longest > u64::from(finest.max(1)) {
        let k = longest.div_ceil(u64::from(finest.max(1)));
        (width, height) = (width.div_ceil(k), height.div_ceil(k));
    }
    width * height * per_texel
}

/// Textures decoded by this process that something still holds, by their bytes (length and
/// a hash keyed at random per process, so that no input can be made to collide with
/// another): a comparison or proof that decodes the same image for both of its assets (an
/// upgrade keeps most images as they are) decodes it once. Only weak references are kept,
/// so a texture lives no longer than its users.
struct Live {
    keys: std::collections::hash_map::RandomState,
    /// By (length, hash, the finest detail it was decoded for).
    textures: std::collections::HashMap<(usize, u64, u32), std::sync::Weak<TextureImage>>,
}

static LIVE: std::sync::Mutex<Option<Live>> = std::sync::Mutex::new(None);

impl Live {
    fn with<R>(f: impl FnOnce(&mut Live) -> R) -> R {
        let mut live = LIVE
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        f(live.get_or_insert_with(|| Live {
            keys: Default::default(),
            textures: Default::default(),
        }))
    }

    fn key(&self, bytes: &[u8], finest: u32) -> (usize, u64, u32) {
        use std::hash::BuildHasher;
        (bytes.len(), self.keys.hash_one(bytes), finest)
    }

    fn get(bytes: &[u8], finest: u32) -> Option<Texture> {
        Live::with(|live| live.textures.get(&live.key(bytes, finest))?.upgrade())
    }

    fn put(bytes: &[u8], finest: u32, texture: &Texture) {
        Live::with(|live| {
            live.textures.retain(|_, held| held.strong_count() > 0);
            let key = live.key(bytes, finest);
            live.textures.insert(key, Arc::downgrade(texture));
        })
    }
}

fn decode_in_parallel(
    sources: &[Option<&[u8]>],
    finest: u32,
) -> Vec<Result<Option<Texture>, String>> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let next = AtomicUsize::new(0);
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(sources.len());
    type Done = Vec<(usize, Result<Texture, String>)>;
    let finished: Vec<Done> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    // Each worker takes the next undecoded image until none is left.
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(source) = sources.get(i) else {
                            return done;
                        };
                        if let Some(bytes) = source {
                            done.push((i, decode_caught(bytes, finest)));
                        }
                    }
                })
            })
            .collect();
        // A worker's own failure is not an image's: it is raised, never a texture left out.
        (workers.into_iter())
            .map(|w| {
                w.join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
            })
            .collect()
    });
    let mut outcomes: Done = finished.into_iter().flatten().collect();
    outcomes.sort_by_key(|(i, _)| *i);
    let mut decoded: Vec<Result<Option<Texture>, String>> = vec![Ok(None); sources.len()];
    for (i, outcome) in outcomes {
        decoded[i] = outcome.map(Some);
    }
    decoded
}

/// [`decode_at_most`], with a panic inside the image libraries (hostile bytes they do not
/// survive) made that image's error rather than a texture silently missing.
fn decode_caught(bytes: &[u8], finest: u32) -> Result<Texture, String> {
    let decode = std::panic::AssertUnwindSafe(|| decode_at_most(bytes, finest));
    std::panic::catch_unwind(decode)
        .unwrap_or_else(|_| Err("its decoder failed on these bytes".to_string()))
}

/// Bilinear sample with repeat wrapping, texel centres at (i + ½) / size.
#[inline(always)]
pub(crate) fn bilinear(texture: &TextureImage, uv: [f64; 2]) -> [f64; 4] {
    sample_of::<false>(texture, uv, Sampler::default())
}

/// A sample of an sRGB-encoded colour texture as `sampler` filters and wraps it: RGB decoded
/// to linear texel by texel before the texels are mixed, as a GPU samples an sRGB texture
/// format ("the conversion … is performed before filtering"), alpha as stored.
pub(crate) fn sampled_srgb(texture: &TextureImage, uv: [f64; 2], sampler: Sampler) -> [f64; 4] {
    sample_of::<true>(texture, uv, sampler)
}

/// A sample as `sampler` filters and wraps it, colours decoded from sRGB when `SRGB`.
#[inline(always)]
fn sample_of<const SRGB: bool>(
    texture: &TextureImage,
    [u, v]: [f64; 2],
    sampler: Sampler,
) -> [f64; 4] {
    let (w, h) = (
        texture.width().max(1) as i64,
        texture.height().max(1) as i64,
    );
    let [wrap_s, wrap_t] = sampler.wrap;
    let texel = |i: i64, j: i64| texture.decoded::<SRGB>(wrap_s.texel(i, w), wrap_t.texel(j, h));
    if sampler.nearest {
        return texel(floor(u * w as f64), floor(v * h as f64));
    }
    let x = u * w as f64 - 0.5;
    let y = v * h as f64 - 0.5;
    let (x0, y0) = (floor(x), floor(y));
    let (fx, fy) = (x - x0 as f64, y - y0 as f64);
    if fx == 0.0 && fy == 0.0 {
        // Exactly on a texel centre (the comparison grid at texture resolution).
        return texel(x0, y0);
    }
    let (a, b, c, d) = (
        texel(x0, y0),
        texel(x0 + 1, y0),
        texel(x0, y0 + 1),
        texel(x0 + 1, y0 + 1),
    );
    std::array::from_fn(|k| {
        let top = a[k] * (1.0 - fx) + b[k] * fx;
        let bottom = c[k] * (1.0 - fx) + d[k] * fx;
        top * (1.0 - fy) + bottom * fy
    })
}

/// What a bilinear sample gives at the corner between four texels (`four`: the texel above
/// left, above right, below left, below right, each as [`sample_of`] gives it at its centre),
/// computed as [`sample_of`] computes it there (both weights ½): the same number, bit for bit.
#[inline(always)]
pub(crate) fn corner_of(four: [&[f64; 4]; 4]) -> [f64; 4] {
    let [a, b, c, d] = four;
    let half = 0.5;
    std::array::from_fn(|k| {
        let top = a[k] * (1.0 - half) + b[k] * half;
        let bottom = c[k] * (1.0 - half) + d[k] * half;
        top * (1.0 - half) + bottom * half
    })
}

/// ⌊x⌋ as an integer (saturating), by a cast: `f64::floor` is a library call on baseline
/// x86-64, and sampling floors two coordinates per texture per texel.
#[inline(always)]
fn floor(x: f64) -> i64 {
    let truncated = x as i64;
    if (truncated as f64) > x {
        truncated - 1
    } else {
        truncated
    }
}

/// Repeat wrapping; the division only for coordinates outside the texture.
#[inline(always)]
fn wrap(i: i64, size: i64) -> i64 {
    if (0..size).contains(&i) {
        i
    } else {
        i.rem_euclid(size)
    }
}

/// How a texture coordinate outside 0..1 reads the texture (glTF 2.0 `wrapS` / `wrapT`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub(crate) enum Wrap {
    /// 10497 REPEAT, the default.
    #[default]
    Repeat,
    /// 33071 CLAMP_TO_EDGE.
    Clamp,
    /// 33648 MIRRORED_REPEAT.
    Mirror,
}

impl Wrap {
    fn from_gl(value: Option<u64>) -> Wrap {
        match value {
            Some(33071) => Wrap::Clamp,
            Some(33648) => Wrap::Mirror,
            _ => Wrap::Repeat,
        }
    }

    #[inline(always)]
    pub(crate) fn texel(self, i: i64, size: i64) -> i64 {
        match self {
            Wrap::Repeat => wrap(i, size),
            Wrap::Clamp => i.clamp(0, size - 1),
            Wrap::Mirror => {
                let m = i.rem_euclid(2 * size);
                if m < size {
                    m
                } else {
                    2 * size - 1 - m
                }
            }
        }
    }
}

/// A texture's sampler as the evaluator reads it: its magnification filter and wrap modes.
/// (The comparison's grid is as fine as the finest texture, so no texture is minified.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub(crate) struct Sampler {
    /// `magFilter` 9728 NEAREST: the nearest texel, not the four around.
    pub nearest: bool,
    /// `wrapS`, `wrapT`.
    pub wrap: [Wrap; 2],
}

impl Sampler {
    /// A glTF 2.0 sampler object (absent members at their defaults: LINEAR, REPEAT).
    pub(crate) fn of(sampler: Option<Node>) -> Sampler {
        let gl = |key: &str| sampler.and_then(|s| s.get(key)).and_then(Node::as_u64);
        Sampler {
            nearest: gl("magFilter") == Some(9728),
            wrap: [Wrap::from_gl(gl("wrapS")), Wrap::from_gl(gl("wrapT"))],
        }
    }
}

/// A textureInfo of a 2.0 material: its texture and its UV transform.
#[derive(Clone)]
struct Binding {
    texture: Texture,
    sampler: Sampler,
    texcoord: u64,
    /// 2×3 affine matrix from KHR_texture_transform (identity when absent).
    transform: [f64; 6],
}

impl Binding {
    /// Its read at a point whose coordinates per set are `uvs`; a colour slot's (`srgb`)
    /// decoded to linear RGB.
    #[inline(always)]
    fn read(&self, uvs: &[[f64; 2]], srgb: bool) -> Read<'_> {
        Read {
            texture: &self.texture,
            at: self.coordinates(uvs),
            sampler: self.sampler,
            srgb,
        }
    }

    /// Where this binding reads a point whose coordinates per set are `uvs`.
    #[inline(always)]
    fn coordinates(&self, uvs: &[[f64; 2]]) -> [f64; 2] {
        // A point that carries fewer sets than the slot names (a UV grid) reads the first.
        let [u, v] = (uvs.get(self.texcoord as usize).or(uvs.first()))
            .copied()
            .unwrap_or([0.0, 0.0]);
        let t = self.transform;
        [t[0] * u + t[1] * v + t[2], t[3] * u + t[4] * v + t[5]]
    }
}

/// One texture read that a material's inputs are made of: the texture, where and how it is
/// read, and whether it holds colours (RGB decoded from sRGB before filtering).
pub(crate) struct Read<'t> {
    texture: &'t TextureImage,
    at: [f64; 2],
    sampler: Sampler,
    srgb: bool,
}

impl Read<'_> {
    /// The texels as a viewer samples them there.
    #[inline(always)]
    pub(crate) fn sampled(&self) -> [f64; 4] {
        match self.srgb {
            true => sample_of::<true>(self.texture, self.at, self.sampler),
            false => sample_of::<false>(self.texture, self.at, self.sampler),
        }
    }
}

/// What a texture read gives, when a material's inputs are made: sampled
/// ([`Read::sampled`]), or known beforehand (see [`MaterialSource::inputs_with`]).
pub(crate) trait Reader: FnMut(Read<'_>) -> [f64; 4] {}
impl<F: FnMut(Read<'_>) -> [f64; 4]> Reader for F {}

/// A 2.0 material's texture reads at one point, each through `read`.
struct Reads<'u, R> {
    uvs: &'u [[f64; 2]],
    read: R,
}

impl<R: Reader> Reads<'_, R> {
    #[inline(always)]
    fn colour(&mut self, binding: &Option<Binding>) -> Option<[f64; 4]> {
        let uvs = self.uvs;
        binding.as_ref().map(|b| (self.read)(b.read(uvs, true)))
    }

    #[inline(always)]
    fn data(&mut self, binding: &Option<Binding>) -> Option<[f64; 4]> {
        let uvs = self.uvs;
        binding.as_ref().map(|b| (self.read)(b.read(uvs, false)))
    }

    #[inline(always)]
    fn data_of(&mut self, binding: &Binding) -> [f64; 4] {
        (self.read)(binding.read(self.uvs, false))
    }
}

/// What a material is made of, ready to be sampled.
#[derive(Clone)]
pub(crate) enum MaterialSource {
    /// A glTF 2.0 material, its JSON resolved once into factors and texture bindings.
    Gltf2(Arc<Prepared>),
    /// A glTF 1.0 PBR-draft material with its two textures.
    Legacy {
        /// The draft material's parameters (boxed: a list of 10^5 sources, most of them
        /// glTF 2.0, then costs a pointer each rather than the draft's size).
        pbr: Box<LegacyPbr>,
        /// Its colour texture (diffuse or base colour).
        colour: Option<Texture>,
        /// Its data texture (metallic-roughness or specular-glossiness).
        data: Option<Texture>,
        /// The samplers of its colour and data textures.
        samplers: [Sampler; 2],
        /// How a specular-glossiness draft is read (see [`SpecGlossReading::DRAFTS`]).
        reading: SpecGlossReading,
        /// Whether both sides are drawn, where the 1.0 material says (its technique).
        double_sided: Option<bool>,
        /// Its textures that cannot be had, each with why (see [`MaterialSource::unmodelled`]).
        unread: Vec<String>,
    },
}

/// A glTF 2.0 material with every member looked up once (sampling runs per texel).
pub(crate) struct Prepared {
    factors: Inputs,
    /// baseColorFactor's (or diffuseFactor's) alpha.
    alpha: f64,
    alpha_mode: AlphaMode,
    spec_gloss: Option<SpecGloss>,
    base_colour: Option<Binding>,
    metallic_roughness: Option<Binding>,
    specular: Option<Binding>,
    specular_colour: Option<Binding>,
    sheen_colour: Option<Binding>,
    sheen_roughness: Option<Binding>,
    anisotropy: Option<Binding>,
    emissive: Option<Binding>,
    occlusion: Option<(Binding, f64)>,
    normal: Option<(Binding, f64)>,
    clearcoat: Option<Binding>,
    clearcoat_roughness: Option<Binding>,
    clearcoat_normal: Option<(Binding, f64)>,
    transmission: Option<Binding>,
    diffuse_transmission: Option<Binding>,
    diffuse_transmission_colour: Option<Binding>,
    volume: Volume,
    iridescence: Option<Binding>,
    /// KHR_materials_iridescence's thickness range (nanometres) and texture (G).
    film_thickness: ([f64; 2], Option<Binding>),
    pub has_sheen: bool,
    /// Whether both sides are drawn (`doubleSided`; for a 1.0 material, where it says).
    double_sided: Option<bool>,
    /// Only its emission and coverage are read (see [`MaterialSource::lit_legacy`]).
    lighting_unread: bool,
    /// What the evaluator cannot show of this material (see [`MaterialSource::unmodelled`]).
    unmodelled: Vec<String>,
    /// Every binding's texture, in [`Prepared::bindings`]' order: the per-point screens read
    /// the textures alone, and walking the slots for them costs more than what they read.
    textures: Vec<Texture>,
    /// The material's JSON and the identities of its decoded textures (see
    /// [`MaterialSource::fingerprint`]).
    fingerprint: String,
}

/// What is said of a glTF 1.0 material drawn by its technique's shaders or by
/// KHR_materials_common's lighting ("color = <emission> + <ambient> * al + …"): the light it
/// emits and how much of the background it hides. Its lighting is a model the evaluator
/// does not shade.
pub(crate) struct LitLegacy {
    /// The emission's colour, linear (1.0 colours are display values, linearised).
    pub emission: V3,
    /// The emission's texture (sRGB), multiplying the colour.
    pub emission_texture: Option<(Texture, Sampler)>,
    /// The opacity: the diffuse colour's alpha times `transparency`.
    pub alpha: f64,
    /// The diffuse texture, whose alpha multiplies `alpha`.
    pub alpha_texture: Option<(Texture, Sampler)>,
    /// How it is blended; `None` when it is not (opaque).
    pub blend: Option<Blend>,
    /// Whether both sides are drawn, where the material says.
    pub double_sided: Option<bool>,
}

/// What a [`LitLegacy`] material leaves out, as [`MaterialSource::unmodelled`] says it.
pub(crate) const LIGHTING_UNREAD: &str = "its lighting (a glTF 1.0 technique's shaders or KHR_materials_common's Blinn, Phong, Lambert or constant model, which the evaluator does not shade): only its emission and coverage are compared";

/// glTF 2.0 `alphaMode`: how the base colour's alpha becomes coverage.
#[derive(Clone, Copy, Debug, PartialEq)]
enum AlphaMode {
    /// "The rendered output is fully opaque and any alpha value is ignored."
    Opaque,
    /// "Fully opaque or fully transparent depending on the alpha value and the specified
    /// alphaCutoff value": opaque where alpha ≥ the cutoff.
    Mask(f64),
    /// "The alpha value is used to composite the source and destination areas."
    Blend,
}

impl AlphaMode {
    fn coverage(self, alpha: f64) -> f64 {
        match self {
            AlphaMode::Opaque => 1.0,
            AlphaMode::Mask(cutoff) => f64::from(u8::from(alpha >= cutoff)),
            AlphaMode::Blend => alpha.clamp(0.0, 1.0),
        }
    }
}

/// KHR_materials_volume: thickness (factor × texture G) and the medium's attenuation.
struct Volume {
    thickness: f64,
    texture: Option<Binding>,
    attenuation_colour: V3,
    attenuation_distance: f64,
}

impl Volume {
    /// "T(x) = c^(x/d)" through `thickness`; a thickness of 0 is thin-walled (nothing is
    /// attenuated), as is an attenuation distance of +∞ (the default).
    fn transmittance(&self, thickness: f64) -> V3 {
        if thickness <= 0.0 || !self.attenuation_distance.is_finite() {
            return [1.0; 3];
        }
        let exponent = thickness / self.attenuation_distance.max(f64::MIN_POSITIVE);
        self.attenuation_colour.map(|c| c.max(0.0).powf(exponent))
    }
}

struct SpecGloss {
    diffuse: V3,
    specular: V3,
    glossiness: f64,
    diffuse_texture: Option<Binding>,
    specular_glossiness_texture: Option<Binding>,
}

/// The material extensions the evaluator draws. Any other extension on a material is
/// reported as not evaluated.
const MODELLED_EXTENSIONS: [&str; 12] = [
    "KHR_materials_iridescence",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_unlit",
    "KHR_materials_specular",
    "KHR_materials_ior",
    "KHR_materials_sheen",
    "KHR_materials_anisotropy",
    "KHR_materials_emissive_strength",
    "KHR_materials_clearcoat",
    "KHR_materials_transmission",
    "KHR_materials_volume",
    "KHR_materials_diffuse_transmission",
];

/// A texture read through texCoord 0, untransformed.
fn plain_binding((texture, sampler): (Texture, Sampler)) -> Binding {
    Binding {
        texture,
        sampler,
        texcoord: 0,
        transform: [1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
    }
}

impl Prepared {
    /// A material that emits `factors.emission` (times `emissive`), hides the background by
    /// `alpha` (times `base_colour`'s alpha) as `alpha_mode` says, and reflects nothing:
    /// black, no specular lobe.
    fn emitting_only(
        emission: V3,
        emissive: Option<Binding>,
        alpha: f64,
        base_colour: Option<Binding>,
        alpha_mode: AlphaMode,
    ) -> Prepared {
        let factors = Inputs {
            base_color: [0.0; 3],
            metallic: 0.0,
            specular: 0.0,
            emission,
            ..Inputs::default()
        };
        let mut prepared = Prepared {
            factors,
            alpha,
            alpha_mode,
            spec_gloss: None,
            base_colour,
            metallic_roughness: None,
            specular: None,
            specular_colour: None,
            sheen_colour: None,
            sheen_roughness: None,
            anisotropy: None,
            emissive,
            occlusion: None,
            normal: None,
            clearcoat: None,
            clearcoat_roughness: None,
            clearcoat_normal: None,
            transmission: None,
            diffuse_transmission: None,
            diffuse_transmission_colour: None,
            volume: Volume {
                thickness: 0.0,
                texture: None,
                attenuation_colour: [1.0; 3],
                attenuation_distance: f64::INFINITY,
            },
            iridescence: None,
            film_thickness: ([100.0, 400.0], None),
            has_sheen: false,
            double_sided: None,
            lighting_unread: false,
            unmodelled: Vec::new(),
            fingerprint: String::new(),
            textures: Vec::new(),
        };
        let bound: Vec<_> = (prepared.bindings())
            .map(|b| (Arc::as_ptr(&b.texture), b.sampler, b.texcoord, b.transform))
            .collect();
        prepared.fingerprint =
            format!("emitting only|{emission:?}|{alpha}|{alpha_mode:?}|{bound:?}");
        prepared.textures = prepared.bindings().map(|b| b.texture.clone()).collect();
        prepared
    }
}

impl MaterialSource {
    /// A glTF 1.0 material drawn by a technique's shaders or by KHR_materials_common: its
    /// emission and coverage, nothing reflected. Compared with another material, that one is
    /// seen the same way ([`MaterialSource::emission_and_coverage`]), and the pair is never
    /// the same: its lighting is `LIGHTING_UNREAD`.
    pub(crate) fn lit_legacy(lit: LitLegacy) -> MaterialSource {
        let alpha_mode = match lit.blend {
            None => AlphaMode::Opaque,
            Some(_) => AlphaMode::Blend,
        };
        let mut prepared = Prepared::emitting_only(
            lit.emission,
            lit.emission_texture.map(plain_binding),
            lit.alpha,
            lit.alpha_texture.map(plain_binding),
            alpha_mode,
        );
        prepared.factors.premultiplied = lit.blend == Some(Blend::Premultiplied);
        prepared.lighting_unread = true;
        prepared.double_sided = lit.double_sided;
        prepared.unmodelled.push(LIGHTING_UNREAD.into());
        prepared.fingerprint += &format!("|{:?}|{:?}", lit.blend, lit.double_sided);
        MaterialSource::Gltf2(Arc::new(prepared))
    }

    /// Whether only this material's emission and coverage are read
    /// ([`MaterialSource::lit_legacy`]).
    pub(crate) fn lighting_unread(&self) -> bool {
        matches!(self, MaterialSource::Gltf2(p) if p.lighting_unread)
    }

    /// This material seen as a [`MaterialSource::lit_legacy`] one is: its emission (an unlit
    /// material's colour, which is what it emits) and its coverage, nothing reflected.
    pub(crate) fn emission_and_coverage(&self) -> MaterialSource {
        let prepared = match self {
            MaterialSource::Gltf2(p) if p.lighting_unread => return self.clone(),
            MaterialSource::Gltf2(p) => {
                // KHR_materials_unlit: "the base color is the final color", which is what it
                // emits.
                let (emission, emissive) = match p.factors.unlit {
                    true => (p.factors.base_color, p.base_colour.clone()),
                    false => (p.factors.emission, p.emissive.clone()),
                };
                let colour_texture = match &p.spec_gloss {
                    Some(sg) => sg.diffuse_texture.clone(),
                    None => p.base_colour.clone(),
                };
                let mut emitting = Prepared::emitting_only(
                    emission,
                    emissive,
                    p.alpha,
                    colour_texture,
                    p.alpha_mode,
                );
                // What could not be read of it still is not (an emissive texture, say).
                emitting.unmodelled = p.unmodelled.clone();
                emitting
            }
            MaterialSource::Legacy {
                pbr,
                colour,
                samplers,
                ..
            } => Prepared::emitting_only(
                [0.0; 3],
                None,
                pbr.colour[3],
                colour.clone().map(|t| plain_binding((t, samplers[0]))),
                AlphaMode::Blend,
            ),
        };
        MaterialSource::Gltf2(Arc::new(prepared))
    }

    /// Prepares a glTF 2.0 material written as a `serde_json::Value` (read as the tree a
    /// document's is); `textures` are the document's, by texture index.
    #[cfg(test)]
    pub(crate) fn gltf2(material: &serde_json::Value, textures: &[Option<Texture>]) -> Self {
        let tree = crate::document::Tree::of(material);
        let textures = TextureSet {
            images: textures,
            ..TextureSet::default()
        };
        MaterialSource::gltf2_sampled(tree.root(), &textures)
    }

    /// Prepares a glTF 2.0 material whose textures are `textures`.
    pub(crate) fn gltf2_sampled(material: Node, textures: &TextureSet) -> MaterialSource {
        MaterialSource::Gltf2(Arc::new(prepare(material, textures)))
    }
}

fn colour3(value: Option<Node>, default: V3) -> V3 {
    value.and_then(Node::as_array).map_or(default, |a| {
        [0, 1, 2].map(|i| a.get(i).and_then(Node::as_f64).unwrap_or(default[i]))
    })
}

fn member<'t>(object: Option<Node<'t>>, key: &str) -> Option<Node<'t>> {
    object.and_then(|o| o.get(key))
}

fn number(object: Option<Node>, key: &str, default: f64) -> f64 {
    object
        .and_then(|o| o.get(key))
        .and_then(Node::as_f64)
        .unwrap_or(default)
}

/// sRGB decode of a texel's colour.
#[inline(always)]
fn srgb3(t: [f64; 4]) -> V3 {
    channels(|i| srgb_texel_to_linear(t[i]))
}

/// A sample's colour channels.
#[inline(always)]
fn rgb(t: [f64; 4]) -> V3 {
    [t[0], t[1], t[2]]
}

impl MaterialSource {
    /// Every texture the material reads (a glTF 2.0 material's in its bindings' order).
    #[inline(always)]
    fn textures(&self) -> impl Iterator<Item = &Texture> {
        let (bound, legacy) = match self {
            MaterialSource::Gltf2(p) => (&p.textures[..], None),
            MaterialSource::Legacy { colour, data, .. } => (&[][..], Some([colour, data])),
        };
        bound.iter().chain(legacy.into_iter().flatten().flatten())
    }

    /// The highest texture resolution involved (for the comparison grid).
    pub(crate) fn max_resolution(&self) -> u32 {
        (self.textures())
            .map(|t| t.width().max(t.height()))
            .max()
            .unwrap_or(1)
    }

    /// A key equal for two sources that evaluate the same way (the same JSON or parameters,
    /// the same decoded textures, the same reading), so that a comparison of identical pairs
    /// is made once.
    pub(crate) fn fingerprint(&self) -> String {
        match self {
            MaterialSource::Gltf2(prepared) => prepared.fingerprint.clone(),
            MaterialSource::Legacy {
                pbr,
                colour,
                data,
                samplers,
                reading,
                double_sided,
                unread,
            } => format!(
                "{pbr:?}|{:?}|{:?}|{samplers:?}|{reading:?}|{double_sided:?}|{unread:?}",
                colour.as_ref().map(Arc::as_ptr),
                data.as_ref().map(Arc::as_ptr)
            ),
        }
    }

    /// This material read as `wanted` when its text can be read several ways (a 1.0
    /// specular-glossiness draft material); itself otherwise.
    pub(crate) fn read_as(&self, wanted: SpecGlossReading) -> MaterialSource {
        match self {
            MaterialSource::Legacy {
                pbr,
                colour,
                data,
                samplers,
                double_sided,
                unread,
                ..
            } if pbr.model == Model::SpecularGlossiness => MaterialSource::Legacy {
                pbr: pbr.clone(),
                colour: colour.clone(),
                data: data.clone(),
                samplers: *samplers,
                reading: wanted,
                double_sided: *double_sided,
                unread: unread.clone(),
            },
            _ => self.clone(),
        }
    }

    /// Whether both of its sides are drawn; `None` for a 1.0 material that does not say (no
    /// technique), whose back is then not compared.
    pub(crate) fn double_sided(&self) -> Option<bool> {
        match self {
            MaterialSource::Gltf2(prepared) => prepared.double_sided,
            MaterialSource::Legacy { double_sided, .. } => *double_sided,
        }
    }

    /// What a culled back face shows: nothing, the background whole.
    pub(crate) fn invisible() -> MaterialSource {
        let mut prepared = Prepared::emitting_only([0.0; 3], None, 0.0, None, AlphaMode::Blend);
        prepared.fingerprint = "invisible".into();
        MaterialSource::Gltf2(Arc::new(prepared))
    }

    /// The readings of its text other than the one it is read as: the other draft
    /// readings for a 1.0 specular-glossiness material, none otherwise.
    pub(crate) fn other_readings(&self) -> Vec<MaterialSource> {
        match self {
            MaterialSource::Legacy { pbr, reading, .. }
                if pbr.model == Model::SpecularGlossiness =>
            {
                (SpecGlossReading::DRAFTS.iter())
                    .filter(|&&other| other != *reading)
                    .map(|&other| self.read_as(other))
                    .collect()
            }
            _ => Vec::new(),
        }
    }

    /// The texCoord sets its textures are read through, each once, in order (none for a
    /// material without textures; set 0 for a 1.0 one: the PBR drafts bind one set).
    pub(crate) fn texcoord_sets(&self) -> Vec<usize> {
        let mut sets: Vec<usize> = match self {
            MaterialSource::Gltf2(p) => p.bindings().map(|b| b.texcoord as usize).collect(),
            MaterialSource::Legacy { .. } => vec![0],
        };
        sets.sort_unstable();
        sets.dedup();
        sets
    }

    /// Whether a texture is read through a texCoord set other than 0 (a 1.0 draft's never is).
    pub(crate) fn reads_other_sets(&self) -> bool {
        match self {
            MaterialSource::Gltf2(p) => p.bindings().any(|b| b.texcoord > 0),
            MaterialSource::Legacy { .. } => false,
        }
    }

    /// Whether every input is an affine function of texels stored on a `grid`² grid: every
    /// texture is `grid`² and read without a transform, and no input bends its texels (a
    /// normal normalised, an anisotropy direction's angle, a MASK threshold on a texture's
    /// alpha, a volume's power, spec-gloss's diffuse · (1 − max specular)). Then its inputs
    /// at a texel corner are the mean of those at the four centres around it.
    pub(crate) fn linear_on(&self, grid: u32) -> bool {
        let on_grid = |t: &TextureImage| t.width() == grid && t.height() == grid;
        match self {
            MaterialSource::Gltf2(p) => {
                let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
                let bends = p.spec_gloss.is_some()
                    || p.anisotropy.is_some()
                    || p.normal.is_some()
                    || p.clearcoat_normal.is_some()
                    || p.volume.texture.is_some()
                    || (matches!(p.alpha_mode, AlphaMode::Mask(_)) && p.base_colour.is_some());
                !bends
                    && p.bindings()
                        .all(|b| on_grid(&b.texture) && b.transform == identity)
            }
            MaterialSource::Legacy {
                pbr,
                colour,
                data,
                samplers,
                ..
            } => {
                pbr.model == Model::MetalRoughness
                    && colour.iter().chain(data).all(|t| on_grid(t))
                    && samplers.iter().all(|s| !s.nearest)
            }
        }
    }

    /// Whether each of its textures is read on the `grid`² comparison grid as stored: every
    /// texture is `grid`² (every texel held), read without a transform and filtered linearly, and `grid` is a
    /// power of two (so a texel centre and a corner are exact coordinates: a centre reads one
    /// texel, a corner the mean of four). Then [`MaterialSource::clear_unlike_left`] can tell,
    /// from the stored texels alone, that a point's inputs are its left neighbour's.
    pub(crate) fn texels_on(&self, grid: u32) -> bool {
        let as_stored = |t: &TextureImage, sampler: Sampler| {
            t.width() == grid && t.height() == grid && !sampler.nearest && t.complete()
        };
        grid.is_power_of_two()
            && match self {
                MaterialSource::Gltf2(p) => {
                    let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
                    p.bindings()
                        .all(|b| as_stored(&b.texture, b.sampler) && b.transform == identity)
                }
                MaterialSource::Legacy {
                    colour,
                    data,
                    samplers,
                    ..
                } => [colour, data]
                    .into_iter()
                    .zip(samplers)
                    .all(|(t, sampler)| t.as_deref().is_none_or(|t| as_stored(t, *sampler))),
            }
    }

    /// For a material whose textures are [`MaterialSource::texels_on`] the grid: clears
    /// `row[x]` wherever some texture's texel (x, y) differs from texel (x − 1, y), as stored,
    /// and at x = 0. A centre whose flag stays set reads what its left neighbour reads, and so
    /// does a corner whose four texels' flags do (the two around it in its row and in the row
    /// above): its inputs are that point's.
    pub(crate) fn clear_unlike_left(&self, y: u32, row: &mut [bool]) {
        self.textures().for_each(|t| t.clear_unlike_left(y, row));
    }

    /// For a material whose textures are [`MaterialSource::texels_on`] the grid: the
    /// textures whose stored texels a centre reads, in turn, but those `left_out` marks (by
    /// their place in that order). Two centres where each of them stores the same texel
    /// ([`TextureImage::stored_fields`]) have equal inputs but for the textures left out.
    pub(crate) fn keyed_textures(&self, left_out: &[bool]) -> Vec<&TextureImage> {
        let left_out = left_out.iter().chain(std::iter::repeat(&false));
        (self.textures().zip(left_out))
            .filter(|(_, &out)| !out)
            .map(|(t, _)| &**t)
            .collect()
    }

    /// For each of this material's textures (in [`MaterialSource::keyed_textures`]' order),
    /// whether every one of `others` reads the same decoded image: where all read textures as
    /// stored, its texel at a centre is then part of each of theirs.
    pub(crate) fn textures_read_by_all(&self, others: &[MaterialSource]) -> Vec<bool> {
        let read_by =
            |t: &Texture, other: &MaterialSource| other.textures().any(|o| Arc::ptr_eq(t, o));
        (self.textures())
            .map(|t| !others.is_empty() && others.iter().all(|other| read_by(t, other)))
            .collect()
    }

    /// What the evaluator cannot show of this material, each with the reason: extensions it
    /// does not model and texture slots whose image it cannot read. A comparison involving
    /// such a material is reported as not evaluated, never as the same.
    pub(crate) fn unmodelled(&self) -> &[String] {
        match self {
            MaterialSource::Gltf2(prepared) => &prepared.unmodelled,
            MaterialSource::Legacy { unread, .. } => unread,
        }
    }

    /// The name of the reading this material is evaluated under, when there is a choice.
    pub(crate) fn reading_name(&self) -> Option<&'static str> {
        match self {
            MaterialSource::Legacy { pbr, reading, .. }
                if pbr.model == Model::SpecularGlossiness =>
            {
                Some(reading.name())
            }
            _ => None,
        }
    }

    /// The BRDF inputs at texture coordinates `uvs` (one pair per TEXCOORD set). Inlined
    /// into the comparison's texel loop, which is compiled for the CPU's vector width.
    #[inline(always)]
    pub(crate) fn inputs_at(&self, uvs: &[[f64; 2]]) -> Inputs {
        self.inputs_with(uvs, |read: Read<'_>| read.sampled())
    }

    /// Its BRDF inputs at `uvs`, each texture read given by `read`: a material makes the
    /// same reads in the same order at every point. [`MaterialSource::inputs_at`] samples
    /// them; a caller that knows them already (a texel corner's, from the centres around
    /// it: see [`corner_of`]) hands them over.
    #[inline(always)]
    pub(crate) fn inputs_with(&self, uvs: &[[f64; 2]], read: impl Reader) -> Inputs {
        match self {
            MaterialSource::Gltf2(prepared) => prepared.inputs_with(&mut Reads { uvs, read }),
            MaterialSource::Legacy {
                pbr,
                colour,
                data,
                samplers: [colour_sampler, data_sampler],
                reading,
                ..
            } => {
                let colour = colour.as_deref().map(|t| (t, *colour_sampler));
                let data = data.as_deref().map(|t| (t, *data_sampler));
                legacy_inputs(pbr, colour, data, uvs[0], *reading, read)
            }
        }
    }
}

/// A document's textures as its materials bind them, each by texture index: the decoded
/// image, the sampler it is read through (default when missing), why it has no image, and
/// the first texture alike (the same image and sampler; empty: each its own).
#[derive(Default)]
pub(crate) struct TextureSet<'t> {
    pub images: &'t [Option<Texture>],
    pub samplers: &'t [Sampler],
    pub unreadable: &'t [Option<String>],
    pub first_alike: &'t [usize],
}

/// The objects of a 2.0 material the evaluator reads: the material, its
/// pbrMetallicRoughness and each extension's block it models (`None` where absent).
#[derive(Clone, Copy)]
struct Blocks<'t> {
    material: Node<'t>,
    pbr: Option<Node<'t>>,
    specular: Option<Node<'t>>,
    sheen: Option<Node<'t>>,
    anisotropy: Option<Node<'t>>,
    clearcoat: Option<Node<'t>>,
    transmission: Option<Node<'t>>,
    volume: Option<Node<'t>>,
    diffuse_transmission: Option<Node<'t>>,
    iridescence: Option<Node<'t>>,
    spec_gloss: Option<Node<'t>>,
}

impl<'t> Blocks<'t> {
    fn of(material: Node<'t>) -> Self {
        let extension = |name: &str| Blocks::extension_of(material, name);
        Blocks {
            material,
            pbr: material.get("pbrMetallicRoughness"),
            specular: extension("KHR_materials_specular"),
            sheen: extension("KHR_materials_sheen"),
            anisotropy: extension("KHR_materials_anisotropy"),
            clearcoat: extension("KHR_materials_clearcoat"),
            transmission: extension("KHR_materials_transmission"),
            volume: extension("KHR_materials_volume"),
            diffuse_transmission: extension("KHR_materials_diffuse_transmission"),
            iridescence: extension("KHR_materials_iridescence"),
            spec_gloss: extension("KHR_materials_pbrSpecularGlossiness"),
        }
    }

    fn extension(self, name: &str) -> Option<Node<'t>> {
        Blocks::extension_of(self.material, name)
    }

    fn extension_of(material: Node<'t>, name: &str) -> Option<Node<'t>> {
        material.get("extensions").and_then(|e| e.get(name))
    }

    /// The inputs its factors give, before any texture is read.
    fn factors(self) -> Inputs {
        let strength = number(
            self.extension("KHR_materials_emissive_strength"),
            "emissiveStrength",
            1.0,
        );
        Inputs {
            base_color: colour3(member(self.pbr, "baseColorFactor"), [1.0; 3]),
            metallic: number(self.pbr, "metallicFactor", 1.0),
            roughness: number(self.pbr, "roughnessFactor", 1.0),
            ior: number(self.extension("KHR_materials_ior"), "ior", 1.5),
            specular: number(self.specular, "specularFactor", 1.0),
            specular_color: colour3(member(self.specular, "specularColorFactor"), [1.0; 3]),
            sheen_color: colour3(member(self.sheen, "sheenColorFactor"), [0.0; 3]),
            sheen_roughness: number(self.sheen, "sheenRoughnessFactor", 0.0),
            anisotropy_strength: number(self.anisotropy, "anisotropyStrength", 0.0),
            anisotropy_angle: number(self.anisotropy, "anisotropyRotation", 0.0),
            unlit: self.extension("KHR_materials_unlit").is_some(),
            emission: colour3(self.material.get("emissiveFactor"), [0.0; 3]).map(|e| e * strength),
            clearcoat: number(self.clearcoat, "clearcoatFactor", 0.0),
            clearcoat_roughness: number(self.clearcoat, "clearcoatRoughnessFactor", 0.0),
            transmission: number(self.transmission, "transmissionFactor", 0.0),
            diffuse_transmission: number(
                self.diffuse_transmission,
                "diffuseTransmissionFactor",
                0.0,
            ),
            diffuse_transmission_color: colour3(
                member(self.diffuse_transmission, "diffuseTransmissionColorFactor"),
                [1.0; 3],
            ),
            iridescence: number(self.iridescence, "iridescenceFactor", 0.0),
            iridescence_film: Film {
                ior: number(self.iridescence, "iridescenceIor", 1.3),
                thickness: number(self.iridescence, "iridescenceThicknessMaximum", 400.0),
            },
            ..Inputs::default()
        }
    }

    /// Its alpha factor (the spec-gloss diffuse's where it has one) and its alpha mode.
    fn coverage(self) -> (f64, AlphaMode) {
        let alpha_of = |colour: Option<Node>| {
            (colour.and_then(|c| c.get(3)).and_then(Node::as_f64)).unwrap_or(1.0)
        };
        let alpha = match self.spec_gloss {
            Some(sg) => alpha_of(sg.get("diffuseFactor")),
            None => alpha_of(member(self.pbr, "baseColorFactor")),
        };
        let material = self.material;
        let mode = match material.get("alphaMode").and_then(Node::as_str) {
            Some("MASK") => AlphaMode::Mask(number(Some(material), "alphaCutoff", 0.5)),
            Some("BLEND") => AlphaMode::Blend,
            _ => AlphaMode::Opaque,
        };
        (alpha, mode)
    }
}

fn prepare(material: Node, textures: &TextureSet) -> Prepared {
    let mut unmodelled = Vec::new();
    let mut bind = |info: Option<Node>, slot: &str| -> Option<Binding> {
        let info = info?;
        let index = (info.get("index").and_then(Node::as_u64)).map(|i| i as usize);
        let texture = index.and_then(|i| textures.images.get(i)?.clone());
        let sampler = (index.and_then(|i| textures.samplers.get(i)).copied()).unwrap_or_default();
        if texture.is_none() {
            let why = (index.and_then(|i| textures.unreadable.get(i)?.as_deref()))
                .unwrap_or("its texture has no image the evaluator reads");
            unmodelled.push(format!("{slot} ({why})"));
        }
        Some(Binding {
            texture: texture?,
            sampler,
            texcoord: effective_texcoord(info),
            transform: uv_transform(info),
        })
    };
    let blocks = Blocks::of(material);
    let Blocks {
        pbr,
        specular,
        sheen,
        anisotropy,
        clearcoat,
        transmission,
        volume,
        diffuse_transmission,
        iridescence,
        spec_gloss: sg,
        ..
    } = blocks;
    let in_pbr = |key: &str| member(pbr, key);
    let (alpha, alpha_mode) = blocks.coverage();
    let with_scale = |binding: Option<Binding>, info: Option<Node>, key: &str| {
        binding.map(|b| (b, number(info, key, 1.0)))
    };
    let normal_info = material.get("normalTexture");
    let occlusion_info = material.get("occlusionTexture");
    let coat_normal_info = member(clearcoat, "clearcoatNormalTexture");
    let spec_gloss = sg.map(|sg| SpecGloss {
        diffuse: colour3(sg.get("diffuseFactor"), [1.0; 3]),
        specular: colour3(sg.get("specularFactor"), [1.0; 3]),
        glossiness: number(Some(sg), "glossinessFactor", 1.0),
        diffuse_texture: bind(sg.get("diffuseTexture"), "diffuseTexture"),
        specular_glossiness_texture: bind(
            sg.get("specularGlossinessTexture"),
            "specularGlossinessTexture",
        ),
    });
    let normal = bind(normal_info, "normalTexture");
    let occlusion = bind(occlusion_info, "occlusionTexture");
    let coat_normal = bind(coat_normal_info, "clearcoatNormalTexture");
    let mut prepared = Prepared {
        factors: blocks.factors(),
        alpha,
        alpha_mode,
        spec_gloss,
        base_colour: bind(in_pbr("baseColorTexture"), "baseColorTexture"),
        metallic_roughness: bind(
            in_pbr("metallicRoughnessTexture"),
            "metallicRoughnessTexture",
        ),
        specular: bind(member(specular, "specularTexture"), "specularTexture"),
        specular_colour: bind(
            member(specular, "specularColorTexture"),
            "specularColorTexture",
        ),
        sheen_colour: bind(member(sheen, "sheenColorTexture"), "sheenColorTexture"),
        sheen_roughness: bind(
            member(sheen, "sheenRoughnessTexture"),
            "sheenRoughnessTexture",
        ),
        anisotropy: bind(member(anisotropy, "anisotropyTexture"), "anisotropyTexture"),
        emissive: bind(material.get("emissiveTexture"), "emissiveTexture"),
        occlusion: with_scale(occlusion, occlusion_info, "strength"),
        normal: with_scale(normal, normal_info, "scale"),
        clearcoat: bind(member(clearcoat, "clearcoatTexture"), "clearcoatTexture"),
        clearcoat_roughness: bind(
            member(clearcoat, "clearcoatRoughnessTexture"),
            "clearcoatRoughnessTexture",
        ),
        clearcoat_normal: with_scale(coat_normal, coat_normal_info, "scale"),
        transmission: bind(
            member(transmission, "transmissionTexture"),
            "transmissionTexture",
        ),
        diffuse_transmission: bind(
            member(diffuse_transmission, "diffuseTransmissionTexture"),
            "diffuseTransmissionTexture",
        ),
        diffuse_transmission_colour: bind(
            member(diffuse_transmission, "diffuseTransmissionColorTexture"),
            "diffuseTransmissionColorTexture",
        ),
        volume: Volume {
            thickness: number(volume, "thicknessFactor", 0.0),
            texture: bind(member(volume, "thicknessTexture"), "thicknessTexture"),
            attenuation_colour: colour3(member(volume, "attenuationColor"), [1.0; 3]),
            attenuation_distance: number(volume, "attenuationDistance", f64::INFINITY),
        },
        iridescence: bind(
            member(iridescence, "iridescenceTexture"),
            "iridescenceTexture",
        ),
        film_thickness: (
            [
                number(iridescence, "iridescenceThicknessMinimum", 100.0),
                number(iridescence, "iridescenceThicknessMaximum", 400.0),
            ],
            bind(
                member(iridescence, "iridescenceThicknessTexture"),
                "iridescenceThicknessTexture",
            ),
        ),
        has_sheen: sheen.is_some(),
        double_sided: Some(material.get("doubleSided").and_then(Node::as_bool) == Some(true)),
        lighting_unread: false,
        unmodelled,
        fingerprint: String::new(),
        textures: Vec::new(),
    };
    prepared.unmodelled.extend(unmodelled_extensions(material));
    let bound: Vec<_> = prepared
        .bindings()
        .map(|b| (Arc::as_ptr(&b.texture), b.sampler))
        .collect();
    prepared.fingerprint = format!("{}|{bound:?}", shading_text(material, textures.first_alike));
    prepared.textures = prepared.bindings().map(|b| b.texture.clone()).collect();
    prepared
}

/// The material's extensions the evaluator does not draw, each with what it would change.
/// An extension whose factors leave it switched off changes nothing and is not listed.
fn unmodelled_extensions(material: Node) -> Vec<String> {
    let Some(extensions) = material.get("extensions").and_then(Node::as_object) else {
        return Vec::new();
    };
    let factor = |name: &str, key: &str| number(extensions.get(name), key, 0.0);
    let mut list = Vec::new();
    for name in extensions.keys() {
        match name {
            known if MODELLED_EXTENSIONS.contains(&known) => {}
            "KHR_materials_dispersion" if factor(name, "dispersion") == 0.0 => {}
            "KHR_materials_dispersion" => list.push(format!(
                "{name} (its colour fringes show only against a structured background; the figure's backgrounds are uniform)"
            )),
            other => list.push(format!("{other} (an extension the evaluator does not know)")),
        }
    }
    list
}

/// A material's JSON without the members that do not change how it shades (`name`,
/// `extras`), each textureInfo's `index` read as the first texture alike (`first_alike`, by
/// texture index; empty: as written): equal for two materials that evaluate the same way
/// with the same textures.
pub(crate) fn shading_text(material: Node, first_alike: &[usize]) -> String {
    let Some(members) = material.as_object() else {
        return material.to_string();
    };
    let mut text = String::from("{");
    for (key, member) in members.iter() {
        if !matches!(key, "name" | "extras") {
            write_member(key, member, first_alike, &mut text);
        }
    }
    text + "}"
}

/// `value` as JSON text, with every textureInfo (a member named `…Texture` holding an
/// `index`) pointing at the first texture alike.
fn write_reindexed(value: Node, first_alike: &[usize], text: &mut String) {
    if let Some(members) = value.as_object() {
        text.push('{');
        for (key, member) in members.iter() {
            write_member(key, member, first_alike, text);
        }
        text.push('}');
    } else if let Some(elements) = value.as_array() {
        text.push('[');
        for element in elements.iter() {
            write_reindexed(element, first_alike, text);
            text.push(',');
        }
        text.push(']');
    } else {
        *text += &value.to_string();
    }
}

/// `"key":value,` (see [`write_reindexed`]).
fn write_member(key: &str, member: Node, first_alike: &[usize], text: &mut String) {
    *text += &serde_json::Value::from(key).to_string();
    text.push(':');
    let index = (member.get("index").and_then(Node::as_u64))
        .filter(|_| key.ends_with("Texture"))
        .and_then(|i| first_alike.get(usize::try_from(i).ok()?));
    match index {
        Some(&first) => write_with_index(member, first, text),
        None => write_reindexed(member, first_alike, text),
    }
    text.push(',');
}

/// A textureInfo as JSON text with its `index` replaced by `index`.
fn write_with_index(info: Node, index: usize, text: &mut String) {
    text.push('{');
    for (key, member) in info.as_object().into_iter().flat_map(|o| o.iter()) {
        *text += &serde_json::Value::from(key).to_string();
        text.push(':');
        match key {
            "index" => *text += &index.to_string(),
            _ => *text += &member.to_string(),
        }
        text.push(',');
    }
    text.push('}');
}

#[inline(always)]
fn times(a: V3, b: V3) -> V3 {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}

impl Prepared {
    /// Every texture binding of the material.
    fn bindings(&self) -> impl Iterator<Item = &Binding> {
        [
            &self.base_colour,
            &self.metallic_roughness,
            &self.specular,
            &self.specular_colour,
            &self.sheen_colour,
            &self.sheen_roughness,
            &self.anisotropy,
            &self.emissive,
            &self.clearcoat,
            &self.clearcoat_roughness,
            &self.transmission,
            &self.diffuse_transmission,
            &self.diffuse_transmission_colour,
            &self.volume.texture,
            &self.iridescence,
            &self.film_thickness.1,
        ]
        .into_iter()
        .chain(
            (self.spec_gloss.iter())
                .flat_map(|s| [&s.diffuse_texture, &s.specular_glossiness_texture]),
        )
        .flatten()
        .chain(
            [&self.occlusion, &self.normal, &self.clearcoat_normal]
                .into_iter()
                .flatten()
                .map(|(binding, _)| binding),
        )
    }

    /// Its inputs, each texture read through `reads` (the same reads in the same order at
    /// every point).
    #[inline(always)]
    fn inputs_with(&self, reads: &mut Reads<impl Reader>) -> Inputs {
        let mut alpha = self.alpha;
        let mut m = if let Some(sg) = &self.spec_gloss {
            let mut diffuse = sg.diffuse;
            if let Some(t) = reads.colour(&sg.diffuse_texture) {
                diffuse = times(diffuse, rgb(t));
                alpha *= t[3];
            }
            let (mut specular, mut glossiness) = (sg.specular, sg.glossiness);
            if let Some(t) = reads.colour(&sg.specular_glossiness_texture) {
                specular = times(specular, rgb(t));
                glossiness *= t[3];
            }
            let reading = SpecGlossReading::ArchivedExtension;
            Inputs {
                emission: self.factors.emission,
                ..Inputs::specular_glossiness(diffuse, specular, glossiness, reading)
            }
        } else {
            self.metal_rough_with(reads, &mut alpha)
        };
        m.coverage = self.alpha_mode.coverage(alpha);
        if let Some(t) = reads.colour(&self.emissive) {
            m.emission = times(m.emission, rgb(t));
        }
        if let Some((binding, strength)) = &self.occlusion {
            m.occlusion = 1.0 + strength * (reads.data_of(binding)[0] - 1.0);
        }
        if let Some((binding, scale)) = &self.normal {
            m.normal = tangent_normal(reads.data_of(binding), *scale);
        }
        m
    }

    /// The metal-roughness inputs and its layers, each texture read through `reads`;
    /// `alpha` is multiplied by the base colour texture's.
    #[inline(always)]
    fn metal_rough_with(&self, reads: &mut Reads<impl Reader>, alpha: &mut f64) -> Inputs {
        let mut m = self.factors.clone();
        if let Some(t) = reads.colour(&self.base_colour) {
            m.base_color = times(m.base_color, rgb(t));
            *alpha *= t[3];
        }
        if let Some(t) = reads.data(&self.metallic_roughness) {
            m.roughness *= t[1];
            m.metallic *= t[2];
        }
        if let Some(t) = reads.data(&self.specular) {
            m.specular *= t[3];
        }
        if let Some(t) = reads.colour(&self.specular_colour) {
            m.specular_color = times(m.specular_color, rgb(t));
        }
        if let Some(t) = reads.colour(&self.sheen_colour) {
            m.sheen_color = times(m.sheen_color, rgb(t));
        }
        if let Some(t) = reads.data(&self.sheen_roughness) {
            m.sheen_roughness *= t[3];
        }
        if let Some(t) = reads.data(&self.anisotropy) {
            let (x, y) = (2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0);
            m.anisotropy_angle += y.atan2(x);
            m.anisotropy_strength *= t[2];
        }
        if let Some(t) = reads.data(&self.clearcoat) {
            m.clearcoat *= t[0];
        }
        if let Some(t) = reads.data(&self.clearcoat_roughness) {
            m.clearcoat_roughness *= t[1];
        }
        if let Some((binding, scale)) = &self.clearcoat_normal {
            m.clearcoat_normal = tangent_normal(reads.data_of(binding), *scale);
        }
        if let Some(t) = reads.data(&self.transmission) {
            m.transmission *= t[0];
        }
        if let Some(t) = reads.data(&self.diffuse_transmission) {
            m.diffuse_transmission *= t[3];
        }
        if let Some(t) = reads.colour(&self.diffuse_transmission_colour) {
            m.diffuse_transmission_color = times(m.diffuse_transmission_color, rgb(t));
        }
        if let Some(t) = reads.data(&self.iridescence) {
            m.iridescence *= t[0];
        }
        if let Some(t) = reads.data(&self.film_thickness.1) {
            // "thickness = mix(iridescenceThicknessMinimum, iridescenceThicknessMaximum,
            // iridescenceThicknessTexture.g)"; without the texture, the maximum.
            let [least, most] = self.film_thickness.0;
            m.iridescence_film.thickness = least + (most - least) * t[1];
        }
        let thickness =
            self.volume.thickness * reads.data(&self.volume.texture).map_or(1.0, |t| t[1]);
        m.volume_transmittance = self.volume.transmittance(thickness);
        m
    }
}

/// A normal texel as a unit normal in the tangent frame: "scaledNormal = normalize((<sampled
/// normal texture value> * 2.0 - 1.0) * vec3(<normal scale>, <normal scale>, 1.0))".
#[inline(always)]
fn tangent_normal(t: [f64; 4], scale: f64) -> V3 {
    let n = [
        (2.0 * t[0] - 1.0) * scale,
        (2.0 * t[1] - 1.0) * scale,
        2.0 * t[2] - 1.0,
    ];
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if length > 0.0 && n[2] > 0.0 {
        n.map(|c| c / length)
    } else {
        // A normal at or below the surface's own plane has no shading frame a viewer would
        // agree on: the geometric normal is kept.
        [0.0, 0.0, 1.0]
    }
}

/// The 1.0 drafts' own model: metal-rough with metallic in R and roughness in G of the data
/// texture; spec-gloss with sRGB diffuse and specular, glossiness in A (2017 draft), under
/// `reading`.
#[inline(always)]
fn legacy_inputs(
    pbr: &LegacyPbr,
    colour: Option<(&TextureImage, Sampler)>,
    data: Option<(&TextureImage, Sampler)>,
    uv: [f64; 2],
    reading: SpecGlossReading,
    mut read: impl Reader,
) -> Inputs {
    let mut read = |(texture, sampler), srgb| {
        read(Read {
            texture,
            at: uv,
            sampler,
            srgb,
        })
    };
    let colour_texel = colour.map(|texture| read(texture, true));
    let mut rgb = [pbr.colour[0], pbr.colour[1], pbr.colour[2]];
    // The drafts blend by the colour's alpha (the upgrade writes BLEND where it is below 1).
    let mut alpha = pbr.colour[3];
    if let Some(t) = colour_texel {
        rgb = times(rgb, self::rgb(t));
        alpha *= t[3];
    }
    let inputs = match pbr.model {
        Model::MetalRoughness => {
            let (mut metallic, mut roughness) = (pbr.metallic, pbr.roughness);
            if let Some(t) = data.map(|texture| read(texture, false)) {
                metallic *= t[0];
                roughness *= t[1];
            }
            Inputs {
                base_color: rgb,
                metallic,
                roughness,
                ..Inputs::default()
            }
        }
        Model::SpecularGlossiness => {
            let (mut specular, mut gloss) = (pbr.specular, pbr.glossiness);
            if let Some(t) = data.map(|texture| read(texture, true)) {
                specular = times(specular, self::rgb(t));
                gloss *= t[3];
            }
            Inputs::specular_glossiness(rgb, specular, gloss, reading)
        }
    };
    Inputs {
        coverage: alpha.clamp(0.0, 1.0),
        ..inputs
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shading_key_reads_every_texture_info_as_its_first_alike_and_ignores_names() {
        use crate::document::Tree;
        use serde_json::json;
        let key =
            |material: serde_json::Value| shading_text(Tree::of(&material).root(), &[0, 0, 2]);
        let coat = |index: u64, name: &str| {
            json!({"name": name, "extras": {"by": name},
                   "normalTexture": {"index": index, "scale": 0.5},
                   "extensions": {"KHR_materials_clearcoat": {
                       "clearcoatFactor": 1.0, "clearcoatTexture": {"index": index}}}})
        };
        // Textures 0 and 1 are alike (one image, one sampler); 2 is another.
        assert_eq!(key(coat(0, "a")), key(coat(1, "b")));
        assert_ne!(key(coat(0, "a")), key(coat(2, "a")));
        let mut brighter = coat(0, "a");
        brighter["extensions"]["KHR_materials_clearcoat"]["clearcoatFactor"] = json!(0.5);
        assert_ne!(key(coat(0, "a")), key(brighter));
        // An `index` outside a `…Texture` member is a value like any other.
        let indexed = |index: u64| key(json!({"extras": {}, "other": {"index": index}}));
        assert_ne!(indexed(0), indexed(1));
    }

    /// A lit 1.0 material's stand-in emits its emission and reflects nothing: over black it
    /// shows its emission exactly, in every direction, whatever it is lit by; blended with
    /// ONE, ONE_MINUS_SRC_ALPHA the emission is added whole, straight it is weighed by alpha.
    #[test]
    fn a_lit_1_0_material_is_seen_by_its_emission_and_coverage_alone() {
        use crate::shade::appearance::seen;
        use crate::shade::brdf::{Geometry, SheenVisibility};
        use crate::shade::material::Shader;
        use crate::shade::sheen_table::SheenTable;
        let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
        let lit = |blend| {
            MaterialSource::lit_legacy(LitLegacy {
                emission: [0.3, 0.2, 0.1],
                emission_texture: None,
                alpha: 0.25,
                alpha_texture: None,
                blend,
                double_sided: None,
            })
        };
        let direction = |theta: f64| [theta.sin(), 0.0, theta.cos()];
        for (blend, weight, coverage) in [
            (None, 1.0, 1.0),
            (Some(Blend::Premultiplied), 1.0, 0.25),
            (Some(Blend::Straight), 0.25, 0.25),
        ] {
            let m = lit(blend);
            assert!(m.lighting_unread() && m.unmodelled() == [LIGHTING_UNREAD]);
            let inputs = m.inputs_at(&[[0.3, 0.7]]);
            for (view, light) in [(0.0, 0.0), (0.4, -0.9), (1.2, 0.3), (1.5, 1.5)] {
                let g = Geometry::new(direction(view), direction(light));
                let s = seen(&shader, &inputs, &g);
                for c in 0..3 {
                    let emitted = [0.3, 0.2, 0.1][c] * weight;
                    assert!(
                        (s.own[c] - emitted).abs() < 1e-12,
                        "{blend:?} {view} {light}: {:?}",
                        s.own
                    );
                    assert!((s.through[c] - (1.0 - coverage)).abs() < 1e-12);
                }
            }
        }
    }

    /// The decode budget admits what real textures decode to (Khronos's ABeautifulGame: PNGs
    /// decoding to 22 times their bytes) and refuses what only a made-up image does (a
    /// header announcing 1 GiB in half a megabyte), from the headers alone.
    #[test]
    fn the_decode_budget_admits_real_compression_and_refuses_a_bomb() {
        // A PNG's signature, an RGBA IHDR of `side`², an empty IDAT, then `bytes` of filler.
        let png = |side: u32, bytes: usize| {
            let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
            png.extend(13u32.to_be_bytes());
            png.extend(b"IHDR");
            png.extend(side.to_be_bytes());
            png.extend(side.to_be_bytes());
            png.extend([8, 6, 0, 0, 0, 0, 0, 0, 0]);
            png.extend([0, 0, 0, 0]);
            png.extend(b"IDAT");
            png.resize(bytes, 0);
            png
        };
        // 24 textures of 2048² RGBA (16 MiB each decoded) in 750 KiB each: 384 MiB of 18 MiB.
        let real: Vec<Vec<u8>> = (0..24).map(|_| png(2048, 750 << 10)).collect();
        let real: Vec<Option<&[u8]>> = real.iter().map(|b| Some(&b[..])).collect();
        assert_eq!(within_budget(&real, AS_STORED), Ok(()));
        let bomb = png(16384, 512 << 10);
        let refused = within_budget(&[Some(&bomb[..])], AS_STORED).unwrap_err();
        assert!(refused.contains("image 0 (16384×16384)"), "{refused}");
        // However large the files, the set stops at the ceiling: nine 8192² RGBA images of
        // 9 MiB each (2.25 GiB decoded, within 32 times their bytes) pass 2 GiB at the ninth.
        let large = png(8192, 9 << 20);
        let refused = within_budget(&[Some(&large[..]); 9], AS_STORED).unwrap_err();
        assert!(refused.starts_with("image 8 (8192×8192)"), "{refused}");
        assert!(refused.contains("past 2048 MiB"), "{refused}");
    }

    /// The decode budget counts a KTX2 as what it is transcoded to (8-bit RGBA), not as the
    /// RGB its descriptor declares.
    #[test]
    fn a_ktx2_is_budgeted_as_the_rgba_it_decodes_to() {
        let rgb = include_bytes!("../../../fixtures/ktx2/base-uastc.ktx2");
        assert_eq!(decoded_size(rgb, 1024), 64 * 64 * 4);
        let texture = decode(rgb).unwrap();
        assert_eq!(
            (texture.width(), texture.height(), texture.channels),
            (64, 64, 4)
        );
    }

    /// `image` encoded as a PNG.
    fn png_of(image: image::DynamicImage) -> Vec<u8> {
        let mut bytes = Vec::new();
        let mut cursor = std::io::Cursor::new(&mut bytes);
        image
            .write_to(&mut cursor, image::ImageFormat::Png)
            .unwrap();
        bytes
    }

    /// Box `(bx, by)` of `k` texels a side, averaged from the full decode, rounded.
    fn box_average(full: &TextureImage, k: usize, bx: usize, by: usize) -> Vec<u64> {
        let (w, h, n) = (full.width as usize, full.height as usize, full.channels);
        let xs = bx * k..w.min((bx + 1) * k);
        let ys = by * k..h.min((by + 1) * k);
        let count = (xs.len() * ys.len()) as u64;
        (0..n)
            .map(|c| {
                let sum: u64 = (ys.clone())
                    .flat_map(|y| xs.clone().map(move |x| (y * w + x) * n + c))
                    .map(|at| match &full.texels {
                        Texels::Unorm8(raw) => u64::from(raw[at]),
                        Texels::Unorm16(raw) => u64::from(raw[at]),
                        Texels::Float(_) => unreachable!("PNGs here are 8 or 16 bits"),
                    })
                    .sum();
                (sum + count / 2) / count
            })
            .collect()
    }

    #[test]
    fn a_png_larger_than_wanted_is_averaged_in_boxes_as_the_full_decode_would_be() {
        let rgb8 = image::RgbImage::from_fn(10, 7, |x, y| {
            image::Rgb([(x * 25) as u8, (y * 36) as u8, (x * y) as u8])
        });
        let la16 = image::ImageBuffer::<image::LumaA<u16>, _>::from_fn(10, 7, |x, y| {
            image::LumaA([(x * 6000 + y * 100) as u16, 65535 - (y * 9000) as u16])
        });
        for png in [png_of(rgb8.into()), png_of(la16.into())] {
            let full = decode(&png).unwrap();
            // 10 texels over 4: boxes of 3, the last column and row partial.
            let reduced = decode_png_reduced(&png, 4).unwrap().unwrap();
            assert_eq!(
                (reduced.width, reduced.height, reduced.channels),
                (4, 3, full.channels)
            );
            for (by, bx) in (0..3).flat_map(|by| (0..4).map(move |bx| (by, bx))) {
                let at = (by * 4 + bx) * full.channels;
                let got: Vec<u64> = match &reduced.texels {
                    Texels::Unorm8(raw) => raw[at..at + full.channels]
                        .iter()
                        .map(|&v| u64::from(v))
                        .collect(),
                    Texels::Unorm16(raw) => raw[at..at + full.channels]
                        .iter()
                        .map(|&v| u64::from(v))
                        .collect(),
                    Texels::Float(_) => unreachable!("stored as the file stores it"),
                };
                assert_eq!(got, box_average(&full, 3, bx, by), "box {bx},{by}");
            }
            assert!(
                decode_png_reduced(&png, 10).is_none(),
                "small enough: decoded whole"
            );
        }
        assert!(decode_png_reduced(b"not a png", 1).is_none());
    }

    #[test]
    fn an_image_still_held_is_shared_and_a_dropped_one_decoded_again() {
        let png = solid_png([12, 34, 56]);
        let first = decode_all(&[Some(Ok(&png[..]))])
            .unwrap()
            .remove(0)
            .unwrap();
        let again = decode_all(&[Some(Ok(&png[..]))])
            .unwrap()
            .remove(0)
            .unwrap();
        assert!(Arc::ptr_eq(&first, &again), "decoded once while held");
        let other = decode_all(&[Some(Ok(&solid_png([12, 34, 57])[..]))]).unwrap();
        assert!(
            !Arc::ptr_eq(&first, other[0].as_ref().unwrap()),
            "other bytes"
        );
        let weak = Arc::downgrade(&first);
        drop((first, again));
        assert!(weak.upgrade().is_none(), "the cache holds no texture alive");
        let fresh = decode_all(&[Some(Ok(&png[..]))])
            .unwrap()
            .remove(0)
            .unwrap();
        assert_eq!(bilinear(&fresh, [0.5, 0.5])[0], 12.0 / 255.0);
    }

    #[test]
    fn every_stored_layout_reads_as_the_rgba_the_image_crate_widens_it_to() {
        use image::{DynamicImage, ImageBuffer};
        let levels8 = |n: usize| (0..2 * n).map(|i| (37 * i + 11) as u8).collect::<Vec<_>>();
        let levels16 = |n: usize| {
            (0..2 * n)
                .map(|i| (9973 * i + 11) as u16)
                .collect::<Vec<_>>()
        };
        let images = [
            DynamicImage::ImageLuma8(ImageBuffer::from_raw(2, 1, levels8(1)).unwrap()),
            DynamicImage::ImageLumaA8(ImageBuffer::from_raw(2, 1, levels8(2)).unwrap()),
            DynamicImage::ImageRgb8(ImageBuffer::from_raw(2, 1, levels8(3)).unwrap()),
            DynamicImage::ImageRgba8(ImageBuffer::from_raw(2, 1, levels8(4)).unwrap()),
            DynamicImage::ImageLuma16(ImageBuffer::from_raw(2, 1, levels16(1)).unwrap()),
            DynamicImage::ImageLumaA16(ImageBuffer::from_raw(2, 1, levels16(2)).unwrap()),
            DynamicImage::ImageRgb16(ImageBuffer::from_raw(2, 1, levels16(3)).unwrap()),
            DynamicImage::ImageRgba16(ImageBuffer::from_raw(2, 1, levels16(4)).unwrap()),
        ];
        for image in images {
            let mut png = Vec::new();
            (image.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)).unwrap();
            let decoded = decode(&png).unwrap();
            let widened = image.to_rgba32f();
            for x in 0..2 {
                let expected = widened.get_pixel(x, 0).0.map(f64::from);
                let read = decoded.decoded::<false>(i64::from(x), 0);
                assert!(
                    (0..4).all(|c| (read[c] - expected[c]).abs() < 1e-7),
                    "{:?} texel {x}: {read:?} against {expected:?}",
                    image.color()
                );
            }
        }
    }

    /// A texel corner's reads made from the four centres around it are, bit for bit, what
    /// sampling the corner gives: colour and data reads, of 8-bit, 16-bit and float texels.
    #[test]
    fn a_corner_made_from_its_four_centres_is_the_corner_sampled() {
        let mut random = crate::test_random::Sequence::new(52);
        let n = 8u32;
        let mut texels = |count: usize| (0..count).map(|_| random.unit()).collect::<Vec<f32>>();
        let stored = [
            (
                4,
                Texels::Unorm8(texels(4 * 64).iter().map(|&v| (v * 255.0) as u8).collect()),
            ),
            (
                3,
                Texels::Unorm16(
                    texels(3 * 64)
                        .iter()
                        .map(|&v| (v * 65535.0) as u16)
                        .collect(),
                ),
            ),
            (4, Texels::Float(texels(4 * 64))),
        ];
        for (channels, texels) in stored {
            let texture = TextureImage {
                width: n,
                height: n,
                channels,
                texels,
            };
            for srgb in [false, true] {
                let read = |x: u32, y: u32, offset: f64| {
                    let at = [(f64::from(x) + offset) / 8.0, (f64::from(y) + offset) / 8.0];
                    let read = Read {
                        texture: &texture,
                        at,
                        sampler: Sampler::default(),
                        srgb,
                    };
                    read.sampled()
                };
                for (x, y) in (1..n).flat_map(|x| (1..n).map(move |y| (x, y))) {
                    let four = [(x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y)];
                    let centres = four.map(|(x, y)| read(x, y, 0.5));
                    let made = corner_of(centres.each_ref());
                    let sampled = read(x, y, 0.0);
                    assert_eq!(
                        made.map(f64::to_bits),
                        sampled.map(f64::to_bits),
                        "{x}, {y}"
                    );
                }
            }
        }
    }
}
