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
use crate::settings::check;
use crate::stats::uncertainty;
use bumpsim_core::model::{ParameterKind, parameter_count, parameter_kind};
use bumpsim_core::units::format_number;
use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::multistart::{self, AllFailed, Search, Searched};
use bumpsim_estimate::observer::Observer;
use bumpsim_estimate::search::exploring;
use std::time::Instant;

pub use crate::error::IdentError;
pub use crate::result::{CaseFit, Identification};
pub use crate::settings::{
    MAX_DOF, MAX_STARTS, SHEET_MASS_TOLERANCE, Settings, uniform_bounds, usable_bounds,
    usable_fixed,
};
pub use bumpsim_estimate::bounds::Bounds;
pub use bumpsim_estimate::multistart::Starts;

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

/// A warning when the masses `theta` (SI, thesis order) the data alone
/// identify (before any prior: a prior on the total mass would follow the
/// sheet) sum to more than [`SHEET_MASS_TOLERANCE`] off the test sheet's
/// mass.
fn sheet_mass_warning(theta: &[f64], settings: &Settings) -> Option<String> {
    let sheet = settings.sheet_mass?;
    let total: f64 = theta[..settings.dof].iter().sum();
    let off = (total - sheet) / sheet;
    (off.abs() > SHEET_MASS_TOLERANCE).then(|| {
        format!(
            "the masses the data alone identify sum to {} kg, {} % off the test sheet's {} kg (more than {} %): \
             the tests do not determine the car's whole mass, or the sheet is not this car's; \
             bound or fix the heaviest mass, or compare another DOF",
            format_number(total, 5),
            format_number(100.0 * off, 3),
            format_number(sheet, 5),
            100.0 * SHEET_MASS_TOLERANCE
        )
    })
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
    let (lower, upper) = log_bounds(settings, &free);
    let make = || Objective::new(cases, settings.dof, &settings.bounds.fixed);
    let mut found = search_of(cases, settings, &make, observer)?;
    // the starts counted by what the data can tell apart as well: the
    // residuals' variance inflation at the best (the effective samples)
    found.count_correlated(crate::stats::effective(&objective, &found.best().parameters).time);
    let start = settings
        .start
        .clone()
        .unwrap_or_else(|| data_start(cases, settings.dof));
    let priors =
        crate::priors::priors(settings, &start, &free).map_err(|e| IdentError::Setting {
            name: "priors",
            reason: e.to_string(),
        })?;
    let posed = crate::prior_fit::fit(
        &make,
        settings.dof,
        &priors,
        found.best(),
        (&lower, &upper),
        &settings.solver,
    );
    let mut result = summarise(
        cases,
        settings,
        &objective,
        &found,
        &posed,
        (&lower, &upper),
        clock,
    )?;
    result.start = objective.theta(found.best_start());
    let data_alone = objective.theta(&found.best().parameters);
    result
        .warnings
        .extend(sheet_mass_warning(&data_alone, settings));
    Ok(result)
}

/// The bounds of the free parameters (`free`, thesis order) in log
/// parameters.
fn log_bounds(settings: &Settings, free: &[usize]) -> (Vec<f64>, Vec<f64>) {
    let log = |v: &[f64]| -> Vec<f64> { free.iter().map(|&i| v[i].ln()).collect() };
    (log(&settings.bounds.lower), log(&settings.bounds.upper))
}

/// The multi-start search [`identify`] runs, of the problems `make` builds
/// (the identification's [`Objective`] of `cases`, or one that wraps it):
/// the starts (the user's, the data-derived, the continuation ones, random
/// ones), bounds and solver of `settings`. One start in all is one solver
/// run to the full tolerances with LM's geodesic acceleration
/// ([`multistart::alone`]: no screening, with nothing to rank; issue 44
/// item 6); more are [`multistart::search`]'s staged search, whose stages
/// take the solver's own steps.
pub fn search_of<P: LeastSquares>(
    cases: &[LoadCase],
    settings: &Settings,
    make: &(dyn Fn() -> P + Sync),
    observer: &dyn Observer,
) -> Result<Searched, AllFailed> {
    let free = Objective::new(cases, settings.dof, &settings.bounds.fixed)
        .free()
        .to_vec();
    let (lower, upper) = log_bounds(settings, &free);
    let data = data_start(cases, settings.dof);
    let fixed = (&settings.start, data.as_slice(), settings.seeds.as_slice());
    let given = usize::from(settings.start.is_some()) + 1 + settings.seeds.len();
    let first = exploring(settings.starts, given);
    let mut points = starting_points(first, settings.seed, fixed, &settings.split_links, &free);
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
    match (points.len(), settings.starts) {
        (1, 0 | 1) => multistart::alone(make, points.remove(0), &search, observer),
        _ => multistart::search(make, points, &search, observer),
    }
}

fn summarise(
    cases: &[LoadCase],
    settings: &Settings,
    objective: &Objective,
    found: &Searched,
    posed: &crate::prior_fit::Posed,
    (lower, upper): (&[f64], &[f64]),
    clock: Instant,
) -> Result<Identification, IdentError> {
    let outcome = &posed.outcome;
    let theta = objective.theta(&outcome.parameters);
    let model = objective
        .model(&outcome.parameters)
        .ok_or_else(|| IdentError::Parameters {
            theta: theta.clone(),
        })?;
    let fits = cases
        .iter()
        .map(|c| Ok(CaseFit::of(c, &c.simulate(&model)?)))
        .collect::<Result<Vec<_>, CaseError>>()?;
    let n = objective.residual_count();
    let q = objective.parameter_count();
    let sse = outcome.objective;
    let spread = total_spread(cases);
    let uncertainty = uncertainty(objective, &outcome.parameters, lower, upper, settings.dof);
    let (uncertainty, moved, prior_warnings) =
        posed.posterior(uncertainty, &theta, objective.free());
    let effective_samples = crate::stats::effective(objective, &outcome.parameters);
    let negative = fits.iter().filter_map(|f| {
        bumpsim_estimate::fit::negative_fit(&f.name, "displacement", f.fit_percent)
    });
    let mut warnings = bumpsim_estimate::warnings(&uncertainty, &found.starts, outcome, negative);
    warnings.extend(prior_warnings);
    // An objective below the rounding of the data (an exact fit of exact
    // synthetic data) counts as that rounding: AIC and BIC stay finite and
    // the smallest exact model wins the comparison.
    let resolved = sse
        .max(spread * f64::EPSILON * f64::EPSILON)
        .max(f64::MIN_POSITIVE);
    let ln_term = n as f64 * (resolved / n as f64).ln();
    let compared = crate::result::Compared::of(cases);
    // the fit % is the displacement's; beyond the thesis's objective its
    // sum of squares is the cases' own
    let displacement_sse = match compared {
        None => sse,
        Some(_) => fits.iter().map(|f| f.sse).sum(),
    };
    Ok(Identification {
        dof: settings.dof,
        model,
        objective: sse,
        compared,
        fit_percent: bumpsim_estimate::fit::from_sums(displacement_sse, spread),
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
        effective_samples,
        cross_validation: None,
        priors: moved,
        prior_noise: (!posed.priors.is_empty()).then_some(posed.noise),
        stated: posed.priors.clone(),
    })
}

/// `Σ_l ‖y_l − ȳ_l‖²` over the windows (each case about its own mean).
fn total_spread(cases: &[LoadCase]) -> f64 {
    cases
        .iter()
        .map(|c| bumpsim_estimate::fit::spread(&c.measured[c.window.0..=c.window.1]))
        .sum()
}
