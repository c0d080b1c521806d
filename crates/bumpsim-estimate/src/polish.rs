//! Screening loosely, polishing the few that matter (issue 19).
//!
//! Most starts of a multi-start identification end in a local minimum worse
//! than the best, and LM spends most of a run creeping along a flat valley
//! at an objective that no longer changes in the sixth digit. Only the best
//! needs the thesis's tolerances, so the search runs in two levels:
//!
//! 1. **Screening:** every start runs with the relative-decrease tolerance
//!    raised to [`SCREEN_FTOL`], in [`crate::search`]'s stages (abandonment,
//!    merging).
//! 2. **Polishing:** the screened optima are clustered (a run within
//!    [`CLUSTER_DISTANCE`] in every log parameter of a better one is merged
//!    into it); the distinct ones within [`POLISH_FACTOR`] of the best
//!    screened objective, at most [`MAX_POLISHED`], continue with the full
//!    tolerances.
//!
//! A start *reaches the best* when the polished run of its cluster ends
//! within 1e-6 (relative) of the best objective; starts of a cluster not
//! polished do not (they are counted as such). With one start (or a user's
//! start alone) the one run is polished: it ends as an unscreened run would,
//! on another path (the polish restarts LM's damping λ); a search of one
//! start in all need not screen at all ([`crate::multistart::alone`]).

use crate::lm::Outcome;
use crate::search::{Fate, Goal, Run, near, race};

/// The relative decrease of F that ends a screening run (the thesis's
/// 1e-12 ends a polishing run).
pub const SCREEN_FTOL: f64 = 1e-6;

/// The relative decrease of F that ends a refining run of the search's
/// second level ([`crate::search`]): a run drawn next to the best creeps
/// along its valley, and at [`SCREEN_FTOL`] it would stop about 1 % above
/// the minimum it is in, short of the best fit it reaches at this
/// tolerance. Its optimum is polished afterwards like any other.
pub const REFINE_FTOL: f64 = 1e-9;

/// Screened optima up to this factor above the best are polished.
pub const POLISH_FACTOR: f64 = 1.2;

/// At most this many distinct screened optima are polished.
pub const MAX_POLISHED: usize = 6;

/// Screened optima closer than this in every log parameter (≈ 5 %) are one.
pub const CLUSTER_DISTANCE: f64 = 0.05;

/// Clusters the finished screening runs (best first; a run within
/// [`CLUSTER_DISTANCE`] of a better one is merged into it) and returns the
/// clusters to polish, best first; the others become [`Fate::Unpolished`].
pub fn candidates(runs: &mut [Run]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..runs.len())
        .filter(|&i| runs[i].fate == Fate::Finished && runs[i].outcome.objective.is_finite())
        .collect();
    order.sort_by(|&a, &b| {
        runs[a]
            .outcome
            .objective
            .total_cmp(&runs[b].outcome.objective)
    });
    let Some(&first) = order.first() else {
        return Vec::new();
    };
    let bar = POLISH_FACTOR * runs[first].outcome.objective;
    let mut kept: Vec<usize> = Vec::new();
    for i in order {
        runs[i].fate = match near(runs, &kept, i, CLUSTER_DISTANCE) {
            Some(j) => Fate::Merged(j),
            None if kept.len() < MAX_POLISHED && runs[i].outcome.objective <= bar => {
                kept.push(i);
                Fate::Finished
            }
            None => Fate::Unpolished,
        };
    }
    kept
}

/// Polishes the `chosen` runs with `solve(start, iterations)`, in
/// parallel, up to the goal's iterations each, in [`crate::search::race`]'s
/// chunks: a candidate that cannot catch up with the best polished
/// objective is abandoned. Iterations and evaluations add up over both
/// levels.
pub fn polish(
    runs: &mut [Run],
    chosen: &[usize],
    goal: Goal,
    solve: &(dyn Fn(&[f64], usize) -> Outcome + Sync),
) {
    let mut polished: Vec<Run> = chosen.iter().map(|&i| runs[i].clone()).collect();
    for run in &mut polished {
        run.outcome.stop = crate::lm::Stop::Iterations;
    }
    let mut running: Vec<usize> = (0..polished.len()).collect();
    race(&mut polished, &mut running, goal, solve);
    for (&i, run) in chosen.iter().zip(polished) {
        runs[i] = run;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lm::Stop;

    /// A run behind the leader but gaining fast enough to overtake it in
    /// the iterations left is kept; a run creeping too slowly is abandoned.
    #[test]
    fn a_race_keeps_the_runs_that_can_still_overtake() {
        use crate::search::{CHUNK, Goal, cannot_catch_up, race};
        // parameter 0: F = 1 + 10 e^(−x/30), x the iterations run (fast);
        // parameter 1: F = 10.9 − 1e-3 x (a flat valley)
        let solve = |p: &[f64], n: usize| {
            let x = p[0] + n as f64;
            let objective = match p[1] {
                0.0 => 1.0 + 10.0 * (-x / 30.0).exp(),
                _ => 10.9 - 1e-3 * x,
            };
            Outcome {
                parameters: vec![x, p[1]],
                objective,
                iterations: n,
                evaluations: n,
                stop: Stop::Iterations,
            }
        };
        let run = |kind: f64, objective: f64| Run {
            outcome: Outcome {
                parameters: vec![0.0, kind],
                objective,
                iterations: 0,
                evaluations: 0,
                stop: Stop::Iterations,
            },
            fate: Fate::Finished,
        };
        // the leader (not running) at F = 2; both runners start at F = 11
        let mut runs = vec![run(0.0, 2.0), run(0.0, 11.0), run(1.0, 11.0)];
        let mut running = vec![1, 2];
        let goal = Goal {
            iterations: 3 * CHUNK,
            target: f64::INFINITY,
            within: 0.0,
        };
        race(&mut runs, &mut running, goal, &solve);
        assert_eq!(runs[1].fate, Fate::Finished, "overtook the leader");
        assert!(runs[1].outcome.objective < 2.0);
        assert_eq!(runs[1].outcome.iterations, 3 * CHUNK);
        assert_eq!(
            runs[2].fate,
            Fate::Abandoned,
            "0.1 a chunk cannot close 8.8"
        );
        assert_eq!(runs[2].outcome.iterations, CHUNK);
        // the rule itself, at twice the pace: 5 → 4.9 with 3 chunks left
        // cannot reach 1; 5 → 4 can
        assert!(cannot_catch_up(5.0, 4.9, 3.0, 1.0));
        assert!(!cannot_catch_up(5.0, 4.0, 3.0, 1.0));
        assert!(cannot_catch_up(5.0, 5.0, 1e9, 1.0)); // no progress at all
    }
}
