//! Material previews: a material ball under a fixed studio rig, tone mapped with Khronos PBR
//! Neutral and encoded as sRGB; and ΔE heat maps.
//!
//! The rig (documented, fixed so previews are comparable across runs and machines):
//! an orthographic camera looking down −z at a unit sphere (y up); three directional lights
//! — key from (−1, 1, 1) with irradiance 2.5, fill from (1, 0.3, 0.8) with 0.8, rim from
//! (0.2, 0.8, −1) with 1.5 — and a uniform sky of radiance 0.3 integrated per pixel by multiple
//! importance sampling of 64 stratified cosine-weighted directions and 64 reflections about
//! GGX visible normals (of the anisotropic lobe, stretched along the anisotropy direction,
//! when there is one),
//! the pattern turned about the normal by a fixed per-pixel angle. The sphere's UVs are equirectangular
//! (u = ½ + φ/2π, v = θ/π) with the analytic tangent along increasing u.
//!
//! Each light is seen through [`appearance::seen`]: normal and clearcoat-normal maps turn
//! the frames on the ball's tangent frame, the clearcoat is layered, the sky is the ambient
//! light that occlusion darkens, emission is added under the coat; behind the ball a
//! checkerboard shows through what its coverage and transmission let pass.

use crate::gltf::color::linear_to_srgb8;
use crate::shade::appearance::{self, Seen};
use crate::shade::brdf::{
    anisotropic_alphas, cross, dot, ggx_aniso_d, into_anisotropy_frame, normalize, Geometry, V3,
};
use crate::shade::material::{Inputs, Shader};
use crate::shade::sample::MaterialSource;
use crate::shade::tone::displayed;
use image::{Rgb, RgbImage};
use std::f64::consts::PI;

const LIGHTS: [(V3, f64); 3] = [
    ([-1.0, 1.0, 1.0], 2.5),
    ([1.0, 0.3, 0.8], 0.8),
    ([0.2, 0.8, -1.0], 1.5),
];
const SKY_RADIANCE: f64 = 0.3;
const SKY_SAMPLES_PER_SIDE: usize = 8;
/// Between a contact sheet's cells.
const SHEET_BACKGROUND: [u8; 3] = [46, 46, 50];

/// The backdrop's two radiances and its squares per ball width: a pattern, so that what a
/// surface lets through reads as such.
const CHECKER: [f64; 2] = [0.02, 0.35];
const CHECKER_SQUARES: f64 = 8.0;

/// The backdrop's radiance at image position (x, y) in −1..1.
fn backdrop(x: f64, y: f64) -> f64 {
    let square = |c: f64| ((c + 1.0) * CHECKER_SQUARES / 2.0).floor() as i64;
    CHECKER[(square(x) + square(y)).rem_euclid(2) as usize]
}

/// Stratified points of the unit square (`n`² of them), shared by both sky sampling strategies.
fn sky_directions(n: usize) -> Vec<[f64; 2]> {
    (0..n * n)
        .map(|k| {
            [
                ((k / n) as f64 + 0.5) / n as f64,
                ((k % n) as f64 + 0.5) / n as f64,
            ]
        })
        .collect()
}

/// The material's specular lobe for sampling: GGX roughnesses along the anisotropy direction
/// and across it (equal when isotropic), and that direction's angle in the tangent plane.
struct Lobe {
    alpha_t: f64,
    alpha_b: f64,
    angle: f64,
}

impl Lobe {
    /// The sharpest specular lobe of `inputs`: a clearcoat smoother than the base is
    /// sampled instead of it (the cosine samples cover the broader one), so that a glossy
    /// coat over a rough base reflects the sky without sparkles.
    fn of(inputs: &crate::shade::material::Inputs) -> Lobe {
        let coat = inputs.clearcoat > 0.0 && inputs.clearcoat_roughness < inputs.roughness;
        if coat {
            let alpha = (inputs.clearcoat_roughness.powi(2)).max(1e-3);
            return Lobe {
                alpha_t: alpha,
                alpha_b: alpha,
                angle: 0.0,
            };
        }
        let alpha = (inputs.roughness * inputs.roughness).max(1e-3);
        let (alpha_t, alpha_b) = anisotropic_alphas(alpha, inputs.anisotropy_strength);
        Lobe {
            alpha_t,
            alpha_b,
            angle: inputs.anisotropy_angle,
        }
    }

    /// Into the lobe's frame (t along the anisotropy direction) and back.
    fn to_lobe(&self, w: V3) -> V3 {
        into_anisotropy_frame(w, self.angle)
    }

    fn out_of_lobe(&self, w: V3) -> V3 {
        into_anisotropy_frame(w, -self.angle)
    }

    /// A half-vector distributed as the normals `v` sees (Heitz 2018, "Sampling the GGX
    /// Distribution of Visible Normals"), from a point of the unit square turned by `phi`
    /// (radians): on the stretched ellipse of an anisotropic lobe, a circle otherwise. Unlike
    /// sampling D(h)·(n·h), almost no reflection lands under the horizon, which a lobe
    /// stretched to α 0.8 would otherwise waste half its samples on at grazing views.
    fn half_vector(&self, v: V3, u1: f64, phi: f64) -> V3 {
        let v = self.to_lobe(v);
        let stretched = normalize([self.alpha_t * v[0], self.alpha_b * v[1], v[2]]);
        let length2 = stretched[0] * stretched[0] + stretched[1] * stretched[1];
        let t1 = if length2 > 0.0 {
            let length = length2.sqrt();
            [-stretched[1] / length, stretched[0] / length, 0.0]
        } else {
            [1.0, 0.0, 0.0]
        };
        let t2 = cross(stretched, t1);
        let r = u1.sqrt();
        let (a, b) = (r * phi.cos(), r * phi.sin());
        let s = 0.5 * (1.0 + stretched[2]);
        let b = (1.0 - s) * (1.0 - a * a).max(0.0).sqrt() + s * b;
        let up = (1.0 - a * a - b * b).max(0.0).sqrt();
        let n = [0, 1, 2].map(|i| a * t1[i] + b * t2[i] + up * stretched[i]);
        let h = normalize([self.alpha_t * n[0], self.alpha_b * n[1], n[2].max(0.0)]);
        self.out_of_lobe(h)
    }

    /// The density of `l` as the reflection of `v` about a half-vector from
    /// [`half_vector`](Self::half_vector): G1(v)·D(h) / (4·(n·v)).
    fn pdf(&self, v: V3, l: V3) -> f64 {
        let h = normalize([v[0] + l[0], v[1] + l[1], v[2] + l[2]]);
        let lobe_v = self.to_lobe(v);
        let slope2 = ((self.alpha_t * lobe_v[0]).powi(2) + (self.alpha_b * lobe_v[1]).powi(2))
            / (lobe_v[2] * lobe_v[2]).max(1e-300);
        let g1 = 2.0 / (1.0 + (1.0 + slope2).sqrt());
        g1 * ggx_aniso_d(self.alpha_t, self.alpha_b, self.to_lobe(h)) / (4.0 * v[2].max(1e-9))
    }
}

/// The uniform sky by multiple importance sampling (balance heuristic): every point gives
/// one cosine-weighted direction and one reflection of `v` about a visible normal sampled
/// from the material's GGX lobe (anisotropic when it is), each weighted by
/// 1 / (N·pdf_cos + N·pdf_ggx) at that direction.
fn sky_radiance(shader: &Shader, inputs: &Inputs, v: V3, points: &[[f64; 2]], turn: f64) -> V3 {
    let lobe = Lobe::of(inputs);
    let inputs = &reflecting(inputs);
    let n = points.len() as f64;
    let pdf_cos = |l: V3| l[2].max(0.0) / PI;
    let mut total = [0.0; 3];
    for &[u1, u2] in points {
        let phi = 2.0 * PI * u2 + turn;
        let r = u1.sqrt();
        let cosine = [r * phi.cos(), r * phi.sin(), (1.0 - u1).sqrt()];
        let h = lobe.half_vector(v, u1, phi);
        let v_dot_h = dot(v, h);
        let reflected = [0, 1, 2].map(|i| 2.0 * v_dot_h * h[i] - v[i]);
        for l in [cosine, reflected] {
            if l[2] <= 0.0 {
                continue;
            }
            let reflected = lit(shader, inputs, v, l);
            let weight = SKY_RADIANCE / PI / (n * pdf_cos(l) + n * lobe.pdf(v, l));
            for c in 0..3 {
                total[c] += reflected[c] * weight;
            }
        }
    }
    total
}

/// `inputs` as they reflect a light and nothing else: nothing emitted, no ambient light,
/// full coverage.
fn reflecting(inputs: &Inputs) -> Inputs {
    Inputs {
        emission: [0.0; 3],
        occlusion: 0.0,
        coverage: 1.0,
        ..inputs.clone()
    }
}

/// The radiance `reflecting` inputs (see [`reflecting`]) send towards `v` from a light of
/// irradiance π at normal incidence from `l` (both in the ball's tangent frame), with the
/// maps' frames and the clearcoat, as [`appearance::seen`] has them.
fn lit(shader: &Shader, reflecting: &Inputs, v: V3, l: V3) -> V3 {
    appearance::seen(shader, reflecting, &Geometry::new(v, l)).own
}

/// Linear radiance of pixel (x, y) of a `size`² image: the ball where it is, the backdrop
/// through and around it.
fn shade_pixel(
    shader: &Shader,
    material: &MaterialSource,
    sky: &[[f64; 2]],
    x: u32,
    y: u32,
    size: u32,
) -> V3 {
    let px = (f64::from(x) + 0.5) / f64::from(size) * 2.0 - 1.0;
    let py = 1.0 - (f64::from(y) + 0.5) / f64::from(size) * 2.0;
    let behind = backdrop(px, py);
    let r2 = px * px + py * py;
    if r2 >= 1.0 {
        return [behind; 3];
    }
    let n = [px, py, (1.0 - r2).sqrt()];
    let phi = n[0].atan2(n[2]);
    let uv = [0.5 + phi / (2.0 * PI), n[1].clamp(-1.0, 1.0).acos() / PI];
    let inputs = material.inputs_at(&[uv]);
    let t = normalize([phi.cos(), 0.0, -phi.sin()]);
    let b = cross(n, t);
    let local = |w: V3| [dot(w, t), dot(w, b), dot(w, n)];
    let v = local([0.0, 0.0, 1.0]);
    // The surface's own parts, seen one at a time through the one appearance model.
    let reflecting = reflecting(&inputs);
    // With the light under the surface nothing is reflected: what is left is the emission
    // (under the coat) and what shows through.
    let rest: Seen<f64> = appearance::seen(
        shader,
        &Inputs {
            occlusion: 0.0,
            coverage: 1.0,
            ..inputs.clone()
        },
        &Geometry::new(v, [0.0, 0.0, -1.0]),
    );
    let mut radiance = rest.own;
    if !inputs.unlit {
        for (direction, irradiance) in LIGHTS {
            let l = local(normalize(direction));
            if l[2] > 0.0 {
                let reflected = lit(shader, &reflecting, v, l);
                for c in 0..3 {
                    radiance[c] += reflected[c] * irradiance / PI;
                }
            }
        }
        // The sampling pattern is turned by a fixed per-pixel angle (from a hash of the
        // pixel, so renders are reproducible): fine noise instead of bands.
        let turn =
            f64::from((x.wrapping_mul(0x9E37_79B9) ^ y.wrapping_mul(0x85EB_CA6B)) % 6283) / 1000.0;
        let sky_light = sky_radiance(shader, &reflecting, v, sky, turn);
        for c in 0..3 {
            radiance[c] += sky_light[c] * inputs.occlusion;
        }
    }
    let coverage = inputs.coverage;
    std::array::from_fn(|c| {
        radiance[c] * coverage + behind * (rest.through[c] * coverage + 1.0 - coverage)
    })
}

fn encode(linear: V3) -> Rgb<u8> {
    Rgb(displayed(linear).map(linear_to_srgb8))
}

/// Renders one material ball.
pub(crate) fn material_ball(shader: &Shader, material: &MaterialSource, size: u32) -> RgbImage {
    ball_with_sky(
        shader,
        material,
        size,
        &sky_directions(SKY_SAMPLES_PER_SIDE),
    )
}

/// A material ball whose sky is integrated with the points `sky`.
fn ball_with_sky(
    shader: &Shader,
    material: &MaterialSource,
    size: u32,
    sky: &[[f64; 2]],
) -> RgbImage {
    let size = size.max(8);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
    let rows_per_thread = size.div_ceil(threads);
    let mut image = RgbImage::new(size, size);
    let row_bytes = size as usize * 3;
    std::thread::scope(|scope| {
        for (chunk, rows) in image
            .chunks_mut(rows_per_thread as usize * row_bytes)
            .enumerate()
        {
            scope.spawn(move || {
                for (i, pixel) in rows.chunks_exact_mut(3).enumerate() {
                    let x = (i % size as usize) as u32;
                    let y = chunk as u32 * rows_per_thread + (i / size as usize) as u32;
                    let radiance = shade_pixel(shader, material, sky, x, y, size);
                    pixel.copy_from_slice(&encode(radiance).0);
                }
            });
        }
    });
    image
}

/// The largest ball's side, in pixels. A picture's time grows with its pixels (every pixel
/// integrates the sky), and a picture four times the default's side takes minutes.
pub const MAX_SIZE: u32 = 1024;

/// The most pixels a picture has: one ball of the largest size. A contact sheet shrinks its
/// cells to stay within it, so that its time and memory do not grow with the number of
/// materials times the size asked for.
pub const MAX_PIXELS: u64 = MAX_SIZE as u64 * MAX_SIZE as u64;

/// The smallest cell a contact sheet draws.
const MIN_CELL: u32 = 8;

/// Where a contact sheet puts its cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SheetLayout {
    /// Cells per row.
    pub columns: u32,
    /// Rows of cells.
    pub rows: u32,
    /// Pixels per side of a cell.
    pub cell: u32,
}

impl SheetLayout {
    /// Up to four cells to a row for up to 16 materials, else a near-square grid; cells of
    /// `size` pixels, or fewer when the sheet would pass [`MAX_PIXELS`]. `None` when not even
    /// cells of 8 pixels fit.
    pub fn new(materials: usize, size: u32) -> Option<SheetLayout> {
        let n = materials.max(1) as u64;
        let columns = n.min(4).max(n.isqrt() + u64::from(n.isqrt().pow(2) < n));
        let rows = n.div_ceil(columns);
        let fitting = (columns.checked_mul(rows)).map_or(0, |cells| (MAX_PIXELS / cells).isqrt());
        let cell = u64::from(size).min(fitting);
        (cell >= u64::from(MIN_CELL)).then_some(SheetLayout {
            columns: columns as u32,
            rows: rows as u32,
            cell: cell as u32,
        })
    }

    /// The (row, column) of cell `k`.
    pub fn place(&self, k: usize) -> (u32, u32) {
        let columns = self.columns as usize;
        ((k / columns) as u32, (k % columns) as u32)
    }
}

/// Balls of one size drawn so far, by material ([`MaterialSource::fingerprint`]): materials
/// alike (an exporter's copies, one per mesh) are drawn once.
pub(crate) struct Balls<'s> {
    shader: &'s Shader,
    size: u32,
    drawn: std::collections::HashMap<String, RgbImage>,
}

impl<'s> Balls<'s> {
    pub(crate) fn new(shader: &'s Shader, size: u32) -> Self {
        Balls {
            shader,
            size,
            drawn: Default::default(),
        }
    }

    /// The ball of `material`, drawn unless one alike was.
    pub(crate) fn of(&mut self, material: &MaterialSource) -> &RgbImage {
        let (shader, size) = (self.shader, self.size);
        (self.drawn.entry(material.fingerprint()))
            .or_insert_with(|| material_ball(shader, material, size))
    }
}

/// Every material's ball on one sheet laid out by `layout`, in material order, each with its
/// name written under it.
pub(crate) fn contact_sheet(
    shader: &Shader,
    materials: &[(&str, &MaterialSource)],
    layout: SheetLayout,
) -> RgbImage {
    let cell = layout.cell;
    let (width, height) = (layout.columns * cell, layout.rows * cell);
    let mut sheet = RgbImage::from_pixel(width, height, Rgb(SHEET_BACKGROUND));
    let scale = (cell / 96).max(1);
    let mut balls = Balls::new(shader, cell);
    for (i, (name, material)) in materials.iter().enumerate() {
        let ball = balls.of(material);
        let (row, column) = layout.place(i);
        let (cx, cy) = (column * cell, row * cell);
        for (x, y, p) in ball.enumerate_pixels() {
            sheet.put_pixel(cx + x, cy + y, *p);
        }
        let baseline = cy + cell - 7 * scale;
        super::label::draw(
            &mut sheet,
            name,
            (cx + 2 * scale, baseline),
            scale,
            cell - 4 * scale,
        );
    }
    sheet
}

/// An image as PNG bytes (encoding an RGB image into memory cannot fail).
pub fn png(image: &RgbImage) -> Vec<u8> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    let _ = image.write_to(&mut bytes, image::ImageFormat::Png);
    bytes.into_inner()
}

/// A ΔE heat map: black at 0, through blue and yellow, red at `threshold` and above; grey
/// off the mesh (a texel not a number), where nothing was sampled.
pub fn heatmap(per_texel: &[f32], grid: u32, threshold: f64) -> RgbImage {
    RgbImage::from_fn(grid, grid, |x, y| {
        let value = per_texel
            .get((y * grid + x) as usize)
            .map_or(0.0, |v| f64::from(*v));
        if value.is_nan() {
            return Rgb([96, 96, 96]);
        }
        let t = (value / threshold.max(1e-9)).clamp(0.0, 1.0);
        let stops = [
            [0.0, 0.0, 0.0],
            [0.1, 0.2, 0.9],
            [0.95, 0.85, 0.1],
            [0.9, 0.05, 0.05],
        ];
        let scaled = t * 3.0;
        let i = (scaled.floor() as usize).min(2);
        let f = scaled - i as f64;
        let c = [0, 1, 2].map(|k| stops[i][k] * (1.0 - f) + stops[i + 1][k] * f);
        Rgb(c.map(|v| (v * 255.0).round() as u8))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::brdf::SheenVisibility;
    use crate::shade::sheen_table::SheenTable;

    #[test]
    fn a_heat_map_runs_from_black_to_red_and_greys_what_was_not_sampled() {
        let map = heatmap(&[0.0, 1.0, 5.0, f32::NAN], 2, 1.0);
        assert_eq!(map.get_pixel(0, 0).0, [0, 0, 0]);
        assert_eq!(
            map.get_pixel(1, 0),
            map.get_pixel(0, 1),
            "red from the threshold on"
        );
        assert_eq!(map.get_pixel(1, 0).0, [230, 13, 13]);
        assert_eq!(map.get_pixel(1, 1).0, [96, 96, 96]);
    }

    /// An exporter's copies of one material (the same JSON under other names) are one ball.
    #[test]
    fn materials_alike_are_drawn_once_and_others_apart() {
        let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
        let material = |name: &str, roughness: f64| {
            let json = serde_json::json!({"name": name,
                "pbrMetallicRoughness": {"roughnessFactor": roughness}});
            MaterialSource::gltf2(&json, &[])
        };
        let mut balls = Balls::new(&shader, 8);
        let first = balls.of(&material("a", 0.5)).clone();
        assert_eq!(balls.of(&material("copy of a", 0.5)), &first);
        assert_eq!(balls.drawn.len(), 1);
        assert_ne!(balls.of(&material("b", 0.1)), &first);
        assert_eq!(balls.drawn.len(), 2);
    }

    #[test]
    fn a_sheet_of_up_to_sixteen_has_four_to_a_row_then_grows_square() {
        let layout = |n| SheetLayout::new(n, 64).unwrap();
        assert_eq!((layout(1).columns, layout(1).rows), (1, 1));
        assert_eq!((layout(3).columns, layout(3).rows), (3, 1));
        assert_eq!((layout(6).columns, layout(6).rows), (4, 2));
        assert_eq!((layout(16).columns, layout(16).rows), (4, 4));
        assert_eq!((layout(17).columns, layout(17).rows), (5, 4));
        assert_eq!((layout(10_000).columns, layout(10_000).rows), (100, 100));
        assert_eq!(layout(6).place(5), (1, 1));
        assert_eq!(layout(6).cell, 64);
    }

    #[test]
    fn a_sheet_shrinks_its_cells_to_its_pixel_limit_and_refuses_past_the_smallest_cell() {
        for (n, size) in [(100, 1024), (10_000, 64), (16_384, 8)] {
            let layout = SheetLayout::new(n, size).unwrap();
            let (width, height) = (layout.columns * layout.cell, layout.rows * layout.cell);
            assert!(
                u64::from(width) * u64::from(height) <= MAX_PIXELS,
                "{n}: {layout:?}"
            );
            assert!(layout.columns as usize * layout.rows as usize >= n);
            assert!((MIN_CELL..=size).contains(&layout.cell), "{n}: {layout:?}");
        }
        assert_eq!(SheetLayout::new(100, 1024).unwrap().cell, 102);
        assert_eq!(SheetLayout::new(10_000, 64).unwrap().cell, 10);
        assert_eq!(SheetLayout::new(16_384, 8).unwrap().cell, 8);
        assert_eq!(SheetLayout::new(16_385, 8), None);
        assert_eq!(SheetLayout::new(usize::MAX, 1024), None);
    }

    /// Root-mean-square difference, in 8-bit levels, between a ball as `render` draws it and
    /// the same ball with 16 times as many sky samples: the sampling noise, apart from the
    /// picture's own detail (a thin anisotropic streak is detail, not noise).
    fn sampling_noise(shader: &Shader, material: &MaterialSource) -> f64 {
        let size = 96;
        let drawn = material_ball(shader, material, size);
        let converged = ball_with_sky(
            shader,
            material,
            size,
            &sky_directions(4 * SKY_SAMPLES_PER_SIDE),
        );
        let squares: Vec<f64> = drawn
            .as_raw()
            .iter()
            .zip(converged.as_raw())
            .map(|(a, b)| (f64::from(*a) - f64::from(*b)).powi(2))
            .collect();
        (squares.iter().sum::<f64>() / squares.len() as f64).sqrt()
    }

    #[test]
    fn the_sky_estimate_converges_to_the_integral_it_samples() {
        // A wrong density in the multiple importance weights would bias the sky, however
        // many samples: compare with quadrature of f·cos·sky over the hemisphere.
        let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
        let theta = 60f64.to_radians();
        let v = [theta.sin(), 0.0, theta.cos()];
        for (strength, angle) in [(0.0, 0.0), (0.9, 0.0), (0.9, 1.0)] {
            let inputs = crate::shade::material::Inputs {
                base_color: [0.9; 3],
                roughness: 0.4,
                anisotropy_strength: strength,
                anisotropy_angle: angle,
                ..Default::default()
            };
            let estimate = sky_radiance(&shader, &inputs, v, &sky_directions(64), 0.3)[0];
            let exact = crate::shade::eval::quadrature::hemisphere(512, 512, |l| {
                shader.brdf(&inputs, &Geometry::new(v, l))[0] * l[2] * SKY_RADIANCE
            });
            assert!(
                (estimate - exact).abs() < 0.01 * exact,
                "strength {strength}, angle {angle}: {estimate} against {exact}"
            );
        }
    }

    #[test]
    fn an_anisotropic_ball_is_no_noisier_than_twice_an_isotropic_one() {
        let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
        let ball = |extensions: serde_json::Value| {
            let material = MaterialSource::gltf2(
                &serde_json::json!({"pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.3, 0.3, 1.0],
                    "metallicFactor": 1.0, "roughnessFactor": 0.3}, "extensions": extensions}),
                &[],
            );
            sampling_noise(&shader, &material)
        };
        let isotropic = ball(serde_json::json!({}));
        let anisotropic =
            ball(serde_json::json!({"KHR_materials_anisotropy": {"anisotropyStrength": 0.9}}));
        println!("sampling noise: isotropic {isotropic:.2}, anisotropic {anisotropic:.2} levels");
        assert!(
            anisotropic <= 2.0 * isotropic.max(0.5),
            "anisotropic {anisotropic:.2} levels against isotropic {isotropic:.2}"
        );
    }

    #[test]
    fn a_grey_ball_is_lit_from_the_upper_left() {
        let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
        let material = MaterialSource::gltf2(
            &serde_json::json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}}),
            &[],
        );
        let image = material_ball(&shader, &material, 32);
        assert_eq!(
            image.get_pixel(0, 0).0,
            encode([backdrop(-1.0 + 1.0 / 32.0, 1.0 - 1.0 / 32.0); 3]).0,
            "corners are backdrop"
        );
        let upper_left = image.get_pixel(10, 10).0[0];
        let lower_right = image.get_pixel(22, 22).0[0];
        assert!(upper_left > lower_right, "{upper_left} vs {lower_right}");
    }

    /// Mean absolute difference of two pictures, in 8-bit levels.
    fn mean_difference(a: &RgbImage, b: &RgbImage) -> f64 {
        let total: f64 = (a.as_raw().iter().zip(b.as_raw()))
            .map(|(x, y)| (f64::from(*x) - f64::from(*y)).abs())
            .sum();
        total / a.as_raw().len() as f64
    }

    #[test]
    fn each_layer_of_the_whole_material_is_drawn() {
        use crate::shade::sample::{decode_all, solid_png};
        let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
        let grey = serde_json::json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0],
            "metallicFactor": 0.0, "roughnessFactor": 0.5}});
        let ball = |extra: serde_json::Value, texel: Option<[u8; 3]>| {
            let mut json = grey.clone();
            for (key, value) in extra.as_object().into_iter().flatten() {
                json[key] = value.clone();
            }
            let textures = match texel {
                Some(texel) => decode_all(&[Some(Ok(solid_png(texel)))]).unwrap(),
                None => Vec::new(),
            };
            material_ball(&shader, &MaterialSource::gltf2(&json, &textures), 32)
        };
        let reference = ball(serde_json::json!({}), None);
        let mut blended = grey.clone();
        blended["alphaMode"] = "BLEND".into();
        blended["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.2.into();
        let layers = [
            ("coverage", blended, None),
            (
                "emission",
                serde_json::json!({"emissiveFactor": [1.0, 1.0, 1.0],
                    "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 10.0}}}),
                None,
            ),
            (
                "normal map",
                serde_json::json!({"normalTexture": {"index": 0}}),
                Some([230, 128, 180]),
            ),
            (
                "clearcoat",
                serde_json::json!({"extensions": {"KHR_materials_clearcoat":
                    {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.05}}}),
                None,
            ),
            (
                "transmission",
                serde_json::json!({"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0}}}),
                None,
            ),
            (
                "occlusion",
                serde_json::json!({"occlusionTexture": {"index": 0}}),
                Some([40, 40, 40]),
            ),
        ];
        for (layer, extra, texel) in layers {
            let difference = mean_difference(&reference, &ball(extra, texel));
            println!("{layer}: {difference:.1} levels from the plain ball");
            assert!(difference > 2.0, "{layer}: {difference:.2} levels");
        }
        // The backdrop shows through a clear ball and not through an opaque one.
        let mut clear = grey.clone();
        clear["alphaMode"] = "BLEND".into();
        clear["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.0.into();
        let clear = material_ball(&shader, &MaterialSource::gltf2(&clear, &[]), 32);
        assert_eq!(
            clear.get_pixel(16, 16).0,
            encode([backdrop(1.0 / 32.0, -1.0 / 32.0); 3]).0
        );
    }
}
