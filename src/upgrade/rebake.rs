//! Texture rebaking for material conversion: new PNG images computed texel by texel from
//! the 1.0 textures. Original images are never modified or reused for a changed meaning.

use crate::document::image_decode;
use crate::document::image_header::{self, Channels};
use crate::gltf::color::{linear_to_srgb, linear_to_srgb8};
use crate::shade::sample::{self, Sampler, TextureImage, Wrap};
use crate::upgrade::fit::{self, Factors, TexelFits, TexelValue};
use hashbrown::hash_map::{Entry, HashMap};
use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{DynamicImage, ExtendedColorType, ImageEncoder, Rgba32FImage};
use std::io::Cursor;

pub(super) fn decode(bytes: &[u8]) -> Result<DynamicImage, String> {
    image_decode::decode(bytes).map_err(|e| e.to_string())
}

/// Encodes linear-or-stored values (0..1) as an 8-bit RGB(A) PNG, or 16-bit when `wide`.
fn encode(image: &Rgba32FImage, alpha: bool, wide: bool) -> Vec<u8> {
    let (width, height) = image.dimensions();
    let channels = if alpha { 4 } else { 3 };
    let quantise = |v: f32, max: f64| level(f64::from(v), max) as u16;
    let values = image.as_raw().chunks_exact(4).flat_map(|p| &p[..channels]);
    let samples = width as usize * height as usize * channels;
    let (bytes, color) = if wide {
        let mut bytes = Vec::with_capacity(samples * 2);
        for &v in values {
            bytes.extend_from_slice(&quantise(v, 65535.0).to_ne_bytes());
        }
        let color = if alpha {
            ExtendedColorType::Rgba16
        } else {
            ExtendedColorType::Rgb16
        };
        (bytes, color)
    } else {
        let mut bytes = Vec::with_capacity(samples);
        for &v in values {
            bytes.push(quantise(v, 255.0) as u8);
        }
        let color = if alpha {
            ExtendedColorType::Rgba8
        } else {
            ExtendedColorType::Rgb8
        };
        (bytes, color)
    };
    let mut png = Vec::new();
    let encoder = PngEncoder::new_with_quality(
        Cursor::new(&mut png),
        CompressionType::Fast,
        FilterType::Adaptive,
    );
    encoder
        .write_image(&bytes, width, height, color)
        .map(|()| png)
        .unwrap_or_default()
}

/// The level of `max` a value 0..1 is stored as: the image crate's float → integer rule,
/// clamp, scale, round (half away from zero, which for these non-negative values is + ½ and
/// truncation, in f64 so that no value just below a half rounds up; `f32::round` is a library
/// call per sample).
fn level(value: f64, max: f64) -> f64 {
    // Non-negative: truncation is the floor, and NaN (clamped to itself) becomes 0, as the
    // image crate stores it.
    ((value.clamp(0.0, 1.0) * max + 0.5) as u32).into()
}

/// Each texel of the image in `bytes` (values 0..1 as stored) mapped by `f`, computed on
/// every core, and whether the image has more than 8 bits per sample.
fn mapped(
    bytes: &[u8],
    f: impl Fn([f64; 4]) -> [f32; 4] + Sync,
) -> Result<(Rgba32FImage, bool), String> {
    let source = sample::decode(bytes)?;
    let (width, height) = (source.width(), source.height());
    // Sampled at its centre, a texel is read as it is.
    let texel = |x: u32, y: u32| f(sample::bilinear(&source, centre(x, y, width, height)));
    Ok((in_parallel_rows(width, height, texel), source.is_wide()))
}

/// 1.0 metal-rough texture (R metallic, G roughness) → 2.0 (G roughness, B metallic).
/// R is written as 1 (no occlusion) for engines that pack occlusion there.
pub(super) fn metal_rough_swizzle(bytes: &[u8]) -> Result<Vec<u8>, String> {
    let (out, wide) = mapped(bytes, |[r, g, _, _]| [1.0, g as f32, r as f32, 1.0])?;
    Ok(encode(&out, false, wide))
}

/// Spec-gloss glossiness (A × factor) → a metal-rough texture: G = 1 − glossiness, B = 0
/// (dielectric), R = 1; and the `roughnessFactor` it is read with. That factor is 1, or the
/// largest roughness when G scaled by it is stored more exactly: a smooth surface's
/// roughness 0.05 lies between two 8-bit levels, a step its specular peak shows, but is
/// exactly the largest level of its own scale. (With glossiness factor 1 the values are
/// 8-bit levels already, and stay unscaled.)
pub(super) fn gloss_to_roughness(
    bytes: &[u8],
    glossiness_factor: f64,
) -> Result<(Vec<u8>, f32), String> {
    let (mut out, wide) = mapped(bytes, |[_, _, _, a]| {
        [1.0, (1.0 - a * glossiness_factor) as f32, 0.0, 1.0]
    })?;
    let levels = if wide { 65535.0 } else { 255.0 };
    let roughness = || out.pixels().map(|p| f64::from(p[1]));
    // As written in the JSON (a float's shortest text), so the texels are divided by the
    // very factor a viewer multiplies them by.
    let largest = f64::from(roughness().fold(0.0, f64::max) as f32);
    let error = |scale: f64| {
        let stored = |r: f64| scale * level(r / scale, levels) / levels;
        roughness()
            .map(|r| (stored(r) - r).abs())
            .fold(0.0, f64::max)
    };
    let scale = if largest > 0.0 && error(largest) < error(1.0) {
        largest
    } else {
        1.0
    };
    if scale != 1.0 {
        out.pixels_mut()
            .for_each(|p| p[1] = (f64::from(p[1]) / scale) as f32);
    }
    Ok((encode(&out, false, wide), scale as f32))
}

/// Spec-gloss base colour, per texel, in linear space: diffuse · (1 − specular) per channel
/// (see `spec_gloss`), or with `fits` its per-texel fit where that is above the proof's
/// threshold; alpha from the diffuse. Either texture may be missing (its factor alone is
/// used). The output has the finest grid of the two (the larger width and the larger
/// height), and each input is sampled through its sampler (bilinearly, or its nearest texel
/// under NEAREST, wrapped as its wrap modes say, as the evaluator and viewers sample it) at
/// the output's texel centres: the rebake is then exact at every
/// output texel centre whatever the two resolutions, where sampling the smaller texture at
/// its nearest texel was not. The grid is held to [`rebake_grid`]. Returns the PNG, whether
/// it has an alpha channel, and the decision when the grid was held.
pub(super) fn spec_gloss_base_colour(
    diffuse: Option<&[u8]>,
    specular: Option<&[u8]>,
    samplers: [Sampler; 2],
    factors: &Factors,
    fits: Option<&mut TexelFits>,
) -> Result<(Vec<u8>, bool, Option<String>), String> {
    let diffuse_bytes = diffuse;
    let diffuse = diffuse_bytes.map(sample::decode).transpose()?;
    // The decode answers for 8-bit texels; wider ones are judged from the bytes (by their
    // 8-bit conversion, as before the decode was at hand).
    let translucent = |(bytes, texture): (&[u8], &sample::Texture)| {
        (texture.has_translucent_texels()).unwrap_or_else(|| has_translucent_texels(bytes))
    };
    let alpha =
        diffuse_bytes.zip(diffuse.as_ref()).is_some_and(translucent) || factors.diffuse[3] < 1.0;
    let specular = specular.map(sample::decode).transpose()?;
    let inputs: Vec<&TextureImage> = diffuse.iter().chain(&specular).map(|t| &**t).collect();
    let width = inputs
        .iter()
        .map(|t| t.width())
        .max()
        .ok_or("no texture to rebake")?;
    let height = inputs.iter().map(|t| t.height()).max().unwrap_or(1);
    let largest = (inputs.iter())
        .map(|t| u64::from(t.width()) * u64::from(t.height()))
        .max()
        .unwrap_or(1);
    let (width, height, held) = rebake_grid(width, height, largest);
    let wide = inputs.iter().any(|t| t.is_wide());
    let at_grid = |width, height| SpecGlossTexels {
        diffuse: diffuse.as_deref(),
        specular: specular.as_deref(),
        samplers,
        factors,
        width,
        height,
    };
    // A rebake fitted texel by texel (a reading without an exact form) keeps the inputs'
    // grid: its fit is made for each stored texel, not for what lies between them. One
    // with an exact form may refine its grid first; its texels' 8-bit levels are settled
    // only on the inputs' grid.
    // Read NEAREST, the rebake is shown texel by texel, never mixed between centres: its
    // inputs' grid is exact.
    let shown_nearest = at_grid(width, height).shown_through().nearest;
    let (source, finer) = match fits.as_ref().is_some_and(|f| f.keeps_grid()) || shown_nearest {
        true => (at_grid(width, height), None),
        false => finest_needed(at_grid(width, height), at_grid),
    };
    let fits = fits.filter(|_| finer.is_none());
    let (width, height) = (source.width, source.height);
    let held = held
        .into_iter()
        .chain(finer)
        .reduce(|a, b| format!("{a} {b}"));
    // With fits, the distinct texel values are listed first so that they are judged
    // together (in parallel); the image is then written from their verdicts.
    let fitted = fits.map(|fits| judged(&source, fits, if wide { 65535.0 } else { 255.0 }));
    let texel = |x: u32, y: u32| -> [f32; 4] {
        let at = y as usize * width as usize + x as usize;
        let fitted =
            (fitted.as_ref()).and_then(|(index, bases)| *bases.get(*index.get(at)? as usize)?);
        let (colour, alpha) = match fitted {
            Some(colour) => (colour, source.alpha(x, y)),
            None => {
                let (value, alpha) = source.at(x, y);
                (factors.base_colour(value.diffuse, value.specular), alpha)
            }
        };
        let channel = |c: usize| {
            if wide {
                linear_to_srgb(colour[c].clamp(0.0, 1.0)) as f32
            } else {
                // Exactly the 8-bit level the encoder would round the value to.
                f32::from(linear_to_srgb8(colour[c])) / 255.0
            }
        };
        [channel(0), channel(1), channel(2), alpha]
    };
    let out = in_parallel_rows(width, height, texel);
    Ok((encode(&out, alpha, wide), alpha, held))
}

/// The most texels a rebake's grid gets beyond its largest input's: 2048².
pub(super) const REBAKE_FLOOR: u64 = 1 << 22;

/// The largest ΔE2000 allowed between a rebake read between its texel centres and the
/// conversion of its inputs read there: half the proof's threshold, the rest of which is
/// left to 8-bit storage and the proof's other directions.
const BETWEEN_CENTRES: f64 = 0.5;

/// The grid the base colour is rebaked at: `start`'s, or a multiple of it where the product
/// diffuse · (1 − specular) is not linear enough between texel centres. A viewer mixes the
/// rebake's texels, not the conversions of mixed inputs, and where the inputs change sharply
/// the two differ at the texels' corners. The inputs' bilinear surfaces bend along the lines
/// through their texel centres: an odd multiple of the grid puts those lines on the rebake's
/// texel centres, where it is exact, and leaves a smooth product in between, whose error a
/// tripled grid divides by nine (an even multiple would put them on texel edges, where the
/// error only halves). Up to [`REBAKE_FLOOR`] texels. Returns the texels to rebake and the
/// decision when the grid was refined; what is still above [`BETWEEN_CENTRES`] there the
/// proof reports.
fn finest_needed<'t>(
    start: SpecGlossTexels<'t>,
    at_grid: impl Fn(u32, u32) -> SpecGlossTexels<'t>,
) -> (SpecGlossTexels<'t>, Option<String>) {
    let refinable =
        |t: &SpecGlossTexels| u64::from(t.width) * u64::from(t.height) * 9 <= REBAKE_FLOOR;
    // A grid that cannot be refined is kept whatever its error, which is then not measured:
    // the proof measures what the viewer sees.
    if !refinable(&start) {
        return (start, None);
    }
    let first = between_centres_error(&start);
    let (mut texels, mut error, mut scale) = (start, first, 1);
    while error > BETWEEN_CENTRES && refinable(&texels) {
        texels = at_grid(texels.width * 3, texels.height * 3);
        error = between_centres_error(&texels);
        scale *= 3;
    }
    let decision = (scale > 1).then(|| {
        format!(
            "the base colour is rebaked at {scale}× its inputs' grid ({}×{}): diffuse · (1 − specular) is not linear, and between the inputs' texel centres a rebake at their grid differed from the conversion of the interpolated inputs by ΔE2000 {first:.2} (at this grid {error:.2}).",
            texels.width, texels.height
        )
    });
    (texels, decision)
}

/// The largest ΔE2000, on the base colour as shown, between the mean of the converted
/// colours at the four texel centres around each texel corner (what a viewer's bilinear
/// filter gives there) and the conversion of the inputs read at that corner.
fn between_centres_error(texels: &SpecGlossTexels) -> f64 {
    use rayon::prelude::*;
    // Rows in bands, each converting its own centres (one row beyond it): no image-sized
    // buffer, whatever the grid.
    let band = 16;
    (0..texels.height.div_ceil(band))
        .into_par_iter()
        .map(|b| {
            let rows = b * band..((b + 1) * band).min(texels.height);
            corners_error(texels, rows)
        })
        .reduce(|| 0.0, f64::max)
}

/// A texel centre's value and its conversion.
struct Centre {
    value: TexelValue,
    base: [f64; 3],
}

/// [`between_centres_error`] at the corners below and right of the centres in `rows`.
fn corners_error(texels: &SpecGlossTexels, rows: std::ops::Range<u32>) -> f64 {
    use crate::shade::delta_e::{ciede2000, ciede2000_bound, lab_from_linear_srgb};
    use crate::shade::tone::displayed;
    let (width, height) = (texels.width, texels.height);
    let shown = |colour: [f64; 3]| lab_from_linear_srgb(displayed(colour));
    let base_at = |value: &TexelValue| texels.factors.base_colour(value.diffuse, value.specular);
    // Where the grid is every input's own, a corner lies midway between four stored texels
    // and each input reads there as their mean: the corner's value is the mean of the four
    // centres' values, with no texture read.
    let on_input_grid = texels
        .inputs()
        .all(|t| (t.width(), t.height()) == (width, height));
    let row = |y: u32| -> Vec<Centre> {
        (0..width)
            .map(|x| {
                let value = texels.at(x, y % height).0;
                let base = base_at(&value);
                Centre { value, base }
            })
            .collect()
    };
    // The texel beyond each centre is the one the rebake's sampler wraps to (itself at a
    // clamped edge, where nothing is mixed).
    let [wrap_s, wrap_t] = texels.shown_through().wrap;
    let beyond =
        |i: u32, size: u32, wrap: Wrap| wrap.texel(i64::from(i) + 1, i64::from(size)) as u32;
    let mut below = row(rows.start);
    let mut worst = 0f64;
    for y in rows {
        let above = std::mem::replace(&mut below, row(beyond(y, height, wrap_t)));
        for x in 0..width as usize {
            let next = beyond(x as u32, width, wrap_s) as usize;
            // On the inputs' grid a corner is a function of its four centres' values: one
            // whose four equal those of the corner before it (a flat run) has that corner's
            // ΔE, which was measured, and cannot raise the maximum.
            let same = |row: &[Centre]| {
                row[x - 1].value == row[x].value && row[x].value == row[next].value
            };
            if on_input_grid && x > 0 && same(&above) && same(&below) {
                continue;
            }
            let around = [&above[x], &above[next], &below[x], &below[next]];
            let mean = |f: fn(&Centre) -> [f64; 3]| -> [f64; 3] {
                std::array::from_fn(|c| around.iter().map(|a| f(a)[c]).sum::<f64>() / 4.0)
            };
            let mixed = mean(|a| a.base);
            let value = if on_input_grid {
                TexelValue {
                    diffuse: mean(|a| a.value.diffuse),
                    specular: mean(|a| a.value.specular),
                    glossiness: around.iter().map(|a| a.value.glossiness).sum::<f64>() / 4.0,
                }
            } else {
                let corner = [
                    (x + 1) as f64 / f64::from(width),
                    f64::from(y + 1) / f64::from(height),
                ];
                texels.value_at(corner)
            };
            let (mixed, exact) = (shown(mixed), shown(base_at(&value)));
            // Only a pair that could raise the maximum is measured in full.
            if ciede2000_bound(mixed, exact) > worst {
                worst = worst.max(ciede2000(mixed, exact));
            }
        }
    }
    worst
}

/// The grid of a rebake of textures whose finest dimensions are `width` × `height` and whose
/// largest holds `largest` texels: that grid, unless it holds more than the largest input or
/// [`REBAKE_FLOOR`], whichever is more; then the grid of that many texels with the same
/// aspect, and the decision saying so. Two textures of 16384×1 and 1×16384 hold 32768
/// texels between them; their finest grid would hold 2^28, every one interpolated.
pub(super) fn rebake_grid(width: u32, height: u32, largest: u64) -> (u32, u32, Option<String>) {
    let finest = u64::from(width) * u64::from(height);
    let most = largest.max(REBAKE_FLOOR);
    if finest <= most {
        return (width, height, None);
    }
    let scale = (most as f64 / finest as f64).sqrt();
    let held = |side: u32| ((f64::from(side) * scale).floor() as u32).clamp(1, side);
    let (w, h) = (held(width), held(height));
    let decision = format!(
        "the rebake's grid is {w}×{h}, not the {width}×{height} the textures' finest dimensions make: that grid would hold {finest} texels, more than the largest texture's {largest} (or {REBAKE_FLOOR}), each interpolated, not stored."
    );
    (w, h, Some(decision))
}

/// The texture coordinates of the centre of texel (x, y) in a `width` × `height` grid.
fn centre(x: u32, y: u32, width: u32, height: u32) -> [f64; 2] {
    [
        (f64::from(x) + 0.5) / f64::from(width),
        (f64::from(y) + 0.5) / f64::from(height),
    ]
}

/// An image computed texel by texel, its rows shared among the cores.
fn in_parallel_rows(
    width: u32,
    height: u32,
    texel: impl Fn(u32, u32) -> [f32; 4] + Sync,
) -> Rgba32FImage {
    use rayon::prelude::*;
    let row = width as usize * 4;
    let mut raw = vec![0f32; row * height as usize];
    raw.par_chunks_mut(row.max(1))
        .enumerate()
        .for_each(|(y, out)| {
            for (x, pixel) in out.chunks_exact_mut(4).enumerate() {
                pixel.copy_from_slice(&texel(x as u32, y as u32));
            }
        });
    // The buffer has exactly width × height pixels: from_raw cannot refuse it.
    Rgba32FImage::from_raw(width, height, raw).unwrap_or_default()
}

/// Each output texel's index into the distinct values, and the base colour `fits` chose for
/// each value (`None`: the closed form, unchecked). At most [`fit::MAX_SCREENED_TEXELS`]
/// values are listed, in the order they first appear row by row, so that memory stays
/// bounded whatever the texture holds.
fn judged(
    source: &SpecGlossTexels,
    fits: &mut TexelFits,
    levels: f64,
) -> (Vec<u32>, Vec<Option<[f64; 3]>>) {
    let width = source.width as usize;
    let (x, y) = (
        |at: usize| (at % width) as u32,
        |at: usize| (at / width) as u32,
    );
    match source.stored_key() {
        Some(stored) => judged_by(source, fits, levels, |at| stored(x(at), y(at))),
        None => judged_by(source, fits, levels, |at| source.at(x(at), y(at)).0.key()),
    }
}

/// [`judged`], texels told apart by `key_at` (the texel at an index, row by row): equal keys
/// must mean equal values.
fn judged_by<K: Copy + Eq + std::hash::Hash + Sync>(
    source: &SpecGlossTexels,
    fits: &mut TexelFits,
    levels: f64,
    key_at: impl Fn(usize) -> K + Sync,
) -> (Vec<u32>, Vec<Option<[f64; 3]>>) {
    use rayon::prelude::*;
    let width = source.width as usize;
    let texels = width * source.height as usize;
    let value_at = |at: usize| source.at((at % width) as u32, (at / width) as u32).0;
    let mut index = vec![0u32; texels];
    let mut distinct: HashMap<K, u32> = HashMap::new();
    let mut values = Vec::new();
    // Texels whose value is already listed are found on every core; the others are listed
    // in order afterwards, so the list is the one a single pass would make. Group by group,
    // so that a value listed early is found, not listed again, in later groups.
    for (g, group) in index.chunks_mut(LISTED_GROUP).enumerate() {
        let first = g * LISTED_GROUP;
        let full = values.len() >= fit::MAX_SCREENED_TEXELS;
        // A texel equal to the one before it (a flat region) takes its index unhashed, or
        // once that is listed.
        let lookup = |(r, run): (usize, &mut [u32])| {
            let mut previous: Option<(K, u32)> = None;
            for (k, slot) in run.iter_mut().enumerate() {
                let key = key_at(first + r * LOOKUP_RUN + k);
                *slot = match previous.filter(|(before, _)| *before == key) {
                    Some((_, NEW | AS_BEFORE)) => AS_BEFORE,
                    Some((_, i)) => i,
                    None => match distinct.get(&key) {
                        Some(&i) => i,
                        None if full => UNLISTED,
                        None => NEW,
                    },
                };
                previous = Some((key, *slot));
            }
        };
        group
            .par_chunks_mut(LOOKUP_RUN)
            .enumerate()
            .for_each(lookup);
        for k in 0..group.len() {
            group[k] = match group[k] {
                NEW => match distinct.entry(key_at(first + k)) {
                    Entry::Occupied(known) => *known.get(),
                    Entry::Vacant(new) if values.len() < fit::MAX_SCREENED_TEXELS => {
                        values.push(value_at(first + k));
                        *new.insert(values.len() as u32 - 1)
                    }
                    Entry::Vacant(_) => UNLISTED,
                },
                AS_BEFORE => group[k - 1],
                listed => listed,
            };
        }
    }
    let bases = fits.resolve(&values, levels);
    let unchecked = |&i: &u32| bases.get(i as usize).is_none_or(Option::is_none);
    fits.unchecked(index.iter().filter(|i| unchecked(i)).count());
    (index, bases)
}

/// Texels [`judged`] looks up in parallel before it lists the new values among them, and
/// texels each core looks up in a row.
const LISTED_GROUP: usize = 1 << 16;
const LOOKUP_RUN: usize = 1 << 10;

/// The index of a texel whose value is not listed, and (while [`judged`] runs) of one whose
/// value is yet to be listed, and of one that equals the texel before it.
const UNLISTED: u32 = u32::MAX;
const NEW: u32 = u32::MAX - 1;
const AS_BEFORE: u32 = u32::MAX - 2;

/// A spec-gloss material's two textures sampled on the rebake's grid.
struct SpecGlossTexels<'t> {
    diffuse: Option<&'t TextureImage>,
    specular: Option<&'t TextureImage>,
    /// The samplers the diffuse and the specular-glossiness textures are read through.
    samplers: [Sampler; 2],
    factors: &'t Factors,
    width: u32,
    height: u32,
}

impl SpecGlossTexels<'_> {
    /// The textures read.
    fn inputs(&self) -> impl Iterator<Item = &TextureImage> {
        self.diffuse.into_iter().chain(self.specular)
    }

    /// The sampler the rebake is read through: the diffuse texture's where there is one
    /// (its texture takes that one's place), else the specular-glossiness texture's.
    fn shown_through(&self) -> Sampler {
        self.samplers[usize::from(self.diffuse.is_none())]
    }

    fn centre(&self, x: u32, y: u32) -> [f64; 2] {
        centre(x, y, self.width, self.height)
    }

    /// Where every texture is stored at the grid's size, a power of two each way (so that a
    /// texel centre's coordinates are exact and read one stored texel), with every texel
    /// held in 8-bit channels, and every factor a value reads is a normal number (so that
    /// distinct levels stay distinct): the stored channels output texel (x, y)'s value reads,
    /// packed into one word. Equal words are then exactly equal values, and a word is
    /// cheaper to hash and compare than the value's seven numbers.
    fn stored_key(&self) -> Option<impl Fn(u32, u32) -> u64 + Sync + '_> {
        let (width, height) = (self.width, self.height);
        let stored = |t: &TextureImage| {
            t.width() == width && t.height() == height && t.narrow_texel(0, 0).is_some()
        };
        let Factors {
            diffuse,
            specular,
            glossiness,
            ..
        } = self.factors;
        let mut factors = diffuse[..3].iter().chain(specular).chain([glossiness]);
        let exact = width.is_power_of_two() && height.is_power_of_two();
        let keyed = exact && factors.all(|f| f.is_normal()) && self.inputs().all(stored);
        // The diffuse alpha is not part of the value (the rebake writes it apart).
        let alpha_bits = if self.diffuse.is_some_and(TextureImage::has_alpha) {
            8
        } else {
            0
        };
        keyed.then_some(move |x, y| {
            let word = |t: Option<&TextureImage>| {
                t.and_then(|t| t.narrow_texel(x, y)).map_or(0, u64::from)
            };
            (word(self.diffuse) >> alpha_bits) << 32 | word(self.specular)
        })
    }

    /// The diffuse alpha (factor applied) at the centre of output texel (x, y).
    fn alpha(&self, x: u32, y: u32) -> f32 {
        let centre = self.centre(x, y);
        let a = (self.diffuse).map_or(1.0, |t| {
            sample::sampled_srgb(t, centre, self.samplers[0])[3]
        });
        (a * self.factors.diffuse[3]) as f32
    }

    /// The value at the centre of output texel (x, y) (linear, factors applied), and the
    /// diffuse alpha.
    fn at(&self, x: u32, y: u32) -> (TexelValue, f32) {
        self.sampled(self.centre(x, y))
    }

    /// The value at texture coordinates `uv`.
    fn value_at(&self, uv: [f64; 2]) -> TexelValue {
        self.sampled(uv).0
    }

    /// The value and the diffuse alpha at texture coordinates `centre`.
    fn sampled(&self, centre: [f64; 2]) -> (TexelValue, f32) {
        // Colours decoded before they are mixed, as the evaluator and viewers sample them.
        let sample = |t: Option<&TextureImage>, sampler| {
            t.map_or([1.0; 4], |t| sample::sampled_srgb(t, centre, sampler))
        };
        let [diffuse_sampler, specular_sampler] = self.samplers;
        let (d, s) = (
            sample(self.diffuse, diffuse_sampler),
            sample(self.specular, specular_sampler),
        );
        let linear =
            |texel: [f64; 4], factor: &[f64]| std::array::from_fn(|c| texel[c] * factor[c]);
        let value = TexelValue {
            diffuse: linear(d, &self.factors.diffuse),
            specular: linear(s, &self.factors.specular),
            glossiness: s[3] * self.factors.glossiness,
        };
        (value, (d[3] * self.factors.diffuse[3]) as f32)
    }
}

/// Whether any texel has alpha below 1 (the material then needs alpha blending). An image
/// whose header declares no alpha (tRNS included) is not decoded.
pub(super) fn has_translucent_texels(bytes: &[u8]) -> bool {
    let header = image_header::read(bytes).map(|info| info.channels);
    if matches!(header, Ok(Channels::Rgb | Channels::Luminance)) {
        return false;
    }
    match decode(bytes) {
        Ok(image) if image.color().has_alpha() => image.to_rgba8().pixels().any(|p| p.0[3] < 255),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(image: image::RgbaImage) -> Vec<u8> {
        let mut bytes = Vec::new();
        DynamicImage::ImageRgba8(image)
            .write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
            .unwrap();
        bytes
    }

    #[test]
    fn metallic_moves_from_red_to_blue_texel_for_texel() {
        let source = image::RgbaImage::from_fn(3, 2, |x, y| {
            image::Rgba([(x * 80) as u8, (y * 90 + 7) as u8, 33, 255])
        });
        let out = decode(&metal_rough_swizzle(&png(source.clone())).unwrap())
            .unwrap()
            .to_rgba8();
        for (x, y, p) in source.enumerate_pixels() {
            let q = out.get_pixel(x, y).0;
            assert_eq!((q[1], q[2]), (p.0[1], p.0[0]), "texel ({x}, {y})");
        }
    }

    #[test]
    fn a_rebake_grid_is_held_to_the_largest_input_or_the_floor_not_their_product() {
        assert_eq!(rebake_grid(2048, 2048, 2048 * 2048), (2048, 2048, None));
        assert_eq!(rebake_grid(8192, 8192, 8192 * 8192), (8192, 8192, None));
        let (w, h, held) = rebake_grid(16384, 16384, 16384);
        assert_eq!((w, h), (2048, 2048));
        assert!(held.is_some_and(|d| d.contains("2048×2048, not the 16384×16384")));
        let (w, h, _) = rebake_grid(65536, 4, 16384);
        assert!(
            u64::from(w) * u64::from(h) <= REBAKE_FLOOR && h >= 1,
            "{w}×{h}"
        );
    }

    #[test]
    fn base_colour_keeps_what_the_specular_lobe_does_not_take() {
        let diffuse = image::RgbaImage::from_pixel(1, 1, image::Rgba([188, 188, 188, 200])); // ≈ 0.5 linear
        let factors = Factors {
            diffuse: [1.0; 4],
            specular: [0.5, 0.2, 0.2],
            glossiness: 1.0,
            reading: crate::shade::material::SpecGlossReading::ArchivedExtension,
        };
        let (bytes, alpha, held) = spec_gloss_base_colour(
            Some(&png(diffuse)),
            None,
            Default::default(),
            &factors,
            None,
        )
        .unwrap();
        assert_eq!(held, None);
        let texel = decode(&bytes).unwrap().to_rgb8().get_pixel(0, 0).0;
        let expected =
            linear_to_srgb(crate::gltf::color::srgb_to_linear(188.0 / 255.0) * 0.5) * 255.0;
        assert!(
            (f64::from(texel[0]) - expected).abs() <= 0.5,
            "{texel:?} vs {expected}"
        );
        assert!(
            alpha,
            "a diffuse with a texel below full alpha keeps its alpha channel"
        );
    }

    /// A `width` × `height` RGBA texture, decoded from its PNG, whose texel (x, y) holds the
    /// bytes of a multiplicative hash of `key(x, y)`: noise, equal where the keys are.
    fn hashed(width: u32, height: u32, key: impl Fn(u32, u32) -> u32) -> sample::Texture {
        sample::decode(&png(hashed_image(width, height, key))).unwrap()
    }

    /// An RGBA image whose texels are a hash of `key` (equal keys, equal texels).
    fn hashed_image(width: u32, height: u32, key: impl Fn(u32, u32) -> u32) -> image::RgbaImage {
        image::RgbaImage::from_fn(width, height, |x, y| {
            let h = key(x, y).wrapping_mul(2_654_435_761);
            image::Rgba([(h >> 8) as u8, (h >> 16) as u8, (h >> 24) as u8, h as u8])
        })
    }

    /// Factors that scale every channel differently, read as the archived extension.
    fn chromatic() -> Factors {
        Factors {
            diffuse: [0.9, 0.8, 1.0, 1.0],
            specular: [0.5, 0.7, 0.2],
            glossiness: 1.0,
            reading: crate::shade::material::SpecGlossReading::ArchivedExtension,
        }
    }

    /// Both textures, on the grid of the diffuse (the two are alike in size here).
    fn both<'t>(
        diffuse: &'t TextureImage,
        specular: &'t TextureImage,
        factors: &'t Factors,
    ) -> SpecGlossTexels<'t> {
        SpecGlossTexels {
            diffuse: Some(diffuse),
            specular: Some(specular),
            samplers: Default::default(),
            factors,
            width: diffuse.width(),
            height: diffuse.height(),
        }
    }

    /// The distinct texel values are listed on every core, yet exactly as one pass in row
    /// order lists them: each texel's index is its value's first appearance, across the
    /// parallel groups, through flat runs (rows of one value, runs of equal texels), and past
    /// the listing's cap every new value is unlisted. So whether texels are told apart by
    /// their stored channels (textures stored at the grid's power-of-two size, normal
    /// factors: the diffuse alpha, which varies here, is no part of a value) or by their
    /// values (any other size, or a factor of 0 that merges levels).
    #[test]
    fn texel_values_are_listed_in_the_order_one_pass_meets_them() {
        let zero_red = Factors {
            specular: [0.0, 0.7, 0.2],
            ..chromatic()
        };
        for (width, height, factors, by_stored_channels) in [
            (600, 250, chromatic(), false),
            (512, 512, chromatic(), true),
            (512, 512, zero_red, false),
        ] {
            let key = |x: u32, y: u32| match y % 3 {
                0 => 7,
                _ => x / (1 + y % 2) + y * 1000,
            };
            // The alpha varies along every run of equal colours.
            let mut diffuse = hashed_image(width, height, key);
            (diffuse.enumerate_pixels_mut()).for_each(|(x, _, p)| p[3] = (x % 7 * 40) as u8);
            let diffuse = sample::decode(&png(diffuse)).unwrap();
            let specular = hashed(width, height, |x, y| key(x, y) % 5);
            let source = both(&diffuse, &specular, &factors);
            assert_eq!(source.stored_key().is_some(), by_stored_channels);
            let reading = crate::shade::material::SpecGlossReading::ArchivedExtension;
            let mut fits = TexelFits::with_budgets(reading, 0, 0);
            let (index, _) = judged(&source, &mut fits, 255.0);
            let mut first_seen: HashMap<[u64; 7], u32> = HashMap::new();
            let expected: Vec<u32> = (0..height)
                .flat_map(|y| (0..width).map(move |x| (x, y)))
                .map(|(x, y)| {
                    let (listed, full) = (
                        first_seen.len(),
                        first_seen.len() >= fit::MAX_SCREENED_TEXELS,
                    );
                    match first_seen.entry(source.at(x, y).0.key()) {
                        Entry::Occupied(known) => *known.get(),
                        Entry::Vacant(_) if full => UNLISTED,
                        Entry::Vacant(new) => *new.insert(listed as u32),
                    }
                })
                .collect();
            // The case covers what it is about: values first met in a later group, and the cap.
            let first_group = expected[..LISTED_GROUP]
                .iter()
                .filter(|&&i| i != UNLISTED)
                .max();
            let later = |&i: &u32| i != UNLISTED && Some(&i) > first_group;
            assert!(expected[LISTED_GROUP..].iter().any(later));
            assert!(expected.contains(&UNLISTED), "{width}×{height}");
            assert_eq!(index, expected, "{width}×{height}");
        }
    }

    /// The between-centres check skips a corner whose four centres equal those of the corner
    /// before it; its maximum is still every corner's, measured one by one through bilinear
    /// reads. Rows alternate flat and split in two, so that a corner under a flat row and
    /// over a split one is where a wrong skip would look away.
    #[test]
    fn the_between_centres_error_is_the_largest_of_every_corner() {
        use crate::shade::delta_e::{ciede2000, lab_from_linear_srgb};
        use crate::shade::tone::displayed;
        let (width, height) = (23, 6);
        for seed in 0..12 {
            let image = |layer: u32| {
                hashed(width, height, |x, y| {
                    let part = u32::from(y % 2 == 1 && x >= 5 + 2 * y);
                    part * 73 + y * 151 + layer * 7919 + seed * 104_729
                })
            };
            let (diffuse, specular) = (image(1), image(2));
            let factors = chromatic();
            let texels = both(&diffuse, &specular, &factors);
            let base = |v: TexelValue| factors.base_colour(v.diffuse, v.specular);
            let shown = |colour: [f64; 3]| lab_from_linear_srgb(displayed(colour));
            let mut every = 0f64;
            for (x, y) in (0..height).flat_map(|y| (0..width).map(move |x| (x, y))) {
                let around = [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)]
                    .map(|(i, j)| base(texels.at(i % width, j % height).0));
                let mixed = std::array::from_fn(|c| around.iter().map(|b| b[c]).sum::<f64>() / 4.0);
                let corner = [
                    f64::from(x + 1) / f64::from(width),
                    f64::from(y + 1) / f64::from(height),
                ];
                let exact = base(texels.value_at(corner));
                every = every.max(ciede2000(shown(mixed), shown(exact)));
            }
            let checked = between_centres_error(&texels);
            assert!(
                (checked - every).abs() <= 1e-9 * every,
                "seed {seed}: {checked} vs {every}"
            );
        }
    }

    #[test]
    fn on_the_inputs_grid_a_texel_corner_reads_as_the_mean_of_its_four_centres() {
        // The premise of `corners_error`'s shortcut: bilinear filtering midway between four
        // texel centres (sRGB decoded first, repeat wrapping at the edges) is their mean.
        let noise = |seed: u32| hashed(7, 5, |x, y| x * 73 + y * 151 + seed);
        let (diffuse, specular) = (noise(1), noise(2));
        let factors = chromatic();
        let texels = both(&diffuse, &specular, &factors);
        for (x, y) in (0..5).flat_map(|y| (0..7).map(move |x| (x, y))) {
            let around = [
                (x, y),
                ((x + 1) % 7, y),
                (x, (y + 1) % 5),
                ((x + 1) % 7, (y + 1) % 5),
            ]
            .map(|(i, j)| texels.at(i, j).0);
            let corner = texels.value_at([f64::from(x + 1) / 7.0, f64::from(y + 1) / 5.0]);
            for c in 0..3 {
                let mean = |f: fn(&TexelValue) -> [f64; 3]| {
                    around.iter().map(|v| f(v)[c]).sum::<f64>() / 4.0
                };
                assert!(
                    (mean(|v| v.diffuse) - corner.diffuse[c]).abs() < 1e-12,
                    "({x}, {y})"
                );
                assert!(
                    (mean(|v| v.specular) - corner.specular[c]).abs() < 1e-12,
                    "({x}, {y})"
                );
            }
        }
    }

    #[test]
    fn only_texels_below_full_alpha_make_a_texture_translucent() {
        let with_alpha = |a| {
            png(image::RgbaImage::from_pixel(
                2,
                2,
                image::Rgba([9, 9, 9, a]),
            ))
        };
        let mut rgb = Vec::new();
        DynamicImage::ImageRgb8(image::RgbImage::new(2, 2))
            .write_to(&mut Cursor::new(&mut rgb), image::ImageFormat::Png)
            .unwrap();
        // Judged from the bytes, and from their decode (as a rebake judges them).
        for (bytes, translucent) in [
            (with_alpha(128), true),
            (with_alpha(255), false),
            (rgb, false),
        ] {
            assert_eq!(has_translucent_texels(&bytes), translucent);
            let decoded = sample::decode(&bytes).unwrap();
            assert_eq!(decoded.has_translucent_texels(), Some(translucent));
        }
        // 16-bit texels are left to the bytes' judgement.
        let mut wide = Vec::new();
        let texel = image::Rgba([9u16, 9, 9, 40_000]);
        DynamicImage::ImageRgba16(image::ImageBuffer::from_pixel(2, 2, texel))
            .write_to(&mut Cursor::new(&mut wide), image::ImageFormat::Png)
            .unwrap();
        assert_eq!(
            sample::decode(&wide).unwrap().has_translucent_texels(),
            None
        );
        assert!(has_translucent_texels(&wide));
    }
}
