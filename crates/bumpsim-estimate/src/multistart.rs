//! One multi-start estimation, for any least-squares problem: the explored
//! starts the model gives, the refining rounds around the best
//! ([`crate::search`]), the polishing of the best few ([`crate::polish`]),
//! and the tally of what became of every start ([`Starts`]).
//!
//! A start *reaches the best fit* when its run (or the run it merged into)
//! ends within one noise variance of the best objective,
//! `F ≤ F_best (1 + 1/(n − q))` with n residuals and q free parameters: the
//! data cannot tell such a fit from the best (its likelihood-ratio
//! statistic `n ln(F/F_best)` is about 1, where a 5 % test needs 3.84).
//!
//! That treats the residuals as independent. Sampled test channels are
//! not: each residual carries 1/κ of an independent one, κ the variance
//! inflation (the integrated autocorrelation time, `(1 + ρ)/(1 − ρ)` for
//! a lag-1 correlation ρ alone; [`crate::effective`]), and the data cannot
//! tell apart fits within `F ≤ F_best (1 + κ/(n − q))`. A model that knows
//! κ at the best counts the starts by that bar too
//! ([`Searched::count_correlated`], [`Starts::reached_correlated`]); the
//! race keeps the first bar.

use crate::lm::{self, LeastSquares, Outcome};
use crate::observer::Observer;
use crate::polish::{REFINE_FTOL, SCREEN_FTOL, candidates, polish};
use crate::search::{Fate, Goal, ROUND, Run, around, representative, staged};
use serde::Serialize;

/// The likelihood-ratio statistic a fit must beat another's by to be told
/// apart from it at 5 %: the 95 % quantile of χ² with one degree of
/// freedom (dimensionless; checked against statrs in the tests).
pub const DISTINGUISHED: f64 = 3.841_458_820_694_124;

/// Every start failed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("all {starts} starts failed: the model could not be simulated from any of them")]
pub struct AllFailed {
    /// Number of starts.
    pub starts: usize,
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
    /// variance of the best objective, `F ≤ F_best (1 + 1/(n − q))`. In a
    /// flat valley (a sloppy 5-DOF model) starts stop at objectives that
    /// differ in the fourth digit, which the 1e-6 count calls misses.
    pub reached_best_fit: usize,
    /// Starts of `reached_best_fit` that got there by their own run.
    pub reached_best_fit_alone: usize,
    /// Starts that reached the best fit with the residuals' correlation
    /// counted: their run (or the one they merged into) ended within `F ≤
    /// F_best (1 + κ/(n − q))`, κ = [`Starts::inflation`]. Equals
    /// `reached_best_fit` until a model states κ
    /// ([`Searched::count_correlated`]).
    pub reached_correlated: usize,
    /// Exploring starts of `reached_correlated` (`explored_best_fit` with
    /// the residuals' correlation counted): independent draws that found a
    /// fit the data cannot tell from the best.
    pub explored_correlated: usize,
    /// The variance inflation κ ≥ 1 (dimensionless) that
    /// `reached_correlated` counts with: the model's, at the best of the
    /// objective the runs ended in (the 1-D identification states the
    /// residuals' integrated autocorrelation time at its data-only search's
    /// best, not necessarily the inflation its intervals apply; the planar
    /// one at its final best, after its starts were carried there, the τ
    /// its intervals count); 1 where the model stated none.
    pub inflation: f64,
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
    /// Index of the best start (0 = the first given start).
    pub best: usize,
}

/// How to search: the starts, the solver, the bounds.
#[derive(Debug, Clone, Copy)]
pub struct Search<'a> {
    /// Starts in all (≥ 1): the explored ones given to [`search`], the rest
    /// refine around the best.
    pub starts: usize,
    /// Seed of the refining draws.
    pub seed: u64,
    /// Solver tolerances and iteration limit.
    pub solver: lm::Settings,
    /// Bounds of the free log parameters.
    pub lower: &'a [f64],
    /// Upper bounds (may be infinite).
    pub upper: &'a [f64],
    /// Where refining draws are clamped, per free log parameter (where the
    /// model can be evaluated).
    pub range: (&'a [f64], &'a [f64]),
}

/// What a search found.
#[derive(Debug, Clone)]
pub struct Searched {
    /// Every start's run, in start order.
    pub runs: Vec<Run>,
    /// Every start's starting point (log parameters).
    pub points: Vec<Vec<f64>>,
    /// The tally.
    pub starts: Starts,
    /// n − q of the problem (residuals less free parameters).
    freedom: usize,
    /// How many of `runs` (the first ones) explored.
    exploring: usize,
}

impl Searched {
    /// The best run's outcome.
    pub fn best(&self) -> &Outcome {
        &self.runs[self.starts.best].outcome
    }

    /// Where the best run started (log parameters).
    pub fn best_start(&self) -> &[f64] {
        &self.points[self.starts.best]
    }

    /// Whether an objective `other` lies below `best` by more than the data
    /// can tell apart, by a likelihood-ratio test at 5 %: `((n − q)/κ)
    /// ln(best/other) > 3.84` ([`DISTINGUISHED`]), κ the inflation of the
    /// last [`Searched::count_correlated`] (1 before it). A choice between
    /// two fits that replaces one by the other asks that much; the tally
    /// of the starts that reached the best asks only that they lie within
    /// one noise variance (the module).
    ///
    /// ```
    /// # use bumpsim_estimate::lm::{self, LeastSquares};
    /// # use bumpsim_estimate::multistart::{self, Search};
    /// # use bumpsim_estimate::observer::Silent;
    /// # use nalgebra::DMatrix;
    /// /// r = (p − 1, p + 1): F = 2 + 2p², least at p = 0 (F = 2); n − q = 1.
    /// struct Bowl;
    /// impl LeastSquares for Bowl {
    ///     fn residual_count(&self) -> usize { 2 }
    ///     fn parameter_count(&self) -> usize { 1 }
    ///     fn evaluate(&self, p: &[f64], r: &mut [f64], j: Option<&mut DMatrix<f64>>) -> bool {
    ///         r[0] = p[0] - 1.0;
    ///         r[1] = p[0] + 1.0;
    ///         if let Some(j) = j { j[(0, 0)] = 1.0; j[(1, 0)] = 1.0; }
    ///         true
    ///     }
    /// }
    /// let search = Search {
    ///     starts: 1, seed: 1, solver: lm::Settings::default(),
    ///     lower: &[-10.0], upper: &[10.0], range: (&[-10.0], &[10.0]),
    /// };
    /// let mut found = multistart::search(&|| Bowl, vec![vec![3.0]], &search, &Silent).unwrap();
    /// // κ = 1 and n − q = 1: lower beyond the noise below 2/e^3.84 = 0.043
    /// assert!(!found.lower_beyond_noise(0.05, 2.0));
    /// assert!(found.lower_beyond_noise(0.04, 2.0));
    /// // κ = 4: four times as far in ln F
    /// found.count_correlated(4.0);
    /// assert!(!found.lower_beyond_noise(0.04, 2.0));
    /// assert!(found.lower_beyond_noise(1e-7, 2.0));
    /// ```
    pub fn lower_beyond_noise(&self, other: f64, best: f64) -> bool {
        let kappa = self.starts.inflation.max(1.0);
        let statistic = self.freedom.max(1) as f64 / kappa * (best / other).ln();
        statistic > DISTINGUISHED
    }

    /// Counts [`Starts::reached_correlated`] again with the variance
    /// inflation `inflation` (κ, dimensionless; below 1 or not finite
    /// taken as 1) at the best run, before anything changes the runs'
    /// objectives (a polish under other weights).
    ///
    /// ```
    /// # use bumpsim_estimate::lm::{self, LeastSquares};
    /// # use bumpsim_estimate::multistart::{self, Search};
    /// # use nalgebra::DMatrix;
    /// /// r = (p − 1, p + 1): F = 2 + 2p², least at p = 0 (F = 2).
    /// struct Bowl;
    /// impl LeastSquares for Bowl {
    ///     fn residual_count(&self) -> usize { 2 }
    ///     fn parameter_count(&self) -> usize { 1 }
    ///     fn evaluate(&self, p: &[f64], r: &mut [f64], j: Option<&mut DMatrix<f64>>) -> bool {
    ///         r[0] = p[0] - 1.0;
    ///         r[1] = p[0] + 1.0;
    ///         if let Some(j) = j { j[(0, 0)] = 1.0; j[(1, 0)] = 1.0; }
    ///         true
    ///     }
    /// }
    /// let search = Search {
    ///     starts: 2, seed: 1, solver: lm::Settings::default(),
    ///     lower: &[-10.0], upper: &[10.0], range: (&[-10.0], &[10.0]),
    /// };
    /// let points = vec![vec![3.0], vec![-2.0]];
    /// # use bumpsim_estimate::observer::Silent;
    /// let mut found = multistart::search(&|| Bowl, points, &search, &Silent).unwrap();
    /// found.count_correlated(50.0);
    /// assert_eq!(found.starts.reached_correlated, 2);
    /// assert!((found.starts.inflation - 50.0).abs() < 1e-12);
    /// ```
    pub fn count_correlated(&mut self, inflation: f64) {
        let inflation = match inflation.is_finite() {
            true => inflation.max(1.0),
            false => 1.0,
        };
        let best = self.runs[self.starts.best].outcome.objective;
        let bar = best * (1.0 + inflation / self.freedom.max(1) as f64) + 1e-300;
        self.starts.reached_correlated = reached_within(&self.runs, bar, true).0;
        self.starts.explored_correlated = explored_within(&self.runs, self.exploring, bar);
        self.starts.inflation = inflation;
    }
}

impl Searched {
    /// Tallies the starts again after their runs' outcomes changed: each
    /// run carried on into another objective (the planar identification
    /// carries its starts along its continuation in the priors' weight),
    /// the best and every count anew in that objective; κ back to 1 until
    /// [`Searched::count_correlated`] states it again. An error when no run
    /// is left finished with a finite objective.
    ///
    /// ```
    /// # use bumpsim_estimate::lm::{self, LeastSquares};
    /// # use bumpsim_estimate::multistart::{self, Search};
    /// # use bumpsim_estimate::observer::Silent;
    /// # use nalgebra::DMatrix;
    /// /// r = (p² − 1, 0.3): F = (p² − 1)² + 0.09, least at p = −1 and at p = 1.
    /// struct Wells;
    /// impl LeastSquares for Wells {
    ///     fn residual_count(&self) -> usize { 2 }
    ///     fn parameter_count(&self) -> usize { 1 }
    ///     fn evaluate(&self, p: &[f64], r: &mut [f64], j: Option<&mut DMatrix<f64>>) -> bool {
    ///         r[0] = p[0] * p[0] - 1.0;
    ///         r[1] = 0.3;
    ///         if let Some(j) = j { j[(0, 0)] = 2.0 * p[0]; j[(1, 0)] = 0.0; }
    ///         true
    ///     }
    /// }
    /// let search = Search {
    ///     starts: 2, seed: 1, solver: lm::Settings::default(),
    ///     lower: &[-10.0], upper: &[10.0], range: (&[-10.0], &[10.0]),
    /// };
    /// let points = vec![vec![3.0], vec![-2.0]];
    /// let mut found = multistart::search(&|| Wells, points, &search, &Silent).unwrap();
    /// // both wells are as deep: both starts at the best
    /// assert_eq!(found.starts.reached_best, 2);
    /// // the best start carried on to a higher objective elsewhere
    /// let (best, other) = (found.starts.best, 1 - found.starts.best);
    /// found.runs[best].outcome.objective = 5.0;
    /// found.tally_again().unwrap();
    /// assert_eq!(found.starts.best, other);
    /// assert_eq!(found.starts.reached_best, 1);
    /// ```
    pub fn tally_again(&mut self) -> Result<(), AllFailed> {
        self.starts = tally(&self.runs, self.freedom, self.exploring)?;
        Ok(())
    }
}

/// Runs a staged multi-start search of the problem `make()` builds (one per
/// solver run, so that runs in parallel share nothing): the `explored`
/// starting points (log parameters), then `search.starts − explored.len()`
/// refining starts in rounds around the best so far, then the polishing of
/// the best screened optima. `observer` hears of every finished start.
pub fn search<P: LeastSquares>(
    make: &(dyn Fn() -> P + Sync),
    explored: Vec<Vec<f64>>,
    search: &Search,
    observer: &dyn Observer,
) -> Result<Searched, AllFailed> {
    let freedom = freedom(&make());
    let (lower, upper) = (search.lower, search.upper);
    // with a solver's geodesic acceleration, the screening of the explored
    // starts runs without it, the refining and polishing runs with it: over
    // the DOF table it cost about 6 % more CPU on every run and saved about
    // 20 % on these alone (docs/benchmarks.md, issue 44 item 6)
    let solve = |start: &[f64], iterations: usize, ftol: f64, accelerated: bool| {
        let solver = lm::Settings {
            max_iterations: iterations,
            ftol,
            acceleration: search.solver.acceleration.filter(|_| accelerated),
            ..search.solver
        };
        lm::minimise(&make(), start, lower, upper, &solver)
    };
    let (limit, ftol) = (search.solver.max_iterations, search.solver.ftol);
    let screen = |p: &[f64], n| solve(p, n, ftol.max(SCREEN_FTOL), false);
    // a run is raced for the best fit: within one noise variance of the best
    let goal = Goal {
        iterations: limit,
        target: f64::INFINITY,
        within: 1.0 / freedom.max(1) as f64,
    };
    let mut points = explored;
    let first = points.len();
    let mut runs = staged(&points, goal, &screen, observer);
    let mut refined = search.starts.max(1).saturating_sub(first);
    // the second level, in rounds: around the best screened optimum so far,
    // each start raced for its fit
    while let Some(best) = best_run(&runs).filter(|_| refined > 0) {
        let round = refined.min(ROUND);
        let more = around(
            &best.parameters,
            round,
            search.seed,
            points.len(),
            search.range,
        );
        let within = Goal {
            target: best.objective * (1.0 + goal.within),
            ..goal
        };
        let offset = runs.len();
        let refine = |p: &[f64], n| solve(p, n, ftol.max(REFINE_FTOL), true);
        runs.extend(
            staged(&more, within, &refine, observer)
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
    polish(&mut runs, &chosen, goal, &|p, n| solve(p, n, ftol, true));
    let starts = tally(&runs, freedom, first)?;
    Ok(Searched {
        runs,
        points,
        starts,
        freedom,
        exploring: first,
    })
}

/// The search of one start in all: its one solver run, to the full
/// tolerances and the iteration limit (one call: nothing to race it
/// against), with the geodesic acceleration: the solver's limit if it
/// names one, else [`lm::ACCELERATION_LIMIT`]. With nothing to rank there
/// is nothing to screen: [`search`] screens a lone start (to
/// [`SCREEN_FTOL`]) and then polishes its optimum in a second LM run that
/// starts afresh (its damping λ reset); from the 1-D identification's
/// default start on the peer series of `bumpsim-ident/tests/iterations.rs`
/// that took 31 Jacobians, one plain run 23 and one accelerated run 17
/// (velocity objective; 76, 76 and 41 on the displacement one; scipy TRF
/// 18 and 60). A lone start reaches its optimum in the fewest Jacobians
/// with the acceleration (not always in less time: each trial adds a
/// residual evaluation and a `Jᵀv`, docs/benchmarks.md), and there are no
/// other starts whose ranking it could change; [`search`]'s stages keep
/// the solver's own steps (plain by default: the acceleration there finds
/// other, deeper minima that few starts reach, docs/identify.md
/// "Iterations"). The 1-D identification
/// takes it (`bumpsim_ident::estimate::search_of`); the planar and link
/// identifications still screen and polish a lone start (the planar one's
/// symmetric stage has one start, and its recorded figures would move in
/// their twelfth digit).
pub fn alone<P: LeastSquares>(
    make: &dyn Fn() -> P,
    start: Vec<f64>,
    search: &Search,
    observer: &dyn Observer,
) -> Result<Searched, AllFailed> {
    let problem = make();
    let solver = lone_solver(&search.solver);
    let outcome = lm::minimise(&problem, &start, search.lower, search.upper, &solver);
    observer.start_finished();
    let runs = vec![Run {
        outcome,
        fate: Fate::Finished,
    }];
    let freedom = freedom(&problem);
    let starts = tally(&runs, freedom, 1)?;
    Ok(Searched {
        runs,
        points: vec![start],
        starts,
        freedom,
        exploring: 1,
    })
}

/// The solver of [`alone`]'s one run: `solver` with the geodesic
/// acceleration, its own limit or [`lm::ACCELERATION_LIMIT`].
fn lone_solver(solver: &lm::Settings) -> lm::Settings {
    lm::Settings {
        acceleration: solver.acceleration.or(Some(lm::ACCELERATION_LIMIT)),
        ..*solver
    }
}

/// The degrees of freedom n − q of a problem (residuals less parameters):
/// one noise variance of its best fit is `F_best / (n − q)`.
fn freedom(problem: &impl LeastSquares) -> usize {
    problem
        .residual_count()
        .saturating_sub(problem.parameter_count())
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
/// of the best fit is `F_best / freedom`. `exploring`: how many of `runs`
/// (the first ones) explored; the rest were drawn around the best so far.
pub fn tally(runs: &[Run], freedom: usize, exploring: usize) -> Result<Starts, AllFailed> {
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
        .ok_or(AllFailed { starts: runs.len() })?;
    let exact = outcome.objective * (1.0 + 1e-6) + 1e-300;
    let noise = outcome.objective * (1.0 + 1.0 / freedom.max(1) as f64) + 1e-300;
    let exploring = exploring.min(runs.len());
    // the exact bar asks for the thesis's tolerances: polished runs only
    let (reached_best, reached_best_alone) = reached_within(runs, exact, false);
    let (reached_best_fit, reached_best_fit_alone) = reached_within(runs, noise, true);
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
        reached_correlated: reached_best_fit,
        inflation: 1.0,
        abandoned: fate(|f| *f == Fate::Abandoned),
        merged: fate(|f| matches!(f, Fate::Merged(_))),
        unpolished: fate(|f| *f == Fate::Unpolished),
        refined: runs.len() - exploring,
        explored_best_fit: explored_within(runs, exploring, noise),
        explored_correlated: explored_within(runs, exploring, noise),
        best,
    })
}

/// Whether run `i` ended below `bar` by itself: polished, or (`screened`)
/// a screened optimum left unpolished.
fn ended_below(runs: &[Run], i: usize, bar: f64, screened: bool) -> bool {
    let ended = runs[i].fate == Fate::Finished || (screened && runs[i].fate == Fate::Unpolished);
    ended && runs[i].outcome.objective <= bar
}

/// How many of the first `exploring` starts reached `bar` (screened
/// optima count), by their own run or the run they merged into.
fn explored_within(runs: &[Run], exploring: usize, bar: f64) -> usize {
    (0..exploring.min(runs.len()))
        .filter(|&i| ended_below(runs, representative(runs, i), bar, true))
        .count()
}

/// How many starts reached `bar` (by their own run or the run they merged
/// into), and how many of them by their own run.
fn reached_within(runs: &[Run], bar: f64, screened: bool) -> (usize, usize) {
    let all = (0..runs.len())
        .filter(|&i| ended_below(runs, representative(runs, i), bar, screened))
        .count();
    let alone = (0..runs.len())
        .filter(|&i| ended_below(runs, i, bar, screened))
        .count();
    (all, alone)
}

/// The warnings a search's tally carries: failed starts, a best found by
/// one exploring start only, a best run that stopped at the iteration limit.
pub fn warnings(starts: &Starts, best: &Outcome) -> Vec<String> {
    let mut out = Vec::new();
    if starts.failed > 0 {
        out.push(format!(
            "{} of {} starts failed (model not simulable) and were discarded",
            starts.failed, starts.total
        ));
    }
    out.extend(single_start_warning(starts));
    if !best.stop.converged() {
        out.push(format!(
            "the best start stopped at the iteration limit ({} iterations)",
            best.iterations
        ));
    }
    out
}

/// The warning when at most one exploring start found the best fit: the
/// starts drawn around the best refine its basin and do not confirm that
/// no better one exists.
pub fn single_start_warning(starts: &Starts) -> Option<String> {
    let exploring = starts.total - starts.refined;
    if exploring < 2 || starts.explored_correlated > 1 {
        return None;
    }
    let within = match starts.inflation > 1.0 {
        true => format!(
            "within κ = {} noise variances",
            bumpsim_core::units::format_number(starts.inflation, 4)
        ),
        false => "within the noise".to_string(),
    };
    let around = match starts.refined {
        0 => String::new(),
        n => format!(
            " ({n} more drawn around the best refine its basin but do not search elsewhere)"
        ),
    };
    Some(format!(
        "{} of the {exploring} exploring starts came {within} of the best objective{around}: a better minimum may exist; raise the number of starts",
        starts.explored_correlated
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lm::Stop;
    use crate::polish::{candidates, polish};
    use crate::search::staged;

    #[test]
    fn the_distinguishing_bar_is_chi_squared_of_one_degree_at_95_percent() {
        use statrs::distribution::{ChiSquared, ContinuousCDF};
        let quantile = ChiSquared::new(1.0).unwrap().inverse_cdf(0.95);
        approx::assert_relative_eq!(super::DISTINGUISHED, quantile, max_relative = 1e-9);
    }

    /// A scripted solver on one parameter: minima at 0 (F = 1), 1 (F = 1.1)
    /// and 5 (F = 100) reached at once; a flat valley near 7 (F = 5) that
    /// makes no progress in a chunk; a hopeless start at 9 (F = 1000).
    fn scripted(p: &[f64], iterations: usize) -> Outcome {
        let (at, objective, stop) = match p[0] {
            x if x < 0.5 => (0.0, 1.0, Stop::Objective),
            x if x < 3.0 => (1.0, 1.1, Stop::Objective),
            x if x < 6.0 => (5.0, 100.0, Stop::Objective),
            x if x < 8.0 && iterations <= 200 => (x, 5.0, Stop::Iterations),
            x if x < 8.0 => (7.0, 5.0, Stop::Objective),
            x => (x, 1000.0, Stop::Iterations),
        };
        Outcome {
            parameters: vec![at],
            objective,
            iterations: iterations.min(7),
            evaluations: 1,
            stop,
        }
    }

    #[test]
    fn stages_abandon_merge_and_polish_and_the_tally_says_so() {
        let points: Vec<Vec<f64>> = [0.0, 0.01, 1.0, 5.0, 7.0, 7.001, 9.0]
            .iter()
            .map(|p| vec![*p])
            .collect();
        let finished = std::sync::atomic::AtomicUsize::new(0);
        let progress = || {
            finished.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        };
        let goal = Goal {
            iterations: 1000,
            target: f64::INFINITY,
            within: 0.0,
        };
        let mut runs = staged(&points, goal, &scripted, &progress);
        assert_eq!(finished.into_inner(), 7, "one progress call per start");
        assert_eq!(runs[6].fate, Fate::Abandoned); // 1000 > 10 × 1 after 200 iterations
        assert_eq!(runs[5].fate, Fate::Merged(4)); // 0.001 from a running start
        // the flat valley: F = 5 after the first stage and no progress in its
        // first chunk, so it cannot reach F = 1 in the iterations left
        assert_eq!(runs[4].fate, Fate::Abandoned);
        assert_eq!(runs[4].outcome.iterations, 14);
        let chosen = candidates(&mut runs);
        assert_eq!(chosen, vec![0, 2]); // F = 1 and 1.1 ≤ 1.2 × 1; 5 and 100 are not
        assert_eq!(runs[1].fate, Fate::Merged(0)); // 0.01 from the best
        assert_eq!(runs[3].fate, Fate::Unpolished);
        polish(&mut runs, &chosen, goal, &scripted);
        let starts = tally(&runs, 1_000_000, runs.len()).unwrap();
        assert_eq!((starts.best, starts.total, starts.failed), (0, 7, 0));
        // starts 0 and 1 reached F = 1: 0 by its own run, 1 merged into it;
        // 5 merged into 4, whose cluster was not polished, does not count
        assert_eq!((starts.reached_best, starts.reached_best_alone), (2, 1));
        // within the noise (here 1e-6 too) the same starts
        assert_eq!(
            (starts.reached_best_fit, starts.reached_best_fit_alone),
            (2, 1)
        );
        assert_eq!(
            (starts.abandoned, starts.merged, starts.unpolished),
            (2, 2, 1)
        );
        assert_eq!(starts.converged, 4);
    }

    /// `a e^(−b t) − y` at t = 0, 0.5, …, 4.5 for y from a = 2, b = 0.5,
    /// in the log parameters (ln a, ln b).
    struct Decay;

    impl LeastSquares for Decay {
        fn residual_count(&self) -> usize {
            10
        }
        fn parameter_count(&self) -> usize {
            2
        }
        fn evaluate(
            &self,
            p: &[f64],
            r: &mut [f64],
            jacobian: Option<&mut nalgebra::DMatrix<f64>>,
        ) -> bool {
            let (a, b) = (p[0].exp(), p[1].exp());
            let times = (0..10).map(|i| 0.5 * i as f64);
            for (i, t) in times.clone().enumerate() {
                r[i] = a * (-b * t).exp() - 2.0 * (-0.5 * t).exp();
            }
            if let Some(j) = jacobian {
                for (i, t) in times.enumerate() {
                    j[(i, 0)] = a * (-b * t).exp();
                    j[(i, 1)] = -a * b * t * (-b * t).exp();
                }
            }
            true
        }
    }

    /// One start in all is one solver run, the run `lm::minimise` makes
    /// from it with the search's solver and the geodesic acceleration,
    /// tallied as one converged start that reached the best.
    #[test]
    fn a_lone_start_is_one_run() {
        let (lower, upper) = ([-5.0; 2], [5.0; 2]);
        let search = Search {
            starts: 1,
            seed: 1,
            solver: lm::Settings::default(),
            lower: &lower,
            upper: &upper,
            range: (&lower, &upper),
        };
        let heard = std::sync::atomic::AtomicUsize::new(0);
        let observer = || {
            heard.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        };
        let start = vec![1.0, 0.0];
        let found = alone(&|| Decay, start.clone(), &search, &observer).unwrap();
        let accelerated = lm::Settings {
            acceleration: Some(lm::ACCELERATION_LIMIT),
            ..search.solver
        };
        assert_eq!(lone_solver(&search.solver), accelerated);
        let run = lm::minimise(&Decay, &start, &lower, &upper, &accelerated);
        assert_eq!(found.best(), &run);
        assert_eq!((found.best_start(), heard.into_inner()), (&start[..], 1));
        let s = found.starts;
        assert_eq!((s.total, s.converged, s.reached_best, s.best), (1, 1, 1, 0));
        assert!((run.parameters[0] - 2f64.ln()).abs() < 1e-6, "{run:?}");
        assert!((run.parameters[1] - 0.5f64.ln()).abs() < 1e-6, "{run:?}");
    }

    fn starts(total: usize, refined: usize, explored_best_fit: usize) -> Starts {
        Starts {
            total,
            converged: total,
            failed: 0,
            reached_best: explored_best_fit,
            reached_best_alone: 1,
            reached_best_fit: total,
            reached_best_fit_alone: 1,
            reached_correlated: total,
            explored_correlated: explored_best_fit,
            inflation: 1.0,
            abandoned: 0,
            merged: total - 1,
            unpolished: 0,
            refined,
            explored_best_fit,
            best: 0,
        }
    }

    /// Three finished runs at F = 1, 1.002 and 1.2 with n − q = 1000: the
    /// white bar (1.001) counts the best alone; κ = 100 (bar 1.1) adds the
    /// second, κ = 300 (bar 1.3) all three; κ below 1 or NaN counts as 1.
    #[test]
    fn the_correlated_count_widens_the_bar_by_the_inflation() {
        let run = |objective: f64| Run {
            outcome: Outcome {
                parameters: vec![objective],
                objective,
                iterations: 1,
                evaluations: 1,
                stop: Stop::Objective,
            },
            fate: Fate::Finished,
        };
        let runs = vec![run(1.2), run(1.0), run(1.002)];
        let starts = tally(&runs, 1000, 2).unwrap();
        let mut found = Searched {
            points: vec![vec![0.0]; 3],
            runs,
            starts,
            freedom: 1000,
            exploring: 2,
        };
        let counted = |found: &Searched| {
            let s = found.starts;
            (s.reached_best_fit, s.reached_correlated, s.inflation)
        };
        let explored = |found: &Searched| found.starts.explored_correlated;
        assert_eq!(counted(&found), (1, 1, 1.0));
        // the first two starts explored: only the best within the noise
        let warned = single_start_warning(&found.starts).unwrap();
        assert!(
            warned.starts_with("1 of the 2 exploring starts came within the noise of"),
            "{warned}"
        );
        found.count_correlated(100.0);
        assert_eq!((counted(&found), explored(&found)), ((1, 2, 100.0), 1));
        found.count_correlated(300.0);
        assert_eq!((counted(&found), explored(&found)), ((1, 3, 300.0), 2));
        assert_eq!(single_start_warning(&found.starts), None);
        for nonsense in [0.5, f64::NAN, f64::INFINITY] {
            found.count_correlated(nonsense);
            assert_eq!(
                (counted(&found), explored(&found)),
                ((1, 1, 1.0), 1),
                "{nonsense}"
            );
        }
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
