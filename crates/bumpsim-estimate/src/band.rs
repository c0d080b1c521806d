//! Linearised predictive bands of a model's histories from its parameters'
//! covariance (issue 44, item 5), for any model whose output `ŷ(t; p)` can
//! be evaluated at perturbed search variables `p` (`ln θ`, or θ for a
//! linear-scale parameter).
//!
//! **Propagation** (the delta method, the same linearisation as the
//! intervals of [`crate::uncertainty`]): with the output's sensitivities
//! `s_k = ∂ŷ_k/∂p` (central differences of step `h`, [`sensitivities`]) and
//! `Σ = Cov(p)`, the parameters' share of the output's variance at sample
//! k is `v_k = s_kᵀ Σ s_k`; a *predictive* band adds the variance `σ_e²` of
//! what the model does not reproduce (measurement noise and model error,
//! estimated by the caller from the training residuals of the same
//! channel): `ŷ_k ± z √(v_k + σ_e²)`, `z = Φ⁻¹((1 + level)/2)` (1.645 for
//! 90 %). Linearised rather than sampled: it costs `2 q` runs of the model
//! instead of hundreds, it is deterministic, and it is exact for a model
//! linear in p ([`linearised`]'s test); it is as good as the covariance it
//! propagates, which is itself the Jacobian's linearisation.
//!
//! **Judged**: the share of measured samples inside the band over a window
//! ([`PredictiveBand::inside`]), and the band's *relative width*: the mean
//! over the window of the parameters' half-width `z √v_k` over the
//! prediction's range `max ŷ − min ŷ` there. A band whose relative width
//! exceeds [`TOO_WIDE`] is too wide to trust: the parameters the training
//! data leave free move this output by more than a quarter of its swing, so
//! the training tests do not determine it.
//!
//! ```
//! use bumpsim_estimate::band::{linearised, sensitivities};
//! use nalgebra::DMatrix;
//! // ŷ(t) = a t with ln a = p, a = 2, SD(ln a) = 0.1: the band's half-width is z · 0.2 t
//! let t = [0.0, 1.0, 2.0];
//! let model = |p: &[f64]| Some(t.iter().map(|t| p[0].exp() * t).collect::<Vec<f64>>());
//! let s = sensitivities(&model, &[2f64.ln()], 1e-4).unwrap();
//! let cov = DMatrix::from_element(1, 1, 0.01);
//! let band = linearised(&[0.0, 2.0, 4.0], &s, &cov, 0.0, 0.9);
//! assert!((band.high[2] - 4.0 - 1.6449 * 0.4).abs() < 1e-3);
//! ```

use nalgebra::DMatrix;
use rayon::prelude::*;
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, Normal};

/// A band whose parameters' half-width averages more than this share of the
/// prediction's range over the window is too wide to trust.
pub const TOO_WIDE: f64 = 0.25;

/// The level of the predictive bands the models print.
pub const LEVEL: f64 = 0.9;

/// A pointwise predictive band around a prediction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PredictiveBand {
    /// The level (0.9: from 5 % to 95 %).
    pub level: f64,
    /// The standard deviation `σ_e` of what the model does not reproduce,
    /// added to the parameters' variance, in the channel's unit.
    pub noise: f64,
    /// Lower end at each sample.
    #[serde(skip)]
    pub low: Vec<f64>,
    /// Upper end at each sample.
    #[serde(skip)]
    pub high: Vec<f64>,
    /// The parameters' half-width `z √v_k` at each sample.
    #[serde(skip)]
    pub parameters: Vec<f64>,
}

/// The sensitivities `∂ŷ/∂p_j` of `model`'s output at `p`, one vector per
/// parameter, by central differences of step `h` (the runs in parallel);
/// `None` when a run fails or the outputs differ in length.
pub fn sensitivities(
    model: &(dyn Fn(&[f64]) -> Option<Vec<f64>> + Sync),
    p: &[f64],
    h: f64,
) -> Option<Vec<Vec<f64>>> {
    (0..p.len())
        .into_par_iter()
        .map(|j| {
            let at = |sign: f64| {
                let mut q = p.to_vec();
                q[j] += sign * h;
                model(&q)
            };
            let (up, down) = (at(1.0)?, at(-1.0)?);
            (up.len() == down.len()).then(|| {
                up.iter()
                    .zip(&down)
                    .map(|(u, d)| (u - d) / (2.0 * h))
                    .collect()
            })
        })
        .collect()
}

/// The band of `level` around `center` from the sensitivities (one vector
/// per parameter, as [`sensitivities`] gives them), the parameters'
/// covariance `covariance` (q × q) and the unreproduced part's standard
/// deviation `noise` (see the module).
pub fn linearised(
    center: &[f64],
    sensitivities: &[Vec<f64>],
    covariance: &DMatrix<f64>,
    noise: f64,
    level: f64,
) -> PredictiveBand {
    let z = quantile(level);
    let q = sensitivities.len();
    let parameters: Vec<f64> = (0..center.len())
        .map(|k| {
            let s = |j: usize| sensitivities[j].get(k).copied().unwrap_or(0.0);
            let variance: f64 = (0..q)
                .flat_map(|a| (0..q).map(move |b| (a, b)))
                .map(|(a, b)| s(a) * covariance[(a, b)] * s(b))
                .sum();
            z * variance.max(0.0).sqrt()
        })
        .collect();
    let half = |k: usize| (parameters[k].powi(2) + (z * noise).powi(2)).sqrt();
    PredictiveBand {
        level,
        noise,
        low: (0..center.len()).map(|k| center[k] - half(k)).collect(),
        high: (0..center.len()).map(|k| center[k] + half(k)).collect(),
        parameters,
    }
}

/// `z` of a two-sided normal interval of `level`.
fn quantile(level: f64) -> f64 {
    Normal::new(0.0, 1.0).map_or(1.645, |n| {
        n.inverse_cdf(0.5 * (1.0 + level.clamp(1e-9, 1.0 - 1e-9)))
    })
}

impl PredictiveBand {
    /// The band widened by a further independent error of standard
    /// deviation `sd(k)` at sample `k` (the measurement's own, e.g. an
    /// accelerometer's bias integrated twice): each half-width `w` about
    /// the same centre becomes `√(w² + (z sd_k)²)`, z of the band's level.
    pub fn widened(&mut self, sd: impl Fn(usize) -> f64) {
        let z = quantile(self.level);
        for k in 0..self.low.len().min(self.high.len()) {
            let centre = 0.5 * (self.low[k] + self.high[k]);
            let half = (0.5 * (self.high[k] - self.low[k])).hypot(z * sd(k));
            (self.low[k], self.high[k]) = (centre - half, centre + half);
        }
    }

    /// The share (0..1) of `measured` samples `a..=b` inside the band; NaN
    /// for an empty window.
    pub fn inside(&self, measured: &[f64], (a, b): (usize, usize)) -> f64 {
        let window = a..=b.min(measured.len().min(self.low.len()).saturating_sub(1));
        let n = window.clone().count();
        let hits = window
            .filter(|&k| self.low[k] <= measured[k] && measured[k] <= self.high[k])
            .count();
        match n {
            0 => f64::NAN,
            n => hits as f64 / n as f64,
        }
    }

    /// The mean of the parameters' half-width over samples `a..=b` over
    /// the range of `center` there (0 for a flat prediction without width,
    /// infinite for a flat one with).
    pub fn relative_width(&self, center: &[f64], (a, b): (usize, usize)) -> f64 {
        let end = b.min(center.len().min(self.parameters.len()).saturating_sub(1));
        if a > end {
            return f64::NAN;
        }
        let window = &center[a..=end];
        let range = window.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v))
            - window.iter().fold(f64::INFINITY, |m, v| m.min(*v));
        let width = self.parameters[a..=end].iter().sum::<f64>() / window.len() as f64;
        match width {
            0.0 => 0.0,
            w => w / range,
        }
    }
}

/// The covariance `Σ_ab = ρ_ab σ_a σ_b` of standard deviations `sd` and
/// correlations `correlation` (a missing correlation counts as 0 off the
/// diagonal).
pub fn covariance(sd: &[f64], correlation: &[Vec<Option<f64>>]) -> DMatrix<f64> {
    let q = sd.len();
    DMatrix::from_fn(q, q, |a, b| {
        let rho = match a == b {
            true => 1.0,
            false => correlation
                .get(a)
                .and_then(|r| r.get(b))
                .copied()
                .flatten()
                .unwrap_or(0.0),
        };
        rho * sd[a] * sd[b]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model linear in p, `ŷ(t) = p₀ + p₁ t`, with a correlated
    /// covariance: the band is `ŷ ± z √(σ₀² + 2 ρ σ₀ σ₁ t + σ₁² t² + σ_e²)` in
    /// closed form, and a Monte Carlo of the same law puts 90 % of its draws
    /// inside it at each t.
    #[test]
    fn a_linear_models_band_is_its_closed_form_and_covers_its_draws() {
        let t: Vec<f64> = (0..11).map(|k| k as f64 * 0.1).collect();
        let model = |p: &[f64]| Some(t.iter().map(|t| p[0] + p[1] * t).collect::<Vec<f64>>());
        let p = [1.0, -2.0];
        let (s0, s1, rho, noise) = (0.3, 0.5, -0.6, 0.1);
        let cov = covariance(&[s0, s1], &[vec![None, Some(rho)], vec![Some(rho), None]]);
        let s = sensitivities(&model, &p, 1e-3).unwrap();
        let center = model(&p).unwrap();
        let band = linearised(&center, &s, &cov, noise, 0.9);
        let z = 1.644_853_626_951_472_2;
        for (k, t) in t.iter().enumerate() {
            let v = s0 * s0 + 2.0 * rho * s0 * s1 * t + s1 * s1 * t * t;
            let half = z * (v + noise * noise).sqrt();
            approx::assert_relative_eq!(band.high[k], center[k] + half, max_relative = 1e-9);
            approx::assert_relative_eq!(band.low[k], center[k] - half, max_relative = 1e-9);
            approx::assert_relative_eq!(band.parameters[k], z * v.sqrt(), max_relative = 1e-9);
        }
        // draws of (p, e) from the same Gaussian law: 90 % inside at each t
        let mut draws = crate::search::Draws::new(3, 0);
        let n = 20_000;
        let mut inside = vec![0usize; t.len()];
        for _ in 0..n {
            let (g0, g1, g2) = (
                crate::posterior::gaussian(&mut draws),
                crate::posterior::gaussian(&mut draws),
                crate::posterior::gaussian(&mut draws),
            );
            let a = p[0] + s0 * g0;
            let b = p[1] + s1 * (rho * g0 + (1.0 - rho * rho).sqrt() * g1);
            for (k, t) in t.iter().enumerate() {
                let y = a + b * t + noise * g2;
                inside[k] += usize::from(band.low[k] <= y && y <= band.high[k]);
            }
        }
        for (k, hits) in inside.iter().enumerate() {
            let share = *hits as f64 / n as f64;
            // binomial SD at 90 % of 20 000 draws: 0.0021
            assert!((share - 0.9).abs() < 0.01, "t = {}: {share}", t[k]);
        }
        // the judged share and width
        let mut measured = center.clone();
        measured[0] += 10.0;
        assert!((band.inside(&measured, (0, 10)) - 10.0 / 11.0).abs() < 1e-12);
        let mean_half: f64 = band.parameters.iter().sum::<f64>() / 11.0;
        assert!((band.relative_width(&center, (0, 10)) - mean_half / 2.0).abs() < 1e-12);
    }

    /// Widening by an independent error adds it in quadrature: a band of
    /// noise σ_e widened by σ_m is the band of noise √(σ_e² + σ_m²).
    #[test]
    fn a_widened_band_adds_the_error_in_quadrature() {
        let center = vec![1.0, 2.0, 3.0];
        let s = vec![vec![0.1, 0.2, 0.3]];
        let cov = covariance(&[0.5], &[vec![None]]);
        let mut band = linearised(&center, &s, &cov, 0.3, 0.9);
        band.widened(|k| 0.4 * k as f64);
        for k in 0..3 {
            let whole = linearised(&center, &s, &cov, 0.3f64.hypot(0.4 * k as f64), 0.9);
            approx::assert_relative_eq!(band.high[k], whole.high[k], max_relative = 1e-12);
            approx::assert_relative_eq!(band.low[k], whole.low[k], max_relative = 1e-12);
        }
    }

    #[test]
    fn a_failed_run_gives_no_sensitivities() {
        let model = |p: &[f64]| (p[0] < 1.0).then(|| vec![p[0]]);
        assert!(sensitivities(&model, &[0.5], 0.1).is_some());
        assert!(sensitivities(&model, &[0.95], 0.1).is_none());
    }
}
