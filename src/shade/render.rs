//! Material previews: a material ball under a fixed studio rig, tone mapped with Khronos PBR
//! Neutral and encoded as sRGB; and ΔE heat maps.
//!
//! The rig (documented, fixed so previews are comparable across runs and machines):
//! an orthographic camera looking down −z at a unit sphere (y up); three directional lights
//! — key from (−1, 1, 1) with irradiance 2.5, fill from (1, 0.3, 0.8) with 0.8, rim from
//! (0.2, 0.8, −1) with 1.5 — and a uniform sky of radiance 0.3 integrated per pixel by multiple
//! importance sampling of 64 stratified cosine-weighted and 64 GGX-distributed directions,
//! the pattern turned about the normal by a fixed per-pixel angle. The sphere's UVs are equirectangular
//! (u = ½ + φ/2π, v = θ/π) with the analytic tangent along increasing u.

use super::brdf::{dot, normalize, Geometry, V3};
use super::material::Shader;
use super::sample::MaterialSource;
use super::tone::displayed;
use crate::gltf::color::linear_to_srgb8;
use image::{Rgb, RgbImage};
use std::f64::consts::PI;

const LIGHTS: [(V3, f64); 3] = [
    ([-1.0, 1.0, 1.0], 2.5),
    ([1.0, 0.3, 0.8], 0.8),
    ([0.2, 0.8, -1.0], 1.5),
];
const SKY_RADIANCE: f64 = 0.3;
const SKY_SAMPLES_PER_SIDE: usize = 8;
const BACKGROUND: [u8; 3] = [46, 46, 50];

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Stratified points of the unit square, shared by both sky sampling strategies.
fn sky_directions() -> Vec<[f64; 2]> {
    let n = SKY_SAMPLES_PER_SIDE;
    (0..n * n)
        .map(|k| {
            [
                ((k / n) as f64 + 0.5) / n as f64,
                ((k % n) as f64 + 0.5) / n as f64,
            ]
        })
        .collect()
}

/// The uniform sky by multiple importance sampling (balance heuristic): every point gives
/// one cosine-weighted direction and one GGX-distributed reflection of `v` for the
/// material's roughness, each weighted by 1 / (N·pdf_cos + N·pdf_ggx) at that direction.
fn sky_radiance(
    shader: &Shader,
    inputs: &super::material::Inputs,
    v: V3,
    points: &[[f64; 2]],
    turn: f64,
) -> V3 {
    let alpha = (inputs.roughness * inputs.roughness).max(1e-3);
    let n = points.len() as f64;
    let pdf_cos = |l: V3| l[2].max(0.0) / PI;
    let pdf_ggx = |l: V3| {
        let h = normalize([v[0] + l[0], v[1] + l[1], v[2] + l[2]]);
        let v_dot_h = dot(v, h).abs().max(1e-9);
        super::brdf::ggx_d(alpha, h[2]) * h[2] / (4.0 * v_dot_h)
    };
    let mut total = [0.0; 3];
    for &[u1, u2] in points {
        let phi = 2.0 * PI * u2 + turn;
        let r = u1.sqrt();
        let cosine = [r * phi.cos(), r * phi.sin(), (1.0 - u1).sqrt()];
        let tan2 = alpha * alpha * u1 / (1.0 - u1).max(1e-12);
        let cos_h = 1.0 / (1.0 + tan2).sqrt();
        let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
        let h = [sin_h * phi.cos(), sin_h * phi.sin(), cos_h];
        let v_dot_h = dot(v, h);
        let reflected = [0, 1, 2].map(|i| 2.0 * v_dot_h * h[i] - v[i]);
        for l in [cosine, reflected] {
            if l[2] <= 0.0 {
                continue;
            }
            let f = shader.brdf(inputs, &Geometry::new(v, l));
            let weight = SKY_RADIANCE * l[2] / (n * pdf_cos(l) + n * pdf_ggx(l));
            for c in 0..3 {
                total[c] += f[c] * weight;
            }
        }
    }
    total
}

/// Linear radiance of the ball at pixel (x, y) of a `size`² image, `None` off the sphere.
fn shade_pixel(
    shader: &Shader,
    material: &MaterialSource,
    sky: &[[f64; 2]],
    x: u32,
    y: u32,
    size: u32,
) -> Option<V3> {
    let px = (f64::from(x) + 0.5) / f64::from(size) * 2.0 - 1.0;
    let py = 1.0 - (f64::from(y) + 0.5) / f64::from(size) * 2.0;
    let r2 = px * px + py * py;
    if r2 >= 1.0 {
        return None;
    }
    let n = [px, py, (1.0 - r2).sqrt()];
    let phi = n[0].atan2(n[2]);
    let uv = [0.5 + phi / (2.0 * PI), n[1].clamp(-1.0, 1.0).acos() / PI];
    let inputs = material.inputs_at(&[uv, uv]);
    if inputs.unlit {
        return Some(inputs.base_color);
    }
    let t = normalize([phi.cos(), 0.0, -phi.sin()]);
    let b = cross(n, t);
    let local = |w: V3| [dot(w, t), dot(w, b), dot(w, n)];
    let v = local([0.0, 0.0, 1.0]);
    let mut radiance = [0.0; 3];
    let mut add = |l: V3, weight: f64| {
        if l[2] > 0.0 {
            let f = shader.brdf(&inputs, &Geometry::new(v, l));
            for c in 0..3 {
                radiance[c] += f[c] * weight;
            }
        }
    };
    for (direction, irradiance) in LIGHTS {
        let l = local(normalize(direction));
        add(l, irradiance * l[2]);
    }
    // The sampling pattern is turned by a fixed per-pixel angle (from a hash of the pixel,
    // so renders are reproducible): fine noise instead of bands.
    let turn =
        f64::from((x.wrapping_mul(0x9E37_79B9) ^ y.wrapping_mul(0x85EB_CA6B)) % 6283) / 1000.0;
    let sky_light = sky_radiance(shader, &inputs, v, sky, turn);
    for c in 0..3 {
        radiance[c] += sky_light[c];
    }
    Some(radiance)
}

fn encode(linear: V3) -> Rgb<u8> {
    Rgb(displayed(linear).map(linear_to_srgb8))
}

/// Renders one material ball.
pub fn material_ball(shader: &Shader, material: &MaterialSource, size: u32) -> RgbImage {
    let sky = sky_directions();
    let size = size.max(8);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
    let rows_per_thread = size.div_ceil(threads);
    let mut image = RgbImage::from_pixel(size, size, Rgb(BACKGROUND));
    let row_bytes = size as usize * 3;
    std::thread::scope(|scope| {
        for (chunk, rows) in image
            .chunks_mut(rows_per_thread as usize * row_bytes)
            .enumerate()
        {
            let sky = &sky;
            scope.spawn(move || {
                for (i, pixel) in rows.chunks_exact_mut(3).enumerate() {
                    let x = (i % size as usize) as u32;
                    let y = chunk as u32 * rows_per_thread + (i / size as usize) as u32;
                    if let Some(radiance) = shade_pixel(shader, material, sky, x, y, size) {
                        pixel.copy_from_slice(&encode(radiance).0);
                    }
                }
            });
        }
    });
    image
}

/// Every material's ball side by side, in rows of up to four, in material order, each with
/// its name written under it.
pub fn contact_sheet(
    shader: &Shader,
    materials: &[(&str, &MaterialSource)],
    cell: u32,
) -> RgbImage {
    let columns = (materials.len() as u32).clamp(1, 4);
    let rows = (materials.len() as u32).div_ceil(columns).max(1);
    let mut sheet = RgbImage::from_pixel(columns * cell, rows * cell, Rgb(BACKGROUND));
    let scale = (cell / 96).max(1);
    for (i, (name, material)) in materials.iter().enumerate() {
        let ball = material_ball(shader, material, cell);
        let (cx, cy) = ((i as u32 % columns) * cell, (i as u32 / columns) * cell);
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

/// A ΔE heat map: black at 0, through blue and yellow, red at `threshold` and above.
pub fn heatmap(per_texel: &[f32], grid: u32, threshold: f64) -> RgbImage {
    RgbImage::from_fn(grid, grid, |x, y| {
        let value = per_texel
            .get((y * grid + x) as usize)
            .map_or(0.0, |v| f64::from(*v));
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
    fn a_grey_ball_is_lit_from_the_upper_left() {
        let shader = Shader::new(SheenTable::compute(2, SheenVisibility::Charlie));
        let material = MaterialSource::gltf2(
            &serde_json::json!({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.6}}),
            &[],
        );
        let image = material_ball(&shader, &material, 32);
        assert_eq!(
            image.get_pixel(0, 0).0,
            BACKGROUND,
            "corners are background"
        );
        let upper_left = image.get_pixel(10, 10).0[0];
        let lower_right = image.get_pixel(22, 22).0[0];
        assert!(upper_left > lower_right, "{upper_left} vs {lower_right}");
    }
}
