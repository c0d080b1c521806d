//! The simpler model the data cannot tell apart (issue 19).
//!
//! Two masses joined by link j may move as one. The reduced model merges
//! them (`m_j + m_{j+1}` on one node; link j removed, the other links kept;
//! an output on either mass is the merged mass's) and is refitted by one
//! LM run from the merged start. Two kinds of link are tried:
//!
//! 1. **An undetermined spring** — at a bound, without an interval, or with
//!    a 95 % interval wider than a factor [`SPREAD`] — widest interval
//!    first. Its merge is suggested when it fits within [`TOLERANCE`] of the
//!    full model's objective.
//! 2. **A determined link the data do not need.** A sloppy model can fit
//!    the noise with a small mass on a soft link instead: every interval is
//!    finite, but the fit is no better than the simpler model's. Of the other
//!    links, the one whose merged start fits best is refitted, and its merge
//!    is suggested when it fits within [`TOLERANCE`] *and* the full model's
//!    improvement is not significant by the extra-sum-of-squares F-test
//!    (Seber & Wild 1989, sec. 5.3):
//!    `F = ((F_r − F)/3) / (F/(n − q))` against `F(3, n − q)`, the three
//!    parameters of the removed mass and link, `p ≥` [`SIGNIFICANCE`].
//!
//! The statement names the link's spring and the two masses, and gives
//! both objectives and the test's p-value (reported for both kinds).
use crate::case::{LoadCase, Objective};
use crate::estimate::{Bounds, Identification, Settings};
use crate::lm::{self, LeastSquares};
use crate::polish::SCREEN_FTOL;
use crate::search::{Fate, Goal, Run, race};
use bumpsim_core::model::{MsdModel, format_parameter, parameter_count, parameter_name};
use bumpsim_core::units::{Dimension, format_number, format_quantity};
use serde::Serialize;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

/// A spring whose 95 % interval spans more than this factor is undetermined.
pub const SPREAD: f64 = 1e3;

/// The reduced model must fit within this fraction of the full objective.
pub const TOLERANCE: f64 = 0.01;

/// A determined link is merged only when the full model's improvement has
/// at least this p-value in the F-test (not significant at 5 %).
pub const SIGNIFICANCE: f64 = 0.05;

/// A reduced model that fits as well.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reduction {
    /// The undetermined spring (`k2`).
    pub parameter: String,
    /// What the user should know, with units.
    pub statement: String,
    /// The refitted reduced model; serialised as `masses`, `dampers`, `springs` (SI).
    pub model: MsdModel,
    /// Its objective, m².
    pub objective: f64,
    /// `F_reduced / F_full − 1`.
    pub relative_objective: f64,
    /// p-value of the F-test of the full model against the reduced one
    /// (large: the extra mass and link do not improve the fit significantly).
    pub p_value: f64,
}

/// How undetermined spring `j` (0-based) of `result` is: the interval's
/// ratio (infinite without one), or `None` when it is determined.
fn spread(result: &Identification, j: usize) -> Option<f64> {
    let i = 2 * result.dof - 1 + j;
    let u = &result.uncertainty;
    if u.fixed[i] {
        return None;
    }
    let ratio = match (u.at_bound[i], u.ci95[i]) {
        (true, _) | (_, None) => f64::INFINITY,
        (false, Some([low, high])) => high / low,
    };
    (ratio > SPREAD).then_some(ratio)
}

/// `model` with masses j and j+1 (0-based) merged and link j removed.
pub fn merged(model: &MsdModel, j: usize) -> Vec<f64> {
    let mut masses = model.masses().to_vec();
    let second = masses.remove(j + 1);
    masses[j] += second;
    let mut dampers = model.dampers().to_vec();
    dampers.remove(j);
    let mut springs = model.springs().to_vec();
    springs.remove(j);
    [masses, dampers, springs].concat()
}

/// The cases measured on the model with masses j and j+1 merged.
fn retargeted(cases: &[LoadCase], j: usize) -> Vec<LoadCase> {
    let mut cases = cases.to_vec();
    for c in &mut cases {
        if c.output_dof > j + 1 {
            c.output_dof -= 1;
        }
    }
    cases
}

/// The first reduced model that fits as well, if any (see the module).
pub(crate) fn suggest(
    cases: &[LoadCase],
    result: &Identification,
    settings: &Settings,
) -> Option<Reduction> {
    if result.dof < 2 || settings.bounds.fixed.iter().any(Option::is_some) {
        return None;
    }
    let mut undetermined: Vec<(usize, f64)> = (0..result.dof - 1)
        .filter_map(|j| spread(result, j).map(|s| (j, s)))
        .collect();
    undetermined.sort_by(|a, b| b.1.total_cmp(&a.1));
    let lower = settings
        .bounds
        .lower
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let merge = |j: usize, target: f64| -> Option<Reduction> {
        let reduced = Refit {
            dof: result.dof - 1,
            cases: &retargeted(cases, j),
            start: &merged(&result.model, j),
            bounds: &Bounds::uniform(result.dof - 1, lower),
            solver: &settings.solver,
        };
        let (model, objective) = reduced.run(target)?;
        Some(reduction(result, j, model, objective))
    };
    let loose = result.objective * (1.0 + TOLERANCE);
    let found = undetermined.iter().find_map(|&(j, _)| merge(j, loose));
    found.or_else(|| {
        let tried: Vec<usize> = undetermined.iter().map(|u| u.0).collect();
        let j = best_merge(cases, result, &tried)?;
        let freedom = result.residuals.saturating_sub(parameter_count(result.dof));
        let insignificant = result.objective * (1.0 + 3.0 * f_critical(freedom) / freedom as f64);
        merge(j, loose.min(insignificant)).filter(|r| r.p_value >= SIGNIFICANCE)
    })
}

/// One refit of a reduced model from a start, SI, all parameters free.
struct Refit<'a> {
    dof: usize,
    cases: &'a [LoadCase],
    start: &'a [f64],
    bounds: &'a Bounds,
    solver: &'a lm::Settings,
}

impl Refit<'_> {
    /// The refitted model and its objective (m²) when it ends at or below
    /// `target` (m²); given up, in [`crate::search::race`]'s chunks, as soon
    /// as it cannot get there. The race runs at the screening tolerance
    /// ([`crate::polish::SCREEN_FTOL`]: whether a merge fits within a
    /// percent does not need the thesis's 1e-12); a refit that gets there
    /// is then polished at the solver's tolerances.
    fn run(&self, target: f64) -> Option<(MsdModel, f64)> {
        let objective = Objective::new(self.cases, self.dof, &[]);
        let log = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x.ln()).collect() };
        let (lower, upper) = (log(&self.bounds.lower), log(&self.bounds.upper));
        let solve = |p: &[f64], iterations: usize, ftol: f64| {
            let settings = lm::Settings {
                max_iterations: iterations,
                ftol,
                ..*self.solver
            };
            lm::minimise(&objective, p, &lower, &upper, &settings)
        };
        // the start's objective, so that the first chunk already has a pace
        let mut start = Run::start(log(self.start));
        let mut residuals = vec![0.0; objective.residual_count()];
        if objective.evaluate(&start.outcome.parameters, &mut residuals, None) {
            start.outcome.objective = residuals.iter().map(|r| r * r).sum();
        }
        let mut runs = vec![start];
        let goal = Goal {
            iterations: self.solver.max_iterations,
            target,
            within: 0.0,
        };
        let screen = self.solver.ftol.max(SCREEN_FTOL);
        race(&mut runs, &mut vec![0], goal, &|p, n| solve(p, n, screen));
        let screened = &runs[0].outcome;
        if runs[0].fate != Fate::Finished || screened.objective > target {
            return None;
        }
        let left = self
            .solver
            .max_iterations
            .saturating_sub(screened.iterations);
        let polished = solve(&screened.parameters, left.max(1), self.solver.ftol);
        let outcome = match polished.objective <= screened.objective {
            true => &polished,
            false => screened,
        };
        Some((objective.model(&outcome.parameters)?, outcome.objective))
    }
}

/// The F(3, `freedom`) quantile a 5 % test compares with.
fn f_critical(freedom: usize) -> f64 {
    FisherSnedecor::new(3.0, freedom.max(1) as f64)
        .map(|f| f.inverse_cdf(1.0 - SIGNIFICANCE))
        .unwrap_or(f64::INFINITY)
}

/// The link, not among `tried`, whose merged start fits `cases` best.
fn best_merge(cases: &[LoadCase], result: &Identification, tried: &[usize]) -> Option<usize> {
    let objective_of = |j: usize| -> Option<f64> {
        let model = MsdModel::from_parameters(result.dof - 1, &merged(&result.model, j)).ok()?;
        retargeted(cases, j).iter().try_fold(0.0, |sum, case| {
            let simulated = case.simulate(&model).ok()?;
            Some(sum + case.fit(&simulated).0)
        })
    };
    (0..result.dof - 1)
        .filter(|j| !tried.contains(j))
        .filter_map(|j| objective_of(j).map(|f| (j, f)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(j, _)| j)
}

/// p-value of the extra-sum-of-squares F-test of the full model
/// (`full`, q parameters, n residuals) against a reduced one with three
/// parameters fewer (`reduced`); 1 when the reduced one fits as well.
pub fn f_test(full: f64, reduced: f64, residuals: usize, parameters: usize) -> f64 {
    let freedom = residuals.saturating_sub(parameters) as f64;
    let statistic = ((reduced - full) / 3.0) / (full / freedom);
    match FisherSnedecor::new(3.0, freedom.max(1.0)) {
        Ok(f) if statistic > 0.0 && statistic.is_finite() => f.sf(statistic),
        _ => 1.0,
    }
}

fn reduction(result: &Identification, j: usize, model: MsdModel, objective: f64) -> Reduction {
    let dof = result.dof;
    let i = 2 * dof - 1 + j;
    let name = parameter_name(dof, i);
    let relative = objective / result.objective - 1.0;
    let p_value = f_test(
        result.objective,
        objective,
        result.residuals,
        parameter_count(dof),
    );
    let u = &result.uncertainty;
    let how = match (u.at_bound[i], u.ci95[i]) {
        (true, _) => format!(
            "is not determined by the data (it is at its bound, {})",
            format_parameter(dof, i, result.model.springs()[j])
        ),
        (false, Some([a, b])) if b / a > SPREAD => format!(
            "is not determined by the data (its 95 % interval is {} .. {})",
            format_parameter(dof, i, a),
            format_parameter(dof, i, b)
        ),
        (false, Some(_)) => format!(
            "is not needed by the data (the fit with it is not significantly better: F-test p = {})",
            format_number(p_value, 2)
        ),
        (false, None) => {
            "is not determined by the data (it has no interval: the Jacobian does not determine it)"
                .into()
        }
    };
    // within 1 % of the objective, but an F-test can still call the
    // difference significant on many samples: then say so instead of
    // recommending the simpler model outright
    let advice = if p_value >= SIGNIFICANCE {
        "prefer the simpler model".to_string()
    } else {
        format!(
            "the simpler model is close, though the F-test calls the difference significant (p = {})",
            format_number(p_value, 2)
        )
    };
    let statement = format!(
        "{name} {how}: m{} and m{} move as one. The {}-DOF model with m{} + m{} = {} fits within {} % of the objective ({} m² against {} m²): {advice}.",
        j + 1,
        j + 2,
        dof - 1,
        j + 1,
        j + 2,
        format_quantity(model.masses()[j], Dimension::Mass),
        format_number(100.0 * relative.max(0.0), 3),
        format_number(objective, 5),
        format_number(result.objective, 5),
    );
    Reduction {
        parameter: name,
        statement,
        model,
        objective,
        relative_objective: relative,
        p_value,
    }
}

#[cfg(test)]
mod tests {
    use super::f_test;
    use approx::assert_relative_eq;

    /// p-values against scipy 1.17 `stats.f.sf(statistic, 3, n − q)`.
    #[test]
    fn the_f_test_agrees_with_scipy() {
        // statistic = ((reduced − full)/3) / (full/(n − q)); full = 1
        let p = |statistic: f64, freedom: usize| {
            let reduced = 1.0 + 3.0 * statistic / freedom as f64;
            f_test(1.0, reduced, freedom + 7, 7)
        };
        assert_relative_eq!(p(2.6, 1493), 0.05073185354500432, max_relative = 1e-9);
        assert_relative_eq!(p(10.0, 50), 2.8522492497201697e-05, max_relative = 1e-9);
        assert_relative_eq!(p(0.5, 3000), 0.6822991765666935, max_relative = 1e-9);
        // a reduced model that fits as well (or better) is not worse at all
        assert_relative_eq!(f_test(1.0, 0.999, 100, 7), 1.0);
    }
}
