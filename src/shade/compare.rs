//! Do two materials render the same? Both are evaluated on a UV grid (at least as fine as
//! their finest texture) for a fixed, stratified set of view/light directions including
//! grazing ones; each result becomes the colour a viewer shows and the two colours are
//! compared with CIEDE2000.
//!
//! The light: one directional light of irradiance π at normal incidence, so a white
//! Lambertian surface lit head-on has radiance 1. Unlit materials emit their colour. The
//! radiance is then exposed and tone-mapped with Khronos PBR Neutral ([`super::tone`]) before
//! CIELAB, as a viewer shows it: L* stays within 0–100, so ΔE 1 is about one just-noticeable
//! difference on a display. (CIELAB is taken of the tone-mapped linear colour, which is what
//! decoding its sRGB encoding gives back.)

use super::brdf::{Geometry, V3};
use super::delta_e::{ciede2000, lab_from_linear_srgb};
use super::lanes::{channels, Lanes, Real};
use super::material::{Inputs, Shader};
use super::sample::MaterialSource;
use super::tone::displayed;
use std::f64::consts::PI;
use std::sync::Arc;

/// The default verdict threshold: ΔE2000 1, about one just-noticeable difference on what a
/// viewer shows (`compare --threshold`, the upgrade proof, the factor fit).
pub const DEFAULT_THRESHOLD: f64 = 1.0;

const DIRECTION_COUNT: usize = 8;

/// (θ_v, θ_l, φ between them), degrees: head-on, off-specular, mirror, crossed (anisotropy)
/// and grazing configurations; the view lies along the tangent (φ_v = 0), which is where an
/// anisotropy angle of 0 points.
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

/// Where the largest difference was found.
#[derive(Debug, Clone, PartialEq)]
pub struct Worst {
    /// Its ΔE2000.
    pub delta_e: f64,
    /// Its texture coordinates.
    pub uv: [f64; 2],
    /// (θ_v, θ_l, φ) in degrees.
    pub directions: (f64, f64, f64),
}

/// The ΔE2000 figures of one material pair.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Largest ΔE2000.
    pub max: f64,
    /// 99th percentile ΔE2000.
    pub p99: f64,
    /// Mean ΔE2000.
    pub mean: f64,
    /// Where the largest was.
    pub worst: Worst,
    /// Grid size per side and the number of (texel, direction) samples compared.
    pub grid: u32,
    /// Texels × directions evaluated.
    pub samples: u64,
    /// The largest ΔE over the directions, per texel (row-major), for heat maps; empty
    /// unless [`TexelMap::Kept`]. Shared: the outcomes of an asset's many identical pairs
    /// hold one map.
    pub per_texel: Arc<[f32]>,
}

/// Whether a comparison keeps its per-texel map, for a heat map: grid² floats (16 MB for a
/// 2048² texture), which a proof of 10^3 distinct materials could not hold for each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexelMap {
    /// Kept in [`Comparison::per_texel`].
    Kept,
    /// Not kept: `per_texel` is empty.
    Dropped,
}

fn direction(theta: f64, phi: f64) -> V3 {
    let (t, p) = (theta.to_radians(), phi.to_radians());
    [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
}

/// One texel's colours for every direction pair, channel by channel, direction per lane.
type Colours = [Lanes<DIRECTION_COUNT>; 3];

/// The fixed direction pairs, evaluated together (one per lane).
struct Directions {
    geometry: Geometry<Lanes<DIRECTION_COUNT>>,
    /// π · NdotL: the exposure's light scaled by the cosine.
    irradiance: Lanes<DIRECTION_COUNT>,
    /// (θ_v, θ_l, φ) for reports.
    angles: [(f64, f64, f64); DIRECTION_COUNT],
}

impl Directions {
    fn new() -> Directions {
        let pairs =
            DIRECTIONS.map(|(tv, tl, phi)| Geometry::new(direction(tv, 0.0), direction(tl, phi)));
        Directions {
            geometry: Geometry::lanes(&pairs),
            irradiance: Lanes(pairs.map(|g| g.l[2] * PI)),
            angles: DIRECTIONS,
        }
    }

    /// The linear colour a material reflects towards each view from a unit light.
    #[inline(always)]
    fn colours(&self, shader: &Shader, m: &Inputs) -> Colours {
        if m.unlit {
            return channels(|i| Lanes::splat(m.base_color[i]));
        }
        let f = shader.brdf(m, &self.geometry);
        channels(|i| f[i] * self.irradiance)
    }
}

/// The largest ΔE2000 over the direction pairs between any of `sources` and `target` at one
/// point (what `compare` computes per texel, for each reading of a source), for fitting
/// factors.
pub fn worst_at_point(shader: &Shader, sources: &[Inputs], target: &Inputs) -> f64 {
    static DIRECTIONS: std::sync::OnceLock<Directions> = std::sync::OnceLock::new();
    let directions = DIRECTIONS.get_or_init(Directions::new);
    let lab = |inputs: &Inputs| {
        let c = directions.colours(shader, inputs);
        let mut lab = [[0.0; 3]; DIRECTION_COUNT];
        for (d, lab) in lab.iter_mut().enumerate() {
            *lab = lab_from_linear_srgb(displayed([c[0].0[d], c[1].0[d], c[2].0[d]]));
        }
        lab
    };
    let target = lab(target);
    let mut worst = 0f64;
    for source in sources {
        for (source, target) in lab(source).into_iter().zip(target) {
            worst = worst.max(ciede2000(source, target));
        }
    }
    worst
}

/// Distinct texels whose samples are converted to ΔE together.
const BATCH_TEXELS: usize = 8;
const BATCH: usize = BATCH_TEXELS * DIRECTION_COUNT;

/// A batch's colours, channel by channel, sample by sample (texel-major).
struct Batch {
    a: [[f64; BATCH]; 3],
    b: [[f64; BATCH]; 3],
}

impl Batch {
    fn put(colours: &mut [[f64; BATCH]; 3], texel: usize, c: Colours) {
        let at = texel * DIRECTION_COUNT;
        for (channel, lanes) in colours.iter_mut().zip(c) {
            channel[at..at + DIRECTION_COUNT].copy_from_slice(&lanes.0);
        }
    }

    /// ΔE2000 of every sample: one scalar formula in a loop over independent samples, which
    /// the compiler turns into vector code (its long dependency chains then overlap).
    #[inline(always)]
    fn delta_e(&self) -> [f64; BATCH] {
        let mut out = [0.0; BATCH];
        for (i, delta) in out.iter_mut().enumerate() {
            let a = [self.a[0][i], self.a[1][i], self.a[2][i]];
            let b = [self.b[0][i], self.b[1][i], self.b[2][i]];
            *delta = ciede2000(
                lab_from_linear_srgb(displayed(a)),
                lab_from_linear_srgb(displayed(b)),
            );
        }
        out
    }
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
}

struct Partial {
    /// `None` when the map is [`TexelMap::Dropped`].
    per_texel: Option<Vec<f32>>,
    sum: f64,
    count: u64,
    worst: Worst,
    histogram: Vec<u32>,
}

/// The finest UV grid compared: 4096² texel centres × every direction is already minutes.
pub const MAX_GRID: u32 = 4096;

/// Compares `a` with `b` on a `grid`² UV grid (texel centres, at most [`MAX_GRID`]); `grid` 0
/// picks the finest texture resolution of either (at least 16).
pub fn compare(shader: &Shader, a: &MaterialSource, b: &MaterialSource, grid: u32) -> Comparison {
    let mut each = compare_readings(shader, std::slice::from_ref(a), b, grid, TexelMap::Kept);
    each.pop().unwrap_or_else(|| merge(Vec::new(), 0))
}

/// Compares each of `readings` (one material read several ways: the same textures and
/// texture coordinates) with `b`, in one pass over the grid: `b` is sampled once per texel
/// for all of them. One comparison per reading, in order; the grid is as in [`compare`].
pub fn compare_readings(
    shader: &Shader,
    readings: &[MaterialSource],
    b: &MaterialSource,
    grid: u32,
    map: TexelMap,
) -> Vec<Comparison> {
    let finest = (readings.iter().map(MaterialSource::max_resolution)).fold(1, u32::max);
    let grid = if grid == 0 {
        finest.max(b.max_resolution()).max(16)
    } else {
        grid
    }
    .min(MAX_GRID);
    let job = Job {
        shader,
        readings,
        b,
        grid,
        directions: Directions::new(),
        map,
    };
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
    let rows_per_thread = grid.div_ceil(threads);
    let by_thread: Vec<Vec<Partial>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let rows = (t * rows_per_thread)..((t + 1) * rows_per_thread).min(grid);
                let job = &job;
                scope.spawn(move || compare_rows(job, rows))
            })
            .collect();
        handles.into_iter().filter_map(|h| h.join().ok()).collect()
    });
    (0..readings.len())
        .map(|r| {
            let partials = by_thread.iter().filter_map(|each| each.get(r));
            merge(partials, grid)
        })
        .collect()
}

/// The rows' samples, with the widest vector instructions the CPU has: the texel loop is
/// plain arithmetic, so compiling it for AVX-512 or AVX2 changes its speed, not its results
/// (no fused multiply-adds are formed; each lane rounds exactly as scalar `f64` does).
fn compare_rows(job: &Job, rows: std::ops::Range<u32>) -> Vec<Partial> {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        if has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
            // SAFETY: the CPU has just been found to support these features.
            return unsafe { compare_rows_avx512(job, rows) };
        }
        if has!("avx2") {
            // SAFETY: as above.
            return unsafe { compare_rows_avx2(job, rows) };
        }
    }
    compare_rows_inline(job, rows)
}

/// # Safety
/// The CPU must support AVX-512 F, DQ and VL.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
unsafe fn compare_rows_avx512(job: &Job, rows: std::ops::Range<u32>) -> Vec<Partial> {
    compare_rows_inline(job, rows)
}

/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn compare_rows_avx2(job: &Job, rows: std::ops::Range<u32>) -> Vec<Partial> {
    compare_rows_inline(job, rows)
}

#[inline(always)]
fn compare_rows_inline(job: &Job, rows: std::ops::Range<u32>) -> Vec<Partial> {
    let Job {
        shader,
        readings,
        b,
        grid,
        ref directions,
        map,
    } = *job;
    let mut partials: Vec<Partial> = readings
        .iter()
        .map(|_| Partial::new(rows.len() * grid as usize, map))
        .collect();
    let mut batches: Vec<Batch> = readings
        .iter()
        .map(|_| Batch {
            a: [[0.0; BATCH]; 3],
            b: [[0.0; BATCH]; 3],
        })
        .collect();
    let texel_uv = |x: u32, y: u32| {
        [
            (f64::from(x) + 0.5) / f64::from(grid),
            (f64::from(y) + 0.5) / f64::from(grid),
        ]
    };
    for y in rows {
        let mut row_of: Vec<Row> = readings.iter().map(|_| Row::default()).collect();
        for x in 0..grid {
            let uv = texel_uv(x, y);
            let target = b.inputs_at(&[uv, uv]);
            let each = (readings.iter()).zip(&mut row_of).zip(&mut batches);
            for (((a, row), batch), partial) in each.zip(&mut partials) {
                let source = a.inputs_at(&[uv, uv]);
                if source == target {
                    // Identical inputs give identical colours, whose ΔE is exactly 0: added
                    // at once unless texels before it wait for their batch. (The previous
                    // texel is left as it was: no texel with differing inputs equals this.)
                    match row.pending.is_empty() {
                        true => partial.add_equal_texel(uv, &directions.angles),
                        false => row.pending.push((x, Source::Zero)),
                    }
                    continue;
                }
                let inputs = (source, target.clone());
                let source = if let Some(same) = row.repeat_of(&inputs) {
                    // A texel like the one before (a flat region of a texture) has its ΔE.
                    same
                } else {
                    let slot = row.unique;
                    Batch::put(&mut batch.a, slot, directions.colours(shader, &inputs.0));
                    Batch::put(&mut batch.b, slot, directions.colours(shader, &inputs.1));
                    row.unique += 1;
                    Source::Slot(slot)
                };
                row.previous = Some((inputs, source));
                row.pending.push((x, source));
                if row.unique == BATCH_TEXELS {
                    row.flush(batch, partial, |x| texel_uv(x, y), &directions.angles);
                }
            }
        }
        let each = (row_of.iter_mut()).zip(&batches).zip(&mut partials);
        for ((row, batch), partial) in each {
            row.flush(batch, partial, |x| texel_uv(x, y), &directions.angles);
        }
    }
    partials
}

/// Where a texel's ΔE samples come from.
#[derive(Clone, Copy)]
enum Source {
    /// Both materials have the same inputs there.
    Zero,
    /// A texel of the batch being filled.
    Slot(usize),
    /// Already computed (a repeat of a texel of an earlier batch).
    Known([f64; DIRECTION_COUNT]),
}

/// The texels of one grid row waiting for their batch's ΔE, in order.
#[derive(Default)]
struct Row {
    /// (x, where its samples come from), in row order.
    pending: Vec<(u32, Source)>,
    /// Texels put into the batch so far.
    unique: usize,
    /// The last texel's inputs and samples: equal inputs give equal colours.
    previous: Option<((Inputs, Inputs), Source)>,
}

impl Row {
    fn repeat_of(&self, inputs: &(Inputs, Inputs)) -> Option<Source> {
        let (previous, source) = self.previous.as_ref()?;
        (previous == inputs).then_some(*source)
    }

    /// Computes the batch's ΔE and hands every pending texel to `partial`, in row order.
    /// Inlined so that the ΔE loop is compiled with the caller's vector instructions.
    #[inline(always)]
    fn flush(
        &mut self,
        batch: &Batch,
        partial: &mut Partial,
        uv: impl Fn(u32) -> [f64; 2],
        angles: &[(f64, f64, f64)],
    ) {
        let deltas = if self.unique > 0 {
            batch.delta_e()
        } else {
            [0.0; BATCH]
        };
        let samples = |source: Source| match source {
            Source::Zero => [0.0; DIRECTION_COUNT],
            Source::Slot(k) => std::array::from_fn(|i| deltas[k * DIRECTION_COUNT + i]),
            Source::Known(known) => known,
        };
        for (x, source) in self.pending.drain(..) {
            match source {
                Source::Zero => partial.add_equal_texel(uv(x), angles),
                _ => partial.add_texel(uv(x), &samples(source), angles),
            }
        }
        if let Some((_, source)) = &mut self.previous {
            *source = Source::Known(samples(*source));
        }
        self.unique = 0;
    }
}

impl Partial {
    fn new(texels: usize, map: TexelMap) -> Partial {
        Partial {
            per_texel: (map == TexelMap::Kept).then(|| Vec::with_capacity(texels)),
            sum: 0.0,
            count: 0,
            worst: Worst {
                delta_e: -1.0,
                uv: [0.0, 0.0],
                directions: (0.0, 0.0, 0.0),
            },
            histogram: vec![0; BINS],
        }
    }

    /// A texel where both materials have the same inputs: ΔE 0 in every direction. (Most
    /// texels of an exact conversion; the general path would update the histogram one
    /// sample at a time.)
    fn add_equal_texel(&mut self, uv: [f64; 2], angles: &[(f64, f64, f64)]) {
        self.count += DIRECTION_COUNT as u64;
        self.histogram[0] += DIRECTION_COUNT as u32;
        if self.worst.delta_e < 0.0 {
            self.worst = Worst {
                delta_e: 0.0,
                uv,
                directions: angles[0],
            };
        }
        self.note_texel(0.0);
    }

    fn note_texel(&mut self, max: f32) {
        if let Some(map) = &mut self.per_texel {
            map.push(max);
        }
    }

    fn add_texel(&mut self, uv: [f64; 2], deltas: &[f64], angles: &[(f64, f64, f64)]) {
        let mut texel_max = 0f64;
        for (&delta, &angles) in deltas.iter().zip(angles) {
            let delta = if delta.is_finite() { delta } else { f64::MAX };
            texel_max = texel_max.max(delta);
            self.sum += delta.min(1e6);
            self.count += 1;
            let bin = ((delta * BINS_PER_UNIT) as usize).min(BINS - 1);
            self.histogram[bin] += 1;
            if delta > self.worst.delta_e {
                self.worst = Worst {
                    delta_e: delta,
                    uv,
                    directions: angles,
                };
            }
        }
        self.note_texel(texel_max as f32);
    }
}

fn merge<'p>(partials: impl IntoIterator<Item = &'p Partial>, grid: u32) -> Comparison {
    let mut histogram = vec![0u64; BINS];
    let mut per_texel = Vec::new();
    let (mut sum, mut count) = (0.0, 0u64);
    // The first worst sample seen (in row order) wins ties, so a comparison with ΔE 0
    // everywhere names a real texel.
    let mut worst: Option<Worst> = None;
    // Partials come in row order: their texels concatenate into the grid.
    for p in partials {
        per_texel.extend(p.per_texel.iter().flatten());
        sum += p.sum;
        count += p.count;
        for (total, n) in histogram.iter_mut().zip(&p.histogram) {
            *total += u64::from(*n);
        }
        if worst.as_ref().is_none_or(|w| p.worst.delta_e > w.delta_e) {
            worst = Some(p.worst.clone());
        }
    }
    let worst = worst.unwrap_or(Worst {
        delta_e: 0.0,
        uv: [0.0, 0.0],
        directions: (0.0, 0.0, 0.0),
    });
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
        mean: sum / count.max(1) as f64,
        worst,
        grid,
        samples: count,
        per_texel: per_texel.into(),
    }
}

#[cfg(test)]
mod sensitivity;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::brdf::SheenVisibility;
    use crate::shade::sheen_table::SheenTable;
    use serde_json::json;

    fn shader() -> Shader {
        Shader::new(SheenTable::compute(4, SheenVisibility::Charlie))
    }

    fn gltf2(material: serde_json::Value) -> MaterialSource {
        MaterialSource::gltf2(&material, &[])
    }

    #[test]
    fn repeated_texels_reuse_their_samples_exactly() {
        // A 48² base colour in runs of three texels (16 distinct per row, so a run continues
        // after its batch of 8 is converted), against the same with another roughness: each
        // texel's ΔE, computed alone, must equal what the row-wise reuse reports.
        let palette = [
            [200, 40, 40],
            [40, 200, 40],
            [40, 40, 200],
            [128, 128, 128],
            [10, 10, 10],
        ];
        let image = image::RgbImage::from_fn(48, 48, |x, y| {
            image::Rgb(palette[((x / 3 + y) % 5) as usize])
        });
        let mut png = Vec::new();
        image::DynamicImage::ImageRgb8(image)
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        let textures = crate::shade::sample::decode_all(&[Some(Ok(png))]).unwrap();
        let textured = |roughness: f64| {
            MaterialSource::gltf2(
                &json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                    "metallicFactor": 0.0, "roughnessFactor": roughness}}),
                &textures,
            )
        };
        let (a, b) = (textured(0.5), textured(0.6));
        let shader = shader();
        let result = compare(&shader, &a, &b, 48);
        for y in 0..48 {
            for x in 0..48 {
                let uv = [(x as f64 + 0.5) / 48.0, (y as f64 + 0.5) / 48.0];
                let alone =
                    worst_at_point(&shader, &[a.inputs_at(&[uv, uv])], &b.inputs_at(&[uv, uv]));
                assert_eq!(
                    result.per_texel[y * 48 + x],
                    alone as f32,
                    "texel ({x}, {y})"
                );
            }
        }
        assert!(
            result.max > 1.0,
            "the roughness change shows: {}",
            result.max
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
        assert_eq!(result.samples, 64 * DIRECTIONS.len() as u64);
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
        let together = compare_readings(&shader(), &readings, &target, 8, TexelMap::Kept);
        assert_eq!(together.len(), readings.len());
        for (reading, result) in readings.iter().zip(&together) {
            assert_eq!(result, &compare(&shader(), reading, &target, 8));
        }
        assert_eq!(together[1].max, 0.0);
        assert!(together[2].max > together[0].max && together[0].max > 0.0);
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_vector_instruction_paths_give_the_portable_results_bit_for_bit() {
        use std::arch::is_x86_feature_detected as has;
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
            };
            // 20 texels per row: two full batches and a partial one.
            let [portable] = &compare_rows_inline(&job, 0..3)[..] else {
                panic!("one reading, one partial");
            };
            assert!(portable.sum > 1.0, "the materials differ: {}", portable.sum);
            let mut vector = Vec::new();
            if has!("avx2") {
                // SAFETY: AVX2 support was checked.
                vector.extend(unsafe { compare_rows_avx2(&job, 0..3) });
            }
            if has!("avx512f") && has!("avx512dq") && has!("avx512vl") {
                // SAFETY: AVX-512 support was checked.
                vector.extend(unsafe { compare_rows_avx512(&job, 0..3) });
            }
            for v in &vector {
                assert_eq!(portable.sum.to_bits(), v.sum.to_bits());
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
}
