//! Colour difference: linear sRGB → CIELAB (D65) and CIEDE2000 (Sharma, Wu & Dalal 2005).
//!
//! Branch-free and generic over [`Real`]. The comparison evaluates it as plain `f64` in a
//! loop over a batch of samples, which the compiler vectorises whole, where
//! [`Lanes`](super::lanes::Lanes)' element-wise form is vectorised only in part.

use super::elementary;
use super::lanes::Real;

/// linear sRGB → XYZ (D65), each row divided by the white point's coordinate, so that the
/// products are CIELAB's X/Xn, Y/Yn, Z/Zn without a division per colour.
const RGB_TO_XYZ_OVER_WHITE: [[f64; 3]; 3] = {
    const XYZ: [[f64; 3]; 3] = [
        [0.412_456_4, 0.357_576_1, 0.180_437_5],
        [0.212_672_9, 0.715_152_2, 0.072_175_0],
        [0.019_333_9, 0.119_192_0, 0.950_304_1],
    ];
    const WHITE: [f64; 3] = [0.950_47, 1.0, 1.088_83];
    let mut m = XYZ;
    let mut row = 0;
    while row < 3 {
        let mut column = 0;
        while column < 3 {
            m[row][column] = XYZ[row][column] / WHITE[row];
            column += 1;
        }
        row += 1;
    }
    m
};

/// CIELAB of a linear sRGB colour (D65 white, Y of white = 1).
#[inline(always)]
pub(crate) fn lab_from_linear_srgb<R: Real>([r, g, b]: [R; 3]) -> [R; 3] {
    let [x, y, z] = RGB_TO_XYZ_OVER_WHITE;
    let fx = lab_f(r * x[0] + g * x[1] + b * x[2]);
    let fy = lab_f(r * y[0] + g * y[1] + b * y[2]);
    let fz = lab_f(r * z[0] + g * z[1] + b * z[2]);
    [fy * 116.0 - 16.0, (fx - fy) * 500.0, (fy - fz) * 200.0]
}

/// CIELAB's f(t): a cube root, linear near black.
#[inline(always)]
fn lab_f<R: Real>(t: R) -> R {
    const DELTA: f64 = 6.0 / 29.0;
    let linear = t * (1.0 / (3.0 * DELTA * DELTA)) + 4.0 / 29.0;
    R::select(t.gt(R::splat(DELTA * DELTA * DELTA)), cube_root(t), linear)
}

/// Cube root of a positive normal number, without a division (the comparison takes six
/// per sample, and vector divisions are slow): y = a^(−1/3) from a first guess on the
/// exponent bits (good to 3.4%; the constant is tuned for the smallest worst case), four
/// Newton steps y ← y·(4 − a·y³)/3 (each squares the error), then ∛a = a·y². Within a few
/// ulps of `cbrt`, several times faster, and the high-word guess needs only a 32-bit
/// division by 3, done as a multiplication, which vectorises. (Halley's method on ∛a needs
/// three divisions.)
#[inline(always)]
fn cube_root<R: Real>(a: R) -> R {
    const MAGIC: u64 = 0x553E_F0F0;
    let mut y = a.map_bits(|bits| {
        let high = (bits >> 32) & 0x7FFF_FFFF;
        let third = (high * 0xAAAA_AAAB) >> 33; // high / 3 for any 32-bit high
        (MAGIC - third) << 32
    });
    for _ in 0..4 {
        y = y * (-(a * y * y * y) + 4.0) * (1.0 / 3.0);
    }
    a * y * y
}

/// CIEDE2000 ΔE between two CIELAB colours (k_L = k_C = k_H = 1).
///
/// Branch-free, and the hue terms come from the a′b′ vectors rather than from hue angles,
/// leaving one arctangent (for Δθ's exponent) where the angle form needs two plus a sine
/// and T's four cosines:
/// - ΔH′² = Δa′² + Δb² − ΔC′², which equals the paper's (2·√(C′₁C′₂)·sin(Δh′/2))², with
///   the sign of Δh′ from the cross product of the two a′b′ vectors;
/// - h̄′ is the direction bisecting the two hue vectors along the shorter arc, which is the
///   mean the paper's case analysis selects.
#[inline(always)]
pub(crate) fn ciede2000<R: Real>([l1, a1, b1]: [R; 3], [l2, a2, b2]: [R; 3]) -> R {
    let g = (-chroma_ratio((length(a1, b1) + length(a2, b2)) * 0.5) + 1.0) * 0.5;
    let (a1p, a2p) = (a1 * (g + 1.0), a2 * (g + 1.0));
    let (c1p, c2p) = (length(a1p, b1), length(a2p, b2));
    let hue = Hue::between([a1p, b1, c1p], [a2p, b2, c2p]);
    let dl = l2 - l1;
    let dc = c2p - c1p;
    let dh = hue.delta_h(a2p - a1p, b2 - b1, dc);
    let l_bar = (l1 + l2) * 0.5;
    let c_bar_p = (c1p + c2p) * 0.5;
    let t = hue_weight(hue.mean_cos, hue.mean_sin);
    let z = (hue.mean_degrees - 275.0) * (1.0 / 25.0);
    let d_theta = elementary::exp(-(z * z)) * 30.0;
    let rc = chroma_ratio(c_bar_p) * 2.0;
    let l50 = (l_bar - 50.0) * (l_bar - 50.0);
    let sl = l50 * 0.015 / (l50 + 20.0).sqrt() + 1.0;
    let sc = c_bar_p * 0.045 + 1.0;
    let sh = c_bar_p * 0.015 * t + 1.0;
    let rt = -elementary::sin_small(d_theta * (2.0 * RADIANS_PER_DEGREE)) * rc;
    let (l, c, h) = (dl / sl, dc / sc, dh / sh);
    (l * l + c * c + h * h + rt * c * h).sqrt()
}

/// An upper bound on [`ciede2000`] from the plain Lab distance (ΔE76), for skipping pairs
/// that cannot change a maximum: ΔE00 ≤ √4.5 · ΔE76. Why: S_L, S_C, S_H ≥ 1 (T is at
/// least 1 − 0.93, positive); |R_T| ≤ 2, so R_T·x·y ≤ x² + y²; ΔC′² + ΔH′² is the squared
/// distance of the a′b′ vectors, and a′ = (1 + G)·a with one G ≤ ½ for both colours. Hence
/// ΔE00² ≤ ΔL² + 2·(2.25·Δa² + Δb²) ≤ 4.5·ΔE76². The factor is rounded up past rounding
/// error.
pub(crate) fn ciede2000_bound([l1, a1, b1]: [f64; 3], [l2, a2, b2]: [f64; 3]) -> f64 {
    let (dl, da, db) = (l1 - l2, a1 - a2, b1 - b2);
    2.1214 * (dl * dl + da * da + db * db).sqrt()
}

/// What `f64::to_radians` multiplies by.
const RADIANS_PER_DEGREE: f64 = std::f64::consts::PI / 180.0;

#[inline(always)]
fn length<R: Real>(x: R, y: R) -> R {
    (x * x + y * y).sqrt()
}

/// √(C⁷ / (C⁷ + 25⁷)), the chroma weight of G and R_C.
#[inline(always)]
fn chroma_ratio<R: Real>(c: R) -> R {
    let c2 = c * c;
    let c7 = c2 * c2 * c2 * c;
    (c7 / (c7 + 25f64.powi(7))).sqrt()
}

/// The hue geometry of a colour pair: ΔH′'s sign and the mean hue h̄′.
struct Hue<R: Real> {
    /// Both chromas are non-zero (otherwise ΔH′ is 0 and h̄′ is the other colour's hue).
    chromatic: R::Mask,
    /// The second hue lies counter-clockwise of the first: Δh′ > 0.
    counter_clockwise: R::Mask,
    mean_degrees: R,
    mean_cos: R,
    mean_sin: R,
}

impl<R: Real> Hue<R> {
    /// From (a′, b, C′) of each colour.
    #[inline(always)]
    fn between([a1, b1, c1]: [R; 3], [a2, b2, c2]: [R; 3]) -> Hue<R> {
        let zero = R::splat(0.0);
        let chromatic = !(c1 * c2).eq(zero);
        let cross = a1 * b2 - b1 * a2;
        // Exactly opposite hues: the paper's Δh′ = h′₂ − h′₁ is +180° when h′₁ < 180°.
        let first_below_half_turn = b1.gt(zero) | (b1.eq(zero) & a1.gt(zero));
        let counter_clockwise = cross.gt(zero) | (cross.eq(zero) & first_below_half_turn);
        // The hue vectors scaled to equal lengths (each by the other's chroma): their sum
        // bisects the shorter arc; past 90° apart the sum cancels, and the perpendicular of
        // their difference, turned towards the shorter arc, is the accurate bisector.
        let (sum_x, sum_y) = (a1 * c2 + a2 * c1, b1 * c2 + b2 * c1);
        let (diff_x, diff_y) = (a2 * c1 - a1 * c2, b2 * c1 - b1 * c2);
        let perp_x = R::select(counter_clockwise, diff_y, -diff_y);
        let perp_y = R::select(counter_clockwise, -diff_x, diff_x);
        let facing = (a1 * a2 + b1 * b2).ge(zero);
        // Without a chroma, the paper's h̄′ = h′₁ + h′₂ is the other colour's hue (or 0).
        let x = R::select(chromatic, R::select(facing, sum_x, perp_x), a1 + a2);
        let y = R::select(chromatic, R::select(facing, sum_y, perp_y), b1 + b2);
        let norm = length(x, y);
        let degenerate = norm.eq(zero);
        let inverse_norm = R::splat(1.0) / norm;
        Hue {
            chromatic,
            counter_clockwise,
            mean_degrees: elementary::atan2_degrees(y, x),
            mean_cos: R::select(degenerate, R::splat(1.0), x * inverse_norm),
            mean_sin: R::select(degenerate, zero, y * inverse_norm),
        }
    }

    /// ΔH′ from Δa′, Δb and ΔC′.
    #[inline(always)]
    fn delta_h(&self, da: R, db: R, dc: R) -> R {
        let magnitude = (da * da + db * db - dc * dc).max(R::splat(0.0)).sqrt();
        let signed = R::select(self.counter_clockwise, magnitude, -magnitude);
        R::select(self.chromatic, signed, R::splat(0.0))
    }
}

/// T(h̄) = 1 − 0.17 cos(h̄ − 30°) + 0.24 cos 2h̄ + 0.32 cos(3h̄ + 6°) − 0.20 cos(4h̄ − 63°),
/// from cos h̄ and sin h̄ by the multiple-angle and angle-sum identities.
#[inline(always)]
fn hue_weight<R: Real>(c1: R, s1: R) -> R {
    let (s2, c2) = (s1 * c1 * 2.0, c1 * c1 * 2.0 - 1.0);
    let (s3, c3) = (s1 * c2 + c1 * s2, c1 * c2 - s1 * s2);
    let (s4, c4) = (s2 * c2 * 2.0, c2 * c2 * 2.0 - 1.0);
    let (s30, c30) = 30f64.to_radians().sin_cos();
    let (s6, c6) = 6f64.to_radians().sin_cos();
    let (s63, c63) = 63f64.to_radians().sin_cos();
    -(c1 * c30 + s1 * s30) * 0.17 + c2 * 0.24 + (c3 * c6 - s3 * s6) * 0.32
        - (c4 * c63 + s4 * s63) * 0.20
        + 1.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::brdf::V3;

    /// Sharma, Wu & Dalal (2005), Table 1: all 34 pairs.
    const PAIRS: [(V3, V3, f64); 34] = [
        ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
        ([50.0, 3.1571, -77.2803], [50.0, 0.0, -82.7485], 2.8615),
        ([50.0, 2.8361, -74.0200], [50.0, 0.0, -82.7485], 3.4412),
        ([50.0, -1.3802, -84.2814], [50.0, 0.0, -82.7485], 1.0000),
        ([50.0, -1.1848, -84.8006], [50.0, 0.0, -82.7485], 1.0000),
        ([50.0, -0.9009, -85.5211], [50.0, 0.0, -82.7485], 1.0000),
        ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
        ([50.0, -1.0, 2.0], [50.0, 0.0, 0.0], 2.3669),
        ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0009], 7.1792),
        ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0010], 7.1792),
        ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0011], 7.2195),
        ([50.0, 2.4900, -0.0010], [50.0, -2.4900, 0.0012], 7.2195),
        ([50.0, -0.0010, 2.4900], [50.0, 0.0009, -2.4900], 4.8045),
        ([50.0, -0.0010, 2.4900], [50.0, 0.0010, -2.4900], 4.8045),
        ([50.0, -0.0010, 2.4900], [50.0, 0.0011, -2.4900], 4.7461),
        ([50.0, 2.5, 0.0], [50.0, 0.0, -2.5], 4.3065),
        ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
        ([50.0, 2.5, 0.0], [61.0, -5.0, 29.0], 22.8977),
        ([50.0, 2.5, 0.0], [56.0, -27.0, -3.0], 31.9030),
        ([50.0, 2.5, 0.0], [58.0, 24.0, 15.0], 19.4535),
        ([50.0, 2.5, 0.0], [50.0, 3.1736, 0.5854], 1.0000),
        ([50.0, 2.5, 0.0], [50.0, 3.2972, 0.0], 1.0000),
        ([50.0, 2.5, 0.0], [50.0, 1.8634, 0.5757], 1.0000),
        ([50.0, 2.5, 0.0], [50.0, 3.2592, 0.3350], 1.0000),
        (
            [60.2574, -34.0099, 36.2677],
            [60.4626, -34.1751, 39.4387],
            1.2644,
        ),
        (
            [63.0109, -31.0961, -5.8663],
            [62.8187, -29.7946, -4.0864],
            1.2630,
        ),
        (
            [61.2901, 3.7196, -5.3901],
            [61.4292, 2.2480, -4.9620],
            1.8731,
        ),
        (
            [35.0831, -44.1164, 3.7933],
            [35.0232, -40.0716, 1.5901],
            1.8645,
        ),
        (
            [22.7233, 20.0904, -46.6940],
            [23.0331, 14.9730, -42.5619],
            2.0373,
        ),
        (
            [36.4612, 47.8580, 18.3852],
            [36.2715, 50.5065, 21.2231],
            1.4146,
        ),
        (
            [90.8027, -2.0831, 1.4410],
            [91.1528, -1.6435, 0.0447],
            1.4441,
        ),
        (
            [90.9257, -0.5406, -0.9208],
            [88.6381, -0.8985, -0.7239],
            1.5381,
        ),
        (
            [6.7747, -0.2908, -2.4247],
            [5.8714, -0.0985, -2.2286],
            0.6377,
        ),
        (
            [2.0776, 0.0795, -1.1350],
            [0.9033, -0.0636, -0.5514],
            0.9082,
        ),
    ];

    #[test]
    fn ciede2000_never_exceeds_its_bound_from_the_lab_distance() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = |scale: f64| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * scale
        };
        let mut tightest = 0f64;
        let pairs = PAIRS.iter().map(|&(a, b, _)| (a, b));
        let random = (0..200_000).map(|_| {
            let a = [50.0 + next(100.0), next(200.0), next(200.0)];
            // Near pairs (where the bound is used) and far ones.
            let spread = if next(1.0) > 0.0 { 2.0 } else { 100.0 };
            (
                a,
                [
                    a[0] + next(spread),
                    a[1] + next(spread),
                    a[2] + next(spread),
                ],
            )
        });
        for (a, b) in pairs.chain(random) {
            let ratio = ciede2000(a, b) / ciede2000_bound(a, b);
            assert!(ratio <= 1.0, "{a:?} {b:?}: ΔE00 is {ratio} of its bound");
            tightest = tightest.max(ratio);
        }
        // Near-neutral colours scale Δa by 1.5: ΔE00 exceeds ΔE76 there, so the bound must be
        // above 1.
        assert!(tightest > 1.0 / 2.1214, "tightest {tightest}");
    }

    #[test]
    fn ciede2000_reproduces_the_sharma_test_pairs() {
        for (i, (a, b, expected)) in PAIRS.iter().enumerate() {
            let got = ciede2000(*a, *b);
            assert!(
                (got - expected).abs() < 5e-5,
                "pair {}: {got} vs {expected}",
                i + 1
            );
            assert!((ciede2000(*b, *a) - got).abs() < 1e-12, "symmetric");
        }
    }

    /// The hue angle of (a, b) in degrees, 0..360; 0 for a neutral colour.
    fn hue_degrees(b: f64, a: f64) -> f64 {
        if a == 0.0 && b == 0.0 {
            0.0
        } else {
            b.atan2(a).to_degrees().rem_euclid(360.0)
        }
    }

    /// CIEDE2000 in the paper's angle form, step by step: the oracle for the vector form.
    fn ciede2000_angle_form([l1, a1, b1]: V3, [l2, a2, b2]: V3) -> f64 {
        let c_bar = (length(a1, b1) + length(a2, b2)) / 2.0;
        let g = 0.5 * (1.0 - chroma_ratio(c_bar));
        let (a1p, a2p) = ((1.0 + g) * a1, (1.0 + g) * a2);
        let (c1p, c2p) = (length(a1p, b1), length(a2p, b2));
        let (h1p, h2p) = (hue_degrees(b1, a1p), hue_degrees(b2, a2p));
        let dh_angle = if c1p * c2p == 0.0 {
            0.0
        } else if (h2p - h1p).abs() <= 180.0 {
            h2p - h1p
        } else if h2p - h1p > 180.0 {
            h2p - h1p - 360.0
        } else {
            h2p - h1p + 360.0
        };
        let dh = 2.0 * (c1p * c2p).sqrt() * (dh_angle.to_radians() / 2.0).sin();
        let h_bar = if c1p * c2p == 0.0 {
            h1p + h2p
        } else if (h1p - h2p).abs() <= 180.0 {
            (h1p + h2p) / 2.0
        } else if h1p + h2p < 360.0 {
            (h1p + h2p + 360.0) / 2.0
        } else {
            (h1p + h2p - 360.0) / 2.0
        };
        let cos = |degrees: f64| degrees.to_radians().cos();
        let t = 1.0 - 0.17 * cos(h_bar - 30.0)
            + 0.24 * cos(2.0 * h_bar)
            + 0.32 * cos(3.0 * h_bar + 6.0)
            - 0.20 * cos(4.0 * h_bar - 63.0);
        let d_theta = 30.0 * (-((h_bar - 275.0) / 25.0).powi(2)).exp();
        let c_bar_p = (c1p + c2p) / 2.0;
        let l_bar = (l1 + l2) / 2.0;
        let sl = 1.0 + 0.015 * (l_bar - 50.0).powi(2) / (20.0 + (l_bar - 50.0).powi(2)).sqrt();
        let (sc, sh) = (1.0 + 0.045 * c_bar_p, 1.0 + 0.015 * c_bar_p * t);
        let rt = -(2.0 * d_theta).to_radians().sin() * 2.0 * chroma_ratio(c_bar_p);
        let (dl, dc) = (l2 - l1, c2p - c1p);
        ((dl / sl).powi(2) + (dc / sc).powi(2) + (dh / sh).powi(2) + rt * (dc / sc) * (dh / sh))
            .sqrt()
    }

    #[test]
    fn the_vector_form_equals_the_angle_form() {
        // Deterministic pseudo-random pairs: far apart, close together (the comparison's
        // usual case), with exactly opposite hues, and with neutral colours.
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut pairs = Vec::new();
        for _ in 0..100_000 {
            let a: V3 = [
                100.0 * next(),
                200.0 * next() - 100.0,
                200.0 * next() - 100.0,
            ];
            let scale = [50.0, 1.0, 1e-3][pairs.len() % 3];
            let b = a.map(|c| c + scale * (2.0 * next() - 1.0));
            pairs.push((a, b));
            // Opposite hues on an axis, where the cross product is exactly 0 (off the axes
            // near-opposite hues sit on the formula's discontinuity, decided by rounding).
            pairs.push(([a[0], a[1], 0.0], [b[0], -b[1], 0.0]));
            pairs.push(([a[0], 0.0, a[2]], [b[0], 0.0, -b[2]]));
            pairs.push((a, [b[0], 0.0, 0.0]));
        }
        for (a, b) in pairs {
            let (fast, reference) = (ciede2000(a, b), ciede2000_angle_form(a, b));
            assert!(
                (fast - reference).abs() <= 1e-9 * reference.max(1.0),
                "{a:?} {b:?}: {fast} vs {reference}"
            );
        }
    }

    #[test]
    fn the_hue_weight_equals_its_four_cosine_definition() {
        for step in 0..=720 {
            let h = f64::from(step) * 0.5;
            let cos = |degrees: f64| degrees.to_radians().cos();
            let direct =
                1.0 - 0.17 * cos(h - 30.0) + 0.24 * cos(2.0 * h) + 0.32 * cos(3.0 * h + 6.0)
                    - 0.20 * cos(4.0 * h - 63.0);
            let (sin, cos) = h.to_radians().sin_cos();
            assert!((hue_weight(cos, sin) - direct).abs() < 1e-14, "h̄ = {h}");
        }
    }

    #[test]
    fn the_cube_root_is_exact_to_a_few_ulps() {
        // CIELAB's cube root starts at (6/29)³ ≈ 0.0089; highlights reach thousands.
        for step in 0..=200_000 {
            let a = 10f64.powf(-3.0 + f64::from(step) * 8.0 / 200_000.0);
            let r = cube_root(a);
            assert!(
                (r - a.cbrt()).abs() <= 4.0 * f64::EPSILON * r,
                "{a}: {r} vs {}",
                a.cbrt()
            );
        }
    }

    #[test]
    fn white_is_lab_100() {
        let [l, a, b] = lab_from_linear_srgb([1.0, 1.0, 1.0]);
        assert!(
            (l - 100.0).abs() < 1e-3 && a.abs() < 1e-2 && b.abs() < 1e-2,
            "{l} {a} {b}"
        );
    }
}
