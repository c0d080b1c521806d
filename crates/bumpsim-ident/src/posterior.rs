//! The posterior of an identified chain's parameters (issue 39): the
//! estimation layer's ensemble sampler ([`bumpsim_estimate::posterior`],
//! Goodman & Weare 2010 as emcee runs it) on the chain's objective, in log
//! parameters within the study's bounds (a log-uniform prior), with the
//! noise model of the model choice: σ integrated out and the residuals
//! counted with their effective sample size,
//! `ln p(θ | data) = −(n_eff/2) ln F(θ)` ([`noise`]). With correlated
//! residuals (n_eff ≪ n) the posterior is as much wider than the local
//! intervals as the data are worth fewer samples.
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
//!     measured: vec![], output_dof: 1, initial_velocity: 0.0, window: (0, 299) };
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
use bumpsim_estimate::posterior::{self as layer, Density, Noise, Posterior, PosteriorError};

/// The noise model of `result`: σ integrated out, its residuals counted
/// with their effective sample size.
pub fn noise(result: &Identification) -> Noise {
    Noise::Effective(result.effective_samples.effective)
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
    let bounds = (log(&settings.bounds.lower), log(&settings.bounds.upper));
    (log(&result.model.parameters()), bounds, free)
}

/// Samples the posterior of `result`, identified from `cases` with
/// `settings` (see the module).
pub fn posterior(
    cases: &[LoadCase],
    settings: &Settings,
    result: &Identification,
    sampling: &layer::Settings,
) -> Result<Posterior, PosteriorError> {
    let make = || Objective::new(cases, settings.dof, &settings.bounds.fixed);
    let (optimum, (lower, upper), free) = problem(&make(), settings, result);
    let parameters = crate::stats::parameters(settings.dof);
    layer::posterior(
        &make,
        &parameters,
        &free,
        &optimum,
        (&lower, &upper),
        sampling,
    )
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

/// The posterior's lines of the summary: each parameter's mean and 90 %
/// interval next to its local 95 % interval, then the diagnostics and any
/// warning.
pub fn lines(post: &Posterior, result: &Identification) -> String {
    let runs = post.ensemble;
    let mut out = format!(
        "posterior ({} walkers × {} steps, {} burnt, seed {}; σ integrated out, {}): mean, 90 % interval; local 95 %\n",
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
            "  {name:<4} {:>14}  90 % {:<30} local 95 % {}\n",
            q(post.mean[i]),
            interval(post.ci90[i]),
            interval(local.get(i).copied().flatten())
        );
    }
    out + &diagnostics(post)
}

fn noise_words(noise: Noise) -> String {
    match noise {
        Noise::Effective(n) => format!("{n:.1} effective samples"),
        Noise::Known(sigma) => format!("σ = {sigma:e} m known"),
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
