//! The fitted conversion of a factor-only 1.0 spec-gloss material. The drafts can be read
//! three ways (see `SpecGlossReading::DRAFTS`), and where their readings disagree (a
//! chromatic specular, or one read with no 1 − F) no closed-form 2.0 material matches all of
//! them. When the closed form's worst ΔE over the readings and the proof's direction pairs is
//! above the proof's threshold, the 2.0 factors (base colour, roughness, specular colour) are
//! fitted to minimise that worst ΔE, the figure the proof reports, and both figures are kept
//! for the conversion report. An upgrade fits each distinct material once and at most
//! [`MAX_DISTINCT_FITS`] of them (about 5 ms each), so that a hostile asset of a million
//! distinct materials cannot make it run for hours.

use crate::shade::brdf::SheenVisibility;
use crate::shade::compare::worst_at_point;
use crate::shade::material::{DiffuseBalance, Inputs, Shader, SpecGlossReading};
use crate::shade::sheen_table::SheenTable;

/// The proof's default threshold: below it the closed form is kept as it is.
const THRESHOLD: f64 = crate::shade::compare::DEFAULT_THRESHOLD;

/// Distinct materials fitted per upgrade; later ones keep their closed form.
pub const MAX_DISTINCT_FITS: usize = 256;

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
    let target = target.inputs();
    sources
        .iter()
        .map(|source| worst_at_point(shader, source, &target))
        .fold(0.0, f64::max)
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
    let sources: Vec<Inputs> = SpecGlossReading::DRAFTS
        .iter()
        .map(|&reading| Inputs::specular_glossiness(diffuse, specular, glossiness, reading))
        .collect();
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

/// Nelder–Mead simplex minimisation from `start` with initial steps of `step`, for at most
/// `evaluations` evaluations: derivative-free, as the worst ΔE over readings and directions
/// is a maximum of smooth functions, not smooth itself.
fn nelder_mead(
    f: impl Fn([f64; 7]) -> f64,
    start: [f64; 7],
    step: f64,
    evaluations: usize,
) -> ([f64; 7], f64) {
    let mut simplex: Vec<([f64; 7], f64)> = (0..=7)
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
        let worst = simplex[7];
        let centroid: [f64; 7] =
            std::array::from_fn(|i| simplex[..7].iter().map(|(x, _)| x[i]).sum::<f64>() / 7.0);
        let towards = |t: f64| -> [f64; 7] {
            std::array::from_fn(|i| centroid[i] + t * (worst.0[i] - centroid[i]))
        };
        let reflected = towards(-1.0);
        let reflected_cost = f(reflected);
        used += 1;
        if reflected_cost < simplex[0].1 {
            let expanded = towards(-2.0);
            let expanded_cost = f(expanded);
            used += 1;
            simplex[7] = if expanded_cost < reflected_cost {
                (expanded, expanded_cost)
            } else {
                (reflected, reflected_cost)
            };
        } else if reflected_cost < simplex[6].1 {
            simplex[7] = (reflected, reflected_cost);
        } else {
            let contracted = towards(0.5);
            let contracted_cost = f(contracted);
            used += 1;
            if contracted_cost < worst.1 {
                simplex[7] = (contracted, contracted_cost);
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
    // The factors written are the clamped ones: report their figure.
    let best = Target::from_vector(simplex[0].0).to_vector();
    (best, f(best))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn closed_form(diffuse: [f64; 3], specular: [f64; 3], glossiness: f64) -> Target {
        Target {
            base_colour: crate::upgrade::spec_gloss::base_colour(diffuse, specular),
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
