//! Propagation of parameter draws (a posterior's, [`crate::posterior`])
//! through any model (issue 39): the model runs once per draw, in
//! parallel; a scalar output becomes its distribution (mean, deviation,
//! equal-tailed interval), a history its pointwise prediction band, a
//! criterion its probability of passing with its exact 95 % bounds
//! ([`crate::binomial`]; the binomial standard error `√(p (1 − p)/n)` too,
//! which is 0 when every draw passes).
//!
//! Monte Carlo over the draws: the intervals are those of the draws' law
//! (the posterior predictive of the model's output without measurement
//! noise), their quantiles interpolated as numpy's default
//! ([`crate::posterior::quantile`]). A draw for which the model fails
//! (`None`) is counted, not used.
//!
//! ```
//! use bumpsim_estimate::propagate::{through, spread, probability};
//! // draws of a stiffness; the output is a force at 10 mm
//! let draws: Vec<Vec<f64>> = (0..1000).map(|k| vec![1e6 * (1.0 + 0.1 * ((k as f64 + 0.5) / 1000.0 - 0.5))]).collect();
//! let run = through(&draws, &|p: &[f64]| Some(p[0] * 0.01));
//! let force = spread(&run.outputs, 0.9).unwrap();
//! assert!((force.median - 1e4).abs() < 10.0);
//! let pass = probability(&run.outputs, |f| *f < 1.0e4);
//! assert!((pass.probability - 0.5).abs() < 0.01);
//! ```

use crate::binomial::Bounds;
use crate::posterior::quantile;
use rayon::prelude::*;
use serde::Serialize;

/// The outputs of a model over the draws.
#[derive(Debug, Clone, PartialEq)]
pub struct Run<T> {
    /// One output per draw the model could run.
    pub outputs: Vec<T>,
    /// Draws for which it failed.
    pub failed: usize,
}

/// Runs `model` at every draw in parallel (draw order kept).
pub fn through<T: Send>(
    draws: &[Vec<f64>],
    model: &(dyn Fn(&[f64]) -> Option<T> + Sync),
) -> Run<T> {
    let all: Vec<Option<T>> = draws.par_iter().map(|d| model(d)).collect();
    let failed = all.iter().filter(|o| o.is_none()).count();
    Run {
        outputs: all.into_iter().flatten().collect(),
        failed,
    }
}

/// The distribution of a scalar output.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spread {
    /// Mean.
    pub mean: f64,
    /// Standard deviation.
    pub sd: f64,
    /// Median.
    pub median: f64,
    /// Lower end of the equal-tailed interval.
    pub low: f64,
    /// Upper end.
    pub high: f64,
    /// The interval's level (0.9: 5 % to 95 %).
    pub level: f64,
    /// Values.
    pub count: usize,
}

/// The distribution of `values` with an equal-tailed interval of `level`;
/// `None` without a finite value.
pub fn spread(values: &[f64], level: f64) -> Option<Spread> {
    let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if sorted.is_empty() {
        return None;
    }
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    let mean = sorted.iter().sum::<f64>() / n;
    let sd = (sorted.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    let tail = (1.0 - level.clamp(0.0, 1.0)) / 2.0;
    Some(Spread {
        mean,
        sd,
        median: quantile(&sorted, 0.5),
        low: quantile(&sorted, tail),
        high: quantile(&sorted, 1.0 - tail),
        level,
        count: sorted.len(),
    })
}

/// A pointwise prediction band of histories sampled at the same instants.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Band {
    /// Lower end at each instant.
    pub low: Vec<f64>,
    /// Median at each instant.
    pub median: Vec<f64>,
    /// Upper end at each instant.
    pub high: Vec<f64>,
    /// The level.
    pub level: f64,
}

/// The band of `histories` at `level`, over the shortest one's instants;
/// `None` without a history.
pub fn band(histories: &[Vec<f64>], level: f64) -> Option<Band> {
    let length = histories.iter().map(Vec::len).min()?;
    let at: Vec<Spread> = (0..length)
        .map(|k| {
            let column: Vec<f64> = histories.iter().map(|h| h[k]).collect();
            spread(&column, level)
        })
        .collect::<Option<Vec<_>>>()?;
    Some(Band {
        low: at.iter().map(|s| s.low).collect(),
        median: at.iter().map(|s| s.median).collect(),
        high: at.iter().map(|s| s.high).collect(),
        level,
    })
}

/// The probability that a criterion passes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Probability {
    /// The share of outputs that pass.
    pub probability: f64,
    /// Its binomial standard error `√(p (1 − p)/n)` (0 when every or no
    /// output passes: read the bounds).
    pub standard_error: f64,
    /// Outputs judged.
    pub count: usize,
    /// Outputs that pass.
    pub passed: usize,
    /// Its exact 95 % bounds (Clopper–Pearson; one-sided when every or no
    /// output passes, [`crate::binomial`]).
    #[serde(flatten)]
    pub bounds: Bounds,
}

impl Probability {
    /// Short, for a table cell: `93.8 % (90.0–96.4 %)`, `≥ 98.5 %`.
    pub fn cell(&self) -> String {
        crate::binomial::cell(self.probability, &self.bounds)
    }

    /// As a sentence: `no failure in 200 draws: P(pass) ≥ 98.5 % (95 %
    /// one-sided); 299 draws would show ≥ 99 %`.
    pub fn sentence(&self) -> String {
        crate::binomial::sentence(self.passed, self.count, &self.bounds)
    }
}

/// The share of `outputs` for which `passes` holds.
pub fn probability<T>(outputs: &[T], passes: impl Fn(&T) -> bool) -> Probability {
    let count = outputs.len();
    let passed = outputs.iter().filter(|o| passes(o)).count();
    let p = match count {
        0 => f64::NAN,
        n => passed as f64 / n as f64,
    };
    Probability {
        probability: p,
        standard_error: (p * (1.0 - p) / count as f64).sqrt(),
        count,
        passed,
        bounds: Bounds::of(passed, count),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gaussian draws of θ through `h(t) = θ t`: the band at t is t times
    /// θ's quantiles (1.645 σ for 90 %), the probability of `θ t < μ t`
    /// one half; a failed draw is counted.
    #[test]
    fn gaussian_draws_give_their_analytic_band_and_probability() {
        let mut draws = crate::search::Draws::new(5, 0);
        let (mu, sigma) = (2.0, 0.3);
        let thetas: Vec<Vec<f64>> = (0..40_000)
            .map(|_| vec![mu + sigma * crate::posterior::gaussian(&mut draws)])
            .collect();
        let run = through(&thetas, &|p: &[f64]| {
            (p[0] > 0.0).then(|| (0..5).map(|k| p[0] * k as f64).collect::<Vec<f64>>())
        });
        assert_eq!(run.failed, 0);
        let b = band(&run.outputs, 0.9).unwrap();
        for k in 1..5 {
            let t = k as f64;
            assert!((b.median[k] - mu * t).abs() < 0.01 * t, "{k}");
            assert!(
                (b.high[k] - (mu + 1.6449 * sigma) * t).abs() < 0.015 * t,
                "{k}"
            );
            assert!(
                (b.low[k] - (mu - 1.6449 * sigma) * t).abs() < 0.015 * t,
                "{k}"
            );
        }
        let last: Vec<f64> = run.outputs.iter().map(|h| h[4]).collect();
        let p = probability(&last, |v| *v < mu * 4.0);
        assert!(
            (p.probability - 0.5).abs() < 3.0 * p.standard_error,
            "{p:?}"
        );
        let s = spread(&last, 0.9).unwrap();
        assert!((s.sd - 4.0 * sigma).abs() < 0.02 * 4.0 * sigma);
        let some_fail = through(&[vec![1.0], vec![-1.0]], &|p: &[f64]| {
            (p[0] > 0.0).then_some(p[0])
        });
        assert_eq!((some_fail.outputs.len(), some_fail.failed), (1, 1));
        assert!(spread(&[], 0.9).is_none() && band(&[], 0.9).is_none());
    }
}
