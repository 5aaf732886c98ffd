//! Deterministic quadrature over the hemisphere: Gauss-Legendre in cos θ, midpoint in φ.

use super::brdf::V3;
use std::f64::consts::PI;

/// Gauss-Legendre nodes and weights on [0, 1].
pub(crate) fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (1..=n)
        .map(|i| {
            // Newton iteration on P_n from the Chebyshev-like initial guess.
            let mut x = (PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            let mut derivative = 1.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let k = k as f64;
                    let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / derivative;
                x -= step;
                if step.abs() < 1e-15 {
                    break;
                }
            }
            let weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
            ((x + 1.0) / 2.0, weight / 2.0)
        })
        .collect()
}

/// ∫ f(ω) dω over the upper hemisphere, with `n_mu` × `n_phi` nodes.
pub(crate) fn hemisphere(n_mu: usize, n_phi: usize, mut f: impl FnMut(V3) -> f64) -> f64 {
    let nodes = gauss_legendre(n_mu);
    let d_phi = 2.0 * PI / n_phi as f64;
    let mut total = 0.0;
    for &(mu, weight) in &nodes {
        let sin = (1.0 - mu * mu).max(0.0).sqrt();
        let mut ring = 0.0;
        for j in 0..n_phi {
            let phi = (j as f64 + 0.5) * d_phi;
            ring += f([sin * phi.cos(), sin * phi.sin(), mu]);
        }
        total += weight * ring * d_phi;
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadrature_integrates_cosine_exactly() {
        let value = hemisphere(16, 8, |w| w[2]);
        assert!((value - PI).abs() < 1e-12, "{value}");
    }
}
