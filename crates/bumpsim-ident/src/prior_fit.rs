//! The chain's fit with its stated priors ([`crate::priors`], issue 44
//! item 3), after the multi-start search of the data alone.
//!
//! With intervals from the integrated noise's random walk (the velocity
//! objective of accelerometer data), the best of the data's search is
//! polished on the whitened moments of that covariance
//! ([`crate::whitened`], `‖m(θ)‖²`) plus `Σ z²`: the mode of the density
//! `--posterior` samples, whose curvature is the data's covariance with
//! the priors' information. Otherwise the priors weigh against the noise
//! of one residual, `σ = √(τ F/(n − q))` ([`bumpsim_estimate::prior::noise`],
//! τ the residuals' integrated autocorrelation time, spectral): minimising
//! `F + σ² Σ z²` maximises the posterior whose likelihood counts the
//! residuals with their effective sample size; σ is known only at an
//! optimum, so the best is polished at its σ and again at the new
//! optimum's until σ changes by less than 10 % (at most [`ROUNDS`] times). The uncertainty is the data's (the
//! random walk's sandwich of [`crate::stats`]) with the priors'
//! information added (`Cov = (C⁻¹ + Σ g gᵀ/s²)⁻¹`,
//! [`bumpsim_estimate::prior::with_priors`]); a parameter whose posterior
//! spread is mostly its prior's is named not determined by the data
//! ([`bumpsim_estimate::prior::prior_only`]).

use crate::case::Objective;
use crate::stats::Uncertainty;
use bumpsim_estimate::effective::{Method, of_residuals};
use bumpsim_estimate::lm::{self, LeastSquares, Outcome, minimise};
use bumpsim_estimate::prior::{self, Moved, Prior, Priored};
use bumpsim_estimate::uncertainty::Correlation;

/// The most polishing rounds at a new σ.
pub const ROUNDS: usize = 5;

/// The estimate with the priors, and what they weigh against.
#[derive(Debug, Clone)]
pub struct Posed {
    /// The optimum (its `objective`: the data's F alone).
    pub outcome: Outcome,
    /// The priors (empty: the data's optimum as it was).
    pub priors: Vec<Prior>,
    /// σ of the priors' residuals at the optimum (1: the whitened
    /// moments').
    pub noise: f64,
}

/// The data's `best` optimum of a `dof`-mass objective (`make` makes
/// it) polished with `priors` within the log `bounds` (see the module);
/// as it was without priors.
pub fn fit<'a>(
    make: &dyn Fn() -> Objective<'a>,
    dof: usize,
    priors: &[Prior],
    best: &Outcome,
    bounds: (&[f64], &[f64]),
    solver: &lm::Settings,
) -> Posed {
    let objective = make();
    let sigma = noise_at(&objective, &best.parameters);
    if priors.is_empty() {
        return Posed {
            outcome: best.clone(),
            priors: Vec::new(),
            noise: sigma,
        };
    }
    let whitened = whitened(make, dof, priors, best, bounds, solver);
    let (outcome, noise) = match whitened {
        Some(outcome) => (outcome, 1.0),
        None => by_noise(&objective, priors, best, bounds, solver, sigma),
    };
    Posed {
        outcome,
        priors: priors.to_vec(),
        noise,
    }
}

/// The posterior's mode over the whitened moments of the random walk's
/// covariance at `best` ([`crate::whitened`]) and the priors, each at
/// unit noise: the density `--posterior` samples. None when the intervals
/// do not come from a random walk or a free parameter has none.
fn whitened<'a>(
    make: &dyn Fn() -> Objective<'a>,
    dof: usize,
    priors: &[Prior],
    best: &Outcome,
    (lower, upper): (&[f64], &[f64]),
    solver: &lm::Settings,
) -> Option<Outcome> {
    let objective = make();
    let p = &best.parameters;
    let u = crate::stats::uncertainty(&objective, p, lower, upper, dof);
    if u.error_model != Correlation::RandomWalk {
        return None;
    }
    let theta = objective.theta(p);
    let covariance = crate::whitened::covariance(&u, &theta, objective.free())?;
    let transform = crate::whitened::transform_of(&objective, &covariance, p)?;
    let moments = crate::whitened::Whitened::new(make(), &transform);
    let posed = Priored::new(moments, priors.to_vec(), 1.0).ok()?;
    let next = minimise(&posed, p, lower, upper, solver);
    Some(Outcome {
        objective: data_objective(&objective, &next.parameters),
        iterations: best.iterations + next.iterations,
        evaluations: best.evaluations + next.evaluations,
        ..next
    })
}

/// The priors weighed against σ of one residual, polished until σ
/// settles (see the module); the optimum and its σ.
fn by_noise(
    objective: &Objective,
    priors: &[Prior],
    best: &Outcome,
    (lower, upper): (&[f64], &[f64]),
    solver: &lm::Settings,
    mut sigma: f64,
) -> (Outcome, f64) {
    let mut outcome = best.clone();
    for _ in 0..ROUNDS {
        let Ok(posed) = Priored::new(objective, priors.to_vec(), sigma) else {
            break;
        };
        let next = minimise(&posed, &outcome.parameters, lower, upper, solver);
        outcome = Outcome {
            objective: data_objective(objective, &next.parameters),
            iterations: outcome.iterations + next.iterations,
            evaluations: outcome.evaluations + next.evaluations,
            ..next
        };
        let at = noise_at(objective, &outcome.parameters);
        let settled = ((at - sigma) / sigma).abs() < 0.1;
        sigma = at;
        if settled {
            break;
        }
    }
    (outcome, sigma)
}

impl Posed {
    /// The data's uncertainty `u` at the optimum (θ `theta`, free
    /// parameters `free`) with the priors' information, each prior with
    /// how far the data moved it, and the warnings: priors the data
    /// disagree with, parameters informed by their prior alone (marked
    /// not determined).
    pub fn posterior(
        &self,
        u: Uncertainty,
        theta: &[f64],
        free: &[usize],
    ) -> (Uncertainty, Vec<Moved>, Vec<String>) {
        if self.priors.is_empty() {
            return (u, Vec::new(), Vec::new());
        }
        let p = &self.outcome.parameters;
        let mut u = prior::with_priors(u, &self.priors, theta, free, p);
        let moved = prior::moved(&self.priors, p);
        let mut warnings = prior::warnings(&moved);
        let log_sd: Vec<Option<f64>> = free
            .iter()
            .map(|&i| u.standard_errors[i].map(|se| se / theta[i]))
            .collect();
        for (j, prior) in prior::prior_only(&self.priors, &log_sd) {
            u.determined[free[j]] = Some(false);
            warnings.push(format!(
                "{} not determined by the data: its interval is mostly its prior's ({}, spread {} of ln θ)",
                prior.name, prior.source, prior::spread_text(prior.spread)
            ));
        }
        (u, moved, warnings)
    }
}

/// The data's F at `p` (∞ where the model cannot be evaluated).
fn data_objective(objective: &Objective, p: &[f64]) -> f64 {
    let mut r = vec![0.0; objective.residual_count()];
    match objective.evaluate(p, &mut r, None) {
        true => r.iter().map(|v| v * v).sum(),
        false => f64::INFINITY,
    }
}

/// σ of one residual at `p`: `√(τ F/(n − q))` (1 where the model cannot
/// be evaluated).
fn noise_at(objective: &Objective, p: &[f64]) -> f64 {
    let mut r = vec![0.0; objective.residual_count()];
    if !objective.evaluate(p, &mut r, None) {
        return 1.0;
    }
    let f: f64 = r.iter().map(|v| v * v).sum();
    let tau = of_residuals(&r, &objective.series(), Method::Spectral).time;
    prior::noise(f, r.len(), p.len(), tau)
}
