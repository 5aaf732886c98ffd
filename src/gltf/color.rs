//! Colour transfer functions shared by the checker, the converter and the shading evaluator.

/// sRGB-encoded value (0..1) to linear, IEC 61966-2-1.
pub(crate) fn srgb_to_linear(encoded: f64) -> f64 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// `srgb_to_linear` for sampled texture values: an exact 8-bit level (most texels) is
/// looked up in a table of the same function instead of calling `powf`.
#[inline(always)]
pub(crate) fn srgb_texel_to_linear(encoded: f64) -> f64 {
    static TABLE: std::sync::OnceLock<[f64; 256]> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| std::array::from_fn(|i| srgb_to_linear(i as f64 / 255.0)));
    let scaled = encoded * 255.0;
    // Rounds to the nearest level for scaled ≥ −0.5 (a cast, where `round` is a library
    // call on baseline x86-64); anything else fails the closeness test below.
    let level = (scaled + 0.5) as usize;
    match table.get(level) {
        Some(&linear) if (scaled - level as f64).abs() < 1e-4 => linear,
        _ => srgb_to_linear(encoded),
    }
}

/// Linear value (0..1) to sRGB-encoded, IEC 61966-2-1.
pub(crate) fn linear_to_srgb(linear: f64) -> f64 {
    if linear <= 0.0031308 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// `round(255 · linear_to_srgb(linear))` for linear values clamped to 0..1, without
/// `powf` (rebaking and rendering encode millions of texels): the level is the number of
/// level boundaries (linear values where the rounded level changes) at or below the value,
/// counted from a bucket table that starts within two levels of the answer.
pub(crate) fn linear_to_srgb8(linear: f64) -> u8 {
    const BUCKETS: usize = 4096;
    struct Tables {
        boundaries: [f64; 255],
        /// The level of each bucket's lower end.
        bucket_start: [u8; BUCKETS],
    }
    static TABLES: std::sync::OnceLock<Tables> = std::sync::OnceLock::new();
    let tables = TABLES.get_or_init(|| {
        let boundaries: [f64; 255] =
            std::array::from_fn(|k| srgb_to_linear((k as f64 + 0.5) / 255.0));
        let count = |v: f64| boundaries.partition_point(|&b| v >= b) as u8;
        Tables {
            bucket_start: std::array::from_fn(|i| count(i as f64 / (BUCKETS - 1) as f64)),
            boundaries,
        }
    });
    // NaN and negatives land in bucket 0 and pass no boundary: level 0.
    let bucket = (linear.clamp(0.0, 1.0) * (BUCKETS - 1) as f64) as usize;
    let mut level = tables.bucket_start[bucket.min(BUCKETS - 1)];
    while level < 255 && linear >= tables.boundaries[usize::from(level)] {
        level += 1;
    }
    level
}

/// Relative luminance of linear Rec.709 / sRGB primaries.
pub(crate) fn luminance([r, g, b]: [f64; 3]) -> f64 {
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transfer_functions_invert_each_other() {
        for i in 0..=255 {
            let encoded = f64::from(i) / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(encoded)) - encoded).abs() < 1e-12);
        }
        assert!((srgb_to_linear(0.5) - 0.214_041_140_5).abs() < 1e-9);
    }

    #[test]
    fn eight_bit_encoding_rounds_the_transfer_function() {
        for step in 0..=1_000_000 {
            let linear = f64::from(step) / 1_000_000.0;
            let expected = (linear_to_srgb(linear) * 255.0).round() as u8;
            assert_eq!(linear_to_srgb8(linear), expected, "{linear}");
        }
        for i in 0..=255u8 {
            let level = srgb_to_linear(f64::from(i) / 255.0);
            assert_eq!(linear_to_srgb8(level), i, "the level's own linear value");
        }
        assert_eq!(
            (
                linear_to_srgb8(-1.0),
                linear_to_srgb8(2.0),
                linear_to_srgb8(f64::NAN)
            ),
            (0, 255, 0)
        );
    }

    #[test]
    fn texel_decoding_matches_the_transfer_function() {
        for i in 0..=255 {
            let level = f64::from(i) / 255.0;
            // Also as an `f32` texel would carry it.
            let stored = f64::from(level as f32);
            assert!((srgb_texel_to_linear(stored) - srgb_to_linear(level)).abs() < 1e-6);
        }
        let between = 100.5 / 255.0;
        assert_eq!(srgb_texel_to_linear(between), srgb_to_linear(between));
    }
}
