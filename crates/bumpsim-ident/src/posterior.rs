//! The posterior of an identified chain's parameters (issue 39): the
//! estimation layer's ensemble sampler ([`bumpsim_estimate::posterior`],
//! Goodman & Weare 2010 as emcee runs it) on the chain's objective, in log
//! parameters within the study's bounds, each side closed at a factor
//! [`PRIOR_SPAN`] from the optimum (a proper log-uniform prior). Its
//! likelihood ([`noise`]) is the identification's own: with intervals from
//! the integrated noise's random walk, the residuals whitened by that
//! covariance ([`crate::whitened`], `ln p = −½ ‖m(θ)‖²`); otherwise the
//! noise model of the model choice, σ integrated out and the residuals
//! counted with their effective sample size,
//! `ln p(θ | data) = −(n_eff/2) ln F(θ)`. The identification's stated
//! priors ([`crate::priors`]) add `−z²/2` each (the whitening then uses the
//! data's covariance without them, [`crate::whitened::transform`]).
//!
//! The walkers start at the optimum's local (Laplace) approximation, so
//! the run explores the basin the multi-start found; its diagnostics
//! (integrated autocorrelation time, split-R̂) say whether it has
//! converged, and [`lines`] prints the posterior next to the local
//! intervals.
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! use bumpsim_ident::{LoadCase, Settings, identify};
//! use bumpsim_ident::posterior::{posterior, sampling};
//! let truth = MsdModel::new(vec![30.0, 900.0], vec![3e3], vec![6e5]).unwrap();
//! let force: Vec<f64> = (0..300).map(|k| 2e4 * (k as f64 * 5e-4 * 40.0).sin().max(0.0)).collect();
//! let mut case = LoadCase { name: "flat".into(), start: 0.0, step: 5e-4, force,
//!     measured: vec![], output_dof: 1, initial_velocity: 0.0, window: (0, 299),
//!     compare: Default::default() };
//! case.measured = case.simulate(&truth).unwrap();
//! for (k, x) in case.measured.iter_mut().enumerate() { *x += 2e-5 * (k as f64 * 1.7).sin(); }
//! let settings = Settings::new(2, 4);
//! let result = identify(&[case.clone()], &settings, &|| {}).unwrap();
//! let mut run = sampling(&result, 1);
//! run.ensemble.steps = 400;
//! run.ensemble.burn = 100;
//! let post = posterior(&[case], &settings, &result, &run).unwrap();
//! let [low, high] = post.ci90[3].unwrap();
//! assert!(low < 6e5 && 6e5 < high, "k1 in {low} .. {high} N/m");
//! ```

use crate::case::{LoadCase, Objective};
use crate::result::Identification;
use crate::settings::Settings;
use bumpsim_core::model::parameter_kind;
use bumpsim_core::units::format_quantity;
use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::posterior::{self as layer, Density};
pub use bumpsim_estimate::posterior::{Noise, Posterior, PosteriorError, quantile};
use bumpsim_estimate::prior::{Prior, Priored};
pub use bumpsim_estimate::sampler::{Diagnostics, Ensemble};
use serde::Serialize;

/// The prior is closed at this factor from the optimum on each side,
/// within the study's bounds: an open bound (the default upper bound is
/// infinite) leaves a log-uniform prior improper, and with few effective
/// samples the walkers then drift off to 1e12 kg.
pub const PRIOR_SPAN: f64 = 1e3;

/// Steps of a run when none are asked (a quarter of them burnt).
pub const STEPS: usize = 4000;
/// The most walkers of a run (resource limit, docs/limits.md).
pub const MAX_WALKERS: usize = 10_000;
/// The most steps of a run (resource limit, docs/limits.md).
pub const MAX_STEPS: usize = 1_000_000;
/// The most draws (walkers × steps) of a run: its chain is held in memory,
/// 8 bytes a parameter a draw (resource limit, docs/limits.md).
pub const MAX_DRAWS: usize = 4_000_000;
/// The fewest steps of a run: a shorter chain says nothing of convergence.
pub const MIN_STEPS: usize = 10;

/// What a front end asks of a posterior run (`None`: the default).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request {
    /// Walkers (default: the larger of 32 and 2 q + 2, q free parameters).
    pub walkers: Option<usize>,
    /// Steps, a quarter of them burnt (default [`STEPS`]).
    pub steps: Option<usize>,
    /// Seed of the random stream.
    pub seed: u64,
}

/// Why a posterior run cannot be made as asked, or could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SamplingError {
    /// A setting of the run (`walkers`, `steps`) out of its range.
    #[error("{setting}: {reason}")]
    Setting {
        /// The setting.
        setting: &'static str,
        /// Why, with the range.
        reason: String,
    },
    /// The sampler could not run.
    #[error(transparent)]
    Posterior(#[from] PosteriorError),
}

impl Request {
    /// The run this request makes for a chain identified with `settings`,
    /// or which setting is out of its range.
    pub fn ensemble(&self, settings: &Settings) -> Result<Ensemble, SamplingError> {
        let free = settings.bounds.fixed.iter().filter(|f| f.is_none()).count();
        let needed = 2 * free + 2;
        let walkers = self.walkers.unwrap_or(needed.max(32));
        let steps = self.steps.unwrap_or(STEPS);
        let setting = |setting, reason| Err(SamplingError::Setting { setting, reason });
        if !walkers.is_multiple_of(2) || walkers < needed || walkers > MAX_WALKERS {
            return setting(
                "walkers",
                format!(
                    "{walkers}: the ensemble sampler needs an even number of walkers from 2 q + 2 = {needed} ({free} free parameters of {} masses) to {MAX_WALKERS}",
                    settings.dof
                ),
            );
        }
        if !(MIN_STEPS..=MAX_STEPS).contains(&steps) {
            return setting(
                "steps",
                format!("{steps}: expected {MIN_STEPS} to {MAX_STEPS} steps"),
            );
        }
        if walkers * steps > MAX_DRAWS {
            return setting(
                "steps",
                format!(
                    "{steps} steps of {walkers} walkers are {} draws: at most {MAX_DRAWS} (the chain is held in memory)",
                    walkers * steps
                ),
            );
        }
        Ok(Ensemble {
            walkers,
            steps,
            burn: steps / 4,
            seed: self.seed,
        })
    }
}

/// Samples the posterior of `result` as `request` asks (its noise model
/// from `result`, [`noise`]), calling `step` after every step (a progress
/// bar's `inc`).
pub fn run(
    cases: &[LoadCase],
    settings: &Settings,
    result: &Identification,
    request: &Request,
    step: &(dyn Fn() + Sync),
) -> Result<Posterior, SamplingError> {
    let ensemble = request.ensemble(settings)?;
    let sampling = layer::Settings {
        ensemble,
        ..sampling(result, request.seed)
    };
    Ok(sample(cases, settings, result, &sampling, step)?)
}

/// The posterior as a front end's JSON carries it: what [`Posterior`]
/// holds but its draws, with each parameter's unit (SI), the optimum and
/// its local 95 % interval beside it. Vectors are in the model's
/// parameter order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary<'a> {
    /// Number of masses.
    pub dof: usize,
    /// Parameter names.
    pub names: &'a [String],
    /// SI unit of each parameter (`kg`, `N·s/m`, `N/m`).
    pub units: Vec<&'static str>,
    /// Posterior means, SI.
    pub mean: &'a [f64],
    /// Posterior medians, SI.
    pub median: &'a [f64],
    /// Posterior standard deviations, SI.
    pub sd: &'a [f64],
    /// Equal-tailed 90 % intervals, SI (`null` for a fixed parameter).
    pub ci90: &'a [Option<[f64; 2]>],
    /// Equal-tailed 95 % intervals, SI.
    pub ci95: &'a [Option<[f64; 2]>],
    /// Parameters held fixed.
    pub fixed: &'a [bool],
    /// The optimum (the identified model), SI.
    pub optimum: Vec<f64>,
    /// Its local 95 % intervals (the parameter table's), SI.
    pub local_ci95: &'a [Option<[f64; 2]>],
    /// The likelihood's error model.
    pub noise: Noise,
    /// The run: walkers, steps, burnt steps, seed.
    pub ensemble: Ensemble,
    /// Its diagnostics (free parameters, in order).
    pub diagnostics: &'a Diagnostics,
    /// Whether the run has converged (the diagnostics' verdict).
    pub converged: bool,
}

impl<'a> Summary<'a> {
    /// The summary of `post`, sampled around `result`.
    pub fn new(post: &'a Posterior, result: &'a Identification) -> Summary<'a> {
        Summary {
            dof: result.dof,
            names: &post.names,
            units: (0..post.names.len())
                .map(|i| parameter_kind(result.dof, i).0.dimension().si_symbol())
                .collect(),
            mean: &post.mean,
            median: &post.median,
            sd: &post.sd,
            ci90: &post.ci90,
            ci95: &post.ci95,
            fixed: &post.fixed,
            optimum: result.model.parameters(),
            local_ci95: &result.uncertainty.ci95,
            noise: post.noise,
            ensemble: post.ensemble,
            diagnostics: &post.diagnostics,
            converged: post.diagnostics.converged,
        }
    }
}

/// The noise model of `result`: whitened by its random-walk covariance
/// when its intervals come from one and every free parameter has a
/// standard error, else σ integrated out and its residuals counted with
/// their effective sample size.
pub fn noise(result: &Identification) -> Noise {
    let whitened = result.uncertainty.error_model
        == bumpsim_estimate::uncertainty::Correlation::RandomWalk
        && (0..result.uncertainty.names.len()).all(|i| {
            result.uncertainty.fixed[i] || result.uncertainty.standard_errors[i].is_some()
        });
    match whitened {
        true => Noise::Whitened,
        false => Noise::Effective(result.effective_samples.effective),
    }
}

/// The layer's default run (4000 steps, 1000 burnt, 32 walkers at least)
/// with `result`'s noise model and `seed`.
pub fn sampling(result: &Identification, seed: u64) -> layer::Settings {
    layer::Settings::new(noise(result), seed)
}

/// The search variables of `result` (free log parameters), their log
/// bounds and the free parameters' indices.
type Problem = (Vec<f64>, (Vec<f64>, Vec<f64>), Vec<usize>);

fn problem(objective: &Objective, settings: &Settings, result: &Identification) -> Problem {
    let free = objective.free().to_vec();
    let log = |v: &[f64]| -> Vec<f64> { free.iter().map(|&i| v[i].ln()).collect() };
    let optimum = log(&result.model.parameters());
    let span = PRIOR_SPAN.ln();
    let close = |bound: Vec<f64>, side: f64| -> Vec<f64> {
        let edge = |(b, p): (f64, &f64)| match side > 0.0 {
            true => b.min(p + span),
            false => b.max(p - span),
        };
        bound.into_iter().zip(&optimum).map(edge).collect()
    };
    let lower = close(log(&settings.bounds.lower), -1.0);
    let upper = close(log(&settings.bounds.upper), 1.0);
    (optimum, (lower, upper), free)
}

/// Samples the posterior of `result`, identified from `cases` with
/// `settings` (see the module).
pub fn posterior(
    cases: &[LoadCase],
    settings: &Settings,
    result: &Identification,
    sampling: &layer::Settings,
) -> Result<Posterior, PosteriorError> {
    sample(cases, settings, result, sampling, &|| {})
}

/// [`posterior`] calling `step` after every step: over the whitened
/// moments ([`crate::whitened`]) when `sampling` asks for
/// [`Noise::Whitened`] and the identification has a covariance of every
/// free parameter, else over the residuals with their effective sample
/// size.
fn sample(
    cases: &[LoadCase],
    settings: &Settings,
    result: &Identification,
    sampling: &layer::Settings,
    step: &(dyn Fn() + Sync),
) -> Result<Posterior, PosteriorError> {
    let make = || Objective::new(cases, settings.dof, &settings.bounds.fixed);
    let (optimum, (lower, upper), free) = problem(&make(), settings, result);
    let parameters = crate::stats::parameters(settings.dof);
    let bounds = (lower.as_slice(), upper.as_slice());
    let at = (free.as_slice(), optimum.as_slice());
    let transform = (sampling.noise == Noise::Whitened)
        .then(|| crate::whitened::transform(&make(), result, &optimum))
        .flatten();
    let stated = &result.stated;
    match transform {
        Some(t) => {
            let make = || {
                let moments = crate::whitened::Whitened::new(make(), &t);
                with_stated(moments, stated, 1.0, &|| {
                    crate::whitened::Whitened::new(make(), &t)
                })
            };
            layer::posterior_observed(&make, &parameters, at, bounds, sampling, step)
        }
        None => {
            let mut effective = *sampling;
            if effective.noise == Noise::Whitened {
                effective.noise = Noise::Effective(result.effective_samples.effective);
            }
            // −(n_eff/2) ln(F + σ² Σ z²) ≈ const − Σ z²/2 near the optimum
            let sigma = match effective.noise {
                Noise::Effective(n) => (result.objective / n).sqrt(),
                Noise::Known(sigma) => sigma,
                Noise::Whitened => 1.0,
            };
            let make = || with_stated(make(), stated, sigma, &make);
            layer::posterior_observed(&make, &parameters, at, bounds, &effective, step)
        }
    }
}

/// `inner` with the stated priors weighed at `noise` (`again` makes
/// another `inner` for the problem without them when they cannot be
/// used: a noise that is not positive).
fn with_stated<P: LeastSquares>(
    inner: P,
    stated: &[Prior],
    noise: f64,
    again: &dyn Fn() -> P,
) -> Priored<P> {
    Priored::new(inner, stated.to_vec(), noise).unwrap_or_else(|_| Priored::none(again()))
}

/// The log posterior density the sampler runs on, over the free log
/// parameters of `result` (for another sampler on the same density), and
/// the optimum's free log parameters.
pub fn density<'a>(
    cases: &'a [LoadCase],
    settings: &Settings,
    result: &Identification,
) -> (Density<Objective<'a>>, Vec<f64>) {
    let objective = Objective::new(cases, settings.dof, &settings.bounds.fixed);
    let (optimum, (lower, upper), _) = problem(&objective, settings, result);
    let density = Density::new(objective, noise(result), (&lower, &upper));
    (density, optimum)
}

/// The posterior's lines of the summary: each parameter's median with its
/// 90 % and 95 % intervals next to its local 95 % interval, then the
/// diagnostics and any warning. The median, not the mean, is the estimate:
/// it always lies inside the intervals (a skewed posterior printed a mean of
/// 110 Ns/mm beside its 90 % interval 0.026 .. 86.8 Ns/mm); the mean stays
/// in the JSON.
pub fn lines(post: &Posterior, result: &Identification) -> String {
    let runs = post.ensemble;
    let mut out = format!(
        "posterior ({} walkers × {} steps, {} burnt, seed {}; {}): median, 90 % and 95 % intervals; local 95 %\n",
        runs.walkers,
        runs.steps,
        runs.burn,
        runs.seed,
        noise_words(post.noise)
    );
    let local = &result.uncertainty.ci95;
    for (i, name) in post.names.iter().enumerate() {
        let unit = parameter_kind(result.dof, i).0.dimension();
        let q = |v: f64| format_quantity(v, unit);
        let interval =
            |c: Option<[f64; 2]>| c.map_or("-".into(), |[a, b]| format!("{} .. {}", q(a), q(b)));
        out += &format!(
            "  {name:<4} {:>14}  90 % {:<30} 95 % {:<30} local 95 % {}\n",
            q(post.median[i]),
            interval(post.ci90[i]),
            interval(post.ci95[i]),
            interval(local.get(i).copied().flatten())
        );
    }
    out + &diagnostics(post)
}

fn noise_words(noise: Noise) -> String {
    match noise {
        Noise::Effective(n) => format!("σ integrated out, {n:.1} effective samples"),
        Noise::Known(sigma) => format!("σ = {sigma:e} m known"),
        Noise::Whitened => "residuals whitened by the intervals' random-walk covariance".into(),
    }
}

/// The diagnostics line and the warnings.
fn diagnostics(post: &Posterior) -> String {
    let d = &post.diagnostics;
    let worst = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
    let mut out = format!(
        "  diagnostics: acceptance {:.2}, largest autocorrelation time {:.0} steps, smallest effective draws {:.0}, largest split-R̂ {:.3}: {}\n",
        d.acceptance,
        worst(&d.autocorrelation_time),
        d.effective_draws.iter().copied().fold(f64::NAN, f64::min),
        worst(&d.r_hat),
        if d.converged {
            "converged"
        } else {
            "NOT converged"
        }
    );
    for w in &d.warnings {
        out += &format!("warning: {w}\n");
    }
    out
}
