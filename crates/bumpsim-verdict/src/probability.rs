//! The probability of passing (issue 39, item 4): the verdict propagated
//! over the car's uncertainty ([`crate::uncertainty`]).
//!
//! `N` seeded draws of the car's parameters, each car run through every
//! test ([`crate::verdict`](mod@crate::verdict)) in parallel
//! ([`bumpsim_estimate::propagate::through`]). A criterion's probability
//! of passing is the share of draws in which it keeps the margin asked
//! for, with its exact 95 % bounds (Clopper–Pearson, one-sided when no
//! draw fails: [`bumpsim_estimate::binomial`]); a test's, the
//! share in which all its criteria do; the verdict's, the share in which
//! every test does. A draw whose car is not valid or whose run fails is
//! counted, not used.

use crate::criteria::Outcome;
use crate::error::{VerdictError, require};
use crate::uncertainty::Part;
pub use crate::uncertainty::{Propagation, Uncertainty};
use crate::verdict::{CarEnd, Setup, Verdict, verdict};
use bumpsim_estimate::propagate::{probability, through};
use serde::Serialize;

/// Fewest and most draws of a propagation.
pub const SAMPLES: [usize; 2] = [10, 100_000];

/// How many draws, and the seed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Sampling {
    /// Draws, within [`SAMPLES`].
    pub samples: usize,
    /// The seed of the draws' streams.
    pub seed: u64,
}

/// Whether each judged criterion of each test passes in one draw.
type Passes = Vec<Vec<Option<bool>>>;

fn passes(v: &Verdict) -> Passes {
    let judged = |o: Outcome| (o != Outcome::Info).then_some(o == Outcome::Pass);
    v.tests
        .iter()
        .map(|t| t.criteria.iter().map(|c| judged(c.outcome)).collect())
        .collect()
}

/// The set-up with every end's car scaled by `factors` (one per part);
/// None when a car is not valid. Shared with the Sobol indices.
pub(crate) fn drawn(setup: &Setup, parts: &[Part], factors: &[f64]) -> Option<Setup> {
    let mut drawn = setup.clone();
    for end in [&mut drawn.front, &mut drawn.rear].into_iter().flatten() {
        let car = crate::uncertainty::scaled(&end.car, parts, factors)?;
        *end = CarEnd::new(car, end.limits.clone()).ok()?;
    }
    Some(drawn)
}

/// The verdict of the set-up with every end's car scaled by `factors`.
fn draw(setup: &Setup, parts: &[Part], factors: &[f64]) -> Option<Passes> {
    verdict(&drawn(setup, parts, factors)?)
        .ok()
        .map(|v| passes(&v))
}

/// Gives each judged criterion, each test and the verdict its probability
/// of passing over `uncertainty` (see the module).
///
/// ```no_run
/// use bumpsim_verdict::prelude::*;
/// use bumpsim_verdict::probability::{Sampling, Uncertainty, propagate};
/// let path = std::path::Path::new("examples/verdict/car.toml");
/// let end = CarEnd::new(bumpsim_planar::PlanarCar::read(path)?, Damageability::read(path)?)?;
/// let setup = Setup::new(vec![end], bumpsim_verdict::protocol::select(&["part581"])?, 0.0)?;
/// let mut v = verdict(&setup)?;
/// let u = Uncertainty::independent("spreads", vec![("bumper.force".into(), 0.1)])?;
/// propagate(&setup, &mut v, &u, Sampling { samples: 200, seed: 1 })?;
/// println!("{}", v.tests[0].criteria[0].probability.unwrap().probability);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn propagate(
    setup: &Setup,
    v: &mut Verdict,
    uncertainty: &Uncertainty,
    sampling: Sampling,
) -> Result<(), VerdictError> {
    let n = sampling.samples;
    let expected = format!("between {} and {}", SAMPLES[0], SAMPLES[1]);
    require(
        "samples",
        n as f64,
        "draws",
        &expected,
        (SAMPLES[0]..=SAMPLES[1]).contains(&n),
    )?;
    for end in [&setup.front, &setup.rear].into_iter().flatten() {
        uncertainty.check(&end.car)?;
    }
    let parts: Vec<Part> = uncertainty.parts();
    let lower = uncertainty.cholesky()?;
    let factors: Vec<Vec<f64>> = (0..n as u64)
        .map(|i| uncertainty.factors(&lower, sampling.seed, i))
        .collect();
    let nominal = passes(v);
    let shaped = |p: &Passes| p.iter().map(Vec::len).eq(nominal.iter().map(Vec::len));
    let run = through(&factors, &|f: &[f64]| draw(setup, &parts, f).filter(shaped));
    for (i, t) in v.tests.iter_mut().enumerate() {
        if t.skipped.is_some() {
            continue;
        }
        for (j, c) in t.criteria.iter_mut().enumerate() {
            c.probability = (nominal[i][j].is_some())
                .then(|| probability(&run.outputs, |o| o[i][j] != Some(false)));
        }
        t.probability = Some(probability(&run.outputs, |o| {
            o[i].iter().all(|p| *p != Some(false))
        }));
    }
    let passing = probability(&run.outputs, |o| {
        o.iter().flatten().all(|p| *p != Some(false))
    });
    v.propagation = Some(Propagation {
        uncertainty: uncertainty.clone(),
        samples: n,
        seed: sampling.seed,
        failed: run.failed,
        passing,
    });
    Ok(())
}
