//! Multi-start bounded identification of one model from several load cases.
//!
//! Parameters are estimated as `p = ln θ` (kg, N·s/m and N/m spanning seven
//! decades become comparable) with [`lm`] within the bounds
//! (thesis: every parameter ≥ 1 SI). Starts (the user's, the data-derived
//! [`data_start`], continuation starts from a smaller model, random ones)
//! are [`crate::search`]'s. Starts run in
//! parallel (rayon); a start whose model cannot be simulated is counted as
//! failed, never propagated.

use crate::case::{CaseError, LoadCase, Objective, VALID_RANGE};
use crate::lm::{self, LeastSquares, Outcome, Stop};
use crate::polish::{REFINE_FTOL, SCREEN_FTOL, candidates, polish};
use crate::search::{
    Fate, Goal, ROUND, Run, around, exploring, representative, staged, starting_points,
};
use crate::stats::{Uncertainty, uncertainty};
use bumpsim_core::model::{MsdModel, ParameterKind, parameter_count, parameter_kind};
use serde::Serialize;
use std::time::Instant;

/// Why identification cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IdentError {
    /// A load case is unusable.
    #[error(transparent)]
    Case(#[from] CaseError),
    /// A setting is out of range.
    #[error("identification setting {name}: {reason}")]
    Setting {
        /// The setting.
        name: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// The best start's parameters do not make a model (cannot happen within
    /// the bounds; checked so that no invalid model is returned).
    #[error("the best parameters {theta:?} (SI) do not make a valid model")]
    Parameters {
        /// The parameters, SI, thesis order.
        theta: Vec<f64>,
    },
    /// Every start failed.
    #[error("all {starts} starts failed: the model could not be simulated from any of them")]
    AllFailed {
        /// Number of starts.
        starts: usize,
    },
}

/// Bounds and fixed values per parameter, SI, thesis order `[m.., c.., k..]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Bounds {
    /// Lower bounds (> 0).
    pub lower: Vec<f64>,
    /// Upper bounds (may be infinite).
    pub upper: Vec<f64>,
    /// Fixed values (not estimated).
    pub fixed: Vec<Option<f64>>,
}

/// Whether `[lower, upper]` (SI) bounds a parameter the search can use:
/// the lower bound within [`VALID_RANGE`] below its ceiling, the upper one
/// above it (it may be infinite). The one rule for settings and studies.
pub fn usable_bounds(lower: f64, upper: f64) -> bool {
    let (floor, ceiling) = (*VALID_RANGE.start(), *VALID_RANGE.end());
    lower >= floor && lower < ceiling && upper > lower
}

/// Whether `value` (SI) can be a fixed parameter: finite and positive (one
/// beyond [`VALID_RANGE`] is not simulable, which every start then reports).
pub fn usable_fixed(value: f64) -> bool {
    value.is_finite() && value > 0.0
}

impl Bounds {
    /// Every parameter in `[lower, ∞)`, none fixed (the thesis: `lower` = 1).
    pub fn uniform(dof: usize, lower: f64) -> Bounds {
        let p = parameter_count(dof);
        Bounds {
            lower: vec![lower; p],
            upper: vec![f64::INFINITY; p],
            fixed: vec![None; p],
        }
    }

    fn check(&self, dof: usize) -> Result<(), IdentError> {
        let p = parameter_count(dof);
        let setting = |reason: String| IdentError::Setting {
            name: "bounds",
            reason,
        };
        if self.lower.len() != p || self.upper.len() != p || self.fixed.len() != p {
            return Err(setting(format!("{p} parameters for {dof} DOF")));
        }
        for i in 0..p {
            let (lo, hi) = (self.lower[i], self.upper[i]);
            let (floor, ceiling) = (*VALID_RANGE.start(), *VALID_RANGE.end());
            if !usable_bounds(lo, hi) {
                let name = bumpsim_core::model::parameter_name(dof, i);
                let unit = parameter_kind(dof, i).0.unit();
                return Err(setting(format!(
                    "{name}: need {floor:e} {unit} <= lower < upper with lower below {ceiling:e} {unit}, got [{lo}, {hi}] {unit}"
                )));
            }
            if let Some(v) = self.fixed[i].filter(|v| !usable_fixed(*v)) {
                let name = bumpsim_core::model::parameter_name(dof, i);
                let unit = parameter_kind(dof, i).0.unit();
                return Err(IdentError::Setting {
                    name: "fixed",
                    reason: format!(
                        "{name} = {v} {unit}: a fixed value must be finite and positive"
                    ),
                });
            }
        }
        Ok(())
    }
}

/// What to estimate and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Number of masses.
    pub dof: usize,
    /// Bounds and fixed values.
    pub bounds: Bounds,
    /// Number of starts (≥ 1).
    pub starts: usize,
    /// Seed of the random starts.
    pub seed: u64,
    /// The user's start, SI, thesis order.
    pub start: Option<Vec<f64>>,
    /// Further given starts (e.g. [`Settings::continue_from`]), SI, thesis
    /// order; they replace random starts, the total stays `starts`.
    pub seeds: Vec<Vec<f64>>,
    /// For each seed (by index; missing: none), the link (0-based) that
    /// joins the two halves of a mass split by [`Settings::continue_from`]:
    /// random starts around that seed draw this link over its whole range
    /// ([`crate::search`]).
    pub split_links: Vec<Option<usize>>,
    /// Solver tolerances.
    pub solver: lm::Settings,
}

impl Settings {
    /// Thesis defaults: every parameter ≥ 1, `starts` starts, seed 1.
    pub fn new(dof: usize, starts: usize) -> Settings {
        Settings {
            dof,
            bounds: Bounds::uniform(dof, 1.0),
            starts,
            seed: 1,
            start: None,
            seeds: Vec::new(),
            split_links: Vec::new(),
            solver: lm::Settings::default(),
        }
    }

    /// Adds the continuation starts from the optimum of the model with one
    /// mass fewer ([`crate::search::continuation_starts`]); any other
    /// `previous` adds nothing.
    pub fn continue_from(&mut self, previous: &MsdModel) {
        if previous.dof() + 1 == self.dof {
            self.seeds = crate::search::continuation_starts(previous);
            // seed j splits mass j: link j joins the halves
            self.split_links = (0..self.seeds.len()).map(Some).collect();
        }
    }
}

/// Fit of one load case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseFit {
    /// Case name.
    pub name: String,
    /// Sum of squared errors in the window, m².
    pub sse: f64,
    /// `100 (1 − ‖y − ŷ‖ / ‖y − ȳ‖)`, %.
    pub fit_percent: f64,
    /// Samples in the window.
    pub samples: usize,
}

/// Start statistics.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Starts {
    /// Starts run.
    pub total: usize,
    /// Starts whose run converged.
    pub converged: usize,
    /// Starts that could not be evaluated or ended non-finite.
    pub failed: usize,
    /// Starts that reached the best objective (within 1e-6 relative): by
    /// their own run, or merged into a start that did.
    pub reached_best: usize,
    /// Starts that reached the best objective by their own (polished) run;
    /// the others of `reached_best` merged into one of these.
    pub reached_best_alone: usize,
    /// Starts that reached the best *fit*: their run (polished or only
    /// screened), or the run they merged into, ended within one noise
    /// variance of the best objective, `F ≤ F_best (1 + 1/(n − q))`. The
    /// data cannot tell such a fit from the best (its likelihood-ratio
    /// statistic `n ln(F/F_best)` is about 1, where a 5 % test needs 3.84);
    /// in a flat valley (a sloppy 5-DOF model) starts stop at objectives
    /// that differ in the fourth digit, which the 1e-6 count calls misses.
    pub reached_best_fit: usize,
    /// Starts of `reached_best_fit` that got there by their own run.
    pub reached_best_fit_alone: usize,
    /// Starts abandoned at a stage end, too far above the incumbent
    /// ([`crate::search::STAGES`]).
    pub abandoned: usize,
    /// Starts merged into a better start next to them
    /// ([`crate::search::MERGE_DISTANCE`], [`crate::polish::CLUSTER_DISTANCE`]).
    pub merged: usize,
    /// Starts whose screened optimum was too far above the best to be
    /// polished ([`crate::polish`]).
    pub unpolished: usize,
    /// Starts drawn around the best screened optimum of the others (the
    /// search's second level, [`crate::search::REFINED`]); they are among
    /// `total`.
    pub refined: usize,
    /// Exploring starts (those not drawn around the best, `total −
    /// refined`) that reached the best fit by their own run or by the run
    /// they merged into: how many independent draws found the best basin.
    /// One means the best was found by a single start.
    pub explored_best_fit: usize,
    /// Index of the best start (0 = the user's or the data start).
    pub best: usize,
}

/// The identified model and everything said about it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Identification {
    /// Number of masses.
    pub dof: usize,
    /// The identified model; serialised as its `masses` (kg), `dampers`
    /// (N·s/m) and `springs` (N/m) at the top level of the result.
    #[serde(flatten)]
    pub model: MsdModel,
    /// `F = Σ (x − x̂)²` over all cases, m².
    pub objective: f64,
    /// Per-case fit.
    pub cases: Vec<CaseFit>,
    /// Overall fit %, from all windows together.
    pub fit_percent: f64,
    /// Akaike information criterion `n ln(F/n) + 2q`.
    pub aic: f64,
    /// Bayesian information criterion `n ln(F/n) + q ln n`.
    pub bic: f64,
    /// Residuals n.
    pub residuals: usize,
    /// Uncertainty of the estimate.
    pub uncertainty: Uncertainty,
    /// Starts.
    pub starts: Starts,
    /// Solver iterations of the best start (screening and polishing).
    pub iterations: usize,
    /// Where the best start began, SI, thesis order (free and fixed
    /// parameters): the user's, the data-derived, a continuation or a
    /// random start.
    pub start: Vec<f64>,
    /// Why the best start stopped.
    pub stop: Stop,
    /// Wall-clock time, s.
    pub run_time: f64,
    /// Warnings for the user.
    pub warnings: Vec<String>,
    /// A simpler model that fits as well, when a spring is undetermined
    /// ([`crate::reduce`]).
    pub reduction: Option<crate::reduce::Reduction>,
}

impl Identification {
    /// The identified model.
    pub fn model(&self) -> &MsdModel {
        &self.model
    }
}

/// A start derived from the data: the total mass from impulse and velocity
/// change of the output, `M = |∫F dt / Δv|`, split equally; one spring
/// stiffness from the window length `D` taken as a half period,
/// `k_eff = M π² / D²`, `k_i = (N − 1) k_eff` (springs in series); dampers at
/// 30 % of critical for `k_i` and `M/N`.
pub fn data_start(cases: &[LoadCase], dof: usize) -> Vec<f64> {
    let estimates: Vec<(f64, f64)> = cases.iter().filter_map(case_estimate).collect();
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied()
    };
    let mass = median(estimates.iter().map(|e| e.0).collect()).unwrap_or(1000.0);
    let duration = median(estimates.iter().map(|e| e.1).collect()).unwrap_or(0.05);
    let k_eff = mass * std::f64::consts::PI.powi(2) / duration.powi(2);
    let spring = k_eff * (dof.max(2) - 1) as f64;
    let damper = 2.0 * 0.3 * (spring * mass / dof as f64).sqrt();
    (0..parameter_count(dof))
        .map(|i| match parameter_kind(dof, i).0 {
            ParameterKind::Mass => mass / dof as f64,
            ParameterKind::Damper => damper,
            ParameterKind::Spring => spring,
        })
        .collect()
}

/// Mass and window duration of one case, when they can be estimated.
fn case_estimate(case: &LoadCase) -> Option<(f64, f64)> {
    let (a, b) = case.window;
    let impulse = bumpsim_core::series::trapezoid(&case.force[a..=b], case.step);
    let tail = ((b - a) / 20).max(1);
    let velocity =
        |k: usize| (case.measured[k] - case.measured[k - tail]) / (tail as f64 * case.step);
    let end_velocity = if b >= a + tail {
        velocity(b)
    } else {
        return None;
    };
    let start_velocity = if a >= tail {
        velocity(a)
    } else {
        case.initial_velocity
    };
    let mass = (impulse / (end_velocity - start_velocity)).abs();
    let duration = (b - a) as f64 * case.step;
    (mass.is_finite() && mass > 0.0 && duration > 0.0).then_some((mass, duration))
}

/// Largest model identified (memory and time grow with the cube of the DOF).
pub const MAX_DOF: usize = 50;
/// Most starts of one identification.
pub const MAX_STARTS: usize = 100_000;

fn check(cases: &[LoadCase], settings: &Settings) -> Result<(), IdentError> {
    let setting = |name, reason: String| Err(IdentError::Setting { name, reason });
    if settings.dof > MAX_DOF {
        return setting(
            "dof",
            format!("{} masses: at most {MAX_DOF} (limit MAX_DOF)", settings.dof),
        );
    }
    if settings.starts > MAX_STARTS {
        return setting(
            "starts",
            format!(
                "{} starts: at most {MAX_STARTS} (limit MAX_STARTS)",
                settings.starts
            ),
        );
    }
    if settings.dof == 0 || settings.starts == 0 || cases.is_empty() {
        return setting(
            "dof/starts/cases",
            "need at least one DOF, one start and one load case".into(),
        );
    }
    for case in cases {
        case.validate()?;
        if case.output_dof > settings.dof {
            return setting(
                "output_dof",
                format!(
                    "case '{}' measures DOF {} of a {}-DOF model",
                    case.name, case.output_dof, settings.dof
                ),
            );
        }
    }
    let p = parameter_count(settings.dof);
    if let Some(start) = &settings.start {
        if start.len() != p {
            let reason = format!("{p} positive values expected for {} DOF", settings.dof);
            return setting("start", reason);
        }
        if let Some(i) = start.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
            let name = bumpsim_core::model::parameter_name(settings.dof, i);
            let unit = parameter_kind(settings.dof, i).0.unit();
            let reason = format!(
                "{name} = {} {unit}: start values must be finite and positive",
                start[i]
            );
            return setting("start", reason);
        }
    }
    if let Some(bad) = settings
        .seeds
        .iter()
        .position(|s| s.len() != p || s.iter().any(|v| !(v.is_finite() && *v > 0.0)))
    {
        return setting(
            "seeds",
            format!("seed start {}: {p} positive values expected", bad + 1),
        );
    }
    settings.bounds.check(settings.dof)?;
    if settings.bounds.fixed.iter().take(p).all(Option::is_some) {
        return setting(
            "fixed",
            format!(
                "every parameter of the {}-DOF model is fixed: nothing is left to identify (`bumpsim predict` evaluates a given model)",
                settings.dof
            ),
        );
    }
    Ok(())
}

/// The outcome of the best finished run with a finite objective.
fn best_run(runs: &[Run]) -> Option<Outcome> {
    runs.iter()
        .filter(|r| r.fate == Fate::Finished && r.outcome.objective.is_finite())
        .map(|r| &r.outcome)
        .min_by(|a, b| a.objective.total_cmp(&b.objective))
        .cloned()
}

/// The start statistics of staged runs; an error when every start failed.
/// `freedom` is n − q (residuals less free parameters): one noise variance
/// of the best fit is `F_best / freedom`.
/// The warning when at most one exploring start found the best fit: the
/// starts drawn around the best refine its basin and do not confirm that
/// no better one exists.
fn single_start_warning(starts: &Starts) -> Option<String> {
    let exploring = starts.total - starts.refined;
    if exploring < 2 || starts.explored_best_fit > 1 {
        return None;
    }
    let around = match starts.refined {
        0 => String::new(),
        n => format!(
            " ({n} more drawn around the best refine its basin but do not search elsewhere)"
        ),
    };
    Some(format!(
        "{} of the {exploring} exploring starts came within the noise of the best objective{around}: a better minimum may exist; raise the number of starts",
        starts.explored_best_fit
    ))
}

/// `exploring`: how many of `runs` (the first ones) explored; the rest were
/// drawn around the best so far.
pub(crate) fn tally(runs: &[Run], freedom: usize, exploring: usize) -> Result<Starts, IdentError> {
    let failed = runs
        .iter()
        .filter(|r| !r.outcome.objective.is_finite())
        .count();
    let (best, outcome) = runs
        .iter()
        .enumerate()
        .filter(|(_, r)| r.fate == Fate::Finished && r.outcome.objective.is_finite())
        .map(|(i, r)| (i, &r.outcome))
        .min_by(|a, b| a.1.objective.total_cmp(&b.1.objective))
        .ok_or(IdentError::AllFailed { starts: runs.len() })?;
    let exact = outcome.objective * (1.0 + 1e-6) + 1e-300;
    let noise = outcome.objective * (1.0 + 1.0 / freedom.max(1) as f64) + 1e-300;
    // a run that ended below `bar` by itself: polished, or a screened
    // optimum left unpolished (for the noise bar only: the exact bar asks
    // for the thesis's tolerances)
    let own = |i: usize, bar: f64, screened: bool| {
        let ended =
            runs[i].fate == Fate::Finished || (screened && runs[i].fate == Fate::Unpolished);
        ended && runs[i].outcome.objective <= bar
    };
    let reached = |i: usize, bar: f64, screened: bool| own(representative(runs, i), bar, screened);
    let count = |bar: f64, screened: bool| {
        let alone = (0..runs.len()).filter(|&i| own(i, bar, screened)).count();
        let all = (0..runs.len())
            .filter(|&i| reached(i, bar, screened))
            .count();
        (all, alone)
    };
    let exploring = exploring.min(runs.len());
    let ((reached_best, reached_best_alone), (reached_best_fit, reached_best_fit_alone)) =
        (count(exact, false), count(noise, true));
    let fate = |f: fn(&Fate) -> bool| runs.iter().filter(|r| f(&r.fate)).count();
    Ok(Starts {
        total: runs.len(),
        converged: runs
            .iter()
            .filter(|r| r.outcome.objective.is_finite() && r.outcome.stop.converged())
            .count(),
        failed,
        reached_best,
        reached_best_alone,
        reached_best_fit,
        reached_best_fit_alone,
        abandoned: fate(|f| *f == Fate::Abandoned),
        merged: fate(|f| matches!(f, Fate::Merged(_))),
        unpolished: fate(|f| *f == Fate::Unpolished),
        refined: runs.len() - exploring,
        explored_best_fit: (0..exploring).filter(|&i| reached(i, noise, true)).count(),
        best,
    })
}

/// Identifies a `settings.dof`-mass model from `cases`, with the reduced
/// model that fits as well when a spring is undetermined
/// ([`crate::reduce`]). `progress` is called once per finished start (from
/// any thread).
pub fn identify(
    cases: &[LoadCase],
    settings: &Settings,
    progress: &(dyn Fn() + Sync),
) -> Result<Identification, IdentError> {
    let mut result = identify_only(cases, settings, progress)?;
    result.reduction = crate::reduce::suggest(cases, &result, settings);
    if let Some(r) = &result.reduction {
        result.warnings.push(r.statement.clone());
    }
    Ok(result)
}

/// [`identify`] without looking for a reduced model.
fn identify_only(
    cases: &[LoadCase],
    settings: &Settings,
    progress: &(dyn Fn() + Sync),
) -> Result<Identification, IdentError> {
    check(cases, settings)?;
    let clock = Instant::now();
    let objective = Objective::new(cases, settings.dof, &settings.bounds.fixed);
    let free = objective.free().to_vec();
    let lower: Vec<f64> = free
        .iter()
        .map(|&i| settings.bounds.lower[i].ln())
        .collect();
    let upper: Vec<f64> = free
        .iter()
        .map(|&i| settings.bounds.upper[i].ln())
        .collect();
    let data = data_start(cases, settings.dof);
    let fixed = (&settings.start, data.as_slice(), settings.seeds.as_slice());
    let given = usize::from(settings.start.is_some()) + 1 + settings.seeds.len();
    let first = exploring(settings.starts, given);
    let mut points = starting_points(first, settings.seed, fixed, &settings.split_links, &free);
    let solve = |start: &[f64], iterations: usize, ftol: f64| {
        let objective = Objective::new(cases, settings.dof, &settings.bounds.fixed);
        let solver = lm::Settings {
            max_iterations: iterations,
            ftol,
            ..settings.solver
        };
        lm::minimise(&objective, start, &lower, &upper, &solver)
    };
    let (limit, ftol) = (settings.solver.max_iterations, settings.solver.ftol);
    let screen = |p: &[f64], n| solve(p, n, ftol.max(SCREEN_FTOL));
    let freedom = objective.residual_count().saturating_sub(free.len());
    // a run is raced for the best fit: within one noise variance of the best
    let goal = Goal {
        iterations: limit,
        target: f64::INFINITY,
        within: 1.0 / freedom.max(1) as f64,
    };
    let mut runs = staged(&points, goal, &screen, progress);
    let mut refined = settings.starts.max(1) - points.len();
    // the second level, in rounds: around the best screened optimum so far,
    // each start raced for its fit
    while let Some(best) = best_run(&runs).filter(|_| refined > 0) {
        let round = refined.min(ROUND);
        let more = around(&best.parameters, round, settings.seed, points.len());
        let within = Goal {
            target: best.objective * (1.0 + goal.within),
            ..goal
        };
        let offset = runs.len();
        let refine = |p: &[f64], n| solve(p, n, ftol.max(REFINE_FTOL));
        runs.extend(
            staged(&more, within, &refine, progress)
                .into_iter()
                .map(|mut run| {
                    if let Fate::Merged(j) = run.fate {
                        run.fate = Fate::Merged(j + offset);
                    }
                    run
                }),
        );
        points.extend(more);
        refined -= round;
    }
    let chosen = candidates(&mut runs);
    polish(&mut runs, &chosen, goal, &|p, n| solve(p, n, ftol));
    let starts = tally(&runs, freedom, first)?;
    let outcome = &runs[starts.best].outcome;
    let mut result = summarise(
        cases, settings, &objective, outcome, starts, &lower, &upper, clock,
    )?;
    result.start = objective.theta(&points[starts.best]);
    Ok(result)
}

#[allow(clippy::too_many_arguments)]
fn summarise(
    cases: &[LoadCase],
    settings: &Settings,
    objective: &Objective,
    outcome: &Outcome,
    starts: Starts,
    lower: &[f64],
    upper: &[f64],
    clock: Instant,
) -> Result<Identification, IdentError> {
    let theta = objective.theta(&outcome.parameters);
    let model = objective
        .model(&outcome.parameters)
        .ok_or(IdentError::Parameters { theta })?;
    let fits = cases
        .iter()
        .map(|c| {
            let (sse, fit_percent) = c.fit(&c.simulate(&model)?);
            Ok(CaseFit {
                name: c.name.clone(),
                sse,
                fit_percent,
                samples: c.window_len(),
            })
        })
        .collect::<Result<Vec<_>, CaseError>>()?;
    let n = objective.residual_count();
    let q = objective.parameter_count();
    let sse = outcome.objective;
    let spread = total_spread(cases);
    let uncertainty = uncertainty(objective, &outcome.parameters, lower, upper, settings.dof);
    let mut warnings = uncertainty.warnings.clone();
    warnings.extend(crate::stats::determination(&uncertainty));
    if starts.failed > 0 {
        warnings.push(format!(
            "{} of {} starts failed (model not simulable) and were discarded",
            starts.failed, starts.total
        ));
    }
    if let Some(warning) = single_start_warning(&starts) {
        warnings.push(warning);
    }
    if !outcome.stop.converged() {
        warnings.push(format!(
            "the best start stopped at the iteration limit ({} iterations)",
            outcome.iterations
        ));
    }
    warnings.extend(fits.iter().filter(|f| f.fit_percent < 0.0).map(|f| {
        format!(
            "case '{}': fit {} %: the model follows the displacement worse than its mean does; check its channels, their window and any note on their time base",
            f.name,
            bumpsim_core::units::format_number(f.fit_percent, 4)
        )
    }));
    // An objective below the rounding of the data (an exact fit of exact
    // synthetic data) counts as that rounding: AIC and BIC stay finite and
    // the smallest exact model wins the comparison.
    let resolved = sse
        .max(spread * f64::EPSILON * f64::EPSILON)
        .max(f64::MIN_POSITIVE);
    let ln_term = n as f64 * (resolved / n as f64).ln();
    Ok(Identification {
        dof: settings.dof,
        model,
        objective: sse,
        fit_percent: 100.0 * (1.0 - (sse / spread).sqrt()),
        cases: fits,
        aic: ln_term + 2.0 * q as f64,
        bic: ln_term + q as f64 * (n as f64).ln(),
        residuals: n,
        uncertainty,
        starts,
        iterations: outcome.iterations,
        start: Vec::new(),
        stop: outcome.stop,
        run_time: clock.elapsed().as_secs_f64(),
        warnings,
        reduction: None,
    })
}

/// `Σ_l ‖y_l − ȳ_l‖²` over the windows (each case about its own mean).
fn total_spread(cases: &[LoadCase]) -> f64 {
    cases
        .iter()
        .map(|c| {
            let w = &c.measured[c.window.0..=c.window.1];
            let mean = w.iter().sum::<f64>() / w.len() as f64;
            w.iter().map(|y| (y - mean).powi(2)).sum::<f64>()
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn starts(total: usize, refined: usize, explored_best_fit: usize) -> Starts {
        Starts {
            total,
            converged: total,
            failed: 0,
            reached_best: explored_best_fit,
            reached_best_alone: 1,
            reached_best_fit: total,
            reached_best_fit_alone: 1,
            abandoned: 0,
            merged: total - 1,
            unpolished: 0,
            refined,
            explored_best_fit,
            best: 0,
        }
    }

    /// `fixed = { k1 = nan }` said "bounds: fixed value NaN must be
    /// positive", naming neither the table nor the parameter.
    #[test]
    fn a_bad_fixed_value_names_its_parameter() {
        let mut bounds = Bounds::uniform(2, 1.0);
        bounds.fixed[3] = Some(f64::NAN);
        let err = bounds.check(2).unwrap_err().to_string();
        assert!(
            err.contains("fixed")
                && err.contains("k1 = NaN N/m: a fixed value must be finite and positive"),
            "{err}"
        );
    }

    /// The remark fired on a 1-DOF model whose 32 starts all reached the
    /// best (31 merged into one run), and stayed silent when one exploring
    /// start found the basin and the refining starts around it followed.
    #[test]
    fn the_single_start_remark_counts_exploring_starts() {
        assert_eq!(single_start_warning(&starts(32, 16, 16)), None);
        assert_eq!(single_start_warning(&starts(32, 16, 2)), None);
        let one = single_start_warning(&starts(32, 16, 1)).unwrap();
        assert!(one.starts_with("1 of the 16 exploring starts"), "{one}");
        assert!(one.contains("16 more drawn around the best"), "{one}");
        let none = single_start_warning(&starts(8, 0, 0)).unwrap();
        assert!(
            none.starts_with("0 of the 8 exploring starts") && !none.contains("around"),
            "{none}"
        );
        assert_eq!(single_start_warning(&starts(1, 0, 1)), None);
    }
}
