//! Do two materials render the same? Both are evaluated at points of a UV grid (at least as
//! fine as their finest texture) where their mesh's triangles lie (the whole UV square when
//! that cannot be told): every texel centre and every texel corner, where a
//! bilinear filter mixes four texels and a conversion that is not linear differs most (a
//! corner where both materials' inputs are the mean of the four centres' is a blend of what
//! those centres compared, and is not sampled: see `Centres`). At
//! each point a fixed, stratified set of view/light directions including grazing ones is
//! evaluated; the points where that set finds the largest differences, and those whose
//! specular lobes are sharpest, are then searched over a dense set of directions around
//! each view's mirror direction and beyond, and the worst one refined (`compare/refine.rs`).
//! Each result becomes the colour a viewer shows and the two colours are compared with
//! CIEDE2000.
//!
//! The scene is [`super::appearance`]'s: a directional light of irradiance π at normal
//! incidence, a uniform ambient light, emission, and what shows through from the
//! backgrounds behind a translucent or transmissive surface (both are looked at, so coverage
//! and colour cannot cancel). Unlit materials emit their colour. The radiance is exposed
//! and tone-mapped with Khronos PBR Neutral ([`super::tone`]) before CIELAB, as a viewer
//! shows it: L* stays within 0–100, so ΔE 1 is about one just-noticeable difference on a
//! display. (CIELAB is taken of the tone-mapped linear colour, which is what decoding its
//! sRGB encoding gives back.)

use super::appearance::{seen, transmits, Seen, BACKGROUNDS};
use super::brdf::{Geometry, V3};
use super::delta_e::{ciede2000, lab_from_linear_srgb};
use super::lanes::{Lanes, Real};
use super::material::{is_mean_of, Bent, Inputs, Shader};
use super::sample::{self, MaterialSource, Read, TextureImage};
use super::surface::Meshes;
use super::tone::displayed;
use crate::gltf::coverage::Seen as OnMesh;
use std::sync::Arc;

mod refine;
pub(crate) use refine::dominant_input;

/// The default verdict threshold: ΔE2000 1, about one just-noticeable difference on what a
/// viewer shows (`compare --threshold`, the upgrade proof, the factor fit).
pub const DEFAULT_THRESHOLD: f64 = 1.0;

const DIRECTION_COUNT: usize = 8;

/// (θ_v, θ_l, φ between them), degrees: head-on, off-specular, mirror, crossed (anisotropy)
/// and grazing configurations; the view lies along the tangent (φ_v = 0), which is where an
/// anisotropy angle of 0 points. Every point is evaluated in these; the dense direction
/// search (`compare/refine.rs`) looks further at the points they find worst.
pub const DIRECTIONS: [(f64, f64, f64); DIRECTION_COUNT] = [
    (0.0, 0.0, 0.0),
    (45.0, 45.0, 180.0),
    (45.0, 45.0, 90.0),
    // In the plane of the anisotropy direction, 40° off the mirror: the half-vector tilts
    // 20° along the tangent, inside the stretched lobe (α_t up to 1) and outside the
    // isotropic one.
    (60.0, 20.0, 180.0),
    (75.0, 75.0, 180.0),
    // Light behind the viewer, both grazing: sheen's retro-reflective peak, where the Charlie
    // distribution (half-vector 80° off the normal) is largest.
    (80.0, 80.0, 0.0),
    (85.0, 20.0, 90.0),
    (88.0, 88.0, 180.0),
];

/// Histogram resolution for the percentile (ΔE up to 100 in steps of 0.001).
const BINS: usize = 100_000;
/// Bins per unit of ΔE: a multiplication per sample where a width of 0.001 would divide.
const BINS_PER_UNIT: f64 = 1000.0;
/// The mean's resolution: samples are summed as whole steps of 2⁻³² ΔE (each at most 10⁶).
const SUM_STEPS_PER_UNIT: f64 = (1u64 << 32) as f64;

/// A view and a light direction, each as (θ from the normal, φ from the tangent), degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Angles {
    /// The direction to the viewer.
    pub view: [f64; 2],
    /// The direction to the light.
    pub light: [f64; 2],
}

impl Angles {
    /// The coarse set's pair (θ_v, θ_l, φ): the view at φ 0.
    fn coarse((theta_v, theta_l, phi): (f64, f64, f64)) -> Angles {
        Angles {
            view: [theta_v, 0.0],
            light: [theta_l, phi],
        }
    }

    /// The two unit vectors, in the tangent frame.
    pub fn vectors(&self) -> (V3, V3) {
        (direction(self.view), direction(self.light))
    }
}

/// Where the largest difference was found.
#[derive(Debug, Clone, PartialEq)]
pub struct Worst {
    /// Its ΔE2000.
    pub delta_e: f64,
    /// Its texture coordinates (in set 0 for a point on a mesh).
    pub uv: [f64; 2],
    /// For a point on a mesh whose texCoord sets differ, its coordinates in each set; empty
    /// for a point of the UV grid (every set reads `uv` there).
    pub sets: Vec<[f64; 2]>,
    /// Its view and light directions.
    pub directions: Angles,
    /// The radiance of the background it was seen over (see [`BACKGROUNDS`]).
    pub background: f64,
    /// Whether it was seen from behind the surface, where one material draws its back face
    /// and the other culls it.
    pub behind: bool,
}

/// The ΔE2000 figures of one material pair.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Largest ΔE2000, over every point and the directions searched there.
    pub max: f64,
    /// 99th percentile ΔE2000 of the fixed directions at every point sampled (texel centres,
    /// and the corners that are not blends of their centres).
    pub p99: f64,
    /// Mean ΔE2000 of the fixed directions at every point sampled.
    pub mean: f64,
    /// Where the largest was.
    pub worst: Worst,
    /// The input whose difference dominates the worst sample ("base colour", "coverage",
    /// "emission", …): setting it to the second material's there removes most of the
    /// difference. `None` when nothing differs.
    pub dominant: Option<&'static str>,
    /// Grid size per side and the number of (point, direction) samples compared.
    pub grid: u32,
    /// Points × directions evaluated.
    pub samples: u64,
    /// Texel corners not sampled because every side's inputs there are the mean of its four
    /// centres' (a blend of pairs the centres compared; see the module's documentation).
    pub blended_corners: u64,
    /// Where on the UV square the grid was sampled.
    pub area: Area,
    /// Points of the grid (centres and corners) off the mesh's triangles: not sampled.
    pub off_mesh: u64,
    /// The largest ΔE over the directions, per texel (row-major; a texel's centre and its
    /// top-left corner; not a number off the mesh), for heat maps; empty unless
    /// [`TexelMap::Kept`]. Shared: the outcomes
    /// of an asset's many identical pairs hold one map.
    pub per_texel: Arc<[f32]>,
}

impl Comparison {
    /// No comparison: nothing evaluated, no sample taken (a material without a model).
    pub(crate) fn nothing() -> Comparison {
        Comparison {
            max: 0.0,
            p99: 0.0,
            mean: 0.0,
            worst: Worst::nowhere(),
            dominant: None,
            grid: 0,
            samples: 0,
            blended_corners: 0,
            area: Area::Whole("nothing was compared"),
            off_mesh: 0,
            per_texel: Arc::new([]),
        }
    }
}

/// Where on the UV square a comparison's grid is sampled.
#[derive(Debug, Clone, PartialEq)]
pub enum Area {
    /// Where the mesh's triangles lie: the texels of the grid a bilinear sample on them reads
    /// (in every texCoord set either material reads), this many.
    Mesh {
        /// Texels of the grid seen.
        texels: u64,
    },
    /// The whole square, and why (no mesh draws the material, its texture coordinates
    /// cannot be read, …).
    Whole(&'static str),
}

impl Worst {
    /// The first point and direction, where a comparison that finds no difference says it was.
    fn nowhere() -> Worst {
        Worst {
            delta_e: 0.0,
            sets: Vec::new(),
            behind: false,
            uv: [0.0, 0.0],
            directions: Angles::coarse(DIRECTIONS[0]),
            background: BACKGROUNDS[0],
        }
    }
}

/// Whether a comparison keeps its per-texel map, for a heat map: grid² floats (16 MB for a
/// 2048² texture), which a proof of 10^3 distinct materials could not hold for each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum TexelMap {
    /// Kept in [`Comparison::per_texel`].
    Kept,
    /// Not kept: `per_texel` is empty.
    Dropped,
}

/// A unit direction from (θ, φ) in degrees.
fn direction([theta, phi]: [f64; 2]) -> V3 {
    let (t, p) = (theta.to_radians(), phi.to_radians());
    [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
}

/// Both materials' inputs at one point.
pub(crate) type Pair = (Inputs, Inputs);

/// One point's colours for every direction pair, channel by channel, direction per lane:
/// the radiance over black (RGB), then the share of the background shown (RGB).
type Colours = [Lanes<DIRECTION_COUNT>; 6];

/// The fixed direction pairs, evaluated together (one per lane).
struct Directions {
    geometry: Geometry<Lanes<DIRECTION_COUNT>>,
    angles: [Angles; DIRECTION_COUNT],
}

impl Directions {
    fn new() -> Directions {
        let angles = DIRECTIONS.map(Angles::coarse);
        let pairs = angles.map(|a| {
            let (v, l) = a.vectors();
            Geometry::new(v, l)
        });
        Directions {
            geometry: Geometry::lanes(&pairs),
            angles,
        }
    }

    /// What a viewer sees of a material in each direction pair.
    #[inline(always)]
    fn colours(&self, shader: &Shader, m: &Inputs) -> Colours {
        let Seen { own, through } = seen(shader, m, &self.geometry);
        [own[0], own[1], own[2], through[0], through[1], through[2]]
    }
}

/// Whether either material lets the background show: then both backgrounds are looked at.
fn translucent(a: &Inputs, b: &Inputs) -> bool {
    a.coverage < 1.0 || b.coverage < 1.0 || transmits(a) || transmits(b)
}

/// ΔE2000 between what a viewer sees of two materials' [`Seen`] values over `background`.
#[inline(always)]
fn delta_over(a: &Seen<f64>, b: &Seen<f64>, background: f64) -> f64 {
    ciede2000(
        lab_from_linear_srgb(displayed(a.over(background))),
        lab_from_linear_srgb(displayed(b.over(background))),
    )
}

/// The largest ΔE2000 between `a` and `b` for one direction pair, over the backgrounds that
/// matter, and the background it was found over.
pub(crate) fn delta_at(shader: &Shader, a: &Inputs, b: &Inputs, angles: &Angles) -> (f64, f64) {
    let (v, l) = angles.vectors();
    let g = Geometry::new(v, l);
    let (sa, sb) = (seen(shader, a, &g), seen(shader, b, &g));
    let backgrounds = if translucent(a, b) {
        &BACKGROUNDS[..]
    } else {
        &BACKGROUNDS[..1]
    };
    (backgrounds.iter())
        .map(|&background| (delta_over(&sa, &sb, background), background))
        .reduce(|worst, each| if each.0 > worst.0 { each } else { worst })
        .unwrap_or((0.0, BACKGROUNDS[0]))
}

/// The fixed direction pairs and the specular peak's (the mirror direction of views from
/// head-on to 75°, and just off it), in lanes: what one point is judged in outside the grid.
struct PointDirections {
    angles: Vec<Angles>,
    /// `angles` a lane each, the last repeated to fill the last group.
    groups: Vec<Geometry<Lanes<DIRECTION_COUNT>>>,
}

fn point_directions() -> &'static PointDirections {
    static SET: std::sync::OnceLock<PointDirections> = std::sync::OnceLock::new();
    SET.get_or_init(|| {
        let angles: Vec<Angles> = (DIRECTIONS.map(Angles::coarse).iter())
            .chain(refine::peak_angles())
            .copied()
            .collect();
        let groups = (angles.chunks(DIRECTION_COUNT))
            .map(|group| {
                let lane = |i: usize| {
                    let (v, l) = group[i.min(group.len() - 1)].vectors();
                    Geometry::new(v, l)
                };
                Geometry::lanes(&std::array::from_fn(lane))
            })
            .collect();
        PointDirections { angles, groups }
    })
}

/// ΔE2000 between `a` and `b` in each of the [`point_directions`] (over the backgrounds that
/// matter), as [`delta_at`] gives them one at a time, computed lane-wise.
fn deltas_at_point(shader: &Shader, a: &Inputs, b: &Inputs) -> Vec<f64> {
    let set = point_directions();
    let (mut colours_a, mut colours_b) = ([[0.0; BATCH]; 6], [[0.0; BATCH]; 6]);
    let mut deltas = Vec::with_capacity(set.groups.len() * DIRECTION_COUNT);
    for batch in set.groups.chunks(BATCH_TEXELS) {
        for (slot, geometry) in batch.iter().enumerate() {
            let colours = |m: &Inputs| {
                let Seen { own, through } = seen(shader, m, geometry);
                [own[0], own[1], own[2], through[0], through[1], through[2]]
            };
            Batch::put(&mut colours_a, slot, colours(a));
            Batch::put(&mut colours_b, slot, colours(b));
        }
        let each = delta_e_of(&colours_a, &colours_b, translucent(a, b));
        deltas.extend_from_slice(&each[..batch.len() * DIRECTION_COUNT]);
    }
    deltas.truncate(set.angles.len());
    deltas
}

/// The largest ΔE2000 between any of `sources` and `target` at one point, over the fixed
/// direction pairs and the specular peak: what a fit of factors minimises. Without the peak
/// a fit trades roughness for the fixed directions' figures and misses the highlight the
/// proof's dense search then finds.
pub(crate) fn worst_at_point(shader: &Shader, sources: &[Inputs], target: &Inputs) -> f64 {
    (sources.iter())
        .flat_map(|source| deltas_at_point(shader, source, target))
        .fold(0.0, f64::max)
}

/// Where two materials differ most at `points` on a mesh (each its UV per texCoord set): each
/// point in the fixed directions and at the specular peak, the worst refined by a climb over
/// the directions. When that exceeds `result`'s maximum, `result` takes it as its worst (and
/// its dominant input); its grid statistics (p99, mean) are kept.
pub(crate) fn on_surface(
    shader: &Shader,
    a: &MaterialSource,
    b: &MaterialSource,
    points: &[Vec<[f64; 2]>],
    result: &mut Comparison,
) {
    let mut best: Option<(f64, Angles, usize, Pair)> = None;
    let angles = &point_directions().angles;
    for (i, point) in points.iter().enumerate() {
        let pair = (a.inputs_at(point), b.inputs_at(point));
        for (d, angles) in deltas_at_point(shader, &pair.0, &pair.1)
            .into_iter()
            .zip(angles)
        {
            if best.as_ref().is_none_or(|(worst, ..)| d > *worst) {
                best = Some((d, *angles, i, pair.clone()));
            }
        }
    }
    let Some((_, start, i, pair)) = best else {
        return;
    };
    let (directions, (delta_e, background)) =
        refine::climb(start, |angles| delta_at(shader, &pair.0, &pair.1, angles));
    if delta_e <= result.max {
        return;
    }
    let worst = Worst {
        delta_e,
        uv: points[i][0],
        sets: points[i].clone(),
        behind: false,
        directions,
        background,
    };
    result.dominant = dominant_input(shader, &pair.0, &pair.1, &worst);
    result.max = delta_e;
    result.worst = worst;
}

/// Distinct points whose samples are converted to ΔE together.
const BATCH_TEXELS: usize = 8;
const BATCH: usize = BATCH_TEXELS * DIRECTION_COUNT;

/// How many 8-byte words (keys and samples) a [`Memo`] holds before it starts again: 16 MiB,
/// about 130 thousand points of a material with a few 8-bit textures, fewer where a point
/// reads many wide texels.
const MEMO_WORDS: usize = 1 << 21;

/// Texel centres already sampled, by the stored texels both materials read there: a
/// texture's repeated values (its flat regions, a palette, a pattern's rows) are sampled
/// once. Equal texels give equal inputs, so a repeat's samples are exactly its first's.
///
/// A repeat is only counted where it is found; its samples join the figures, times the
/// count, when the memo is full or the pass ends (the figures are sums and counts, so the
/// order does not matter). Lookups so touch the keys, a few words per entry, and not the
/// samples.
struct Memo {
    /// Entry numbers, by their key's hash.
    table: hashbrown::HashTable<u32>,
    /// Words per key (a material's keys all have one length).
    width: usize,
    /// Each entry's key words and then how many repeats found it since its samples were
    /// last counted.
    keys: Vec<u64>,
    /// Each entry's samples.
    samples: Vec<[f64; DIRECTION_COUNT]>,
    /// Lookups and hits since the hit rate was last looked at.
    lookups: u32,
    hits: u32,
    /// Centres left before the memo is consulted again (see [`Memo::consulted`]), and the
    /// length of the last rest.
    resting: u32,
    rest: u32,
}

/// Lookups between two looks at a [`Memo`]'s hit rate.
const MEMO_WINDOW: u32 = 1 << 12;
/// A window that hits fewer than one lookup in this many rests the memo: a lookup that
/// misses (a cache miss into a large table, and the entry put) costs about what sampling a
/// point saves, so texels that rarely repeat (a photograph's) are sampled without it.
const MEMO_MISS_RATIO: u32 = 4;
/// The longest rest, in centres: each window of few hits in a row doubles the rest from
/// one window's length, and one that never pays costs a window in seventeen.
const MEMO_REST: u32 = 1 << 16;
/// Entries a memo holds before its hit rate is judged: one still filling with a texture's
/// first values (each thread's first rows) misses most lookups however much the texture
/// repeats later.
const MEMO_WARM: usize = 8 * MEMO_WINDOW as usize;

impl Memo {
    fn new() -> Memo {
        Memo {
            table: hashbrown::HashTable::new(),
            width: 0,
            keys: Vec::new(),
            samples: Vec::new(),
            lookups: 0,
            hits: 0,
            resting: 0,
            rest: 0,
        }
    }

    /// Whether the next centre is looked up (and, if not found, remembered): not while the
    /// memo rests after a window of few hits. Either way a centre's samples are the same
    /// (a repeat's are exactly its first's): only the time differs.
    fn consulted(&mut self) -> bool {
        if self.resting > 0 {
            self.resting -= 1;
            return false;
        }
        true
    }

    /// Counts a lookup; after a window of few hits the memo rests.
    fn count(&mut self, hit: bool) {
        self.lookups += 1;
        self.hits += u32::from(hit);
        if self.lookups == MEMO_WINDOW {
            let cold = self.table.len() < MEMO_WARM;
            self.rest = match !cold && self.hits * MEMO_MISS_RATIO < MEMO_WINDOW {
                true => (self.rest * 2).clamp(MEMO_WINDOW, MEMO_REST),
                false => 0,
            };
            self.resting = self.rest;
            (self.lookups, self.hits) = (0, 0);
        }
    }

    /// A multiply-rotate hash: the words are texels, not chosen by an adversary who could
    /// profit from clashes (a clash costs a comparison, never a wrong answer).
    fn hash(key: &[u64]) -> u64 {
        let mixed = key.iter().fold(0u64, |h, &w| {
            (h.rotate_left(26) ^ w).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        });
        mixed ^ mixed >> 29
    }

    /// Words per entry in `keys`: its key's, then its count of repeats.
    fn stride(&self) -> usize {
        self.width + 1
    }

    /// An entry's key words and its count of repeats.
    fn entry(&self, entry: u32) -> &[u64] {
        let at = entry as usize * self.stride();
        &self.keys[at..at + self.stride()]
    }

    /// The entry of `key`, if it is held.
    fn find(&self, key: &[u64]) -> Option<u32> {
        if key.len() != self.width {
            return None;
        }
        // Word by word: keys are a few words, and a slice comparison calls `memcmp`.
        let equal = |&e: &u32| self.entry(e).iter().zip(key).all(|(a, b)| a == b);
        let found = (self.table).find(Memo::hash(key), equal);
        found.copied()
    }

    /// Counts `times` more repeats of `entry`.
    fn repeated(&mut self, entry: u32, times: u32) {
        let count = (entry as usize + 1) * self.stride() - 1;
        self.keys[count] += u64::from(times);
    }

    fn samples(&self, entry: u32) -> [f64; DIRECTION_COUNT] {
        self.samples[entry as usize]
    }

    /// Adds every entry's counted repeats to `partial`'s figures, and starts their counts
    /// again.
    fn count_into(&mut self, partial: &mut Partial) {
        let stride = self.stride();
        for (entry, samples) in self.keys.chunks_exact_mut(stride).zip(&self.samples) {
            let repeats = &mut entry[stride - 1];
            if *repeats > 0 {
                // At most one per centre of a grid of 4096², well within 32 bits.
                partial.count(samples, *repeats as u32);
                *repeats = 0;
            }
        }
    }

    /// Holds `key`'s samples (unless it is held, or has another width). A full memo adds its
    /// repeats to `partial` and starts again.
    fn put(&mut self, key: &[u64], samples: [f64; DIRECTION_COUNT], partial: &mut Partial) {
        if self.width == 0 {
            self.width = key.len();
        }
        if key.len() != self.width || key.is_empty() || self.find(key).is_some() {
            return;
        }
        let stride = self.stride();
        if self.keys.len() + stride + (self.samples.len() + 1) * DIRECTION_COUNT > MEMO_WORDS {
            self.count_into(partial);
            self.table.clear();
            self.keys.clear();
            self.samples.clear();
        }
        let keys = &self.keys;
        let rehash = |&e: &u32| Memo::hash(&keys[e as usize * stride..][..stride - 1]);
        let entry = self.samples.len() as u32;
        self.table.insert_unique(Memo::hash(key), entry, rehash);
        self.keys.extend_from_slice(key);
        self.keys.push(0);
        self.samples.push(samples);
    }
}

/// The textures whose stored texels make one side's part of a centre's key, listed once
/// for a pass (see [`MaterialSource::keyed_textures`]).
struct Keyed<'a>(Vec<&'a TextureImage>);

impl<'a> Keyed<'a> {
    fn of(material: &'a MaterialSource, left_out: &[bool]) -> Keyed<'a> {
        Keyed(material.keyed_textures(left_out))
    }

    /// The stored texels read at the centre of texel (x, y), packed into `words`: every
    /// centre has fields of the same widths in the same order, so two centres have equal
    /// words exactly when they read equal texels.
    #[inline(always)]
    fn words(&self, x: u32, y: u32, words: &mut Vec<u64>) {
        let mut free = 0;
        let mut push = |field: u64, bits: u32| {
            if bits > free {
                words.push(0);
                free = 64;
            }
            if let Some(word) = words.last_mut() {
                *word |= field << (64 - free);
            }
            free -= bits;
        };
        for texture in &self.0 {
            texture.stored_fields(x, y, &mut push);
        }
    }
}

/// A batch's colours, channel by channel, sample by sample (point-major), the points'
/// inputs (for the search of [`refine`]), and the points sampled before.
struct Batch {
    a: [[f64; BATCH]; 6],
    b: [[f64; BATCH]; 6],
    /// Whether a point of the batch lets the background show.
    translucent: bool,
    pairs: Vec<Pair>,
    /// Each slot's texel key (empty but for a centre whose memo was consulted), as a range
    /// of `key_words`.
    keys: Vec<std::ops::Range<usize>>,
    key_words: Vec<u64>,
    memo: Memo,
    /// The key of the point at hand.
    key: Vec<u64>,
}

impl Batch {
    fn new() -> Batch {
        Batch {
            a: [[0.0; BATCH]; 6],
            b: [[0.0; BATCH]; 6],
            translucent: false,
            pairs: Vec::with_capacity(BATCH_TEXELS),
            keys: Vec::with_capacity(BATCH_TEXELS),
            key_words: Vec::new(),
            memo: Memo::new(),
            key: Vec::new(),
        }
    }

    fn put(colours: &mut [[f64; BATCH]; 6], slot: usize, c: Colours) {
        let at = slot * DIRECTION_COUNT;
        for (channel, lanes) in colours.iter_mut().zip(c) {
            channel[at..at + DIRECTION_COUNT].copy_from_slice(&lanes.0);
        }
    }

    /// Makes the key of the centre of texel (x, y) as reading `a` reads it (`key_b`: the
    /// other material's words), and gives its memo entry if it has one.
    fn known(&mut self, a: &Keyed, x: u32, y: u32, key_b: &[u64]) -> Option<u32> {
        self.key.clear();
        a.words(x, y, &mut self.key);
        self.key.extend_from_slice(key_b);
        let found = self.memo.find(&self.key);
        self.memo.count(found.is_some());
        found
    }

    /// Shades a pair of inputs in the next slot of `row`: both sides' colours in every
    /// direction, the pair (for the search around the worst), and the point's texel key
    /// when it is `keyed` (a centre read as stored, remembered once its samples are known).
    #[inline(always)]
    fn shade(
        &mut self,
        row: &mut Row,
        shader: &Shader,
        directions: &Directions,
        source: Inputs,
        target: &Inputs,
    ) -> Source {
        let slot = row.unique;
        Batch::put(&mut self.a, slot, directions.colours(shader, &source));
        Batch::put(&mut self.b, slot, directions.colours(shader, target));
        self.translucent |= translucent(&source, target);
        let inputs = (source, target.clone());
        self.pairs.push(inputs.clone());
        let start = self.key_words.len();
        self.key_words.extend_from_slice(&self.key);
        self.keys.push(start..self.key_words.len());
        row.unique += 1;
        row.previous = Some((Some(inputs), Source::Slot(slot)));
        Source::Slot(slot)
    }

    /// ΔE2000 of every sample (see [`delta_e_of`]).
    #[inline(always)]
    fn delta_e(&self) -> [f64; BATCH] {
        delta_e_of(&self.a, &self.b, self.translucent)
    }
}

/// ΔE2000 of every sample of two batches of colours (over both backgrounds when
/// `translucent`): one scalar formula in a loop over independent samples, which the
/// compiler turns into vector code (its long dependency chains then overlap).
#[inline(always)]
fn delta_e_of(a: &[[f64; BATCH]; 6], b: &[[f64; BATCH]; 6], translucent: bool) -> [f64; BATCH] {
    let mut out = [0.0; BATCH];
    let over = |colours: &[[f64; BATCH]; 6], i: usize, background: f64| -> V3 {
        std::array::from_fn(|c| colours[c][i] + colours[c + 3][i] * background)
    };
    let backgrounds = if translucent {
        &BACKGROUNDS[..]
    } else {
        &BACKGROUNDS[..1]
    };
    for &background in backgrounds {
        for (i, delta) in out.iter_mut().enumerate() {
            let d = ciede2000(
                lab_from_linear_srgb(displayed(over(a, i, background))),
                lab_from_linear_srgb(displayed(over(b, i, background))),
            );
            *delta = delta.max(d);
        }
    }
    out
}

/// One comparison: the readings of the first material, the second material, the grid
/// size and the direction pairs.
struct Job<'a> {
    shader: &'a Shader,
    readings: &'a [MaterialSource],
    b: &'a MaterialSource,
    grid: u32,
    directions: Directions,
    map: TexelMap,
    /// The texels on the mesh (None: the whole square).
    on_mesh: Option<OnMesh>,
}

struct Partial {
    /// `None` when the map is [`TexelMap::Dropped`].
    per_texel: Option<Vec<f32>>,
    /// The samples' sum in steps of 1 / [`SUM_STEPS_PER_UNIT`]: integers add up to the same total
    /// however the grid's rows are shared among threads, floating-point numbers do not.
    sum: u128,
    count: u64,
    blended: u64,
    off_mesh: u64,
    worst: Worst,
    histogram: Histogram,
    candidates: refine::Candidates,
}

/// Samples counted by ΔE in bins of 1 / [`BINS_PER_UNIT`], the last bin holding everything
/// from ΔE 100 on. Held only as far as the largest bin used: a comparison whose ΔE stays small
/// (a material with itself, each of an asset's 10⁴ materials) neither clears nor merges all
/// [`BINS`] of them.
#[derive(Debug, Default, PartialEq)]
struct Histogram(Vec<u32>);

impl Histogram {
    #[inline(always)]
    fn add(&mut self, delta: f64, samples: u32) {
        let bin = ((delta * BINS_PER_UNIT) as usize).min(BINS - 1);
        if bin >= self.0.len() {
            self.0.resize(bin + 1, 0);
        }
        self.0[bin] += samples;
    }

    /// Adds its counts to `totals`, bin by bin (growing it to its length).
    fn add_to(&self, totals: &mut Vec<u64>) {
        if totals.len() < self.0.len() {
            totals.resize(self.0.len(), 0);
        }
        for (total, n) in totals.iter_mut().zip(&self.0) {
            *total += u64::from(*n);
        }
    }
}

/// The finest UV grid compared: 4096² texels (each its centre and a corner) × every
/// direction is already minutes.
pub(crate) const MAX_GRID: u32 = 4096;

/// Compares `a` with `b` over the whole UV square on a `grid`² UV grid (texel centres and
/// corners, at most [`MAX_GRID`]); `grid` 0 picks the finest texture resolution of either (at
/// least 16).
#[cfg(test)]
pub(crate) fn compare(
    shader: &Shader,
    a: &MaterialSource,
    b: &MaterialSource,
    grid: u32,
) -> Comparison {
    let whole = Meshes::default();
    let mut each = compare_readings(
        shader,
        std::slice::from_ref(a),
        b,
        grid,
        TexelMap::Kept,
        &whole,
    );
    each.pop().unwrap_or_else(Comparison::nothing)
}

/// Compares each of `readings` (one material read several ways: the same textures and
/// texture coordinates) with `b`, in one pass over the grid: `b` is sampled once per point
/// for all of them, where `meshes`' triangles lie. One comparison per reading, in order; the
/// grid is `grid`² (0: the finest texture resolution of either side, at least 16; at most
/// [`MAX_GRID`]).
pub(crate) fn compare_readings(
    shader: &Shader,
    readings: &[MaterialSource],
    b: &MaterialSource,
    grid: u32,
    map: TexelMap,
    meshes: &Meshes,
) -> Vec<Comparison> {
    if readings.is_empty() {
        return Vec::new();
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
    compare_on_threads(shader, readings, b, (grid, meshes), map, threads)
}

/// [`compare_readings`] with the grid's rows shared among `threads`: the figures are the
/// same for any number (see `refine::Candidates`).
fn compare_on_threads(
    shader: &Shader,
    readings: &[MaterialSource],
    b: &MaterialSource,
    (grid, meshes): (u32, &Meshes),
    map: TexelMap,
    threads: u32,
) -> Vec<Comparison> {
    let grid = chosen_grid(readings, b, grid);
    let mut sets: Vec<usize> = (readings.iter().chain([b]))
        .flat_map(MaterialSource::texcoord_sets)
        .collect();
    sets.sort_unstable();
    sets.dedup();
    let (on_mesh, area) = match meshes.seen(&sets, grid) {
        Ok(seen) => {
            let texels = seen.count() as u64;
            // A mesh over every texel leaves nothing to pass over: no point asks the mask.
            let partial = texels < u64::from(grid) * u64::from(grid);
            (partial.then_some(seen), Area::Mesh { texels })
        }
        Err(why) => (None, Area::Whole(why)),
    };
    let job = Job {
        shader,
        readings,
        b,
        grid,
        directions: Directions::new(),
        map,
        on_mesh,
    };
    let rows_per_thread = grid.div_ceil(threads.max(1));
    let by_thread: Vec<Vec<Partial>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let rows = (t * rows_per_thread)..((t + 1) * rows_per_thread).min(grid);
                let job = &job;
                scope.spawn(move || compare_rows(job, rows))
            })
            .collect();
        // A worker's panic is the comparison's: its rows must not silently go missing.
        let joined = handles.into_iter().map(|h| h.join());
        joined
            .map(|rows| rows.unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
            .collect()
    });
    (0..readings.len())
        .map(|r| {
            let partials = by_thread.iter().filter_map(|each| each.get(r));
            let reading = &readings[r];
            let at = |uv: [f64; 2]| Some((reading.inputs_at(&[uv]), b.inputs_at(&[uv])));
            merge(shader, partials, (grid, area.clone()), &at)
        })
        .collect()
}

/// The grid [`compare_readings`] samples for `grid` (0: the finest texture resolution of
/// either side, at least 16), at most [`MAX_GRID`].
pub(crate) fn chosen_grid(readings: &[MaterialSource], b: &MaterialSource, grid: u32) -> u32 {
    let finest = (readings.iter().map(MaterialSource::max_resolution)).fold(1, u32::max);
    let grid = if grid == 0 {
        finest.max(b.max_resolution()).max(16)
    } else {
        grid
    };
    grid.min(MAX_GRID)
}

/// The rows' samples, with the widest vector instructions the CPU has: the texel loop is
/// plain arithmetic, so compiling it for AVX-512 or AVX2 changes its speed, not its results.
fn compare_rows(job: &Job, rows: std::ops::Range<u32>) -> Vec<Partial> {
    crate::system::with_widest_vectors(
        #[inline(always)]
        || compare_rows_inline(job, rows),
    )
}

/// Which points of a texel row are sampled: its centres, then its top-left corners.
#[derive(Clone, Copy, PartialEq)]
enum Points {
    Centres,
    Corners,
}

#[inline(always)]
fn compare_rows_inline(job: &Job, rows: std::ops::Range<u32>) -> Vec<Partial> {
    let mut pass = Pass::new(job, &rows);
    for y in rows {
        pass.here.clear();
        pass.centres.next_row();
        pass.next_row(y);
        pass.row(y, Points::Centres);
        pass.row(y, Points::Corners);
        pass.above = Some(std::mem::take(&mut pass.here));
    }
    for (batch, partial) in pass.batches.iter_mut().zip(&mut pass.partials) {
        batch.memo.count_into(partial);
    }
    pass.partials
}

/// One thread's pass over its rows: each reading's figures and batch, the corner screen, and
/// which centres of this row and the row above have equal inputs on both sides.
struct Pass<'j, 'a> {
    job: &'j Job<'a>,
    partials: Vec<Partial>,
    batches: Vec<Batch>,
    centres: Centres<'a>,
    /// Where both materials are linear in texels of this grid, a corner between four
    /// centres whose inputs agree has agreeing inputs too: it is not sampled.
    linear: bool,
    /// Where every texture is read as stored, a point whose texels equal its left
    /// neighbour's (a flat region) has that point's inputs: it is not sampled again.
    as_stored: bool,
    /// The textures keyed on each reading's side, and on the other material's but for those
    /// every reading reads too: their texels are in each reading's part of the key already
    /// (an upgrade keeps most images as they are).
    keyed: Vec<Keyed<'a>>,
    keyed_b: Keyed<'a>,
    /// The other material's part of the key of the centre at hand.
    key_b: Vec<u64>,
    /// Where every texture is read as stored: for each centre of this row and of the row
    /// above (empty above the grid's first row), whether every side reads there what it
    /// reads at the centre to its left.
    like_left: Vec<bool>,
    like_left_above: Vec<bool>,
    above: Option<Vec<bool>>,
    here: Vec<bool>,
}

impl<'j, 'a> Pass<'j, 'a> {
    #[inline(always)]
    fn new(job: &'j Job<'a>, rows: &std::ops::Range<u32>) -> Self {
        let Job {
            readings,
            b,
            grid,
            map,
            ..
        } = *job;
        let as_stored = readings.iter().all(|a| a.texels_on(grid)) && b.texels_on(grid);
        Pass {
            job,
            partials: (readings.iter())
                .map(|_| Partial::new(rows.len() * grid as usize, map))
                .collect(),
            batches: readings.iter().map(|_| Batch::new()).collect(),
            centres: Centres::new(readings, b, grid, as_stored, rows.start),
            linear: readings.iter().all(|a| a.linear_on(grid)) && b.linear_on(grid),
            as_stored,
            keyed: readings.iter().map(|a| Keyed::of(a, &[])).collect(),
            keyed_b: Keyed::of(b, &b.textures_read_by_all(readings)),
            key_b: Vec::new(),
            like_left: Vec::new(),
            like_left_above: Vec::new(),
            above: None,
            here: Vec::new(),
        }
    }

    /// Readies the flags of row `y` (and, at the first row of the pass, of the row above)
    /// that say which centres read what their left neighbours read.
    fn next_row(&mut self, y: u32) {
        if !self.as_stored {
            return;
        }
        if self.like_left.is_empty() && y > 0 {
            self.like_left = self.reading_as_left(y - 1);
        }
        let here = self.reading_as_left(y);
        self.like_left_above = std::mem::replace(&mut self.like_left, here);
    }

    /// Row `y`'s flags: whether each centre reads on every side what the one to its left
    /// reads.
    fn reading_as_left(&self, y: u32) -> Vec<bool> {
        let Job {
            readings, b, grid, ..
        } = *self.job;
        let mut row = vec![true; grid as usize];
        for side in readings.iter().chain([b]) {
            side.clear_unlike_left(y, &mut row);
        }
        row
    }

    /// Whether the point at column `x` of this row (a centre, or a corner) reads on every
    /// side the texels the point to its left reads: a corner reads the texels left and right
    /// of it in this row and the row above. Never where a read wraps around an edge.
    #[inline(always)]
    fn reads_as_left(&self, x: u32, points: Points) -> bool {
        let x = x as usize;
        let alike = |row: &[bool], columns: std::ops::RangeInclusive<usize>| {
            row.get(columns)
                .is_some_and(|flags| flags.iter().all(|&f| f))
        };
        match points {
            Points::Centres => alike(&self.like_left, x..=x),
            Points::Corners => {
                x >= 1
                    && alike(&self.like_left, x - 1..=x)
                    && alike(&self.like_left_above, x - 1..=x)
            }
        }
    }

    /// Row `y`'s centres, or its top-left corners.
    #[inline(always)]
    fn row(&mut self, y: u32, points: Points) {
        let Job {
            readings,
            grid,
            ref directions,
            ..
        } = *self.job;
        let size = f64::from(grid);
        let offset = if points == Points::Centres { 0.5 } else { 0.0 };
        let uv_of = |x: u32| {
            [
                (f64::from(x) + offset) / size,
                (f64::from(y) + offset) / size,
            ]
        };
        // Centres add their texel to the map, corners raise it.
        let map_length = (self.partials.first())
            .and_then(|p| p.per_texel.as_ref())
            .map(Vec::len);
        let row_start = map_length.map_or(0, |length| match points {
            Points::Centres => length,
            Points::Corners => length - grid as usize,
        });
        let corner = points == Points::Corners;
        let place = |x: u32| Place {
            uv: uv_of(x),
            texel: corner.then_some(row_start + x as usize),
            order: (u64::from(y) * 2 + u64::from(corner)) * u64::from(grid) + u64::from(x),
        };
        let mut row_of: Vec<Row> = readings.iter().map(|_| Row::default()).collect();
        // Whether the corner before was a blend: a corner that reads the texels its left
        // neighbour reads lies between the same centres, and is one too.
        let mut left_blended = false;
        for x in 0..grid {
            let uv = uv_of(x);
            if !self.on_mesh(x, y, points) {
                self.off_mesh(x, points, &mut row_of, place);
                left_blended = false;
                continue;
            }
            if points == Points::Corners
                && self.corner_unsampled(x, uv, &mut left_blended, &mut row_of, place)
            {
                continue;
            }
            if self.repeats_left(x, points, &mut row_of, place) {
                continue;
            }
            self.sample(x, y, uv, points, &mut row_of, place);
        }
        let each = (row_of.iter_mut())
            .zip(&mut self.batches)
            .zip(&mut self.partials);
        for ((row, batch), partial) in each {
            row.flush(batch, partial, place, &directions.angles);
        }
    }

    /// Whether the point at column `x` of row `y` is on the mesh: a centre whose texel a
    /// bilinear sample on a triangle reads, a corner whose four texels around it are all read
    /// (as they are where a triangle holds the corner).
    #[inline(always)]
    fn on_mesh(&self, x: u32, y: u32, points: Points) -> bool {
        let Some(seen) = &self.job.on_mesh else {
            return true;
        };
        let grid = self.job.grid;
        let (left, up) = ((x + grid - 1) % grid, (y + grid - 1) % grid);
        match points {
            Points::Centres => seen.contains(x, y),
            Points::Corners => [(left, up), (x, up), (left, y), (x, y)]
                .iter()
                .all(|&(x, y)| seen.contains(x, y)),
        }
    }

    /// Passes over the point at column `x`, off the mesh: a centre keeps its place in the
    /// row's flags and kept inputs, which no corner on the mesh reads.
    fn off_mesh(
        &mut self,
        x: u32,
        points: Points,
        row_of: &mut [Row],
        place: impl Fn(u32) -> Place + Copy,
    ) {
        if points == Points::Centres {
            self.here.push(false);
            self.centres.pass_over();
        }
        for (row, partial) in row_of.iter_mut().zip(&mut self.partials) {
            row.add_off_mesh(partial, x, place);
        }
    }

    /// Whether the corner at column `x` is left unsampled: a blend of the four centres
    /// around it on every side, or (both materials linear) between four centres whose
    /// inputs agree, which it then adds with ΔE 0.
    #[inline(always)]
    fn corner_unsampled(
        &mut self,
        x: u32,
        uv: [f64; 2],
        left_blended: &mut bool,
        row_of: &mut [Row],
        place: impl Fn(u32) -> Place + Copy,
    ) -> bool {
        let Job {
            grid,
            ref directions,
            ..
        } = *self.job;
        let as_left = || self.reads_as_left(x, Points::Corners);
        *left_blended = self.centres.skips(x, uv, *left_blended, as_left);
        if *left_blended {
            for (row, partial) in row_of.iter_mut().zip(&mut self.partials) {
                row.forget_last();
                partial.blended += 1;
            }
            return true;
        }
        if !self.linear {
            return false;
        }
        let left = (x + grid - 1) % grid;
        let agree = |row: &[bool]| row[x as usize] && row[left as usize];
        if !(self.above.as_deref().is_some_and(agree) && agree(&self.here)) {
            return false;
        }
        for (row, partial) in row_of.iter_mut().zip(&mut self.partials) {
            row.add_equal(partial, x, place, &directions.angles);
        }
        true
    }

    /// Whether the point at column `x` reads on every side the texels its left neighbour
    /// reads (every texture read as stored): it then takes that point's samples.
    #[inline(always)]
    fn repeats_left(
        &mut self,
        x: u32,
        points: Points,
        row_of: &mut [Row],
        place: impl Fn(u32) -> Place + Copy,
    ) -> bool {
        let directions = &self.job.directions;
        if !(self.as_stored
            && x > 0
            && row_of.iter().all(|row| row.last().is_some())
            && self.reads_as_left(x, points))
        {
            return false;
        }
        if points == Points::Centres {
            self.here.push(self.here[x as usize - 1]);
            self.centres.repeat_left();
        }
        for (row, partial) in row_of.iter_mut().zip(&mut self.partials) {
            match row.last() {
                Some(Source::Zero) | None => row.add_equal(partial, x, place, &directions.angles),
                Some(source) => row.repeat(x, source),
            }
        }
        true
    }

    /// Samples the point at column `x` (texture coordinates `uv`) for every reading: by its
    /// texels where those were sampled before (a centre read as stored), else by its inputs.
    #[inline(always)]
    fn sample(
        &mut self,
        x: u32,
        y: u32,
        uv: [f64; 2],
        points: Points,
        row_of: &mut [Row],
        place: impl Fn(u32) -> Place + Copy,
    ) {
        let Job { readings, b, .. } = *self.job;
        let centre = points == Points::Centres;
        let mut target = None;
        if centre {
            self.here.push(true);
        }
        let keyed = centre && self.as_stored;
        // The other material's texels, read for the first reading whose memo is consulted.
        let mut key_b_read = false;
        let each = (readings.iter())
            .zip(row_of.iter_mut())
            .zip(&mut self.batches);
        for (r, (((a, row), batch), partial)) in each.zip(&mut self.partials).enumerate() {
            let consulted = keyed && batch.memo.consulted();
            if consulted && !key_b_read {
                self.key_b.clear();
                self.keyed_b.words(x, y, &mut self.key_b);
                key_b_read = true;
            }
            let known = match consulted {
                true => batch.known(&self.keyed[r], x, y, &self.key_b),
                // No key: a point sampled while the memo rests is not remembered.
                false => {
                    batch.key.clear();
                    None
                }
            };
            if let Some(known) = known {
                // Known texels: no input is read but what a corner needs.
                self.here[x as usize] = false;
                self.centres.keep(r, a, uv);
                row.take_known(x, known);
                continue;
            }
            // A centre's inputs are made through the corner screen, which keeps what a
            // corner needs of them.
            let centres = &mut self.centres;
            let target = &*target.get_or_insert_with(|| match centre {
                true => centres.inputs(readings.len(), b, uv),
                false => b.inputs_at(&[uv]),
            });
            let source = match centre {
                true => centres.inputs(r, a, uv),
                false => a.inputs_at(&[uv]),
            };
            let equal = row.add_pair(batch, partial, self.job, x, (source, target), place);
            if !equal && centre {
                self.here[x as usize] = false;
            }
        }
        if centre && target.is_none() {
            self.centres.keep(readings.len(), b, uv);
        }
    }
}

/// How far (relative to each number's size, at least 1) a corner's inputs may be from the
/// mean of its four centres' and still be called their blend: a sixteenth of an 8-bit step,
/// less than storing any input in a texture moves it.
const BLEND_TOLERANCE: f64 = 1.0 / 4096.0;

/// Which corners need sampling, on a grid whose textures are all read as stored (see
/// [`MaterialSource::texels_on`]). There a corner reads the mean of the four texels around
/// it in every texture, so a side whose inputs are affine in its texels
/// ([`MaterialSource::linear_on`]) has at the corner the mean of its four centres' inputs,
/// and a side that bends them (spec-gloss's diffuse · (1 − max specular), a normalised
/// normal) has the inputs it can bend ([`Inputs::bent`]) checked against the centres of this
/// row and the row above. Where every side has its centres' mean, the viewer's interpolation
/// of one material's texels shows what the other's shows: the corner is a blend of the pairs
/// its four centres compared, and is not sampled. Where a side bends, the corner is where a
/// conversion that is not linear differs most, and it is sampled.
///
/// A bending side's texture reads at each centre are kept with its bent inputs: the reads
/// at a corner are made from the four centres' ([`sample::corner_of`]), not sampled again.
struct Centres<'a> {
    /// Whether corners are screened at all (every texture read as stored).
    active: bool,
    /// The sides that bend their texels, and for each side (readings, then the other
    /// material) its place among them.
    bending: Vec<&'a MaterialSource>,
    slot: Vec<Option<usize>>,
    /// Each bending side's centres of the row above and of this row.
    above: Option<Vec<Kept>>,
    here: Vec<Kept>,
    started: bool,
}

/// A centre off the mesh in [`Kept::index`].
const OFF_MESH: u32 = u32::MAX;

/// One bending side's centres of one row: each one's bent inputs and texture reads (the same
/// number at every centre, see [`MaterialSource::inputs_with`]), held once for a run of
/// centres that read alike.
#[derive(Default)]
struct Kept {
    /// Each centre's place in `bent` (and its reads' in `reads`).
    index: Vec<u32>,
    bent: Vec<Bent>,
    reads: Vec<[f64; 4]>,
}

impl Kept {
    /// Makes `side`'s inputs at `uv` (a centre of this row), keeping what a corner needs.
    #[inline(always)]
    fn inputs(&mut self, side: &MaterialSource, uv: [f64; 2]) -> Inputs {
        let reads = &mut self.reads;
        let inputs = side.inputs_with(&[uv], |read: Read<'_>| {
            let texels = read.sampled();
            reads.push(texels);
            texels
        });
        self.index.push(self.bent.len() as u32);
        self.bent.push(inputs.bent());
        inputs
    }

    /// The next centre repeats the one before.
    fn repeat_last(&mut self) {
        if let Some(&last) = self.index.last() {
            self.index.push(last);
        }
    }

    /// The next centre is off the mesh: nothing is kept of it.
    fn pass_over(&mut self) {
        self.index.push(OFF_MESH);
    }

    /// Centre `x`'s bent inputs and texture reads (None off the mesh).
    fn centre(&self, x: usize) -> Option<(&Bent, &[[f64; 4]])> {
        let at = *self.index.get(x).filter(|&&at| at != OFF_MESH)? as usize;
        let per_centre = self.reads.len() / self.bent.len().max(1);
        Some((&self.bent[at], &self.reads[at * per_centre..][..per_centre]))
    }
}

impl<'a> Centres<'a> {
    /// The screen for rows from `first` on: the centres of the row above `first` are read
    /// here, so that which corners are sampled does not depend on how the grid's rows are
    /// shared out.
    fn new(
        readings: &'a [MaterialSource],
        b: &'a MaterialSource,
        grid: u32,
        active: bool,
        first: u32,
    ) -> Self {
        let sides = readings.iter().chain(std::iter::once(b));
        let mut bending = Vec::new();
        let slot = sides
            .map(|side| {
                (active && !side.linear_on(grid)).then(|| {
                    bending.push(side);
                    bending.len() - 1
                })
            })
            .collect();
        let size = f64::from(grid);
        let row_above = |side: &&MaterialSource| {
            let v = (f64::from(first) - 0.5) / size;
            let mut kept = Kept::default();
            for x in 0..grid {
                kept.inputs(side, [(f64::from(x) + 0.5) / size, v]);
            }
            kept
        };
        let here = bending.iter().map(|_| Kept::default()).collect();
        Centres {
            active,
            above: (first > 0).then(|| bending.iter().map(row_above).collect()),
            bending,
            slot,
            here,
            started: false,
        }
    }

    fn next_row(&mut self) {
        if self.started {
            let empty = self.bending.iter().map(|_| Kept::default()).collect();
            self.above = Some(std::mem::replace(&mut self.here, empty));
        }
        self.started = true;
    }

    /// Side `side`'s inputs at this row's next centre (`material` at `uv`), kept if it bends.
    #[inline(always)]
    fn inputs(&mut self, side: usize, material: &MaterialSource, uv: [f64; 2]) -> Inputs {
        match self.slot.get(side) {
            Some(Some(k)) => self.here[*k].inputs(material, uv),
            _ => material.inputs_at(&[uv]),
        }
    }

    /// Keeps side `side`'s inputs at this row's next centre, if it bends.
    #[inline(always)]
    fn keep(&mut self, side: usize, material: &MaterialSource, uv: [f64; 2]) {
        if let Some(Some(k)) = self.slot.get(side) {
            self.here[*k].inputs(material, uv);
        }
    }

    /// This row's next centre is off the mesh.
    fn pass_over(&mut self) {
        self.here.iter_mut().for_each(Kept::pass_over);
    }

    /// This row's next centre reads what the one before it read.
    fn repeat_left(&mut self) {
        self.here.iter_mut().for_each(Kept::repeat_last);
    }

    /// Whether the corner at column `x` (texture coordinates `uv`) is not sampled, given
    /// whether the corner before it was not and whether it reads that one's texels
    /// (`as_left`, asked only where a side bends: otherwise the screen reads nothing).
    #[inline(always)]
    fn skips(
        &self,
        x: u32,
        uv: [f64; 2],
        left_blended: bool,
        as_left: impl FnOnce() -> bool,
    ) -> bool {
        match self.bending.is_empty() {
            true => self.blend_at(x, uv),
            false => (left_blended && as_left()) || self.blend_at(x, uv),
        }
    }

    /// Whether the corner at column `x` of this row (texture coordinates `uv`) is a blend of
    /// the four centres around it on every side. Corners on the grid's first row and column
    /// read texels across the texture's edge, as its wrap mode says: they are sampled.
    #[inline(always)]
    fn blend_at(&self, x: u32, uv: [f64; 2]) -> bool {
        let Some(above) = self.above.as_ref().filter(|_| self.active && x >= 1) else {
            return false;
        };
        let x = x as usize;
        (self.bending.iter().zip(above).zip(&self.here)).all(|((side, above), here)| {
            let four = [
                above.centre(x - 1),
                above.centre(x),
                here.centre(x - 1),
                here.centre(x),
            ];
            // A corner on the mesh has its centres on it; were one off, it would be sampled.
            let [Some(a), Some(b), Some(c), Some(d)] = four else {
                return false;
            };
            let four = [a, b, c, d];
            // A material makes the same reads at every point; were one missing, it would be
            // sampled, never guessed.
            let mut next = 0;
            let corner = side.inputs_with(&[uv], |read: Read<'_>| {
                let kept = four.map(|(_, reads)| reads.get(next));
                next += 1;
                match kept {
                    [Some(a), Some(b), Some(c), Some(d)] => sample::corner_of([a, b, c, d]),
                    _ => read.sampled(),
                }
            });
            is_mean_of(&corner.bent(), four.map(|(bent, _)| bent), BLEND_TOLERANCE)
        })
    }
}

/// Where a point lies: its texture coordinates, the texel of the map it raises (a corner)
/// or `None` (a centre, which adds its texel), and its place in one pass over the grid (row
/// by row, each row's centres then its corners).
struct Place {
    uv: [f64; 2],
    texel: Option<usize>,
    order: u64,
}

/// Where a point's ΔE samples come from.
#[derive(Clone, Copy)]
enum Source {
    /// Both materials have the same inputs there.
    Zero,
    /// A point of the batch being filled.
    Slot(usize),
    /// Already computed (a repeat of a point of an earlier batch).
    Known([f64; DIRECTION_COUNT]),
    /// A centre found in the batch's memo by its texels: counted there.
    Memo(u32),
    /// Off the mesh: not sampled.
    OffMesh,
}

/// Points of a grid row waiting for their batch's ΔE: the one at column `x`, and the
/// `repeats` after it that read what it reads.
struct Pending {
    x: u32,
    source: Source,
    repeats: u32,
}

impl Pending {
    fn at(x: u32, source: Source) -> Pending {
        Pending {
            x,
            source,
            repeats: 0,
        }
    }
}

/// The points of one grid row waiting for their batch's ΔE, in order.
#[derive(Default)]
struct Row {
    /// Where their samples come from, in row order.
    pending: Vec<Pending>,
    /// Points put into the batch so far.
    unique: usize,
    /// The last point with differing inputs: its inputs (unless it was known by its texels)
    /// and samples (equal inputs give equal colours).
    previous: Option<(Option<Pair>, Source)>,
    /// Whether the last point had equal inputs on both sides.
    last_equal: bool,
}

impl Row {
    /// A point with the same inputs on both sides: ΔE 0, added at once unless points before
    /// it wait for their batch.
    fn add_equal(
        &mut self,
        partial: &mut Partial,
        x: u32,
        place: impl Fn(u32) -> Place,
        angles: &[Angles; DIRECTION_COUNT],
    ) {
        self.last_equal = true;
        match self.pending.is_empty() {
            true => partial.add_equal_point(&place(x), angles),
            false => self.pending.push(Pending::at(x, Source::Zero)),
        }
    }

    /// Adds the point at column `x` with inputs `source` and `target`; returns whether they
    /// are equal. Identical inputs give identical colours, whose ΔE is exactly 0; a point
    /// like the one before (a flat region of a texture) has its ΔE, nothing is copied; any
    /// other is shaded in the batch.
    #[inline(always)]
    fn add_pair(
        &mut self,
        batch: &mut Batch,
        partial: &mut Partial,
        job: &Job,
        x: u32,
        (source, target): (Inputs, &Inputs),
        place: impl Fn(u32) -> Place,
    ) -> bool {
        let angles = &job.directions.angles;
        if source == *target {
            // The previous point is left as it was: no point with differing inputs equals
            // this.
            self.add_equal(partial, x, place, angles);
            return true;
        }
        self.last_equal = false;
        let source = match self.repeat_of(&source, target) {
            Some(same) => same,
            None => batch.shade(self, job.shader, &job.directions, source, target),
        };
        self.pending.push(Pending::at(x, source));
        if self.unique == BATCH_TEXELS {
            self.flush(batch, partial, place, angles);
        }
        false
    }

    /// Where the row's last point's samples come from (`None` before its first point).
    fn last(&self) -> Option<Source> {
        match self.last_equal {
            true => Some(Source::Zero),
            false => self.previous.as_ref().map(|(_, source)| *source),
        }
    }

    /// A point found in the memo by its texels (its inputs are not compared).
    fn take_known(&mut self, x: u32, entry: u32) {
        let known = Source::Memo(entry);
        self.last_equal = false;
        self.previous = Some((None, known));
        self.pending.push(Pending::at(x, known));
    }

    /// The point at column `x` reads what the point before it read (whose samples come from
    /// `source`): a run of such points is handed on at once.
    fn repeat(&mut self, x: u32, source: Source) {
        match self.pending.last_mut() {
            Some(last)
                if last.x + last.repeats + 1 == x
                    && !matches!(last.source, Source::Zero | Source::OffMesh) =>
            {
                last.repeats += 1
            }
            _ => self.pending.push(Pending::at(x, source)),
        }
    }

    /// A point off the mesh, added at once unless points before it wait for their batch;
    /// the next point cannot take its samples.
    fn add_off_mesh(&mut self, partial: &mut Partial, x: u32, place: impl Fn(u32) -> Place) {
        self.forget_last();
        match self.pending.is_empty() {
            true => partial.add_off_mesh_point(&place(x)),
            false => self.pending.push(Pending::at(x, Source::OffMesh)),
        }
    }

    /// The point before was not sampled: the next one cannot take its samples.
    fn forget_last(&mut self) {
        self.previous = None;
        self.last_equal = false;
    }

    fn repeat_of(&self, a: &Inputs, b: &Inputs) -> Option<Source> {
        let (Some((previous_a, previous_b)), source) = self.previous.as_ref()? else {
            return None;
        };
        (previous_b == b && previous_a == a).then_some(*source)
    }

    /// Computes the batch's ΔE and hands every pending point to `partial`, in row order.
    /// Inlined so that the ΔE loop is compiled with the caller's vector instructions.
    #[inline(always)]
    fn flush(
        &mut self,
        batch: &mut Batch,
        partial: &mut Partial,
        place: impl Fn(u32) -> Place,
        angles: &[Angles; DIRECTION_COUNT],
    ) {
        let deltas = if self.unique > 0 {
            batch.delta_e()
        } else {
            [0.0; BATCH]
        };
        let samples = |source: Source, memo: &Memo| match source {
            Source::Zero | Source::OffMesh => [0.0; DIRECTION_COUNT],
            Source::Slot(k) => std::array::from_fn(|i| deltas[k * DIRECTION_COUNT + i]),
            Source::Known(known) => known,
            Source::Memo(entry) => memo.samples(entry),
        };
        for Pending { x, source, repeats } in self.pending.drain(..) {
            let at = place(x);
            let deltas = match source {
                Source::Zero => {
                    partial.add_equal_point(&at, angles);
                    continue;
                }
                Source::OffMesh => {
                    partial.add_off_mesh_point(&at);
                    continue;
                }
                Source::Slot(k) => {
                    let deltas = samples(source, &batch.memo);
                    partial.add_point(&at, &deltas, angles, &batch.pairs[k]);
                    deltas
                }
                // A repeat of a point sampled before: its figures count, and it cannot be a
                // new worst (the point it repeats was offered).
                Source::Known(known) => {
                    partial.add_samples(&at, &known, 1);
                    known
                }
                // Counted in the memo; only a map of texels needs each point's samples.
                Source::Memo(entry) => {
                    batch.memo.repeated(entry, 1 + repeats);
                    if partial.per_texel.is_some() {
                        let deltas = samples(source, &batch.memo);
                        (x..=x + repeats).for_each(|x| partial.note_point(&place(x), &deltas));
                    }
                    continue;
                }
            };
            // Points that read what the one before read: the same, counted again. (None is
            // a new worst, nor a new candidate: each is a repeat of a point offered.)
            if repeats > 0 {
                partial.add_samples(&place(x + 1), &deltas, repeats);
                for more in x + 2..=x + repeats {
                    partial.note_point(&place(more), &deltas);
                }
            }
        }
        if let Some((_, source)) = &mut self.previous {
            *source = Source::Known(samples(*source, &batch.memo));
        }
        self.unique = 0;
        for (k, key) in batch.keys.iter().enumerate() {
            let samples = std::array::from_fn(|i| deltas[k * DIRECTION_COUNT + i]);
            batch
                .memo
                .put(&batch.key_words[key.clone()], samples, partial);
        }
        batch.pairs.clear();
        batch.keys.clear();
        batch.key_words.clear();
        batch.translucent = false;
    }
}

impl Partial {
    fn new(texels: usize, map: TexelMap) -> Partial {
        Partial {
            per_texel: (map == TexelMap::Kept).then(|| Vec::with_capacity(texels)),
            sum: 0,
            count: 0,
            blended: 0,
            off_mesh: 0,
            worst: Worst {
                delta_e: -1.0,
                sets: Vec::new(),
                behind: false,
                uv: [0.0, 0.0],
                directions: Angles::coarse(DIRECTIONS[0]),
                background: BACKGROUNDS[0],
            },
            histogram: Histogram::default(),
            candidates: refine::Candidates::default(),
        }
    }

    /// A point where both materials have the same inputs: ΔE 0 in every direction. (Most
    /// points of an exact conversion; the general path would update the histogram one
    /// sample at a time.)
    fn add_equal_point(&mut self, at: &Place, angles: &[Angles; DIRECTION_COUNT]) {
        self.count += DIRECTION_COUNT as u64;
        self.histogram.add(0.0, DIRECTION_COUNT as u32);
        if self.worst.delta_e < 0.0 {
            self.worst = Worst {
                delta_e: 0.0,
                sets: Vec::new(),
                behind: false,
                uv: at.uv,
                directions: angles[0],
                background: BACKGROUNDS[0],
            };
        }
        self.note_max(at, 0.0);
    }

    /// A point off the mesh: not sampled, and marked so in the map of texels (a centre
    /// adds its texel as not a number; a corner leaves its texel as it was).
    fn add_off_mesh_point(&mut self, at: &Place) {
        self.off_mesh += 1;
        self.note_max(at, f32::NAN);
    }

    /// Puts a point's largest sample into the map of texels, if one is kept.
    fn note_point(&mut self, at: &Place, deltas: &[f64]) {
        if self.per_texel.is_some() {
            self.note_max(at, largest(deltas).0 as f32);
        }
    }

    fn note_max(&mut self, at: &Place, max: f32) {
        if let Some(map) = &mut self.per_texel {
            match at.texel.and_then(|i| map.get_mut(i)) {
                Some(texel) => *texel = texel.max(max),
                None => map.push(max),
            }
        }
    }

    /// Adds the samples of `times` points alike (the first at `at`) to the figures; returns
    /// their largest and its direction.
    fn add_samples(&mut self, at: &Place, deltas: &[f64], times: u32) -> (f64, usize) {
        self.count(deltas, times);
        let (point_max, arg) = largest(deltas);
        self.note_max(at, point_max as f32);
        (point_max, arg)
    }

    /// Adds the samples of `times` points alike to the sum, the count and the histogram.
    fn count(&mut self, deltas: &[f64], times: u32) {
        for &delta in deltas {
            let delta = if delta.is_finite() { delta } else { f64::MAX };
            // At most 10⁶ · 2³² < 2⁶³: one conversion instruction, where a float to a
            // 128-bit integer is a library call per sample.
            let steps = ((delta.min(1e6) * SUM_STEPS_PER_UNIT) as i64) as u128;
            self.sum += steps * u128::from(times);
            self.count += u64::from(times);
            self.histogram.add(delta, times);
        }
    }

    fn add_point(
        &mut self,
        at: &Place,
        deltas: &[f64],
        angles: &[Angles; DIRECTION_COUNT],
        pair: &Pair,
    ) {
        let (point_max, arg) = self.add_samples(at, deltas, 1);
        if point_max > self.worst.delta_e {
            // Which background it was found over is settled once, for the final worst.
            self.worst = Worst {
                delta_e: point_max,
                sets: Vec::new(),
                behind: false,
                uv: at.uv,
                directions: angles[arg],
                background: BACKGROUNDS[0],
            };
        }
        self.candidates.offer(point_max, at.uv, at.order, pair);
    }
}

/// A point's largest sample (a sample that is not a number counting as the largest there
/// is) and its direction.
fn largest(deltas: &[f64]) -> (f64, usize) {
    let (mut point_max, mut arg) = (0f64, 0);
    for (k, &delta) in deltas.iter().enumerate() {
        let delta = if delta.is_finite() { delta } else { f64::MAX };
        if delta > point_max {
            (point_max, arg) = (delta, k);
        }
    }
    (point_max, arg)
}

/// The partials' figures together, and the search of [`refine`] around their worst points
/// (`at` gives both materials' inputs anywhere).
fn merge<'p>(
    shader: &Shader,
    partials: impl IntoIterator<Item = &'p Partial>,
    (grid, area): (u32, Area),
    at: &dyn Fn([f64; 2]) -> Option<Pair>,
) -> Comparison {
    let mut histogram: Vec<u64> = Vec::new();
    let mut per_texel = Vec::new();
    let (mut sum, mut count, mut blended, mut off_mesh) = (0u128, 0u64, 0u64, 0u64);
    // The first worst sample seen (in row order) wins ties, so a comparison with ΔE 0
    // everywhere names a real point.
    let mut worst: Option<Worst> = None;
    let mut candidates = refine::Candidates::default();
    // Partials come in row order: their texels concatenate into the grid.
    for p in partials {
        per_texel.extend(p.per_texel.iter().flatten());
        sum += p.sum;
        count += p.count;
        blended += p.blended;
        off_mesh += p.off_mesh;
        p.histogram.add_to(&mut histogram);
        if worst.as_ref().is_none_or(|w| p.worst.delta_e > w.delta_e) {
            worst = Some(p.worst.clone());
        }
        candidates.absorb(&p.candidates);
    }
    let mut worst = worst.unwrap_or_else(Worst::nowhere);
    // The worst point is the first of the candidates (offered in row order, ties kept first).
    let mut pair = candidates.worst_pair().cloned();
    if let Some(pair) = &pair {
        worst.background = delta_at(shader, &pair.0, &pair.1, &worst.directions).1;
    }
    let texel = 1.0 / f64::from(grid.max(1));
    if let Some(found) = refine::search(shader, &candidates, texel, at) {
        if found.worst.delta_e > worst.delta_e {
            worst = found.worst;
            pair = Some(*found.pair);
        }
    }
    let dominant = (pair.as_ref())
        .filter(|_| worst.delta_e > 0.0)
        .and_then(|pair| dominant_input(shader, &pair.0, &pair.1, &worst));
    let target = (count as f64 * 0.99).ceil() as u64;
    let mut seen = 0;
    let mut p99 = 0.0;
    for (bin, n) in histogram.iter().enumerate() {
        seen += n;
        if seen >= target {
            p99 = (bin + 1) as f64 / BINS_PER_UNIT;
            break;
        }
    }
    Comparison {
        max: worst.delta_e,
        p99: p99.min(worst.delta_e),
        mean: sum as f64 / SUM_STEPS_PER_UNIT / count.max(1) as f64,
        worst,
        dominant,
        grid,
        samples: count,
        blended_corners: blended,
        area,
        off_mesh,
        per_texel: per_texel.into(),
    }
}

#[cfg(test)]
mod reference;
#[cfg(test)]
mod sensitivity;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::brdf::SheenVisibility;
    use crate::shade::sheen_table::SheenTable;
    use serde_json::json;

    fn whole() -> Meshes {
        Meshes::default()
    }

    fn shader() -> Shader {
        Shader::new(SheenTable::compute(4, SheenVisibility::Charlie))
    }

    fn gltf2(material: serde_json::Value) -> MaterialSource {
        MaterialSource::gltf2(&material, &[])
    }

    /// The lane-wise figure of a point's fixed and peak directions is, direction by direction,
    /// what [`delta_at`] gives one at a time: opaque and translucent pairs, a sheen and a
    /// clearcoat among them.
    #[test]
    fn a_points_directions_in_lanes_equal_their_one_at_a_time_figures() {
        let inputs = |roughness, coverage, sheen: f64, clearcoat| Inputs {
            base_color: [0.6, 0.3, 0.2],
            metallic: 0.2,
            roughness,
            coverage,
            sheen_color: [sheen; 3],
            sheen_roughness: 0.4,
            clearcoat,
            clearcoat_roughness: 0.1,
            ..Inputs::default()
        };
        let s = shader();
        let pairs = [
            (inputs(0.5, 1.0, 0.0, 0.0), inputs(0.2, 1.0, 0.0, 0.0)),
            (inputs(0.3, 0.4, 0.8, 0.0), inputs(0.3, 0.9, 0.2, 1.0)),
        ];
        let angles = &point_directions().angles;
        for (a, b) in &pairs {
            let lanes = deltas_at_point(&s, a, b);
            assert_eq!(lanes.len(), angles.len());
            for (lane, angle) in lanes.iter().zip(angles) {
                assert_eq!(*lane, delta_at(&s, a, b, angle).0, "{angle:?}");
            }
            let worst = worst_at_point(&s, std::slice::from_ref(a), b);
            assert_eq!(worst, lanes.iter().copied().fold(0.0, f64::max));
            assert!(worst > 1.0, "{worst}");
        }
    }

    /// A `size`² PNG in runs of `run` texels of five colours; rows that `changed` picks are
    /// shifted by one colour.
    fn runs_png(size: u32, run: u32, changed: impl Fn(u32) -> bool) -> Vec<u8> {
        let palette = [
            [200, 40, 40],
            [40, 200, 40],
            [40, 40, 200],
            [128, 128, 128],
            [10, 10, 10],
        ];
        let image = image::RgbImage::from_fn(size, size, |x, y| {
            let shift = u32::from(changed(y));
            image::Rgb(palette[((x / run + y + shift) % 5) as usize])
        });
        let mut png = Vec::new();
        image::DynamicImage::ImageRgb8(image)
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        png
    }

    /// Each texel's entry in `a` against `b` on a `size`² grid equals the ΔE of its centre and
    /// (where it is sampled) its corner computed alone; returns the comparison. Where both
    /// materials are linear in texels read as stored, only the corners of the first row and
    /// column are sampled: the others are blends of their centres.
    fn assert_each_texel_as_alone(a: &MaterialSource, b: &MaterialSource, size: u32) -> Comparison {
        let shader = shader();
        let result = compare(&shader, a, b, size);
        let n = f64::from(size);
        let screened = [a, b]
            .iter()
            .all(|m| m.texels_on(size) && m.linear_on(size));
        for y in 0..size {
            for x in 0..size {
                let corner_sampled = !screened || x == 0 || y == 0;
                // A texel's entry is the larger of its centre's and its sampled corner's.
                let at = |offset: f64| {
                    let uv = [(f64::from(x) + offset) / n, (f64::from(y) + offset) / n];
                    let (a, b) = (a.inputs_at(&[uv]), b.inputs_at(&[uv]));
                    (DIRECTIONS.map(Angles::coarse).iter())
                        .map(|angles| delta_at(&shader, &a, &b, angles).0)
                        .fold(0.0, f64::max)
                };
                let alone = if corner_sampled {
                    at(0.5).max(at(0.0))
                } else {
                    at(0.5)
                };
                assert_eq!(
                    result.per_texel[(y * size + x) as usize],
                    alone as f32,
                    "texel ({x}, {y})"
                );
            }
        }
        result
    }

    fn base_coloured(png: Vec<u8>, roughness: f64) -> MaterialSource {
        let textures = crate::shade::sample::decode_all(&[Some(Ok(png))]).unwrap();
        MaterialSource::gltf2(
            &json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                "metallicFactor": 0.0, "roughnessFactor": roughness}}),
            &textures,
        )
    }

    /// An image both sides read (an upgrade keeps most images as they are) is left out of
    /// the other material's part of a centre's key only where every reading reads it too:
    /// each reading's part then holds its texel already.
    #[test]
    fn an_image_every_reading_reads_is_left_out_of_the_other_sides_key() {
        let shared = runs_png(8, 2, |_| false);
        let own = runs_png(8, 3, |_| true);
        let textures = crate::shade::sample::decode_all(&[Some(Ok(shared)), Some(Ok(own))]);
        let textures = textures.unwrap();
        let reading = |slots: serde_json::Value| {
            MaterialSource::gltf2(&json!({ "pbrMetallicRoughness": slots }), &textures)
        };
        let b = reading(json!({"baseColorTexture": {"index": 1},
            "metallicRoughnessTexture": {"index": 0}}));
        let shares = reading(json!({"baseColorTexture": {"index": 0}}));
        let does_not = reading(json!({"baseColorTexture": {"index": 1}}));
        let left_out = b.textures_read_by_all(std::slice::from_ref(&shares));
        assert_eq!(
            left_out.iter().filter(|&&out| out).count(),
            1,
            "{left_out:?}"
        );
        // What is left of b's texels is the other image's texel.
        let words = |material: &MaterialSource, left_out: &[bool]| {
            let mut words = Vec::new();
            Keyed::of(material, left_out).words(3, 5, &mut words);
            words
        };
        assert_eq!(words(&b, &left_out), words(&does_not, &[]));
        assert_ne!(words(&b, &left_out), words(&b, &[]));
        let none_left_out = |readings: &[MaterialSource]| {
            let marks = b.textures_read_by_all(readings);
            marks.len() == 2 && marks.iter().all(|&out| !out)
        };
        assert!(
            none_left_out(&[shares, does_not]),
            "one reading does not read it"
        );
        assert!(none_left_out(&[]));
    }

    #[test]
    fn repeated_texels_reuse_their_samples_exactly() {
        // Runs of three texels (16 distinct per row, so a run continues after its batch of 8
        // is converted), against the same with another roughness: on a 48² grid, where a
        // point's inputs are sampled and then found to repeat, and on a 64² grid, where
        // equal stored texels say so before sampling.
        for size in [48, 64] {
            let png = || runs_png(size, 3, |_| false);
            let (a, b) = (base_coloured(png(), 0.5), base_coloured(png(), 0.6));
            let result = assert_each_texel_as_alone(&a, &b, size);
            assert!(
                result.max > 1.0,
                "the roughness change shows: {}",
                result.max
            );
        }
    }

    /// Texels in runs of eight alike along each row: every point of a run counts, each with
    /// its samples, though a run's repeats are handed on together.
    #[test]
    fn every_point_of_a_run_of_texels_alike_counts() {
        let image = image::RgbImage::from_fn(32, 32, |x, y| {
            let level = ((x / 8 * 53 + y * 31) % 200) as u8 + 30;
            image::Rgb([level, 255 - level, 90])
        });
        let mut png = Vec::new();
        image::DynamicImage::ImageRgb8(image)
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        let textures = crate::shade::sample::decode_all(&[Some(Ok(png))]).unwrap();
        let material = |roughness| {
            MaterialSource::gltf2(
                &json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                    "metallicFactor": 0.0, "roughnessFactor": roughness}}),
                &textures,
            )
        };
        let (a, b) = (material(0.3), material(0.45));
        let readings = std::slice::from_ref(&a);
        let c = compare_on_threads(&shader(), readings, &b, (32, &whole()), TexelMap::Kept, 1)
            .remove(0);
        let points = 2 * 32 * 32 - c.blended_corners;
        assert_eq!(c.samples, DIRECTION_COUNT as u64 * points);
        assert_eq!(c.per_texel.len(), 32 * 32);
        // Within a run, past its first two texels, every centre and corner reads alike.
        for (y, row) in c.per_texel.chunks(32).enumerate().skip(1) {
            for run in row.chunks(8) {
                assert!(run[2..].iter().all(|&t| t == run[2]), "row {y}: {run:?}");
            }
        }
        assert!(c.max > 0.0 && c.mean > 0.0);
    }

    #[test]
    fn the_figures_are_the_same_however_many_threads_share_the_grid() {
        // Five colours and normals scattered without a pattern, against the same with
        // another roughness: each texel's ΔE repeats in every thread's rows, with other
        // neighbours each time, each thread knows its own repeats by their texels, and the
        // normals bend, so that what lies between the centres is searched.
        let png = |texel: fn(usize) -> [u8; 3]| {
            let image = image::RgbImage::from_fn(64, 64, |x, y| {
                image::Rgb(texel(
                    ((x * 7919 + y * 104_729) ^ (x * y * 31)) as usize % 5,
                ))
            });
            let mut png = Vec::new();
            image::DynamicImage::ImageRgb8(image)
                .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
                .unwrap();
            Some(Ok(png))
        };
        let colours = png(|i| {
            [
                [200, 40, 40],
                [40, 200, 40],
                [40, 40, 200],
                [128; 3],
                [10; 3],
            ][i]
        });
        let normals = png(|i| {
            [
                [128, 128, 255],
                [200, 128, 200],
                [60, 180, 220],
                [128, 60, 230],
                [160, 160, 210],
            ][i]
        });
        let textures = crate::shade::sample::decode_all(&[colours, normals]).unwrap();
        let material = |roughness| {
            MaterialSource::gltf2(
                &json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                    "metallicFactor": 0.0, "roughnessFactor": roughness},
                    "normalTexture": {"index": 1}}),
                &textures,
            )
        };
        let (a, b) = (material(0.3), material(0.45));
        let on = |threads, meshes: &Meshes| {
            let readings = std::slice::from_ref(&a);
            let mut each = compare_on_threads(
                &shader(),
                readings,
                &b,
                (64, meshes),
                TexelMap::Dropped,
                threads,
            );
            let c = each.pop().unwrap();
            (
                c.max,
                c.worst.uv,
                c.worst.directions,
                c.p99,
                c.mean,
                c.samples,
                c.off_mesh,
            )
        };
        // The whole square, and a mesh on part of it: a triangle, and one across the
        // texture's edges (its UVs wrap), so that rows start and end off the mesh.
        let part = Meshes::of_triangles(&[
            [[0.1, 0.1], [0.6, 0.2], [0.3, 0.7]],
            [[0.9, 0.8], [1.2, 0.8], [0.9, 1.1]],
        ]);
        let mut samples = Vec::new();
        for meshes in [whole(), part] {
            let one = on(1, &meshes);
            assert!(one.0 > 1.0, "the roughness change shows: {one:?}");
            for threads in [2, 3, 5, 8] {
                assert_eq!(on(threads, &meshes), one, "{threads} threads");
            }
            samples.push((one.5, one.6));
        }
        assert_eq!(samples[0].1, 0, "nothing is off the whole square");
        assert!(
            samples[1].0 < samples[0].0 / 2 && samples[1].1 > 64 * 64,
            "{samples:?}"
        );
    }

    /// Where the mesh lies, the grid is sampled; off it, a difference is not seen (a
    /// viewer never shows it), and the heat map greys those texels.
    #[test]
    fn only_the_grid_on_the_mesh_is_sampled() {
        // The texture's lower rows differ, its upper rows are alike.
        let a = base_coloured(runs_png(16, 2, |_| false), 0.5);
        let b = base_coloured(runs_png(16, 2, |y| y >= 10), 0.5);
        let compared = |meshes: &Meshes| {
            let one = std::slice::from_ref(&a);
            compare_readings(&shader(), one, &b, 16, TexelMap::Kept, meshes).remove(0)
        };
        let upper = Meshes::of_triangles(&[[[0.1, 0.05], [0.9, 0.05], [0.5, 0.4]]]);
        let lower = Meshes::of_triangles(&[[[0.1, 0.75], [0.9, 0.75], [0.5, 0.95]]]);
        let (on_upper, on_lower, whole) = (compared(&upper), compared(&lower), compared(&whole()));
        assert_eq!(on_upper.max, 0.0, "{on_upper:?}");
        assert!(on_lower.max > 1.0 && whole.max >= on_lower.max);
        assert!(matches!(on_upper.area, Area::Mesh { texels } if texels > 0 && texels < 16 * 8));
        assert_eq!(whole.area, Area::Whole(crate::shade::surface::NOT_DRAWN));
        let off = |c: &Comparison| c.per_texel.iter().filter(|t| t.is_nan()).count();
        assert_eq!(on_upper.per_texel.len(), 16 * 16);
        assert!(off(&on_upper) > 16 * 8 && off(&whole) == 0);
        assert!(on_upper.samples < whole.samples / 2);
        // Off the mesh means what the filter of a point inside a triangle never reads: the
        // texel rows a bilinear sample between v = 0.05 and 0.4 (0.3 and 5.9 in texel rows)
        // and between 0.75 and 0.95 (11.5 and 14.7) reads.
        let sampled_rows = |c: &Comparison| {
            (c.per_texel.chunks(16).enumerate())
                .filter(|(_, row)| row.iter().any(|t| !t.is_nan()))
                .map(|(y, _)| y)
                .collect::<Vec<_>>()
        };
        assert_eq!(sampled_rows(&on_upper), (0..=6).collect::<Vec<_>>());
        assert_eq!(sampled_rows(&on_lower), (11..=15).collect::<Vec<_>>());
    }

    #[test]
    fn flat_regions_read_from_stored_texels_keep_equal_and_differing_points_apart() {
        // Every third row of the second texture differs: rows of equal inputs, rows that
        // differ, and corners between them, each run read once.
        let a = base_coloured(runs_png(64, 4, |_| false), 0.5);
        let b = base_coloured(runs_png(64, 4, |y| y % 3 == 0), 0.5);
        assert!(a.texels_on(64) && !a.texels_on(32) && !a.texels_on(48));
        let result = assert_each_texel_as_alone(&a, &b, 64);
        assert!(result.max > 1.0, "the changed rows show: {}", result.max);
        assert!(
            result.per_texel.iter().filter(|&&d| d == 0.0).count() > 64 * 20,
            "the rows between are equal"
        );
    }

    #[test]
    fn a_material_compared_with_itself_differs_by_zero() {
        let m = gltf2(
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1.0], "metallicFactor": 0.2, "roughnessFactor": 0.4},
            "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.9], "sheenRoughnessFactor": 0.5}}}),
        );
        let result = compare(&shader(), &m, &m, 8);
        assert_eq!((result.max, result.mean, result.p99), (0.0, 0.0, 0.0));
        assert_eq!(
            result.worst.uv,
            [0.0625, 0.0625],
            "the worst sample is a real texel centre"
        );
        assert_eq!(
            (result.samples, result.blended_corners),
            ((64 + 15) * DIRECTIONS.len() as u64, 64 - 15),
            "every texel's centre, and the corners of the first row and column (the others \
             are blends of their centres)"
        );
    }

    #[test]
    fn readings_compared_together_give_what_each_gives_alone() {
        let source = |diffuse: f64| {
            gltf2(
                json!({"pbrMetallicRoughness": {"baseColorFactor": [diffuse, 0.3, 0.2, 1.0], "roughnessFactor": 0.4}}),
            )
        };
        let target = source(0.5);
        let readings = [source(0.52), source(0.5), source(0.8)];
        let together = compare_readings(&shader(), &readings, &target, 8, TexelMap::Kept, &whole());
        assert_eq!(together.len(), readings.len());
        for (reading, result) in readings.iter().zip(&together) {
            assert_eq!(result, &compare(&shader(), reading, &target, 8));
        }
        assert_eq!(together[1].max, 0.0);
        let none = compare_readings(&shader(), &[], &target, 8, TexelMap::Kept, &whole());
        assert!(none.is_empty(), "no reading, no comparison");
        assert!(together[2].max > together[0].max && together[0].max > 0.0);
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_vector_instruction_paths_give_the_portable_results_bit_for_bit() {
        use crate::system::{compiled_for, Vectors};
        let sheen = gltf2(
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1.0], "metallicFactor": 0.2, "roughnessFactor": 0.4},
            "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.9], "sheenRoughnessFactor": 0.5},
                "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 0.3}}}),
        );
        let plain = gltf2(
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.6, 0.9, 1.0], "metallicFactor": 0.7, "roughnessFactor": 0.05}}),
        );
        let shader = shader();
        let mut checked = 0;
        for (a, b) in [(&sheen, &plain), (&plain, &sheen)] {
            let job = Job {
                shader: &shader,
                readings: std::slice::from_ref(a),
                b,
                grid: 20,
                directions: Directions::new(),
                map: TexelMap::Kept,
                on_mesh: None,
            };
            // 20 texels per row: two full batches and a partial one.
            let [portable] = &compare_rows_inline(&job, 0..3)[..] else {
                panic!("one reading, one partial");
            };
            let one = SUM_STEPS_PER_UNIT as u128;
            assert!(portable.sum > one, "the materials differ: {}", portable.sum);
            let vector: Vec<Partial> = (Vectors::ALL.into_iter())
                .filter_map(|vectors| {
                    compiled_for(
                        vectors,
                        #[inline(always)]
                        || compare_rows_inline(&job, 0..3),
                    )
                })
                .flatten()
                .collect();
            for v in &vector {
                assert_eq!(portable.sum, v.sum);
                assert_eq!(portable.per_texel, v.per_texel);
                assert_eq!(portable.histogram, v.histogram);
                assert_eq!(portable.worst, v.worst);
            }
            checked += vector.len();
        }
        if checked == 0 {
            eprintln!("neither AVX2 nor AVX-512 on this CPU: only the portable path ran");
        }
    }

    #[test]
    fn spec_gloss_converted_by_the_documented_mapping_matches_and_a_naive_one_does_not() {
        let source = gltf2(
            json!({"extensions": {"KHR_materials_pbrSpecularGlossiness": {
            "diffuseFactor": [0.6, 0.5, 0.4, 1.0], "specularFactor": [0.2, 0.2, 0.2], "glossinessFactor": 0.75}}}),
        );
        let converted = gltf2(
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.48, 0.4, 0.32, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.25},
            "extensions": {"KHR_materials_specular": {"specularColorFactor": [0.2, 0.2, 0.2]}, "KHR_materials_ior": {"ior": 0}}}),
        );
        let naive = gltf2(
            json!({"pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.5, 0.4, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.25},
            "extensions": {"KHR_materials_specular": {"specularColorFactor": [0.2, 0.2, 0.2]}, "KHR_materials_ior": {"ior": 0}}}),
        );
        let good = compare(&shader(), &source, &converted, 4);
        assert!(good.max < 1e-6, "{good:?}");
        let bad = compare(&shader(), &source, &naive, 4);
        assert!(
            bad.max > 1.0,
            "baseColor = diffuse without (1 − max specular) must be caught: {bad:?}"
        );
    }

    /// A corner is skipped only where both materials are linear in the grid's texels and
    /// its four centres agree; a corner of a bent material is still sampled, and finds what
    /// lies between agreeing centres.
    #[test]
    fn corners_between_agreeing_centres_are_skipped_only_for_linear_materials() {
        use crate::shade::sample::{decode_all, solid_png};
        let textures = decode_all(&[Some(Ok(solid_png([200, 100, 50])))]).unwrap();
        let textured = json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}});
        let linear = MaterialSource::gltf2(&textured, &textures);
        assert!(linear.linear_on(2), "a 2² texture read as stored");
        assert!(!linear.linear_on(4), "another grid");
        let mut moved = textured.clone();
        moved["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] =
            json!({"KHR_texture_transform": {"offset": [0.5, 0.0]}});
        assert!(!MaterialSource::gltf2(&moved, &textures).linear_on(2));
        let normal = json!({"normalTexture": {"index": 0}});
        assert!(!MaterialSource::gltf2(&normal, &textures).linear_on(2));
        // Two normal maps whose texels agree at every centre of a 4² grid but not between:
        // a 2² map of two tilts against the same tilts repeated on a 4² map.
        let tilts = |side: u32| {
            let image = image::RgbImage::from_fn(side, side, |x, _| match x * 2 / side {
                0 => image::Rgb([230, 128, 180]),
                _ => image::Rgb([30, 128, 180]),
            });
            vec![Some(crate::shade::sample::texture_of(image))]
        };
        let (coarse, fine) = (tilts(2), tilts(4));
        let a = MaterialSource::gltf2(&normal, &coarse);
        let b = MaterialSource::gltf2(&normal, &fine);
        let result = compare(&shader(), &a, &b, 4);
        assert!(result.max > 1.0, "between the centres: {}", result.max);
    }

    /// A comparison of 10⁴ materials each with itself must not clear and merge 10⁵ bins a
    /// pair: the histogram grows to its largest sample only.
    #[test]
    fn the_histogram_holds_bins_up_to_its_largest_sample_and_the_rest_in_the_last() {
        let mut histogram = Histogram::default();
        histogram.add(0.0, 8);
        assert_eq!(histogram.0, [8]);
        histogram.add(0.0025, 1);
        assert_eq!(histogram.0, [8, 0, 1]);
        histogram.add(1e9, 1);
        histogram.add(f64::MAX, 1);
        assert_eq!(histogram.0.len(), BINS);
        assert_eq!(histogram.0[BINS - 1], 2);
        assert_eq!(histogram.0.iter().sum::<u32>(), 11);
    }

    #[test]
    fn the_memo_of_sampled_centres_stays_within_its_words_and_keeps_what_it_holds() {
        let mut memo = Memo::new();
        let mut partial = Partial::new(0, TexelMap::Dropped);
        let samples = |i: u64| std::array::from_fn(|k| (i * 8 + k as u64) as f64);
        for i in 0..100_000u64 {
            // Wide keys: a point that reads many float textures.
            memo.put(&[i; 60], samples(i), &mut partial);
            let held = memo.keys.len() + memo.samples.len() * DIRECTION_COUNT;
            assert!(held <= MEMO_WORDS, "{held} words after {i} points");
        }
        let last = memo.find(&[99_999; 60]).map(|entry| memo.samples(entry));
        assert_eq!(last, Some(samples(99_999)));
        assert_eq!(memo.find(&[12; 60]), None, "started again when full");
        assert_eq!(memo.find(&[99_999; 59]), None, "another width");
    }

    /// Repeats are counted where they are found and join the figures when the memo starts
    /// again or the pass ends, each counted once.
    #[test]
    fn the_memo_counts_each_repeat_once_when_full_and_when_emptied() {
        let mut memo = Memo::new();
        let mut partial = Partial::new(0, TexelMap::Dropped);
        let wide = [7u64; 60];
        memo.put(&wide, [0.5; DIRECTION_COUNT], &mut partial);
        let entry = memo.find(&wide).expect("held");
        memo.repeated(entry, 3);
        assert_eq!(
            partial.count, 0,
            "counted in the memo while it holds the entry"
        );
        // Filling the memo until it starts again counts the repeats in.
        let mut i = 0u64;
        while memo.find(&wide).is_some() {
            i += 1;
            memo.put(&[1_000_000 + i; 60], [0.0; DIRECTION_COUNT], &mut partial);
        }
        assert_eq!(partial.count, 3 * DIRECTION_COUNT as u64);
        assert_eq!(partial.histogram.0[500], 3 * DIRECTION_COUNT as u32);
        let entry = memo.find(&[1_000_000 + i; 60]).expect("the last one put");
        memo.repeated(entry, 2);
        memo.count_into(&mut partial);
        memo.count_into(&mut partial);
        assert_eq!(partial.count, 5 * DIRECTION_COUNT as u64, "emptied once");
    }

    /// Centres consulted in turn, each looked up; returns how many were consulted.
    fn consult(memo: &mut Memo, centres: u32, hit: bool) -> u32 {
        let mut consulted = 0;
        for _ in 0..centres {
            if memo.consulted() {
                memo.count(hit);
                consulted += 1;
            }
        }
        consulted
    }

    #[test]
    fn a_memo_whose_lookups_rarely_hit_rests_longer_each_time_up_to_its_longest() {
        let mut memo = Memo::new();
        let mut partial = Partial::new(0, TexelMap::Dropped);
        let cold = consult(&mut memo, 2 * MEMO_WINDOW, false);
        assert_eq!(cold, 2 * MEMO_WINDOW, "filling: no rest");
        for key in 0..MEMO_WARM as u64 {
            memo.put(&[key], [0.0; DIRECTION_COUNT], &mut partial);
        }
        assert_eq!(
            consult(&mut memo, MEMO_WINDOW, true),
            MEMO_WINDOW,
            "hits: no rest"
        );
        // Misses: a window, then a rest as long as a window, then twice as long, ...
        let mut rest = MEMO_WINDOW;
        assert_eq!(consult(&mut memo, MEMO_WINDOW + rest, false), MEMO_WINDOW);
        while rest < MEMO_REST {
            rest *= 2;
            assert_eq!(consult(&mut memo, MEMO_WINDOW + rest, false), MEMO_WINDOW);
        }
        assert_eq!(
            consult(&mut memo, MEMO_WINDOW + MEMO_REST, false),
            MEMO_WINDOW
        );
        // A window of hits ends the rests.
        assert_eq!(consult(&mut memo, 2 * MEMO_WINDOW, true), 2 * MEMO_WINDOW);
    }

    /// A spec-gloss material (its base colour, diffuse times a function of specular, bends its texels)
    /// against its texel-by-texel metal-rough conversion: the same at every centre but for
    /// 8-bit steps, different between centres where diffuse and specular change together.
    /// Those corners are sampled; the corners that are blends of their centres are not, and
    /// none of them shows more than its centres do.
    #[test]
    fn corners_are_sampled_where_a_side_bends_its_texels_and_a_skipped_one_hides_nothing() {
        use crate::gltf::color::{linear_to_srgb8, srgb_to_linear};
        use crate::shade::sample::texture_of;
        let size = 16;
        // Diffuse in squares of 4 texels, specular in squares of 8 offset by 4: at some edges
        // diffuse and specular change together, at others (the texture's own edges among
        // them) only diffuse does.
        let square = |x: u32, y: u32, side: u32| ((x / side + y / side) % 2) as usize;
        let diffuse = |x, y| [[200, 60, 60], [40, 40, 160]][square(x, y, 4)];
        let specular = |x, y| [[230, 230, 200], [20, 30, 20]][square(x + 4, y + 4, 8)];
        let sg = image::RgbaImage::from_fn(size, size, |x, y| {
            let [r, g, b] = specular(x, y);
            image::Rgba([r, g, b, 160])
        });
        // The converter's base colour: diffuse · (1 − specular), channel by channel.
        let base = image::RgbImage::from_fn(size, size, |x, y| {
            let linear = |c: u8| srgb_to_linear(f64::from(c) / 255.0);
            let (d, s) = (diffuse(x, y), specular(x, y));
            image::Rgb(std::array::from_fn(|c| {
                linear_to_srgb8(linear(d[c]) * (1.0 - linear(s[c])))
            }))
        });
        let diffuse = image::RgbImage::from_fn(size, size, |x, y| image::Rgb(diffuse(x, y)));
        let source = MaterialSource::gltf2(
            &json!({"extensions": {"KHR_materials_pbrSpecularGlossiness": {
                "diffuseTexture": {"index": 0}, "specularGlossinessTexture": {"index": 1}}}}),
            &[Some(texture_of(diffuse)), Some(texture_of(sg.clone()))],
        );
        let converted = MaterialSource::gltf2(
            &json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0,
                "roughnessFactor": 1.0 - 160.0 / 255.0},
                "extensions": {"KHR_materials_specular": {"specularColorTexture": {"index": 1}},
                    "KHR_materials_ior": {"ior": 0}}}),
            &[Some(texture_of(base)), Some(texture_of(sg))],
        );
        assert!(!source.linear_on(size) && converted.linear_on(size));
        let shader = shader();
        let result = compare(&shader, &source, &converted, size);
        let n = f64::from(size);
        let alone = |x: u32, y: u32, offset: f64| {
            let uv = [(f64::from(x) + offset) / n, (f64::from(y) + offset) / n];
            let (a, b) = (source.inputs_at(&[uv]), converted.inputs_at(&[uv]));
            (DIRECTIONS.map(Angles::coarse).iter())
                .map(|angles| delta_at(&shader, &a, &b, angles).0)
                .fold(0.0, f64::max)
        };
        let centres_max = (0..size * size)
            .map(|i| alone(i % size, i / size, 0.5))
            .fold(0.0, f64::max);
        let mut corners_max: f64 = 0.0;
        for (x, y) in (1..size).flat_map(|y| (1..size).map(move |x| (x, y))) {
            let corner = alone(x, y, 0.0);
            corners_max = corners_max.max(corner);
            let around = [(x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y)];
            if around
                .iter()
                .all(|&(i, j)| specular(i, j) == specular(x, y))
            {
                // Only diffuse changes here: a blend, which shows no more than its centres.
                let most = around
                    .map(|(x, y)| alone(x, y, 0.5))
                    .into_iter()
                    .fold(0.0, f64::max);
                assert!(
                    corner <= most + 0.05,
                    "corner ({x}, {y}): {corner} against {most}"
                );
            }
        }
        assert!(
            corners_max > 2.0 * centres_max.max(0.5),
            "the difference lies between centres: corners {corners_max}, centres {centres_max}"
        );
        assert!(
            result.max >= corners_max,
            "the worst corner is sampled: {} against {corners_max}",
            result.max
        );
        // Exactly the corners off the first row and column whose source inputs are the
        // mean of its centres' (the conversion is linear in its texels) are not sampled.
        let inputs = |x: u32, y: u32, offset: f64| {
            source.inputs_at(&[[(f64::from(x) + offset) / n, (f64::from(y) + offset) / n]])
        };
        let blends = (1..size)
            .flat_map(|y| (1..size).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                let around = [(x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y)];
                let around = around.map(|(x, y)| inputs(x, y, 0.5));
                inputs(x, y, 0.0).all_mean_of(around.each_ref(), BLEND_TOLERANCE)
            })
            .count() as u64;
        assert_eq!(result.blended_corners, blends);
        let corners = u64::from(size * size);
        assert!(
            blends > corners / 2 && blends < corners - 2 * 16,
            "most corners are blends, not all: {blends} of {corners}"
        );
    }

    /// The corner screen compares only the inputs a texture can bend; it is right only if
    /// every other input is affine in its texels. Each texture slot alone on noise: at every
    /// corner, the bent inputs are their centres' mean exactly where all inputs are.
    #[test]
    fn every_input_left_out_of_the_bent_ones_is_affine_in_its_texels() {
        let size = 8;
        let mut random = crate::test_random::Sequence::new(0x5eed_ba5e);
        let noise = image::RgbaImage::from_fn(size, size, |_, _| {
            image::Rgba(std::array::from_fn(|_| random.below(256) as u8))
        });
        let t = || json!({"index": 0});
        let slots = [
            json!({"pbrMetallicRoughness": {"baseColorTexture": t()}}),
            json!({"pbrMetallicRoughness": {"baseColorTexture": t()}, "alphaMode": "BLEND"}),
            json!({"pbrMetallicRoughness": {"baseColorTexture": t()}, "alphaMode": "MASK"}),
            json!({"pbrMetallicRoughness": {"metallicRoughnessTexture": t()}}),
            json!({"normalTexture": t()}),
            json!({"occlusionTexture": t()}),
            json!({"emissiveTexture": t(), "emissiveFactor": [1, 1, 1]}),
            json!({"extensions": {"KHR_materials_specular": {
                "specularTexture": t(), "specularColorTexture": t()}}}),
            json!({"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1],
                "sheenColorTexture": t(), "sheenRoughnessFactor": 1, "sheenRoughnessTexture": t()}}}),
            json!({"extensions": {"KHR_materials_anisotropy": {
                "anisotropyStrength": 1, "anisotropyTexture": t()}}}),
            json!({"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1,
                "clearcoatTexture": t(), "clearcoatRoughnessFactor": 1,
                "clearcoatRoughnessTexture": t()}}}),
            json!({"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1,
                "clearcoatNormalTexture": t()}}}),
            json!({"extensions": {"KHR_materials_transmission": {
                "transmissionFactor": 1, "transmissionTexture": t()}}}),
            json!({"extensions": {"KHR_materials_diffuse_transmission": {
                "diffuseTransmissionFactor": 1, "diffuseTransmissionTexture": t(),
                "diffuseTransmissionColorTexture": t()}}}),
            json!({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                "KHR_materials_volume": {"thicknessFactor": 1, "thicknessTexture": t(),
                "attenuationColor": [0.5, 0.7, 0.9], "attenuationDistance": 0.5}}}),
            json!({"extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1,
                "iridescenceTexture": t(), "iridescenceThicknessTexture": t()}}}),
            json!({"extensions": {"KHR_materials_pbrSpecularGlossiness": {
                "diffuseTexture": t()}}}),
            json!({"extensions": {"KHR_materials_pbrSpecularGlossiness": {
                "specularGlossinessTexture": t()}}}),
        ];
        let n = f64::from(size);
        let (mut blends, mut bent) = (0, 0);
        for slot in slots {
            let material = MaterialSource::gltf2(
                &slot,
                &[Some(crate::shade::sample::texture_of(noise.clone()))],
            );
            let inputs = |x: u32, y: u32, offset: f64| {
                material.inputs_at(&[[(f64::from(x) + offset) / n, (f64::from(y) + offset) / n]])
            };
            for (x, y) in (1..size).flat_map(|y| (1..size).map(move |x| (x, y))) {
                let around = [(x - 1, y - 1), (x, y - 1), (x - 1, y), (x, y)];
                let around = around.map(|(x, y)| inputs(x, y, 0.5));
                let corner = inputs(x, y, 0.0);
                let all = corner.all_mean_of(around.each_ref(), BLEND_TOLERANCE);
                let screened = is_mean_of(
                    &corner.bent(),
                    around.each_ref().map(|m| m.bent()).each_ref(),
                    BLEND_TOLERANCE,
                );
                assert_eq!(all, screened, "{slot} at corner ({x}, {y})");
                (blends, bent) = (blends + usize::from(all), bent + usize::from(!all));
            }
        }
        // Both kinds occur: affine slots blend, bending ones do not.
        assert!(blends > 0 && bent > 0, "{blends} blends, {bent} bent");
    }
}
