//! The BRDF lobes, each written from its specification text (see shading-anchors.md §1):
//! glTF 2.0 Appendix B, KHR_materials_specular / _ior / _sheen / _anisotropy. Directions are
//! in the local shading frame: normal (0, 0, 1), tangent (1, 0, 0), bitangent (0, 1, 0).
//! Every function returns a finite value for any unit input, including α = 0 and grazing
//! angles (the smallest α evaluated is [`MIN_ALPHA`]).
//!
//! The lobes are generic over `Real`: material parameters are plain `f64`, the directions
//! are one pair (`f64`) or several evaluated together (`Lanes`), and the results agree bit
//! for bit. Conditions on the directions are selects, not branches.

use super::lanes::{Lanes, Mask, Real};
use std::f64::consts::PI;

/// A 3-vector (directions, RGB).
pub(crate) type V3 = [f64; 3];

/// Appendix B forbids evaluating GGX at α = 0 (a Dirac lobe); below this α is clamped.
pub(crate) const MIN_ALPHA: f64 = 1e-4;

/// The dot product.
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The cross product.
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a` scaled to unit length.
pub(crate) fn normalize(a: V3) -> V3 {
    let length = dot(a, a).sqrt();
    if length == 0.0 {
        [0.0, 0.0, 1.0]
    } else {
        a.map(|c| c / length)
    }
}

/// The half vector of `v` and `l`.
pub(crate) fn half(v: V3, l: V3) -> V3 {
    normalize([v[0] + l[0], v[1] + l[1], v[2] + l[2]])
}

/// The largest of three values.
pub(crate) fn max3<R: Real>([a, b, c]: [R; 3]) -> R {
    a.max(b).max(c)
}

/// A view/light pair and what every lobe derives from it, computed once per pair.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Geometry<R: Real> {
    /// Direction to the viewer.
    pub v: [R; 3],
    /// Direction to the light.
    pub l: [R; 3],
    /// The half vector.
    pub h: [R; 3],
    /// Both directions are above the surface; the BRDF is 0 otherwise.
    pub above: R::Mask,
    /// Schlick's (1 − |VdotH|)⁵.
    pub fresnel_weight: R,
}

impl Geometry<f64> {
    /// The geometry of one view/light pair (unit vectors in the shading frame).
    pub(crate) fn new(v: V3, l: V3) -> Geometry<f64> {
        let h = half(v, l);
        Geometry {
            v,
            l,
            h,
            above: v[2] > 0.0 && l[2] > 0.0,
            fresnel_weight: schlick_weight(dot(v, h)),
        }
    }
}

impl<const N: usize> Geometry<Lanes<N>> {
    /// N pairs, one per lane.
    pub(crate) fn lanes(pairs: &[Geometry<f64>; N]) -> Geometry<Lanes<N>> {
        let lanes = |f: &dyn Fn(&Geometry<f64>) -> f64| Lanes(pairs.each_ref().map(f));
        let vector = |f: &dyn Fn(&Geometry<f64>) -> V3| [0, 1, 2].map(|i| lanes(&|g| f(g)[i]));
        Geometry {
            v: vector(&|g| g.v),
            l: vector(&|g| g.l),
            h: vector(&|g| g.h),
            above: Mask::from_bools(pairs.each_ref().map(|g| g.above)),
            fresnel_weight: lanes(&|g| g.fresnel_weight),
        }
    }
}

/// Schlick's (1 − |VdotH|)⁵, clamped to 0..1.
pub(crate) fn schlick_weight(v_dot_h: f64) -> f64 {
    (1.0 - v_dot_h.abs()).clamp(0.0, 1.0).powi(5)
}

/// Schlick's Fresnel from its weight: F = f0 + (f90 − f0)·weight.
#[inline(always)]
pub(crate) fn fresnel<R: Real>(f0: f64, f90: f64, weight: R) -> R {
    weight * (f90 - f0) + f0
}

/// Schlick's Fresnel, F = f0 + (f90 − f0)(1 − |VdotH|)⁵.
#[cfg(test)]
pub(crate) fn schlick(f0: f64, f90: f64, v_dot_h: f64) -> f64 {
    fresnel(f0, f90, schlick_weight(v_dot_h))
}

/// f0 of a dielectric with index of refraction `ior` against air; ior 0 means infinite
/// (KHR_materials_ior's compatibility mode), giving 1.
pub(crate) fn f0_from_ior(ior: f64) -> f64 {
    if ior == 0.0 {
        1.0
    } else {
        ((ior - 1.0) / (ior + 1.0)).powi(2)
    }
}

/// Isotropic GGX (Trowbridge-Reitz) distribution, α = roughness².
#[inline(always)]
pub(crate) fn ggx_d<R: Real>(alpha: f64, n_dot_h: R) -> R {
    let a2 = alpha.max(MIN_ALPHA).powi(2);
    let f = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    let d = R::splat(a2) / (f * f * PI);
    R::select(n_dot_h.gt(R::splat(0.0)), d, R::splat(0.0))
}

/// Height-correlated Smith visibility V = G2 / (4 |NdotL| |NdotV|), Appendix B.
#[inline(always)]
pub(crate) fn smith_vis<R: Real>(alpha: f64, n_dot_l: R, n_dot_v: R) -> R {
    let a2 = alpha.max(MIN_ALPHA).powi(2);
    let (l, v) = (n_dot_l.abs(), n_dot_v.abs());
    let ggx_v = l * (v * v * (1.0 - a2) + a2).sqrt();
    let ggx_l = v * (l * l * (1.0 - a2) + a2).sqrt();
    let denominator = ggx_v + ggx_l;
    let zero = R::splat(0.0);
    R::select(denominator.gt(zero), R::splat(0.5) / denominator, zero)
}

/// Smith Λ for the isotropic GGX lobe, for the Λ-form cross-check and the furnace tests.
#[cfg(test)]
pub(crate) fn smith_lambda(alpha: f64, n_dot_w: f64) -> f64 {
    let c2 = n_dot_w * n_dot_w;
    let tan2 = (1.0 - c2).max(0.0) / c2.max(1e-300);
    (-1.0 + (1.0 + alpha.max(MIN_ALPHA).powi(2) * tan2).sqrt()) / 2.0
}

/// KHR_materials_anisotropy roughnesses: α_t = mix(α, 1, strength²), α_b = α.
pub(crate) fn anisotropic_alphas(alpha: f64, strength: f64) -> (f64, f64) {
    let s2 = strength.clamp(0.0, 1.0).powi(2);
    let alpha = alpha.max(MIN_ALPHA);
    (alpha + (1.0 - alpha) * s2, alpha)
}

/// `w` in the anisotropy frame: t along the direction at `angle` in the tangent plane, b
/// perpendicular to it, the normal unchanged (an angle of −a turns it back).
#[inline(always)]
pub(crate) fn into_anisotropy_frame<R: Real>(w: [R; 3], angle: f64) -> [R; 3] {
    let (s, c) = angle.sin_cos();
    [w[0] * c + w[1] * s, w[1] * c - w[0] * s, w[2]]
}

/// Anisotropic GGX with (t, b) the anisotropy direction and its perpendicular in the
/// tangent plane (an orthonormal frame with the normal).
pub(crate) fn ggx_aniso_d<R: Real>(alpha_t: f64, alpha_b: f64, h: [R; 3]) -> R {
    let (at, ab) = (alpha_t.max(MIN_ALPHA), alpha_b.max(MIN_ALPHA));
    let (x, y) = (h[0] / at, h[1] / ab);
    let f = x * x + y * y + h[2] * h[2];
    let d = R::splat(1.0) / (f * f * (PI * at * ab));
    R::select(h[2].gt(R::splat(0.0)), d, R::splat(0.0))
}

/// Anisotropic height-correlated visibility (KHR_materials_anisotropy).
pub(crate) fn smith_vis_aniso<R: Real>(alpha_t: f64, alpha_b: f64, v: [R; 3], l: [R; 3]) -> R {
    let (at, ab) = (alpha_t.max(MIN_ALPHA), alpha_b.max(MIN_ALPHA));
    let length = |w: [R; 3]| {
        let (x, y) = (w[0] * at, w[1] * ab);
        (x * x + y * y + w[2] * w[2]).sqrt()
    };
    let denominator = l[2].abs() * length(v) + v[2].abs() * length(l);
    let zero = R::splat(0.0);
    R::select(denominator.gt(zero), R::splat(0.5) / denominator, zero)
}

/// Which sheen visibility term is used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SheenVisibility {
    /// Conty & Kulla 2017, with the Λ fit quoted by KHR_materials_sheen.
    Charlie,
    /// Ashikhmin / Neubelt: 1 / (4 (NdotL + NdotV − NdotL·NdotV)).
    Ashikhmin,
    /// Charlie with Conty & Kulla's terminator softening on the light side,
    /// Λ'(θ_l) = Λ(θ_l)^(1 + 2(1 − cos θ_l)⁸): their one deliberately non-physical (and
    /// non-reciprocal) adjustment, for a softer light terminator.
    CharlieSoftened,
}

/// The Charlie sheen distribution with r = sheenRoughness².
pub(crate) fn charlie_d<R: Real>(sheen_roughness: f64, n_dot_h: R) -> R {
    let r = (sheen_roughness * sheen_roughness).max(1e-7);
    let sin2 = (-(n_dot_h * n_dot_h) + 1.0).max(R::splat(0.0));
    sin2.map(|s| s.powf(0.5 / r)) * ((2.0 + 1.0 / r) / (2.0 * PI))
}

/// Conty-Kulla's fit of the Charlie Λ.
pub(crate) fn charlie_lambda(sheen_roughness: f64, cos_theta: f64) -> f64 {
    const P0: [f64; 5] = [25.3245, 3.32435, 0.16801, -1.27393, -4.85967];
    const P1: [f64; 5] = [21.5473, 3.82987, 0.19823, -1.97760, -4.32054];
    let r = sheen_roughness * sheen_roughness;
    let t = (1.0 - r).powi(2);
    let p: [f64; 5] = std::array::from_fn(|i| P1[i] * (1.0 - t) + P0[i] * t);
    let l = |x: f64| p[0] / (1.0 + p[1] * x.powf(p[2])) + p[3] * x + p[4];
    let c = cos_theta.abs();
    if c < 0.5 {
        l(c).exp()
    } else {
        (2.0 * l(0.5) - l(1.0 - c)).exp()
    }
}

/// Sheen visibility for the chosen term.
pub(crate) fn sheen_vis<R: Real>(
    visibility: SheenVisibility,
    sheen_roughness: f64,
    n_dot_l: R,
    n_dot_v: R,
) -> R {
    let floor = R::splat(1e-9);
    let (l, v) = (n_dot_l.abs().max(floor), n_dot_v.abs().max(floor));
    let lambda = |c: R| c.map(|c| charlie_lambda(sheen_roughness, c));
    let charlie =
        |light_lambda: R| R::splat(1.0) / ((lambda(v) + light_lambda + 1.0) * 4.0 * l * v);
    match visibility {
        SheenVisibility::Charlie => charlie(lambda(l)),
        SheenVisibility::CharlieSoftened => charlie(
            l.map(|l| charlie_lambda(sheen_roughness, l).powf(1.0 + 2.0 * (1.0 - l).powi(8))),
        ),
        SheenVisibility::Ashikhmin => R::splat(1.0) / ((l + v - l * v) * 4.0),
    }
}

/// The sheen lobe for a unit sheen colour: D_s · V_s (0 below the horizon).
pub(crate) fn sheen_lobe<R: Real>(
    visibility: SheenVisibility,
    sheen_roughness: f64,
    g: &Geometry<R>,
) -> R {
    let lobe =
        charlie_d(sheen_roughness, g.h[2]) * sheen_vis(visibility, sheen_roughness, g.l[2], g.v[2]);
    R::select(g.above, lobe, R::splat(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tolerance: f64) -> bool {
        (a - b).abs() <= tolerance * b.abs().max(1.0)
    }

    #[test]
    fn spot_values_match_the_anchors() {
        assert!(close(ggx_d(0.25, 1.0), 5.092958, 1e-6));
        assert!(close(ggx_d(0.25, 0.9), 0.343596, 1e-6));
        assert!(close(smith_vis(0.25, 0.8, 0.5), 0.593218, 1e-6));
        for alpha in [0.01, 0.3, 1.0] {
            assert!(close(smith_vis(alpha, 1.0, 1.0), 0.25, 1e-12));
        }
        let h = [0.3, 0.2, 0.87f64.sqrt()];
        assert!(close(ggx_aniso_d(0.5, 0.1, h), 0.232743, 1e-6));
        assert!(close(charlie_d(0.5, 0.5), 0.537148, 1e-6));
        assert!(close(charlie_d(0.5, 0.0), 0.954930, 1e-6));
        for (c, lambda) in [
            (0.1, 10.117),
            (0.3, 2.85613),
            (0.5, 1.37883),
            (0.8, 0.404351),
        ] {
            assert!(close(charlie_lambda(0.5, c), lambda, 1e-4), "Λ({c})");
        }
        assert!(close(
            sheen_vis(SheenVisibility::Charlie, 0.5, 0.8, 0.5),
            0.224564,
            1e-5
        ));
        assert!(close(
            sheen_vis(SheenVisibility::Ashikhmin, 0.5, 0.8, 0.5),
            0.277778,
            1e-6
        ));
        for (ior, f0) in [
            (1.5, 0.04),
            (1.33, 0.020059),
            (1000.0, 0.996008),
            (0.0, 1.0),
        ] {
            assert!(close(f0_from_ior(ior), f0, 1e-5), "ior {ior}");
        }
    }

    #[test]
    fn the_visibility_term_equals_the_lambda_form() {
        for alpha in [0.05, 0.3, 0.9] {
            for (l, v) in [(0.8, 0.5), (0.2, 0.9), (0.05, 0.6)] {
                let g2 = 1.0 / (1.0 + smith_lambda(alpha, l) + smith_lambda(alpha, v));
                assert!(close(smith_vis(alpha, l, v), g2 / (4.0 * l * v), 1e-12));
            }
        }
    }

    #[test]
    fn terminator_softening_changes_only_the_light_side_away_from_the_normal() {
        let (charlie, soft) = (SheenVisibility::Charlie, SheenVisibility::CharlieSoftened);
        // cos θ_l = 1: the exponent is 1, nothing changes.
        assert_eq!(
            sheen_vis(charlie, 0.6, 1.0, 0.4),
            sheen_vis(soft, 0.6, 1.0, 0.4)
        );
        // Near the terminator the light-side Λ is raised to a power above 1.
        let (a, b) = (
            sheen_vis(charlie, 0.6, 0.05, 0.9),
            sheen_vis(soft, 0.6, 0.05, 0.9),
        );
        assert!(a.is_finite() && b.is_finite() && a != b, "{a} {b}");
        // Hence not reciprocal, as the paper says.
        assert_ne!(
            sheen_vis(soft, 0.6, 0.05, 0.9),
            sheen_vis(soft, 0.6, 0.9, 0.05)
        );
    }

    #[test]
    fn zero_roughness_and_grazing_angles_stay_finite() {
        let grazing = [1.0, 0.0, 0.0];
        for value in [
            ggx_d(0.0, 1.0),
            smith_vis(0.0, 0.0, 0.0),
            ggx_aniso_d(0.0, 0.0, [0.0, 0.0, 1.0]),
            smith_vis_aniso(0.0, 0.0, grazing, grazing),
            charlie_d(0.0, 1.0),
            charlie_d(0.0, 0.0),
            sheen_vis(SheenVisibility::Charlie, 0.0, 0.0, 0.0),
            sheen_lobe(
                SheenVisibility::Charlie,
                0.0,
                &Geometry::new([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]),
            ),
            schlick(0.04, 1.0, 0.0),
        ] {
            assert!(value.is_finite(), "{value}");
        }
    }
}
