//! The staged multi-start search (issue 19), for any least-squares
//! problem.
//!
//! The search has two levels. The first *explores*: the given starts and
//! random ones, at least [`MIN_EXPLORING`] and half of all. The second
//! *refines*, in rounds of [`ROUND`]: each round's starts are drawn within
//! [`REFINE_SPREAD`] of the best screened optimum found so far and run at
//! [`crate::polish::REFINE_FTOL`], raced for its fit (abandoned when they
//! cannot come within one noise variance of it). A deeper minimum found by
//! a round becomes the next round's centre, so the best is either confirmed
//! by many starts or improved upon; on ten synthetic 5-DOF problems every
//! best was reached by at least 9 of 32 starts, and most were deeper than a
//! 32-start single-level search found. The count is reported
//! ([`crate::multistart::Starts::refined`]).
//!
//! **Random starts** are log-uniform points around a centre ([`Draws`]):
//! parameter `p_i = c_i + ln(spread) (2u − 1)` with `u` uniform from a
//! ChaCha8 stream seeded by `seed + start index` (the same starts on any
//! number of threads); the model decides the centres (its data-derived
//! start, its continuation starts, its template).
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

use crate::lm::{Outcome, Stop};
use crate::observer::Observer;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;

/// The random numbers of one start: a ChaCha8 stream seeded by `seed +
/// index`, so that start `index` is the same on any number of threads.
///
/// ```
/// use bumpsim_estimate::search::Draws;
/// let centre = [0.0, 10.0];
/// let a = Draws::new(1, 5).around(&centre, 10.0);
/// assert_eq!(a, Draws::new(1, 5).around(&centre, 10.0));   // reproducible
/// assert!(a.iter().zip(&centre).all(|(p, c)| (p - c).abs() <= 10f64.ln()));
/// ```
#[derive(Debug, Clone)]
pub struct Draws(ChaCha8Rng);

impl Draws {
    /// The stream of start `index` under `seed`.
    pub fn new(seed: u64, index: u64) -> Draws {
        Draws(ChaCha8Rng::seed_from_u64(seed.wrapping_add(index)))
    }

    /// A uniform number in [0, 1) from 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.0.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A log-uniform point within a factor `spread` of `centre` (both in
    /// log parameters): `c + ln(spread) (2u − 1)` for each parameter.
    pub fn around(&mut self, centre: &[f64], spread: f64) -> Vec<f64> {
        centre
            .iter()
            .map(|c| c + spread.ln() * (2.0 * self.unit() - 1.0))
            .collect()
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
pub fn exploring(count: usize, given: usize) -> usize {
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
/// as the random starts from index `first` on, each parameter clamped into
/// `[floor, ceiling]` (log; where the model can be evaluated).
pub fn around(
    centre: &[f64],
    count: usize,
    seed: u64,
    first: usize,
    (floor, ceiling): (&[f64], &[f64]),
) -> Vec<Vec<f64>> {
    (first..first + count)
        .map(|index| {
            let point = Draws::new(seed, index as u64).around(centre, REFINE_SPREAD);
            point
                .iter()
                .enumerate()
                .map(|(i, v)| v.clamp(floor[i], ceiling[i]))
                .collect()
        })
        .collect()
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
/// use bumpsim_estimate::search::cannot_catch_up;
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
pub enum Fate {
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
pub struct Run {
    /// The last outcome, with iterations and evaluations summed over stages.
    pub outcome: Outcome,
    /// How it ended.
    pub fate: Fate,
}

impl Run {
    /// A run not yet started at `parameters` (log).
    pub fn start(parameters: Vec<f64>) -> Run {
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
pub fn staged(
    points: &[Vec<f64>],
    goal: Goal,
    solve: &(dyn Fn(&[f64], usize) -> Outcome + Sync),
    observer: &dyn Observer,
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
        (running.len()..before).for_each(|_| observer.start_finished());
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
    (0..before).for_each(|_| observer.start_finished());
    runs
}

/// What a race runs for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goal {
    /// Iterations each run may take.
    pub iterations: usize,
    /// An objective to reach whatever the runs do (∞: none).
    pub target: f64,
    /// A run is kept while it can reach `(1 + within)` times the best
    /// objective: `1/(n − q)`, one noise variance, for a search (a run that
    /// ends there reaches the best fit, [`crate::multistart::Starts`]).
    pub within: f64,
}

/// Advances the `running` runs in chunks of [`CHUNK`] up to the goal's
/// iterations, abandoning after each chunk those that cannot catch up with
/// the best objective of all `runs` (within the goal's tolerance), or with
/// its target when that is lower ([`cannot_catch_up`]); the rest run until
/// their solver stops.
pub fn race(
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
pub fn near(runs: &[Run], kept: &[usize], i: usize, distance: f64) -> Option<usize> {
    let p = &runs[i].outcome.parameters;
    kept.iter().copied().find(|&j| {
        let q = &runs[j].outcome.parameters;
        p.iter().zip(q).all(|(a, b)| (a - b).abs() < distance)
    })
}

/// The start whose fate start `i` shares: itself, or the end of its chain
/// of merges.
pub fn representative(runs: &[Run], mut i: usize) -> usize {
    while let Fate::Merged(j) = runs[i].fate {
        i = j;
    }
    i
}
