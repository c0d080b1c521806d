//! The posterior's whitened likelihood (issue 44): the chain's residuals
//! mapped onto the identification's own covariance, so that the posterior
//! and the local intervals count the data alike.
//!
//! With the Jacobian `J` at the optimum θ̂, `P = (JᵀJ)⁻¹` and the local
//! covariance `C = L Lᵀ` of the free log parameters (the random walk's
//! sandwich plus what the fit leaves, [`bumpsim_estimate::walk`]), the
//! whitened residuals are the q moments
//!
//! `m(θ) = L⁻¹ P Jᵀ r(θ)`,
//!
//! and `ln L(θ) = −½ ‖m(θ)‖²` ([`bumpsim_estimate::posterior::Noise::Whitened`]). Near θ̂,
//! `Jᵀ r(θ) ≈ JᵀJ (θ − θ̂)`, so `‖m‖² ≈ (θ − θ̂)ᵀ C⁻¹ (θ − θ̂)`: the
//! posterior's curvature is the covariance the intervals come from, while
//! `r(θ)` keeps the model's nonlinearity away from θ̂ (a Laplace-type
//! quasi-posterior, Chernozhukov & Hong 2003, with the score as its
//! moment). The effective-sample likelihood `−(n_eff/2) ln F` counted every
//! direction with one n_eff and, on the bundled example, did not converge.

use crate::case::Objective;
use crate::result::Identification;
use crate::stats::Uncertainty;
use bumpsim_estimate::lm::LeastSquares;
use nalgebra::DMatrix;

/// The whitened moments of an objective (see the module).
pub struct Whitened<'a> {
    objective: Objective<'a>,
    /// `L⁻¹ P Jᵀ`, q × n.
    transform: DMatrix<f64>,
    residuals: std::cell::RefCell<(Vec<f64>, DMatrix<f64>)>,
}

impl<'a> Whitened<'a> {
    /// The whitened moments of `objective` by `transform` ([`transform`]).
    pub fn new(objective: Objective<'a>, transform: &DMatrix<f64>) -> Whitened<'a> {
        let (n, q) = (objective.residual_count(), objective.free().len());
        Whitened {
            objective,
            transform: transform.clone(),
            residuals: std::cell::RefCell::new((vec![0.0; n], DMatrix::zeros(n, q))),
        }
    }
}

/// `L⁻¹ P Jᵀ` of `objective` around `result` (free log parameters
/// `optimum`), `C` the data's covariance: the intervals' less the
/// information of the result's stated priors (`C⁻¹ = C_post⁻¹ − Σ g gᵀ/s²`,
/// undoing [`bumpsim_estimate::prior::with_priors`]; the posterior adds
/// the priors itself); None when a free parameter has no standard error
/// (at a bound, undetermined) or a matrix is singular.
pub fn transform(
    objective: &Objective,
    result: &Identification,
    optimum: &[f64],
) -> Option<DMatrix<f64>> {
    let theta = result.model.parameters();
    let mut covariance = covariance(&result.uncertainty, &theta, objective.free())?;
    if !result.stated.is_empty() {
        let information = bumpsim_estimate::prior::information(&result.stated, optimum);
        covariance = (covariance.try_inverse()? - information).try_inverse()?;
    }
    transform_of(objective, &covariance, optimum)
}

/// `L⁻¹ P Jᵀ` of `objective` at `optimum` for the covariance `C = L Lᵀ`
/// of its free log parameters.
pub fn transform_of(
    objective: &Objective,
    covariance: &DMatrix<f64>,
    optimum: &[f64],
) -> Option<DMatrix<f64>> {
    let (n, q) = (objective.residual_count(), objective.free().len());
    let (mut r, mut j) = (vec![0.0; n], DMatrix::zeros(n, q));
    if !objective.evaluate(optimum, &mut r, Some(&mut j)) {
        return None;
    }
    let normal = (j.transpose() * &j).try_inverse()?;
    let inverse = covariance.clone().cholesky()?.l().try_inverse()?;
    let transform = inverse * normal * j.transpose();
    transform.iter().all(|v| v.is_finite()).then_some(transform)
}

/// The covariance of the free log parameters `free` from the standard
/// errors and correlations of `u` at `theta`; None when one is missing.
pub fn covariance(u: &Uncertainty, theta: &[f64], free: &[usize]) -> Option<DMatrix<f64>> {
    let log_se: Vec<f64> = free
        .iter()
        .map(|&i| u.standard_errors[i].map(|se| se / theta[i]))
        .collect::<Option<_>>()?;
    let q = free.len();
    let mut c = DMatrix::zeros(q, q);
    for a in 0..q {
        for b in 0..q {
            c[(a, b)] = u.correlation[free[a]][free[b]]? * log_se[a] * log_se[b];
        }
    }
    Some(c)
}

impl LeastSquares for Whitened<'_> {
    fn residual_count(&self) -> usize {
        self.transform.nrows()
    }

    fn parameter_count(&self) -> usize {
        self.objective.parameter_count()
    }

    fn evaluate(&self, p: &[f64], out: &mut [f64], jac: Option<&mut DMatrix<f64>>) -> bool {
        let mut scratch = self.residuals.borrow_mut();
        let (r, j) = &mut *scratch;
        let with_jacobian = jac.is_some();
        if !self
            .objective
            .evaluate(p, r, with_jacobian.then_some(&mut *j))
        {
            return false;
        }
        let moments = &self.transform * nalgebra::DVector::from_column_slice(r);
        out.copy_from_slice(moments.as_slice());
        if let Some(jac) = jac {
            jac.copy_from(&(&self.transform * &*j));
        }
        out.iter().all(|v| v.is_finite())
    }

    /// `(T J)ᵀ v = Jᵀ (Tᵀ v)`, T the transform: the objective's own.
    fn transposed(&self, p: &[f64], v: &[f64], product: &mut nalgebra::DVector<f64>) -> bool {
        if v.len() != self.residual_count() {
            return false;
        }
        let pulled = self
            .transform
            .tr_mul(&nalgebra::DVector::from_column_slice(v));
        self.objective.transposed(p, pulled.as_slice(), product)
    }
}
