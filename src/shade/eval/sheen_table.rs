//! The sheen albedo E(μ, sheenRoughness) = ∫ D_s V_s (n·l) dω_l for a unit sheen colour,
//! computed in-process by deterministic quadrature for the exact lobe the evaluator uses,
//! on a declared grid: row i ↔ sheenRoughness (i + ½)/N, column j ↔ μ = NdotV (j + ½)/N
//! (texel centres), looked up bilinearly and clamped at the edges, except below the first
//! row: there E is interpolated towards its limit at sheenRoughness 0 (see [`SheenTable::limit`]).

use super::brdf::{sheen_lobe, Geometry, SheenVisibility};
use super::quadrature::hemisphere;
use super::sheen_charlie16;

/// Quadrature nodes in cos θ and φ: within 3e−4 of a 512 × 256 rule over the whole table
/// (and within 1e−3 of the published Conty-Kulla values, see the tests).
const NODES_MU: usize = 384;
const NODES_PHI: usize = 64;

/// The directional albedo E(μ, sheenRoughness) of the sheen lobe, on a square grid.
#[derive(Debug, Clone)]
pub struct SheenTable {
    /// Samples per side.
    pub size: usize,
    /// The visibility term it was computed with.
    pub visibility: SheenVisibility,
    /// Row-major: `values[row * size + column]`, row = roughness, column = μ.
    pub values: Vec<f64>,
    /// E at sheenRoughness 0 for each column's μ: the row below the first. Clamping there
    /// would take E from roughness 1/(2·size) for the spec's default roughness 0, where E
    /// peaks (1.63 at 16², 3.24 at 32² at grazing μ) and would dim the base by that much.
    /// At roughness 0 the Charlie distribution is a spike at half-vectors in the tangent
    /// plane, which no pair of directions above the horizon has, so the lobe and its albedo
    /// vanish: computing this row with the evaluator's own lobe gives that limit, 0.
    pub limit: Vec<f64>,
}

impl SheenTable {
    /// The exact albedo of the sheen lobe at one (μ, sheenRoughness), which the table
    /// holds at its texel centres.
    pub fn albedo(visibility: SheenVisibility, mu: f64, sheen_roughness: f64) -> f64 {
        let mu = mu.clamp(1e-4, 1.0);
        let v = [(1.0 - mu * mu).sqrt(), 0.0, mu];
        hemisphere(NODES_MU, NODES_PHI, |l| {
            sheen_lobe(visibility, sheen_roughness, &Geometry::new(v, l)) * l[2]
        })
    }

    /// The side of the table the evaluator shades sheen with.
    pub const STANDARD_SIZE: usize = 16;

    /// The table the evaluator shades sheen with: [`STANDARD_SIZE`](Self::STANDARD_SIZE)²,
    /// Charlie visibility, the values [`compute`](Self::compute) gives, stored rather than
    /// computed again by every process.
    pub fn standard() -> SheenTable {
        SheenTable {
            size: Self::STANDARD_SIZE,
            visibility: SheenVisibility::Charlie,
            values: sheen_charlie16::VALUES.to_vec(),
            limit: sheen_charlie16::LIMIT.to_vec(),
        }
    }

    /// Computes the table by quadrature.
    pub fn compute(size: usize, visibility: SheenVisibility) -> SheenTable {
        let size = size.max(2);
        let centre = |i: usize| (i as f64 + 0.5) / size as f64;
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let mut values = vec![0.0; size * size];
        // Rows are independent: one chunk of rows per core.
        let rows_per_chunk = size.div_ceil(threads);
        std::thread::scope(|scope| {
            for (chunk, out) in values.chunks_mut(rows_per_chunk * size).enumerate() {
                scope.spawn(move || {
                    for (k, value) in out.iter_mut().enumerate() {
                        let k = chunk * rows_per_chunk * size + k;
                        *value = SheenTable::albedo(visibility, centre(k % size), centre(k / size));
                    }
                });
            }
        });
        let limit = (0..size)
            .map(|j| SheenTable::albedo(visibility, centre(j), 0.0))
            .collect();
        SheenTable {
            size,
            visibility,
            values,
            limit,
        }
    }

    /// Bilinear lookup between texel centres, clamped at the μ edges and at roughness 1;
    /// between roughness 0 and the first row it interpolates from the [`limit`](Self::limit).
    pub fn lookup(&self, mu: f64, sheen_roughness: f64) -> f64 {
        let n = self.size;
        let coordinate = |x: f64| {
            let t = (x.clamp(0.0, 1.0) * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
            let i = (t.floor() as usize).min(n - 2);
            (i, t - i as f64)
        };
        let (j, fx) = coordinate(mu);
        let across = |row: &[f64]| row[j] * (1.0 - fx) + row[j + 1] * fx;
        let row = |i: usize| &self.values[i * n..(i + 1) * n];
        let first_centre = 0.5 / n as f64;
        if sheen_roughness < first_centre {
            let fy = sheen_roughness.max(0.0) / first_centre;
            return across(&self.limit) * (1.0 - fy) + across(row(0)) * fy;
        }
        let (i, fy) = coordinate(sheen_roughness);
        across(row(i)) * (1.0 - fy) + across(row(i + 1)) * fy
    }

    /// One row per roughness, one column per μ, with a header naming the grid.
    pub fn to_csv(&self) -> String {
        let n = self.size;
        let mut out = format!(
            "# sheen albedo E, {:?} visibility; row i: sheenRoughness = (i+0.5)/{n}; column j: NdotV = (j+0.5)/{n}\n",
            self.visibility
        );
        for row in self.values.chunks(n) {
            let cells: Vec<String> = row.iter().map(|v| format!("{v:.6}")).collect();
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }

    /// 16-bit greyscale PNG, same layout (x = μ, y = roughness); values above 1 are clamped.
    pub fn to_png(&self) -> Vec<u8> {
        let n = self.size as u32;
        let image = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(n, n, |x, y| {
            let v = self.values[(y * n + x) as usize].clamp(0.0, 1.0);
            image::Luma([(v * 65535.0).round() as u16])
        });
        let mut bytes = Vec::new();
        let _ = image::DynamicImage::ImageLuma16(image).write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        );
        bytes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn albedo_matches_the_conty_kulla_column() {
        // shading-anchors.md §2.4, "E, Charlie V (CK17 Λ)" and "E, Ashikhmin V".
        for (roughness, mu, charlie, ashikhmin) in [
            (0.25, 0.5, 0.0599, 0.0989),
            (0.5, 0.1, 0.5666, 0.6393),
            (0.5, 0.5, 0.1879, 0.2296),
            (0.75, 0.5, 0.2980, 0.2716),
            (1.0, 0.1, 0.7205, 0.4940),
            (1.0, 0.9, 0.1943, 0.1674),
        ] {
            let e = SheenTable::albedo(SheenVisibility::Charlie, mu, roughness);
            assert!(
                (e - charlie).abs() < 1e-3,
                "Charlie E({mu}, {roughness}) = {e}"
            );
            let e = SheenTable::albedo(SheenVisibility::Ashikhmin, mu, roughness);
            assert!(
                (e - ashikhmin).abs() < 1e-3,
                "Ashikhmin E({mu}, {roughness}) = {e}"
            );
        }
    }

    #[test]
    fn below_the_first_row_e_goes_to_its_vanishing_limit_not_to_the_first_row() {
        for size in [16, 32] {
            let table = SheenTable::compute(size, SheenVisibility::Charlie);
            let first_row_peak = table.values[..size].iter().cloned().fold(0.0, f64::max);
            assert!(
                first_row_peak > 1.0,
                "{size}²: the first row peaks at {first_row_peak}"
            );
            for mu in [0.01, 0.1, 0.5, 1.0] {
                let e = table.lookup(mu, 0.0);
                assert!(e.abs() < 1e-9, "{size}²: E({mu}, 0) = {e}");
                // Between 0 and the first row: between the limit and the first row's value.
                let halfway = table.lookup(mu, 0.25 / size as f64);
                let first = table.lookup(mu, 0.5 / size as f64);
                assert!(
                    (halfway - first / 2.0).abs() < 1e-12,
                    "{size}²: {halfway} vs {first}"
                );
            }
        }
    }

    #[test]
    fn the_standard_table_is_exactly_what_the_quadrature_gives() {
        let computed = SheenTable::compute(SheenTable::STANDARD_SIZE, SheenVisibility::Charlie);
        let standard = SheenTable::standard();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert!(
            bits(&computed.values) == bits(&standard.values)
                && bits(&computed.limit) == bits(&standard.limit),
            "the lobe changed: paste these into sheen_charlie16.rs\nVALUES {:?}\nLIMIT {:?}",
            computed.values,
            computed.limit
        );
    }

    #[test]
    fn lookup_returns_texel_centres_exactly_and_interpolates_between() {
        let table = SheenTable {
            size: 2,
            visibility: SheenVisibility::Charlie,
            values: vec![0.0, 1.0, 2.0, 3.0],
            limit: vec![-1.0, -1.0],
        };
        assert_eq!(table.lookup(0.25, 0.25), 0.0);
        assert_eq!(table.lookup(0.75, 0.75), 3.0);
        assert_eq!(table.lookup(0.5, 0.5), 1.5);
        assert_eq!(table.lookup(0.0, 1.0), 2.0, "clamped at the edges");
        assert_eq!(
            table.lookup(0.25, 0.0),
            -1.0,
            "the limit row at roughness 0"
        );
        assert_eq!(table.lookup(0.25, 0.125), -0.5, "halfway to the first row");
        let csv = table.to_csv();
        assert_eq!(csv.lines().nth(1), Some("0.000000,1.000000"));
    }
}
