//! Colour transfer functions shared by the checker, the converter and the shading evaluator.

/// sRGB-encoded value (0..1) to linear, IEC 61966-2-1.
pub fn srgb_to_linear(encoded: f64) -> f64 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear value (0..1) to sRGB-encoded, IEC 61966-2-1.
pub fn linear_to_srgb(linear: f64) -> f64 {
    if linear <= 0.0031308 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// Relative luminance of linear Rec.709 / sRGB primaries.
pub fn luminance([r, g, b]: [f64; 3]) -> f64 {
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
}
