//! The starts of an identification (issue 19).
//!
//! The search has two levels. The first *explores*: the given starts and
//! random ones (below), at least [`MIN_EXPLORING`] and half of all. The
//! second *refines*, in rounds of [`ROUND`]: each round's starts are drawn
//! within [`REFINE_SPREAD`] of the best screened optimum found so far and
//! run at [`crate::polish::REFINE_FTOL`], raced for its fit (abandoned when they
//! cannot come within one noise variance of it). A deeper minimum found by
//! a round becomes the next round's centre, so the best is either
//! confirmed by many starts or improved upon; on ten synthetic 5-DOF
//! problems every best was reached by at least 9 of 32 starts, and most
//! were deeper than a 32-start single-level search found. The count is
//! reported ([`crate::estimate::Starts::refined`]).
//!
//! **Exploring starts**, in this order: the user's start, the data-derived start
//! ([`crate::estimate::data_start`]), the continuation starts (below), then
//! log-uniform random points drawn from a ChaCha8 stream seeded by
//! `seed + start index` (the same starts on any number of threads), around
//! the data start and the continuation starts in turn: within a factor 30
//! of the data start, within [`NEIGHBOURHOOD`] of a continuation
//! start (the neighbourhood of the smaller model's optimum is searched
//! where it is, instead of hoping a wide draw lands there). Every start is
//! clamped into [`VALID_RANGE`], where a model can be evaluated (a split
//! of a wall-like mass would otherwise need a link stiffer than any model
//! can be, and the start would be lost).
//!
//! **Continuation across the DOF table.** When the (n−1)-mass optimum is
//! known, each of its masses is split in turn into two halves joined by a
//! link whose frequency is √(1e5) ≈ 316 times the smaller model's fastest
//! mode bound (damper at 30 % of critical for the halves): n−1 starts whose
//! objective is, within a percent, that of the (n−1)-mass optimum (tested),
//! so the n-mass search begins where the smaller model ended. A link that
//! stiff is a stationary point (the data cannot see it: its Jacobian
//! column is zero), so random starts around such a seed draw the link's
//! frequency and damping over their whole range (`Split` below).
//!
//! **Stages.** Every start runs [`STAGES`]' first length of iterations;
//! then a start whose objective is still more than 10 times the incumbent
//! (the best objective of any start so far) is abandoned, and a start
//! within [`MERGE_DISTANCE`] of a better running start is merged into it
//! (it would follow the same path). The rest run on to the iteration
//! limit in chunks of [`CHUNK`] iterations; after each, a start that could
//! not reach the incumbent in the iterations left even at the pace of its
//! last chunk is abandoned too (a run creeping along a flat valley only
//! slows down). Stages run in parallel; every decision is taken in start
//! order from the stage's results, so the result is the same on any number
//! of threads. [`crate::polish`] then clusters and polishes the screened
//! optima, in the same chunks with the same rule.

use crate::case::VALID_RANGE;
use crate::lm::{Outcome, Stop};
use bumpsim_core::model::MsdModel;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;

/// Starts from the (n−1)-mass optimum `previous` for an n-mass model, SI,
/// thesis order `[m.., c.., k..]`: one per mass of `previous`, that mass split
/// into two halves joined by a link with `ω_link² = 1e5 ω²`, where
/// `ω² = max k_j (1/m_j + 1/m_{j+1})` bounds the fastest mode of `previous`.
/// None for a single rigid mass.
///
/// ```
/// use bumpsim_core::model::MsdModel;
/// use bumpsim_ident::search::continuation_starts;
/// let two = MsdModel::new(vec![10.0, 1000.0], vec![2e3], vec![1e6]).unwrap();
/// let starts = continuation_starts(&two);
/// assert_eq!(starts.len(), 2);
/// assert_eq!(&starts[0][..3], &[5.0, 5.0, 1000.0]);      // m1 split in halves
/// let omega2 = 1e6 * (1.0 / 10.0 + 1.0 / 1000.0);
/// assert!((starts[0][5] - 1e5 * omega2 * 2.5).abs() < 1e-6 * starts[0][5]); // k = ω_link² m1/4
/// assert!(continuation_starts(&MsdModel::new(vec![900.0], vec![], vec![]).unwrap()).is_empty());
/// ```
pub fn continuation_starts(previous: &MsdModel) -> Vec<Vec<f64>> {
    let (m, k) = (previous.masses(), previous.springs());
    let omega2 = (0..k.len())
        .map(|j| k[j] * (1.0 / m[j] + 1.0 / m[j + 1]))
        .fold(0.0, f64::max);
    if omega2 <= 0.0 {
        return Vec::new(); // a rigid mass has no time scale to be stiffer than
    }
    (0..previous.dof())
        .map(|j| split(previous, j, 1e5 * omega2))
        .collect()
}

/// `previous` with mass `j` split into halves joined by a link of natural
/// frequency² `omega2` (reduced mass m_j/4), damped at 30 % of critical.
fn split(previous: &MsdModel, j: usize, omega2: f64) -> Vec<f64> {
    let half = 0.5 * previous.masses()[j];
    let stiff = omega2 * 0.5 * half;
    let damper = 2.0 * 0.3 * (stiff * 0.5 * half).sqrt();
    let mut masses = previous.masses().to_vec();
    masses[j] = half;
    masses.insert(j, half);
    let mut dampers = previous.dampers().to_vec();
    dampers.insert(j, damper);
    let mut springs = previous.springs().to_vec();
    springs.insert(j, stiff);
    [masses, dampers, springs].concat()
}

/// The starting points in log space, free parameters only: `user`, `data`,
/// `seeds`, then random points around `data` and the seeds, `count` in all;
/// around a seed with a split link (`links[i]`), that link is drawn over
/// its range (`Split` below).
pub(crate) fn starting_points(
    count: usize,
    seed: u64,
    fixed: (&Option<Vec<f64>>, &[f64], &[Vec<f64>]),
    links: &[Option<usize>],
    free: &[usize],
) -> Vec<Vec<f64>> {
    let (user, data, seeds) = fixed;
    let log = |theta: &[f64]| -> Vec<f64> { free.iter().map(|&i| theta[i].ln()).collect() };
    let mut points: Vec<Vec<f64>> = user.iter().map(|u| log(u)).collect();
    points.push(log(data));
    points.extend(seeds.iter().map(|s| log(s)));
    let split = |(i, s): (usize, &Vec<f64>)| {
        let link = links.get(i).copied().flatten();
        link.and_then(|l| Split::of(s, l, free))
    };
    let centres: Vec<(Vec<f64>, f64, Option<Split>)> = std::iter::once((log(data), 30.0, None))
        .chain(
            seeds
                .iter()
                .enumerate()
                .map(|(i, s)| (log(s), NEIGHBOURHOOD, split((i, s)))),
        )
        .collect();
    let mut index = points.len() as u64;
    while points.len() < count.max(1) {
        let (centre, spread, link) = &centres[index as usize % centres.len()];
        points.push(draw(centre, *spread, link.as_ref(), seed, index));
        index += 1;
    }
    points.truncate(count.max(1));
    let (floor, ceiling) = (VALID_RANGE.start().ln(), VALID_RANGE.end().ln());
    for value in points.iter_mut().flatten() {
        *value = value.clamp(floor, ceiling);
    }
    points
}

/// A log-uniform point within a factor `spread` of `centre` (log space),
/// from the ChaCha8 stream seeded by `seed + index`; with a split link, that
/// link drawn over its range.
fn draw(centre: &[f64], spread: f64, link: Option<&Split>, seed: u64, index: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed.wrapping_add(index));
    let mut point: Vec<f64> = centre
        .iter()
        .map(|c| c + spread.ln() * (2.0 * unit(&mut rng) - 1.0))
        .collect();
    if let Some(link) = link {
        link.draw(&mut point, unit(&mut rng), unit(&mut rng));
    }
    point
}

/// The link that joins the halves of a mass split by a continuation start,
/// in free log parameters: its spring and damper positions, the seed's
/// `ln k` (the link at `1e5 ω²`, far above the data's bandwidth: a
/// stationary point, whose Jacobian column is zero), and `ln μ` of the
/// halves (μ = m/4).
///
/// Random starts around the seed draw the link's frequency log-uniform
/// from the smaller model's fastest mode to the seed's (`ω_link² / ω² ∈
/// [1, 1e5]`) and its damping ratio from 0.05 to 1, so that they begin
/// where the data can see the new mass, and descend from there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Split {
    spring: usize,
    damper: usize,
    ln_k: f64,
    ln_mu: f64,
}

/// The split link's frequency range, `ω_link² / ω²` (see `Split`).
pub const SPLIT_STIFFNESS: f64 = 1e5;

/// The split link's damping ratios drawn (see `Split`).
pub const SPLIT_DAMPING: (f64, f64) = (0.05, 1.0);

impl Split {
    /// The split link `l` of continuation seed `theta` (SI, thesis order)
    /// when its spring and damper are free.
    fn of(theta: &[f64], l: usize, free: &[usize]) -> Option<Split> {
        // 3n − 2 parameters
        let dof = theta.len().div_ceil(3);
        let (spring, damper) = (2 * dof - 1 + l, dof + l);
        let position = |i: usize| free.iter().position(|&f| f == i);
        let (m1, m2) = (*theta.get(l)?, *theta.get(l + 1)?);
        Some(Split {
            spring: position(spring)?,
            damper: position(damper)?,
            ln_k: theta.get(spring)?.ln(),
            ln_mu: (m1 * m2 / (m1 + m2)).ln(),
        })
    }

    /// Sets the link in `point` from two uniform numbers.
    fn draw(&self, point: &mut [f64], frequency: f64, damping: f64) {
        let ln_k = self.ln_k - frequency * SPLIT_STIFFNESS.ln();
        let (low, high) = SPLIT_DAMPING;
        let ln_zeta = low.ln() + damping * (high / low).ln();
        // c = 2 ζ √(k μ)
        point[self.spring] = ln_k;
        point[self.damper] = 2f64.ln() + ln_zeta + 0.5 * (ln_k + self.ln_mu);
    }
}

/// The share of the starts drawn around the best screened optimum of the
/// others (the second level of the search, see the module).
pub const REFINED: f64 = 0.5;

/// Starts drawn in one round of the second level: each round centres on
/// the best screened optimum found so far.
pub const ROUND: usize = 4;

/// At least this many starts explore (fewer refine nothing): with fewer,
/// the first level misses basins a refinement cannot make up for.
pub const MIN_EXPLORING: usize = 8;

/// How many of `count` starts explore: the given ones, at least
/// [`MIN_EXPLORING`] and at least `1 − REFINED` of all; the rest refine.
pub(crate) fn exploring(count: usize, given: usize) -> usize {
    let refined = (count as f64 * REFINED) as usize;
    count
        .saturating_sub(refined)
        .max(given)
        .max(MIN_EXPLORING)
        .min(count.max(1))
}

/// Second-level starts lie within this factor of the best so far.
pub const REFINE_SPREAD: f64 = 1.1;

/// `count` points within [`REFINE_SPREAD`] of `centre` (log space), drawn
/// as the random starts from index `first` on.
pub(crate) fn around(centre: &[f64], count: usize, seed: u64, first: usize) -> Vec<Vec<f64>> {
    let (floor, ceiling) = (VALID_RANGE.start().ln(), VALID_RANGE.end().ln());
    (first..first + count)
        .map(|index| {
            let point = draw(centre, REFINE_SPREAD, None, seed, index as u64);
            point.into_iter().map(|v| v.clamp(floor, ceiling)).collect()
        })
        .collect()
}

/// Random starts around a continuation start lie within this factor of
/// it: they explore the basin the smaller model's optimum leads into (±20 %); the wide draws around the data start
/// explore elsewhere. A factor of 3 around continuation starts threw most
/// of them into other basins: on ten synthetic 5-DOF problems
/// (tests/identification/five_dof.rs) many ended 1e5 × above the best.
pub const NEIGHBOURHOOD: f64 = 1.2;

/// A uniform number in [0, 1) from 53 random bits.
fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// The stages of the search: iterations each surviving start runs in the
/// stage, and how far above the incumbent (the best objective so far, ×)
/// a start may still be at the stage's end. The last stage runs the rest of
/// the iteration limit and abandons nothing.
pub const STAGES: [(usize, f64); 1] = [(200, 10.0)];

/// A run is given this many times the pace of its last chunk
/// ([`cannot_catch_up`]).
pub const PACE_MARGIN: f64 = 2.0;

/// After the first stage, running starts advance in chunks of this many
/// iterations, each followed by [`cannot_catch_up`]'s test.
pub const CHUNK: usize = 100;

/// Whether a run whose objective went from `before` to `after` in its last
/// chunk stays above `incumbent` after `chunks_left` more chunks at
/// [`PACE_MARGIN`] times that pace. LM's decrease along a valley mostly
/// slows; the margin is for the runs that speed up again.
///
/// ```
/// use bumpsim_ident::search::cannot_catch_up;
/// assert!(cannot_catch_up(5.0, 4.9, 3.0, 1.0)); // 0.2 a chunk, 3 chunks: 4.3 > 1
/// assert!(!cannot_catch_up(5.0, 4.0, 3.0, 1.0)); // 2 a chunk can get there
/// ```
pub fn cannot_catch_up(before: f64, after: f64, chunks_left: f64, incumbent: f64) -> bool {
    let pace = (before - after).max(0.0);
    after - PACE_MARGIN * pace * chunks_left > incumbent
}

/// Two running starts closer than this in every log parameter (≈ 1 %)
/// are one: the worse is merged into the better and shares its fate.
pub const MERGE_DISTANCE: f64 = 0.01;

/// What became of one start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Fate {
    /// Ran until the solver stopped (converged, iteration limit or failed).
    Finished,
    /// Stopped at a stage end, its objective too far above the incumbent.
    Abandoned,
    /// Stopped next to a better start (its index), sharing its fate.
    Merged(usize),
    /// A screened optimum not polished ([`crate::polish`]).
    Unpolished,
}

/// One start's run through the stages.
#[derive(Debug, Clone)]
pub(crate) struct Run {
    /// The last outcome, with iterations and evaluations summed over stages.
    pub outcome: Outcome,
    /// How it ended.
    pub fate: Fate,
}

impl Run {
    /// A run not yet started at `parameters` (log).
    pub(crate) fn start(parameters: Vec<f64>) -> Run {
        Run {
            outcome: Outcome {
                parameters,
                objective: f64::INFINITY,
                iterations: 0,
                evaluations: 0,
                stop: Stop::Iterations,
            },
            fate: Fate::Finished,
        }
    }
}

/// Runs every start in stages ([`STAGES`]): after each, starts still
/// running are abandoned when their objective exceeds the stage's factor
/// times the incumbent, and merged into a better running start within
/// [`MERGE_DISTANCE`]. `solve(point, iterations)` runs the solver; stages
/// run in parallel, decisions in start order (the same on any thread count).
pub(crate) fn staged(
    points: &[Vec<f64>],
    goal: Goal,
    solve: &(dyn Fn(&[f64], usize) -> Outcome + Sync),
    progress: &(dyn Fn() + Sync),
) -> Vec<Run> {
    let max_iterations = goal.iterations;
    let mut runs: Vec<Run> = points.iter().map(|p| Run::start(p.clone())).collect();
    let mut running: Vec<usize> = (0..points.len()).collect();
    let mut used = 0;
    for &(length, factor) in &STAGES {
        let (length, before) = (length.min(max_iterations - used), running.len());
        advance(&mut runs, &running, length, solve);
        used += length;
        running.retain(|&i| runs[i].outcome.stop == Stop::Iterations && used < max_iterations);
        screen(&mut runs, &mut running, factor, goal.target);
        (running.len()..before).for_each(|_| progress());
        if running.is_empty() {
            return runs;
        }
    }
    let before = running.len();
    let rest = Goal {
        iterations: max_iterations - used,
        ..goal
    };
    race(&mut runs, &mut running, rest, solve);
    (0..before).for_each(|_| progress());
    runs
}

/// What a race runs for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Goal {
    /// Iterations each run may take.
    pub iterations: usize,
    /// An objective to reach whatever the runs do (∞: none).
    pub target: f64,
    /// A run is kept while it can reach `(1 + within)` times the best
    /// objective: `1/(n − q)`, one noise variance, for a search (a run that
    /// ends there reaches the best fit, [`crate::estimate::Starts`]).
    pub within: f64,
}

/// Advances the `running` runs in chunks of [`CHUNK`] up to the goal's
/// iterations, abandoning after each chunk those that cannot catch up with
/// the best objective of all `runs` (within the goal's tolerance), or with
/// its target when that is lower ([`cannot_catch_up`]); the rest run until
/// their solver stops.
pub(crate) fn race(
    runs: &mut [Run],
    running: &mut Vec<usize>,
    goal: Goal,
    solve: &(dyn Fn(&[f64], usize) -> Outcome + Sync),
) {
    let (budget, mut used) = (goal.iterations, 0);
    while !running.is_empty() && used < budget {
        let length = CHUNK.min(budget - used);
        let before: Vec<f64> = running.iter().map(|&i| runs[i].outcome.objective).collect();
        advance(runs, running, length, solve);
        used += length;
        let best = runs
            .iter()
            .map(|r| r.outcome.objective)
            .fold(f64::INFINITY, f64::min);
        let incumbent = goal.target.min(best * (1.0 + goal.within));
        let chunks_left = (budget - used) as f64 / CHUNK as f64;
        let mut kept = Vec::with_capacity(running.len());
        for (&i, before) in running.iter().zip(before) {
            let outcome = &runs[i].outcome;
            if outcome.stop != Stop::Iterations || used >= budget {
                continue;
            }
            match cannot_catch_up(before, outcome.objective, chunks_left, incumbent) {
                true => runs[i].fate = Fate::Abandoned,
                false => kept.push(i),
            }
        }
        *running = kept;
    }
}

/// Runs the `running` starts `length` iterations further, in parallel.
fn advance(
    runs: &mut [Run],
    running: &[usize],
    length: usize,
    solve: &(dyn Fn(&[f64], usize) -> Outcome + Sync),
) {
    let step = |&i: &usize| solve(&runs[i].outcome.parameters, length);
    // one run alone needs no thread pool: starting rayon's workers costs a
    // single start more than it could gain (and they spin on its cores)
    let next: Vec<Outcome> = match running.len() {
        0 | 1 => running.iter().map(step).collect(),
        _ => running.par_iter().map(step).collect(),
    };
    for (&i, mut outcome) in running.iter().zip(next) {
        let before = &runs[i].outcome;
        outcome.iterations += before.iterations;
        outcome.evaluations += before.evaluations;
        runs[i].outcome = outcome;
    }
}

/// Abandons and merges among the `running` starts (best first).
fn screen(runs: &mut [Run], running: &mut Vec<usize>, factor: f64, target: f64) {
    let incumbent = runs
        .iter()
        .map(|r| r.outcome.objective)
        .fold(target, f64::min);
    running.sort_by(|&a, &b| {
        runs[a]
            .outcome
            .objective
            .total_cmp(&runs[b].outcome.objective)
    });
    let mut kept: Vec<usize> = Vec::new();
    for &i in running.iter() {
        let objective = runs[i].outcome.objective;
        if objective.is_nan() || objective > factor * incumbent {
            runs[i].fate = Fate::Abandoned;
            continue;
        }
        match near(runs, &kept, i, MERGE_DISTANCE) {
            Some(j) => runs[i].fate = Fate::Merged(j),
            None => kept.push(i),
        }
    }
    kept.sort_unstable();
    *running = kept;
}

/// The first of the `kept` runs within `distance` of run `i` in every
/// (log) parameter.
pub(crate) fn near(runs: &[Run], kept: &[usize], i: usize, distance: f64) -> Option<usize> {
    let p = &runs[i].outcome.parameters;
    kept.iter().copied().find(|&j| {
        let q = &runs[j].outcome.parameters;
        p.iter().zip(q).all(|(a, b)| (a - b).abs() < distance)
    })
}

/// The start whose fate start `i` shares: itself, or the end of its chain
/// of merges.
pub(crate) fn representative(runs: &[Run], mut i: usize) -> usize {
    while let Fate::Merged(j) = runs[i].fate {
        i = j;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;
    use bumpsim_core::discrete::Method;
    use bumpsim_core::series::UniformSeries;
    use bumpsim_core::simulate::{InitialState, simulate};

    #[test]
    fn a_split_start_responds_like_the_smaller_model() {
        let two = MsdModel::new(vec![20.0, 1000.0], vec![3e3], vec![8e5]).unwrap();
        let force: Vec<f64> = (0..600)
            .map(|k| 2e4 * (k as f64 * 1e-4 * 60.0).sin().max(0.0))
            .collect();
        let force = UniformSeries::new(0.0, 1e-4, force).unwrap();
        let x = |m: &MsdModel| {
            let r = simulate(m, &force, Method::Zoh, &InitialState::Rest).unwrap();
            r.displacement[0].clone()
        };
        let reference = x(&two);
        let peak = reference.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for start in continuation_starts(&two) {
            let three = MsdModel::from_parameters(3, &start).unwrap();
            let split = x(&three);
            let worst = split
                .iter()
                .zip(&reference)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(
                worst < 2e-3 * peak,
                "split start differs by {worst} of {peak}"
            );
        }
    }
}
