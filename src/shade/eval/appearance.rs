//! What a viewer sees of a material at one surface point, for one view/light pair or several
//! at once: the light it reflects (a directional light and a uniform ambient light), what it
//! emits, and what shows through it from a background behind, all weighed by its coverage.
//!
//! The scene, stated once for `compare`, the upgrade's proof and the factor fit:
//! - one directional light of irradiance π at normal incidence, so that a white Lambertian
//!   surface lit head-on has radiance 1;
//! - a uniform ambient light of radiance [`AMBIENT`], which `occlusionTexture` darkens
//!   (glTF 2.0: "areas of indirect lighting"), reflected by the split-sum approximation of
//!   the specular lobe with Karis's analytic fit of its scale and bias ("Physically Based
//!   Shading on Mobile", 2014) and by the diffuse albedo, each weighed by the same Fresnel
//!   balance as the BRDF (so two materials whose BRDFs agree at every angle agree here too);
//!   the sheen layer is lit by the directional light only;
//! - behind the surface a uniform background of radiance B; the surface shows
//!   `own + B · through`, where `through` is what its coverage lets pass (1 − coverage) and
//!   what its transmitting layers carry: `mix(diffuse_bsdf, specular_btdf · baseColor,
//!   transmission)` of KHR_materials_transmission with `diffuse_btdf(diffuseTransmissionColor)`
//!   of KHR_materials_diffuse_transmission, against a uniform background the microfacet BTDF
//!   integrates to 1 − F (roughness blurs nothing there), times the volume's transmittance
//!   (KHR_materials_volume: "T(x) = c^(x/d)"). Comparisons look over [`BACKGROUNDS`], so
//!   that coverage and colour cannot cancel;
//! - KHR_materials_clearcoat layered as its README gives: `mix(material, clearcoat_brdf,
//!   clearcoat · fresnel(0.04, N_c · V))` with its own normal, the emission under it ("the
//!   emission is darkened by the Fresnel term").
//!
//! Directions are in the geometric tangent frame (normal +z, tangent +x); a normal map turns
//! the base's frame and a clearcoat normal map the coat's.

use super::brdf::{f0_from_ior, fresnel, ggx_d, max3, smith_vis, Geometry, V3};
use super::iridescence::fresnel_lanes;
use super::lanes::{channels, Real};
use super::material::{DiffuseBalance, Inputs, Shader};
use std::f64::consts::PI;

/// The ambient light's radiance, a quarter of what the directional light gives a white
/// Lambertian surface head-on.
pub(crate) const AMBIENT: f64 = 0.25;

/// The backgrounds a comparison looks at a translucent surface over: black and a white
/// of radiance 1 (what a white Lambertian surface lit head-on shows).
pub(crate) const BACKGROUNDS: [f64; 2] = [0.0, 1.0];

/// What a viewer sees at a point over a background of radiance B: `own + B · through`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Seen<R> {
    /// Radiance the surface itself sends: reflected and emitted light, times its coverage.
    pub own: [R; 3],
    /// The share of the background's radiance that reaches the viewer, per channel.
    pub through: [R; 3],
}

impl<R: Real> Seen<R> {
    /// The radiance shown over a background of radiance `background`.
    #[inline(always)]
    pub(crate) fn over(&self, background: f64) -> [R; 3] {
        channels(|c| self.through[c] * background + self.own[c])
    }
}

/// The least N·V a shading normal gives: Filament's `MIN_N_DOT_V` (its `clampNoV`); the
/// Sample Viewer clamps to 0, which the visibility terms' own floors make the same.
pub(crate) const MIN_N_DOT_V: f64 = 1e-4;

/// `g` seen in the frame whose normal is `normal` (a unit vector in the tangent frame),
/// its tangent the geometric tangent made orthogonal to it. Both directions must lie above
/// the geometric surface, and the light above the shading normal's horizon. A view below
/// that horizon (a normal map tilting the surface away from a grazing viewer) is still
/// seen, with N·V clamped to [`MIN_N_DOT_V`], as viewers shade it: a BRDF switched off
/// there would make shading jump as a texel crosses the horizon, which no viewer shows.
#[inline(always)]
pub(crate) fn in_frame<R: Real>(g: &Geometry<R>, normal: V3) -> Geometry<R> {
    if normal == [0.0, 0.0, 1.0] {
        return *g;
    }
    let n = normal;
    // The tangent (1, 0, 0) without its component along n; a normal along the tangent
    // takes the bitangent instead.
    let t = {
        let t = [1.0 - n[0] * n[0], -n[0] * n[1], -n[0] * n[2]];
        let length = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
        if length > 1e-9 {
            t.map(|c| c / length)
        } else {
            [0.0, 1.0, 0.0]
        }
    };
    let b = [
        n[1] * t[2] - n[2] * t[1],
        n[2] * t[0] - n[0] * t[2],
        n[0] * t[1] - n[1] * t[0],
    ];
    let rotate = |w: [R; 3]| {
        let along = |axis: V3| w[0] * axis[0] + w[1] * axis[1] + w[2] * axis[2];
        [along(t), along(b), along(n)]
    };
    let (mut v, l) = (rotate(g.v), rotate(g.l));
    v[2] = v[2].max(R::splat(MIN_N_DOT_V));
    Geometry {
        v,
        l,
        // V·H is the same in every frame: the Fresnel weight is kept.
        h: rotate(g.h),
        above: g.above & l[2].gt(R::splat(0.0)),
        fresnel_weight: g.fresnel_weight,
    }
}

/// Schlick's (1 − cos θ)⁵ for a cosine in 0..1.
#[inline(always)]
fn schlick_weight_of<R: Real>(cosine: R) -> R {
    let x = -cosine.max(R::splat(0.0)).min(R::splat(1.0)) + 1.0;
    let x2 = x * x;
    x2 * x2 * x
}

/// The scale and bias of F0 in the specular lobe's hemispherical albedo under a uniform
/// light (the split sum's second factor), by Karis's analytic fit: (A, B) with albedo
/// F0 · A + F90 · B.
#[inline(always)]
fn environment_scale_bias<R: Real>(roughness: f64, n_dot_v: R) -> (R, R) {
    let r = [
        1.0 - roughness,
        0.0425 - 0.0275 * roughness,
        1.04 - 0.572 * roughness,
        0.022 * roughness - 0.04,
    ];
    // 2^(−9.28 · N·V) by the branch-free e^x, which vectorises; exp2 is a library call per
    // lane.
    let falloff = super::elementary::exp(n_dot_v * (-9.28 * std::f64::consts::LN_2));
    let a004 = falloff.min(R::splat(r[0] * r[0])) * r[0] + r[1];
    (a004 * -1.04 + r[2], a004 * 1.04 + r[3])
}

/// The dielectric's Fresnel term at the view's incidence (the ambient light's and the
/// transmitted light's), per channel, with the thin film's where there is one.
#[inline(always)]
fn view_fresnel<R: Real>(m: &Inputs, n_dot_v: R) -> [R; 3] {
    let f0_ior = f0_from_ior(m.ior);
    let f0: V3 = channels(|c| (f0_ior * m.specular_color[c]).min(1.0) * m.specular);
    let weight = schlick_weight_of(n_dot_v);
    let plain = channels(|c| fresnel(f0[c], m.specular, weight));
    if m.iridescence == 0.0 {
        return plain;
    }
    let film = fresnel_lanes(m.iridescence_film, f0, n_dot_v);
    channels(|c| plain[c] * (1.0 - m.iridescence) + film[c] * m.iridescence)
}

/// The base's reflection of the uniform ambient light of radiance 1.
#[inline(always)]
fn ambient_reflection<R: Real>(m: &Inputs, n_dot_v: R, fresnel_v: &[R; 3]) -> [R; 3] {
    let (scale, bias) = environment_scale_bias(m.roughness, n_dot_v);
    let f0_ior = f0_from_ior(m.ior);
    let max_f = max3(*fresnel_v);
    let kept = m.diffuse_reflected();
    let reflected: [R; 3] = channels(|c| {
        let f0 = (f0_ior * m.specular_color[c]).min(1.0) * m.specular;
        let diffuse_weight = match m.diffuse_balance {
            DiffuseBalance::MaxFresnel => -max_f + 1.0,
            DiffuseBalance::PerChannelFresnel => -fresnel_v[c] + 1.0,
            DiffuseBalance::Unbalanced => R::splat(1.0),
        };
        let dielectric = scale * f0 + bias * m.specular + diffuse_weight * (m.base_color[c] * kept);
        let metal = scale * m.base_color[c] + bias;
        dielectric * (1.0 - m.metallic) + metal * m.metallic
    });
    if m.iridescence == 0.0 || m.metallic == 0.0 {
        return reflected;
    }
    // A metal's film reflects F_film · (A + B) of the split sum, mixed by its strength.
    let film = fresnel_lanes(m.iridescence_film, m.base_color, n_dot_v);
    let metal_film: [R; 3] =
        channels(|c| (film[c] * (scale + bias) - (scale * m.base_color[c] + bias)) * m.iridescence);
    channels(|c| reflected[c] + metal_film[c] * m.metallic)
}

/// What the base passes from a uniform background behind it, per channel.
#[inline(always)]
fn transmitted<R: Real>(m: &Inputs, fresnel_v: &[R; 3]) -> [R; 3] {
    let entering = -max3(*fresnel_v) + 1.0;
    let dielectric = 1.0 - m.metallic;
    channels(|c| {
        let specular = m.transmission * m.base_color[c] * m.volume_transmittance[c];
        let diffuse =
            (1.0 - m.transmission) * m.diffuse_transmission * m.diffuse_transmission_color[c];
        entering * ((specular + diffuse) * dielectric)
    })
}

/// Whether the material passes anything from behind it (besides what its coverage leaves).
pub(crate) fn transmits(m: &Inputs) -> bool {
    !m.unlit && m.metallic < 1.0 && (m.transmission > 0.0 || m.diffuse_transmission > 0.0)
}

/// What a viewer sees of material `m` for the view/light pairs of `g` (tangent frame).
#[inline(always)]
pub(crate) fn seen<R: Real>(shader: &Shader, m: &Inputs, g: &Geometry<R>) -> Seen<R> {
    let coverage = m.coverage;
    let zero = R::splat(0.0);
    if m.unlit {
        // KHR_materials_unlit: "the base color is the final color", lit by nothing.
        return Seen {
            own: channels(|c| R::splat(m.base_color[c] * coverage)),
            through: [R::splat(1.0 - coverage); 3],
        };
    }
    let base = in_frame(g, m.normal);
    let f = shader.brdf(m, &base);
    let n_dot_l = base.l[2].max(zero);
    let n_dot_v = base.v[2].max(zero).min(R::splat(1.0));
    let fresnel_v = view_fresnel(m, n_dot_v);
    let ambient = ambient_reflection(m, n_dot_v, &fresnel_v);
    let lit = AMBIENT * m.occlusion;
    let mut own: [R; 3] = channels(|c| f[c] * n_dot_l * PI + ambient[c] * lit + m.emission[c]);
    let mut through = if transmits(m) {
        transmitted(m, &fresnel_v)
    } else {
        [zero; 3]
    };
    if m.clearcoat > 0.0 {
        let coat = in_frame(g, m.clearcoat_normal);
        let alpha = m.clearcoat_roughness * m.clearcoat_roughness;
        let lobe = ggx_d(alpha, coat.h[2]) * smith_vis(alpha, coat.l[2], coat.v[2]);
        let lobe = R::select(coat.above, lobe, zero);
        let coat_v = coat.v[2].max(zero).min(R::splat(1.0));
        let weight = fresnel(0.04, 1.0, schlick_weight_of(coat_v)) * m.clearcoat;
        let (scale, bias) = environment_scale_bias(m.clearcoat_roughness, coat_v);
        let layer = lobe * coat.l[2].max(zero) * PI + (scale * 0.04 + bias) * lit;
        let kept = -weight + 1.0;
        own = channels(|c| own[c] * kept + layer * weight);
        through = channels(|c| through[c] * kept);
    }
    let weight = if m.premultiplied { 1.0 } else { coverage };
    Seen {
        own: channels(|c| own[c] * weight),
        through: channels(|c| through[c] * coverage + (1.0 - coverage)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::brdf::SheenVisibility;
    use crate::shade::eval::quadrature::hemisphere;
    use crate::shade::sheen_table::SheenTable;

    fn shader() -> Shader {
        Shader::new(SheenTable::compute(2, SheenVisibility::Charlie))
    }

    fn view(theta: f64) -> V3 {
        [theta.sin(), 0.0, theta.cos()]
    }

    /// The analytic fit is the albedo of the specular lobe it stands for, within a few
    /// hundredths: ∫ f_spec(v, l) (n·l) dl with F0 = 0.04, against F0 · A + B.
    #[test]
    fn the_ambient_specular_fit_is_the_lobes_albedo() {
        let material = |roughness| Inputs {
            base_color: [0.0; 3],
            metallic: 0.0,
            roughness,
            ..Inputs::default()
        };
        let s = shader();
        for roughness in [0.3, 0.6, 1.0] {
            for theta in [0.0f64, 0.7, 1.2] {
                let m = material(roughness);
                let v = view(theta);
                let albedo = hemisphere(512, 256, |l| s.brdf(&m, &Geometry::new(v, l))[0] * l[2]);
                let (a, b) = environment_scale_bias(roughness, theta.cos());
                let fit = 0.04 * a + b;
                assert!(
                    (albedo - fit).abs() < 0.03,
                    "roughness {roughness}, θ {theta}: albedo {albedo}, fit {fit}"
                );
            }
        }
    }

    #[test]
    fn an_opaque_surface_hides_the_background_and_a_transparent_one_shows_it() {
        let s = shader();
        let g = Geometry::new(view(0.5), view(-0.3));
        let opaque = seen(&s, &Inputs::default(), &g);
        assert_eq!(opaque.through, [0.0; 3]);
        let clear = Inputs {
            coverage: 0.0,
            ..Inputs::default()
        };
        let shown = seen(&s, &clear, &g);
        assert_eq!((shown.own, shown.through), ([0.0; 3], [1.0; 3]));
    }

    #[test]
    fn a_transmissive_dielectric_passes_its_base_colour_less_the_fresnel_term() {
        let m = Inputs {
            base_color: [0.9, 0.5, 0.2],
            metallic: 0.0,
            transmission: 1.0,
            ..Inputs::default()
        };
        let shown = seen(&shader(), &m, &Geometry::new(view(0.0), view(0.4)));
        for c in 0..3 {
            let expected = m.base_color[c] * (1.0 - 0.04);
            assert!((shown.through[c] - expected).abs() < 1e-12, "{shown:?}");
        }
    }

    #[test]
    fn a_normal_map_turns_the_frame_the_light_is_seen_in() {
        let g = Geometry::new(view(0.0), view(0.6));
        let flat = in_frame(&g, [0.0, 0.0, 1.0]);
        assert_eq!(flat.l, g.l);
        // Tilted towards the light: the light is closer to the normal.
        let tilt = 0.3f64;
        let towards = in_frame(&g, [tilt.sin(), 0.0, tilt.cos()]);
        assert!((towards.l[2] - (0.6f64 - tilt).cos()).abs() < 1e-12);
        assert!((towards.v[2] - tilt.cos()).abs() < 1e-12);
    }

    /// A normal map tilting the surface away from a grazing viewer: as the tilt carries the
    /// view across the shading normal's horizon, what is seen changes smoothly, as in viewers
    /// (which clamp N·V), instead of the direct light going out.
    #[test]
    fn shading_is_continuous_as_a_normal_tilts_the_view_below_its_horizon() {
        let s = shader();
        let grazing = 88f64.to_radians();
        let g = Geometry::new(view(grazing), view(-grazing));
        let seen_with = |n_dot_v: f64| {
            // Tilted about the bitangent, away from the viewer, until N·V is `n_dot_v`.
            let tilt = n_dot_v.acos() - grazing;
            let m = Inputs {
                normal: [-tilt.sin(), 0.0, tilt.cos()],
                roughness: 0.5,
                metallic: 0.0,
                ..Inputs::default()
            };
            assert!((in_frame(&g, m.normal).v[2].max(0.0) - n_dot_v.max(0.0)).abs() < 2e-4);
            seen(&s, &m, &g).own[0]
        };
        let (above, below) = (seen_with(1e-3), seen_with(-1e-3));
        assert!(above > 1.0, "a lit grazing highlight: {above}");
        assert!(
            (above - below).abs() < 0.02 * above,
            "{above} above the horizon, {below} below"
        );
    }
}
