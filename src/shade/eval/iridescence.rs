//! KHR_materials_iridescence's thin-film Fresnel term, as its README gives it (the
//! Belcour-Barla model with Schlick's interfaces, the phase shifts of 0 or π, and the
//! analytic spectral integration of its first two orders into linear sRGB).

use super::brdf::V3;
use super::lanes::Real;
use std::f64::consts::PI;

/// A thin film: its index of refraction and its thickness in nanometres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Film {
    /// `iridescenceIor`.
    pub ior: f64,
    /// Nanometres: `iridescenceThicknessMaximum`, or the texture's place between the minimum
    /// and the maximum.
    pub thickness: f64,
}

/// "R = |(n1 − n2) / (n1 + n2)|²" at normal incidence.
fn ior_to_f0(transmitted: f64, incident: f64) -> f64 {
    ((transmitted - incident) / (transmitted + incident)).powi(2)
}

/// "Fresnel0ToIor": the index whose normal-incidence reflectance against air is `f0`.
fn f0_to_ior(f0: f64) -> f64 {
    let root = f0.clamp(0.0, 0.9999).sqrt();
    (1.0 + root) / (1.0 - root)
}

fn schlick(f0: f64, cosine: f64) -> f64 {
    f0 + (1.0 - f0) * (1.0 - cosine).clamp(0.0, 1.0).powi(5)
}

/// "evalSensitivity": the film's m-th order interference, integrated against the CIE
/// matching functions (Gaussian fits) and taken to linear sRGB.
fn sensitivity(opd: f64, shift: V3) -> V3 {
    let phase = 2.0 * PI * opd * 1.0e-9;
    let val = [5.4856e-13, 4.4201e-13, 5.2481e-13];
    let pos = [1.6810e+06, 1.7953e+06, 2.2084e+06];
    let var = [4.3278e+09, 9.3046e+09, 6.6121e+09];
    let mut xyz: V3 = std::array::from_fn(|i| {
        val[i]
            * (2.0 * PI * var[i]).sqrt()
            * (pos[i] * phase + shift[i]).cos()
            * (-phase * phase * var[i]).exp()
    });
    xyz[0] += 9.7470e-14
        * (2.0 * PI * 4.5282e+09f64).sqrt()
        * (2.2399e+06 * phase + shift[0]).cos()
        * (-4.5282e+09 * phase * phase).exp();
    let xyz = xyz.map(|c| c / 1.0685e-7);
    // XYZ → linear Rec. 709, the README's matrix (its columns as GLSL lists them).
    [
        3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2],
        -0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2],
        0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2],
    ]
}

/// The film's Fresnel reflectance over a base of normal-incidence reflectance `base_f0`
/// (per channel), seen from outside (air) at `cos_theta1`.
pub(crate) fn fresnel(film: Film, base_f0: V3, cos_theta1: f64) -> V3 {
    const OUTSIDE: f64 = 1.0;
    // "mix(outsideIOR, eta2, smoothstep(0.0, 0.03, thinFilmThickness))" is the Sample
    // Viewer's; the README takes the film's index as it is.
    let ior = film.ior;
    let sin2_theta2 = (OUTSIDE / ior).powi(2) * (1.0 - cos_theta1 * cos_theta1);
    let cos2_theta2 = 1.0 - sin2_theta2;
    if cos2_theta2 < 0.0 {
        // Total internal reflection.
        return [1.0; 3];
    }
    let cos_theta2 = cos2_theta2.sqrt();
    let r12 = schlick(ior_to_f0(ior, OUTSIDE), cos_theta1);
    let t121 = 1.0 - r12;
    let phi12 = if ior < OUTSIDE { PI } else { 0.0 };
    let phi21 = PI - phi12;
    let base_ior = base_f0.map(|f0| f0_to_ior(f0 + 0.0001));
    let r23: V3 = std::array::from_fn(|i| schlick(ior_to_f0(base_ior[i], ior), cos_theta2));
    let phi23: V3 = base_ior.map(|b| if b < ior { PI } else { 0.0 });
    let opd = 2.0 * ior * film.thickness * cos_theta2;
    let phi: V3 = phi23.map(|p| phi21 + p);
    let r123: V3 = r23.map(|r| (r12 * r).clamp(1e-5, 0.9999));
    let rs: V3 = std::array::from_fn(|i| t121 * t121 * r23[i] / (1.0 - r123[i]));
    let mut intensity: V3 = std::array::from_fn(|i| r12 + rs[i]);
    let mut cm: V3 = std::array::from_fn(|i| rs[i] - t121);
    for m in 1..=2 {
        let m = f64::from(m);
        let sm = sensitivity(m * opd, phi.map(|p| m * p));
        for i in 0..3 {
            cm[i] *= r123[i].sqrt();
            intensity[i] += cm[i] * 2.0 * sm[i];
        }
    }
    intensity.map(|c| c.max(0.0))
}

/// [`fresnel`] for one or several view angles (one per lane).
#[inline(always)]
pub(crate) fn fresnel_lanes<R: Real>(film: Film, base_f0: V3, cos_theta1: R) -> [R; 3] {
    std::array::from_fn(|i| cos_theta1.map(|c| fresnel(film, base_f0, c)[i]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_film_of_no_thickness_reflects_like_its_interfaces_and_a_thick_one_colours() {
        // At normal incidence with thickness 0 the orders add in phase or against it: the
        // result is a grey (equal in every channel within the fit's colour error), while a
        // film half a wavelength thick reflects a colour.
        let thin = fresnel(
            Film {
                ior: 1.3,
                thickness: 0.0,
            },
            [0.04; 3],
            1.0,
        );
        assert!((thin[0] - thin[2]).abs() < 0.02, "{thin:?}");
        let coloured = fresnel(
            Film {
                ior: 1.3,
                thickness: 300.0,
            },
            [0.04; 3],
            1.0,
        );
        let spread = coloured.iter().cloned().fold(f64::MIN, f64::max)
            - coloured.iter().cloned().fold(f64::MAX, f64::min);
        assert!(spread > 0.01, "{coloured:?}");
        assert!(
            coloured.iter().all(|c| (0.0..=1.0).contains(c)),
            "{coloured:?}"
        );
    }
}
