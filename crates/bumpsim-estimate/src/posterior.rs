//! The posterior of any least-squares model's parameters (issue 39),
//! sampled by the ensemble sampler ([`crate::sampler`]) in the search
//! variables p (`ln θ` or θ, [`Parameter`]).
//!
//! **Likelihood: the noise model of the effective sample size.** With
//! Gaussian errors of unknown variance σ², n residuals worth n_eff
//! independent ones ([`crate::effective`]) and σ integrated out under
//! Jeffreys' prior `p(σ) ∝ 1/σ`:
//!
//! `ln L(p) = −(n_eff/2) ln F(p)`, `F = Σ r²` ([`Noise::Effective`]).
//!
//! For a linear model with n_eff = n this is the textbook marginal
//! posterior, a Student t with n − q degrees of freedom about the least
//! squares estimate and scale `s² (XᵀX)⁻¹`, `s² = F̂/(n − q)` (Box & Tiao
//! 1973, sec. 2.7); near the optimum it is a Gaussian of covariance
//! `(F̂/n_eff)(JᵀJ)⁻¹`, the local covariance inflated by `n/n_eff` as the
//! intervals of correlated residuals are. With a known noise level,
//! `ln L = −F/(2σ²)` ([`Noise::Known`]).
//!
//! **Prior**: uniform in p within the bounds: log-uniform for a positive
//! θ (scale-invariant: no unit or decade is preferred), uniform for a
//! linear one; fixed parameters stay fixed.
//!
//! **Start**: the walkers are drawn from the local (Laplace) approximation
//! `N(p̂, s² (JᵀJ)⁺)` at the optimum (at most a factor e in each direction
//! the data leave free), mirrored into the bounds at a bound (a parameter
//! at its bound keeps walkers on its inner side) and pulled back towards
//! the optimum where the model cannot be evaluated.
//!
//! **Summary**: for each parameter the posterior mean, median, standard
//! deviation and the equal-tailed 90 % and 95 % intervals of θ (quantiles
//! interpolated linearly between order statistics, numpy's default), the
//! sampler's diagnostics with their warnings, and up to
//! [`Settings::kept`] draws of θ (evenly thinned) for plots and
//! propagation.
//!
//! ```
//! use bumpsim_estimate::lm::LeastSquares;
//! use bumpsim_estimate::posterior::{Noise, Settings, posterior};
//! use bumpsim_estimate::uncertainty::Parameter;
//! use nalgebra::DMatrix;
//! /// y = a x + b, a and b searched as is
//! struct Line { x: Vec<f64>, y: Vec<f64> }
//! impl LeastSquares for Line {
//!     fn residual_count(&self) -> usize { self.x.len() }
//!     fn parameter_count(&self) -> usize { 2 }
//!     fn evaluate(&self, p: &[f64], r: &mut [f64], jac: Option<&mut DMatrix<f64>>) -> bool {
//!         for k in 0..self.x.len() { r[k] = p[0] * self.x[k] + p[1] - self.y[k]; }
//!         if let Some(j) = jac { for k in 0..self.x.len() { j[(k, 0)] = self.x[k]; j[(k, 1)] = 1.0; } }
//!         true
//!     }
//! }
//! let x: Vec<f64> = (0..40).map(|k| k as f64 / 40.0).collect();
//! let y = x.iter().enumerate().map(|(k, x)| 2.0 * x + 1.0 + 0.05 * (k as f64 * 2.3).sin()).collect();
//! let line = Line { x, y };
//! let parameters = [Parameter::with_symbol("a", "-").linear(1.0), Parameter::with_symbol("b", "-").linear(1.0)];
//! let settings = Settings::new(Noise::Effective(40.0), 1);
//! let bounds = (vec![-10.0; 2], vec![10.0; 2]);
//! let optimum = [2.0, 1.0];
//! let post = posterior(&|| &line, &parameters, &[0, 1], &optimum, (&bounds.0, &bounds.1), &settings).unwrap();
//! assert!((post.mean[0] - 2.0).abs() < 0.05 && (post.mean[1] - 1.0).abs() < 0.05);
//! let [low, high] = post.ci90[0].unwrap();
//! assert!(low < 2.0 && 2.0 < high);
//! ```

use crate::lm::LeastSquares;
use crate::sampler::{Chain, Diagnostics, Ensemble, LogDensity, SamplerError, sample_observed};
use crate::search::Draws;
use crate::uncertainty::{Parameter, RANK_TOLERANCE};
use nalgebra::DMatrix;
use serde::Serialize;

/// The error model of the likelihood.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Noise {
    /// σ unknown and integrated out, with this effective sample size:
    /// `ln L = −(n_eff/2) ln F`.
    Effective(f64),
    /// σ known (residual unit): `ln L = −F/(2σ²)`.
    Known(f64),
    /// Residuals already whitened to unit variance (a quasi-likelihood
    /// whose curvature is the local covariance, e.g. the chain's
    /// random-walk covariance): `ln L = −F/2`.
    Whitened,
}

impl Noise {
    /// `ln L` of an objective F.
    pub fn log_likelihood(self, objective: f64) -> f64 {
        match self {
            Noise::Effective(n) => -0.5 * n * objective.ln(),
            Noise::Known(sigma) => -0.5 * objective / (sigma * sigma),
            Noise::Whitened => -0.5 * objective,
        }
    }

    /// The variance `s²` of the local approximation at objective F̂.
    fn variance(self, objective: f64) -> f64 {
        match self {
            Noise::Effective(n) => objective / n,
            Noise::Known(sigma) => sigma * sigma,
            Noise::Whitened => 1.0,
        }
    }
}

/// How the posterior is sampled.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Settings {
    /// The likelihood's error model.
    pub noise: Noise,
    /// Walkers, steps, burn-in and seed (walkers: 0 for the default, the
    /// larger of 32 and 2 d + 2 rounded up to even).
    pub ensemble: Ensemble,
    /// The most draws of θ kept in the summary.
    pub kept: usize,
}

impl Settings {
    /// 4000 steps of which 1000 burnt, the default walkers, 4000 draws
    /// kept.
    pub fn new(noise: Noise, seed: u64) -> Settings {
        Settings {
            noise,
            ensemble: Ensemble {
                walkers: 0,
                steps: 4000,
                burn: 1000,
                seed,
            },
            kept: 4000,
        }
    }
}

/// The sampled posterior (see the module). Vectors are in the model's
/// parameter order; a fixed parameter has its value as mean and median,
/// zero deviation and no interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Posterior {
    /// Parameter names.
    pub names: Vec<String>,
    /// Posterior means of θ, SI.
    pub mean: Vec<f64>,
    /// Medians of θ, SI.
    pub median: Vec<f64>,
    /// Standard deviations of θ, SI.
    pub sd: Vec<f64>,
    /// Equal-tailed 90 % intervals (5 % and 95 % quantiles), SI.
    pub ci90: Vec<Option<[f64; 2]>>,
    /// Equal-tailed 95 % intervals, SI.
    pub ci95: Vec<Option<[f64; 2]>>,
    /// Parameters held fixed.
    pub fixed: Vec<bool>,
    /// The likelihood's error model.
    pub noise: Noise,
    /// The run.
    pub ensemble: Ensemble,
    /// Its diagnostics (of the free parameters, in their order).
    pub diagnostics: Diagnostics,
    /// Draws of θ (every parameter), evenly thinned.
    pub draws: Vec<Vec<f64>>,
}

/// Why the posterior cannot be sampled.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PosteriorError {
    /// The sampler refused the run.
    #[error("posterior: {0}")]
    Sampler(#[from] SamplerError),
    /// No free parameter.
    #[error("posterior: no free parameter to sample")]
    Nothing,
}

/// The log posterior of a problem: its log likelihood within the bounds
/// (the density the sampler runs on, public so that another sampler can
/// run on the same one).
pub struct Density<P> {
    problem: P,
    noise: Noise,
    lower: Vec<f64>,
    upper: Vec<f64>,
    residuals: Vec<f64>,
}

impl<P: LeastSquares> Density<P> {
    /// The log posterior of `problem` with `noise` within the bounds of
    /// the search variables.
    pub fn new(problem: P, noise: Noise, (lower, upper): (&[f64], &[f64])) -> Density<P> {
        let residuals = vec![0.0; problem.residual_count()];
        Density {
            problem,
            noise,
            lower: lower.to_vec(),
            upper: upper.to_vec(),
            residuals,
        }
    }
}

impl<P: LeastSquares> LogDensity for Density<P> {
    fn log_density(&mut self, p: &[f64]) -> f64 {
        let inside = (0..p.len()).all(|i| p[i] >= self.lower[i] && p[i] <= self.upper[i]);
        if !inside || !self.problem.evaluate(p, &mut self.residuals, None) {
            return f64::NEG_INFINITY;
        }
        let objective: f64 = self.residuals.iter().map(|r| r * r).sum();
        match objective.is_finite() {
            true => self.noise.log_likelihood(objective),
            false => f64::NEG_INFINITY,
        }
    }
}

/// Samples the posterior of the problem `make()` builds (one per parallel
/// task): `parameters` every parameter of the model, `free` the indices of
/// the searched ones, `optimum` their search variables at the optimum,
/// `bounds` theirs (see the module).
pub fn posterior<P: LeastSquares>(
    make: &(dyn Fn() -> P + Sync),
    parameters: &[Parameter],
    free: &[usize],
    optimum: &[f64],
    (lower, upper): (&[f64], &[f64]),
    settings: &Settings,
) -> Result<Posterior, PosteriorError> {
    let bounds = (lower, upper);
    posterior_observed(make, parameters, (free, optimum), bounds, settings, &|| {})
}

/// [`posterior`], calling `step` after every step of the ensemble (a
/// progress bar's `inc`); `free` and `optimum` as one pair.
pub fn posterior_observed<P: LeastSquares>(
    make: &(dyn Fn() -> P + Sync),
    parameters: &[Parameter],
    (free, optimum): (&[usize], &[f64]),
    (lower, upper): (&[f64], &[f64]),
    settings: &Settings,
    step: &(dyn Fn() + Sync),
) -> Result<Posterior, PosteriorError> {
    let d = free.len();
    if d == 0 {
        return Err(PosteriorError::Nothing);
    }
    let mut ensemble = settings.ensemble;
    if ensemble.walkers == 0 {
        ensemble.walkers = (2 * d + 2).max(32).next_multiple_of(2);
    }
    let density = || Density::new(make(), settings.noise, (lower, upper));
    let starts = laplace_starts(&mut density(), optimum, settings.noise, &ensemble);
    let chain = sample_observed(&density, starts, &ensemble, step)?;
    let names: Vec<String> = free.iter().map(|&i| parameters[i].name.clone()).collect();
    let diagnostics = chain.diagnose_named(&names);
    Ok(summarise(
        &chain,
        parameters,
        free,
        optimum,
        (ensemble, diagnostics, settings),
    ))
}

/// The walkers' starts: draws of the Laplace approximation at `optimum`,
/// each pulled back towards it until it has a density.
fn laplace_starts<P: LeastSquares>(
    density: &mut Density<P>,
    optimum: &[f64],
    noise: Noise,
    ensemble: &Ensemble,
) -> Vec<Vec<f64>> {
    let spread = laplace_spread(&density.problem, optimum, noise);
    let mut draws = Draws::new(ensemble.seed, u64::MAX / 2);
    (0..ensemble.walkers)
        .map(|_| {
            let z: Vec<f64> = (0..spread.ncols()).map(|_| gaussian(&mut draws)).collect();
            let offset = &spread * nalgebra::DVector::from_vec(z);
            let mut scale = 1.0;
            for _ in 0..40 {
                let p: Vec<f64> = (0..optimum.len())
                    .map(|i| {
                        mirror(
                            optimum[i] + scale * offset[i],
                            &density.lower[i],
                            &density.upper[i],
                        )
                    })
                    .collect();
                if density.log_density(&p).is_finite() {
                    return p;
                }
                scale *= 0.5;
            }
            optimum.to_vec()
        })
        .collect()
}

/// `p` mirrored into `[lower, upper]` at the bound it crossed.
fn mirror(p: f64, lower: &f64, upper: &f64) -> f64 {
    let inside = match (p < *lower, p > *upper) {
        (true, _) => 2.0 * lower - p,
        (_, true) => 2.0 * upper - p,
        _ => p,
    };
    inside.clamp(*lower, *upper)
}

/// A standard normal draw (Box–Muller).
pub fn gaussian(draws: &mut Draws) -> f64 {
    let (a, b) = (1.0 - draws.unit(), draws.unit());
    (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
}

/// A square root L of the Laplace covariance `s² (JᵀJ)⁺` (`L Lᵀ`), each
/// direction's deviation at most 1 (a factor e of a log parameter); the
/// identity times 1e-3 when the Jacobian cannot be evaluated.
fn laplace_spread<P: LeastSquares>(problem: &P, optimum: &[f64], noise: Noise) -> DMatrix<f64> {
    let (m, d) = (problem.residual_count(), optimum.len());
    let mut r = vec![0.0; m];
    let mut jacobian = DMatrix::zeros(m, d);
    let fallback = DMatrix::identity(d, d) * 1e-3;
    if !problem.evaluate(optimum, &mut r, Some(&mut jacobian)) {
        return fallback;
    }
    let s = noise.variance(r.iter().map(|v| v * v).sum()).sqrt();
    let svd = jacobian.svd(false, true);
    let (Some(v_t), largest) = (svd.v_t.as_ref(), svd.singular_values.max()) else {
        return fallback;
    };
    if !(largest > 0.0 && largest.is_finite() && s.is_finite()) {
        return fallback;
    }
    DMatrix::from_fn(d, svd.singular_values.len(), |i, k| {
        let sigma = svd.singular_values[k].max(RANK_TOLERANCE * largest);
        v_t[(k, i)] * (s / sigma).min(1.0)
    })
}

/// The summary of `chain` (see [`Posterior`]).
fn summarise(
    chain: &Chain,
    parameters: &[Parameter],
    free: &[usize],
    optimum: &[f64],
    (ensemble, diagnostics, settings): (Ensemble, Diagnostics, &Settings),
) -> Posterior {
    let total = parameters.len();
    let mut fixed_theta: Vec<f64> = vec![f64::NAN; total];
    let fixed: Vec<bool> = (0..total).map(|i| !free.contains(&i)).collect();
    for (j, &i) in free.iter().enumerate() {
        fixed_theta[i] = parameters[i].theta(optimum[j]);
    }
    let mut post = Posterior {
        names: parameters.iter().map(|p| p.name.clone()).collect(),
        mean: fixed_theta.clone(),
        median: fixed_theta,
        sd: vec![0.0; total],
        ci90: vec![None; total],
        ci95: vec![None; total],
        fixed,
        noise: settings.noise,
        ensemble,
        diagnostics,
        draws: Vec::new(),
    };
    for (j, &i) in free.iter().enumerate() {
        let mut theta: Vec<f64> = chain
            .draws(j)
            .into_iter()
            .map(|p| parameters[i].theta(p))
            .collect();
        let mean = theta.iter().sum::<f64>() / theta.len() as f64;
        let var = theta.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / theta.len() as f64;
        theta.sort_by(f64::total_cmp);
        post.mean[i] = mean;
        post.sd[i] = var.sqrt();
        post.median[i] = quantile(&theta, 0.5);
        post.ci90[i] = Some([quantile(&theta, 0.05), quantile(&theta, 0.95)]);
        post.ci95[i] = Some([quantile(&theta, 0.025), quantile(&theta, 0.975)]);
    }
    post.draws = thinned(chain, parameters, free, &post.mean, settings.kept);
    post
}

/// At most `kept` draws of θ (every parameter; fixed ones at `values`),
/// evenly spaced over the chain.
fn thinned(
    chain: &Chain,
    parameters: &[Parameter],
    free: &[usize],
    values: &[f64],
    kept: usize,
) -> Vec<Vec<f64>> {
    let count = chain.steps * chain.walkers;
    let stride = count.div_ceil(kept.max(1)).max(1);
    (0..count)
        .step_by(stride)
        .map(|k| {
            let mut theta = values.to_vec();
            for (j, &i) in free.iter().enumerate() {
                theta[i] = parameters[i].theta(chain.values[k * chain.dimension + j]);
            }
            theta
        })
        .collect()
}

/// The q-quantile of sorted values, linear between order statistics
/// (numpy's default, Hyndman & Fan type 7).
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    match sorted.len() {
        0 => f64::NAN,
        n => {
            let h = (n - 1) as f64 * q.clamp(0.0, 1.0);
            let (below, fraction) = (h.floor() as usize, h - h.floor());
            let above = (below + 1).min(n - 1);
            sorted[below] + fraction * (sorted[above] - sorted[below])
        }
    }
}
