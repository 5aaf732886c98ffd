//! A material's BRDF at one point: glTF 2.0 metal-roughness with KHR_materials_specular,
//! _ior, _sheen and _anisotropy; KHR_materials_pbrSpecularGlossiness; KHR_materials_unlit.
//!
//! Readings chosen where the texts leave room (each is a documented decision):
//! - the dielectric is `F_d · specular + (1 − max3(F_d)) · diffuse` (KHR_materials_specular),
//!   which equals Appendix B's `fresnel_mix` whenever F is grey;
//! - sheen is layered with the reciprocal albedo scaling
//!   `max(0, min(1 − c·E(NdotV), 1 − c·E(NdotL)))`, c = max3(sheenColor), E from the table of
//!   the same lobe. E exceeds 1 at low sheen roughness and grazing angles (Charlie 2.5 at
//!   sheenRoughness 0.02, μ 0.02), where the unclamped scaling goes negative; Appendix B says
//!   the BRDF MUST be positive, so the base is switched off there instead;
//! - spec-gloss is evaluated by its own texts, never by its conversion's model (see
//!   [`SpecGlossReading`]): the archived 2.0 extension weighs the diffuse by `1 − F` per
//!   channel, where KHR_materials_specular weighs it by `1 − max3(F)`; the 1.0 drafts are
//!   ambiguous, and each of their readings is evaluated;
//! - the glTF 1.0 metal-rough drafts are evaluated as core metal-rough.

use super::brdf::{
    anisotropic_alphas, f0_from_ior, fresnel, ggx_aniso_d, ggx_d, into_anisotropy_frame, max3,
    sheen_lobe, smith_vis, smith_vis_aniso, Geometry, SheenVisibility, V3,
};
use super::iridescence::{fresnel_lanes, Film};
use super::lanes::{channels, Real};
use super::sheen_table::SheenTable;
use std::f64::consts::PI;

/// Every input of the BRDF at one surface point, linear values.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Inputs {
    /// Base colour, linear RGB.
    pub base_color: V3,
    /// Metalness, 0–1.
    pub metallic: f64,
    /// Perceptual roughness, 0–1.
    pub roughness: f64,
    /// Index of refraction (KHR_materials_ior).
    pub ior: f64,
    /// Specular strength (KHR_materials_specular).
    pub specular: f64,
    /// Specular colour, linear RGB.
    pub specular_color: V3,
    /// Sheen colour, linear RGB.
    pub sheen_color: V3,
    /// Sheen roughness, 0–1.
    pub sheen_roughness: f64,
    /// Anisotropy strength, 0–1.
    pub anisotropy_strength: f64,
    /// Anisotropy direction angle in the tangent plane (texture direction + rotation).
    pub anisotropy_angle: f64,
    /// KHR_materials_unlit: the base colour is emitted as is.
    pub unlit: bool,
    /// How the dielectric's diffuse is weighed against its Fresnel term.
    pub diffuse_balance: DiffuseBalance,
    /// Emitted radiance, linear RGB: emissiveFactor × emissiveTexture ×
    /// KHR_materials_emissive_strength.
    pub emission: V3,
    /// The fraction of the background the surface hides, 0–1: 1 for OPAQUE, the base colour's
    /// alpha for BLEND, 0 or 1 by `alphaCutoff` for MASK.
    pub coverage: f64,
    /// Whether the surface's colour is added whole where it covers part of the background,
    /// as glTF 1.0 blends it (blend functions ONE, ONE_MINUS_SRC_ALPHA: "properly blended RGB
    /// and alpha values", KHR_materials_common's implementation note), rather than weighed
    /// by the coverage as glTF 2.0's BLEND does.
    pub premultiplied: bool,
    /// The ambient light kept, 0–1: 1 + strength · (occlusion − 1).
    pub occlusion: f64,
    /// The shading normal in the tangent frame (normalTexture with its scale), unit length.
    pub normal: V3,
    /// KHR_materials_clearcoat: the layer's weight, perceptual roughness and normal.
    pub clearcoat: f64,
    /// The clearcoat layer's perceptual roughness.
    pub clearcoat_roughness: f64,
    /// The clearcoat layer's normal in the tangent frame, unit length.
    pub clearcoat_normal: V3,
    /// KHR_materials_transmission: the fraction of the dielectric base that is specular
    /// transmission.
    pub transmission: f64,
    /// KHR_materials_volume: what light keeps crossing the volume beneath the surface,
    /// attenuationColor^(thickness / attenuationDistance) per channel (1 when thin-walled).
    pub volume_transmittance: V3,
    /// KHR_materials_diffuse_transmission: the fraction of the diffuse base that transmits.
    pub diffuse_transmission: f64,
    /// The colour of the diffusely transmitted light, linear RGB.
    pub diffuse_transmission_color: V3,
    /// KHR_materials_iridescence: the thin film's strength (0 switches it off).
    pub iridescence: f64,
    /// The thin film's index of refraction and thickness (nanometres).
    pub iridescence_film: Film,
}

/// How a dielectric's diffuse term is weighed against the specular Fresnel term F (RGB).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DiffuseBalance {
    /// `(1 − max3(F)) · diffuse`: glTF 2.0 with KHR_materials_specular ("dielectric_brdf =
    /// … (1 - max_value(dielectric_fresnel)) * diffuse_brdf").
    MaxFresnel,
    /// `(1 − F_c) · diffuse` in each channel: Appendix B's `fresnel_mix` with an RGB Fresnel,
    /// which the archived KHR_materials_pbrSpecularGlossiness was written against, and the
    /// 1.0 drafts' "the diffuse term should be balanced using the inverse of the Fresnel term".
    PerChannelFresnel,
    /// `diffuse`, not weighed at all: the January 2017 FRAUNHOFER example shader.
    Unbalanced,
}

/// A reading of a specular-glossiness text: how its diffuse colour and its balance against
/// the Fresnel term are taken. The 1.0 drafts disagree with each other: an upgrade converts
/// under one reading (by default [`SpecGlossReading::DraftAppendix`], the one the ratified
/// KHR_materials_pbrSpecularGlossiness kept) and reports how far the others are from it as
/// the source's own ambiguity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpecGlossReading {
    /// KHR_materials_pbrSpecularGlossiness (archived): "c_diff = diffuse.rgb * (1 -
    /// max(specular.r, specular.g, specular.b))", F0 = specular, against Appendix B.
    ArchivedExtension,
    /// The drafts' Appendix ("balanced using the inverse of the Fresnel term", per channel)
    /// with the January 2017 energy conservation `diffuse * (1 - max(specular))`.
    DraftAppendix,
    /// The 2016 drafts' Appendix alone: c_diff is the diffuse colour, balanced by 1 − F.
    DraftAppendix2016,
    /// The January 2017 example shader: `diffuse * (1 - max(specular.rgb))`, no (1 − F).
    DraftExampleShader,
}

impl SpecGlossReading {
    /// Every reading of the glTF 1.0 PBR drafts, the default first.
    pub const DRAFTS: [SpecGlossReading; 3] = [
        SpecGlossReading::DraftAppendix,
        SpecGlossReading::DraftAppendix2016,
        SpecGlossReading::DraftExampleShader,
    ];

    /// A short name for reports.
    pub fn name(self) -> &'static str {
        match self {
            SpecGlossReading::ArchivedExtension => "KHR_materials_pbrSpecularGlossiness (archived)",
            SpecGlossReading::DraftAppendix => {
                "drafts' Appendix with the 2017 diffuse · (1 − max specular)"
            }
            SpecGlossReading::DraftAppendix2016 => "2016 drafts' Appendix (diffuse not scaled)",
            SpecGlossReading::DraftExampleShader => "January 2017 example shader (no 1 − F)",
        }
    }

    fn balance(self) -> DiffuseBalance {
        match self {
            SpecGlossReading::DraftExampleShader => DiffuseBalance::Unbalanced,
            _ => DiffuseBalance::PerChannelFresnel,
        }
    }

    fn scales_diffuse(self) -> bool {
        self != SpecGlossReading::DraftAppendix2016
    }

    /// The metal-rough + KHR_materials_specular + ior 0 base colour that draws this
    /// reading's diffuse, and whether it does so exactly at every angle.
    ///
    /// The target weighs its base colour by 1 − max_c F_c; with ior 0, F_c = s_c + (1 −
    /// s_c)·w for one Schlick weight w, so 1 − F_c = (1 − s_c)(1 − w) and 1 − max F = (1 −
    /// max s)(1 − w). A reading balanced per channel (c_diff,c · (1 − F_c)) is therefore
    /// drawn exactly by base_c = c_diff,c · (1 − s_c) / (1 − max s), as long as that is at
    /// most 1: for c_diff = diffuse · (1 − max s) (the archived extension, the drafts'
    /// Appendix with the 2017 scaling) it is diffuse_c · (1 − s_c). A reading with no 1 − F
    /// at all (the example shader) has no exact form: the target always weighs by
    /// 1 − max F, so the base colour that matches it at normal incidence, c_diff / (1 − max
    /// s) = diffuse, is the start a fit improves on.
    pub fn closed_form_base(self, diffuse: V3, specular: V3) -> (V3, bool) {
        let largest = max3(specular).min(1.0);
        let keep = |c: usize| (1.0 - specular[c]).clamp(0.0, 1.0);
        match (self.balance(), self.scales_diffuse()) {
            (DiffuseBalance::PerChannelFresnel, true) | (DiffuseBalance::MaxFresnel, _) => {
                (channels(|c| diffuse[c] * keep(c)), true)
            }
            (DiffuseBalance::PerChannelFresnel, false) => {
                // With all of the light reflected (max s = 1) the target draws no diffuse.
                let base = channels(|c| match largest < 1.0 {
                    true => diffuse[c] * keep(c) / (1.0 - largest),
                    false => 0.0,
                });
                let exact =
                    base.iter().all(|&b| b <= 1.0) && (largest < 1.0 || diffuse == [0.0; 3]);
                (base.map(|b| b.min(1.0)), exact)
            }
            (DiffuseBalance::Unbalanced, scaled) => {
                let c_diff = channels(|c| diffuse[c] * if scaled { 1.0 - largest } else { 1.0 });
                let base = channels(|c| match largest < 1.0 {
                    true => (c_diff[c] / (1.0 - largest)).min(1.0),
                    false => 0.0,
                });
                (base, largest == 0.0)
            }
        }
    }

    /// The reading named as `--draft-reading` takes it.
    pub fn option_name(self) -> &'static str {
        match self {
            SpecGlossReading::ArchivedExtension => "archived-extension",
            SpecGlossReading::DraftAppendix => "appendix",
            SpecGlossReading::DraftAppendix2016 => "appendix-2016",
            SpecGlossReading::DraftExampleShader => "example-shader",
        }
    }
}

impl Default for Inputs {
    fn default() -> Self {
        Inputs {
            base_color: [1.0; 3],
            metallic: 1.0,
            roughness: 1.0,
            ior: 1.5,
            specular: 1.0,
            specular_color: [1.0; 3],
            sheen_color: [0.0; 3],
            sheen_roughness: 0.0,
            anisotropy_strength: 0.0,
            anisotropy_angle: 0.0,
            unlit: false,
            diffuse_balance: DiffuseBalance::MaxFresnel,
            emission: [0.0; 3],
            coverage: 1.0,
            premultiplied: false,
            occlusion: 1.0,
            normal: [0.0, 0.0, 1.0],
            clearcoat: 0.0,
            clearcoat_roughness: 0.0,
            clearcoat_normal: [0.0, 0.0, 1.0],
            transmission: 0.0,
            volume_transmittance: [1.0; 3],
            diffuse_transmission: 0.0,
            diffuse_transmission_color: [1.0; 3],
            iridescence: 0.0,
            iridescence_film: Film {
                ior: 1.3,
                thickness: 400.0,
            },
        }
    }
}

/// How many inputs a texture can bend (see [`Inputs::bent`]).
pub(crate) const BENT: usize = 15;

/// The inputs a texture can bend (see [`Inputs::bent`]), in a fixed order.
pub(crate) type Bent = [f64; BENT];

/// Whether `corner` is the mean of `four`, each number to within `tolerance` of its size (at
/// least 1): what a material has at the corner between four texel centres where the inputs
/// its textures bend are, there too, the mean of the centres' (every other input is).
#[inline(always)]
pub(crate) fn is_mean_of(corner: &Bent, four: [&Bent; 4], tolerance: f64) -> bool {
    // Every number is checked, none skipped on the first failure: the loop is then plain
    // vector arithmetic.
    (0..BENT).fold(true, |all, i| {
        let mean = (four[0][i] + four[1][i] + four[2][i] + four[3][i]) / 4.0;
        all & ((corner[i] - mean).abs() <= tolerance * mean.abs().max(1.0))
    })
}

impl Inputs {
    /// The inputs a texture can bend, which are not affine in the texels they are read
    /// from: the base colour (spec-gloss's diffuse · (1 − max specular)), the coverage (a
    /// MASK threshold, a 1.0 alpha clamped), the normals (normalised), the anisotropy
    /// (a direction's angle) and the volume's transmittance (a power). Every other input is
    /// a constant times one texel channel plus a constant (the test
    /// `every_input_left_out_of_the_bent_ones_is_affine_in_its_texels` holds it), and the
    /// switches are the material's own: at a texel corner those are the mean of the four
    /// centres' around it.
    #[inline(always)]
    pub(crate) fn bent(&self) -> Bent {
        let ([r, g, b], [nx, ny, nz]) = (self.base_color, self.normal);
        let ([cx, cy, cz], [vr, vg, vb]) = (self.clearcoat_normal, self.volume_transmittance);
        let (strength, angle) = (self.anisotropy_strength, self.anisotropy_angle);
        [
            r,
            g,
            b,
            self.coverage,
            nx,
            ny,
            nz,
            cx,
            cy,
            cz,
            strength,
            angle,
            vr,
            vg,
            vb,
        ]
    }

    /// Whether these inputs are the mean of `four`'s, each number to within `tolerance` of
    /// its size (at least 1), with the same switches: the whole of what [`is_mean_of`]
    /// checks of the bent inputs, for the test that holds the others affine.
    #[cfg(test)]
    pub(crate) fn all_mean_of(&self, four: [&Inputs; 4], tolerance: f64) -> bool {
        // Every field, named: a field added to the inputs must be added below.
        let Inputs {
            base_color: _,
            metallic: _,
            roughness: _,
            ior: _,
            specular: _,
            specular_color: _,
            sheen_color: _,
            sheen_roughness: _,
            anisotropy_strength: _,
            anisotropy_angle: _,
            unlit: _,
            diffuse_balance: _,
            emission: _,
            coverage: _,
            premultiplied: _,
            occlusion: _,
            normal: _,
            clearcoat: _,
            clearcoat_roughness: _,
            clearcoat_normal: _,
            transmission: _,
            volume_transmittance: _,
            diffuse_transmission: _,
            diffuse_transmission_color: _,
            iridescence: _,
            iridescence_film:
                Film {
                    ior: _,
                    thickness: _,
                },
        } = self;
        let switches = |m: &Inputs| (m.unlit, m.premultiplied, m.diffuse_balance);
        let near = |here: f64, each: [f64; 4]| {
            let mean = (each[0] + each[1] + each[2] + each[3]) / 4.0;
            (here - mean).abs() <= tolerance * mean.abs().max(1.0)
        };
        let one = |get: fn(&Inputs) -> f64| near(get(self), four.map(get));
        let three = |get: fn(&Inputs) -> V3| {
            let (here, each) = (get(self), four.map(get));
            (0..3).all(|i| near(here[i], each.map(|v| v[i])))
        };
        four.iter().all(|m| switches(m) == switches(self))
            && three(|m| m.base_color)
            && one(|m| m.metallic)
            && one(|m| m.roughness)
            && one(|m| m.ior)
            && one(|m| m.specular)
            && three(|m| m.specular_color)
            && three(|m| m.sheen_color)
            && one(|m| m.sheen_roughness)
            && one(|m| m.anisotropy_strength)
            && one(|m| m.anisotropy_angle)
            && three(|m| m.emission)
            && one(|m| m.coverage)
            && one(|m| m.occlusion)
            && three(|m| m.normal)
            && one(|m| m.clearcoat)
            && one(|m| m.clearcoat_roughness)
            && three(|m| m.clearcoat_normal)
            && one(|m| m.transmission)
            && three(|m| m.volume_transmittance)
            && one(|m| m.diffuse_transmission)
            && three(|m| m.diffuse_transmission_color)
            && one(|m| m.iridescence)
            && one(|m| m.iridescence_film.ior)
            && one(|m| m.iridescence_film.thickness)
    }

    /// The share of the dielectric's diffuse that is reflected: "mix(diffuse_bsdf,
    /// specular_btdf · baseColor, transmission)" and "mix(diffuse_brdf, diffuse_btdf,
    /// diffuseTransmission)" (KHR_materials_transmission, _diffuse_transmission); the
    /// transmitted shares reach the viewer from behind the surface, not from the light.
    pub(crate) fn diffuse_reflected(&self) -> f64 {
        (1.0 - self.transmission) * (1.0 - self.diffuse_transmission)
    }
}

impl Inputs {
    /// A specular-glossiness material under `reading`, in the evaluator's terms: a
    /// dielectric whose F0 is the specular colour (ior 0 makes f0_ior = 1), α = (1 −
    /// glossiness)², and whose diffuse and its balance are the reading's.
    pub(crate) fn specular_glossiness(
        diffuse: V3,
        specular: V3,
        glossiness: f64,
        reading: SpecGlossReading,
    ) -> Inputs {
        let keep = if reading.scales_diffuse() {
            1.0 - max3(specular)
        } else {
            1.0
        };
        Inputs {
            base_color: channels(|i| diffuse[i] * keep),
            metallic: 0.0,
            roughness: 1.0 - glossiness,
            ior: 0.0,
            specular_color: specular,
            diffuse_balance: reading.balance(),
            ..Inputs::default()
        }
    }
}

/// Evaluates materials; holds the sheen albedo table for its visibility term.
pub(crate) struct Shader {
    /// The sheen albedo table of its visibility term.
    pub sheen_table: SheenTable,
}

impl Shader {
    /// A shader using `sheen_table`.
    pub(crate) fn new(sheen_table: SheenTable) -> Shader {
        Shader { sheen_table }
    }

    /// The sheen visibility term its table was computed for.
    pub(crate) fn visibility(&self) -> SheenVisibility {
        self.sheen_table.visibility
    }

    /// The BRDF f(v, l) (not multiplied by NdotL), RGB, directions in the shading frame.
    /// Unlit materials return their colour as radiance-like value: callers treat them apart.
    #[inline(always)]
    pub(crate) fn brdf<R: Real>(&self, m: &Inputs, g: &Geometry<R>) -> [R; 3] {
        let base = base_brdf(m, g);
        let c = max3(m.sheen_color);
        let layered = if c == 0.0 {
            // A zero sheen colour disables the layer: the base, bit for bit.
            base
        } else {
            let lobe = sheen_lobe(self.visibility(), m.sheen_roughness, g);
            let e = |mu: R| mu.map(|mu| self.sheen_table.lookup(mu, m.sheen_roughness));
            let scale = (-(e(g.v[2]) * c) + 1.0)
                .min(-(e(g.l[2]) * c) + 1.0)
                .max(R::splat(0.0));
            channels(|i| lobe * m.sheen_color[i] + base[i] * scale)
        };
        let zero = R::splat(0.0);
        channels(|i| R::select(g.above, layered[i], zero))
    }
}

/// The metal-roughness BRDF with specular, ior and anisotropy, before sheen.
#[inline(always)]
pub(crate) fn base_brdf<R: Real>(m: &Inputs, g: &Geometry<R>) -> [R; 3] {
    let alpha = m.roughness * m.roughness;
    let specular = if m.anisotropy_strength > 0.0 {
        let (alpha_t, alpha_b) = anisotropic_alphas(alpha, m.anisotropy_strength);
        let rotate = |w: [R; 3]| into_anisotropy_frame(w, m.anisotropy_angle);
        ggx_aniso_d(alpha_t, alpha_b, rotate(g.h))
            * smith_vis_aniso(alpha_t, alpha_b, rotate(g.v), rotate(g.l))
    } else {
        ggx_d(alpha, g.h[2]) * smith_vis(alpha, g.l[2], g.v[2])
    };
    let f0_ior = f0_from_ior(m.ior);
    let mut dielectric_f: [R; 3] = channels(|i| {
        fresnel(
            (f0_ior * m.specular_color[i]).min(1.0) * m.specular,
            m.specular,
            g.fresnel_weight,
        )
    });
    let mut metal_f: [R; 3] = channels(|i| fresnel(m.base_color[i], 1.0, g.fresnel_weight));
    if m.iridescence > 0.0 {
        // KHR_materials_iridescence: "mix(specular_weight * fr, iridescent_f,
        // iridescence_strength)" over the dielectric's F0 times its specular weight, and
        // "mix(conductor_fresnel(base_f0), … iridescent_fresnel(…, base_f0, …))" over the
        // metal's base colour, at the viewing angle.
        let cos_view = g.v[2].max(R::splat(0.0));
        let film_f0 = channels(|i| (f0_ior * m.specular_color[i]).min(1.0) * m.specular);
        let (strength, film) = (m.iridescence, m.iridescence_film);
        let over_dielectric = fresnel_lanes(film, film_f0, cos_view);
        let over_metal = fresnel_lanes(film, m.base_color, cos_view);
        dielectric_f =
            channels(|i| dielectric_f[i] * (1.0 - strength) + over_dielectric[i] * strength);
        metal_f = channels(|i| metal_f[i] * (1.0 - strength) + over_metal[i] * strength);
    }
    let max_f = max3(dielectric_f);
    let diffuse_weight = |i: usize| match m.diffuse_balance {
        DiffuseBalance::MaxFresnel => -max_f + 1.0,
        DiffuseBalance::PerChannelFresnel => -dielectric_f[i] + 1.0,
        DiffuseBalance::Unbalanced => R::splat(1.0),
    };
    let reflected = m.diffuse_reflected();
    channels(|i| {
        let diffuse = m.base_color[i] * reflected / PI;
        let dielectric = dielectric_f[i] * specular + diffuse_weight(i) * diffuse;
        let metal = metal_f[i] * specular;
        dielectric * (1.0 - m.metallic) + metal * m.metallic
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::brdf::{half, schlick};
    use crate::shade::eval::quadrature::hemisphere;

    fn shader() -> Shader {
        Shader::new(SheenTable::compute(8, SheenVisibility::Charlie))
    }

    fn direction(theta: f64, phi: f64) -> V3 {
        [
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ]
    }

    /// Appendix B exactly as written: fresnel_mix with the scalar Fresnel of ior 1.5.
    fn appendix_b(m: &Inputs, v: V3, l: V3) -> V3 {
        let h = half(v, l);
        let alpha = m.roughness * m.roughness;
        let specular = ggx_d(alpha, h[2]) * smith_vis(alpha, l[2], v[2]);
        let v_dot_h = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
        let f = schlick(0.04, 1.0, v_dot_h);
        [0, 1, 2].map(|i| {
            let dielectric = (1.0 - f) * m.base_color[i] / PI + f * specular;
            let metal = schlick(m.base_color[i], 1.0, v_dot_h) * specular;
            dielectric * (1.0 - m.metallic) + metal * m.metallic
        })
    }

    fn assert_close(a: V3, b: V3) {
        for i in 0..3 {
            assert!(
                (a[i] - b[i]).abs() <= 1e-12 * b[i].abs().max(1.0),
                "{a:?} vs {b:?}"
            );
        }
    }

    fn pairs() -> Vec<(V3, V3)> {
        let mut out = Vec::new();
        for (tv, pv) in [(0.2, 0.0), (0.9, 1.0), (1.5, 2.5)] {
            for (tl, pl) in [(0.1, 3.0), (0.7, 0.4), (1.4, 5.0)] {
                out.push((direction(tv, pv), direction(tl, pl)));
            }
        }
        out
    }

    fn material() -> Inputs {
        Inputs {
            base_color: [0.8, 0.4, 0.2],
            metallic: 0.3,
            roughness: 0.45,
            ..Inputs::default()
        }
    }

    /// Sheen, anisotropy, a chromatic specular colour and a non-default ior together.
    fn every_extension() -> Inputs {
        Inputs {
            sheen_color: [0.9, 0.5, 0.3],
            sheen_roughness: 0.6,
            anisotropy_strength: 0.7,
            anisotropy_angle: 0.3,
            specular_color: [1.2, 0.8, 1.0],
            ior: 1.7,
            ..material()
        }
    }

    #[test]
    fn default_specular_and_ior_reduce_to_appendix_b() {
        for (v, l) in pairs() {
            assert_close(
                base_brdf(&material(), &Geometry::new(v, l)),
                appendix_b(&material(), v, l),
            );
        }
    }

    #[test]
    fn zero_anisotropy_strength_is_isotropic() {
        let mut aniso = material();
        aniso.anisotropy_angle = 0.7;
        for (v, l) in pairs() {
            let isotropic = base_brdf(&material(), &Geometry::new(v, l));
            aniso.anisotropy_strength = 1e-300; // takes the anisotropic path with s² = 0
            assert_close(base_brdf(&aniso, &Geometry::new(v, l)), isotropic);
        }
    }

    #[test]
    fn zero_sheen_colour_returns_the_base_bit_for_bit() {
        let s = shader();
        let mut m = material();
        m.sheen_roughness = 0.5;
        for (v, l) in pairs() {
            assert_eq!(
                s.brdf(&m, &Geometry::new(v, l)),
                base_brdf(&m, &Geometry::new(v, l))
            );
        }
    }

    #[test]
    fn lanes_evaluate_each_pair_exactly_as_a_single_pair_does() {
        let s = shader();
        let below = (direction(1.8, 0.0), direction(0.4, 1.0)); // view under the horizon
        let mut pairs: Vec<(V3, V3)> = pairs();
        pairs.truncate(7);
        pairs.push(below);
        let singles: [Geometry<f64>; 8] =
            std::array::from_fn(|i| Geometry::new(pairs[i].0, pairs[i].1));
        let lanes = Geometry::lanes(&singles);
        for m in [material(), every_extension()] {
            let together = s.brdf(&m, &lanes);
            for (i, single) in singles.iter().enumerate() {
                let alone = s.brdf(&m, single);
                for c in 0..3 {
                    assert_eq!(together[c].0[i].to_bits(), alone[c].to_bits(), "pair {i}");
                }
            }
            assert_eq!(together[0].0[7], 0.0, "below the horizon");
        }
    }

    #[test]
    fn every_lobe_is_reciprocal() {
        let s = shader();
        let m = every_extension();
        for (v, l) in pairs() {
            assert_close(
                s.brdf(&m, &Geometry::new(v, l)),
                s.brdf(&m, &Geometry::new(l, v)),
            );
        }
    }

    #[test]
    fn ggx_and_charlie_are_normalised_and_pass_the_weak_furnace() {
        for alpha in [0.1, 0.3, 0.7, 1.0] {
            let d = hemisphere(2000, 256, |h| ggx_d(alpha, h[2]) * h[2]);
            assert!((d - 1.0).abs() < 1e-6, "GGX α = {alpha}: {d}");
        }
        for (at, ab) in [(0.3, 0.3), (0.5, 0.1), (1.0, 0.2)] {
            let d = hemisphere(2000, 512, |h| ggx_aniso_d(at, ab, h) * h[2]);
            assert!((d - 1.0).abs() < 1e-5, "anisotropic ({at}, {ab}): {d}");
        }
        for r in [0.3, 0.7, 1.0] {
            let d = hemisphere(2000, 64, |h| crate::shade::brdf::charlie_d(r, h[2]) * h[2]);
            assert!((d - 1.0).abs() < 1e-6, "Charlie {r}: {d}");
        }
        // Heitz 2014: ∫ G1(v) D(h) max(0, v·h) dω_h = v·n.
        for theta in [0.3f64, 1.2] {
            let v = direction(theta, 0.0);
            let alpha = 0.4;
            let g1 = 1.0 / (1.0 + crate::shade::brdf::smith_lambda(alpha, v[2]));
            let value = hemisphere(2000, 256, |h| {
                g1 * ggx_d(alpha, h[2]) * (v[0] * h[0] + v[1] * h[1] + v[2] * h[2]).max(0.0)
            });
            assert!(
                (value - v[2]).abs() < 1e-5,
                "θ = {theta}: {value} vs {}",
                v[2]
            );
        }
    }

    /// The first closed-form conversion: base colour = diffuse · (1 − max specular),
    /// roughness = 1 − glossiness, specularColor = specular, ior 0.
    fn converted(diffuse: V3, specular: V3, gloss: f64) -> Inputs {
        let keep = 1.0 - max3(specular);
        per_channel_converted(diffuse.map(|d| d * keep), specular, gloss)
    }

    /// A conversion with base colour `base`, the rest as the converter writes it.
    fn per_channel_converted(base: V3, specular: V3, gloss: f64) -> Inputs {
        Inputs {
            base_color: base,
            metallic: 0.0,
            roughness: 1.0 - gloss,
            ior: 0.0,
            specular: 1.0,
            specular_color: specular,
            ..Inputs::default()
        }
    }

    #[test]
    fn an_achromatic_spec_gloss_is_its_conversion_exactly() {
        let (diffuse, specular, gloss) = ([0.6, 0.5, 0.4], [0.2, 0.2, 0.2], 0.75);
        let sg = Inputs::specular_glossiness(
            diffuse,
            specular,
            gloss,
            SpecGlossReading::ArchivedExtension,
        );
        for (v, l) in pairs() {
            let (a, b) = (
                base_brdf(&sg, &Geometry::new(v, l)),
                base_brdf(&converted(diffuse, specular, gloss), &Geometry::new(v, l)),
            );
            assert_close(a, b);
        }
    }

    /// Chromatic spec-gloss materials (diffuse, specular, glossiness) and their evaluation
    /// under the archived extension's text.
    fn chromatic_spec_gloss() -> impl Iterator<Item = (V3, V3, f64, Inputs)> {
        let (diffuse, gloss) = ([0.8, 0.7, 0.6], 0.6);
        [[0.9, 0.1, 0.1], [0.0, 0.3, 0.0], [0.4, 0.04, 0.04]]
            .map(|specular| {
                let reading = SpecGlossReading::ArchivedExtension;
                let source = Inputs::specular_glossiness(diffuse, specular, gloss, reading);
                (diffuse, specular, gloss, source)
            })
            .into_iter()
    }

    /// The proof can fail: under its own text (1 − F per channel) a chromatic spec-gloss
    /// exceeds its conversion (1 − max3(F)) by exactly c_diff,c · (1 − w) · (max s − s_c) / π,
    /// w = (1 − V·H)⁵, in every channel.
    #[test]
    fn a_chromatic_spec_gloss_keeps_the_analytic_residual_of_its_own_model() {
        for (diffuse, specular, gloss, source) in chromatic_spec_gloss() {
            let target = converted(diffuse, specular, gloss);
            let max_s = max3(specular);
            for (v, l) in pairs() {
                let g = Geometry::new(v, l);
                let (a, b) = (base_brdf(&source, &g), base_brdf(&target, &g));
                let h = half(v, l);
                let w = (1.0 - (v[0] * h[0] + v[1] * h[1] + v[2] * h[2])).powi(5);
                for c in 0..3 {
                    let expected = target.base_color[c] * (1.0 - w) * (max_s - specular[c]) / PI;
                    // The source keeps more diffuse: 1 − F_c ≥ 1 − max3(F).
                    assert!(
                        ((a[c] - b[c]) - expected).abs() < 1e-6,
                        "{specular:?} channel {c}: {} vs {expected}",
                        a[c] - b[c]
                    );
                }
                assert!(
                    max3(channels(|c| (b[c] - a[c]).abs())) > 1e-3,
                    "{specular:?}: the residual shows"
                );
            }
        }
    }

    /// The converter's mapping (upgrade/spec_gloss.rs), base colour = diffuse · (1 − s_c) per
    /// channel: 1 − F_c = (1 − s_c)(1 − w) and 1 − max3(F) = (1 − max s)(1 − w), so the source's
    /// c_diff · (1 − F_c) equals base_c · (1 − max3 F) at every angle.
    #[test]
    fn per_channel_base_colour_reproduces_a_chromatic_spec_gloss_exactly() {
        for (diffuse, specular, gloss, source) in chromatic_spec_gloss() {
            let base = channels(|c| diffuse[c] * (1.0 - specular[c]));
            let target = per_channel_converted(base, specular, gloss);
            for (v, l) in pairs() {
                let g = Geometry::new(v, l);
                assert_close(base_brdf(&source, &g), base_brdf(&target, &g));
            }
        }
    }

    /// White furnace: a white sheen layered on a white Lambert base (no specular lobe) reflects
    /// at most what arrives, with the 16² table `compare` uses for sheen materials, except
    /// where the sheen lobe alone reflects more: the Charlie lobe is not energy conserving at
    /// grazing view and low roughness (its own albedo is 1.0035 at sheenRoughness 0.05, μ 0.05,
    /// and KHR_materials_sheen does not normalise it). The layering itself adds nothing: the
    /// base is scaled by 1 − E (clamped at 0) from the table.
    #[test]
    fn a_white_sheen_on_a_white_lambert_base_reflects_at_most_what_arrives() {
        let shader = Shader::new(SheenTable::compute(16, SheenVisibility::Charlie));
        let mut above_one = 0;
        for sheen_roughness in [0.05, 0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.0] {
            let material = Inputs {
                base_color: [1.0; 3],
                metallic: 0.0,
                specular: 0.0,
                sheen_color: [1.0; 3],
                sheen_roughness,
                ..Inputs::default()
            };
            for theta_v in [0.0, 0.4, 0.8, 1.1, 1.3, 1.45, 1.52] {
                let v = direction(theta_v, 0.0);
                let albedo = crate::shade::eval::quadrature::hemisphere(384, 64, |l| {
                    shader.brdf(&material, &Geometry::new(v, l))[0] * l[2]
                });
                let lobe = SheenTable::albedo(SheenVisibility::Charlie, v[2], sheen_roughness);
                assert!(
                    albedo <= lobe.max(1.0) + 1e-3,
                    "sheen roughness {sheen_roughness}, θv {theta_v}: albedo {albedo}, lobe {lobe}"
                );
                if lobe > 1.0 {
                    above_one += 1;
                }
            }
        }
        assert!(
            above_one > 0,
            "the sweep reaches where the lobe alone exceeds 1"
        );
    }

    #[test]
    fn no_brdf_value_is_negative_at_low_sheen_roughness_and_grazing_angles() {
        let shader = Shader::new(SheenTable::compute(32, SheenVisibility::Charlie));
        let mut checked = 0;
        for step in 0..=10 {
            let material = Inputs {
                base_color: [0.9, 0.8, 0.7],
                metallic: 0.0,
                roughness: 0.5,
                sheen_color: [1.0, 1.0, 1.0],
                sheen_roughness: 0.005 * step as f64,
                ..Inputs::default()
            };
            for theta_v in [0.2, 1.0, 1.45, 1.55, 1.5608] {
                for theta_l in [0.1, 0.8, 1.4, 1.55, 1.5608] {
                    for phi in [0.0, 1.5, 3.1] {
                        let g = Geometry::new(direction(theta_v, 0.0), direction(theta_l, phi));
                        let value = shader.brdf(&material, &g);
                        assert!(
                            value.iter().all(|&c| c >= 0.0),
                            "{value:?} at sr {}",
                            material.sheen_roughness
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 11 * 5 * 5 * 3);
    }
}
