//! Effective sample size: how many independent samples n correlated ones
//! are worth, for residual series (model choice, the posterior's noise
//! model) and for Markov chains (the sampler's diagnostics) alike.
//!
//! - **AR(1)**: `n_eff = n (1 − ρ)/(1 + ρ)` with ρ the pooled lag-1
//!   autocorrelation (Bayley & Hammersley 1946); exact for first-order
//!   autoregressive errors.
//! - **Spectral**: `n_eff = n / τ` with the integrated autocorrelation time
//!   `τ = 1 + 2 Σ_{k=1}^{M} ρ_k = S(0)/σ²` (the spectral density at zero
//!   frequency over the variance; for AR(1) errors `(1 + ρ)/(1 − ρ)`
//!   again). The window M is Sokal's automatic one, the smallest with
//!   `M ≥ c τ(M)` (Sokal 1997, *Monte Carlo methods in statistical
//!   mechanics*, sec. 3; emcee's `autocorr.integrated_time`, `c = 5`);
//!   `ρ_k = Σ_t x_t x_{t+k} / Σ_t x_t²` (the biased estimate emcee uses),
//!   pooled over the series: their lag products and powers are summed
//!   before the ratio (so a series of a noisier case weighs more, as its
//!   squares do in the objective).
//!
//! **Model choice** ([`bic`]): the Bayesian information criterion on the
//! effective number of residuals, `BIC = n_eff ln(F/n) + q ln n_eff`
//! (Schwarz 1978; n residuals of objective F, q free parameters): the
//! chain's and the planar car's link verdicts (issue 46 item 3).
//!
//! A window that would reach beyond the longest series cannot be trusted
//! ([`Effective::reliable`] false; emcee raises its `AutocorrError`): the
//! series are shorter than c τ.
//!
//! ```
//! use bumpsim_estimate::effective::{Method, of_series};
//! // an AR(1) series with ρ = 0.9: τ = 19, n_eff = n/19
//! let (mut x, mut state) = (vec![0.0; 20000], 0x2545F4914F6CDD1Du64);
//! let mut uniform = || { state ^= state << 13; state ^= state >> 7; state ^= state << 17;
//!     (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5 };
//! for k in 1..x.len() { x[k] = 0.9 * x[k - 1] + uniform(); }
//! let ar1 = of_series(&[&x], Method::Ar1, false);
//! assert!((ar1.lag_one - 0.9).abs() < 0.01);
//! let spectral = of_series(&[&x], Method::Spectral, true);
//! assert!((spectral.time - 19.0).abs() < 4.0 && spectral.reliable, "{spectral:?}");
//! ```

use serde::Serialize;

/// One residual series (a case's window of one signal): residual `start +
/// stride k` for `k < len`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Series {
    /// Its first residual.
    pub start: usize,
    /// Its samples.
    pub len: usize,
    /// The distance between its consecutive samples among the residuals.
    pub stride: usize,
}

impl Series {
    /// Contiguous series of the given lengths, one after the other (stride 1).
    ///
    /// ```
    /// use bumpsim_estimate::uncertainty::Series;
    /// let s = Series::contiguous([3, 2].into_iter());
    /// assert_eq!((s[1].start, s[1].len, s[1].stride), (3, 2, 1));
    /// ```
    pub fn contiguous(lengths: impl Iterator<Item = usize>) -> Vec<Series> {
        let mut start = 0;
        lengths
            .map(|len| {
                let s = Series {
                    start,
                    len,
                    stride: 1,
                };
                start += len;
                s
            })
            .collect()
    }
}

/// Sokal's window constant: the window is the smallest M with M ≥ c τ(M).
pub const WINDOW: f64 = 5.0;

/// How the effective sample size is estimated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Every sample counts: `n_eff = n`.
    Independent,
    /// `n_eff = n (1 − ρ)/(1 + ρ)`, ρ the lag-1 autocorrelation.
    Ar1,
    /// `n_eff = n / τ`, τ the integrated autocorrelation time.
    Spectral,
}

impl Method {
    /// Its name as printed (`AR(1)`, `spectral`, `independent`).
    pub fn label(self) -> &'static str {
        match self {
            Method::Independent => "independent",
            Method::Ar1 => "AR(1)",
            Method::Spectral => "spectral",
        }
    }
}

/// An effective sample size.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Effective {
    /// The method.
    pub method: Method,
    /// Samples n.
    pub samples: usize,
    /// Effective samples `n / τ`, at most n, at least 1 when n ≥ 1.
    pub effective: f64,
    /// The variance inflation τ = n / n_eff (the integrated
    /// autocorrelation time, or `(1 + ρ)/(1 − ρ)`, or 1).
    pub time: f64,
    /// The pooled lag-1 autocorrelation, clamped to [0, 0.999999].
    pub lag_one: f64,
    /// Sokal's window M (spectral; 1 otherwise).
    pub window: usize,
    /// False when the window reached the longest series: τ is then a lower
    /// bound.
    pub reliable: bool,
}

/// The effective size of the residual series `series` of `residuals`
/// (residuals of a fit: not centred).
pub fn of_residuals(residuals: &[f64], series: &[Series], method: Method) -> Effective {
    let gathered: Vec<Vec<f64>> = series
        .iter()
        .map(|s| {
            (0..s.len)
                .map(|k| residuals[s.start + s.stride * k])
                .collect()
        })
        .collect();
    let views: Vec<&[f64]> = gathered.iter().map(Vec::as_slice).collect();
    of_series(&views, method, false)
}

/// The effective size of `series` pooled; `centred`: each series about
/// its own mean first (a Markov chain), else as given (residuals).
pub fn of_series(series: &[&[f64]], method: Method, centred: bool) -> Effective {
    let centred_series: Vec<Vec<f64>> = series
        .iter()
        .map(|s| {
            let mean = match centred && !s.is_empty() {
                true => s.iter().sum::<f64>() / s.len() as f64,
                false => 0.0,
            };
            s.iter().map(|v| v - mean).collect()
        })
        .collect();
    let views: Vec<&[f64]> = centred_series.iter().map(Vec::as_slice).collect();
    let samples: usize = views.iter().map(|s| s.len()).sum();
    let longest = views.iter().map(|s| s.len()).max().unwrap_or(0);
    let lag_one = autocorrelation(&views, 1).clamp(0.0, 0.999_999);
    let (time, window, reliable) = match method {
        Method::Independent => (1.0, 1, true),
        Method::Ar1 => ((1.0 + lag_one) / (1.0 - lag_one), 1, true),
        Method::Spectral => integrated_time(&views, longest),
    };
    let effective = match samples {
        0 => 0.0,
        n => (n as f64 / time).clamp(1.0, n as f64),
    };
    Effective {
        method,
        samples,
        effective,
        time: time.max(1.0),
        lag_one,
        window,
        reliable,
    }
}

/// The pooled autocorrelation of `series` at `lag` (0 without power).
pub fn autocorrelation(series: &[&[f64]], lag: usize) -> f64 {
    let power = lag_products(series, 0);
    match power > 0.0 {
        true => lag_products(series, lag) / power,
        false => 0.0,
    }
}

/// `Σ_series Σ_t x_t x_{t+lag}`.
fn lag_products(series: &[&[f64]], lag: usize) -> f64 {
    series
        .iter()
        .filter(|s| lag < s.len())
        .map(|s| s.iter().zip(&s[lag..]).map(|(a, b)| a * b).sum::<f64>())
        .sum()
}

/// τ with Sokal's window over lags below `longest`: (τ, window, reliable).
fn integrated_time(series: &[&[f64]], longest: usize) -> (f64, usize, bool) {
    let power = lag_products(series, 0);
    if power.is_nan() || power <= 0.0 {
        return (1.0, 1, true);
    }
    let mut tau = 1.0;
    for lag in 1..longest {
        tau += 2.0 * lag_products(series, lag) / power;
        if lag as f64 >= WINDOW * tau {
            return (tau.max(1.0), lag, true);
        }
    }
    (tau.max(1.0), longest.saturating_sub(1), false)
}

/// The Bayesian information criterion of an objective `objective` (sum
/// of squares) on `n` residuals of which `effective` are independent, with
/// `q` free parameters (see the module): lower is preferred.
pub fn bic(objective: f64, n: usize, effective: f64, q: usize) -> f64 {
    effective * (objective / n as f64).ln() + q as f64 * effective.ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Independent noise has τ ≈ 1; AR(1) noise of ρ = 0.95 has τ = 39 by
    /// both methods; a series too short for the window is flagged.
    #[test]
    fn white_and_ar1_noise_have_their_textbook_times() {
        let mut draws = crate::search::Draws::new(7, 0);
        let white: Vec<f64> = (0..50_000).map(|_| draws.unit() - 0.5).collect();
        let w = of_series(&[&white], Method::Spectral, true);
        assert!((w.time - 1.0).abs() < 0.1, "{w:?}");
        let mut ar = vec![0.0; 200_000];
        for k in 1..ar.len() {
            ar[k] = 0.95 * ar[k - 1] + draws.unit() - 0.5;
        }
        let spectral = of_series(&[&ar], Method::Spectral, true);
        let ar1 = of_series(&[&ar], Method::Ar1, true);
        assert!((spectral.time - 39.0).abs() < 4.0, "{spectral:?}");
        assert!((ar1.time - 39.0).abs() < 2.0, "{ar1:?}");
        assert!((spectral.effective - 200_000.0 / spectral.time).abs() < 1e-6);
        // a constant offset (a residual drift): every lag correlates
        let short = of_series(&[&[1.0; 40]], Method::Spectral, false);
        assert!(!short.reliable);
        let nothing = of_series(&[], Method::Spectral, true);
        assert_eq!((nothing.samples, nothing.effective), (0, 0.0));
    }
}
