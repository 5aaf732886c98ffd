//! Branch-free elementary functions for the comparison's inner loop, accurate to a few ulps.
//!
//! The comparison evaluates CIEDE2000 for tens of millions of colour pairs. The C library's
//! `atan2`, `exp` and `sin` are calls the compiler cannot vectorise, so each would stay one
//! lane at a time while the arithmetic around them runs four or eight lanes wide. These are
//! written in plain arithmetic and selects (range reduction plus a Taylor polynomial, each
//! truncated where its next term is below 1e-17 of the result), so a loop over lanes
//! vectorises whole. Tests hold each to the standard library's result.

use super::lanes::Real;
use std::f64::consts::LOG2_E;

/// Horner evaluation of Σ cᵢ xⁱ.
#[inline(always)]
fn polynomial<R: Real, const N: usize>(coefficients: &[f64; N], x: R) -> R {
    // An indexed loop: the iterator form left a call per polynomial in the vector code.
    let mut sum = R::splat(0.0);
    for i in (0..N).rev() {
        sum = sum * x + coefficients[i];
    }
    sum
}

/// (−1)ⁿ / (2n + 1): atan's Taylor coefficients in r².
const ATAN_SERIES: [f64; 9] = {
    let mut c = [0.0; 9];
    let mut n = 0;
    while n < 9 {
        let sign = if n % 2 == 0 { 1.0 } else { -1.0 };
        c[n] = sign / (2 * n + 1) as f64;
        n += 1;
    }
    c
};

/// tan(jπ/16), j = 0..4: the reduction centres of atan on [0, 1].
const ATAN_CENTRES: [f64; 5] = [
    0.0,
    0.198_912_367_379_658,
    0.414_213_562_373_095_03,
    0.668_178_637_919_298_9,
    1.0,
];

/// tan((2j + 1)π/32): where the nearest centre changes.
const ATAN_THRESHOLDS: [f64; 4] = [
    0.098_491_403_357_164_25,
    0.303_346_683_607_342_4,
    0.534_511_135_950_791_6,
    0.820_678_790_828_660_2,
];

/// The angle of the vector (x, y) in degrees, in [0, 360); 0 for the zero vector. Equals
/// `y.atan2(x).to_degrees().rem_euclid(360.0)`, without the branch for negative angles.
#[inline(always)]
pub(crate) fn atan2_degrees<R: Real>(y: R, x: R) -> R {
    let zero = R::splat(0.0);
    let (ax, ay) = (x.abs(), y.abs());
    let (small, large) = (ax.min(ay), ax.max(ay));
    // atan(t), t = small/large in [0, 1], is jπ/16 + atan(r) with c_j the nearest centre
    // and r = (t − c_j)/(1 + t·c_j) = (small − c_j·large)/(large + c_j·small), |r| ≤
    // tan(π/32): one division where forming t first would take two.
    let (mut centre, mut sixteenths) = (zero, zero);
    for (j, &threshold) in ATAN_THRESHOLDS.iter().enumerate() {
        let above = small.gt(large * threshold);
        centre = R::select(above, R::splat(ATAN_CENTRES[j + 1]), centre);
        sixteenths = R::select(above, R::splat((j + 1) as f64), sixteenths);
    }
    let r = R::select(
        large.eq(zero),
        zero,
        (small - centre * large) / (large + centre * small),
    );
    let within_octant =
        sixteenths * 11.25 + r * polynomial(&ATAN_SERIES, r * r) * DEGREES_PER_RADIAN;
    let first_quadrant = R::select(ay.gt(ax), -within_octant + 90.0, within_octant);
    let upper_half = R::select(x.lt(zero), -first_quadrant + 180.0, first_quadrant);
    R::select(y.lt(zero), -upper_half + 360.0, upper_half)
}

/// What `f64::to_degrees` multiplies by.
const DEGREES_PER_RADIAN: f64 = 180.0 / std::f64::consts::PI;

/// 1 / n!, n = 0..14: exp's Taylor coefficients.
const EXP_SERIES: [f64; 15] = {
    let mut c = [1.0; 15];
    let mut n = 1;
    while n < 15 {
        c[n] = c[n - 1] / n as f64;
        n += 1;
    }
    c
};

/// ln 2 = LN_2_HIGH + LN_2_LOW to twice double precision; LN_2_HIGH has its low 21 bits
/// zero, so k · LN_2_HIGH is exact for every k exp's range reduction meets.
const LN_2_HIGH: f64 = 0.693_147_180_369_123_8;
const LN_2_LOW: f64 = 1.908_214_929_270_587_7e-10;

/// e^x for x in [−700, 700] (clamped there).
#[inline(always)]
pub(crate) fn exp<R: Real>(x: R) -> R {
    // Adding 1.5 · 2⁵² rounds to an integer that lands in the low mantissa bits.
    const SHIFTER: f64 = 6_755_399_441_055_744.0;
    let x = x.max(R::splat(-700.0)).min(R::splat(700.0));
    let shifted = x * LOG2_E + SHIFTER;
    let k = shifted - SHIFTER;
    let r = (x - k * LN_2_HIGH) - k * LN_2_LOW;
    // 2^k, assembled in the exponent field from the integer k.
    let two_to_k =
        shifted.map_bits(|bits| bits.wrapping_sub(SHIFTER.to_bits()).wrapping_add(1023) << 52);
    polynomial(&EXP_SERIES, r) * two_to_k
}

/// (−1)ⁿ / (2n + 1)!: sin's Taylor coefficients in x².
const SIN_SERIES: [f64; 12] = {
    let mut c = [1.0; 12];
    let mut n = 1;
    while n < 12 {
        c[n] = -c[n - 1] / ((2 * n) * (2 * n + 1)) as f64;
        n += 1;
    }
    c
};

/// sin x for |x| ≤ π/2.
#[inline(always)]
pub(crate) fn sin_small<R: Real>(x: R) -> R {
    x * polynomial(&SIN_SERIES, x * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ulps(a: f64, b: f64) -> f64 {
        (a - b).abs() / (b.abs() * f64::EPSILON).max(f64::MIN_POSITIVE)
    }

    #[test]
    fn the_reduction_centres_are_the_tangents_of_sixteenths_of_pi() {
        for (j, c) in ATAN_CENTRES.iter().enumerate() {
            let exact = (j as f64 * std::f64::consts::PI / 16.0).tan();
            assert!((c - exact).abs() <= 2e-16, "{j}: {c} vs {exact}");
        }
    }

    #[test]
    fn atan2_degrees_matches_the_standard_library_all_round_the_circle() {
        let mut worst: f64 = 0.0;
        for step in 0..200_000 {
            let angle = f64::from(step) * 1.8e-3_f64.to_radians() + 1e-7;
            for radius in [1e-9, 0.37, 1.0, 250.0] {
                let (y, x) = (radius * angle.sin(), radius * angle.cos());
                let expected = y.atan2(x).to_degrees().rem_euclid(360.0);
                // Within 4 ulps of 360°, the scale of the result's range.
                let error = (atan2_degrees(y, x) - expected).abs();
                worst = worst.max(error);
            }
        }
        assert!(worst <= 4.0 * 360f64 * f64::EPSILON, "worst {worst}°");
        for (y, x, expected) in [
            (0.0, 0.0, 0.0),
            (0.0, 2.0, 0.0),
            (0.0, -2.0, 180.0),
            (-0.0, -2.0, 180.0),
            (3.0, 0.0, 90.0),
            (-3.0, 0.0, 270.0),
            (1.0, 1.0, 45.0),
            (-1.0, -1.0, 225.0),
        ] {
            assert_eq!(atan2_degrees(y, x), expected, "({y}, {x})");
        }
    }

    #[test]
    fn ln_2_is_split_into_an_exact_high_part_and_its_remainder() {
        assert_eq!(LN_2_HIGH.to_bits() & ((1 << 21) - 1), 0);
        assert_eq!(LN_2_HIGH + LN_2_LOW, std::f64::consts::LN_2);
    }

    #[test]
    fn exp_matches_the_standard_library() {
        for step in 0..=200_000 {
            let x = -150.0 + f64::from(step) * 1e-3;
            let (got, expected) = (exp(x), x.exp());
            assert!(ulps(got, expected) <= 4.0, "e^{x}: {got} vs {expected}");
        }
        assert_eq!(exp(0.0), 1.0);
    }

    #[test]
    fn sin_matches_the_standard_library_up_to_a_quarter_turn() {
        for step in 0..=100_000 {
            let x = f64::from(step) * std::f64::consts::FRAC_PI_2 / 100_000.0;
            let (got, expected) = (sin_small(x), x.sin());
            assert!(ulps(got, expected) <= 2.0, "sin {x}: {got} vs {expected}");
        }
    }
}
