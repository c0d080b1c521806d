//! The one forward-difference Jacobian of the estimation layer, for the
//! models whose residuals have no exact sensitivities (yet): column j of
//! `J = ∂r/∂p` is
//!
//! ```text
//! J[:, j] = (r(p + h e_j) − r(p)) / h
//! ```
//!
//! (a first-order difference: truncation `O(h |r''|)`, rounding
//! `O(ε |r| / h)`; in log parameters `h = 1e-6` balances the two for
//! residuals of order one, a larger step spans the kinks a sampled history
//! makes). The columns are independent and evaluated in parallel; each
//! shifted `p` is `p` with `h` added to its entry j, so a column is what a
//! sequential loop over the same residuals gives, bit for bit.
//!
//! ```
//! use bumpsim_estimate::difference::forward_jacobian;
//! use nalgebra::DMatrix;
//! // r(p) = [p0², p0 p1]: J = [[2 p0, 0], [p1, p0]]
//! let residuals = |p: &[f64], r: &mut [f64]| {
//!     r[0] = p[0] * p[0];
//!     r[1] = p[0] * p[1];
//!     true
//! };
//! let p = [3.0, 2.0];
//! let mut r = [0.0; 2];
//! residuals(&p, &mut r);
//! let mut j = DMatrix::zeros(2, 2);
//! assert!(forward_jacobian(&p, &r, 1e-7, &residuals, &mut j));
//! assert!((j[(0, 0)] - 6.0).abs() < 1e-5 && j[(0, 1)] == 0.0);
//! assert!((j[(1, 0)] - 2.0).abs() < 1e-6 && (j[(1, 1)] - 3.0).abs() < 1e-6);
//! ```

use nalgebra::DMatrix;
use rayon::prelude::*;

/// Fills `jacobian` (rows: `r.len()`, columns: `p.len()`) with the forward
/// differences of step `step` of `residuals` at `p`, whose residuals are
/// `r`; false when a shifted evaluation fails (`residuals` returns false).
pub fn forward_jacobian(
    p: &[f64],
    r: &[f64],
    step: f64,
    residuals: &(dyn Fn(&[f64], &mut [f64]) -> bool + Sync),
    jacobian: &mut DMatrix<f64>,
) -> bool {
    let columns: Vec<Option<Vec<f64>>> = (0..p.len())
        .into_par_iter()
        .map(|j| {
            let mut shifted = p.to_vec();
            shifted[j] += step;
            let mut column = vec![0.0; r.len()];
            residuals(&shifted, &mut column)
                .then(|| column.iter().zip(r).map(|(a, b)| (a - b) / step).collect())
        })
        .collect();
    for (j, column) in columns.into_iter().enumerate() {
        let Some(column) = column else {
            return false;
        };
        jacobian.column_mut(j).copy_from_slice(&column);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth residual's differences approach its derivative as O(h),
    /// and a failing evaluation is reported.
    #[test]
    fn differences_approach_the_derivative_and_report_failures() {
        let residuals = |p: &[f64], r: &mut [f64]| {
            r[0] = p[0].exp() * p[1].sin();
            r[1] = p[1] * p[1];
            true
        };
        let p = [0.3, 1.1];
        let mut r = [0.0; 2];
        residuals(&p, &mut r);
        let exact = [
            [p[0].exp() * p[1].sin(), p[0].exp() * p[1].cos()],
            [0.0, 2.0 * p[1]],
        ];
        let mut j = DMatrix::zeros(2, 2);
        for h in [1e-3, 1e-4] {
            assert!(forward_jacobian(&p, &r, h, &residuals, &mut j));
            for (row, line) in exact.iter().enumerate() {
                for (col, e) in line.iter().enumerate() {
                    assert!((j[(row, col)] - e).abs() < 2.0 * h, "{h} {row} {col}");
                }
            }
        }
        let failing = |p: &[f64], r: &mut [f64]| {
            r.fill(1.0);
            p[1] < 1.1
        };
        assert!(!forward_jacobian(&p, &r, 1e-6, &failing, &mut j));
    }
}
