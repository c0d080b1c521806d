//! Residual errors that are a random walk: the covariance of a
//! least-squares estimate when each series' measurement error is the
//! running sum of stationary noise (a velocity integrated from an
//! accelerometer, issue 44), less that noise's mean over a bias window.
//!
//! In a series whose residual i lies `K_i = lead + i` samples after the
//! start of the integration, the error is
//! `e_i = Σ_{k=0}^{K_i} (n_k − n̄_B)`, with `n` stationary increments of
//! long-run variance `ω²` and `n̄_B` their mean over the bias window `B`
//! (|B| samples; the pre-trigger, where the bias is removed). Then
//! `Jᵀe = Σ_k c_k n_k` with
//!
//! `c_k = Σ_{i: K_i ≥ k} J_i − [k ∈ B] Σ_i (K_i + 1) J_i / |B|`,
//!
//! and the estimate's covariance is the sandwich
//! `Cov = P (ω² Σ_k c_k c_kᵀ) P`, `P = (JᵀJ)⁻¹` (White 1980; the error
//! covariance given by its generating process, not by the residuals'
//! autocorrelation: the fit absorbs the error's components along the
//! Jacobian's columns, so residual-based estimates such as Newey–West's
//! miss exactly the directions that matter). `ω² = s_d² τ_d`, the variance
//! of the residuals' first differences within each series times their
//! integrated autocorrelation time ([`crate::effective`], spectral): the
//! differences are the stationary increments, coloured by the
//! measurement's filter.
//!
//! Unlike one inflation factor for every direction, this weighs each
//! direction by how the walk's low frequencies reach it.
//!
//! ```
//! use bumpsim_estimate::walk::{Walk, meat};
//! use bumpsim_estimate::uncertainty::Series;
//! use nalgebra::DMatrix;
//! // one parameter, J = 1 at both residuals, walk from the first: c = (2, 1)
//! let j = DMatrix::from_element(2, 1, 1.0);
//! let m = meat(&j, &Series::contiguous([2].into_iter()), &[Walk { lead: 0, bias: None }], 1.0);
//! assert_eq!(m[(0, 0)], 5.0);
//! ```

use crate::effective::{Method, Series, of_series};
use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

/// Where a series' random walk starts and where its bias was removed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Walk {
    /// Samples from the start of the integration to the series' first
    /// residual.
    pub lead: usize,
    /// The bias window `(first, samples)`, counted from the start of the
    /// integration (None: no bias removed).
    pub bias: Option<(usize, usize)>,
}

/// The long-run variance ω² of the residuals' increments: the variance of
/// their first differences within each series times the differences'
/// integrated autocorrelation time (1 without differences).
pub fn increment_variance(residuals: &[f64], series: &[Series]) -> f64 {
    let differences: Vec<Vec<f64>> = series
        .iter()
        .map(|s| {
            (1..s.len)
                .map(|k| {
                    residuals[s.start + s.stride * k] - residuals[s.start + s.stride * (k - 1)]
                })
                .collect()
        })
        .collect();
    let views: Vec<&[f64]> = differences.iter().map(Vec::as_slice).collect();
    let count: usize = views.iter().map(|d| d.len()).sum();
    if count == 0 {
        return 0.0;
    }
    let variance = views
        .iter()
        .flat_map(|d| d.iter())
        .map(|v| v * v)
        .sum::<f64>()
        / count as f64;
    variance * of_series(&views, Method::Spectral, true).time
}

/// `ω² Σ_k c_k c_kᵀ` over every series (see the module) for the Jacobian
/// `jacobian` (residuals × parameters); `walks` one per series (a missing
/// one: the walk starts at the series' first residual, no bias).
pub fn meat(
    jacobian: &DMatrix<f64>,
    series: &[Series],
    walks: &[Walk],
    omega2: f64,
) -> DMatrix<f64> {
    let q = jacobian.ncols();
    let mut out = DMatrix::zeros(q, q);
    for (index, s) in series.iter().enumerate() {
        let walk = walks.get(index).copied().unwrap_or_default();
        let row = |i: usize| -> DVector<f64> { jacobian.row(s.start + s.stride * i).transpose() };
        // suffix sums: suffix[i] = Σ_{i' ≥ i} J_i'
        let mut suffix = vec![DVector::zeros(q); s.len + 1];
        let mut weighted = DVector::zeros(q);
        for i in (0..s.len).rev() {
            suffix[i] = &suffix[i + 1] + row(i);
            weighted += row(i) * (walk.lead + i + 1) as f64;
        }
        let last = walk.lead + s.len;
        let (b0, blen) = walk.bias.unwrap_or((0, 0));
        let end = last.max(b0 + blen);
        for k in 0..end {
            let mut c = match k.checked_sub(walk.lead) {
                None => suffix[0].clone(),
                Some(i) if i < s.len => suffix[i].clone(),
                Some(_) => DVector::zeros(q),
            };
            if blen > 0 && (b0..b0 + blen).contains(&k) {
                c -= &weighted / blen as f64;
            }
            out += &c * c.transpose();
        }
    }
    out * omega2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A constant J over a walk sampled from its start: Σ_k c_k² is
    /// Σ_k (n − k)² for n residuals, and removing the bias over a
    /// pre-trigger of the walk's own samples ends the walk there (a
    /// Brownian bridge): the pre-trigger's mean removed, the sum over it
    /// vanishes.
    #[test]
    fn a_constant_jacobian_gives_the_sum_of_squares_of_the_walk() {
        let n = 10;
        let j = DMatrix::from_element(n, 1, 1.0);
        let series = Series::contiguous([n].into_iter());
        let free = meat(
            &j,
            &series,
            &[Walk {
                lead: 0,
                bias: None,
            }],
            2.0,
        );
        let expected: f64 = (0..n).map(|k| ((n - k) as f64).powi(2)).sum();
        approx::assert_relative_eq!(free[(0, 0)], 2.0 * expected, epsilon = 1e-12);
        // led by 5 samples: those add 5 n²
        let led = meat(
            &j,
            &series,
            &[Walk {
                lead: 5,
                bias: None,
            }],
            1.0,
        );
        approx::assert_relative_eq!(
            led[(0, 0)],
            expected + 5.0 * (n * n) as f64,
            epsilon = 1e-12
        );
        // the lead's mean removed: c_k = n − Σ_i (5 + i + 1)/5 over it
        let bridged = meat(
            &j,
            &series,
            &[Walk {
                lead: 5,
                bias: Some((0, 5)),
            }],
            1.0,
        );
        let mean: f64 = (0..n).map(|i| (5 + i + 1) as f64).sum::<f64>() / 5.0;
        let lead_part = 5.0 * (n as f64 - mean).powi(2);
        approx::assert_relative_eq!(bridged[(0, 0)], expected + lead_part, epsilon = 1e-12);
    }

    /// A random walk of white increments of variance 4: ω² = 4 (τ ≈ 1).
    #[test]
    fn the_increments_of_a_walk_have_its_variance() {
        let mut draws = crate::search::Draws::new(3, 0);
        let mut walk = vec![0.0; 40_000];
        for k in 1..walk.len() {
            // uniform on ±√12: variance 1, times 2: variance 4
            walk[k] = walk[k - 1] + 2.0 * 12f64.sqrt() * (draws.unit() - 0.5);
        }
        let omega2 = increment_variance(&walk, &Series::contiguous([walk.len()].into_iter()));
        assert!((omega2 / 4.0 - 1.0).abs() < 0.1, "{omega2}");
    }
}
