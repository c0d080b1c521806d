//! The robust (sandwich) covariance of a least-squares estimate whose
//! residuals are neither independent nor of one variance, nor the model
//! the data's (issue 44): Huber–White with each residual series' own
//! autocorrelation (Newey & West 1987, *Econometrica* 55, 703–708).
//!
//! At the optimum the estimate's error is, to first order,
//! `δp = −P Jᵀ ε`, `P = (JᵀJ)⁻¹`, whatever produced the errors ε; so
//! `Cov(p) = P (Jᵀ Ω J) P`, `Ω = Cov(ε)`. The meat `Jᵀ Ω J` is estimated
//! from the residuals themselves, series by series (a case's window of one
//! sensor): with the scores `g_t = J_tᵀ r_t`,
//!
//! `Jᵀ Ω J ≈ Σ_series Σ_t Σ_u w(|t − u|) g_t g_uᵀ`,
//! `w(l) = 1 − l/(M + 1)` (Bartlett's kernel, positive semi-definite),
//!
//! M the series' own window: Sokal's `M ≥ 5 τ(M)` of its residuals
//! ([`crate::effective`]). A series whose misfit is large and slow (a model
//! family's error where a parameter is determined) weighs as much as it
//! actually moves that parameter, where one pooled `σ² τ` spreads the
//! pool's noise over every direction alike. With `S_k = Σ_{t=k−M}^{k} g_t`
//! the double sum is `Σ_k S_k S_kᵀ / (M + 1)`: one pass per series.
//!
//! Rows outside every series (stated priors) are independent with the
//! working variance `v` they were scaled to ([`crate::information::counted`]),
//! so the meat adds `v J_pᵀ J_p`; for independent data errors of variance
//! `v` the sandwich is `v P`, the Gaussian posterior's covariance.
//!
//! ```
//! use bumpsim_estimate::robust::meat;
//! use bumpsim_estimate::uncertainty::Series;
//! use nalgebra::DMatrix;
//! // one parameter, J = 1, residuals +1, −1, ...: the Bartlett sum of
//! // an alternating series is small next to Σ r² = 6
//! let r = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0];
//! let j = DMatrix::from_element(6, 1, 1.0);
//! let m = meat(&j, &r, &Series::contiguous([6].into_iter()), 0.0);
//! assert!(m[(0, 0)] < 6.0);
//! ```

use crate::effective::{Method, Series, of_series};
use nalgebra::{DMatrix, DVector};

/// The window M of one series' residuals (Sokal's; the whole series when
/// it does not settle).
fn window(values: &[f64]) -> usize {
    of_series(&[values], Method::Spectral, false)
        .window
        .min(values.len().saturating_sub(1))
}

/// The meat `Jᵀ Ω J` (see the module) over the columns of `jacobian`:
/// Bartlett-weighted score products within each series of `residuals`,
/// plus `prior_variance · J_pᵀ J_p` over the rows no series reaches.
pub fn meat(
    jacobian: &DMatrix<f64>,
    residuals: &[f64],
    series: &[Series],
    prior_variance: f64,
) -> DMatrix<f64> {
    let q = jacobian.ncols();
    let mut out = DMatrix::zeros(q, q);
    let mut data = 0;
    for s in series {
        let rows: Vec<usize> = (0..s.len).map(|k| s.start + s.stride * k).collect();
        data = rows.iter().fold(data, |d, &i| d.max(i + 1));
        let values: Vec<f64> = rows.iter().map(|&i| residuals[i]).collect();
        let m = window(&values);
        let score = |k: usize| -> DVector<f64> {
            jacobian.row(rows[k]).transpose() * residuals[rows[k]]
        };
        // S_k = Σ_{t = k − M}^{k} g_t for k = 0 .. n + M − 1
        let mut sum = DVector::zeros(q);
        let mut part = DMatrix::zeros(q, q);
        for k in 0..s.len + m {
            if k < s.len {
                sum += score(k);
            }
            if k > m {
                sum -= score(k - m - 1);
            }
            part += &sum * sum.transpose();
        }
        out += part / (m + 1) as f64;
    }
    for row in data.min(jacobian.nrows())..jacobian.nrows() {
        let a = jacobian.row(row).transpose();
        out += &a * a.transpose() * prior_variance;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Independent residuals: the Bartlett meat approaches `Σ r² JᵀJ/n`
    /// times n, the classical `σ² JᵀJ`; a slow misfit (a constant offset
    /// over the series) weighs far more than its `Σ r²`.
    #[test]
    fn white_residuals_give_the_classical_meat_and_a_slow_misfit_more() {
        let mut draws = crate::search::Draws::new(3, 0);
        let n = 20_000;
        let r: Vec<f64> = (0..n).map(|_| draws.unit() - 0.5).collect();
        let j = DMatrix::from_fn(n, 2, |i, c| if c == 0 { 1.0 } else { (i % 7) as f64 });
        let series = Series::contiguous([n].into_iter());
        let m = meat(&j, &r, &series, 0.0);
        let sse: f64 = r.iter().map(|v| v * v).sum();
        let classical = j.transpose() * &j * (sse / n as f64);
        for (a, b) in m.iter().zip(classical.iter()) {
            assert!((a - b).abs() < 0.1 * classical[(1, 1)], "{m} {classical}");
        }
        let offset = vec![0.1; 2000];
        let one = DMatrix::from_element(2000, 1, 1.0);
        let slow = meat(&one, &offset, &Series::contiguous([2000].into_iter()), 0.0);
        assert!(slow[(0, 0)] > 100.0 * 0.01 * 2000.0, "{slow}");
    }

    /// Rows beyond the series are the priors: `v aaᵀ` each.
    #[test]
    fn prior_rows_add_their_working_variance() {
        let j = DMatrix::from_row_slice(3, 1, &[0.0, 0.0, 2.0]);
        let m = meat(&j, &[0.0, 0.0, 0.0], &Series::contiguous([2].into_iter()), 0.5);
        approx::assert_relative_eq!(m[(0, 0)], 2.0, epsilon = 1e-12);
    }
}
