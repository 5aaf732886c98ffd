//! The spec-gloss → metal-rough closed form's vocabulary (the source's [`Factors`], read
//! under one [`SpecGlossReading`], and its closed-form base colour) and what improves on it
//! where that reading has no exact 2.0 form: the fitted conversion of a factor-only 1.0
//! spec-gloss material, and of a textured one's base colour texel by texel ([`TexelFits`]).
//! This is the bottom of the mapping: `rebake` and `spec_gloss` build on it.
//!
//! A fit always moves the output towards the one reading the upgrade converts under, never
//! towards a compromise between readings: under the default reading (the drafts' Appendix)
//! the closed form is exact for factors and the fits only settle 8-bit quantisation of
//! rebaked texels; under the example-shader reading (no 1 − F), which no 2.0 material draws
//! exactly, they fit base colour, roughness and specular colour to it. An upgrade fits each
//! distinct material once and at most [`MAX_DISTINCT_FITS`] of them (about 5 ms each), so
//! that a hostile asset of a million distinct materials cannot make it run for hours.

use crate::gltf::color::{linear_to_srgb, linear_to_srgb8, srgb_to_linear};
use crate::shade::brdf::SheenVisibility;
use crate::shade::compare::worst_at_point;
use crate::shade::material::{DiffuseBalance, Inputs, Shader, SpecGlossReading};
use crate::shade::sheen_table::SheenTable;

/// The proof's default threshold: below it the closed form is kept as it is.
const THRESHOLD: f64 = crate::shade::compare::DEFAULT_THRESHOLD;

/// Distinct materials fitted per upgrade; later ones keep their closed form.
pub(super) const MAX_DISTINCT_FITS: usize = 256;

/// A spec-gloss material's factors (diffuse RGBA, specular RGB, glossiness) and the
/// reading its text is converted under.
#[derive(Debug, Clone, Copy)]
pub(super) struct Factors {
    pub diffuse: [f64; 4],
    pub specular: [f64; 3],
    pub glossiness: f64,
    pub reading: SpecGlossReading,
}

impl Factors {
    /// The closed-form base colour of `diffuse` and `specular` under this reading.
    pub(super) fn base_colour(&self, diffuse: [f64; 3], specular: [f64; 3]) -> [f64; 3] {
        self.reading.closed_form_base(diffuse, specular).0
    }
}

/// A metal-rough + KHR_materials_specular + ior 0 material's factors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Target {
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

/// The outcome: the closed form's ΔE under the reading, and the fitted factors with theirs
/// when the fit was needed and did better.
#[derive(Debug, Clone)]
pub(super) struct Fit {
    pub closed_form: f64,
    pub fitted: Option<(Target, f64)>,
}

/// The ΔE of `target` against the spec-gloss `source`.
fn difference(shader: &Shader, source: &Inputs, target: &Target) -> f64 {
    worst_at_point(shader, std::slice::from_ref(source), &target.inputs())
}

/// The fits of one upgrade: each distinct material fitted once, at most
/// [`MAX_DISTINCT_FITS`] of them, towards one reading.
pub(super) struct Fits {
    done: std::collections::HashMap<[u64; 7], Fit>,
    budget: usize,
    reading: SpecGlossReading,
}

impl Fits {
    /// Fits towards `reading`, at most [`MAX_DISTINCT_FITS`] distinct materials.
    pub(super) fn new(reading: SpecGlossReading) -> Fits {
        Fits::with_budget(reading, MAX_DISTINCT_FITS)
    }

    /// At most `budget` distinct materials fitted.
    pub(super) fn with_budget(reading: SpecGlossReading, budget: usize) -> Fits {
        Fits {
            done: Default::default(),
            budget,
            reading,
        }
    }

    /// The reading fitted towards.
    pub(super) fn reading(&self) -> SpecGlossReading {
        self.reading
    }

    /// [`fit`], remembered by the source's factors; None once the budget is spent.
    pub(super) fn fit(
        &mut self,
        diffuse: [f64; 3],
        specular: [f64; 3],
        glossiness: f64,
        closed: Target,
    ) -> Option<Fit> {
        let key = TexelValue {
            diffuse,
            specular,
            glossiness,
        }
        .key();
        if let Some(done) = self.done.get(&key) {
            return Some(done.clone());
        }
        if self.done.len() >= self.budget {
            return None;
        }
        let outcome = fit(diffuse, specular, glossiness, self.reading, closed);
        self.done.insert(key, outcome.clone());
        Some(outcome)
    }
}

/// Distinct texel values whose closed form is evaluated per upgrade (about 5 µs each); texels
/// past it keep the closed form unchecked, so that a photograph's million distinct texels
/// (or a hostile 8192² texture) add well under a second.
pub(super) const MAX_SCREENED_TEXELS: usize = 1 << 16;

/// A texel whose nearest 8-bit levels are this far (ΔE2000) from its source has its
/// neighbouring levels tried: half the proof's threshold, the rest left to what lies between
/// texel centres.
pub(super) const LEVELS_TRIED_ABOVE: f64 = 0.5;

/// How far (ΔE2000, the base colour alone) rounding a base colour to its nearest 8-bit
/// levels may move it before the texel is evaluated in the scene: below it, the scene's
/// figure stays under [`LEVELS_TRIED_ABOVE`] (a test holds this over the colour cube).
pub(super) const ROUNDING_SEEN_ABOVE: f64 = 0.3;

/// Whether rounding `base` to its nearest 8-bit levels moves it more than
/// [`ROUNDING_SEEN_ABOVE`]: a texel of an exact closed form whose rounding does not is not
/// evaluated (an evaluation costs tens of microseconds, this one CIEDE2000).
fn rounding_shows(base: [f64; 3]) -> bool {
    use crate::shade::delta_e::{ciede2000, lab_from_linear_srgb};
    let rounded = base.map(|c| srgb_to_linear(f64::from(linear_to_srgb8(c)) / 255.0));
    ciede2000(lab_from_linear_srgb(base), lab_from_linear_srgb(rounded)) > ROUNDING_SEEN_ABOVE
}

/// Distinct texel values fitted per upgrade (about 0.5 ms each); later ones above the
/// threshold keep the closed form.
pub(super) const MAX_TEXEL_FITS: usize = 1024;

/// Per-texel fits of textured draft spec-gloss materials. Where the rebaked base colour's
/// closed form under the reading, as the PNG stores it, is above the proof's threshold at a
/// texel (8-bit rounding of a dark texel, or a reading with no exact form), the base colour
/// of that texel is fitted to the smallest ΔE under that reading (roughness and specular
/// colour stay the textures' own, which the output reads as they are). Each distinct texel
/// value is evaluated once for the whole upgrade.
pub(super) struct TexelFits {
    done: std::collections::HashMap<[u64; 7], [f64; 3]>,
    /// Whether the rebake keeps the inputs' grid for these fits (a reading without an exact
    /// form, fitted per stored texel) or may refine it first, checking the texels only where
    /// it does not.
    keeps_grid: bool,
    screen_budget: usize,
    fits_left: usize,
    reading: SpecGlossReading,
    /// What the texels rebaked since the last [`TexelFits::take_report`] came to.
    report: TexelReport,
}

/// The figures of one material's texels (distinct texel values, each counted once).
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct TexelReport {
    /// Distinct texel values evaluated.
    pub screened: usize,
    /// Of those, not evaluated in the scene: their rounding does not show (see
    /// [`TexelFits::for_exact_form`]).
    pub unseen_rounding: usize,
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

impl TexelFits {
    /// Fits towards `reading` within [`MAX_SCREENED_TEXELS`] and [`MAX_TEXEL_FITS`].
    pub(super) fn new(reading: SpecGlossReading) -> TexelFits {
        TexelFits::with_budgets(reading, MAX_SCREENED_TEXELS, MAX_TEXEL_FITS)
    }

    /// At most `screened` distinct texel values evaluated and `fits` fitted.
    pub(super) fn with_budgets(
        reading: SpecGlossReading,
        screened: usize,
        fits: usize,
    ) -> TexelFits {
        TexelFits {
            done: Default::default(),
            keeps_grid: true,
            screen_budget: screened,
            fits_left: fits,
            reading,
            report: TexelReport::default(),
        }
    }

    /// The check of a glTF 2.0 asset's rebakes (the archived extension's reading, which has an
    /// exact form): it settles each texel's 8-bit levels where the rebake keeps the inputs'
    /// grid, and leaves a refined grid to the closed form.
    pub(super) fn for_exact_form() -> TexelFits {
        TexelFits {
            keeps_grid: false,
            ..TexelFits::new(SpecGlossReading::ArchivedExtension)
        }
    }

    /// Whether a rebake checked by these fits keeps its inputs' grid (see
    /// [`TexelFits::for_exact_form`]).
    pub(super) fn keeps_grid(&self) -> bool {
        self.keeps_grid
    }

    /// The base colour written for each distinct texel value (linear diffuse, specular,
    /// glossiness, factors applied), in order; `None` for a value past the check's budget,
    /// which keeps the closed form unchecked. A value is judged by what a viewer samples
    /// from the PNG: its sRGB encoding rounded to `levels` (255 or 65535) steps. New values
    /// are evaluated in parallel; which of them are checked and fitted depends only on their
    /// order.
    pub(super) fn resolve(&mut self, values: &[TexelValue], levels: f64) -> Vec<Option<[f64; 3]>> {
        use rayon::prelude::*;
        let new: Vec<&TexelValue> = (values.iter())
            .filter(|v| !self.done.contains_key(&v.key()))
            .take(self.screen_budget.saturating_sub(self.done.len()))
            .collect();
        let reading = self.reading;
        // (the closed form's figure, `None` where its rounding does not show; the figure and
        // base colour of the best 8-bit levels)
        let exact_form = !self.keeps_grid;
        let screened: Vec<(Option<f64>, f64, [f64; 3])> = (new.par_iter())
            .map(|v| {
                let closed = v.closed_form(reading);
                if exact_form && levels == 255.0 && !rounding_shows(closed) {
                    return (None, 0.0, closed);
                }
                let figure = v.cost(closed, levels, reading);
                let (best, base) = match figure > LEVELS_TRIED_ABOVE && levels == 255.0 {
                    true => v.best_levels(closed, figure, reading),
                    false => (figure, closed),
                };
                (Some(figure), best, base)
            })
            .collect();
        let report = &mut self.report;
        report.screened += new.len();
        let mut to_fit = Vec::new();
        for (k, &(closed, figure, _)) in screened.iter().enumerate() {
            report.unseen_rounding += usize::from(closed.is_none());
            report.closed_worst = report.closed_worst.max(closed.unwrap_or(0.0));
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
                let cost = |base: [f64; 3]| new[k].cost(base, levels, reading);
                nelder_mead(cost, screened[k].2, 0.05, 100)
            })
            .collect();
        let mut chosen: Vec<(f64, [f64; 3])> = (screened.iter())
            .map(|&(_, figure, base)| (figure, base))
            .collect();
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
    pub(super) fn unchecked(&mut self, texels: usize) {
        self.report.unscreened += texels;
    }

    /// The figures since the last call, and a fresh start for the next material (the
    /// values evaluated are remembered).
    pub(super) fn take_report(&mut self) -> TexelReport {
        std::mem::take(&mut self.report)
    }
}

/// One texel of a spec-gloss source: linear diffuse and specular colours and glossiness,
/// factors applied.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct TexelValue {
    pub diffuse: [f64; 3],
    pub specular: [f64; 3],
    pub glossiness: f64,
}

impl TexelValue {
    /// Equal exactly for equal values.
    pub(super) fn key(&self) -> [u64; 7] {
        let ([d0, d1, d2], [s0, s1, s2]) = (self.diffuse, self.specular);
        [d0, d1, d2, s0, s1, s2, self.glossiness].map(f64::to_bits)
    }

    fn closed_form(&self, reading: SpecGlossReading) -> [f64; 3] {
        reading.closed_form_base(self.diffuse, self.specular).0
    }

    /// The 8-bit levels around `closed`'s (each channel's nearest, one below and one above)
    /// whose colour is nearest `closed` itself (CIEDE2000 of the base colour, cheap), kept
    /// when the scene under `reading` shows it nearer than the nearest levels (whose ΔE is
    /// `nearest`): that ΔE and the base colour. Rounding each channel alone can turn a
    /// near-grey texel's hue where the eye is most sensitive to it; a neighbouring level
    /// restores it.
    fn best_levels(
        &self,
        closed: [f64; 3],
        nearest: f64,
        reading: SpecGlossReading,
    ) -> (f64, [f64; 3]) {
        use crate::shade::delta_e::{ciede2000, lab_from_linear_srgb};
        let level = closed.map(|c| i32::from(linear_to_srgb8(c)));
        let wanted = lab_from_linear_srgb(closed);
        let candidate = |k: i32| -> [f64; 3] {
            let step = [k % 3, (k / 3) % 3, k / 9].map(|d| d - 1);
            std::array::from_fn(|c| {
                srgb_to_linear(f64::from((level[c] + step[c]).clamp(0, 255)) / 255.0)
            })
        };
        let distance = |base: [f64; 3]| ciede2000(wanted, lab_from_linear_srgb(base));
        let nearest_base = candidate(13);
        let best = (0..27)
            .map(candidate)
            .min_by(|a, b| distance(*a).total_cmp(&distance(*b)))
            .unwrap_or(nearest_base);
        if best == nearest_base {
            return (nearest, closed);
        }
        let figure = self.cost(best, 255.0, reading);
        match figure < nearest {
            true => (figure, best),
            false => (nearest, closed),
        }
    }

    /// The ΔE under `reading` of `base_colour` as the PNG stores it.
    fn cost(&self, base_colour: [f64; 3], levels: f64, reading: SpecGlossReading) -> f64 {
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
        let source =
            Inputs::specular_glossiness(self.diffuse, self.specular, self.glossiness, reading);
        difference(shader(), &source, &target)
    }
}

/// The evaluator the fits use: no sheen is involved, so the smallest table will do; made
/// once per process.
fn shader() -> &'static Shader {
    static SHADER: std::sync::OnceLock<Shader> = std::sync::OnceLock::new();
    SHADER.get_or_init(|| Shader::new(SheenTable::compute(2, SheenVisibility::Charlie)))
}

/// Fits the 2.0 factors for a spec-gloss source (diffuse, specular, glossiness) read as
/// `reading`, whose closed-form conversion is `closed`.
pub(super) fn fit(
    diffuse: [f64; 3],
    specular: [f64; 3],
    glossiness: f64,
    reading: SpecGlossReading,
    closed: Target,
) -> Fit {
    let shader = shader();
    let source = Inputs::specular_glossiness(diffuse, specular, glossiness, reading);
    let cost = |x: [f64; 7]| difference(shader, &source, &Target::from_vector(x));
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
/// over directions is a maximum of smooth functions, not smooth itself. The
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

    fn closed_form(
        diffuse: [f64; 3],
        specular: [f64; 3],
        glossiness: f64,
        reading: SpecGlossReading,
    ) -> Target {
        Target {
            base_colour: reading.closed_form_base(diffuse, specular).0,
            roughness: 1.0 - glossiness,
            specular_colour: specular,
        }
    }

    /// The drafts' own factor cases and the chromatic ones the issue names.
    const MATERIALS: [([f64; 3], [f64; 3], f64); 5] = [
        ([0.6, 0.5, 0.4], [0.2; 3], 0.75),
        ([0.6, 0.3, 0.2], [0.2; 3], 0.7),
        ([0.8; 3], [0.9, 0.1, 0.1], 0.5),
        ([0.5, 0.4, 0.3], [0.04, 0.3, 0.6], 0.9),
        ([0.1; 3], [0.04; 3], 0.2),
    ];

    #[test]
    fn each_reading_is_drawn_exactly_by_its_own_closed_form_where_it_says_so() {
        let mut exact_seen = 0;
        for reading in SpecGlossReading::DRAFTS {
            for (d, s, g) in MATERIALS {
                let (_, exact) = reading.closed_form_base(d, s);
                let figure = fit(d, s, g, reading, closed_form(d, s, g, reading)).closed_form;
                if exact {
                    exact_seen += 1;
                    assert!(figure < 0.05, "{reading:?} {d:?} {s:?}: ΔE {figure}");
                }
            }
        }
        // The Appendix (all five), and the 2016 reading where diffuse · (1 − s)/(1 − max s)
        // stays at most 1 (the achromatic cases).
        assert!(exact_seen >= 5 + 3, "{exact_seen}");
        let (d, s, g) = MATERIALS[2];
        let appendix = SpecGlossReading::DraftAppendix;
        let (base, exact) = appendix.closed_form_base(d, s);
        assert!(exact);
        for (got, want) in base.iter().zip([0.08, 0.72, 0.72]) {
            assert!((got - want).abs() < 1e-12, "{base:?}");
        }
        let figure = fit(d, s, g, appendix, closed_form(d, s, g, appendix)).closed_form;
        assert!(figure < 0.05, "a chromatic specular is exact too: {figure}");
    }

    #[test]
    fn a_reading_with_no_exact_form_is_fitted_towards_itself_and_reports_its_own_figure() {
        // The example shader (no 1 − F): no 2.0 material draws it exactly.
        let reading = SpecGlossReading::DraftExampleShader;
        let (d, s, g) = ([0.5, 0.4, 0.3], [0.04; 3], 0.5);
        assert!(!reading.closed_form_base(d, s).1);
        let fit = fit(d, s, g, reading, closed_form(d, s, g, reading));
        if let Some((target, figure)) = fit.fitted {
            assert!(
                figure < fit.closed_form,
                "{figure} against {}",
                fit.closed_form
            );
            let source = Inputs::specular_glossiness(d, s, g, reading);
            assert_eq!(difference(shader(), &source, &target), figure);
        } else {
            assert!(fit.closed_form <= THRESHOLD, "{}", fit.closed_form);
        }
    }

    /// Rounding each channel of a near-grey texel to its nearest 8-bit level turns its hue
    /// by about one just-noticeable difference; the evaluator's choice among the neighbouring
    /// levels brings it well under half of one, one level away at most per channel.
    #[test]
    fn a_near_grey_texel_takes_the_neighbouring_8_bit_levels_the_evaluator_prefers() {
        let reading = SpecGlossReading::ArchivedExtension;
        let value = TexelValue {
            diffuse: [42, 45, 42].map(|v| srgb_to_linear(f64::from(v) / 255.0)),
            specular: [0.1; 3],
            glossiness: 0.95,
        };
        let closed = value.closed_form(reading);
        let nearest = value.cost(closed, 255.0, reading);
        assert!(nearest > 1.0, "the nearest levels: {nearest}");
        let mut fits = TexelFits::for_exact_form();
        let [Some(base)] = fits.resolve(&[value], 255.0)[..] else {
            panic!("checked");
        };
        let chosen = value.cost(base, 255.0, reading);
        assert!(chosen < 0.5, "the chosen levels: {chosen}");
        for c in 0..3 {
            let (from, to) = (linear_to_srgb8(closed[c]), linear_to_srgb8(base[c]));
            assert!(from.abs_diff(to) <= 1, "channel {c}: {from} → {to}");
        }
        let report = fits.take_report();
        assert_eq!((report.screened, report.above, report.fitted), (1, 0, 0));
        assert!((report.closed_worst - nearest).abs() < 1e-12 && report.written_worst == chosen);
    }

    /// Over the colour cube (every ninth, eleventh and thirteenth level) and a spread of
    /// specular colours and glossiness, a texel whose nearest 8-bit levels move its base
    /// colour by at most [`ROUNDING_SEEN_ABOVE`] shows at most [`LEVELS_TRIED_ABOVE`] in the
    /// scene: the check of an exact closed form may skip it.
    #[test]
    fn a_rounding_that_does_not_move_the_base_colour_does_not_show_in_the_scene() {
        let reading = SpecGlossReading::ArchivedExtension;
        let mut skipped = 0;
        for r in (0..=255u8).step_by(9) {
            for g in (0..=255u8).step_by(11) {
                for b in (0..=255u8).step_by(13) {
                    for (s, glossiness) in [(0.02, 0.2), (0.04, 0.95), (0.1, 0.6), (0.3, 0.95)] {
                        let value = TexelValue {
                            diffuse: [r, g, b].map(|v| srgb_to_linear(f64::from(v) / 255.0)),
                            specular: [s; 3],
                            glossiness,
                        };
                        let closed = value.closed_form(reading);
                        if rounding_shows(closed) {
                            continue;
                        }
                        skipped += 1;
                        let figure = value.cost(closed, 255.0, reading);
                        assert!(figure <= LEVELS_TRIED_ABOVE, "{r} {g} {b} {s}: {figure}");
                    }
                }
            }
        }
        assert!(skipped > 20_000, "most texels are skipped: {skipped}");
    }

    #[test]
    fn texel_values_are_judged_once_and_within_their_budgets() {
        // Texels the 2016 reading cannot be drawn exactly for: its base colour would pass 1.
        let value = |diffuse| TexelValue {
            diffuse,
            specular: [0.6, 0.1, 0.1],
            glossiness: 0.545,
        };
        let (first, nearby, black) = (
            value([0.9, 0.85, 0.8]),
            value([0.8, 0.9, 0.85]),
            value([0.0; 3]),
        );
        let reading = SpecGlossReading::DraftAppendix2016;
        let mut fits = TexelFits::with_budgets(reading, 2, 1);
        let chosen = fits.resolve(&[first, nearby, black, first], 255.0);
        let report = fits.take_report();
        assert_eq!((report.screened, report.above), (2, 2));
        assert!(report.fitted <= 1 && report.closed_worst > THRESHOLD);
        let written = chosen[0].expect("judged");
        assert!(
            first.cost(written, 255.0, reading)
                <= first.cost(first.closed_form(reading), 255.0, reading)
        );
        // Past the fits' budget: the closed form's own or neighbouring 8-bit levels.
        let (kept, closed) = (chosen[1].expect("judged"), nearby.closed_form(reading));
        for c in 0..3 {
            let (from, to) = (linear_to_srgb8(closed[c]), linear_to_srgb8(kept[c]));
            assert!(
                from.abs_diff(to) <= 1,
                "past the fits' budget: {from} → {to}"
            );
        }
        assert!(nearby.cost(kept, 255.0, reading) <= nearby.cost(closed, 255.0, reading));
        assert_eq!(
            chosen[2], None,
            "past the check's budget: the closed form, unchecked"
        );
        assert_eq!(chosen[3], chosen[0], "a value judged once");
        // Remembered for the rest of the upgrade, with nothing new to report.
        assert_eq!(fits.resolve(&[first], 255.0), vec![Some(written)]);
        assert_eq!(fits.take_report().screened, 0);
    }

    #[test]
    fn each_distinct_material_is_fitted_once_and_only_so_many() {
        let budget = 3;
        let reading = SpecGlossReading::DraftExampleShader;
        let mut fits = Fits::with_budget(reading, budget);
        let (s, g) = ([0.04; 3], 0.5);
        let material = |i: usize| [0.5, 0.4, 0.3 + i as f64 * 1e-4];
        let closed = |d| closed_form(d, s, g, reading);
        for i in 0..budget {
            let d = material(i);
            assert!(fits.fit(d, s, g, closed(d)).is_some(), "fit {i}");
        }
        let again = material(0);
        assert!(fits.fit(again, s, g, closed(again)).is_some(), "remembered");
        let one_more = material(budget);
        assert!(
            fits.fit(one_more, s, g, closed(one_more)).is_none(),
            "over budget"
        );
    }
}
