//! The spec-gloss → metal-rough closed form's vocabulary (the source's [`Factors`], the
//! closed-form [`base_colour`]) and what improves on it: the fitted conversion of a
//! factor-only 1.0 spec-gloss material, and of a textured one's base colour texel by texel
//! ([`TexelFits`]). This is the bottom of the mapping: `rebake` and `spec_gloss` build on it.
//!
//! A factor-only 1.0 spec-gloss material: the drafts can be read
//! three ways (see `SpecGlossReading::DRAFTS`), and where their readings disagree (a
//! chromatic specular, or one read with no 1 − F) no closed-form 2.0 material matches all of
//! them. When the closed form's worst ΔE over the readings and the proof's direction pairs is
//! above the proof's threshold, the 2.0 factors (base colour, roughness, specular colour) are
//! fitted to minimise that worst ΔE, the figure the proof reports, and both figures are kept
//! for the conversion report. An upgrade fits each distinct material once and at most
//! [`MAX_DISTINCT_FITS`] of them (about 5 ms each), so that a hostile asset of a million
//! distinct materials cannot make it run for hours.

use crate::gltf::color::{linear_to_srgb, linear_to_srgb8, srgb_to_linear};
use crate::shade::brdf::SheenVisibility;
use crate::shade::compare::worst_at_point;
use crate::shade::material::{DiffuseBalance, Inputs, Shader, SpecGlossReading};
use crate::shade::sheen_table::SheenTable;

/// The proof's default threshold: below it the closed form is kept as it is.
const THRESHOLD: f64 = crate::shade::compare::DEFAULT_THRESHOLD;

/// Distinct materials fitted per upgrade; later ones keep their closed form.
pub const MAX_DISTINCT_FITS: usize = 256;

/// A spec-gloss material's factors (diffuse RGBA, specular RGB, glossiness).
#[derive(Debug, Clone, Copy)]
pub struct Factors {
    pub diffuse: [f64; 4],
    pub specular: [f64; 3],
    pub glossiness: f64,
}

/// The closed-form base colour: diffuse · (1 − specular), channel by channel (a specular
/// above 1 takes all of the diffuse, never more).
pub fn base_colour(diffuse: [f64; 3], specular: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| diffuse[i] * (1.0 - specular[i]).max(0.0))
}

/// A metal-rough + KHR_materials_specular + ior 0 material's factors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    pub base_colour: [f64; 3],
    pub roughness: f64,
    pub specular_colour: [f64; 3],
}

impl Target {
    fn inputs(&self) -> Inputs {
        Inputs {
            base_color: self.base_colour,
            metallic: 0.0,
            roughness: self.roughness,
            ior: 0.0,
            specular_color: self.specular_colour,
            diffuse_balance: DiffuseBalance::MaxFresnel,
            ..Inputs::default()
        }
    }

    fn to_vector(self) -> [f64; 7] {
        let (b, s) = (self.base_colour, self.specular_colour);
        [b[0], b[1], b[2], self.roughness, s[0], s[1], s[2]]
    }

    fn from_vector(x: [f64; 7]) -> Target {
        let x = x.map(|v| v.clamp(0.0, 1.0));
        Target {
            base_colour: [x[0], x[1], x[2]],
            roughness: x[3],
            specular_colour: [x[4], x[5], x[6]],
        }
    }
}

/// The outcome: the closed form's worst ΔE, and the fitted factors with theirs when the
/// fit was needed and did better.
#[derive(Debug, Clone)]
pub struct Fit {
    pub closed_form: f64,
    pub fitted: Option<(Target, f64)>,
}

/// The worst ΔE of `target` against the spec-gloss source under every draft reading.
fn worst_over_readings(shader: &Shader, sources: &[Inputs], target: &Target) -> f64 {
    worst_at_point(shader, sources, &target.inputs())
}

/// The fits of one upgrade: each distinct material fitted once, at most
/// [`MAX_DISTINCT_FITS`] of them.
pub struct Fits {
    done: std::collections::HashMap<[u64; 7], Fit>,
    budget: usize,
}

impl Default for Fits {
    fn default() -> Self {
        Fits::with_budget(MAX_DISTINCT_FITS)
    }
}

impl Fits {
    /// At most `budget` distinct materials fitted.
    pub fn with_budget(budget: usize) -> Fits {
        Fits {
            done: Default::default(),
            budget,
        }
    }

    /// [`fit`], remembered by the source's factors; None once the budget is spent.
    pub fn fit(
        &mut self,
        diffuse: [f64; 3],
        specular: [f64; 3],
        glossiness: f64,
        closed: Target,
    ) -> Option<Fit> {
        let [d0, d1, d2] = diffuse;
        let [s0, s1, s2] = specular;
        let key = [d0, d1, d2, s0, s1, s2, glossiness].map(f64::to_bits);
        if let Some(done) = self.done.get(&key) {
            return Some(done.clone());
        }
        if self.done.len() >= self.budget {
            return None;
        }
        let outcome = fit(diffuse, specular, glossiness, closed);
        self.done.insert(key, outcome.clone());
        Some(outcome)
    }
}

/// Distinct texel values whose closed form is evaluated per upgrade (about 5 µs each); texels
/// past it keep the closed form unchecked, so that a photograph's million distinct texels
/// (or a hostile 8192² texture) add well under a second.
pub const MAX_SCREENED_TEXELS: usize = 1 << 16;

/// Distinct texel values fitted per upgrade (about 0.5 ms each); later ones above the
/// threshold keep the closed form.
pub const MAX_TEXEL_FITS: usize = 1024;

/// Per-texel fits of textured draft spec-gloss materials. Where the rebaked base colour's
/// closed form, diffuse · (1 − specular), is above the proof's threshold under the drafts'
/// readings at a texel, the base colour of that texel is fitted to the smallest worst ΔE over
/// the readings (roughness and specular colour stay the textures' own, which the output
/// reads as they are). Each distinct texel value is evaluated once for the whole upgrade.
pub struct TexelFits {
    done: std::collections::HashMap<[u64; 7], [f64; 3]>,
    screen_budget: usize,
    fits_left: usize,
    /// What the texels rebaked since the last [`TexelFits::take_report`] came to.
    report: TexelReport,
}

/// The figures of one material's texels (distinct texel values, each counted once).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TexelReport {
    /// Distinct texel values evaluated.
    pub screened: usize,
    /// Of those, above the threshold under the closed form.
    pub above: usize,
    /// Of those, fitted to a smaller worst ΔE.
    pub fitted: usize,
    /// The closed form's worst ΔE over the evaluated values.
    pub closed_worst: f64,
    /// The worst ΔE of what is written (fitted or closed form), before 8-bit quantisation.
    pub written_worst: f64,
    /// Texels left with the closed form unchecked, past [`MAX_SCREENED_TEXELS`].
    pub unscreened: usize,
}

impl Default for TexelFits {
    fn default() -> Self {
        TexelFits::with_budgets(MAX_SCREENED_TEXELS, MAX_TEXEL_FITS)
    }
}

impl TexelFits {
    /// At most `screened` distinct texel values evaluated and `fits` fitted.
    pub fn with_budgets(screened: usize, fits: usize) -> TexelFits {
        TexelFits {
            done: Default::default(),
            screen_budget: screened,
            fits_left: fits,
            report: TexelReport::default(),
        }
    }

    /// The base colour written for each distinct texel value (linear diffuse, specular,
    /// glossiness, factors applied), in order; `None` for a value past the check's budget,
    /// which keeps the closed form unchecked. A value is judged by what a viewer samples
    /// from the PNG: its sRGB encoding rounded to `levels` (255 or 65535) steps. New values
    /// are evaluated in parallel; which of them are checked and fitted depends only on their
    /// order.
    pub fn resolve(&mut self, values: &[TexelValue], levels: f64) -> Vec<Option<[f64; 3]>> {
        use rayon::prelude::*;
        let new: Vec<&TexelValue> = (values.iter())
            .filter(|v| !self.done.contains_key(&v.key()))
            .take(self.screen_budget.saturating_sub(self.done.len()))
            .collect();
        let screened: Vec<(f64, [f64; 3])> = (new.par_iter())
            .map(|v| {
                let closed = v.closed_form();
                (v.cost(closed, levels), closed)
            })
            .collect();
        let report = &mut self.report;
        report.screened += new.len();
        let mut to_fit = Vec::new();
        for (k, &(figure, _)) in screened.iter().enumerate() {
            report.closed_worst = report.closed_worst.max(figure);
            if figure > THRESHOLD {
                report.above += 1;
                if to_fit.len() < self.fits_left {
                    to_fit.push(k);
                }
            }
        }
        self.fits_left -= to_fit.len();
        let fitted: Vec<([f64; 3], f64)> = (to_fit.par_iter())
            .map(|&k| {
                let cost = |base: [f64; 3]| new[k].cost(base, levels);
                nelder_mead(cost, screened[k].1, 0.05, 100)
            })
            .collect();
        let mut chosen = screened;
        for (&k, &(base, figure)) in to_fit.iter().zip(&fitted) {
            if figure < chosen[k].0 - 1e-3 {
                report.fitted += 1;
                chosen[k] = (figure, base);
            }
        }
        for (value, (figure, base)) in new.iter().zip(chosen) {
            report.written_worst = report.written_worst.max(figure);
            self.done.insert(value.key(), base);
        }
        (values.iter())
            .map(|v| self.done.get(&v.key()).copied())
            .collect()
    }

    /// Counts `texels` left with the closed form unchecked.
    pub fn unchecked(&mut self, texels: usize) {
        self.report.unscreened += texels;
    }

    /// The figures since the last call, and a fresh start for the next material (the
    /// values evaluated are remembered).
    pub fn take_report(&mut self) -> TexelReport {
        std::mem::take(&mut self.report)
    }
}

/// One texel of a spec-gloss source: linear diffuse and specular colours and glossiness,
/// factors applied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TexelValue {
    pub diffuse: [f64; 3],
    pub specular: [f64; 3],
    pub glossiness: f64,
}

impl TexelValue {
    /// Equal exactly for equal values.
    pub fn key(&self) -> [u64; 7] {
        let ([d0, d1, d2], [s0, s1, s2]) = (self.diffuse, self.specular);
        [d0, d1, d2, s0, s1, s2, self.glossiness].map(f64::to_bits)
    }

    fn closed_form(&self) -> [f64; 3] {
        base_colour(self.diffuse, self.specular)
    }

    /// The worst ΔE over the drafts' readings of `base_colour` as the PNG stores it.
    fn cost(&self, base_colour: [f64; 3], levels: f64) -> f64 {
        // The level the rebake writes: the 8-bit one by the same table, or the 16-bit
        // encoder's rounding of the f32 it is given.
        let stored = base_colour.map(|c| {
            let level = if levels == 255.0 {
                f64::from(linear_to_srgb8(c))
            } else {
                let encoded = linear_to_srgb(c.clamp(0.0, 1.0)) as f32;
                (f64::from(encoded) * levels + 0.5).floor()
            };
            srgb_to_linear(level / levels)
        });
        let target = Target {
            base_colour: stored,
            roughness: 1.0 - self.glossiness,
            specular_colour: self.specular,
        };
        let sources = draft_readings(self.diffuse, self.specular, self.glossiness);
        worst_over_readings(shader(), &sources, &target)
    }
}

/// A spec-gloss source under each of the drafts' readings.
fn draft_readings(diffuse: [f64; 3], specular: [f64; 3], glossiness: f64) -> Vec<Inputs> {
    SpecGlossReading::DRAFTS
        .iter()
        .map(|&reading| Inputs::specular_glossiness(diffuse, specular, glossiness, reading))
        .collect()
}

/// The evaluator the fits use: no sheen is involved, so the smallest table will do; made
/// once per process.
fn shader() -> &'static Shader {
    static SHADER: std::sync::OnceLock<Shader> = std::sync::OnceLock::new();
    SHADER.get_or_init(|| Shader::new(SheenTable::compute(2, SheenVisibility::Charlie)))
}

/// Fits the 2.0 factors for a spec-gloss source (diffuse, specular, glossiness) whose
/// closed-form conversion is `closed`.
pub fn fit(diffuse: [f64; 3], specular: [f64; 3], glossiness: f64, closed: Target) -> Fit {
    let shader = shader();
    let sources = draft_readings(diffuse, specular, glossiness);
    let cost = |x: [f64; 7]| worst_over_readings(shader, &sources, &Target::from_vector(x));
    let closed_form = cost(closed.to_vector());
    if closed_form <= THRESHOLD {
        return Fit {
            closed_form,
            fitted: None,
        };
    }
    let (best, figure) = nelder_mead(cost, closed.to_vector(), 0.1, 600);
    let fitted = (figure < closed_form - 1e-3).then(|| (Target::from_vector(best), figure));
    Fit {
        closed_form,
        fitted,
    }
}

/// Nelder–Mead simplex minimisation over parameters in 0..1 from `start` with initial
/// steps of `step`, for at most `evaluations` evaluations: derivative-free, as the worst ΔE
/// over readings and directions is a maximum of smooth functions, not smooth itself. The
/// result is clamped to 0..1, as the factors written are, and its figure is its own.
fn nelder_mead<const N: usize>(
    f: impl Fn([f64; N]) -> f64,
    start: [f64; N],
    step: f64,
    evaluations: usize,
) -> ([f64; N], f64) {
    let mut simplex: Vec<([f64; N], f64)> = (0..=N)
        .map(|k| {
            let mut x = start;
            if k > 0 {
                // Step towards the middle of 0..1 so the vertex stays in range.
                x[k - 1] += if x[k - 1] > 0.5 { -step } else { step };
            }
            (x, f(x))
        })
        .collect();
    let mut used = simplex.len();
    while used < evaluations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let worst = simplex[N];
        let centroid: [f64; N] =
            std::array::from_fn(|i| simplex[..N].iter().map(|(x, _)| x[i]).sum::<f64>() / N as f64);
        let towards = |t: f64| -> [f64; N] {
            std::array::from_fn(|i| centroid[i] + t * (worst.0[i] - centroid[i]))
        };
        let reflected = towards(-1.0);
        let reflected_cost = f(reflected);
        used += 1;
        if reflected_cost < simplex[0].1 {
            let expanded = towards(-2.0);
            let expanded_cost = f(expanded);
            used += 1;
            simplex[N] = if expanded_cost < reflected_cost {
                (expanded, expanded_cost)
            } else {
                (reflected, reflected_cost)
            };
        } else if reflected_cost < simplex[N - 1].1 {
            simplex[N] = (reflected, reflected_cost);
        } else {
            let contracted = towards(0.5);
            let contracted_cost = f(contracted);
            used += 1;
            if contracted_cost < worst.1 {
                simplex[N] = (contracted, contracted_cost);
            } else {
                // Shrink every vertex towards the best.
                let best = simplex[0].0;
                for vertex in &mut simplex[1..] {
                    vertex.0 = std::array::from_fn(|i| best[i] + 0.5 * (vertex.0[i] - best[i]));
                    vertex.1 = f(vertex.0);
                    used += 1;
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    let best = simplex[0].0.map(|v| v.clamp(0.0, 1.0));
    (best, f(best))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn closed_form(diffuse: [f64; 3], specular: [f64; 3], glossiness: f64) -> Target {
        Target {
            base_colour: base_colour(diffuse, specular),
            roughness: 1.0 - glossiness,
            specular_colour: specular,
        }
    }

    #[test]
    fn a_closed_form_within_the_threshold_is_kept() {
        // A dark grey plastic: the readings differ by less than one JND.
        let (d, s, g) = ([0.1; 3], [0.04; 3], 0.5);
        let fit = fit(d, s, g, closed_form(d, s, g));
        assert!(fit.closed_form <= THRESHOLD, "{}", fit.closed_form);
        assert!(fit.fitted.is_none());
    }

    #[test]
    fn a_fit_halves_the_worst_reading_and_reports_its_own_figure() {
        // A grey plastic the example-shader reading (no 1 − F) sets apart: closed form 1.05.
        let (d, s, g) = ([0.5, 0.4, 0.3], [0.04; 3], 0.5);
        let fit = fit(d, s, g, closed_form(d, s, g));
        let (target, figure) = fit.fitted.expect("a fit that does better");
        assert!(
            figure < 0.6 * fit.closed_form && figure < THRESHOLD,
            "fitted {figure} against closed form {}",
            fit.closed_form
        );
        // The figure is the fitted factors' own, recomputed here.
        let sources: Vec<Inputs> = SpecGlossReading::DRAFTS
            .iter()
            .map(|&r| Inputs::specular_glossiness(d, s, g, r))
            .collect();
        assert_eq!(worst_over_readings(shader(), &sources, &target), figure);
    }

    #[test]
    fn texel_values_are_judged_once_and_within_their_budgets() {
        // The verify bench's worst texel (closed form 1.11 as stored in 8 bits), one near it
        // one, and a black one.
        let value = |diffuse| TexelValue {
            diffuse,
            specular: [0.0106, 0.0298, 0.0106],
            glossiness: 0.545,
        };
        let (bench, nearby, black) = (
            value([0.807, 0.491, 0.188]),
            value([0.8, 0.49, 0.19]),
            value([0.0; 3]),
        );
        let mut fits = TexelFits::with_budgets(2, 1);
        let chosen = fits.resolve(&[bench, nearby, black, bench], 255.0);
        let report = fits.take_report();
        assert_eq!((report.screened, report.above, report.fitted), (2, 2, 1));
        assert!(report.closed_worst > 1.1 && report.written_worst > THRESHOLD);
        let fitted = chosen[0].expect("judged");
        assert_ne!(fitted, bench.closed_form(), "the first is fitted");
        assert!(bench.cost(fitted, 255.0) <= THRESHOLD);
        assert_eq!(
            chosen[1],
            Some(nearby.closed_form()),
            "past the fits' budget"
        );
        assert_eq!(
            chosen[2], None,
            "past the check's budget: the closed form, unchecked"
        );
        assert_eq!(chosen[3], chosen[0], "a value judged once");
        // Remembered for the rest of the upgrade, with nothing new to report.
        assert_eq!(fits.resolve(&[bench], 255.0), vec![Some(fitted)]);
        assert_eq!(fits.take_report().screened, 0);
    }

    #[test]
    fn each_distinct_material_is_fitted_once_and_only_so_many() {
        let budget = 3;
        let mut fits = Fits::with_budget(budget);
        let (s, g) = ([0.04; 3], 0.5);
        let material = |i: usize| [0.1, 0.1, 0.1 + i as f64 * 1e-4];
        for i in 0..budget {
            let d = material(i);
            assert!(fits.fit(d, s, g, closed_form(d, s, g)).is_some(), "fit {i}");
        }
        let again = material(0);
        assert!(
            fits.fit(again, s, g, closed_form(again, s, g)).is_some(),
            "remembered"
        );
        let one_more = material(budget);
        assert!(
            fits.fit(one_more, s, g, closed_form(one_more, s, g))
                .is_none(),
            "over budget"
        );
    }
}
