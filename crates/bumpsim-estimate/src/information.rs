//! The information of a priored estimate as the intervals count it: the
//! data's at the noise the error model gives them, each prior's at its own
//! stated spread (issue 44).
//!
//! A search weighs its priors' residuals `r_p = ν (ln θ − ln c)/s` against
//! some noise ν of one data residual ([`crate::prior::Priored`]); the
//! Gaussian approximation of the posterior is
//!
//! `Cov(ln θ)⁻¹ = J_dᵀ J_d / (σ² κ) + Σ_p a_p a_pᵀ / s_p²`,
//!
//! σ² the data residuals' variance `F_d/(n + n_p − q)` (as the layer
//! counts the degrees of freedom of the stacked rows), κ the variance inflation
//! of their correlation ([`crate::effective`]: the integrated
//! autocorrelation time τ for [`Correlation::Spectral`]; `(1 + ρ)/(1 − ρ)`
//! for AR(1); 1 for independent errors), `a_p` a prior's gradient in
//! `ln θ` (Bishop 2006, *Pattern Recognition and Machine Learning*,
//! eq. 3.54, with the noise precision `1/(σ² κ)`). The layer's
//! [`crate::uncertainty`] gives `σ² κ (JᵀJ)⁻¹` of the stacked rows, which is
//! this covariance exactly when each prior row carries `√(σ² κ)` instead of
//! ν: [`counted`] rescales them, whatever ν the search used, so the
//! intervals neither borrow the search's weighting nor count a prior
//! tighter or looser than stated.
//!
//! ```
//! use bumpsim_estimate::information::counted;
//! use bumpsim_estimate::uncertainty::{Correlation, Series};
//! use nalgebra::DMatrix;
//! // two data residuals (F_d = 2; 3 rows, 1 parameter: σ² = 1) and one
//! // prior row weighed by ν = 0.5
//! let (mut r, mut j) = (vec![1.0, -1.0, 0.3], DMatrix::from_element(3, 1, 1.0));
//! let series = Series::contiguous([2].into_iter());
//! let noise = counted(&mut r, &mut j, &series, Correlation::Independent, 0.5);
//! assert!((noise - 1.0).abs() < 1e-12);
//! // the prior row now carries √(σ² κ)/ν = 2 times its Jacobian, no residual
//! assert!((j[(2, 0)] - 2.0).abs() < 1e-12 && r[2] == 0.0);
//! ```

use crate::effective::{Method, Series, of_residuals};
use crate::uncertainty::{Correlation, lag_one};
use nalgebra::DMatrix;

/// The variance inflation κ of `correlation` for the residual `series`:
/// 1, `(1 + ρ)/(1 − ρ)` or τ (a random walk's own sandwich: τ of what the
/// fit leaves, as [`crate::uncertainty`] adds it).
pub fn inflation(residuals: &[f64], series: &[Series], correlation: Correlation) -> f64 {
    match correlation {
        Correlation::Independent => 1.0,
        Correlation::Ar1 => {
            let rho = lag_one(residuals, series);
            (1.0 + rho) / (1.0 - rho)
        }
        Correlation::Spectral | Correlation::RandomWalk => {
            of_residuals(residuals, series, Method::Spectral).time
        }
    }
}

/// Rescales the prior rows of a priored problem's `residuals` and
/// `jacobian` (every row after the last one `series` reach, each weighed
/// by `prior_noise`, [`crate::prior::Priored::noise`]) to the noise the
/// intervals count for the data rows, `√(σ² κ)` (see the module), and sets
/// their residuals to 0 so that σ² is the data's; returns that noise.
/// Without prior rows nothing changes.
pub fn counted(
    residuals: &mut [f64],
    jacobian: &mut DMatrix<f64>,
    series: &[Series],
    correlation: Correlation,
    prior_noise: f64,
) -> f64 {
    let data = series
        .iter()
        .map(|s| s.start + s.stride * s.len.saturating_sub(1) + 1)
        .max()
        .unwrap_or(0)
        .min(residuals.len());
    let q = jacobian.ncols();
    let sse: f64 = residuals[..data].iter().map(|v| v * v).sum();
    let dof = residuals.len().saturating_sub(q).max(1) as f64;
    let kappa = inflation(&residuals[..data], series, correlation).max(1.0);
    let noise = (sse / dof * kappa).sqrt();
    if !(noise.is_finite() && noise > 0.0 && prior_noise > 0.0) {
        return noise;
    }
    let scale = noise / prior_noise;
    residuals[data..].fill(0.0);
    for row in data..jacobian.nrows() {
        jacobian.row_mut(row).scale_mut(scale);
    }
    noise
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::uncertainty::{Estimated, Parameter, uncertainty};

    /// One parameter, data of information 10 at σ² κ = 1 and a prior of
    /// spread 0.1 (information 100): the variance is 1/(10 + 100) in ln θ,
    /// whatever noise the search weighed the prior by.
    #[test]
    fn the_posterior_variance_adds_the_data_and_the_prior_at_its_spread() {
        let n = 10;
        let r: Vec<f64> = (0..n)
            .map(|k| if k % 2 == 0 { 1.0 } else { -1.0 })
            .chain([0.7])
            .collect();
        let series = Series::contiguous([n].into_iter());
        for search_noise in [0.01, 1.0, 30.0] {
            let mut j = DMatrix::from_element(n + 1, 1, 1.0);
            j[(n, 0)] = search_noise / 0.1;
            let mut rr = r.clone();
            counted(
                &mut rr,
                &mut j,
                &series,
                Correlation::Independent,
                search_noise,
            );
            let u = uncertainty(&Estimated {
                parameters: &[Parameter::with_symbol("a", "-")],
                theta: &[1.0],
                free: &[0],
                p: &[0.0],
                bounds: (&[-10.0], &[10.0]),
                residuals: &rr,
                jacobian: &j,
                series: &series,
                correlation: Correlation::Independent,
            });
            // σ² = 10/(11 − 1) = 1 from the data alone (the prior's residual zeroed)
            let expected = (1.0 / (n as f64 / 1.0 + 100.0)).sqrt();
            let se = u.standard_errors[0].unwrap();
            approx::assert_relative_eq!(se, expected, max_relative = 1e-12);
        }
    }
}
