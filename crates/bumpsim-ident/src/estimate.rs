//! Multi-start bounded identification of one chain model from several
//! load cases, on the estimation layer of `bumpsim-estimate`.
//!
//! Parameters are estimated as `p = ln θ` (kg, N·s/m and N/m spanning seven
//! decades become comparable) with the layer's bounded LM within the bounds
//! (thesis: every parameter ≥ 1 SI). Starts (the user's, the data-derived
//! [`data_start`], continuation starts from a smaller model, random ones)
//! are [`crate::search`]'s; the layer runs them in stages, refines around
//! the best, polishes the best few and tallies them
//! ([`bumpsim_estimate::multistart`]); a start whose model cannot be
//! simulated is counted as failed, never propagated. Uncertainty, fit % and
//! the reduced-model advice are the layer's too ([`crate::stats`],
//! [`crate::reduce`]).

use crate::case::{CaseError, LoadCase, Objective, VALID_RANGE};
use crate::search::starting_points;
use crate::stats::{Uncertainty, uncertainty};
use bumpsim_core::model::{MsdModel, ParameterKind, parameter_count, parameter_kind};
use bumpsim_estimate::lm::{self, LeastSquares, Stop};
use bumpsim_estimate::multistart::{self, Search, Searched};
use bumpsim_estimate::observer::Observer;
use bumpsim_estimate::search::exploring;
use serde::Serialize;
use std::time::Instant;

pub use bumpsim_estimate::bounds::Bounds;
pub use bumpsim_estimate::multistart::Starts;

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
    #[error(transparent)]
    AllFailed(#[from] multistart::AllFailed),
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

/// The bounds of a `dof`-mass chain: every parameter in `[lower, ∞)`, none
/// fixed (the thesis: `lower` = 1).
pub fn uniform_bounds(dof: usize, lower: f64) -> Bounds {
    Bounds::uniform(parameter_count(dof), lower)
}

/// Checks `bounds` for a `dof`-mass chain: one entry per parameter, each
/// usable ([`usable_bounds`], [`usable_fixed`]).
fn check_bounds(bounds: &Bounds, dof: usize) -> Result<(), IdentError> {
    {
        let p = parameter_count(dof);
        let setting = |reason: String| IdentError::Setting {
            name: "bounds",
            reason,
        };
        if bounds.lower.len() != p || bounds.upper.len() != p || bounds.fixed.len() != p {
            return Err(setting(format!("{p} parameters for {dof} DOF")));
        }
        for i in 0..p {
            let (lo, hi) = (bounds.lower[i], bounds.upper[i]);
            let (floor, ceiling) = (*VALID_RANGE.start(), *VALID_RANGE.end());
            if !usable_bounds(lo, hi) {
                let name = bumpsim_core::model::parameter_name(dof, i);
                let unit = parameter_kind(dof, i).0.unit();
                return Err(setting(format!(
                    "{name}: need {floor:e} {unit} <= lower < upper with lower below {ceiling:e} {unit}, got [{lo}, {hi}] {unit}"
                )));
            }
            if let Some(v) = bounds.fixed[i].filter(|v| !usable_fixed(*v)) {
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
            bounds: uniform_bounds(dof, 1.0),
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
    check_bounds(&settings.bounds, settings.dof)?;
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

/// Identifies a `settings.dof`-mass model from `cases`, with the reduced
/// model that fits as well when a spring is undetermined
/// ([`crate::reduce`]). `observer` hears of every finished start (from any
/// thread; a closure `|| bar.inc(1)` is one).
pub fn identify(
    cases: &[LoadCase],
    settings: &Settings,
    observer: &dyn Observer,
) -> Result<Identification, IdentError> {
    let mut result = identify_only(cases, settings, observer)?;
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
    observer: &dyn Observer,
) -> Result<Identification, IdentError> {
    check(cases, settings)?;
    let clock = Instant::now();
    let objective = Objective::new(cases, settings.dof, &settings.bounds.fixed);
    let free = objective.free().to_vec();
    let log = |v: &[f64]| -> Vec<f64> { free.iter().map(|&i| v[i].ln()).collect() };
    let (lower, upper) = (log(&settings.bounds.lower), log(&settings.bounds.upper));
    let data = data_start(cases, settings.dof);
    let fixed = (&settings.start, data.as_slice(), settings.seeds.as_slice());
    let given = usize::from(settings.start.is_some()) + 1 + settings.seeds.len();
    let first = exploring(settings.starts, given);
    let points = starting_points(first, settings.seed, fixed, &settings.split_links, &free);
    let (floor, ceiling) = (
        vec![VALID_RANGE.start().ln(); free.len()],
        vec![VALID_RANGE.end().ln(); free.len()],
    );
    let search = Search {
        starts: settings.starts,
        seed: settings.seed,
        solver: settings.solver,
        lower: &lower,
        upper: &upper,
        range: (&floor, &ceiling),
    };
    let make = || Objective::new(cases, settings.dof, &settings.bounds.fixed);
    let found = multistart::search(&make, points, &search, observer)?;
    let mut result = summarise(cases, settings, &objective, &found, (&lower, &upper), clock)?;
    result.start = objective.theta(found.best_start());
    Ok(result)
}

fn summarise(
    cases: &[LoadCase],
    settings: &Settings,
    objective: &Objective,
    found: &Searched,
    (lower, upper): (&[f64], &[f64]),
    clock: Instant,
) -> Result<Identification, IdentError> {
    let outcome = found.best();
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
    let mut warnings = bumpsim_estimate::uncertainty::warnings(&uncertainty);
    warnings.extend(multistart::warnings(&found.starts, outcome));
    warnings.extend(fits.iter().filter_map(|f| {
        bumpsim_estimate::fit::negative_fit(&f.name, "displacement", f.fit_percent)
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
        fit_percent: bumpsim_estimate::fit::from_sums(sse, spread),
        cases: fits,
        aic: ln_term + 2.0 * q as f64,
        bic: ln_term + q as f64 * (n as f64).ln(),
        residuals: n,
        uncertainty,
        starts: found.starts,
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
        .map(|c| bumpsim_estimate::fit::spread(&c.measured[c.window.0..=c.window.1]))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `fixed = { k1 = nan }` said "bounds: fixed value NaN must be
    /// positive", naming neither the table nor the parameter.
    #[test]
    fn a_bad_fixed_value_names_its_parameter() {
        let mut bounds = uniform_bounds(2, 1.0);
        bounds.fixed[3] = Some(f64::NAN);
        let err = check_bounds(&bounds, 2).unwrap_err().to_string();
        assert!(
            err.contains("fixed")
                && err.contains("k1 = NaN N/m: a fixed value must be finite and positive"),
            "{err}"
        );
    }
}
