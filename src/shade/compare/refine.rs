//! Where the fixed directions do not look: the specular peak. A smooth material's lobe is
//! a fraction of a degree wide, and two lobes of different widths differ most just off the
//! mirror direction, which no fixed set of eight directions meets. So the points where the
//! fixed set found the largest differences, and the points whose lobes are sharpest (the
//! smallest roughness of either material, base or clearcoat), are searched again over a
//! dense set: views from head-on to 75° (see [`MAX_THETA`]), at three azimuths (an anisotropic lobe is not
//! symmetric about the normal), each with its mirror direction, the mirror offset in four
//! ways by angles from 0.03° to 20° (a GGX lobe of roughness r has its half width near r²
//! radians: the offsets bracket every roughness from 0.02 up, and below that both lobes are
//! narrower than any display's pixel), and a spread of lights over the hemisphere. The
//! worst direction found is then refined by a pattern search that halves its step down to
//! 0.001°. ΔE between two materials changes smoothly with direction outside the lobes, so
//! the spread bounds it there; inside them the offsets and the refinement do.

use super::{delta_at, Angles, Pair, Worst, BACKGROUNDS};
use crate::shade::appearance::{seen, Seen};
use crate::shade::brdf::Geometry;
use crate::shade::delta_e::{ciede2000, lab_from_linear_srgb};
use crate::shade::lanes::Lanes;
use crate::shade::material::{Inputs, Shader};
use crate::shade::tone::displayed;
use std::sync::OnceLock;

/// The most grazing view or light searched, degrees: the fixed set's. Past it a sphere
/// shows the surface as a rim a few hundredths of its radius wide, and a normal map's
/// slightest tilt puts the view under the shading horizon, where every viewer clamps.
pub(super) const MAX_THETA: f64 = 75.0;

/// How many of the points the fixed directions found worst are searched again.
const WORST_POINTS: usize = 4;
/// How many of the points with the sharpest lobes are searched again.
const SHARPEST_POINTS: usize = 2;

/// A point to search, with both materials' inputs there.
#[derive(Clone)]
struct Candidate {
    delta_e: f64,
    uv: [f64; 2],
    /// The point's place in the grid's one pass (see [`Candidates`]).
    order: u64,
    sharpness: f64,
    pair: Box<Pair>,
}

/// The points worth a dense search, gathered as the grid is compared: the distinct pairs
/// of inputs whose fixed directions found the largest ΔE, and those with the sharpest
/// lobes, each pair at the first point (in the order one pass over the grid meets them)
/// that has it, ties going to the earlier point. Neither depends on how the grid's rows
/// are shared among threads, nor on which points a thread knew by their texels: a repeat
/// of a listed pair adds nothing, and lists made apart merge into the list one pass makes.
#[derive(Clone, Default)]
pub(super) struct Candidates {
    worst: Vec<Candidate>,
    sharpest: Vec<Candidate>,
}

/// The smallest roughness a material's lobes have: the sharper, the narrower its peak.
fn lobe_roughness(m: &Inputs) -> f64 {
    let coat = if m.clearcoat > 0.0 {
        m.clearcoat_roughness
    } else {
        1.0
    };
    m.roughness.min(coat)
}

/// Whether rank `a` comes before rank `b`: (a key, smallest first; the order).
fn ranks_before(a: (f64, u64), b: (f64, u64)) -> bool {
    (a.0.total_cmp(&b.0).then(a.1.cmp(&b.1))).is_lt()
}

/// Inserts `candidate` into `list` ranked by `key` then order, keeping `keep`; a pair
/// already listed keeps its earlier point.
fn keep_best(
    list: &mut Vec<Candidate>,
    candidate: Candidate,
    keep: usize,
    key: fn(&Candidate) -> f64,
) {
    if let Some(i) = list.iter().position(|c| c.pair == candidate.pair) {
        if list[i].order <= candidate.order {
            return;
        }
        list.remove(i);
    }
    let rank = |c: &Candidate| (key(c), c.order);
    let at = list.partition_point(|c| ranks_before(rank(c), rank(&candidate)));
    if at < keep {
        list.insert(at, candidate);
        list.truncate(keep);
    }
}

fn by_delta_e(c: &Candidate) -> f64 {
    -c.delta_e
}

fn by_sharpness(c: &Candidate) -> f64 {
    c.sharpness
}

impl Candidates {
    /// Offers the point `order` (at `uv`) whose fixed directions found `delta_e` at most.
    pub(super) fn offer(&mut self, delta_e: f64, uv: [f64; 2], order: u64, pair: &Pair) {
        let sharpness = lobe_roughness(&pair.0).min(lobe_roughness(&pair.1));
        // Ranked against each list's last before the pair is copied: most points are not.
        let wanted = |list: &Vec<Candidate>, keep: usize, key: fn(&Candidate) -> f64, own| {
            list.len() < keep
                || (list.last()).is_some_and(|c| ranks_before((own, order), (key(c), c.order)))
        };
        // A pair listed at an earlier point stays there (see `keep_best`): with few distinct
        // pairs a list never fills, and every point would be copied only to be found listed.
        // Equal inputs give equal figures, so a listed point of another figure is another pair
        // and its inputs need no comparing.
        let listed = |list: &Vec<Candidate>| {
            (list.iter()).any(|c| c.delta_e == delta_e && c.order <= order && *c.pair == *pair)
        };
        let wanted_worst =
            wanted(&self.worst, WORST_POINTS, by_delta_e, -delta_e) && !listed(&self.worst);
        let wanted_sharp = wanted(&self.sharpest, SHARPEST_POINTS, by_sharpness, sharpness)
            && !listed(&self.sharpest);
        if !(wanted_worst || wanted_sharp) {
            return;
        }
        let candidate = Candidate {
            delta_e,
            uv,
            order,
            sharpness,
            pair: Box::new(pair.clone()),
        };
        if wanted_worst {
            keep_best(&mut self.worst, candidate.clone(), WORST_POINTS, by_delta_e);
        }
        if wanted_sharp {
            keep_best(&mut self.sharpest, candidate, SHARPEST_POINTS, by_sharpness);
        }
    }

    /// Both materials' inputs at the point the fixed directions found worst.
    pub(super) fn worst_pair(&self) -> Option<&Pair> {
        self.worst.first().map(|c| &*c.pair)
    }

    /// Takes in another part's candidates.
    pub(super) fn absorb(&mut self, other: &Candidates) {
        for c in other.worst.iter().chain(&other.sharpest) {
            self.offer(c.delta_e, c.uv, c.order, &c.pair);
        }
    }
}

/// The dense direction set, eight pairs at a time.
struct Dense {
    groups: Vec<(Geometry<Lanes<8>>, [Angles; 8])>,
}

fn dense() -> &'static Dense {
    static DENSE: OnceLock<Dense> = OnceLock::new();
    DENSE.get_or_init(|| {
        let angles = dense_angles();
        let groups = angles
            .chunks(8)
            .map(|chunk| {
                let group: [Angles; 8] = std::array::from_fn(|i| chunk[i.min(chunk.len() - 1)]);
                let pairs = group.map(|a| {
                    let (v, l) = a.vectors();
                    Geometry::new(v, l)
                });
                (Geometry::lanes(&pairs), group)
            })
            .collect();
        Dense { groups }
    })
}

/// The mirror direction of `view` (θ, φ in degrees) and, for each of `offsets`, the four
/// lights that far off it: nearer and further from the normal, and to either side.
fn mirror_lights([theta_v, phi_v]: [f64; 2], offsets: &[f64]) -> Vec<[f64; 2]> {
    let mirror = [theta_v, phi_v + 180.0];
    let mut lights = vec![mirror];
    for &delta in offsets {
        for theta in [theta_v - delta, theta_v + delta] {
            lights.push(match theta < 0.0 {
                true => [-theta, phi_v],
                false => [theta, mirror[1]],
            });
        }
        let across = delta / theta_v.to_radians().sin().max(delta.to_radians().sin());
        lights.push([theta_v.max(delta), mirror[1] + across]);
        lights.push([theta_v.max(delta), mirror[1] - across]);
    }
    lights
}

/// The specular peak for fitting factors: the mirror direction of views from head-on to
/// [`MAX_THETA`] and lights just off it (a fit needs the peak, not the whole dense set).
pub(super) fn peak_angles() -> &'static [Angles] {
    static PEAK: OnceLock<Vec<Angles>> = OnceLock::new();
    PEAK.get_or_init(|| {
        let views = [0.0, 30.0, 50.0, 65.0, MAX_THETA];
        (views.into_iter())
            .flat_map(|theta| {
                let view = [theta, 0.0];
                (mirror_lights(view, &[0.3, 1.0, 3.0, 8.0]).into_iter())
                    .filter(|light| light[0] <= MAX_THETA)
                    .map(move |light| Angles { view, light })
            })
            .collect()
    })
}

/// Views × (mirror, mirror offsets, spread), as the module's documentation gives them.
fn dense_angles() -> Vec<Angles> {
    const THETA_V: [f64; 8] = [0.0, 15.0, 30.0, 40.0, 50.0, 60.0, 68.0, 75.0];
    const OFFSETS: [f64; 7] = [0.03, 0.1, 0.3, 1.0, 3.0, 8.0, 20.0];
    const SPREAD_THETA: [f64; 5] = [0.0, 20.0, 40.0, 60.0, 75.0];
    let mut out = Vec::new();
    for theta_v in THETA_V {
        let azimuths: &[f64] = if theta_v == 0.0 {
            &[0.0]
        } else {
            &[0.0, 45.0, 90.0]
        };
        for &phi_v in azimuths {
            let mut lights = mirror_lights([theta_v, phi_v], &OFFSETS);
            for theta in SPREAD_THETA {
                let count = if theta == 0.0 { 1 } else { 6 };
                lights.extend((0..count).map(|k| [theta, phi_v + 60.0 * k as f64]));
            }
            out.extend(
                (lights.into_iter())
                    .filter(|light| light[0] <= MAX_THETA)
                    .map(|light| Angles {
                        view: [theta_v, phi_v],
                        light,
                    }),
            );
        }
    }
    out
}

/// The worst sample the dense search and its refinement find.
pub(super) struct Found {
    pub worst: Worst,
    pub pair: Box<Pair>,
}

/// The point near `candidate` (within half a texel of the grid, in quarter-texel steps)
/// where the fixed directions find the largest difference: a conversion that is not linear
/// in its texels differs most somewhere between a texel's centre and its corner, and where
/// depends on the colours (CIELAB is more sensitive in the dark).
fn nearby_worst(
    shader: &Shader,
    candidate: &Candidate,
    texel: f64,
    at: &dyn Fn([f64; 2]) -> Option<Pair>,
) -> Candidate {
    let coarse = super::DIRECTIONS.map(Angles::coarse);
    let worst_of = |pair: &Pair| {
        (coarse.iter())
            .map(|angles| delta_at(shader, &pair.0, &pair.1, angles).0)
            .fold(0.0, f64::max)
    };
    let mut best = candidate.clone();
    best.delta_e = worst_of(&best.pair);
    let steps = [-0.5, -0.25, 0.0, 0.25, 0.5];
    for dy in steps {
        for dx in steps {
            // Textures repeat: the point is named inside the unit square.
            let uv = [
                (candidate.uv[0] + dx * texel).rem_euclid(1.0),
                (candidate.uv[1] + dy * texel).rem_euclid(1.0),
            ];
            let Some(pair) = at(uv) else {
                return best;
            };
            // The candidate's own inputs (a flat region, a material of factors) give its own
            // figure: nothing to evaluate.
            if pair == *candidate.pair {
                continue;
            }
            let delta_e = worst_of(&pair);
            if delta_e > best.delta_e {
                best = Candidate {
                    delta_e,
                    uv,
                    pair: Box::new(pair),
                    ..*candidate
                };
            }
        }
    }
    best
}

/// The largest ΔE over the dense set at each candidate point (moved to the worst point
/// near it), refined around the worst. `texel` is the grid's spacing, and `at` gives both
/// materials' inputs anywhere.
pub(super) fn search(
    shader: &Shader,
    candidates: &Candidates,
    texel: f64,
    at: &dyn Fn([f64; 2]) -> Option<Pair>,
) -> Option<Found> {
    // A point both among the worst and the sharpest is searched once.
    let listed: Vec<&Candidate> = candidates.worst.iter().collect();
    let again = |c: &Candidate| listed.iter().any(|w| w.uv == c.uv && w.pair == c.pair);
    let sharpest = (candidates.sharpest.iter()).filter(|c| !again(c));
    let moved: Vec<Candidate> = (listed.iter().copied().chain(sharpest))
        .map(|c| nearby_worst(shader, c, texel, at))
        .collect();
    let mut best: Option<(f64, Angles, &Candidate)> = None;
    for candidate in &moved {
        let (a, b) = (&candidate.pair.0, &candidate.pair.1);
        let both = super::translucent(a, b);
        for (geometry, angles) in &dense().groups {
            let (sa, sb) = (seen(shader, a, geometry), seen(shader, b, geometry));
            for (lane, angles) in angles.iter().enumerate() {
                let pick = |s: &Seen<Lanes<8>>| Seen {
                    own: s.own.map(|c| c.0[lane]),
                    through: s.through.map(|c| c.0[lane]),
                };
                let (pa, pb) = (pick(&sa), pick(&sb));
                let backgrounds = if both {
                    &BACKGROUNDS[..]
                } else {
                    &BACKGROUNDS[..1]
                };
                for &background in backgrounds {
                    let d = ciede2000(
                        lab_from_linear_srgb(displayed(pa.over(background))),
                        lab_from_linear_srgb(displayed(pb.over(background))),
                    );
                    if best.as_ref().is_none_or(|(worst, ..)| d > *worst) {
                        best = Some((d, *angles, candidate));
                    }
                }
            }
        }
    }
    let (_, start, candidate) = best?;
    let (a, b) = (&candidate.pair.0, &candidate.pair.1);
    let (angles, (delta_e, background)) = climb(start, |angles| delta_at(shader, a, b, angles));
    Some(Found {
        worst: Worst {
            delta_e,
            sets: Vec::new(),
            behind: false,
            uv: candidate.uv,
            directions: angles,
            background,
        },
        pair: candidate.pair.clone(),
    })
}

/// Climbs from `start` to a local maximum of `f` over (θ_v, φ_v, θ_l, φ_l), halving the step
/// from 1° to 0.001°.
pub(super) fn climb(start: Angles, f: impl Fn(&Angles) -> (f64, f64)) -> (Angles, (f64, f64)) {
    let mut at = start;
    let mut value = f(&at);
    let mut step = 1.0;
    while step >= 1e-3 {
        let mut moved = false;
        for coordinate in 0..4 {
            for sign in [-1.0, 1.0] {
                let mut next = at;
                let slot = match coordinate {
                    0 => &mut next.view[0],
                    1 => &mut next.view[1],
                    2 => &mut next.light[0],
                    _ => &mut next.light[1],
                };
                *slot += sign * step;
                let inside = |theta: f64| (0.0..=MAX_THETA).contains(&theta);
                if !inside(next.view[0]) || !inside(next.light[0]) {
                    continue;
                }
                let candidate = f(&next);
                if candidate.0 > value.0 {
                    (at, value, moved) = (next, candidate, true);
                }
            }
        }
        if !moved {
            step /= 2.0;
        }
    }
    (at, value)
}

/// Gives the first material the second's value of one input.
type Take = fn(&mut Inputs, &Inputs);

/// Each input a comparison can name, and how to give a material the other's value of it.
const INPUTS: [(&str, Take); 18] = [
    ("base colour", |a, b| a.base_color = b.base_color),
    ("coverage", |a, b| a.coverage = b.coverage),
    ("metallic", |a, b| a.metallic = b.metallic),
    ("roughness", |a, b| a.roughness = b.roughness),
    ("specular", |a, b| {
        a.specular = b.specular;
        a.specular_color = b.specular_color;
    }),
    ("ior", |a, b| a.ior = b.ior),
    ("sheen", |a, b| {
        a.sheen_color = b.sheen_color;
        a.sheen_roughness = b.sheen_roughness;
    }),
    ("anisotropy", |a, b| {
        a.anisotropy_strength = b.anisotropy_strength;
        a.anisotropy_angle = b.anisotropy_angle;
    }),
    ("emission", |a, b| a.emission = b.emission),
    ("occlusion", |a, b| a.occlusion = b.occlusion),
    ("normal", |a, b| a.normal = b.normal),
    ("clearcoat", |a, b| {
        a.clearcoat = b.clearcoat;
        a.clearcoat_roughness = b.clearcoat_roughness;
        a.clearcoat_normal = b.clearcoat_normal;
    }),
    ("transmission", |a, b| a.transmission = b.transmission),
    ("volume", |a, b| {
        a.volume_transmittance = b.volume_transmittance
    }),
    ("diffuse transmission", |a, b| {
        a.diffuse_transmission = b.diffuse_transmission;
        a.diffuse_transmission_color = b.diffuse_transmission_color;
    }),
    ("iridescence", |a, b| {
        a.iridescence = b.iridescence;
        a.iridescence_film = b.iridescence_film;
    }),
    ("unlit", |a, b| a.unlit = b.unlit),
    ("diffuse balance", |a, b| {
        a.diffuse_balance = b.diffuse_balance
    }),
];

/// The input whose difference dominates the worst sample: the one that, set to `b`'s
/// value in `a`, removes the most of the difference there. `None` when no single input
/// removes any (the difference is several inputs' together).
pub(crate) fn dominant_input(
    shader: &Shader,
    a: &Inputs,
    b: &Inputs,
    worst: &Worst,
) -> Option<&'static str> {
    let mut best: Option<(&'static str, f64)> = None;
    for (name, take) in INPUTS {
        let mut changed = a.clone();
        take(&mut changed, b);
        if changed == *a {
            continue;
        }
        let left = delta_at(shader, &changed, b, &worst.directions).0;
        let removed = worst.delta_e - left;
        if removed > 0.0 && best.is_none_or(|(_, most)| removed > most) {
            best = Some((name, removed));
        }
    }
    best.map(|(name, _)| name)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points of three pairs (ΔE 3, 2 and 1, the first pair twice), in one pass's order.
    fn points() -> Vec<(f64, u64, Pair)> {
        let pair = |roughness: f64| {
            let inputs = Inputs {
                roughness,
                ..Inputs::default()
            };
            (inputs.clone(), inputs)
        };
        vec![
            (3.0, 0, pair(0.5)),
            (2.0, 1, pair(0.4)),
            (3.0, 2, pair(0.5)),
            (1.0, 3, pair(0.3)),
        ]
    }

    /// Each list's points, by their order.
    fn listed(c: &Candidates) -> [Vec<u64>; 2] {
        [&c.worst, &c.sharpest].map(|list| list.iter().map(|c| c.order).collect())
    }

    fn offered(points: &[(f64, u64, Pair)]) -> Candidates {
        let mut c = Candidates::default();
        for (delta_e, order, pair) in points {
            c.offer(*delta_e, [0.0; 2], *order, pair);
        }
        c
    }

    #[test]
    fn a_repeat_of_a_listed_pair_adds_nothing() {
        let [worst, sharpest] = listed(&offered(&points()));
        assert_eq!(worst, [0, 1, 3], "the repeat at 2 is the pair listed at 0");
        assert_eq!(sharpest, [3, 1]);
    }

    #[test]
    fn lists_made_apart_merge_into_the_list_one_pass_makes_in_any_order() {
        let all = points();
        let whole = offered(&all);
        for split in 0..=all.len() {
            let (first, second) = (offered(&all[..split]), offered(&all[split..]));
            for (mut into, from) in [(first.clone(), &second), (second.clone(), &first)] {
                into.absorb(from);
                assert_eq!(listed(&into), listed(&whole), "split at {split}");
            }
        }
    }
}
