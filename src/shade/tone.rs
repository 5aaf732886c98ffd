//! What a viewer shows: radiance under a stated exposure, tone-mapped with Khronos PBR
//! Neutral. `render` encodes the result as sRGB; `compare` takes CIELAB of it, so L* stays in
//! 0–100 and a ΔE of 1 is a just-noticeable difference on a display, not on unbounded
//! radiance (where a mirror highlight reached L* 4,000 and any change read as huge).

use super::brdf::V3;

/// The exposure both use: radiance is multiplied by 1 before tone mapping. With `compare`'s
/// light (irradiance π at normal incidence) a white Lambertian surface lit head-on has
/// radiance 1, which PBR Neutral shows at 0.87 (L* 95).
pub(crate) const EXPOSURE: f64 = 1.0;

/// Khronos PBR Neutral tone mapping (linear in, linear out, 0..1), written without branches
/// so that `compare`'s per-sample loop stays vector code.
#[inline(always)]
pub(crate) fn pbr_neutral(colour: V3) -> V3 {
    const START_COMPRESSION: f64 = 0.8 - 0.04;
    const DESATURATION: f64 = 0.15;
    let x = colour[0].min(colour[1]).min(colour[2]);
    let offset = if x < 0.08 { x - 6.25 * x * x } else { 0.04 };
    let c = colour.map(|v| v - offset);
    let peak = c[0].max(c[1]).max(c[2]);
    let d = 1.0 - START_COMPRESSION;
    let new_peak = 1.0 - d * d / (peak + d - START_COMPRESSION);
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    // Below the compression start the colour passes unchanged (new_peak / peak would not be
    // 1 there, so the choice is made per value, not by an early return).
    let compressed = peak >= START_COMPRESSION;
    c.map(|v| {
        let scaled = v * new_peak / peak;
        let mapped = scaled * (1.0 - g) + new_peak * g;
        if compressed {
            mapped
        } else {
            v
        }
    })
}

/// The displayed linear colour of a radiance: negative parts cut, exposed, tone-mapped.
#[inline(always)]
pub(crate) fn displayed(radiance: V3) -> V3 {
    pbr_neutral(radiance.map(|c| c.max(0.0) * EXPOSURE))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pbr_neutral_leaves_dark_colours_nearly_alone_and_compresses_highlights() {
        let dark = pbr_neutral([0.3, 0.2, 0.1]);
        assert!((dark[0] - (0.3 - 0.04)).abs() < 1e-12, "{dark:?}");
        let bright = pbr_neutral([4.0, 4.0, 4.0]);
        assert!(bright.iter().all(|c| *c < 1.0 && *c > 0.9), "{bright:?}");
        // Continuous where compression starts.
        let below = pbr_neutral([0.8 - 1e-9; 3]);
        let above = pbr_neutral([0.8 + 1e-9; 3]);
        assert!((below[0] - above[0]).abs() < 1e-8, "{below:?} {above:?}");
    }

    #[test]
    fn what_a_viewer_shows_is_bounded_whatever_the_radiance() {
        for radiance in [0.0, 0.5, 1.0, 10.0, 4_477.0, 1e300] {
            let shown = displayed([radiance, radiance * 0.5, -1.0]);
            assert!(
                shown.iter().all(|c| (0.0..=1.0).contains(c)),
                "{radiance}: {shown:?}"
            );
        }
        let white = displayed([1.0; 3])[0];
        assert!(
            (white - 0.87).abs() < 0.005,
            "white Lambertian head-on shows {white}"
        );
    }
}
