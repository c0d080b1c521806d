//! The staged search of a planar identification with its priors (issue 44,
//! items 3 and 4).
//!
//! 1. **Symmetric stage.** When the two chains have the same size, the
//!    right chain is tied to the left ([`bumpsim_estimate::tied`]) and the
//!    tied car (body, one chain, tyres, lines of action) is searched from the
//!    template and a few random starts: the 1-D-like fit of the tests'
//!    common x motion, which the symmetric tests determine best.
//! 2. **Full search** from the symmetric optimum, the template and random
//!    starts within the study's `spread` of the template, refined and polished as every search of
//!    the layer ([`bumpsim_estimate::multistart`]).
//!
//! Both stages search with the bumper's effective width held within
//! [`super::WIDTH_SPREAD`] of its prior's centre ([`held`]); the best is
//! polished under the stated priors. Where the width is estimated, both
//! stages run a second time with the width pinned at that centre, its best
//! then released under the stated priors ([`pinned`]), and the lower of
//! the two searches is kept.
//!
//! **What the starts search.** The full search weighs the priors at the
//! noise of the symmetric optimum, which fits far worse than the final
//! car: on cars 0–19 of tests/peers/planar_yaw_rate.py that noise is 8–132
//! times the final one, 20 times on the bundled series; the priors dominate and the starts
//! converge to one point near their centres; the polishing that follows
//! (the noise re-estimated at each optimum) is what moves the car to the
//! data, one path from that point (a continuation in the priors' weight).
//! Every other start that ended on its own is then carried along the same
//! path ([`carried`]: polished at each of its noises in turn; a start
//! merged into another shares its continuation), so that the starts'
//! tally counts where their continuations end in the final objective,
//! not the prior-weighted basin they ran in ([`Found::search_noise`]
//! records the noise they ran at); the best is the lowest of them. With
//! [`Plan::confirm`] the full search runs again from the polished best, at
//! its noise, until the starts ran within a factor [`CONFIRMED`] of the
//! final noise (at most [`CONFIRMING`] times), its random starts drawn
//! from the priors ([`from_priors`]) and each first fitted with the priors
//! weighed at [`EASED`] times the noise ([`eased`]), and its tally counts
//! starts in the final objective (docs/planar.md, "What the starts
//! search").
//!
//! The priors weigh against the noise of one residual,
//! `σ = √(κ F/(n − q))` ([`bumpsim_estimate::prior::noise`]), which is
//! known only at an optimum: each stage takes σ at the start it starts
//! from (the symmetric stage's at the template, where the misfit makes the
//! priors strong and keeps the first stage near them), and the best of the
//! full search is polished again with σ at its own optimum until σ changes
//! by less than 10 %.

use super::Unknowns;
use super::objective::Objective;
use bumpsim_estimate::lm::{self, LeastSquares};
use bumpsim_estimate::multistart::{self, AllFailed, Search, Searched};
use bumpsim_estimate::observer::{Observer, Silent};
use bumpsim_estimate::posterior::gaussian;
use bumpsim_estimate::prior::{Prior, Priored, noise};
use bumpsim_estimate::search::{Draws, Fate, Run, exploring};
use bumpsim_estimate::tied::Tied;
use bumpsim_estimate::uncertainty::lag_one;
use rayon::prelude::*;

/// What the staged search found.
pub(super) struct Found {
    /// The full search (its best polished at the final noise).
    pub searched: Searched,
    /// The noise the priors weigh against at the best.
    pub noise: f64,
    /// The noise the priors were weighed against while the full search's
    /// starts ran (see the module).
    pub search_noise: f64,
}

/// How to search.
pub(super) struct Plan<'a> {
    pub unknowns: &'a Unknowns,
    pub priors: &'a [Prior],
    pub starts: usize,
    pub seed: u64,
    pub spread: f64,
    pub staged: bool,
    pub solver: lm::Settings,
    pub bounds: (&'a [f64], &'a [f64]),
    /// Run the full search again from its polished best, at the noise
    /// there (see the module).
    pub confirm: bool,
}

/// The noise of one residual of `objective` at `p` (∞-safe).
pub(super) fn noise_at(objective: &Objective, p: &[f64]) -> f64 {
    let mut r = vec![0.0; objective.residual_count()];
    let ok = objective.evaluate(p, &mut r, None);
    let f: f64 = r.iter().map(|v| v * v).sum();
    let rho = lag_one(&r, &objective.series());
    let inflation = (1.0 + rho) / (1.0 - rho);
    match ok && f.is_finite() {
        true => noise(f, r.len(), p.len(), inflation),
        false => 1.0,
    }
}

/// The starts of `searched` counted by what the data can tell apart: with
/// the residuals' integrated autocorrelation time τ at its best (the
/// inflation the intervals count, [`super::CORRELATION`]); left as tallied
/// where the car cannot be simulated there.
fn count_correlated(objective: &Objective, searched: &mut Searched) {
    let mut r = vec![0.0; objective.residual_count()];
    let ok = objective.evaluate(&searched.best().parameters, &mut r, None);
    if ok && r.iter().all(|v| v.is_finite()) {
        let method = bumpsim_estimate::effective::Method::Spectral;
        let tau = bumpsim_estimate::effective::of_residuals(&r, &objective.series(), method).time;
        searched.count_correlated(tau);
    }
}

/// With `confirm` ([`super::Setup::confirm`]), the full search runs again while its starts
/// weighed the priors at more than this factor of the final noise.
pub const CONFIRMED: f64 = 2.0;

/// With `confirm` ([`super::Setup::confirm`]), at most this many more full searches.
pub const CONFIRMING: usize = 2;

impl super::Setup {
    /// How many starts the search runs at most, for a progress bar: each
    /// full search's `starts`, up to [`CONFIRMING`] more searches with
    /// `confirm`, all twice where the effective width is estimated (the
    /// second search with it pinned; docs/planar.md, "The width pinned in a
    /// second search (w25)").
    pub fn start_count(&self) -> usize {
        let searches = 1 + usize::from(self.confirm) * CONFIRMING;
        self.starts * searches * (1 + usize::from(self.width))
    }
}

/// Runs the staged search (see the module); where the bumper's effective
/// width is estimated, twice (see [`pinned`]; the two side by side, so
/// that one's serial polish overlaps the other's starts), keeping the
/// lower ([`lower`]), or the pinned one where every start of the other
/// failed.
pub(super) fn search(
    objective: &Objective,
    plan: &Plan,
    observer: &dyn Observer,
) -> Result<Found, AllFailed> {
    let (held, pinned) = rayon::join(
        || search_once(objective, plan, observer),
        || pinned(objective, plan, observer),
    );
    match (held, pinned) {
        (Ok(held), Some(pinned)) => Ok(lower(objective, plan, held, pinned)),
        (Err(_), Some(pinned)) => Ok(pinned),
        (held, None) => held,
    }
}

/// The staged search with the bumper's effective width pinned at its
/// prior's centre (the start car's width where the prior was removed; a
/// centre outside the search's bounds at the nearer bound),
/// its best then released: continued under the stated priors with the
/// width free, every other start carried along. None where the width is
/// not estimated or the search fails.
///
/// Why: the replays see the width through which segments a wall's cell
/// holds, a piecewise function, and the search with the width held near
/// its centre can end in a basin of a higher objective along the width's
/// trade with the yaw inertia: on six of the twenty cars of
/// tests/peers/planar_independent.py (`--yaw-rate`) the pinned search's
/// best lay 10–85 % lower (car 6: 1.76e-2 against 2.65e-3 (m/s)² under
/// the priors, I_z +15.6 % against +4.5 %; car 2's held-out offset yaw
/// 85.35 % against 99.44 %); docs/planar.md, "The width pinned in a
/// second search (w25)".
fn pinned(objective: &Objective, plan: &Plan, observer: &dyn Observer) -> Option<Found> {
    let i = plan.unknowns.width_index()?;
    let centre = plan
        .priors
        .iter()
        .find(|p| p.name == super::EFFECTIVE_WIDTH)
        .map_or_else(
            || plan.unknowns.search(&plan.unknowns.start())[i],
            |p| p.centre.ln(),
        );
    // a stated centre outside the search's range is pinned at its edge
    let centre = centre.clamp(plan.bounds.0[i], plan.bounds.1[i]);
    let (mut lower, mut upper) = (plan.bounds.0.to_vec(), plan.bounds.1.to_vec());
    (lower[i], upper[i]) = (centre, centre);
    let pinned = Plan {
        bounds: (&lower, &upper),
        ..*plan
    };
    let mut found = search_once(objective, &pinned, observer).ok()?;
    let best = found.searched.starts.best;
    let outcome = &mut found.searched.runs[best].outcome;
    let (path, ended) = continuation(objective, plan, outcome, found.noise, true);
    carried(objective, plan, &mut found.searched, (best, ended), &path).ok()?;
    count_correlated(objective, &mut found.searched);
    found.noise = path.last().copied().unwrap_or(found.noise);
    Some(found)
}

/// Of the search with the width held and the one with it pinned, the
/// pinned one where its best lies lower beyond what the data can tell
/// apart ([`Searched::lower_beyond_noise`]: a likelihood-ratio test at 5 %
/// with the residuals' correlation counted; both valued under the stated
/// priors weighed at the lower of their final noises), else the held one.
///
/// Why a test and not one noise variance: on car 3 of
/// tests/peers/planar_yaw_rate.py the pinned best lay 0.6 % lower, a
/// statistic of 1.0 at κ = 20.6, and forecast the offset test's force at
/// 86.4 % against the held best's 90.7 %. Of 19 cars of two families where
/// the pinned best was the lower, the 13 that keep it have statistics of
/// 6.1 to 98, the 6 that no longer do 1.0 to 3.5 (docs/planar.md,
/// "The pinned search kept by a test (w26)").
fn lower(objective: &Objective, plan: &Plan, held: Found, pinned: Found) -> Found {
    let problem = priored(objective, plan, held.noise.min(pinned.noise));
    let value = |f: &Found| valued(&problem, &f.searched.best().parameters);
    match held
        .searched
        .lower_beyond_noise(value(&pinned), value(&held))
    {
        true => pinned,
        false => held,
    }
}

/// The staged search once (see the module).
fn search_once(
    objective: &Objective,
    plan: &Plan,
    observer: &dyn Observer,
) -> Result<Found, AllFailed> {
    let (lower, upper) = plan.bounds;
    let searching = held(plan.priors);
    let mut start = plan.unknowns.search(&plan.unknowns.start());
    let mut sigma = noise_at(objective, &start);
    if let Some(map) = plan.staged.then(|| ties(plan.unknowns)).flatten() {
        let priored = Priored::new(objective.clone(), searching.clone(), sigma)
            .expect("the priors were checked");
        let tied = Tied::new(priored, map).expect("a symmetric car's tie map");
        let (lo, hi) = (tied.reduce(lower), tied.reduce(upper));
        let centre = tied.reduce(&start);
        let count = plan.starts.div_ceil(4).clamp(1, 4);
        let points = (0..count)
            .map(|k| match k {
                0 => centre.clone(),
                k => draw(&centre, plan, k),
            })
            .collect();
        let search = Search {
            starts: count,
            seed: plan.seed,
            solver: plan.solver,
            lower: &lo,
            upper: &hi,
            range: (&lo, &hi),
        };
        let make = || {
            let priored = Priored::new(objective.clone(), searching.clone(), sigma)
                .expect("the priors were checked");
            Tied::new(priored, tied.map().to_vec()).expect("a symmetric car's tie map")
        };
        if let Ok(symmetric) = multistart::search(&make, points, &search, &Silent) {
            start = tied.expand(&symmetric.best().parameters);
            sigma = noise_at(objective, &start);
        }
    }
    let first = (start, sigma);
    let (mut searched, mut noise) = full(
        objective,
        plan,
        &searching,
        first,
        Drawn::Template,
        observer,
    )?;
    let mut search_noise = sigma;
    // confirmed: searched again from the best until the starts ran within
    // a factor [`CONFIRMED`] of the final noise (at most [`CONFIRMING`] more)
    for _ in 0..CONFIRMING {
        if !plan.confirm || search_noise / noise <= CONFIRMED {
            break;
        }
        let best = searched.runs[searched.starts.best]
            .outcome
            .parameters
            .clone();
        search_noise = noise_at(objective, &best);
        let again = (best, search_noise);
        (searched, noise) = full(objective, plan, &searching, again, Drawn::Priors, observer)?;
    }
    Ok(Found {
        searched,
        noise,
        search_noise,
    })
}

/// The full search from `start` (the symmetric optimum, or the best of a
/// first search) with the priors `searching` weighed at `sigma`, its best
/// polished under the stated priors at the noise of its optimum: the
/// search and that final noise.
fn full(
    objective: &Objective,
    plan: &Plan,
    searching: &[Prior],
    (start, sigma): (Vec<f64>, f64),
    drawn: Drawn,
    observer: &dyn Observer,
) -> Result<(Searched, f64), AllFailed> {
    let (lower, upper) = plan.bounds;
    // the start, then the template and random points around it (around
    // the symmetric optimum they would leave the range the template's
    // integration step is stable in)
    let template = plan.unknowns.search(&plan.unknowns.start());
    let first = exploring(plan.starts, 1);
    let points = (0..first)
        .map(|k| match k {
            0 => start.clone(),
            1 => template.clone(),
            k => match drawn {
                Drawn::Template => draw(&template, plan, k),
                Drawn::Priors => from_priors(draw(&template, plan, k), searching, plan.seed, k),
            },
        })
        .collect::<Vec<Vec<f64>>>();
    let points = match drawn {
        Drawn::Template => points,
        Drawn::Priors => eased(points, objective, searching, sigma, plan),
    };
    let search = Search {
        starts: plan.starts,
        seed: plan.seed,
        solver: plan.solver,
        lower,
        upper,
        range: (lower, upper),
    };
    let make = || {
        Priored::new(objective.clone(), searching.to_vec(), sigma).expect("the priors were checked")
    };
    let mut searched = multistart::search(&make, points, &search, observer)?;
    // held priors: the best is polished at least once under the stated ones
    let held = searching != plan.priors;
    let first_best = searched.starts.best;
    let best = &mut searched.runs[first_best].outcome;
    let (path, ended) = continuation(objective, plan, best, sigma, held);
    let sigma = path.last().copied().unwrap_or(sigma);
    carried(objective, plan, &mut searched, (first_best, ended), &path)?;
    count_correlated(objective, &mut searched);
    Ok((searched, sigma))
}

/// Every start carried along the continuation the best took: each other
/// finished run polished from its end under the stated priors at each
/// noise of `path` in turn, each screened optimum left unpolished valued
/// in the last of them, and the starts tallied again there. The tally
/// then counts the final objective's basins, not the prior-weighted first
/// one the starts ran in (see the module), and the best is the lowest
/// continuation (the first best's unless another start's ends lower; the
/// priors' noise stays `path`'s last, the objective every run is compared
/// in). A start merged during the search into a better one next to it
/// shares that one's continuation, as it shares its fate in the search
/// (the layer's count, [`bumpsim_estimate::multistart::Starts::reached_best`]):
/// carried by runs of their own, the merged starts of the bundled series
/// and of cars 4, 6, 12 and 14 of tests/peers/planar_yaw_rate.py ended
/// within one noise variance of their best as their representative did,
/// every one, at 23–34 % more search time (docs/planar.md, "Each start
/// carried to the final objective"). `done`: the run already carried,
/// and whether its last polish held (else it is valued like the runs
/// whose carrying failed part-way); nothing to do without a continuation (`path` empty: the search noise
/// already within 10 % of the final one and no prior held apart, or no
/// stated priors).
fn carried(
    objective: &Objective,
    plan: &Plan,
    searched: &mut Searched,
    (done, done_ended): (usize, bool),
    path: &[f64],
) -> Result<(), AllFailed> {
    let Some(&last) = path.last() else {
        return Ok(());
    };
    let carry = |(i, run): (usize, &mut Run)| {
        let counted = matches!(run.fate, Fate::Finished | Fate::Unpolished);
        if !counted || !run.outcome.objective.is_finite() {
            return;
        }
        // a run whose last polish held has its objective in the last noise's
        let ended = match (i == done, run.fate) {
            (true, _) => done_ended,
            (false, Fate::Finished) => carry_one(objective, plan, &mut run.outcome, path),
            _ => false,
        };
        if !ended {
            let problem = priored(objective, plan, last);
            run.outcome.objective = valued(&problem, &run.outcome.parameters);
        }
    };
    searched.runs.par_iter_mut().enumerate().for_each(carry);
    searched.tally_again()
}

/// The continuation of the best run's `outcome` from the search's noise
/// `sigma`: polished under the stated priors with the noise re-estimated
/// at its optimum each time, until it changes by less than 10 % (at most
/// three times; at least once when `held`, the search's priors held apart
/// from the stated ones). The noises it was polished at, in order, and
/// whether the last polish held (`outcome` then ended in that noise's
/// objective).
fn continuation(
    objective: &Objective,
    plan: &Plan,
    outcome: &mut lm::Outcome,
    mut sigma: f64,
    mut held: bool,
) -> (Vec<f64>, bool) {
    let (mut path, mut ended) = (Vec::new(), false);
    for _ in 0..3 {
        let at = noise_at(objective, &outcome.parameters);
        if !std::mem::take(&mut held) && (plan.priors.is_empty() || (at / sigma).ln().abs() < 0.1) {
            break;
        }
        sigma = at;
        path.push(sigma);
        ended = polish_at(objective, plan, outcome, sigma);
    }
    (path, ended)
}

/// `outcome` polished under the stated priors at each noise of `path` in
/// turn: whether every polish held (`outcome` then ended in the last
/// noise's objective); where one fails (the car not simulable from there)
/// it keeps the last that did, which [`carried`] then values in the final
/// objective.
fn carry_one(objective: &Objective, plan: &Plan, outcome: &mut lm::Outcome, path: &[f64]) -> bool {
    path.iter()
        .all(|&sigma| polish_at(objective, plan, outcome, sigma))
}

/// `outcome` polished under the stated priors weighed at the noise
/// `sigma`, its iterations and evaluations summed; false (`outcome` kept)
/// where the polish fails.
fn polish_at(objective: &Objective, plan: &Plan, outcome: &mut lm::Outcome, sigma: f64) -> bool {
    let (lower, upper) = plan.bounds;
    let problem = priored(objective, plan, sigma);
    let polished = lm::minimise(&problem, &outcome.parameters, lower, upper, &plan.solver);
    if !polished.objective.is_finite() {
        return false;
    }
    *outcome = lm::Outcome {
        iterations: outcome.iterations + polished.iterations,
        evaluations: outcome.evaluations + polished.evaluations,
        ..polished
    };
    true
}

/// The identification's objective under the stated priors weighed at
/// the noise `sigma`.
fn priored<'a>(objective: &Objective<'a>, plan: &Plan, sigma: f64) -> Priored<Objective<'a>> {
    Priored::new(objective.clone(), plan.priors.to_vec(), sigma).expect("the priors were checked")
}

/// `F = Σ r²` of `problem` at `p` (∞ where it cannot be evaluated).
fn valued(problem: &impl LeastSquares, p: &[f64]) -> f64 {
    let mut r = vec![0.0; problem.residual_count()];
    let ok = problem.evaluate(p, &mut r, None);
    let f: f64 = r.iter().map(|v| v * v).sum();
    match ok && f.is_finite() {
        true => f,
        false => f64::INFINITY,
    }
}

/// Where a full search draws its random starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Drawn {
    /// Within the study's spread of the template (log-uniform).
    Template,
    /// Each parameter with a prior of its own from that prior (normal in
    /// the log, its centre and spread), the others as [`Drawn::Template`]:
    /// the confirming searches, where the priors weigh what the engineer
    /// knows against the data at the final noise.
    Priors,
}

/// `point` (a start drawn around the template, index `k` under `seed`)
/// with each parameter that has a prior of its own among `priors` drawn
/// from it.
fn from_priors(mut point: Vec<f64>, priors: &[Prior], seed: u64, k: usize) -> Vec<f64> {
    // a stream apart from the template's draws of the same start
    let mut draws = Draws::new(seed ^ PRIOR_STREAM, k as u64);
    for prior in priors
        .iter()
        .filter(|p| p.terms.len() == 1 && p.less.is_empty())
    {
        if let Some(p) = point.get_mut(prior.terms[0]) {
            *p = prior.centre.ln() + prior.spread * gaussian(&mut draws);
        }
    }
    point
}

/// The confirming searches first fit each start but the first (the best
/// found) with the priors weighed at this multiple of the noise (their
/// weight 16 times), for at most [`EASED_ITERATIONS`]: each start's own
/// short continuation towards the final objective ([`eased`]).
pub const EASED: f64 = 4.0;

/// The iterations of a start's eased fit ([`EASED`]).
pub const EASED_ITERATIONS: usize = 100;

/// `points` with each but the first replaced by its fit under the priors
/// weighed at [`EASED`] times `sigma` (kept where that fit fails): on the
/// yaw-rate generator's cars the confirming starts drawn from the priors
/// and run at the final noise alone ended far above the best (10 of 20
/// cars reached it to 1e-6 from 4 or more of 16 starts); eased, 15 of 20
/// (all 20 within κ noise variances; docs/planar.md, "What the starts
/// search").
fn eased(
    points: Vec<Vec<f64>>,
    objective: &Objective,
    searching: &[Prior],
    sigma: f64,
    plan: &Plan,
) -> Vec<Vec<f64>> {
    let (lower, upper) = plan.bounds;
    let problem = Priored::new(objective.clone(), searching.to_vec(), EASED * sigma)
        .expect("the priors were checked");
    let solver = lm::Settings {
        max_iterations: EASED_ITERATIONS,
        ..plan.solver
    };
    let ease = |(k, p): (usize, Vec<f64>)| match k {
        0 => p,
        _ => {
            let fit = lm::minimise(&problem, &p, lower, upper, &solver);
            match fit.objective.is_finite() {
                true => fit.parameters,
                false => p,
            }
        }
    };
    points.into_par_iter().enumerate().map(ease).collect()
}

/// The seed offset of [`from_priors`]' stream.
const PRIOR_STREAM: u64 = 0x5052_494f_5253;

/// The priors the multi-start stages search under: the stated ones with
/// the bumper's effective width held within [`super::WIDTH_SPREAD`] of its
/// centre (a continuation). The replays see the width only through the
/// struck cells' lines of action, where it trades with the yaw inertia; a
/// wider stated prior (the cells compared in the joint stage,
/// [`super::CELLS_WIDTH_SPREAD`]) let the starts wander along that trade
/// into basins of a higher objective (car 8 of tests/peers/planar_yaw_rate.py:
/// one start of 16 at the best, I_z −15.8 %). The best is then polished
/// under the stated priors, and the joint stage and the uncertainty use
/// them.
fn held(priors: &[Prior]) -> Vec<Prior> {
    let held = |p: &Prior| match p.name == super::EFFECTIVE_WIDTH {
        true => Prior {
            spread: p.spread.min(super::WIDTH_SPREAD),
            ..p.clone()
        },
        false => p.clone(),
    };
    priors.iter().map(held).collect()
}

/// A random start of the search around `centre` (its lines anywhere on
/// the bumper), index `k`.
fn draw(centre: &[f64], plan: &Plan, k: usize) -> Vec<f64> {
    plan.unknowns.draw(centre, plan.spread, plan.seed, k as u64)
}

/// The tie map of a car whose two chains have the same size: each
/// `right.*` parameter takes its `left.*` twin's index; `None` otherwise.
pub(super) fn ties(unknowns: &Unknowns) -> Option<Vec<usize>> {
    let car = unknowns.template();
    if car.left().masses.len() != car.right().masses.len() {
        return None;
    }
    let names: Vec<String> = unknowns.names().into_iter().map(|(n, _)| n).collect();
    let mut reduced = Vec::with_capacity(names.len());
    let mut map = Vec::with_capacity(names.len());
    for name in &names {
        let twin = name
            .strip_prefix("right.")
            .and_then(|rest| names.iter().position(|n| *n == format!("left.{rest}")));
        match twin {
            Some(left) => map.push(map[left]),
            None => {
                map.push(reduced.len());
                reduced.push(name.clone());
            }
        }
    }
    Some(map)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_progress_counts_every_search_the_setup_runs() {
        let chain = bumpsim_core::model::MsdModel::new(vec![8.0, 1200.0], vec![2e3], vec![1.5e6]);
        let bumper = bumpsim_impact::bumper::Bumper::three_part(1.5e6, 60e3, 6e6).unwrap();
        let layout = crate::car::Layout::default();
        let car = crate::car::PlanarCar::symmetric(&chain.unwrap(), &bumper, &layout).unwrap();
        let mut setup = super::super::Setup::new(car);
        setup.starts = 16;
        assert_eq!(setup.start_count(), 16);
        // the width estimated: a second search with it pinned
        setup.width = true;
        assert_eq!(setup.start_count(), 32);
        setup.confirm = true;
        assert_eq!(setup.start_count(), 16 * (1 + CONFIRMING) * 2);
    }

    #[test]
    fn the_search_holds_the_width_alone_within_its_narrow_prior() {
        let width = |spread| Prior::single(super::super::EFFECTIVE_WIDTH, 0, 1.6, spread).unwrap();
        let mass = Prior::single("body.mass", 1, 1200.0, 0.1).unwrap();
        let searching = held(&[width(0.05), mass.clone()]);
        assert!((searching[0].spread - super::super::WIDTH_SPREAD).abs() < 1e-15);
        assert_eq!(searching[1], mass);
        // a narrower stated prior is searched as stated
        assert_eq!(held(&[width(0.01)]), vec![width(0.01)]);
    }

    #[test]
    fn confirming_starts_draw_each_parameter_with_a_prior_of_its_own_from_it() {
        let inertia = Prior::single("body.yaw_inertia", 1, 2000.0, 0.1).unwrap();
        let total = Prior::sum("total_mass", vec![0, 2], 1300.0, 0.01).unwrap();
        let point = vec![7.0, 8.0, 1.5, 0.3];
        let drawn = |k| from_priors(point.clone(), &[inertia.clone(), total.clone()], 1, k);
        // reproducible; only the single prior's parameter moves
        assert_eq!(drawn(3), drawn(3));
        let values: Vec<f64> = (0..400).map(|k| drawn(k)[1]).collect();
        for k in 0..400 {
            let p = drawn(k);
            assert_eq!((p[0], p[2], p[3]), (7.0, 1.5, 0.3));
        }
        // normal in the log about the centre with the prior's spread
        let mean = values.iter().sum::<f64>() / 400.0;
        let sd = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 399.0).sqrt();
        assert!((mean - 2000f64.ln()).abs() < 0.03, "{mean}");
        assert!((sd / 0.1 - 1.0).abs() < 0.15, "{sd}");
    }
}
