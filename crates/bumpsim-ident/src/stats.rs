//! Uncertainty of a chain identification: the layer's
//! ([`bumpsim_estimate::uncertainty`]: `Cov(ln θ) = σ² (JᵀJ)⁻¹` at the
//! optimum, delta-method standard errors, Student-t 95 % intervals, rank
//! and determination flags, the weakest direction) on the exact Jacobian of
//! [`Objective`], with the thesis's parameter names (`m1`, `c1`, `k1`) and
//! units.
//!
//! The error model is the objective's ([`Objective::correlation`]):
//! independent errors for the thesis's displacements, a random walk of
//! known start for velocities integrated from accelerations (the sandwich
//! of [`bumpsim_estimate::walk`]), else the spectral inflation. The pooled
//! lag-1 autocorrelation of the residuals is reported
//! ([`Uncertainty::residual_correlation`]).

use crate::case::Objective;
use bumpsim_core::model::{parameter_count, parameter_kind, parameter_name};
use bumpsim_estimate::effective::{Effective, Method, of_residuals};
use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::uncertainty::{Estimated, Parameter};
use nalgebra::DMatrix;

pub use bumpsim_estimate::uncertainty::{
    NULL_SHARE, RANK_TOLERANCE, Share, Uncertainty, determination, is_determined,
};

/// The parameters of a `dof`-mass chain (`m1`.., `c1`.., `k1`..).
pub fn parameters(dof: usize) -> Vec<Parameter> {
    (0..parameter_count(dof))
        .map(|i| Parameter::new(parameter_name(dof, i), parameter_kind(dof, i).0.dimension()))
        .collect()
}

/// The effective sample size (spectral) of the residual series of
/// `objective` at free log parameters `p` (every sample when they cannot
/// be evaluated).
pub fn effective(objective: &Objective, p: &[f64]) -> Effective {
    let mut r = vec![0.0; objective.residual_count()];
    let method = match objective.evaluate(p, &mut r, None) {
        true => Method::Spectral,
        false => Method::Independent,
    };
    of_residuals(&r, &objective.series(), method)
}

/// Uncertainty at free log parameters `p` of `objective`, within the log
/// bounds `lower`, `upper` of the free parameters.
pub fn uncertainty(
    objective: &Objective,
    p: &[f64],
    lower: &[f64],
    upper: &[f64],
    dof: usize,
) -> Uncertainty {
    let (m, q) = (objective.residual_count(), objective.free().len());
    let mut r = vec![0.0; m];
    let mut jacobian = DMatrix::zeros(m, q);
    let evaluated = objective.evaluate(p, &mut r, Some(&mut jacobian));
    let theta = objective.theta(p);
    let parameters = parameters(dof);
    let series = objective.series();
    let walks = objective.walks();
    let u = bumpsim_estimate::uncertainty::with_walks(
        &Estimated {
            parameters: &parameters,
            theta: &theta,
            free: objective.free(),
            p,
            bounds: (lower, upper),
            residuals: &r,
            jacobian: &jacobian,
            series: &series,
            correlation: objective.correlation(),
        },
        &walks,
    );
    match evaluated {
        true => u,
        false => bumpsim_estimate::uncertainty::unassessed(u),
    }
}
